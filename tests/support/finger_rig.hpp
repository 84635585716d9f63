#pragma once
/// @file
/// A two-finger test rig: fingers sliding along ±y of a fixed hand (inner faces at y = ±q, open
/// 0.04 m each), a 30 mm cube of 50 g floating between them 5 mm off centre.

#include <string>

namespace mjarm::test {

/// The rig's MJCF. @p servos: position servos of gain @p kp (ctrlrange 0…0.04) instead of
/// motors (±30 N); @p gravity on or off; MuJoCo's noslip solver with @p noslip iterations.
inline std::string finger_rig(bool servos, bool gravity, double kp = 400.0, int noslip = 10) {
  const std::string gain = std::to_string(kp);
  const std::string actuators =
      servos ? "<general name='left' joint='left' gainprm='" + gain +
                   "' biastype='affine' biasprm='0 -" + gain +
                   " -2' ctrllimited='true' ctrlrange='0 0.04'/>"
                   "<general name='right' joint='right' gainprm='" +
                   gain + "' biastype='affine' biasprm='0 -" + gain +
                   " -2' ctrllimited='true' ctrlrange='0 0.04'/>"
             : "<motor name='left' joint='left' ctrllimited='true' ctrlrange='-30 30'/>"
               "<motor name='right' joint='right' ctrllimited='true' ctrlrange='-30 30'/>";
  return std::string("<mujoco model='fingers'><option timestep='0.002' gravity='0 0 ") +
         (gravity ? "-9.81" : "0") + "' noslip_iterations='" + std::to_string(noslip) +
         "'/><worldbody><body name='hand' pos='0 0 0.5'>"
         "<body name='left'><joint name='left' type='slide' axis='0 1 0' range='0 0.04' "
         "damping='2' armature='0.01'/><geom name='left' type='box' pos='0 0.008 0' "
         "size='0.012 0.008 0.025' mass='0.03' friction='1 0.005 0.0001'/></body>"
         "<body name='right'><joint name='right' type='slide' axis='0 -1 0' range='0 0.04' "
         "damping='2' armature='0.01'/><geom name='right' type='box' pos='0 -0.008 0' "
         "size='0.012 0.008 0.025' mass='0.03' friction='1 0.005 0.0001'/></body></body>"
         "<body name='cube' pos='0 0.005 0.5'><freejoint name='cube'/><geom name='cube' "
         "type='box' size='0.015 0.015 0.015' mass='0.05'/></body></worldbody><actuator>" +
         actuators + "</actuator></mujoco>";
}

}  // namespace mjarm::test
