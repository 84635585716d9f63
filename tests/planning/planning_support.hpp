#pragma once
// Shared by the planning tests: the panda with torque motors, its home configuration, a scene
// with a box obstacle, and a 5-waypoint path around home.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mjarm/lie/pose.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm::planning_test {

inline Eigen::VectorXd home_q(const Robot& robot) {
  const std::vector<double> qpos = robot.keyframe_qpos("home");
  return Eigen::Map<const Eigen::VectorXd>(qpos.data(), 7);
}

/// The bundled panda body and motors plus a box obstacle centred at @p centre (half-size @p half).
inline Robot panda_with_box(const Eigen::Vector3d& centre, double half) {
  const std::string xml = R"(<mujoco model="panda_box">
  <compiler angle="radian" autolimits="true"/>
  <option timestep="0.002" integrator="Euler"/>
  <include file="common/scene.xml"/>
  <include file="panda/panda_body.xml"/>
  <worldbody>
    <geom name="obstacle" type="box" pos=")" +
                          std::to_string(centre.x()) + " " + std::to_string(centre.y()) + " " +
                          std::to_string(centre.z()) + R"(" size=")" + std::to_string(half) + " " +
                          std::to_string(half) + " " + std::to_string(half) + R"("/>
  </worldbody>
  <actuator>
    <motor name="joint1" joint="joint1" ctrlrange="-87 87"/>
    <motor name="joint2" joint="joint2" ctrlrange="-87 87"/>
    <motor name="joint3" joint="joint3" ctrlrange="-87 87"/>
    <motor name="joint4" joint="joint4" ctrlrange="-87 87"/>
    <motor name="joint5" joint="joint5" ctrlrange="-12 12"/>
    <motor name="joint6" joint="joint6" ctrlrange="-12 12"/>
    <motor name="joint7" joint="joint7" ctrlrange="-12 12"/>
  </actuator>
  <keyframe><key name="home" qpos="0 -0.785 0 -2.356 0 1.571 0.785"/></keyframe>
</mujoco>)";
  return Robot::from_string(xml, Robot::models_dir());
}

/// Five positions around the panda's home tool position (0.307, 0, 0.590), tool pointing down.
inline std::vector<Pose> five_waypoints() {
  Eigen::Matrix3d R;
  R << 0.707388, -0.706825, 0.0, -0.706825, -0.707388, 0.0, 0.0, 0.0, -1.0;
  R = Eigen::Quaterniond(R).normalized().toRotationMatrix();
  const std::vector<Eigen::Vector3d> points{{0.45, 0.0, 0.50},
                                            {0.45, 0.20, 0.40},
                                            {0.35, 0.25, 0.35},
                                            {0.30, 0.10, 0.45},
                                            {0.40, -0.15, 0.50}};
  std::vector<Pose> poses;
  for (const Eigen::Vector3d& p : points) {
    Pose X;
    X.R = R;
    X.p = p;
    poses.push_back(X);
  }
  return poses;
}

}  // namespace mjarm::planning_test
