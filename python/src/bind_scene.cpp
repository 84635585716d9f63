// scene room: the parts of a scene (specs), Scene (compose, find and edit, compile), scene files,
// the pose of a free object in a Data.
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
  py::enum_<ObjectShape>(m, "ObjectShape", "Shapes of objects and fixtures.")
      .value("box", ObjectShape::box)
      .value("sphere", ObjectShape::sphere)
      .value("cylinder", ObjectShape::cylinder)
      .value("capsule", ObjectShape::capsule)
      .value("mesh", ObjectShape::mesh);
  py::enum_<SensorType>(m, "SensorType", "Sensor types a scene can add.")
      .value("jointpos", SensorType::jointpos)
      .value("framepos", SensorType::framepos)
      .value("framequat", SensorType::framequat)
      .value("touch", SensorType::touch)
      .value("force", SensorType::force)
      .value("torque", SensorType::torque);

  auto arena = py::class_<ArenaSpec>(
      m, "ArenaSpec",
      "Floor, two lights and an optional table. Names: arena/floor, arena/table (body), "
      "arena/table_top (geom), arena/table_surface (site on the top's centre).");
  fields_init<ArenaSpec>(arena, "ArenaSpec");
  array_property<ArenaSpec>(arena, "floor_half_size", &ArenaSpec::floor_half_size,
                            "floor plane half extents x, y (2,) [m]");
  arena.def_readwrite("table", &ArenaSpec::table, "add a table");
  array_property<ArenaSpec>(arena, "table_center", &ArenaSpec::table_center,
                            "table centre x, y in world (2,) [m]");
  array_property<ArenaSpec>(arena, "table_half_size", &ArenaSpec::table_half_size,
                            "table top half extents x, y (2,) [m]");
  arena.def_readwrite("table_height", &ArenaSpec::table_height, "top surface height [m]");
  array_property<ArenaSpec>(arena, "table_friction", &ArenaSpec::table_friction,
                            "sliding, torsional, rolling (3,)");

  auto robot = py::class_<RobotSpec>(
      m, "RobotSpec",
      "A robot from any MJCF (bundled name or file); its names get the prefix name + '/', its "
      "root bodies sit in a fixed body 'name' at pos, quat.");
  fields_init<RobotSpec>(robot, "RobotSpec");
  robot.def_readwrite("name", &RobotSpec::name, "prefix, unique in the scene")
      .def_readwrite("model", &RobotSpec::model, "bundled name or MJCF file path");
  array_property<RobotSpec>(robot, "pos", &RobotSpec::pos, "mount position in world (3,) [m]");
  array_property<RobotSpec>(robot, "quat", &RobotSpec::quat, "mount orientation (4,) w, x, y, z");
  robot.def_readwrite("keep_arena", &RobotSpec::keep_arena,
                      "keep the model's own floor planes, lights and skybox");

  auto gripper = py::class_<GripperSpec>(
      m, "GripperSpec",
      "A gripper MJCF attached rigidly at a site or body of a robot (no joint in between); names "
      "get the prefix robot + '/' + name + '/'.");
  fields_init<GripperSpec>(gripper, "GripperSpec");
  gripper.def_readwrite("robot", &GripperSpec::robot, "a robot already in the scene")
      .def_readwrite("model", &GripperSpec::model, "bundled gripper name or MJCF file path")
      .def_readwrite("frame", &GripperSpec::frame, "site or body of the robot, unprefixed")
      .def_readwrite("name", &GripperSpec::name, "prefix inside the robot's");

  auto object = py::class_<ObjectSpec>(
      m, "ObjectSpec",
      "A rigid object: free (Scene.add_object: a free joint, nq += 7) or fixed "
      "(Scene.add_fixture). Names: body 'name', geom 'name/geom', site 'name/center', joint "
      "'name/joint', mesh 'name/mesh'.");
  fields_init<ObjectSpec>(object, "ObjectSpec");
  object.def_readwrite("name", &ObjectSpec::name);
  enum_property<ObjectSpec>(
      object, "shape", &ObjectSpec::shape, [](const std::string& s) { return object_shape(s); },
      "ObjectShape or its name ('box', 'sphere', 'cylinder', 'capsule', 'mesh')");
  list_property<ObjectSpec>(object, "size", &ObjectSpec::size,
                            "box: 3 half extents; sphere: radius; cylinder, capsule: radius, "
                            "half length [m]; mesh: 3 scale factors or empty");
  object.def_readwrite("mesh_file", &ObjectSpec::mesh_file, "STL/OBJ/MSH file, for shape mesh")
      .def_readwrite("mass", &ObjectSpec::mass, "[kg], > 0");
  array_property<ObjectSpec>(object, "friction", &ObjectSpec::friction,
                             "sliding, torsional, rolling (3,), >= 0");
  array_property<ObjectSpec>(object, "pos", &ObjectSpec::pos, "position in world (3,) [m]");
  array_property<ObjectSpec>(object, "quat", &ObjectSpec::quat, "orientation (4,) w, x, y, z");
  array_property<ObjectSpec>(object, "rgba", &ObjectSpec::rgba, "colour (4,)");

  auto compound = py::class_<CompoundFixtureSpec>(
      m, "CompoundFixtureSpec",
      "A fixture of several pieces (ObjectSpec, each at its pose in the fixture's frame) in one "
      "static body. Names: body 'name', geoms 'name/<piece>', site 'name/center'.");
  fields_init<CompoundFixtureSpec>(compound, "CompoundFixtureSpec");
  compound.def_readwrite("name", &CompoundFixtureSpec::name);
  array_property<CompoundFixtureSpec>(compound, "pos", &CompoundFixtureSpec::pos,
                                      "position of the body in world (3,) [m]");
  array_property<CompoundFixtureSpec>(compound, "quat", &CompoundFixtureSpec::quat,
                                      "orientation (4,) w, x, y, z");
  compound.def_readwrite("pieces", &CompoundFixtureSpec::pieces,
                         "list[ObjectSpec]; a copy: assign the whole list");

  auto camera = py::class_<SceneCameraSpec>(
      m, "SceneCameraSpec", "A camera fixed to a body (or the world), optionally tracking a body.");
  fields_init<SceneCameraSpec>(camera, "SceneCameraSpec");
  camera.def_readwrite("name", &SceneCameraSpec::name)
      .def_readwrite("body", &SceneCameraSpec::body, "parent body, '' for the world");
  array_property<SceneCameraSpec>(camera, "pos", &SceneCameraSpec::pos,
                                  "in the parent body (3,) [m]");
  array_property<SceneCameraSpec>(camera, "xyaxes", &SceneCameraSpec::xyaxes,
                                  "image x and y axes in the parent body (6,); zeros: use quat");
  array_property<SceneCameraSpec>(camera, "quat", &SceneCameraSpec::quat, "(4,) w, x, y, z");
  camera.def_readwrite("fovy", &SceneCameraSpec::fovy, "vertical field of view [deg]")
      .def_readwrite("target", &SceneCameraSpec::target, "body to look at, or ''");

  auto site = py::class_<SiteSpec>(m, "SiteSpec", "A site on a body (or the world).");
  fields_init<SiteSpec>(site, "SiteSpec");
  site.def_readwrite("name", &SiteSpec::name)
      .def_readwrite("body", &SiteSpec::body, "parent body, '' for the world");
  array_property<SiteSpec>(site, "pos", &SiteSpec::pos, "in the parent body (3,) [m]");
  array_property<SiteSpec>(site, "quat", &SiteSpec::quat, "(4,) w, x, y, z");
  site.def_readwrite("size", &SiteSpec::size, "sphere radius [m]");
  array_property<SiteSpec>(site, "rgba", &SiteSpec::rgba, "colour (4,)");

  auto sensor = py::class_<SensorSpec>(
      m, "SensorSpec",
      "A sensor on a named element: a joint (jointpos), a site (touch, force, torque) or a site, "
      "body, geom or camera (framepos, framequat).");
  fields_init<SensorSpec>(sensor, "SensorSpec");
  sensor.def_readwrite("name", &SensorSpec::name);
  enum_property<SensorSpec>(
      sensor, "type", &SensorSpec::type, [](const std::string& s) { return sensor_type(s); },
      "SensorType or its name");
  sensor.def_readwrite("target", &SensorSpec::target, "the element it reads");

  auto weld = py::class_<WeldSpec>(
      m, "WeldSpec", "A weld equality between two bodies, inactive unless active is set.");
  fields_init<WeldSpec>(weld, "WeldSpec");
  weld.def_readwrite("name", &WeldSpec::name)
      .def_readwrite("body1", &WeldSpec::body1, "e.g. 'arm/hand'")
      .def_readwrite("body2", &WeldSpec::body2, "e.g. 'cube'")
      .def_readwrite("active", &WeldSpec::active);
  array_property<WeldSpec>(weld, "solref", &WeldSpec::solref,
                           "time constant [s], damping ratio (2,)");

  auto free = py::class_<FreePose>(m, "FreePose", "Pose of a free body B in world W.");
  fields_init<FreePose>(free, "FreePose");
  array_property<FreePose>(free, "p_WB", &FreePose::p_WB, "position (3,) [m]");
  array_property<FreePose>(free, "quat_WB", &FreePose::quat_WB, "orientation (4,) w, x, y, z");
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
