#include "mjarm/control/hqp_ac.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "control_checks.hpp"
#include "mjarm/control/task_error.hpp"
#include "mjarm/model/actuator_limits.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Relative widening of the null-space QP's bounds (see solve_null).
constexpr double kNullSlack = 1e-9;

/// @p v with one entry per joint: a single entry repeated, or n entries as given.
/// @throws Error naming @p what when the size is neither 1 nor n.
Eigen::VectorXd hqp_per_joint(const Eigen::VectorXd& v, int n, const char* what) {
  if (v.size() == 1) return Eigen::VectorXd::Constant(n, v[0]);
  if (v.size() == n) return v;
  throw Error(std::string("hqp-ac: ") + what + " must have 1 or " + std::to_string(n) +
              " entries (one per chain joint), got " + std::to_string(v.size()));
}

/// The checked options: each declared field in its range, the per-joint sizes, a non-zero axis.
const HqpAcOptions& hqp_checked(const HqpAcOptions& o, const Chain& chain) {
  check_fields(o, "hqp-ac");
  const int n = chain.size();
  hqp_per_joint(o.max_velocity, n, "max_velocity");
  if (o.max_torque.size() > 0) hqp_per_joint(o.max_torque, n, "max_torque");
  if (!(o.preload.axis.norm() > 0.0)) {
    throw Error("hqp-ac: preload axis must be non-zero, got " +
                detail::values_text(o.preload.axis));
  }
  return o;
}

FrictionFeedForwardOptions hqp_friction_options(const HqpAcOptions& o) {
  FrictionFeedForwardOptions f = o.friction;
  // ĥ cancels the damping (compensate_passive) or the user wants it left alone: never here
  f.damping = DampingCompensation::by_controller;
  return f;
}

ManipulabilityOptions hqp_manipulability_options() {
  ManipulabilityOptions m;
  m.block = JacobianBlock::full;
  return m;
}

}  // namespace

struct HqpAcController::Factors {
  explicit Factors(int n) : llt(n) {}
  Eigen::LLT<Eigen::MatrixXd> llt;  // of H (n×n)
  Eigen::LLT<Matrix6d> gram_llt;    // of J·Jᵀ
};

HqpAcController::HqpAcController(const Chain& chain, const HqpAcOptions& options)
    : options_(hqp_checked(options, chain)),
      dynamics_(chain),
      task_space_(chain.size(), 6, options.task_space),
      compliance_(options.compliance),
      manipulability_(chain, hqp_manipulability_options()),
      source_(chain, options.force),
      friction_(chain, hqp_friction_options(options)),
      friction_on_(options.friction_feed_forward && friction_.active()),
      main_qp_(chain.size(), 0, chain.size()),
      null_qp_(chain.size(), 6, chain.size()),
      factors_(make_workspace<Factors>(chain.size())) {
  const int n = chain.size();
  main_qp_.settings() = options.qp;
  null_qp_.settings() = options.qp;
  v_max_ = hqp_per_joint(options.max_velocity, n, "max_velocity");
  tau_min_.resize(n);
  tau_max_.resize(n);
  if (options.max_torque.size() == 0) {
    for (int i = 0; i < n; ++i) {
      const TorqueRange r = joint_torque_range(chain, i);
      tau_min_[i] = r.lower;
      tau_max_[i] = r.upper;
    }
  } else {
    tau_max_ = hqp_per_joint(options.max_torque, n, "max_torque");
    tau_min_ = -tau_max_;
  }
  friction_room_ = friction_on_ ? friction_.friction() : Eigen::VectorXd::Zero(n);
  tau_lo_ = tau_min_ + friction_room_;
  tau_hi_ = tau_max_ - friction_room_;
  for (int i = 0; i < n; ++i) {
    if (!(tau_lo_[i] < tau_hi_[i])) {
      throw Error("hqp-ac: the torque range of joint '" + chain.joint_names()[i] + "' [" +
                  number_text(tau_min_[i]) + ", " + number_text(tau_max_[i]) +
                  "] N·m leaves no room once its friction feed-forward (" +
                  number_text(friction_room_[i]) + " N·m) is set aside");
    }
  }
  q_lo_ = chain.lower();
  q_hi_ = chain.upper();
  axis_ = options.preload.axis.normalized();
  q_start_.setZero(n);
  H_.setZero(n, n);
  M_.setZero(n, n);
  J_.setZero(6, n);
  for (Eigen::VectorXd* v :
       {&g_, &h_hat_, &lb_, &ub_, &row_lo_, &row_hi_, &null_lb_, &null_ub_, &null_row_lo_,
        &null_row_hi_, &qdd1_, &qdd0_, &qdd_, &gradient_, &goal_, &tau_ff_}) {
    v->setZero(n);
  }
}

