#pragma once
/// @file
/// `AccelerationController`: end-effector control at the acceleration level through inverse
/// dynamics (target → desired task acceleration → joint acceleration → joint torque).

#include <Eigen/Core>
#include <array>
#include <span>
#include <string>
#include <string_view>

#include "mjarm/control/controller.hpp"
#include "mjarm/control/task_error.hpp"
#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/workspace_ptr.hpp"

namespace mjarm {

/// Gains of an `AccelerationController`. Task entries are [x, y, z, rx, ry, rz] in world axes;
/// in `TaskMode::position` only the first three are used (and checked).
struct AccelerationControlOptions {
  TaskMode mode = TaskMode::pose;  ///< 6-D pose or 3-D position task
  /// Kp [1/s²] (≥ 0): task acceleration per unit error; ω_n = √Kp.
  Vector6d stiffness = Vector6d::Constant(400.0);
  /// Kd [1/s] (≥ 0); 2·√Kp is critical damping of ë + Kd·ė + Kp·e = 0.
  Vector6d damping = Vector6d::Constant(40.0);
  /// Manipulability threshold w₀ (> 0): below it the pseudo-inverse is damped. w = √det(J·Jᵀ)
  /// (√det(Jᵀ·J) when the task has more rows than the chain has joints), in the mixed units of
  /// J's rows. The panda's 6-row w is about 0.05–0.1 in the middle of its workspace.
  double manipulability_threshold = 0.01;
  /// Largest damping λ_max (≥ 0) of the damped least-squares inverse, reached at w = 0.
  double max_damping = 0.1;
  /// Null-space joint damping [1/s] (≥ 0): q̈₀ = −kd·q̇ + kp·(q_ref − q).
  double nullspace_damping = 10.0;
  /// Null-space posture stiffness [1/s²] (≥ 0) towards reference.joint.q (used when that has n
  /// entries). 0 by default: damping only.
  double nullspace_stiffness = 0.0;
  /// Cancels the model's passive forces (joint damping, springs: qfrc_passive) so that the
  /// commanded acceleration is what MuJoCo's forward dynamics produces.
  bool compensate_passive = true;
};

constexpr auto declared_fields(const AccelerationControlOptions*) {
  using S = AccelerationControlOptions;
  return declare<S>("accel", field("mode", &S::mode, "6-D pose or 3-D position task"),
                    field("stiffness", &S::stiffness, "1/s²", Range::non_negative(),
                          "Kp, task acceleration per unit error"),
                    field("damping", &S::damping, "1/s", Range::non_negative(), "Kd"),
                    field("manipulability_threshold", &S::manipulability_threshold, "",
                          Range::positive(), "w₀: below it the pseudo-inverse is damped"),
                    field("max_damping", &S::max_damping, "", Range::non_negative(),
                          "λ_max of the damped least-squares inverse"),
                    field("nullspace_damping", &S::nullspace_damping, "1/s", Range::non_negative(),
                          "null-space joint damping"),
                    field("nullspace_stiffness", &S::nullspace_stiffness, "1/s²",
                          Range::non_negative(), "null-space posture stiffness"),
                    field("compensate_passive", &S::compensate_passive, "cancel qfrc_passive"));
}

/// Acceleration-level control through inverse dynamics. Each tick:
///
///     ẍ_d = A_WD + Kp·e + Kd·ė                              (task acceleration, m rows)
///     q̈   = J⁺·(ẍ_d − J̇·q̇) + (I − J⁺·J)·q̈₀               (joint acceleration)
///     τ   = M·q̈ + h − τ_passive                              (inverse dynamics)
///
/// with e = task_error(X_WE, X_WD), ė = V_WD − J·q̇ (world axes, linear first), J the
/// world-aligned Jacobian (its first 3 rows in position mode), and J⁺ the damped least-squares
/// inverse Jᵀ·(J·Jᵀ + λ²·I)⁻¹ (= (Jᵀ·J + λ²·I)⁻¹·Jᵀ when m > n). The damping follows the
/// manipulability w (Nakamura & Hanafusa 1986): λ = λ_max·(1 − w/w₀) when w < w₀, else 0, so away
/// from singularities J·q̈ + J̇·q̇ = ẍ_d exactly and near them q̈ stays bounded. q̈₀ = −kd·q̇ (+
/// kp·(q_ref − q)) acts in the kinematic null space only.
///
/// Unlike copying one error to every joint, the error is distributed by J⁺, and the dynamics are
/// cancelled exactly (M from MuJoCo's M, h its bias forces): with the model exact, the task
/// error obeys ë + Kd·ė + Kp·e = 0 in every direction (to first order in the orientation error).
///
/// Internals: position_error [m], orientation_error [rad], manipulability w, damping λ.
class AccelerationController final : public Controller {
 public:
  /// @throws Error when a gain is negative or not finite, or w₀ is not > 0.
  explicit AccelerationController(const Chain& chain, const AccelerationControlOptions& options = {});
  ~AccelerationController() override;
  AccelerationController(const AccelerationController& other);
  AccelerationController& operator=(const AccelerationController& other);
  AccelerationController(AccelerationController&& other) noexcept;
  AccelerationController& operator=(AccelerationController&& other) noexcept;

  std::string_view name() const noexcept override { return "accel"; }
  CommandKind command_kind() const noexcept override { return CommandKind::torque; }
  const Chain& chain() const noexcept override { return dynamics_.chain(); }
  const AccelerationControlOptions& options() const noexcept { return options_; }

  /// One tick; a command of the wrong size is left untouched.
  void compute(const mjData& data, const Reference& reference,
               JointCommand& command) noexcept override;

  /// Joint acceleration q̈ of the last `compute` (n) [rad/s² or m/s²].
  const Eigen::VectorXd& joint_acceleration() const noexcept { return qdd_; }
  /// Desired task acceleration ẍ_d of the last `compute` (first m entries used).
  const Vector6d& task_acceleration() const noexcept { return xdd_; }

  std::span<const std::string> internal_names() const noexcept override { return names_; }
  std::span<const double> internal_values() const noexcept override { return values_; }

 private:
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
  using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;

  /// x = J⁺·y (y: m, x: n) with the factorization of the last `factor`.
  void apply_pinv(const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> x) noexcept;

  AccelerationControlOptions options_;
  int rows_ = 6;
  ChainDynamics dynamics_;
  // workspace
  Eigen::MatrixXd J_;        // m×n
  Small gram_;               // J·Jᵀ (m ≤ n) or Jᵀ·J (m > n), + λ²·I
  struct Factor;             // its Cholesky factor (in the .cpp: Eigen/Cholesky)
  WorkspacePtr<Factor> llt_;
  SmallVector small_;        // m or n
  Vector6d xdd_ = Vector6d::Zero();
  Eigen::VectorXd qdd_;      // n
  Eigen::VectorXd qdd0_;     // n
  Eigen::VectorXd task_;     // m
  Eigen::VectorXd back_;     // n
  Eigen::VectorXd passive_;  // n
  std::array<std::string, 4> names_{"position_error", "orientation_error", "manipulability",
                                    "damping"};
  std::array<double, 4> values_{0.0, 0.0, 0.0, 0.0};
};

}  // namespace mjarm
