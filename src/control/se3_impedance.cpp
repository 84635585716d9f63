#include "mjarm/control/se3_impedance.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <string>

#include "control_checks.hpp"
#include "mjarm/lie/coefficients.hpp"
#include "mjarm/lie/se3.hpp"
#include "mjarm/lie/se3_jacobian.hpp"
#include "mjarm/trajectory/smoothstep.hpp"

namespace mjarm {
namespace {

/// "[[a, b, …], …]" of a 6×6 matrix for error messages.
std::string se3_matrix_text(const Matrix6d& m) {
  std::string text = "[";
  for (int r = 0; r < 6; ++r) text += (r ? ", " : "") + detail::values_text(m.row(r).transpose());
  return text + "]";
}

/// Eigenvalues (ascending) of a symmetric matrix of at most 6×6, without heap allocation.
Vector6d se3_eigenvalues(const Matrix6d& m) {
  Eigen::SelfAdjointEigenSolver<Matrix6d> solver(m, Eigen::EigenvaluesOnly);
  return solver.eigenvalues();
}

/// @throws Error unless @p m is finite and symmetric (to 1e-9 of its largest entry).
void se3_require_symmetric(const Matrix6d& m, const char* what) {
  if (!m.allFinite()) {
    throw Error(std::string("se3: ") + what + " must be finite, got " + se3_matrix_text(m));
  }
  const double scale = std::max(1.0, m.cwiseAbs().maxCoeff());
  if ((m - m.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) {
    throw Error(std::string("se3: ") + what + " must be symmetric, got " + se3_matrix_text(m));
  }
}

/// @throws Error unless @p m is symmetric positive definite.
void se3_require_positive_definite(const Matrix6d& m, const char* what) {
  se3_require_symmetric(m, what);
  const Vector6d eig = se3_eigenvalues(m);
  if (!(eig[0] > 1e-12 * std::max(1.0, eig[5]))) {
    throw Error(std::string("se3: ") + what +
                " must be symmetric positive definite; its eigenvalues are " +
                detail::values_text(eig));
  }
}

/// @throws Error unless @p K is symmetric positive semi-definite and positive definite on the
/// axes not in @p released.
void se3_require_stiffness(const Matrix6d& K, const std::array<bool, 6>& released) {
  se3_require_symmetric(K, "stiffness K");
  const Vector6d eig = se3_eigenvalues(K);
  const double scale = std::max(1.0, eig[5]);
  if (eig[0] < -1e-12 * scale) {
    throw Error("se3: stiffness K must be symmetric positive semi-definite; its eigenvalues are " +
                detail::values_text(eig));
  }
  // the principal block of the axes that keep their stiffness
  Matrix6d kept = Matrix6d::Zero();
  int n = 0;
  std::string axes;
  static const char* const kAxis[6] = {"x", "y", "z", "rx", "ry", "rz"};
  for (int i = 0; i < 6; ++i) {
    if (released[static_cast<std::size_t>(i)]) continue;
    int c = 0;
    for (int j = 0; j < 6; ++j) {
      if (!released[static_cast<std::size_t>(j)]) kept(n, c++) = K(i, j);
    }
    axes += (n ? ", " : "") + std::string(kAxis[i]);
    ++n;
  }
  if (n == 0) return;
  using Block = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
  const Block block = kept.topLeftCorner(n, n);
  Eigen::SelfAdjointEigenSolver<Block> solver(block, Eigen::EigenvaluesOnly);
  if (!(solver.eigenvalues()[0] > 1e-12 * scale)) {
    throw Error("se3: stiffness K must be positive definite on the axes not released [" + axes +
                "] (only an axis named in release.axes may have zero stiffness); the eigenvalues "
                "of that block are " +
                detail::values_text(solver.eigenvalues()));
  }
}

/// blkdiag(R, R)·x for a linear-first 6-vector.
Vector6d se3_rotate6(const Eigen::Matrix3d& R, const Vector6d& x) noexcept {
  Vector6d y;
  y << R * x.head<3>(), R * x.tail<3>();
  return y;
}

FrictionFeedForwardOptions se3_friction_options(const Se3ImpedanceOptions& o) {
  FrictionFeedForwardOptions f = o.friction;
  f.damping =
      o.compensate_passive ? DampingCompensation::by_controller : DampingCompensation::feed_forward;
  return f;
}

}  // namespace

Se3ImpedanceController::Se3ImpedanceController(const Chain& chain,
                                               const Se3ImpedanceOptions& options)
    : options_(options),
      dynamics_(chain),
      task_space_(chain.size(), 6, options.task_space),
      limits_(chain, options.joint_limits),
      friction_(chain, se3_friction_options(options)),
      friction_on_(options.friction_feed_forward && friction_.active()) {
  se3_require_positive_definite(options.inertia, "inertia A");
  se3_require_positive_definite(options.damping, "damping D");
  se3_require_stiffness(options.stiffness, options.release.axes);
  check_fields(options, "se3");
  inertia_inverse_ = options.inertia.llt().solve(Matrix6d::Identity());
  for (int i = 0; i < 6; ++i) release_mask_[i] = options.release.axes[static_cast<std::size_t>(i)];
  stiffness_now_ = options.stiffness;
  const int n = chain.size();
  tau0_.setZero(n);
  null_.setZero(n);
  passive_.setZero(n);
  moving_.setZero(n);
  friction_torque_.setZero(n);
}

void Se3ImpedanceController::reset() noexcept {
  wrench_.setZero();
  release_started_ = false;
  release_armed_ = true;
  release_start_ = 0.0;
  release_ = 0.0;
  stiffness_now_ = options_.stiffness;
  status_ = Se3ImpedanceStatus::ok;
  lambda_.setZero();
  lambda_dot_.setZero();
  accel_ref_.setZero();
  dexp_.setIdentity();
}

void Se3ImpedanceController::start_release(double time) noexcept {
  if (release_started_ || release_mask_.isZero() || !std::isfinite(time)) return;
  release_started_ = true;
  release_start_ = time;
}

void Se3ImpedanceController::set_release_armed(bool armed) noexcept {
  release_armed_ = armed;
  if (armed) return;
  release_started_ = false;
  release_ = 0.0;
}

void Se3ImpedanceController::update_release(double t) noexcept {
  release_ =
      release_started_ ? smoothstep((t - release_start_) / options_.release.duration).s : 0.0;
  const Vector6d s = Vector6d::Ones() - release_ * release_mask_;
  stiffness_now_ = s.asDiagonal() * options_.stiffness * s.asDiagonal();
}

void Se3ImpedanceController::hold(const mjData& data, Eigen::Ref<Eigen::VectorXd> tau,
                                  Se3ImpedanceStatus status) noexcept {
  status_ = status;
  tau = dynamics_.bias() - options_.nullspace_damping * dynamics_.qd();
  if (options_.compensate_passive) {
    detail::read_passive(dynamics_.chain(), data, passive_);
    tau -= passive_;
  }
  if (!tau.allFinite()) tau.setZero();
  friction_torque_.setZero();
  accel_ref_.setZero();
  write_values();
}

void Se3ImpedanceController::compute(const mjData& data, const Reference& reference,
                                     JointCommand& command) noexcept {
  command.kind = CommandKind::torque;
  const int n = dynamics_.size();
  if (command.value.size() != n) return;
  auto tau = command.value.head(n);
  dynamics_.update(data);

  // state, then target: anything not finite gets the hold command and an honest status
  if (!detail::state_valid(dynamics_) || !std::isfinite(data.time)) {
    return hold(data, tau, Se3ImpedanceStatus::invalid_state);
  }
  const TaskSpaceStatus task_status = task_space_.update(dynamics_);
  if (task_status == TaskSpaceStatus::not_positive_definite) {
    return hold(data, tau, Se3ImpedanceStatus::invalid_state);
  }
  const TaskReference& target = reference.task;
  if (!target.X_WE.p.allFinite() || !detail::is_rotation(target.X_WE.R) ||
      !target.V_WE.allFinite() || !target.A_WE.allFinite()) {
    return hold(data, tau, Se3ImpedanceStatus::invalid_target);
  }
  Se3ImpedanceStatus status =
      task_status == TaskSpaceStatus::ok ? Se3ImpedanceStatus::ok : Se3ImpedanceStatus::damped;
  Vector6d F_E = wrench_;
  if (!F_E.allFinite()) {
    F_E.setZero();
    status = Se3ImpedanceStatus::invalid_wrench;
  }

  // the desired wrench, made by the spring: the target moved by K_ii⁻¹·F_d,i on the kept axes
  target_ = target.X_WE;
  const Vector6d& F_d = target.F_ext;
  if (options_.wrench_feed_forward && F_d.allFinite() && !F_d.isZero(0.0)) {
    const Vector6d F_D = se3_rotate6(target.X_WE.R.transpose(), F_d);
    Vector6d shift = Vector6d::Zero();
    for (int i = 0; i < 6; ++i) {
      // on a kept axis K(t)_ii = K_ii (S_ii = 1): the release never changes the shift
      const double k = options_.stiffness(i, i);
      if (release_mask_[i] == 0.0 && k > 0.0) shift[i] = F_D[i] / k;
    }
    target_ = target.X_WE * se3::exp(shift);
  }

  // contact-triggered release of the chosen stiffness axes
  if (release_armed_ && !release_started_ &&
      F_E.head<3>().norm() >= options_.release.contact_force) {
    start_release(data.time);
  }
  update_release(data.time);

  // error T̃ = X_ED and its coordinates λ (principal branch, ‖ω‖ ≤ π < 2π)
  const Pose& X_WE = dynamics_.pose();
  const Eigen::Matrix3d& R = X_WE.R;
  const Pose X_ED = X_WE.inverse() * target_;
  lambda_ = se3::log(X_ED);
  const double theta = lambda_.tail<3>().norm();
  if (!lambda_.allFinite() || !(theta < lie::kTwoPi)) {
    return hold(data, tau, Se3ImpedanceStatus::invalid_state);  // unreachable for a rotation
  }

  // body twists of E and D, and D's body acceleration
  const Vector6d& V_W = dynamics_.velocity();  // [ṗ_WE; ω_WE] in W
  const Vector6d V = se3_rotate6(R.transpose(), V_W);
  const Eigen::Matrix3d R_WDt = target_.R.transpose();
  const Vector6d V_d = se3_rotate6(R_WDt, target.V_WE);
  Vector6d A_d = se3_rotate6(R_WDt, target.A_WE);
  A_d.head<3>() -= V_d.tail<3>().cross(V_d.head<3>());

  // Ṽ = Ad_T̃·V_d − V, λ̇ = E⁻¹·Ṽ, Ė
  const Vector6d V_err = se3::transform_twist(X_ED, V_d) - V;
  dexp_ = se3::left_jacobian(lambda_);
  lambda_dot_.noalias() = se3::left_jacobian_inverse(lambda_) * V_err;  // θ < 2π: never throws
  const Matrix6d dexp_dot = se3::left_jacobian_derivative(lambda_, lambda_dot_);

  // the impedance in λ: λ̈_ref = A⁻¹(γ − D·λ̇ − K·λ), γ = −Eᵀ·F_E
  const Vector6d gamma = -dexp_.transpose() * F_E;
  const Vector6d lambda_ddot =
      inertia_inverse_ * (gamma - options_.damping * lambda_dot_ - stiffness_now_ * lambda_);

  // V̇_ref = Ad_T̃·V̇_d − E·λ̈_ref + ad_Ṽ·V − Ė·λ̇
  Vector6d ad_V;
  ad_V << V_err.tail<3>().cross(V.head<3>()) + V_err.head<3>().cross(V.tail<3>()),
      V_err.tail<3>().cross(V.tail<3>());
  accel_ref_ =
      se3::transform_twist(X_ED, A_d) - dexp_ * lambda_ddot + ad_V - dexp_dot * lambda_dot_;

  // τ = J_bᵀ·Λ_b·(V̇_ref − J̇_b·q̇) + h − τ_passive − J_bᵀ·F_E + Nᵀ·τ₀, evaluated with the
  // world-aligned J = blkdiag(R, R)·J_b: blkdiag(R, R)·(V̇_ref − J̇_b·q̇) = blkdiag(R, R)·V̇_ref −
  // J̇·q̇ + [ω × ṗ; 0] and J_bᵀ·F_E = Jᵀ·blkdiag(R, R)·F_E
  Vector6d task_accel = se3_rotate6(R, accel_ref_) - dynamics_.bias_acceleration();
  task_accel.head<3>() += V_W.tail<3>().cross(V_W.head<3>());
  Vector6d force;
  force.noalias() = task_space_.lambda() * task_accel;
  force -= se3_rotate6(R, F_E);
  tau.noalias() = dynamics_.jacobian().transpose() * force;
  tau += dynamics_.bias();
  if (options_.compensate_passive) {
    detail::read_passive(dynamics_.chain(), data, passive_);
    tau -= passive_;
  }
  tau0_ = -options_.nullspace_damping * dynamics_.qd();
  const auto& q_ref = reference.joint.q;
  if (options_.nullspace_stiffness > 0.0 && q_ref.size() == n && q_ref.allFinite()) {
    tau0_ += options_.nullspace_stiffness * (q_ref - dynamics_.q());
  }
  task_space_.project_torque(tau0_, null_);
  tau += null_;
  if (limits_.enabled()) {
    limits_.update(dynamics_.q(), dynamics_.qd());
    limits_.add_to(&task_space_, tau);
  }
  if (friction_on_) {
    // the part of τ that moves the joints sets the torque mode's sign
    const Chain& c = dynamics_.chain();
    for (int i = 0; i < n; ++i) {
      moving_[i] = tau[i] - dynamics_.bias()[i] + data.qfrc_passive[c.dof_address(i)];
    }
    friction_torque_ = moving_;
    friction_.apply(dynamics_.qd(), friction_torque_);
    friction_torque_ -= moving_;
    tau += friction_torque_;
  }
  if (!tau.allFinite()) return hold(data, tau, Se3ImpedanceStatus::invalid_state);
  status_ = status;
  write_values();
}

void Se3ImpedanceController::write_values() noexcept {
  for (int i = 0; i < 6; ++i) {
    values_[static_cast<std::size_t>(i)] = lambda_[i];
    values_[static_cast<std::size_t>(6 + i)] = lambda_dot_[i];
  }
  values_[12] = 0.0;  // dexp_condition: see internal_values()
  values_[13] = 0.0;  // task_condition: see internal_values()
  values_[14] = task_space_.status() == TaskSpaceStatus::damped ? 1.0 : 0.0;
  values_[15] = release_;
  values_[16] = static_cast<double>(static_cast<int>(status_));
}

std::span<const double> Se3ImpedanceController::internal_values() const noexcept {
  const Eigen::JacobiSVD<Matrix6d> svd(dexp_);
  const Vector6d& sigma = svd.singularValues();
  values_[12] = sigma[5] > 0.0 ? sigma[0] / sigma[5] : INFINITY;
  values_[13] = task_space_.condition();
  return values_;
}

}  // namespace mjarm
