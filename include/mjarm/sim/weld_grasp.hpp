#pragma once
/// @file
/// `WeldGrasp`: a grasp made by a weld equality between a gripper body and an object, switched
/// on where the object already is — so switching it on does not move the object.

#include <string>
#include <string_view>

#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"

namespace mjarm {

class Simulation;

/// Solver settings of a weld grasp.
struct WeldGraspOptions {
  /// MuJoCo's solref of the weld: time constant [s] (> 0; MuJoCo treats values below two
  /// timesteps as two timesteps) and damping ratio (> 0). [0.002, 1] is the common choice: stiff
  /// at the bundled models' 2 ms step, critically damped.
  double time_constant = 0.002;
  double damping_ratio = 1.0;
};

constexpr auto declared_fields(const WeldGraspOptions*) {
  using S = WeldGraspOptions;
  return declare<S>("weld grasp",
                    field("time_constant", &S::time_constant, "s", Range::positive(),
                          "solref time constant of the weld"),
                    field("damping_ratio", &S::damping_ratio, "", Range::positive(),
                          "solref damping ratio of the weld"));
}

/// A weld grasp on one `Simulation`: body1 (the gripper) holds body2 (the object).
///
/// The layout of a weld's `eq_data` (mjNEQDATA = 12 values in MuJoCo 4; engine behaviour pinned
/// by tests/sim/weld_grasp_test.cpp): [0..2] the anchor point in body2's frame, [3..5] the same
/// point in body1's frame, [6..9] the orientation of body2 relative to body1 (quaternion
/// w x y z), [10] the torque scale, [11] nonzero when the compiler computed [3..9] at qpos0
/// (`mj_setConst` then recomputes them). The constraint drives p₁ + R₁·d[3..5] onto
/// p₂ + R₂·d[0..2] and q₁⁻¹·q₂ onto d[6..9] (p, R, q of the body frames, world). The compiler
/// fills d[3..9] with the relative pose at qpos0 — wherever the robot and the object happened to
/// be in the file — so a weld switched on later with those values yanks the object there.
///
/// `activate` instead reads X_12 = X_W1⁻¹·X_W2 from the current state (the body frames in
/// data.xpos / data.xquat, which must be current: inside a control tick they are) and writes the
/// anchor 0 (body2's origin), p_12 and q_12 (and clears [11], so `mj_setConst` keeps them),
/// then switches the weld on: the constraint is satisfied exactly at that instant and the object
/// does not jump. `release` switches it off: the object moves freely again. The weld's data goes into the simulation's own model copy
/// (the constructor asks for one: `Simulation::own_model()`), the switch into its data
/// (`mjData::eq_active`). Both allocate nothing and never throw: a task calls them inside a
/// control tick.
class WeldGrasp {
 public:
  /// The weld equality called @p weld (body1 = gripper, body2 = object).
  /// @throws Error when the model has no equality of that name (the closest names listed), it is
  ///         not a weld, or the solref values are not positive and finite. Gives the simulation
  ///         its own model copy, sets the weld's solref there and switches the weld off.
  WeldGrasp(Simulation& simulation, std::string_view weld, const WeldGraspOptions& options = {});

  /// The weld equality between bodies @p gripper and @p object (either order in the model).
  /// @throws Error when a body does not exist (the closest names listed) or no weld joins them.
  static WeldGrasp between(Simulation& simulation, std::string_view gripper,
                           std::string_view object, const WeldGraspOptions& options = {});

  /// Switches the weld on, holding body2 at its current pose relative to body1. Returns false
  /// (and changes nothing) when the state holds a non-finite pose.
  bool activate() noexcept;
  /// Switches the weld off.
  void release() noexcept;
  /// Whether the weld is on.
  bool active() const noexcept;

  /// The pose of body2 in body1's frame written at the last `activate` (identity before).
  const Pose& relative_pose() const noexcept { return X_12_; }
  /// Distance [m] between body2's origin and where the weld holds it (p₁ + R₁·p_12), in the
  /// simulation's current state: 0 at activation, and how far the object has been pushed off
  /// its grasped pose since (0 when the weld was never activated).
  double deviation() const noexcept;

  int equality() const noexcept { return id_; }  ///< equality id
  int body1() const noexcept { return body1_; }  ///< gripper body id
  int body2() const noexcept { return body2_; }  ///< object body id
  const std::string& name() const noexcept { return name_; }
  const WeldGraspOptions& options() const noexcept { return options_; }

 private:
  WeldGrasp(Simulation& simulation, int id, const WeldGraspOptions& options);

  Simulation* simulation_;
  int id_ = -1;
  int body1_ = -1;
  int body2_ = -1;
  std::string name_;
  WeldGraspOptions options_;
  Pose X_12_;
  bool activated_once_ = false;
};

}  // namespace mjarm
