// scene room: the parts of a scene (specs), Scene (compose, find and edit, compile), scene files,
// the pose of a free object in a Data.
#include "declared_fields.hpp"
#include "mjarm/scene/free_pose.hpp"
#include "mjarm/scene/scene.hpp"
#include "mjarm/scene/scene_file.hpp"
#include "mjarm/scene/scene_spec.hpp"
#include "spec_support.hpp"

namespace mjarm::python {
namespace {

/// `Scene.add_*`: a spec, or its fields as keywords.
template <typename T>
auto adder(void (Scene::*add)(const T&), const char* call, const char* type) {
  return [add, call, type](Scene& s, const py::object& spec, const py::kwargs& fields) {
    (s.*add)(spec_of<T>(spec, fields, call, type));
  };
}

/// The Data of @p robot that a free pose is written into: owned, or the user's mujoco.MjData.
mjData& writable_data(const Robot& robot, DataHandle& h, const char* call) {
  mjData& data = data_of(robot, h, call);
  if (!h.writable()) {
    throw Error(std::string(call) +
                ": only data from Robot.make_data() or a mujoco.MjData can be written here; a "
                "simulation's state is written with Simulation.set_state");
  }
  return data;
}

void bind_scene_specs(py::module_& m) {
  def_enum<ObjectShape>(m, "ObjectShape", "Shapes of objects and fixtures.");
  def_enum<SensorType>(m, "SensorType", "Sensor types a scene can add.");

  auto arena = py::class_<ArenaSpec>(
      m, "ArenaSpec",
      "Floor, two lights and an optional table. Names: arena/floor, arena/table (body), "
      "arena/table_top (geom), arena/table_surface (site on the top's centre).");
  fields_init<ArenaSpec>(arena, "ArenaSpec");
  def_fields(arena);

  auto robot = py::class_<RobotSpec>(
      m, "RobotSpec",
      "A robot from any MJCF (bundled name or file); its names get the prefix name + '/', its "
      "root bodies sit in a fixed body 'name' at pos, quat.");
  fields_init<RobotSpec>(robot, "RobotSpec");
  def_fields(robot);

  auto gripper = py::class_<GripperSpec>(
      m, "GripperSpec",
      "A gripper MJCF attached rigidly at a site or body of a robot (no joint in between); names "
      "get the prefix robot + '/' + name + '/'.");
  fields_init<GripperSpec>(gripper, "GripperSpec");
  def_fields(gripper);

  auto object = py::class_<ObjectSpec>(
      m, "ObjectSpec",
      "A rigid object: free (Scene.add_object: a free joint, nq += 7) or fixed "
      "(Scene.add_fixture). Names: body 'name', geom 'name/geom', site 'name/center', joint "
      "'name/joint', mesh 'name/mesh'.");
  fields_init<ObjectSpec>(object, "ObjectSpec");
  def_fields(object);
  // the enum fields also take their names
  enum_property<ObjectSpec>(
      object, "shape", &ObjectSpec::shape, [](const std::string& s) { return object_shape(s); },
      "ObjectShape or its name ('box', 'sphere', 'cylinder', 'capsule', 'mesh')");

  auto compound = py::class_<CompoundFixtureSpec>(
      m, "CompoundFixtureSpec",
      "A fixture of several pieces (ObjectSpec, each at its pose in the fixture's frame) in one "
      "static body. Names: body 'name', geoms 'name/<piece>', site 'name/center'.");
  fields_init<CompoundFixtureSpec>(compound, "CompoundFixtureSpec");
  def_fields(compound);
  compound.def_readwrite("pieces", &CompoundFixtureSpec::pieces,
                         "list[ObjectSpec]; a copy: assign the whole list");

  auto camera = py::class_<SceneCameraSpec>(
      m, "SceneCameraSpec", "A camera fixed to a body (or the world), optionally tracking a body.");
  fields_init<SceneCameraSpec>(camera, "SceneCameraSpec");
  def_fields(camera);

  auto site = py::class_<SiteSpec>(m, "SiteSpec", "A site on a body (or the world).");
  fields_init<SiteSpec>(site, "SiteSpec");
  def_fields(site);

  auto sensor = py::class_<SensorSpec>(
      m, "SensorSpec",
      "A sensor on a named element: a joint (jointpos), a site (touch, force, torque) or a site, "
      "body, geom or camera (framepos, framequat).");
  fields_init<SensorSpec>(sensor, "SensorSpec");
  def_fields(sensor);
  enum_property<SensorSpec>(
      sensor, "type", &SensorSpec::type, [](const std::string& s) { return sensor_type(s); },
      "SensorType or its name");

  auto weld = py::class_<WeldSpec>(
      m, "WeldSpec", "A weld equality between two bodies, inactive unless active is set.");
  fields_init<WeldSpec>(weld, "WeldSpec");
  def_fields(weld);

  auto free = py::class_<FreePose>(m, "FreePose", "Pose of a free body B in world W.");
  fields_init<FreePose>(free, "FreePose");
  def_fields(free);
}

}  // namespace

namespace {

/// A Python value as MJCF attribute text: a string as it is, a bool as true/false, a number or a
/// sequence of numbers in the shortest round-trip form, separated by spaces.
std::string mjcf_text(const py::handle& value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value))
    return number_text(value.cast<double>());
  const Eigen::VectorXd v = to_vector(value, "attribute value");
  std::string text;
  for (const double x : v) text += (text.empty() ? "" : " ") + number_text(x);
  return text;
}

}  // namespace