HqpAcController::~HqpAcController() = default;
HqpAcController::HqpAcController(HqpAcController&& other) noexcept = default;
HqpAcController& HqpAcController::operator=(HqpAcController&& other) noexcept = default;

void HqpAcController::reset() noexcept {
  source_.reset();
  main_qp_.reset_warm_start();
  null_qp_.reset_warm_start();
  has_start_ = false;
  in_contact_ = false;
  preload_level_ = 0.0;
  preload_from_ = 0.0;
  contact_time_ = 0.0;
  tick_ = HqpAcTick{};
  diagnostics_ = HqpAcSolveDiagnostics{};
  counters_ = HqpAcCounters{};
  wrench_.setZero();
  preload_force_.setZero();
  values_.fill(0.0);
}

void HqpAcController::hold(const mjData& data, Eigen::Ref<Eigen::VectorXd> tau,
                           HqpAcStatus status) noexcept {
  // τ = ĥ − M·D_p·q̇ (gravity held, joints braked), zero when not finite, within the limits
  update_bias(data);
  qdd_ = -options_.posture_damping * dynamics_.qd();
  tau.noalias() = dynamics_.mass_matrix() * qdd_;
  tau += h_hat_;
  if (!tau.allFinite()) {
    tau.setZero();
    qdd_.setZero();
  }
  tau = tau.cwiseMax(tau_min_).cwiseMin(tau_max_);
  finish(status);
}

void HqpAcController::update_preload(double force, double time) noexcept {
  // contact with hysteresis; each change restarts a linear ramp from the level it had then
  const HqpAcPreload& p = options_.preload;
  const bool contact =
      in_contact_ ? force >= p.release_ratio * p.contact_force : force >= p.contact_force;
  if (contact != in_contact_) {
    in_contact_ = contact;
    preload_from_ = preload_level_;
    contact_time_ = time;
  }
  const double elapsed = std::max(0.0, time - contact_time_);
  preload_level_ = in_contact_ ? std::min(1.0, preload_from_ + elapsed / p.ramp_time)
                               : std::max(0.0, preload_from_ - elapsed / p.release_time);
}

