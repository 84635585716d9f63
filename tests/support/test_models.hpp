#pragma once
// Small models written for tests: each exercises something the bundled arms do not.

namespace mjarm::test {

/// A 5-joint arm with everything that makes kinematics tricky: body and site rotations, a joint
/// anchor away from the body origin, a joint with a non-zero reference (qpos0), a slide joint,
/// a branch off the path (with its own hinge), a free-floating object in the scene.
inline constexpr const char* kTrickyArm = R"(
<mujoco model="tricky">
  <compiler angle="radian" autolimits="true"/>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="base" pos="0.1 -0.2 0.3" quat="0.9238795 0 0.3826834 0">
      <joint name="j1" type="hinge" axis="0 0 1" range="-3 3"/>
      <geom type="capsule" fromto="0 0 0 0 0 0.2" size="0.04"/>
      <body name="l1" pos="0 0.05 0.2" euler="0.3 -0.2 0.1">
        <joint name="j2" type="hinge" axis="0 1 0" pos="0 0 0.02" ref="0.4" range="-2 2"/>
        <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.035"/>
        <body name="branch" pos="0 0.1 0">
          <joint name="off_path" type="hinge" axis="1 0 0"/>
          <geom type="sphere" size="0.02"/>
        </body>
        <body name="l2" pos="0.3 0 0">
          <joint name="j3" type="slide" axis="1 0.2 0" range="-0.1 0.2"/>
          <geom type="box" size="0.05 0.02 0.02"/>
          <body name="l3" pos="0.1 0 0" quat="0.7071068 0.7071068 0 0">
            <joint name="j4" type="hinge" axis="0.3 0.4 0.866" range="-2.5 2.5"/>
            <joint name="j5" type="hinge" axis="1 0 0" range="-2.5 2.5"/>
            <geom type="capsule" fromto="0 0 0 0 0 0.15" size="0.03"/>
            <site name="tool" pos="0.01 0.02 0.15" euler="0.5 0.2 -0.3"/>
          </body>
        </body>
      </body>
    </body>
    <body name="box" pos="0.5 0.5 0.1">
      <freejoint name="box_free"/>
      <geom type="box" size="0.05 0.05 0.05"/>
    </body>
  </worldbody>
</mujoco>
)";

}  // namespace mjarm::test
