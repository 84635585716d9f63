#include "mjarm/tasks/wiping/scene.hpp"

#include <string>
#include <vector>

#include "mjarm/tasks/docking/scene.hpp"

namespace mjarm {

Scene wiping_scene(const WipingSurface& surface) {
  check_fields(surface);
  Scene scene("wiping");
  // MuJoCo's contacts are a convex relaxation: a sliding contact pushes its bodies apart at
  // about μ·|v_t|. With pyramidal cones and a stiff pad the sliding pad hops off the table every
  // few milliseconds (contact 37 % of a 0.1 m/s stroke); elliptic cones and a soft pad (felt)
  // keep it down (docs/scenarios.md).
  scene.set_option("cone", "elliptic");
  scene.add_arena();
  scene.add_robot({WipingNames::robot, "iiwa14_torque", {0.0, 0.0, 0.0}, {1, 0, 0, 0}, false});
  scene.attach_gripper({WipingNames::robot, "wiping_tool", "attachment_site", "tool"});
  const std::string pad = std::string(WipingNames::robot) + "/tool/pad";
  const double radius[1] = {surface.pad_radius};
  scene.set_attribute("geom", pad, "size", radius);
  // the pad's centre stays 0.08 m past the flange; the tip is its lowest point
  const double tip[3] = {0.0, 0.0, 0.08 + surface.pad_radius};
  scene.set_attribute("site", WipingNames::tip, "pos", tip);
  const double friction[3] = {surface.friction, 0.005, 0.0001};
  scene.set_attribute("geom", pad, "friction", friction);
  const double solref[2] = {surface.pad_time_constant, 1.0};
  scene.set_attribute("geom", pad, "solref", solref);
  scene.add_sensor({WipingNames::force, SensorType::force, WipingNames::ft_site});
  scene.add_sensor({WipingNames::torque, SensorType::torque, WipingNames::ft_site});
  if (surface.joint_friction) add_franka_joint_friction(scene, WipingNames::robot);
  ObjectSpec table;
  table.name = WipingNames::table;
  table.shape = ObjectShape::box;
  table.size = {0.5 * kWipingTableDepth, 0.5 * kWipingTableWidth, 0.5 * surface.table_height};
  table.pos = {kWipingTableNear + 0.5 * kWipingTableDepth, 0.0, 0.5 * surface.table_height};
  table.friction = {surface.friction, 0.005, 0.0001};
  table.rgba = {0.72, 0.62, 0.48, 1.0};
  scene.add_fixture(table);
  scene.set_attribute("geom", std::string(WipingNames::table) + "/geom", "solref", solref);
  return scene;
}

bool same_surface(const WipingSurface& a, const WipingSurface& b) noexcept {
  return a.table_height == b.table_height && a.friction == b.friction &&
         a.pad_radius == b.pad_radius && a.pad_time_constant == b.pad_time_constant &&
         a.joint_friction == b.joint_friction;
}

WipingScene build_wiping_scene(const WipingSurface& surface) {
  Robot robot = wiping_scene(surface).compile();
  Chain chain(robot, WipingNames::tip);
  WipingScene scene{.robot = robot, .chain = chain, .surface = surface};
  scene.tool = GeomSet::of_bodies(robot, {WipingNames::tool});
  scene.table = GeomSet::of_bodies(robot, {WipingNames::table});
  std::vector<std::string> links;
  for (int k = 0; k <= 7; ++k)
    links.push_back(std::string(WipingNames::robot) + "/link" + std::to_string(k));
  scene.arm = GeomSet::of_bodies(robot, links, false);
  return scene;
}

}  // namespace mjarm
