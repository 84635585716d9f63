// 10_scene: compose a pick-and-place scene in C++ — a table, the Panda with the Franka Hand
// attached at its flange, a small cube and a sensor on it — compile it, drop the cube onto the
// table from 5 cm with the arm held at home, and check that it comes to rest on the top.

#include <cmath>
#include <cstdio>

#include "mjarm/scene/free_pose.hpp"
#include "mjarm/scene/scene.hpp"

int main() {
  mjarm::Scene scene("example_scene");
  mjarm::ArenaSpec arena;
  arena.table = true;
  arena.table_center = {0.45, 0.0};
  arena.table_half_size = {0.45, 0.6};
  arena.table_height = 0.4;
  scene.add_arena(arena);
  scene.add_robot({"panda", "panda", {0.12, 0.0, 0.4}, {1, 0, 0, 0}, false});
  scene.attach_gripper({"panda", "franka_hand", "attachment_site", "hand"});
  mjarm::ObjectSpec cube;
  cube.name = "cube";
  cube.size = {0.0075, 0.0075, 0.0075};  // half extents [m]
  cube.mass = 0.02;
  scene.add_object(cube);
  scene.add_sensor({"cube_pos", mjarm::SensorType::framepos, "cube"});
  scene.add_weld({"grasp", "panda/hand/hand", "cube", false, {0.002, 1.0}});
  // an edit: the classic finger travel
  const double travel[2] = {0.0, 0.012};
  for (const char* finger : {"panda/hand/finger_left", "panda/hand/finger_right"})
    scene.set_attribute("actuator", finger, "ctrlrange", travel);

  const mjarm::Robot robot = scene.compile();
  std::printf("scene '%s': nq %d, nv %d, nu %d (panda 7 + hand 2 + cube 7)\n", robot.name().c_str(),
              robot.nq(), robot.nv(), robot.nu());

  // the arm at its home key, the cube 5 cm above the table
  const mjModel& m = robot.model();
  mjarm::DataPtr d = robot.make_data();
  const int home = robot.keyframe("home");
  for (int i = 0; i < m.nq; ++i) d->qpos[i] = m.key_qpos[home * m.nq + i];
  for (int i = 0; i < m.nu; ++i) d->ctrl[i] = m.key_ctrl[home * m.nu + i];
  mjarm::set_free_pose(robot, *d, "cube", {{0.5, 0.1, 0.45}, {1.0, 0.0, 0.0, 0.0}});
  for (int step = 0; step < 500; ++step) mj_step(&m, d.get());  // 1 s

  const auto p = robot.sensor_values(*d, "cube_pos");
  const double rest = arena.table_height + cube.size[2];
  std::printf("cube after 1 s: %.4f %.4f %.4f m (resting height %.4f m)\n", p[0], p[1], p[2], rest);
  return std::fabs(p[2] - rest) < 2e-3 ? 0 : 1;
}