void bind_scene(py::module_& m) {
  bind_scene_specs(m);
  py::class_<Scene>(
      m, "Scene",
      "One MuJoCo model composed of parts (arena, robots, grippers, objects, fixtures, cameras, "
      "sites, sensors, welds), every part's names prefixed; found and edited by name, then "
      "compiled into a Robot. Every add_* takes a spec or its fields as keywords, checks it and "
      "leaves the scene unchanged when it raises mjarm.Error. A Scene is a value: copy() it per "
      "trial. docs/scene.md.")
      .def(py::init<std::string>(), py::arg("name") = "scene", "An empty scene (no floor).")
      .def(
          "add_arena",
          [](Scene& s, const py::object& spec, const py::kwargs& fields) {
            s.add_arena(spec.is_none()
                            ? from_fields<ArenaSpec>(fields, "ArenaSpec")
                            : spec_of<ArenaSpec>(spec, fields, "add_arena", "ArenaSpec"));
          },
          py::arg("spec") = py::none(),
          "add_arena(spec: ArenaSpec | None = None, **fields): floor, lights, optional table")
      .def("add_robot", adder(&Scene::add_robot, "add_robot", "RobotSpec"),
           py::arg("spec") = py::none(),
           "add_robot(spec: RobotSpec | None = None, **fields): a robot, names prefixed 'name/'")
      .def("attach_gripper", adder(&Scene::attach_gripper, "attach_gripper", "GripperSpec"),
           py::arg("spec") = py::none(),
           "attach_gripper(spec: GripperSpec | None = None, **fields): a gripper at a robot's "
           "site or body")
      .def("add_object", adder(&Scene::add_object, "add_object", "ObjectSpec"),
           py::arg("spec") = py::none(),
           "add_object(spec: ObjectSpec | None = None, **fields): a free object (nq += 7)")
      .def(
          "add_fixture",
          [](Scene& s, const py::object& spec, const py::kwargs& fields) {
            if (py::isinstance<CompoundFixtureSpec>(spec))
              s.add_fixture(
                  spec_of<CompoundFixtureSpec>(spec, fields, "add_fixture", "CompoundFixtureSpec"));
            else
              s.add_fixture(spec_of<ObjectSpec>(spec, fields, "add_fixture", "ObjectSpec"));
          },
          py::arg("spec") = py::none(),
          "add_fixture(spec: ObjectSpec | CompoundFixtureSpec | None = None, **fields): an "
          "object fixed to the world, or several pieces in one static body")
      .def("add_camera", adder(&Scene::add_camera, "add_camera", "SceneCameraSpec"),
           py::arg("spec") = py::none(),
           "add_camera(spec: SceneCameraSpec | None = None, **fields)")
      .def("add_site", adder(&Scene::add_site, "add_site", "SiteSpec"),
           py::arg("spec") = py::none(), "add_site(spec: SiteSpec | None = None, **fields)")
      .def("add_sensor", adder(&Scene::add_sensor, "add_sensor", "SensorSpec"),
           py::arg("spec") = py::none(), "add_sensor(spec: SensorSpec | None = None, **fields)")
      .def("add_weld", adder(&Scene::add_weld, "add_weld", "WeldSpec"),
           py::arg("spec") = py::none(),
           "add_weld(spec: WeldSpec | None = None, **fields): a weld, inactive unless asked")
      .def(
          "add",
          [](Scene& s, const std::string& tag, const std::string& name, const std::string& parent,
             const std::string& class_name, const py::object& attributes, const py::kwargs& more) {
            ElementSpec e{tag, name, parent, class_name, {}};
            const auto take = [&e](const py::handle& items) {
              for (const auto& [key, value] : items.cast<py::dict>())
                e.attributes.emplace_back(py::str(key).cast<std::string>(), mjcf_text(value));
            };
            if (!attributes.is_none()) take(attributes);
            take(more);
            s.add(e);
          },
          py::arg("tag"), py::arg("name"), py::arg("parent") = "", py::arg("class_name") = "",
          py::arg("attributes") = py::none(),
          "Adds any element by its MJCF tag (body, joint, geom, site, camera, light; general, "
          "motor, position, velocity; a sensor's tag; default) and attributes, given as keywords "
          "or a dict (a default's as 'geom.rgba'; values as text, numbers or sequences of "
          "numbers): checked now, with the closest names for an unknown tag, parent, class or "
          "attribute; the scene is unchanged when it raises. parent: the parent body ('' = the "
          "world), or a default's parent class; class_name: the default class it starts from.")
      .def("has", &Scene::has, py::arg("kind"), py::arg("name"),
           "Whether an element of kind ('body', 'joint', 'geom', 'site', 'camera', 'light', "
           "'actuator', 'sensor', 'tendon', 'equality', 'mesh', 'material', 'texture', "
           "'default') is called name.")
      .def("names", &Scene::names, py::arg("kind"), "Names of the elements of kind, sorted.")
      .def("attribute", &Scene::attribute, py::arg("kind"), py::arg("name"), py::arg("attribute"),
           "The MJCF attribute's value the element holds, as text (None where it holds none); "
           "an unknown element or attribute raises mjarm.Error with the closest names.")
      .def(
          "set_attribute",
          [](Scene& s, std::string_view kind, std::string_view name, std::string_view attribute,
             py::handle value) {
            if (py::isinstance<py::str>(value)) {
              s.set_attribute(kind, name, attribute, value.cast<std::string>());
            } else if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
              const double x = value.cast<double>();
              s.set_attribute(kind, name, attribute, std::span<const double>(&x, 1));
            } else {
              const Eigen::VectorXd v = to_vector(value, "value");
              s.set_attribute(kind, name, attribute,
                              std::span<const double>(v.data(), static_cast<size_t>(v.size())));
            }
          },
          py::arg("kind"), py::arg("name"), py::arg("attribute"), py::arg("value"),
          "Sets an MJCF attribute (text, a number or numbers (n,)); takes effect at the next "
          "compile(). The value is read now (kind, count, keywords); MuJoCo judges the rest at "
          "compile(). Renaming is refused.")
      .def("set_option", &Scene::set_option, py::arg("attribute"), py::arg("value"),
           "Sets <option attribute=value> (timestep, impratio, noslip_iterations, integrator, "
           "...); it wins over the parts' own.")
      .def("xml", &Scene::xml,
           "The scene as one MJCF document (MuJoCo's mj_saveXMLString: every number exact, "
           "radians, the combined keyframes); it loads into the model compile() gives.")
      .def(
          "compile",
          [](const Scene& s) {
            py::gil_scoped_release release;
            return s.compile();
          },
          "Compiles the scene into a Robot (GIL released); keyframes combined by name ('home' "
          "holds every part's home). MuJoCo's message on failure.")
      .def_property_readonly("name", &Scene::name, "the scene's (and the model's) name")
      .def_property_readonly("warnings", &Scene::warnings,
                             "MuJoCo's parser warnings and its word on the parts' global "
                             "settings (taken or merged)")
      .def(
          "copy", [](const Scene& s) { return Scene(s); }, "An independent copy.")
      .def("__copy__", [](const Scene& s) { return Scene(s); })
      .def(
          "__deepcopy__", [](const Scene& s, const py::dict&) { return Scene(s); }, py::arg("memo"))
      .def_static("bundled_grippers", &Scene::bundled_grippers,
                  "Names of the bundled grippers, sorted.");

  m.def("load_scene_file", &load_scene_file, py::arg("path"),
        "A Scene from a YAML or JSON file (docs/scene.md); errors name the line and the key.");
  m.def(
      "parse_scene",
      [](std::string_view text, const std::filesystem::path& base_dir, const std::string& source) {
        return parse_scene(text, base_dir, source);
      },
      py::arg("text"), py::arg("base_dir") = std::filesystem::path("."),
      py::arg("source") = "<scene>",
      "A Scene from YAML/JSON text; base_dir resolves relative paths, source names it in errors.");
  m.def("is_scene_file", &is_scene_file, py::arg("path"),
        "Whether path names a scene file (.yaml, .yml, .json).");

  m.def("free_qpos_address", &free_qpos_address, py::arg("robot"), py::arg("body"),
        "The qpos address of the free joint of a body (or of the free joint by name).");
  m.def(
      "set_free_pose",
      [](const Robot& robot, DataHandle& data, std::string_view body, py::handle p_WB,
         py::handle quat_WB) {
        FreePose X;
        const Eigen::Vector3d p = to_fixed<3>(p_WB, "p_WB");
        const Eigen::Vector4d q = to_fixed<4>(quat_WB, "quat_WB");
        for (int i = 0; i < 3; ++i) X.p_WB[i] = p[i];
        for (int i = 0; i < 4; ++i) X.quat_WB[i] = q[i];
        set_free_pose(robot, writable_data(robot, data, "set_free_pose"), body, X);
      },
      py::arg("robot"), py::arg("data"), py::arg("body"), py::arg("p_WB"),
      py::arg("quat_WB") = std::array<double, 4>{1.0, 0.0, 0.0, 0.0},
      "Writes a free body's pose p_WB (3,) [m], quat_WB (4,) w x y z (normalized) into owned "
      "data's qpos; call data.forward() after.");
  m.def(
      "free_pose",
      [](const Robot& robot, const DataHandle& data, std::string_view body) {
        return free_pose(robot, data_of(robot, data, "free_pose"), body);
      },
      py::arg("robot"), py::arg("data"), py::arg("body"),
      "The pose of a free body read from data.qpos (FreePose).");
}

}  // namespace mjarm::python
