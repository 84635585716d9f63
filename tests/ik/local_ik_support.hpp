#pragma once
// Shared helpers of the local IK tests: bundled arms with their end-effector frames and a small
// two-branch model for multi-target tests (random configurations are in
// support/random_configurations.hpp).

#include <string>
#include <vector>

#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm::test {

/// A bundled arm and the frame its IK moves.
struct ArmCase {
  std::string model;
  std::string frame;
};

/// The chain of bundled arm @p robot up to its attachment site.
inline Chain chain_of(const char* robot) { return Chain(Robot::bundled(robot), "attachment_site"); }

/// The single-chain bundled arms (dual_arm is covered by the multi-target tests and by its
/// right-hand chain here).
inline std::vector<ArmCase> bundled_arms() {
  return {{"planar2", "tip"},           {"arm6", "grip"},
          {"panda", "attachment_site"}, {"iiwa14", "attachment_site"},
          {"ur5e", "attachment_site"},  {"dual_arm", "right_hand"}};
}

/// A torso on a lift with two horizontal 3-link arms (yaw joints only, sites left_tip and
/// right_tip), so the height of each hand is set by the shared lift alone: two hands asked for
/// different heights conflict. A post stands in the right arm's sweep for collision tests.
inline constexpr const char* kTwoBranch = R"(
<mujoco model="two_branch">
  <compiler angle="radian" autolimits="true"/>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="torso" pos="0 0 0.5">
      <joint name="lift" type="slide" axis="0 0 1" range="-0.2 0.3"/>
      <geom name="torso" type="box" size="0.05 0.1 0.05"/>
      <body name="l1" pos="0 0.2 0">
        <joint name="l_yaw1" axis="0 0 1" range="-2.5 2.5"/>
        <geom name="l_link1" type="capsule" fromto="0 0 0 0.3 0 0" size="0.02"/>
        <body name="l2" pos="0.3 0 0">
          <joint name="l_yaw2" axis="0 0 1" range="-2.5 2.5"/>
          <geom name="l_link2" type="capsule" fromto="0 0 0 0.25 0 0" size="0.02"/>
          <body name="l3" pos="0.25 0 0">
            <joint name="l_yaw3" axis="0 0 1" range="-2.5 2.5"/>
            <geom name="l_link3" type="capsule" fromto="0 0 0 0.1 0 0" size="0.02"/>
            <site name="left_tip" pos="0.1 0 0"/>
          </body>
        </body>
      </body>
      <body name="r1" pos="0 -0.2 0">
        <joint name="r_yaw1" axis="0 0 1" range="-2.5 2.5"/>
        <geom name="r_link1" type="capsule" fromto="0 0 0 0.3 0 0" size="0.02"/>
        <body name="r2" pos="0.3 0 0">
          <joint name="r_yaw2" axis="0 0 1" range="-2.5 2.5"/>
          <geom name="r_link2" type="capsule" fromto="0 0 0 0.25 0 0" size="0.02"/>
          <body name="r3" pos="0.25 0 0">
            <joint name="r_yaw3" axis="0 0 1" range="-2.5 2.5"/>
            <geom name="r_link3" type="capsule" fromto="0 0 0 0.1 0 0" size="0.02"/>
            <site name="right_tip" pos="0.1 0 0"/>
          </body>
        </body>
      </body>
    </body>
    <body name="post" pos="0.3 -0.55 0.5">
      <geom name="post" type="cylinder" size="0.05 0.5"/>
    </body>
  </worldbody>
</mujoco>
)";

/// The joints of kTwoBranch: lift, left arm, right arm.
inline std::vector<std::string> two_branch_joints() {
  return {"lift", "l_yaw1", "l_yaw2", "l_yaw3", "r_yaw1", "r_yaw2", "r_yaw3"};
}

/// The joints of the bundled dual_arm: lift, left arm, right arm.
inline std::vector<std::string> dual_arm_joints() {
  std::vector<std::string> joints{"lift"};
  for (const char* side : {"left", "right"})
    for (int i = 1; i <= 7; ++i) joints.push_back(std::string(side) + "_joint" + std::to_string(i));
  return joints;
}

}  // namespace mjarm::test