void HqpAcController::compute(const mjData& data, const Reference& reference,
                              JointCommand& command) noexcept {
  command.kind = CommandKind::torque;
  const int n = dynamics_.size();
  if (command.value.size() != n) return;
  auto tau = command.value.head(n);
  tick_ = HqpAcTick{};
  diagnostics_ = HqpAcSolveDiagnostics{};
  ++counters_.ticks;
  dynamics_.update(data);

  // state, then target: anything not finite gets the hold command and an honest status
  if (!detail::state_valid(dynamics_) || !std::isfinite(data.time)) {
    return hold(data, tau, HqpAcStatus::invalid_state);
  }
  const TaskSpaceStatus task_status = task_space_.update(dynamics_);
  if (task_status == TaskSpaceStatus::not_positive_definite) {
    return hold(data, tau, HqpAcStatus::invalid_state);
  }
  tick_.task_damped = task_status == TaskSpaceStatus::damped;
  const TaskReference& target = reference.task;
  if (!target.X_WE.p.allFinite() || !detail::is_rotation(target.X_WE.R) ||
      !target.V_WE.allFinite() || !target.A_WE.allFinite()) {
    return hold(data, tau, HqpAcStatus::invalid_target);
  }
  if (!has_start_) {
    q_start_ = dynamics_.q();
    has_start_ = true;
  }

  // measured wrench, contact latch, adaptive stiffness and damping
  const Pose& X_WE = dynamics_.pose();
  tick_.wrench_valid = source_.measure(data, X_WE) == WrenchStatus::ok;
  wrench_ = source_.wrench();
  update_preload(wrench_.head<3>().norm(), data.time);
  tick_.in_contact = in_contact_;
  compliance_.update(wrench_, task_space_.lambda_inverse());

  // reference force F_r = −D_r·Δν − K_r·e, the preload, and the main QP's target
  const Vector6d e = -task_error(X_WE, target.X_WE);
  const Vector6d dv = dynamics_.velocity() - target.V_WE;
  Vector6d F = -(compliance_.damping() * dv) - compliance_.stiffness() * e;
  preload_force_.setZero();
  if (options_.preload.force > 0.0 && preload_level_ > 0.0) {
    preload_force_ = preload_level_ * options_.preload.force * (X_WE.R * axis_);
    F.head<3>() += preload_force_;
  }
  b_ = target.A_WE - dynamics_.bias_acceleration();
  b_.noalias() += task_space_.lambda_inverse() * F;

  // ĥ = h − τ_passive, the bounds, then the two QPs
  update_bias(data);
  M_ = dynamics_.mass_matrix();
  J_ = dynamics_.jacobian();
  build_bounds();
  bool main_ok = solve_main();
  bool null_ok = true;
  if (main_ok) {
    null_goal();
    null_ok = solve_null();
    if (!null_ok) qdd_ = qdd1_;
  } else {
    least_squares();
  }

  // τ = M·q̈ + ĥ (+ the friction feed-forward on the moving part M·q̈)
  tau.noalias() = M_ * qdd_;
  if (friction_on_) {
    tau_ff_ = tau;
    friction_.apply(dynamics_.qd(), tau_ff_);
    tau_ff_ -= tau;
    tau += tau_ff_;
  } else {
    tau_ff_.setZero();
  }
  tau += h_hat_;
  if (!tau.allFinite()) return hold(data, tau, HqpAcStatus::invalid_state);
  // a solved QP keeps τ inside (to its tolerance); a fallback may need the clip
  for (int i = 0; i < n; ++i) {
    const double tol = 1e-6 * (1.0 + std::abs(tau[i]));
    if (tau[i] > tau_max_[i] + tol || tau[i] < tau_min_[i] - tol) tick_.torque_clipped = true;
    tau[i] = std::clamp(tau[i], tau_min_[i], tau_max_[i]);
  }
  source_.record_command(data, dynamics_, tau);

  HqpAcStatus status = HqpAcStatus::ok;
  if (tick_.task_damped) status = HqpAcStatus::damped;
  if (!tick_.wrench_valid) status = HqpAcStatus::invalid_wrench;
  if (!null_ok) status = HqpAcStatus::null_space_dropped;
  if (!main_ok) status = HqpAcStatus::least_squares;
  values_[0] = e.head<3>().norm();
  values_[1] = e.tail<3>().norm();
  finish(status);
}

void HqpAcController::update_bias(const mjData& data) noexcept {
  if (options_.compensate_passive) {
    detail::read_passive(dynamics_.chain(), data, h_hat_);
    h_hat_ = dynamics_.bias() - h_hat_;
  } else {
    h_hat_ = dynamics_.bias();
  }
}

