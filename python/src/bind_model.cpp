// model room: Robot (bundled, file, string; names and ids), Chain, the Data handle.
#include <mujoco/mujoco.h>

#include "bindings.hpp"
#include "declared_fields.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/dh_model.hpp"
#include "mjarm/model/model_size.hpp"
#include "spec_support.hpp"

namespace mjarm::python {
namespace {

/// A NumPy array over @p size doubles of a Data handle: writable view (owned, the user's),
/// read-only view (a simulation's) or copy (a call's).
py::array_t<double> data_array(py::object self, double* values, int size) {
  auto& h = self.cast<DataHandle&>();
  h.get();
  if (h.borrowed()) return to_array(values, size);
  if (h.writable()) return writable_view(values, size, self);
  return readonly_view(values, size, self);
}

template <typename Getter>
void data_field(py::class_<DataHandle>& cls, const char* name, Getter getter, const char* doc) {
  cls.def_property_readonly(
      name,
      [getter](py::object self) {
        auto& h = self.cast<DataHandle&>();
        const auto [ptr, size] = getter(h.model(), h.get());
        return data_array(self, ptr, size);
      },
      doc);
}

}  // namespace

void bind_model(py::module_& m) {
  def_enum<JointType>(m, "JointType", "Joint types in MuJoCo's order.");
  def_enum<ActuatorKind>(m, "ActuatorKind", "What an actuator does, from its gain and bias.");

  py::class_<JointInfo>(m, "JointInfo", "One joint of the model.")
      .def_readonly("name", &JointInfo::name, "the joint's name in the model")
      .def_readonly("id", &JointInfo::id, "the joint's id in the model")
      .def_readonly("type", &JointInfo::type, "free, ball, slide or hinge")
      .def_readonly("body", &JointInfo::body, "body the joint moves")
      .def_readonly("qpos_address", &JointInfo::qpos_address, "first index into qpos")
      .def_readonly("dof_address", &JointInfo::dof_address, "first index into qvel")
      .def_readonly("limited", &JointInfo::limited, "the joint has a range [lower, upper]")
      .def_readonly("lower", &JointInfo::lower, "range [rad or m] (when limited)")
      .def_readonly("upper", &JointInfo::upper, "range [rad or m] (when limited)")
      .def("__repr__", [](const JointInfo& j) {
        return "<JointInfo '" + j.name + "' " + to_string(j.type) + " id " + std::to_string(j.id) +
               ">";
      });
  py::class_<ActuatorInfo>(m, "ActuatorInfo", "One actuator of the model.")
      .def_readonly("name", &ActuatorInfo::name, "the actuator's name in the model")
      .def_readonly("id", &ActuatorInfo::id, "the actuator's id in the model")
      .def_readonly("kind", &ActuatorInfo::kind,
                    "what the actuator does, read from its gain and bias parameters")
      .def_readonly("joint", &ActuatorInfo::joint, "joint id it drives, or None")
      .def_readonly("ctrl_limited", &ActuatorInfo::ctrl_limited,
                    "the control input is clamped to [ctrl_lower, ctrl_upper]")
      .def_readonly("ctrl_lower", &ActuatorInfo::ctrl_lower,
                    "lower end of the control range (meaningful when ctrl_limited)")
      .def_readonly("ctrl_upper", &ActuatorInfo::ctrl_upper,
                    "upper end of the control range (meaningful when ctrl_limited)")
      .def_readonly("force_limited", &ActuatorInfo::force_limited,
                    "the actuator force is clamped to [force_lower, force_upper]")
      .def_readonly("force_lower", &ActuatorInfo::force_lower,
                    "lower end of the force range [N or N·m] (meaningful when force_limited)")
      .def_readonly("force_upper", &ActuatorInfo::force_upper,
                    "upper end of the force range [N or N·m] (meaningful when force_limited)")
      .def_readonly("gear", &ActuatorInfo::gear, "first gear component")
      .def("__repr__", [](const ActuatorInfo& a) {
        return "<ActuatorInfo '" + a.name + "' " + to_string(a.kind) + ">";
      });
  py::class_<SensorInfo>(m, "SensorInfo",
                         "One sensor; values at sensordata[address:address+dimension].")
      .def_readonly("name", &SensorInfo::name, "the sensor's name in the model")
      .def_readonly("id", &SensorInfo::id, "the sensor's id in the model")
      .def_readonly("type", &SensorInfo::type, "e.g. \"jointpos\", \"framepos\", \"force\"")
      .def_readonly("address", &SensorInfo::address,
                    "first index of the sensor's values in sensordata")
      .def_readonly("dimension", &SensorInfo::dimension, "number of values the sensor writes");

  auto data = py::class_<DataHandle>(
      m, "Data",
      "An mjData lent to Python. From Robot.make_data(): owned, arrays are writable views. From "
      "Simulation.data: read-only views that keep the simulation alive. Given to a Python "
      "controller: copies, valid during that call only. Data(d) of a mujoco.MjData d: d itself, "
      "not a copy (writable views, d kept alive). Every call taking a Data also takes a "
      "mujoco.MjData.");
  data.def(py::init([](const DataArgument& d) { return data_from_mujoco(d); }), py::arg("data"),
           "Borrows a mujoco.MjData (no copy): what every call does with one, done once.");
  data.def_property_readonly(
      "time", [](const DataHandle& h) { return h.get().time; }, "simulated time [s]");
  data_field(
      data, "qpos",
      [](const mjModel& mm, mjData& d) {
        return std::pair{d.qpos, mm.nq};
      },
      "joint positions (nq,)");
  data_field(
      data, "qvel",
      [](const mjModel& mm, mjData& d) {
        return std::pair{d.qvel, mm.nv};
      },
      "joint velocities (nv,)");
  data_field(
      data, "qacc",
      [](const mjModel& mm, mjData& d) {
        return std::pair{d.qacc, mm.nv};
      },
      "joint accelerations (nv,)");
  data_field(
      data, "ctrl",
      [](const mjModel& mm, mjData& d) {
        return std::pair{d.ctrl, mm.nu};
      },
      "actuator inputs (nu,)");
  data_field(
      data, "qfrc_bias",
      [](const mjModel& mm, mjData& d) {
        return std::pair{d.qfrc_bias, mm.nv};
      },
      "bias forces C(q, qd) qd + g(q) (nv,) [N m or N]");
  data_field(
      data, "qfrc_applied",
      [](const mjModel& mm, mjData& d) {
        return std::pair{d.qfrc_applied, mm.nv};
      },
      "applied generalized forces (nv,)");
  data_field(
      data, "actuator_force",
      [](const mjModel& mm, mjData& d) {
        return std::pair{d.actuator_force, mm.nu};
      },
      "actuator forces (nu,)");
  data_field(
      data, "sensordata",
      [](const mjModel& mm, mjData& d) {
        return std::pair{d.sensordata, mm.nsensordata};
      },
      "all sensor values (nsensordata,)");
  data.def(
      "forward",
      [](DataHandle& h) {
        if (!h.writable()) {
          throw Error(
              "Data.forward: only data from Robot.make_data() or a mujoco.MjData can be "
              "recomputed here; use Simulation.forward() for a simulation's data");
        }
        mj_forward(&h.model(), &h.get());
      },
      "mj_forward on owned data or a mujoco.MjData: recomputes kinematics and dynamics after "
      "writing qpos/qvel.");
  data.def_property_readonly(
      "valid", [](const DataHandle& h) { return h.valid && h.data; },
      "False once a call's data outlived its call.");

  py::class_<Robot>(m, "Robot",
                    "A loaded MuJoCo model, shared and immutable. Names never fail silently: an "
                    "unknown name raises mjarm.Error listing the closest ones. Robot(model) of a "
                    "mujoco.MjModel shares it (no copy); every call taking a Robot also takes a "
                    "mujoco.MjModel.")
      .def(py::init([](const ModelArgument& model) { return robot_from_mujoco(model); }),
           py::arg("model"),
           "Shares a mujoco.MjModel (no copy, kept alive): what every call does with one, done "
           "once.")
      .def_static(
          "from_file", [](const std::filesystem::path& p) { return Robot::from_file(p); },
          py::arg("path"),
          "Loads MJCF or URDF as MuJoCo loads it; includes and assets are read through the "
          "checked reader, errors name the file and line.")
      .def_static(
          "from_string",
          [](std::string_view xml, const std::filesystem::path& base) {
            return Robot::from_string(xml, base);
          },
          py::arg("xml"), py::arg("base_dir") = std::filesystem::path(),
          "Loads MJCF or URDF text; relative assets resolve against base_dir.")
      .def_static("bundled", &Robot::bundled, py::arg("name"),
                  "A bundled model by name ('panda', 'ur5e_torque', ...).")
      .def_static("load", py::overload_cast<std::string_view>(&Robot::load),
                  py::arg("name_or_path"), "A bundled name (no '/' nor extension) or a file path.")
      .def_static("models_dir", &Robot::models_dir, "Directory of the bundled models.")
      .def_static("bundled_names", &Robot::bundled_names, "Names of the bundled models, sorted.")
      .def_property_readonly("name", &Robot::name, "the model's name")
      .def_property_readonly("source", &Robot::source, "where it was loaded from")
      .def_property_readonly("load_warnings", &Robot::load_warnings,
                             "MuJoCo's warnings while loading the model (parser and compiler)")
      .def_property_readonly("nq", &Robot::nq, "position coordinates")
      .def_property_readonly("nv", &Robot::nv, "degrees of freedom")
      .def_property_readonly("nu", &Robot::nu, "number of actuators")
      .def_property_readonly(
          "timestep", [](const Robot& r) { return r.model().opt.timestep; }, "physics timestep [s]")
      .def("joint", &Robot::joint, py::arg("name"), "joint id by name")
      .def("body", &Robot::body, py::arg("name"), "body id by name")
      .def("site", &Robot::site, py::arg("name"), "site id by name")
      .def("geom", &Robot::geom, py::arg("name"), "geom id by name")
      .def("actuator", &Robot::actuator, py::arg("name"), "actuator id by name")
      .def("sensor", &Robot::sensor, py::arg("name"), "sensor id by name")
      .def("camera", &Robot::camera, py::arg("name"), "camera id by name")
      .def("keyframe", &Robot::keyframe, py::arg("name"), "keyframe id by name")
      .def("joints", &Robot::joints, "every joint, in id order")
      .def("joint_info", &Robot::joint_info, py::arg("id"))
      .def("actuators", &Robot::actuators, "every actuator, in id order")
      .def("sensors", &Robot::sensors, "every sensor, in id order")
      .def("body_names", &Robot::body_names)
      .def("site_names", &Robot::site_names)
      .def("camera_names", &Robot::camera_names)
      .def("keyframe_names", &Robot::keyframe_names)
      .def(
          "keyframe_qpos",
          [](const Robot& r, std::string_view name) {
            const auto q = r.keyframe_qpos(name);
            return to_array(q.data(), static_cast<Eigen::Index>(q.size()));
          },
          py::arg("name"), "qpos of a keyframe (nq,)")
      .def(
          "make_data", [](const Robot& r) { return DataHandle(r, r.make_data()); },
          "A fresh owned Data at the reference configuration, kinematics computed.")
      .def("__repr__", [](const Robot& r) {
        return "<Robot '" + r.name() + "' nq=" + std::to_string(r.nq()) +
               " nv=" + std::to_string(r.nv()) + " nu=" + std::to_string(r.nu()) + ">";
      });

  def_enum<DhConvention>(m, "DhConvention", "Where a DH row's constant transform sits.");
  def_enum<DhActuators>(m, "DhActuators", "How a DH arm's joints are driven.");
  auto dh_link = py::class_<DhLink>(m, "DhLink", "One row of a DH table: the link and its joint.");
  fields_init<DhLink>(dh_link, "DhLink");
  def_fields(dh_link);
  auto dh_arm = py::class_<DhArm>(
      m, "DhArm",
      "An arm from its DH table: links (DhLink rows), base (world) and tool (after the last row) "
      "as 4x4 transforms; dh_robot(arm) builds and loads it.");
  fields_init<DhArm>(dh_arm, "DhArm");
  def_fields(dh_arm);
  dh_arm.def_readwrite("links", &DhArm::links, "the table's rows, base to tool");
  fixed_property<DhArm>(dh_arm, "base", &DhArm::base, "the base frame in the world (4, 4)");
  fixed_property<DhArm>(dh_arm, "tool", &DhArm::tool,
                        "the end site in the last row's frame (4, 4)");
  m.def("dh_mjcf", &dh_mjcf, py::arg("arm"),
        "The arm's MJCF: bodies link1..n, joints joint1..n, site 'end', keyframe 'zero'.");
  m.def("dh_robot", &dh_robot, py::arg("arm"), "The arm's MJCF, loaded.");

  py::enum_<FrameKind>(m, "FrameKind")
      .value("site", FrameKind::site)
      .value("body", FrameKind::body);
  py::class_<FrameRef>(m, "FrameRef", "An end-effector frame: a site or a body.")
      .def_readonly("kind", &FrameRef::kind, "site or body")
      .def_readonly("id", &FrameRef::id, "the site's or body's id in the model")
      .def_readonly("name", &FrameRef::name, "the site's or body's name");

  py::class_<Chain>(m, "Chain",
                    "The joints an algorithm moves, in order (index i = column i of a Jacobian), "
                    "and the end-effector frame (a site or a body).")
      .def(py::init<const Robot&, std::string_view>(), py::arg("robot"), py::arg("frame"),
           "Every hinge and slide joint on the path from the world to the frame.")
      .def(py::init<const Robot&, const std::vector<std::string>&, std::string_view>(),
           py::arg("robot"), py::arg("joints"), py::arg("frame"), "An explicit list of joints.")
      .def_property_readonly("robot", &Chain::robot, "the model the chain belongs to")
      .def_property_readonly("frame", &Chain::frame, "the end-effector frame (a site or a body)")
      .def_property_readonly("size", &Chain::size, "number of joints n")
      .def("__len__", &Chain::size)
      .def_property_readonly("joint_names", &Chain::joint_names,
                             "name of each chain joint, base to tip (n,)")
      .def_property_readonly("joint_ids", &Chain::joint_ids,
                             "model id of each chain joint, base to tip (n,)")
      .def_property_readonly("dof_addresses", &Chain::dof_addresses,
                             "index into qvel of each chain joint (n,)")
      .def_property_readonly(
          "qpos_addresses",
          [](const Chain& c) {
            std::vector<int> a;
            for (int i = 0; i < c.size(); ++i) a.push_back(c.qpos_address(i));
            return a;
          },
          "index into qpos of each chain joint (n,)")
      .def("actuator", &Chain::actuator, py::arg("i"), "actuator driving joint i, or None")
      .def_property_readonly(
          "lower", [](const Chain& c) { return Eigen::VectorXd(c.lower()); },
          "joint lower bounds (n,) [rad or m]; -inf when unlimited")
      .def_property_readonly(
          "upper", [](const Chain& c) { return Eigen::VectorXd(c.upper()); },
          "joint upper bounds (n,)")
      .def("center", &Chain::center, "middle of each range (n,) (0 when unlimited)")
      .def(
          "within_limits",
          [](const Chain& c, py::handle q, double tol) {
            return c.within_limits(to_vector(q, "q", c.size()), tol);
          },
          py::arg("q"), py::arg("tolerance") = 0.0)
      .def(
          "clamp",
          [](const Chain& c, py::handle q) { return c.clamp(to_vector(q, "q", c.size())); },
          py::arg("q"), "q clipped into the bounds (n,)")
      .def(
          "gather",
          [](const Chain& c, py::handle qpos) {
            const Eigen::VectorXd full = to_vector(qpos, "qpos", c.robot().nq());
            return c.gather(full.data());
          },
          py::arg("qpos"), "the chain's joint values (n,) from a full qpos (nq,)")
      .def(
          "scatter",
          [](const Chain& c, py::handle q, py::handle qpos) {
            Eigen::VectorXd full = to_vector(qpos, "qpos", c.robot().nq());
            c.scatter(to_vector(q, "q", c.size()), full.data());
            return full;
          },
          py::arg("q"), py::arg("qpos"), "a copy of qpos (nq,) with the chain's joints set to q")
      .def("__repr__", [](const Chain& c) {
        return "<Chain " + std::to_string(c.size()) + " joints -> " + c.frame().name + ">";
      });

  static const std::string max_elements_doc =
      "Sets the bound on a model's elements (XML elements, <replicate> copies counted) for "
      "every later load in this process: Robot.from_file/from_string/bundled, scenes, "
      "environments (the CLI's --max-model-elements; default " +
      std::to_string(kDefaultMaxModelElements) + "). Raises mjarm.Error for 0 or more than " +
      std::to_string(kLargestMaxModelElements) + ".";
  m.def("set_max_model_elements", &set_max_model_elements, py::arg("count"),
        max_elements_doc.c_str());
  m.def("max_model_elements", &max_model_elements,
        "The bound on a model's elements that every load applies (set_max_model_elements).");
  m.def("find_frame", &find_frame, py::arg("robot"), py::arg("name"),
        "The frame called name: a site first, then a body.");
}

}  // namespace mjarm::python
