#include "mjarm/env/observation_set.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mjarm/error.hpp"
#include "mjarm/lie/rotation.hpp"
#include "mjarm/model/names.hpp"
#include "observation_pixels.hpp"

namespace mjarm {
namespace {

constexpr std::string_view kSensorPrefix = "sensor:";

std::string names_text(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "(none)" : out;
}

const std::vector<std::string>& builtin_observations() {
  static const std::vector<std::string> names{"joint_positions", "joint_velocities", "ee_pose",
                                              "ee_twist", "contact_forces"};
  return names;
}

// the spec of MJCF sensor @p id: its dimension, bounded by its cutoff (and at 0 when positive)
ArraySpec sensor_spec(const mjModel& m, int id, const std::string& name) {
  ArraySpec spec = ArraySpec::vector(name, m.sensor_dim[id]);
  const double cutoff = m.sensor_cutoff[id];
  if (cutoff > 0.0) {
    spec.minimum.setConstant(-cutoff);
    spec.maximum.setConstant(cutoff);
  }
  if (m.sensor_datatype[id] == mjDATATYPE_POSITIVE) spec.minimum.setZero();
  return spec;
}

// contact_forces needs contacts: not disabled, and some geom of the arm that collides
void check_contacts_on(const Robot& robot, const GeomSet& arm, const std::string& task) {
  const mjModel& m = robot.model();
  if (m.opt.disableflags & mjDSBL_CONTACT)
    throw Error("observation 'contact_forces' is switched off in task '" + task + "': model '" +
                robot.name() + "' disables contacts (<flag contact=\"disable\"/>)");
  for (int g = 0; g < m.ngeom; ++g) {
    if (arm.contains(g) && (m.geom_contype[g] != 0 || m.geom_conaffinity[g] != 0)) return;
  }
  throw Error("observation 'contact_forces' is switched off in task '" + task +
              "': no geom of the "
              "arm in model '" +
              robot.name() + "' collides (contype = conaffinity = 0)");
}

}  // namespace

const std::vector<std::string>& ObservationSet::task_names() {
  static const std::vector<std::string> names{
      "target", "target_offset", "object_pose", "object_velocity", "wrench", "insertion", "grasp"};
  return names;
}

std::vector<std::string> ObservationSet::available(const EnvTask& task) {
  std::vector<std::string> names = builtin_observations();
  for (const ArraySpec& spec : task.observation_specs()) names.push_back(spec.name);
  const mjModel& m = task.robot().model();
  for (int id = 0; id < m.nsensor; ++id) {
    const char* name = mj_id2name(&m, mjOBJ_SENSOR, id);
    if (name != nullptr && name[0] != '\0') names.push_back(std::string(kSensorPrefix) + name);
  }
  for (std::string& p : pixel_observations(task.robot())) names.push_back(std::move(p));
  return names;
}

ObservationSet::~ObservationSet() = default;

ObservationSet::ObservationSet(const EnvTask& task, Simulation& sim,
                               const std::vector<std::string>& names, int pixels_width,
                               int pixels_height) {
  const std::string task_name(task.name());
  if (names.empty())
    throw Error("observations of task '" + task_name +
                "': none requested; available: " + names_text(available(task)));
  const Chain& chain = task.chain();
  const Robot& robot = task.robot();
  const mjModel& m = robot.model();
  const int n = chain.size();
  const std::vector<ArraySpec> task_specs = task.observation_specs();
  std::vector<ArraySpec> specs;
  for (const std::string& name : names) {
    Entry entry;
    if (name == "joint_positions") {
      entry.source = Source::joint_positions;
      // unbounded: MuJoCo's joint limits are soft, the arm can pass them (a spec promises
      // every value the environment can return)
      specs.push_back(ArraySpec::vector(name, n));
    } else if (name == "joint_velocities") {
      entry.source = Source::joint_velocities;
      specs.push_back(ArraySpec::vector(name, n));
    } else if (name == "ee_pose") {
      entry.source = Source::ee_pose;
      ArraySpec spec = ArraySpec::vector(name, 7);
      spec.minimum.tail<4>().setConstant(-1.0);
      spec.maximum.tail<4>().setConstant(1.0);
      specs.push_back(spec);
    } else if (name == "ee_twist") {
      entry.source = Source::ee_twist;
      specs.push_back(ArraySpec::vector(name, 6));
    } else if (name == "contact_forces") {
      entry.source = Source::contact_forces;
      const int root =
          m.body_rootid[chain.frame().kind == FrameKind::site ? m.site_bodyid[chain.frame().id]
                                                              : chain.frame().id];
      const char* root_name = mj_id2name(&m, mjOBJ_BODY, root);
      const GeomSet arm = GeomSet::of_bodies(robot, {root_name ? root_name : ""});
      check_contacts_on(robot, arm, task_name);
      entry.index = sim.watch_contacts(arm, GeomSet{});
      specs.push_back(ArraySpec::vector(name, 3));
    } else if (name.rfind("pixels:", 0) == 0 || name.rfind("depth:", 0) == 0) {
      const bool pixels = name[0] == 'p';
      if (!cameras_) cameras_ = std::make_unique<Cameras>(robot, pixels_width, pixels_height);
      entry.source = pixels ? Source::pixels : Source::depth;
      entry.index = cameras_->camera(name.substr(pixels ? 7 : 6));
      ArraySpec spec;
      spec.name = name;
      spec.shape = pixels ? std::vector<int>{pixels_height, pixels_width, 3}
                          : std::vector<int>{pixels_height, pixels_width};
      spec.minimum = Eigen::VectorXd::Zero(spec.size());
      spec.maximum = Eigen::VectorXd::Constant(
          spec.size(), pixels ? 255.0 : std::numeric_limits<double>::infinity());
      specs.push_back(spec);
    } else if (name.rfind(kSensorPrefix, 0) == 0) {
      const std::string sensor = name.substr(kSensorPrefix.size());
      const int id = try_find_object(m, mjOBJ_SENSOR, sensor);
      if (id < 0) {
        std::vector<std::string> sensors;
        for (const std::string& a : available(task))
          if (a.rfind(kSensorPrefix, 0) == 0) sensors.push_back(a);
        throw Error("observation '" + name + "': model '" + robot.name() + "' has no sensor '" +
                    sensor + "'" +
                    (sensors.empty() ? std::string("; it has no named sensors")
                                     : "; sensors: " + names_text(sensors)));
      }
      entry.source = Source::sensor;
      entry.index = id;
      specs.push_back(sensor_spec(m, id, name));
    } else {
      const auto it = std::find_if(task_specs.begin(), task_specs.end(),
                                   [&](const ArraySpec& s) { return s.name == name; });
      if (it == task_specs.end()) {
        std::vector<std::string> provided;
        for (const ArraySpec& s : task_specs) provided.push_back(s.name);
        const auto& known = task_names();
        if (std::find(known.begin(), known.end(), name) != known.end())
          throw Error(
              "observation '" + name + "' is switched off in task '" + task_name +
              "' (the task does not provide it; task observations: " + names_text(provided) + ")");
        const std::vector<std::string> all = available(task);
        const std::vector<std::string> close = closest_names(name, all);
        throw Error("unknown observation '" + name + "' for task '" + task_name + "'" +
                    (close.empty() ? "" : "; closest: " + names_text(close)) +
                    "; available: " + names_text(all));
      }
      entry.source = Source::task;
      entry.index = static_cast<int>(it - task_specs.begin());
      specs.push_back(*it);
    }
    entries_.push_back(entry);
  }
  spec_ = ObservationSpec(std::move(specs));  // refuses a name listed twice
}

void ObservationSet::fill(const StepContext& context, const EnvTask& task,
                          std::span<double> out) const noexcept {
  const Chain& chain = task.chain();
  const mjData& d = context.data();
  const int n = chain.size();
  if (cameras_) cameras_->rendered = -1;  // a new state: pictures are drawn again
  for (std::size_t k = 0; k < entries_.size(); ++k) {
    const Entry& e = entries_[k];
    const int size = spec_.arrays()[k].size();
    double* o = out.data() + spec_.offset(static_cast<int>(k));
    switch (e.source) {
      case Source::joint_positions:
        for (int i = 0; i < n; ++i) o[i] = d.qpos[chain.qpos_address(i)];
        break;
      case Source::joint_velocities:
        for (int i = 0; i < n; ++i) o[i] = d.qvel[chain.dof_address(i)];
        break;
      case Source::ee_pose: {
        const Eigen::Vector4d q = quaternion_from_rotation(context.X_WE.R);
        for (int i = 0; i < 3; ++i) o[i] = context.X_WE.p[i];
        for (int i = 0; i < 4; ++i) o[3 + i] = q[i];
        break;
      }
      case Source::ee_twist:
        for (int i = 0; i < 6; ++i) o[i] = context.V_WE[i];
        break;
      case Source::contact_forces: {
        // the watch reports the force the arm exerts on the rest: the arm feels the opposite
        const Eigen::Vector3d& f = context.simulation().contacts(e.index).force_W;
        for (int i = 0; i < 3; ++i) o[i] = -f[i];
        break;
      }
      case Source::sensor: {
        const mjModel& m = context.simulation().model();
        const double* values = d.sensordata + m.sensor_adr[e.index];
        for (int i = 0; i < size; ++i) o[i] = values[i];
        break;
      }
      case Source::task:
        task.observe(e.index, context, std::span<double>(o, static_cast<std::size_t>(size)));
        break;
      case Source::pixels:
        cameras_->render(e.index, d);
        std::copy(cameras_->image.rgb.begin(), cameras_->image.rgb.end(), o);
        break;
      case Source::depth:
        cameras_->render(e.index, d);
        std::copy(cameras_->depth.begin(), cameras_->depth.end(), o);
        break;
    }
  }
}

}  // namespace mjarm
