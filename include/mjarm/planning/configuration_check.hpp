#pragma once
/// @file
/// The checks a planned motion passes at every waypoint and at samples between them: joint
/// limits, distance from singularities, torque by inverse dynamics, and contacts between the
/// moving robot and the rest of the scene — on an owned scratch `mjData`, never the caller's.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/kinematics/manipulability.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/planning/joint_limits.hpp"
#include "mjarm/planning/robot_contacts.hpp"

namespace mjarm {

/// Which check a state failed, in the order they are judged.
enum class CheckFailure {
  none,          ///< every check passed
  invalid,       ///< q, q̇ or q̈ holds NaN/inf
  joint_limits,  ///< a joint outside its range
  collision,     ///< a moving geom of the robot touches another geom
  singular,      ///< σmin of the 6×n Jacobian below the threshold
  torque         ///< τ = M·q̈ + h beyond a joint's torque limit
};

constexpr auto declared_names(const CheckFailure*) {
  using F = CheckFailure;
  return std::array{EnumName{F::none, "none", "every check passed"},
                    EnumName{F::invalid, "invalid", "q, q̇ or q̈ holds NaN/inf"},
                    EnumName{F::joint_limits, "joint_limits", "a joint outside its range"},
                    EnumName{F::collision, "collision", "a moving geom touches another geom"},
                    EnumName{F::singular, "singular", "σmin below the threshold"},
                    EnumName{F::torque, "torque", "a joint's torque beyond its limit"}};
}

/// Thresholds of the checks.
struct CheckOptions {
  /// Smallest singular value σmin of the world-aligned 6×n Jacobian J_WE (rows [v; ω], so σ mixes
  /// m/rad and rad/rad) that is still accepted (≥ 0).
  double min_singular_value = 0.02;
  /// A contact counts when its signed distance is below this [m] (≥ 0). MuJoCo reports contacts
  /// only within the geoms' margins, so a margin beyond them finds nothing more.
  double collision_margin = 0.0;
  /// Joints may exceed their range by this much [rad or m] (≥ 0; round-off of IK clamping).
  double limit_tolerance = 1e-9;
};

constexpr auto declared_fields(const CheckOptions*) {
  using S = CheckOptions;
  return declare<S>(
      "configuration check",
      field("min_singular_value", &S::min_singular_value, "", Range::non_negative(),
            "smallest σmin of J_WE still accepted"),
      field("collision_margin", &S::collision_margin, "m", Range::non_negative(),
            "a contact counts below this signed distance"),
      field("limit_tolerance", &S::limit_tolerance, "rad or m", Range::non_negative(),
            "how far joints may exceed their range"));
}

/// @throws Error naming the option that is negative or not finite.
void check(const CheckOptions& options);

/// What one state measured, and the first failure in `CheckFailure` order.
struct ConfigurationCheck {
  CheckFailure failure = CheckFailure::none;
  double sigma_min = 0.0;     ///< σmin of J_WE
  double torque_ratio = 0.0;  ///< max_i |τ_i| / τ_max,i (0 when no joint has a torque limit)
  int torque_joint = -1;      ///< the joint of torque_ratio
  int limit_joint = -1;       ///< the first joint outside its range (−1: none)
  int geom1 = -1;             ///< the deepest counted contact: a moving geom … (−1: none)
  int geom2 = -1;             ///< … and the other geom
  double distance = std::numeric_limits<double>::infinity();  ///< its signed distance [m]
  bool ok() const noexcept { return failure == CheckFailure::none; }
};

/// Checks states (q, q̇, q̈) of one chain. "The robot" is every geom on a body moved by a chain
/// joint; a contact counts when at least one of its geoms is such a geom and the pair is not
/// allowed (`RobotContacts`; the model's contype/conaffinity filters and MuJoCo's parent–child
/// exclusion apply). Torques are
/// τ = M(q)·q̈ + C(q, q̇)·q̇ + g(q) on the chain's dofs (`ChainDynamics::inverse_dynamics`; passive
/// forces excluded). One `check` runs MuJoCo's `mj_fwdPosition` and `mj_fwdVelocity` on the
/// owned scratch `mjData` and allocates nothing.
class ConfigurationChecker {
 public:
  /// @throws Error for invalid limits (wrong sizes, non-positive) or options.
  ConfigurationChecker(const Chain& chain, const JointLimits& limits,
                       const CheckOptions& options = {});

  const Chain& chain() const noexcept { return chain_; }
  const JointLimits& limits() const noexcept { return limits_; }
  const CheckOptions& options() const noexcept { return options_; }

  /// Sets the joints that are not in the chain (full qpos, nq entries; default qpos0).
  /// @throws Error when the size is not nq or a value is not finite.
  void set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos);

  /// The contact filter (none allowed by default): allow pairs on it (`RobotContacts::allow`).
  RobotContacts& contacts() noexcept { return contacts_; }

  /// Checks the state (n entries each, unchecked sizes). Never throws, allocates nothing.
  const ConfigurationCheck& check(const Eigen::Ref<const Eigen::VectorXd>& q,
                                  const Eigen::Ref<const Eigen::VectorXd>& qd,
                                  const Eigen::Ref<const Eigen::VectorXd>& qdd) noexcept;
  /// A state at rest: q̇ = q̈ = 0 (the torque is the gravity torque).
  const ConfigurationCheck& check(const Eigen::Ref<const Eigen::VectorXd>& q) noexcept;

  /// The failure of @p result in words, naming the joint or the geoms and the values against
  /// their bounds ("joint 'joint4' at -3.1 rad outside [-3.07, -0.07]"); "ok" when it passed.
  std::string describe(const ConfigurationCheck& result) const;

 private:
  Chain chain_;
  JointLimits limits_;
  CheckOptions options_;
  Manipulability manipulability_;
  ChainDynamics dynamics_;
  DataPtr data_;
  Eigen::VectorXd fixed_qpos_;
  RobotContacts contacts_;
  Eigen::VectorXd zero_, tau_, q_;
  ConfigurationCheck result_;
};

}  // namespace mjarm
