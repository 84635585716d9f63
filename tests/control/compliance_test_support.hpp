#pragma once
// Shared pieces of the compliant-controller tests (CIC, HQP-AC, wrench source): the iiwa14 in
// torque mode with a tool on its flange, an F/T sensor between them, optional joint friction and
// an optional table under the tool; pushing the tool with xfrc_applied.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "control/task_control_support.hpp"
#include "dynamics/sensing_test_support.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm::test {

/// The tool: a 0.3 kg cylinder, 0.1 m long, on the flange of link7; site "ft" at the flange
/// (the F/T sensor pair), site "tip" at its far end.
inline const char* kFtTool = R"(
  <body name="tool" pos="0 0 0.126">
    <inertial pos="0 0 0.05" mass="0.3" diaginertia="0.0003 0.0003 0.0001"/>
    <geom name="tool" type="cylinder" fromto="0 0 0 0 0 0.1" size="0.015"/>
    <site name="ft"/>
    <site name="tip" pos="0 0 0.1"/>
  </body>)";

/// The iiwa14_torque with the tool and the sensor pair at "ft"; frictionloss @p friction per
/// joint (none when empty); @p world extra worldbody elements (e.g. a table).
inline Robot iiwa_ft_tool(const std::vector<double>& friction = {}, const std::string& world = "") {
  std::string xml = iiwa_torque_xml(friction, kFtTool, R"(<force site="ft"/><torque site="ft"/>)");
  if (!world.empty()) {
    const std::string end = "</worldbody>";
    xml.replace(xml.rfind(end), end.size(), world + end);
  }
  return Robot::from_string(xml, Robot::models_dir());
}

/// Sets xfrc_applied of @p body to the force @p f applied at the world point @p p (world axes).
inline void push_body(const mjModel& m, mjData& d, int body, const Eigen::Vector3d& f,
                      const Eigen::Vector3d& p) {
  const Eigen::Vector3d com = Eigen::Map<const Eigen::Vector3d>(d.xipos + 3 * body);
  const Eigen::Vector3d t = (p - com).cross(f);
  for (int i = 0; i < 3; ++i) {
    d.xfrc_applied[6 * body + i] = f[i];
    d.xfrc_applied[6 * body + 3 + i] = t[i];
  }
  (void)m;
}

}  // namespace mjarm::test
