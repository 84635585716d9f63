#include "mjarm/scene/scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"
#include "support/error_message.hpp"
#include "support/files.hpp"

namespace mjarm {
namespace {

using test::error_of;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

ObjectSpec cube_spec(const std::string& name, double x) {
  ObjectSpec cube;
  cube.name = name;
  cube.shape = ObjectShape::box;
  cube.size = {0.0075, 0.0075, 0.0075};
  cube.mass = 0.05;
  cube.friction = {1.2, 0.01, 0.0002};
  cube.pos = {x, 0.0, 0.42};
  return cube;
}

Scene two_robots_two_objects() {
  Scene scene("two_arms");
  ArenaSpec arena;
  arena.table = true;
  scene.add_arena(arena);
  scene.add_robot({"left", "arm6", {0.0, -0.6, 0.0}, {1, 0, 0, 0}, false});
  scene.add_robot({"right", "panda_hand", {0.0, 0.6, 0.4}, {0, 0, 0, 1}, false});
  scene.add_object(cube_spec("cube", 0.5));
  ObjectSpec ball;
  ball.name = "ball";
  ball.shape = ObjectShape::sphere;
  ball.size = {0.02};
  ball.pos = {0.6, 0.1, 0.45};
  scene.add_object(ball);
  return scene;
}

TEST(Scene, TwoRobotsAndTwoObjectsCompileWithoutClash) {
  const Robot arm6 = Robot::bundled("arm6");
  const Robot panda = Robot::bundled("panda_hand");
  const Robot robot = two_robots_two_objects().compile();
  EXPECT_EQ(robot.name(), "two_arms");
  EXPECT_EQ(robot.nq(), arm6.nq() + panda.nq() + 2 * 7);
  EXPECT_EQ(robot.nv(), arm6.nv() + panda.nv() + 2 * 6);
  EXPECT_EQ(robot.nu(), arm6.nu() + panda.nu());
  EXPECT_EQ(robot.nq(), 8 + 9 + 14);
  // the robots' own floors are left out: one floor, the arena's
  EXPECT_EQ(try_find_object(robot.model(), mjOBJ_GEOM, "left/floor"), -1);
  EXPECT_GE(robot.geom("arena/floor"), 0);
  EXPECT_GE(robot.geom("arena/table_top"), 0);
  int skyboxes = 0;
  for (int t = 0; t < robot.model().ntex; ++t)
    skyboxes += robot.model().tex_type[t] == mjTEXTURE_SKYBOX;
  EXPECT_EQ(skyboxes, 1);
}

TEST(Scene, KeepArenaKeepsARobotsOwnFloorAndLights) {
  Scene scene;
  scene.add_robot({"arm", "arm6", {}, {1, 0, 0, 0}, true});
  const Robot robot = scene.compile();
  EXPECT_GE(robot.geom("arm/floor"), 0);
  EXPECT_EQ(robot.model().nlight, Robot::bundled("arm6").model().nlight);
}

TEST(Scene, PrefixedReferencesResolveToThePartsOwnElements) {
  const Robot arm6 = Robot::bundled("arm6");
  const Robot panda = Robot::bundled("panda_hand");
  const Robot robot = two_robots_two_objects().compile();
  const mjModel& m = robot.model();
  for (const auto& [prefix, alone] : {std::pair{"left", &arm6}, std::pair{"right", &panda}}) {
    const mjModel& a = alone->model();
    for (int i = 0; i < a.nu; ++i) {
      const std::string name = mj_id2name(&a, mjOBJ_ACTUATOR, i);
      const int id = robot.actuator(std::string(prefix) + "/" + name);
      const std::string joint = mj_id2name(&a, mjOBJ_JOINT, a.actuator_trnid[2 * i]);
      EXPECT_EQ(m.actuator_trnid[2 * id], robot.joint(std::string(prefix) + "/" + joint)) << name;
      EXPECT_EQ(m.actuator_gainprm[id * mjNGAIN], a.actuator_gainprm[i * mjNGAIN]) << name;
    }
    // geoms take the values of their own default classes (friction, contype)
    for (int g = 0; g < a.ngeom; ++g) {
      const char* n = mj_id2name(&a, mjOBJ_GEOM, g);
      if (!n || std::string(n) == "floor") continue;
      const int id = robot.geom(std::string(prefix) + "/" + n);
      EXPECT_EQ(m.geom_contype[id], a.geom_contype[g]) << n;
      EXPECT_EQ(m.geom_conaffinity[id], a.geom_conaffinity[g]) << n;
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(m.geom_friction[3 * id + k], a.geom_friction[3 * g + k]) << n;
      for (int k = 0; k < 3; ++k) EXPECT_EQ(m.geom_size[3 * id + k], a.geom_size[3 * g + k]) << n;
    }
    for (int j = 0; j < a.njnt; ++j) {
      const int id = robot.joint(std::string(prefix) + "/" + mj_id2name(&a, mjOBJ_JOINT, j));
      EXPECT_EQ(m.jnt_range[2 * id], a.jnt_range[2 * j]);
      EXPECT_EQ(m.jnt_range[2 * id + 1], a.jnt_range[2 * j + 1]);
      EXPECT_EQ(m.dof_damping[m.jnt_dofadr[id]], a.dof_damping[a.jnt_dofadr[j]]);
    }
  }
  // objects: geom and free joint of their own
  const int cube = robot.body("cube");
  EXPECT_EQ(m.jnt_type[m.body_jntadr[cube]], mjJNT_FREE);
  EXPECT_EQ(m.geom_bodyid[robot.geom("cube/geom")], cube);
  EXPECT_NEAR(m.body_mass[cube], 0.05, 1e-12);
  EXPECT_EQ(m.geom_friction[3 * robot.geom("cube/geom")], 1.2);
  EXPECT_EQ(m.jnt_type[robot.joint("ball/joint")], mjJNT_FREE);
}

TEST(Scene, RobotsSitWhereTheyAreMounted) {
  const Robot panda = Robot::bundled("panda_hand");
  const Robot robot = two_robots_two_objects().compile();
  DataPtr alone = panda.make_data();
  DataPtr scene = robot.make_data();
  const double* p = alone->site_xpos + 3 * panda.site("tcp");
  const double* s = scene->site_xpos + 3 * robot.site("right/tcp");
  // mounted at (0, 0.6, 0.4), turned by pi about z
  EXPECT_NEAR(s[0], -p[0], 1e-12);
  EXPECT_NEAR(s[1], 0.6 - p[1], 1e-12);
  EXPECT_NEAR(s[2], 0.4 + p[2], 1e-12);
}

TEST(Scene, AttachedGripperKeepsTheArmsJointsAndAddsOnlyTheFingers) {
  Scene scene("panda_with_hand");
  scene.add_robot({"arm", "panda", {}, {1, 0, 0, 0}, false});
  const int arm_nq = scene.compile().nq();
  scene.attach_gripper({"arm", "franka_hand", "attachment_site", "hand"});
  const Robot robot = scene.compile();
  const Robot reference = Robot::bundled("panda_hand");
  EXPECT_EQ(arm_nq, 7);
  EXPECT_EQ(robot.nq(), arm_nq + 2);
  EXPECT_EQ(robot.nq(), reference.nq());
  EXPECT_EQ(robot.nu(), reference.nu());
  // same kinematics and mass as the bundled panda_hand, at random configurations
  DataPtr a = robot.make_data();
  DataPtr b = reference.make_data();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (int trial = 0; trial < 20; ++trial) {
    for (int i = 0; i < 7; ++i) a->qpos[i] = b->qpos[i] = u(rng);
    a->qpos[7] = b->qpos[7] = 0.02;
    a->qpos[8] = b->qpos[8] = 0.03;
    mj_kinematics(&robot.model(), a.get());
    mj_kinematics(&reference.model(), b.get());
    for (const char* site : {"tcp"}) {
      const double* p = a->site_xpos + 3 * robot.site(std::string("arm/hand/") + site);
      const double* q = b->site_xpos + 3 * reference.site(site);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(p[k], q[k], 1e-12);
    }
    for (const char* body : {"finger_left", "finger_right"}) {
      const double* p = a->xpos + 3 * robot.body(std::string("arm/hand/") + body);
      const double* q = b->xpos + 3 * reference.body(body);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(p[k], q[k], 1e-12);
    }
  }
  double mass_a = 0.0, mass_b = 0.0;
  for (int i = 0; i < robot.model().nbody; ++i) mass_a += robot.model().body_mass[i];
  for (int i = 0; i < reference.model().nbody; ++i) mass_b += reference.model().body_mass[i];
  EXPECT_NEAR(mass_a, mass_b, 1e-12);
}

TEST(Scene, GripperAttachesToABodyToo) {
  Scene scene;
  scene.add_robot({"arm", "panda", {}, {1, 0, 0, 0}, false});
  scene.attach_gripper({"arm", "franka_hand", "link7", "hand"});
  const Robot robot = scene.compile();
  EXPECT_EQ(robot.nq(), 9);
  EXPECT_EQ(robot.model().body_parentid[robot.body("arm/hand")], robot.body("arm/link7"));
}

TEST(Scene, EditsTakeEffectAfterCompile) {
  Scene scene = two_robots_two_objects();
  const std::vector<double> gain{3200.0};
  const std::vector<double> bias{0.0, -3200.0, -10.0};
  scene.set_attribute("actuator", "left/finger_left", "gainprm", gain);
  scene.set_attribute("actuator", "left/finger_left", "biasprm", bias);
  const std::vector<double> travel{0.0, 0.012};
  scene.set_attribute("actuator", "left/finger_left", "ctrlrange", travel);
  scene.set_attribute("joint", "left/finger_left", "range", travel);
  const std::vector<double> half{0.01, 0.02, 0.03};
  scene.set_attribute("geom", "cube/geom", "size", half);
  const std::vector<double> pos{0.3, -0.2, 0.5};
  scene.set_attribute("body", "ball", "pos", pos);
  EXPECT_EQ(scene.attribute("geom", "cube/geom", "size"), "0.01 0.02 0.03");
  // the value the element holds, written or not; nullopt where it holds none
  EXPECT_EQ(scene.attribute("geom", "cube/geom", "margin"), "0");
  EXPECT_EQ(scene.attribute("geom", "cube/geom", "fromto"), std::nullopt);
  EXPECT_EQ(scene.attribute("actuator", "left/finger_left", "gainprm"), "3200 0 0 0 0 0 0 0 0 0");

  const Robot robot = scene.compile();
  const mjModel& m = robot.model();
  const int a = robot.actuator("left/finger_left");
  EXPECT_EQ(m.actuator_gainprm[a * mjNGAIN], 3200.0);
  EXPECT_EQ(m.actuator_biasprm[a * mjNBIAS + 1], -3200.0);
  EXPECT_EQ(m.actuator_ctrlrange[2 * a + 1], 0.012);
  EXPECT_EQ(m.jnt_range[2 * robot.joint("left/finger_left") + 1], 0.012);
  const int g = robot.geom("cube/geom");
  EXPECT_EQ(m.geom_size[3 * g + 2], 0.03);
  const double* ball = m.qpos0 + m.jnt_qposadr[robot.joint("ball/joint")];
  EXPECT_EQ(ball[0], 0.3);
  EXPECT_EQ(ball[2], 0.5);
}

TEST(Scene, CopiesAreIndependent) {
  const Scene base = two_robots_two_objects();
  Scene edited = base;
  const std::vector<double> mass{2.0};
  edited.set_attribute("geom", "cube/geom", "mass", mass);
  EXPECT_NEAR(edited.compile().model().body_mass[edited.compile().body("cube")], 2.0, 1e-12);
  const Robot original = base.compile();
  EXPECT_NEAR(original.model().body_mass[original.body("cube")], 0.05, 1e-12);
}

TEST(Scene, SensorsCamerasSitesAndAnInactiveWeld) {
  Scene scene = two_robots_two_objects();
  scene.add_site({"left/pad", "left/link6", {0, 0, 0.12}, {1, 0, 0, 0}, 0.01, {1, 0, 0, 1}});
  scene.add_camera(
      {"overview", "", {1.5, 0, 1.2}, {0, 1, 0, -0.6, 0, 0.8}, {1, 0, 0, 0}, 50.0, ""});
  scene.add_camera({"follow", "", {1.0, 1.0, 1.0}, {}, {1, 0, 0, 0}, 45.0, "cube"});
  scene.add_sensor({"q1", SensorType::jointpos, "left/joint1"});
  scene.add_sensor({"cube_p", SensorType::framepos, "cube"});
  scene.add_sensor({"cube_q", SensorType::framequat, "cube"});
  scene.add_sensor({"grip_p", SensorType::framepos, "left/grip"});
  scene.add_sensor({"pad_touch", SensorType::touch, "left/pad"});
  scene.add_sensor({"pad_force", SensorType::force, "left/pad"});
  scene.add_sensor({"pad_torque", SensorType::torque, "left/pad"});
  scene.add_weld({"grasp", "left/link6", "cube", false, {0.002, 1.0}});
  const Robot robot = scene.compile();
  const mjModel& m = robot.model();
  const auto sensors = robot.sensors();
  ASSERT_EQ(sensors.size(), 7u);
  EXPECT_EQ(sensors[0].type, "jointpos");
  EXPECT_EQ(sensors[2].type, "framequat");
  EXPECT_EQ(sensors[2].dimension, 4);
  EXPECT_EQ(sensors[4].type, "touch");
  EXPECT_EQ(sensors[5].type, "force");
  EXPECT_EQ(sensors[6].type, "torque");
  EXPECT_EQ(m.cam_mode[robot.camera("follow")], mjCAMLIGHT_TARGETBODY);
  const int weld = try_find_object(m, mjOBJ_EQUALITY, "grasp");
  ASSERT_GE(weld, 0);
  EXPECT_EQ(m.eq_type[weld], mjEQ_WELD);
  EXPECT_EQ(m.eq_active0[weld], 0);
  EXPECT_EQ(m.eq_obj1id[weld], robot.body("left/link6"));
  EXPECT_EQ(m.eq_obj2id[weld], robot.body("cube"));
  EXPECT_EQ(m.eq_solref[2 * weld], 0.002);

  DataPtr d = robot.make_data();
  mj_forward(&m, d.get());
  const auto p = robot.sensor_values(*d, "cube_p");
  for (int k = 0; k < 3; ++k) EXPECT_EQ(p[k], d->xpos[3 * robot.body("cube") + k]);
  const auto g = robot.sensor_values(*d, "grip_p");
  for (int k = 0; k < 3; ++k) EXPECT_EQ(g[k], d->site_xpos[3 * robot.site("left/grip") + k]);
  EXPECT_EQ(robot.sensor_values(*d, "q1")[0], d->qpos[m.jnt_qposadr[robot.joint("left/joint1")]]);
}

TEST(Scene, KeyframesOfThePartsAreCombinedByName) {
  const Robot arm6 = Robot::bundled("arm6");
  const Robot panda = Robot::bundled("panda_hand");
  const Robot robot = two_robots_two_objects().compile();
  const auto home = robot.keyframe_qpos("home");
  const auto left = arm6.keyframe_qpos("home");
  const auto right = panda.keyframe_qpos("home");
  const mjModel& m = robot.model();
  EXPECT_EQ(home[m.jnt_qposadr[robot.joint("left/joint3")]], left[2]);
  EXPECT_EQ(home[m.jnt_qposadr[robot.joint("right/joint4")]], right[3]);
  // an object keeps its initial pose
  EXPECT_EQ(home[m.jnt_qposadr[robot.joint("cube/joint")]], 0.5);
  const int key = robot.keyframe("home");
  EXPECT_EQ(m.key_ctrl[key * m.nu + robot.actuator("right/joint4")], right[3]);
}

TEST(Scene, XmlLoadsIntoTheSameModel) {
  Scene scene = two_robots_two_objects();
  scene.add_robot({"arm", "panda", {1.0, 0.0, 0.0}, {1, 0, 0, 0}, false});
  scene.attach_gripper({"arm", "franka_hand", "attachment_site", "hand"});
  scene.add_weld({"grasp", "arm/hand/hand", "cube", false, {0.002, 1.0}});
  scene.add_camera({"follow", "", {1.0, 1.0, 1.0}, {}, {1, 0, 0, 0}, 45.0, "cube"});
  const std::vector<double> gain{3200.0};
  scene.set_attribute("actuator", "arm/hand/finger_left", "gainprm", gain);
  const Robot direct = scene.compile();
  const Robot reloaded = Robot::from_string(scene.xml());
  const mjModel& a = direct.model();
  const mjModel& b = reloaded.model();
  ASSERT_EQ(a.nq, b.nq);
  ASSERT_EQ(a.nbody, b.nbody);
  ASSERT_EQ(a.ngeom, b.ngeom);
  ASSERT_EQ(a.nu, b.nu);
  ASSERT_EQ(a.njnt, b.njnt);
  ASSERT_EQ(a.nkey, b.nkey);
  const auto same = [](const double* x, const double* y, int n, const char* what) {
    for (int i = 0; i < n; ++i) EXPECT_EQ(x[i], y[i]) << what << "[" << i << "]";
  };
  same(a.body_pos, b.body_pos, 3 * a.nbody, "body_pos");
  same(a.body_quat, b.body_quat, 4 * a.nbody, "body_quat");
  same(a.body_mass, b.body_mass, a.nbody, "body_mass");
  same(a.geom_size, b.geom_size, 3 * a.ngeom, "geom_size");
  same(a.geom_friction, b.geom_friction, 3 * a.ngeom, "geom_friction");
  same(a.jnt_range, b.jnt_range, 2 * a.njnt, "jnt_range");
  same(a.actuator_gainprm, b.actuator_gainprm, mjNGAIN * a.nu, "actuator_gainprm");
  same(a.key_qpos, b.key_qpos, a.nq * a.nkey, "key_qpos");
  same(a.eq_data, b.eq_data, mjNEQDATA * a.neq, "eq_data");
}

TEST(Scene, NameClashesAreNamed) {
  Scene scene = two_robots_two_objects();
  std::string message = error_of([&] { scene.add_object(cube_spec("cube", 0.3)); });
  EXPECT_TRUE(contains(message, "name clash in scene 'two_arms'")) << message;
  EXPECT_TRUE(contains(message, "already defined by object 'cube'")) << message;
  message = error_of([&] { scene.add_robot({"left", "panda", {}, {1, 0, 0, 0}, false}); });
  EXPECT_TRUE(contains(message, "robot name 'left' is used twice")) << message;
  // an object named like a robot takes its mount body's name
  message = error_of([&] { scene.add_object(cube_spec("right", 0.3)); });
  EXPECT_TRUE(contains(message, "body 'right'")) << message;
  message = error_of([&] {
    scene.add_sensor({"q", SensorType::jointpos, "left/joint1"});
    scene.add_sensor({"q", SensorType::jointpos, "left/joint2"});
  });
  EXPECT_TRUE(contains(message, "sensor 'q'")) << message;
  message = error_of([&] { scene.add_arena(); });
  EXPECT_TRUE(contains(message, "already has an arena")) << message;
  // the scene is unchanged after a refused part
  EXPECT_EQ(scene.compile().nq(), 31);
}

TEST(Scene, UnknownAttachmentFrameNamesTheClosestFrames) {
  Scene scene;
  scene.add_robot({"arm", "panda", {}, {1, 0, 0, 0}, false});
  const std::string message = error_of([&] {
    scene.attach_gripper({"arm", "franka_hand", "attachment_sit", "hand"});
  });
  EXPECT_TRUE(contains(message, "unknown attachment frame 'attachment_sit' on robot 'arm'"))
      << message;
  EXPECT_TRUE(contains(message, "closest: attachment_site")) << message;
  EXPECT_TRUE(contains(error_of([&] {
                         scene.attach_gripper({"arn", "franka_hand", "link7", "hand"});
                       }),
                       "no robot named 'arn'"));
}

TEST(Scene, UnknownRobotGripperAndShapeNamedWithSuggestions) {
  Scene scene;
  std::string message = error_of([&] {
    scene.add_robot({"a", "pandahand", {}, {1, 0, 0, 0}, false});
  });
  EXPECT_TRUE(contains(message, "unknown robot 'pandahand'; closest: panda, panda_hand"))
      << message;
  scene.add_robot({"arm", "panda", {}, {1, 0, 0, 0}, false});
  message = error_of([&] { scene.attach_gripper({"arm", "franka_hnd", "link7", "hand"}); });
  EXPECT_TRUE(contains(message, "unknown gripper 'franka_hnd'; closest: franka_hand")) << message;
  message = error_of([] { object_shape("cilinder"); });
  EXPECT_TRUE(contains(message, "unknown object shape 'cilinder'; closest: cylinder")) << message;
  message = error_of([&] {
    scene.add_robot({"b", "/nonexistent/arm.xml", {}, {1, 0, 0, 0}, false});
  });
  EXPECT_TRUE(contains(message, "'/nonexistent/arm.xml' does not exist")) << message;
}

TEST(Scene, MissingMeshFileIsNamed) {
  Scene scene;
  ObjectSpec mug;
  mug.name = "mug";
  mug.shape = ObjectShape::mesh;
  mug.size = {};
  mug.mesh_file = "no_such_dir/mug.stl";
  const std::string message = error_of([&] { scene.add_object(mug); });
  EXPECT_TRUE(contains(message,
                       "/no_such_dir/mug.stl' does not exist (object 'mug', given as "
                       "'no_such_dir/mug.stl')"))
      << message;
  EXPECT_FALSE(scene.has("body", "mug"));
}

TEST(Scene, MeshObjectsLoadFromAnAbsolutePath) {
  // a tetrahedron as a Wavefront OBJ
  const auto file = test::scratch() / "tetra.obj";
  {
    std::ofstream out(file);
    out << "v 0 0 0\nv 0.04 0 0\nv 0 0.04 0\nv 0 0 0.04\n";
    out << "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  }
  Scene scene;
  ObjectSpec tetra;
  tetra.name = "tetra";
  tetra.shape = ObjectShape::mesh;
  tetra.size = {};
  tetra.mesh_file = file.string();
  tetra.mass = 0.2;
  scene.add_object(tetra);
  const Robot robot = scene.compile();
  EXPECT_EQ(robot.model().nmesh, 1);
  EXPECT_EQ(robot.nq(), 7);
  EXPECT_NEAR(robot.model().body_mass[robot.body("tetra")], 0.2, 1e-9);
}

TEST(Scene, MeshObjectsFromTheirVertices) {
  Scene scene;
  ObjectSpec tetra;
  tetra.name = "tetra";
  tetra.shape = ObjectShape::mesh;
  tetra.size = {};
  tetra.mesh_vertices = {0, 0, 0, 0.04, 0, 0, 0, 0.04, 0, 0, 0, 0.04};
  tetra.mass = 0.2;
  scene.add_object(tetra);
  const Robot robot = scene.compile();
  const mjModel& m = robot.model();
  ASSERT_EQ(m.nmesh, 1);
  EXPECT_EQ(m.mesh_vertnum[0], 4);
  EXPECT_EQ(m.geom_type[robot.geom("tetra/geom")], mjGEOM_MESH);
  EXPECT_NEAR(m.body_mass[robot.body("tetra")], 0.2, 1e-9);
  // its centre of mass: the tetrahedron's, a quarter of the way along each edge from the origin
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(m.body_ipos[3 * robot.body("tetra") + i], 0.01, 1e-6);
  // exactly one of file and vertices, whole points, at least four
  ObjectSpec bad = tetra;
  bad.name = "bad";
  bad.mesh_file = "tetra.obj";
  EXPECT_TRUE(contains(error_of([&] { scene.add_object(bad); }), "one of the two"));
  bad.mesh_file.clear();
  bad.mesh_vertices.pop_back();
  EXPECT_TRUE(contains(error_of([&] { scene.add_object(bad); }), "x y z triples of at least 4"));
  bad.mesh_vertices = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  EXPECT_TRUE(contains(error_of([&] { scene.add_object(bad); }), "got 9 values"));
  ObjectSpec box = cube_spec("box", 0.2);
  box.mesh_vertices = tetra.mesh_vertices;
  EXPECT_TRUE(contains(error_of([&] { scene.add_object(box); }), "its shape is not mesh"));
}

TEST(Scene, BadValuesAreNamed) {
  Scene scene = two_robots_two_objects();
  ObjectSpec heavy = cube_spec("heavy", 0.2);
  heavy.mass = -1.0;
  EXPECT_TRUE(contains(error_of([&] { scene.add_object(heavy); }), "mass must be positive"));
  ObjectSpec flat = cube_spec("flat", 0.2);
  flat.size = {0.1, 0.1};
  EXPECT_TRUE(contains(error_of([&] { scene.add_object(flat); }), "size expects 3 value(s)"));
  const std::vector<double> nan{std::nan("")};
  EXPECT_TRUE(contains(error_of([&] { scene.set_attribute("geom", "cube/geom", "size", nan); }),
                       "must be finite"));
  EXPECT_TRUE(contains(error_of([&] { scene.set_attribute("geom", "cueb/geom", "size", "1"); }),
                       "closest: cube/geom"));
  EXPECT_TRUE(contains(error_of([&] { scene.set_attribute("body", "cube", "name", "box"); }),
                       "renaming is not supported"));
  // values are read when they are set
  std::string message = error_of([&] { scene.set_attribute("geom", "cube/geom", "size", "abc"); });
  EXPECT_TRUE(contains(message, "geom 'cube/geom': size expects numbers, got 'abc'")) << message;
  message = error_of([&] { scene.set_attribute("geom", "cube/geom", "frction", "1"); });
  EXPECT_TRUE(contains(message, "geom 'cube/geom': no attribute 'frction'; closest: friction"))
      << message;
  const std::vector<double> four{1.0, 2.0, 3.0, 4.0};
  message = error_of([&] { scene.set_attribute("geom", "cube/geom", "pos", four); });
  EXPECT_TRUE(contains(message, "pos expects 3 numbers, got 4")) << message;
  const std::vector<double> half{0.5};
  message = error_of([&] { scene.set_attribute("geom", "cube/geom", "contype", half); });
  EXPECT_TRUE(contains(message, "contype expects whole numbers")) << message;
  EXPECT_EQ(scene.attribute("geom", "cube/geom", "contype"), "1");  // unchanged
  message = error_of([&] { scene.set_attribute("geom", "cube/geom", "type", "cube"); });
  EXPECT_TRUE(contains(message, "type expects one of plane, hfield, sphere")) << message;
  message = error_of([&] { scene.set_option("integrater", "RK4"); });
  EXPECT_TRUE(contains(message, "option: no attribute 'integrater'; closest: integrator"))
      << message;
  // MuJoCo judges the values when the scene compiles
  scene.set_attribute("geom", "cube/geom", "size", "-0.01 0.02 0.03");
  message = error_of([&] { scene.compile(); });
  EXPECT_TRUE(contains(message, "scene 'two_arms' does not compile")) << message;
  EXPECT_TRUE(contains(message, "size")) << message;
  EXPECT_TRUE(contains(error_of([&] {
                         scene.add_weld({"w", "left/link6", "cub", false, {0.002, 1}});
                       }),
                       "no body named 'cub'"));
  EXPECT_TRUE(contains(error_of([&] {
                         scene.add_sensor({"s", SensorType::touch, "left/grp"});
                       }),
                       "closest: left/grip"));
}

// issue 29, item 5: compiled from a spec, MuJoCo 4.0.1 keeps a zero quaternion (the body's
// rotation matrix all zero, `fk` exit 0) and refuses a zero or parallel axis naming the element's
// index only; the scene refuses each one, naming the element and the attribute
TEST(Scene, DegenerateFramesAreRefusedNamingTheElementAndTheAttribute) {
  Scene scene = two_robots_two_objects();
  const auto refused = [&](const char* kind, const char* name, const char* attribute,
                           const std::string& value) {
    return error_of([&] { scene.set_attribute(kind, name, attribute, value); });
  };
  std::string message = refused("body", "left/link3", "quat", "0 0 0 0");
  EXPECT_TRUE(contains(message, "body 'left/link3': quat is a zero quaternion")) << message;
  message = refused("geom", "cube/geom", "zaxis", "0 0 0");
  EXPECT_TRUE(contains(message, "geom 'cube/geom': zaxis is a zero vector")) << message;
  message = refused("site", "left/grip", "axisangle", "0 0 0 1.5");
  EXPECT_TRUE(contains(message, "site 'left/grip': axisangle has a zero axis")) << message;
  message = refused("body", "ball", "xyaxes", "0 0 0 0 1 0");
  EXPECT_TRUE(contains(message, "body 'ball': xyaxes has a zero x axis")) << message;
  message = refused("body", "ball", "xyaxes", "1 0 0 -2 0 0");
  EXPECT_TRUE(contains(message, "xyaxes has its y axis parallel to its x axis")) << message;
  message = refused("body", "ball", "xyaxes", "1 0 0 0 0 0");
  EXPECT_TRUE(contains(message, "xyaxes has a zero y axis")) << message;
  const std::vector<double> nan_euler{std::nan(""), 0.0, 0.0};
  message = error_of([&] { scene.set_attribute("body", "ball", "euler", nan_euler); });
  EXPECT_TRUE(contains(message, "body 'ball': euler must be finite numbers")) << message;
  // nothing was written: the scene compiles with the frames it had
  const Robot robot = scene.compile();
  const mjModel& m = robot.model();
  EXPECT_EQ(m.body_quat[4 * robot.body("left/link3")], 1.0);
  // a frame at an angle is taken
  scene.set_attribute("body", "ball", "xyaxes", "0 1 0 -1 0 0");
  EXPECT_NEAR(scene.compile().model().body_quat[4 * robot.body("ball") + 3], std::sqrt(0.5),
              1e-12);

  SceneCameraSpec camera;
  camera.name = "c";
  camera.xyaxes = {0, 1, 0, 0, 3, 0};
  message = error_of([&] { scene.add_camera(camera); });
  EXPECT_TRUE(contains(message, "camera 'c': xyaxes has its y axis parallel")) << message;
  camera.xyaxes = {0, 1, 0, -0.5, 0, 0.8};
  camera.quat = {0, 1, 0, 0};
  message = error_of([&] { scene.add_camera(camera); });
  EXPECT_TRUE(contains(message, "camera 'c' has both xyaxes and a quat")) << message;
  EXPECT_FALSE(scene.has("camera", "c"));
  SiteSpec site;
  site.name = "s";
  site.quat = {0, 0, 0, 0};
  EXPECT_TRUE(contains(error_of([&] { scene.add_site(site); }), "site 's': quat is a zero"));
  ObjectSpec tilted = cube_spec("tilted", 0.3);
  tilted.quat = {std::nan(""), 0, 0, 1};
  EXPECT_TRUE(contains(error_of([&] { scene.add_object(tilted); }),
                       "object 'tilted': quat holds a value that is not finite"));
}

TEST(Scene, CompoundFixtureIsOneStaticBodyWithItsPiecesInPlace) {
  Scene scene("compound");
  scene.add_arena();
  CompoundFixtureSpec bin;
  bin.name = "bin";
  bin.pos = {0.5, 0.1, 0.2};
  const double s = std::sqrt(0.5);
  bin.quat = {s, 0.0, 0.0, s};  // 90° about z
  ObjectSpec floor_piece = cube_spec("floor", 0.0);
  floor_piece.size = {0.1, 0.1, 0.005};
  floor_piece.pos = {0.0, 0.0, 0.0};
  ObjectSpec wall = cube_spec("wall", 0.0);
  wall.size = {0.005, 0.1, 0.05};
  wall.pos = {0.1, 0.0, 0.05};
  wall.quat = {s, s, 0.0, 0.0};  // 90° about x
  bin.pieces = {floor_piece, wall};
  scene.add_fixture(bin);
  const Robot robot = scene.compile();
  const mjModel& m = robot.model();
  const int body = robot.body("bin");
  EXPECT_EQ(m.body_weldid[body], 0);  // static: welded to the world
  const int floor_geom = robot.geom("bin/floor");
  const int wall_geom = robot.geom("bin/wall");
  EXPECT_EQ(m.geom_bodyid[floor_geom], body);
  EXPECT_EQ(m.geom_bodyid[wall_geom], body);
  DataPtr d = robot.make_data();
  mj_forward(&m, d.get());
  // the wall's centre: (0.5, 0.1, 0.2) + R_z(90°)·(0.1, 0, 0.05) = (0.5, 0.2, 0.25)
  EXPECT_NEAR(d->geom_xpos[3 * wall_geom + 0], 0.5, 1e-12);
  EXPECT_NEAR(d->geom_xpos[3 * wall_geom + 1], 0.2, 1e-12);
  EXPECT_NEAR(d->geom_xpos[3 * wall_geom + 2], 0.25, 1e-12);
  // its y axis is R_z(90°)·R_x(90°)·ŷ = R_z(90°)·ẑ = ẑ
  EXPECT_NEAR(d->geom_xmat[9 * wall_geom + 5], 0.0, 1e-12);
  EXPECT_NEAR(d->geom_xmat[9 * wall_geom + 8], 0.0, 1e-12);
  EXPECT_NEAR(d->geom_xmat[9 * wall_geom + 7], 1.0, 1e-12);
  EXPECT_TRUE(scene.has("site", "bin/center"));
  EXPECT_DOUBLE_EQ(m.geom_size[3 * wall_geom + 2], 0.05);
}

TEST(Scene, CompoundFixtureRefusesBadPieces) {
  Scene scene("compound");
  CompoundFixtureSpec bin;
  bin.name = "bin";
  EXPECT_TRUE(contains(error_of([&] { scene.add_fixture(bin); }), "fixture 'bin' has no pieces"));
  bin.pieces = {cube_spec("a", 0.0), cube_spec("a", 0.1)};
  EXPECT_TRUE(contains(error_of([&] { scene.add_fixture(bin); }), "piece name 'a' is used twice"));
  bin.pieces = {cube_spec("a", 0.0)};
  bin.pieces[0].size = {0.1};
  EXPECT_TRUE(contains(error_of([&] { scene.add_fixture(bin); }), "fixture 'bin': "));
  bin.pieces[0].size = {0.1, 0.1, 0.1};
  bin.pos = {0.0, std::nan(""), 0.0};
  EXPECT_TRUE(contains(error_of([&] { scene.add_fixture(bin); }), "fixture 'bin' pos"));
  bin.pos = {0.0, 0.0, 0.0};
  scene.add_fixture(bin);
  EXPECT_TRUE(contains(error_of([&] { scene.add_fixture(bin); }), "name clash"));
}

}  // namespace
}  // namespace mjarm