void HqpAcController::build_bounds() noexcept {
  const double dt = options_.horizon;
  const Eigen::VectorXd& q = dynamics_.q();
  const Eigen::VectorXd& v = dynamics_.qd();
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    // |v + dt·q̈| ≤ v_max and q_lo ≤ q + dt·v + ½dt²·q̈ ≤ q_hi (±inf for an unlimited joint)
    const double lo_v = (-v_max_[i] - v[i]) / dt, hi_v = (v_max_[i] - v[i]) / dt;
    const double drift = q[i] + dt * v[i];
    const double lo_p = std::isfinite(q_lo_[i]) ? 2.0 * (q_lo_[i] - drift) / (dt * dt) : -kInf;
    const double hi_p = std::isfinite(q_hi_[i]) ? 2.0 * (q_hi_[i] - drift) / (dt * dt) : kInf;
    lb_[i] = std::max(lo_v, lo_p);
    ub_[i] = std::min(hi_v, hi_p);
  }
  row_lo_ = tau_lo_ - h_hat_;
  row_hi_ = tau_hi_ - h_hat_;
}

bool HqpAcController::solve_main() noexcept {
  // H = JᵀJ + ε·(tr(JᵀJ)/tr(M))·M: positive definite, unit-consistent regularization; the
  // least-squares fallback needs them too
  H_.noalias() = J_.transpose() * J_;
  const double scale = options_.regularization * H_.trace() / M_.trace();
  H_ += scale * M_;
  g_.noalias() = -J_.transpose() * b_;
  // an empty box or torque interval is infeasible before any solve
  if ((lb_.array() > ub_.array()).any() || (row_lo_.array() > row_hi_.array()).any()) {
    tick_.main_qp = qp::QpStatus::infeasible;
    return false;
  }
  main_qp_.set_hessian(H_);
  main_qp_.set_gradient(g_);
  main_qp_.set_inequalities(M_, row_lo_, row_hi_);
  main_qp_.set_bounds(lb_, ub_);
  const auto start = std::chrono::steady_clock::now();
  const qp::QpResult& r = main_qp_.solve(qp::QpStart::warm);
  record_solve(start, r.iterations, main_qp_.active_count(), false);
  tick_.main_qp = r.status;
  tick_.main_iterations = r.iterations;
  if (r.status != qp::QpStatus::solved) return false;
  qdd1_ = r.x;
  qdd_ = qdd1_;
  return true;
}

void HqpAcController::least_squares() noexcept {
  // the main QP's unconstrained minimizer, H·q̈ = −g (H and g of solve_main), clamped into the
  // box (a crossed pair of bounds clamps between them)
  factors_->llt.compute(H_);
  if (factors_->llt.info() == Eigen::Success) {
    qdd_ = -g_;
    factors_->llt.solveInPlace(qdd_);
  } else {
    qdd_.setZero();
  }
  for (Eigen::Index i = 0; i < qdd_.size(); ++i) {
    const double lo = std::min(lb_[i], ub_[i]), hi = std::max(lb_[i], ub_[i]);
    qdd_[i] = std::clamp(qdd_[i], lo, hi);
  }
  if (!qdd_.allFinite()) qdd_.setZero();
  qdd1_ = qdd_;
  qdd0_.setZero();
}

void HqpAcController::null_goal() noexcept {
  const Eigen::VectorXd& q = dynamics_.q();
  qdd0_ = options_.posture_stiffness * (q_start_ - q) - options_.posture_damping * dynamics_.qd();
  // ω = √det(J·Jᵀ) from the Cholesky factor of the 6×6 Gram matrix (Π L_ii); the analytic
  // gradient (an SVD in `Manipulability`) only below the threshold, where the term acts
  gram_.noalias() = J_ * J_.transpose();
  factors_->gram_llt.compute(gram_);
  double w = 0.0;
  if (factors_->gram_llt.info() == Eigen::Success)
    w = factors_->gram_llt.matrixLLT().diagonal().prod();
  if (w < options_.manipulability_threshold) {
    // the state is finite (checked), so the evaluation cannot throw
    w = manipulability_.evaluate(q, gradient_).manipulability;
    const double deficit = options_.manipulability_threshold - w;
    if (deficit > 0.0) qdd0_ += (options_.singularity_gain * deficit) * gradient_;
  }
  tick_.manipulability = w;
  goal_ = qdd1_ + qdd0_;
}

bool HqpAcController::solve_null() noexcept {
  // min ½(q̈ − goal)ᵀ·M·(q̈ − goal) s.t. J·q̈ = J·q̈₁ and the bounds: the M-metric projection of
  // q̈₀ onto the null space of J, i.e. q̈₁ + N·q̈₀ when no bound is active
  tick_.null_qp_ran = true;
  Vector6d beq;
  beq.noalias() = J_ * qdd1_;
  g_.noalias() = -M_ * goal_;
  null_qp_.set_hessian(M_);
  null_qp_.set_gradient(g_);
  null_qp_.set_equalities(J_, beq);
  // the bounds widened by a hair (1e-9 relative): q̈₁ sits on the main QP's active bounds, and
  // with them and J·q̈ = J·q̈₁ the feasible set can shrink to the point q̈₁ itself, which the
  // active-set method would call infeasible from rounding alone
  auto widen = [](const Eigen::VectorXd& lo, const Eigen::VectorXd& hi, Eigen::VectorXd& wlo,
                  Eigen::VectorXd& whi) {
    wlo = lo - kNullSlack * (1.0 + lo.array().abs()).matrix();
    whi = hi + kNullSlack * (1.0 + hi.array().abs()).matrix();
  };
  widen(row_lo_, row_hi_, null_row_lo_, null_row_hi_);
  widen(lb_, ub_, null_lb_, null_ub_);
  null_qp_.set_inequalities(M_, null_row_lo_, null_row_hi_);
  null_qp_.set_bounds(null_lb_, null_ub_);
  const auto start = std::chrono::steady_clock::now();
  const qp::QpResult& r = null_qp_.solve(qp::QpStart::warm);
  record_solve(start, r.iterations, null_qp_.active_count(), true);
  tick_.null_qp = r.status;
  tick_.null_iterations = r.iterations;
  if (r.status != qp::QpStatus::solved) return false;
  qdd_ = r.x;
  return true;
}

void HqpAcController::record_solve(std::chrono::steady_clock::time_point start, int iterations,
                                   int active, bool null_space) noexcept {
  const std::chrono::duration<double, std::micro> took = std::chrono::steady_clock::now() - start;
  HqpAcSolveDiagnostics& g = diagnostics_;
  const int n = dynamics_.size();
  g.solve_time_us += took.count();
  g.iterations += iterations;
  if (null_space) {
    g.null_iterations = iterations;
    g.null_active = active;
    g.null_constraints = 6 + 2 * n;
  } else {
    g.main_iterations = iterations;
    g.main_active = active;
    g.main_constraints = 2 * n;
  }
}

void HqpAcController::finish(HqpAcStatus status) noexcept {
  tick_.status = status;
  switch (status) {
    case HqpAcStatus::least_squares:
      ++counters_.least_squares;
      break;
    case HqpAcStatus::null_space_dropped:
      ++counters_.null_space_dropped;
      break;
    case HqpAcStatus::invalid_target:
      ++counters_.invalid_target;
      break;
    case HqpAcStatus::invalid_state:
      ++counters_.invalid_state;
      break;
    default:
      break;
  }
  if (!tick_.wrench_valid) ++counters_.invalid_wrench;
  if (tick_.torque_clipped) ++counters_.torque_clipped;
  if (status == HqpAcStatus::invalid_target || status == HqpAcStatus::invalid_state) {
    values_[0] = values_[1] = 0.0;
  }
  values_[2] = compliance_.effective_force();
  values_[3] = compliance_.scale();
  values_[4] = preload_force_.norm();
  values_[5] = tick_.manipulability;
  values_[6] = tick_.main_iterations;
  values_[7] = tick_.null_iterations;
  values_[8] = static_cast<double>(counters_.least_squares);
  values_[9] = static_cast<double>(counters_.null_space_dropped);
  values_[10] = static_cast<double>(counters_.torque_clipped);
  values_[11] = static_cast<double>(static_cast<int>(status));
  values_[12] = diagnostics_.main_active;
  values_[13] = diagnostics_.null_active;
}

}  // namespace mjarm
