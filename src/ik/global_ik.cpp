#include "mjarm/ik/global_ik.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/ik/targets.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/random.hpp"
#include "validate_pose.hpp"

namespace mjarm {
namespace {

constexpr int kMaxStallWindow = kGlobalIkMaxStallWindow;

/// start + timeout on the steady clock, saturated: a timeout beyond half the clock's remaining
/// range (about 146 years) never expires. A plain duration_cast of a huge double duration to
/// int64 nanoseconds overflows (1e13 ms did) and put the deadline in the past.
std::chrono::steady_clock::time_point deadline_after(std::chrono::steady_clock::time_point start,
                                                     std::chrono::duration<double> timeout) {
  using Clock = std::chrono::steady_clock;
  const std::chrono::duration<double> room = (Clock::time_point::max() - start) / 2;
  if (!(timeout < room)) return Clock::time_point::max();
  return start + std::chrono::duration_cast<Clock::duration>(timeout);
}

}  // namespace

void check(const GlobalIkOptions& o) {
  if (!(o.timeout.count() > 0.0) || !std::isfinite(o.timeout.count())) {
    throw Error("global IK: timeout must be positive and finite [s], got " +
                number_text(o.timeout.count()));
  }
  check_tolerance(o.tolerance);
  check_fields(o);
}

GlobalIk::GlobalIk(const Chain& chain, const GlobalIkOptions& options)
    : options_(options), kin_(chain), qp_(chain.size(), 0, 0) {
  check(options_);
  const int n = chain.size();
  // restarts sample the limits; an unlimited joint samples one turn (hinge) or ±1 m (slide)
  sample_lower_ = chain.lower();
  sample_upper_ = chain.upper();
  const mjModel& m = chain.robot().model();
  for (int i = 0; i < n; ++i) {
    const double half = m.jnt_type[chain.joint_id(i)] == mjJNT_HINGE ? std::numbers::pi : 1.0;
    if (!std::isfinite(sample_lower_[i])) sample_lower_[i] = -half;
    if (!std::isfinite(sample_upper_[i])) sample_upper_[i] = half;
  }
  // the closed form holds for the frame on a fixed base (joints off the chain would move it)
  if (chain.unmoved_path_joints().empty() && analyze_analytic_ik(chain).solvable) {
    analytic_.emplace(chain);
  }
  J_ = Matrix6Xd::Zero(6, n);
  H_ = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::VectorXd* v :
       {&q_, &q_trial_, &dq_, &g_, &lb_, &ub_, &q_seed_, &q_best_, &q_solution_}) {
    *v = Eigen::VectorXd::Zero(n);
  }
}

void GlobalIk::set_options(const GlobalIkOptions& options) {
  check(options);
  options_ = options;
}

void GlobalIk::set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  kin_.set_fixed_qpos(qpos);
}

IkResult GlobalIk::solve(const Pose& X_WT, const Eigen::Ref<const Eigen::VectorXd>& q_seed) {
  IkResult result;
  solve(X_WT, q_seed, result);
  return result;
}

double GlobalIk::uniform() noexcept { return mjarm::uniform(rng_); }

void GlobalIk::random_configuration(Eigen::VectorXd& q) noexcept {
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    q[i] = sample_lower_[i] + uniform() * (sample_upper_[i] - sample_lower_[i]);
  }
}

double GlobalIk::evaluate(const Eigen::VectorXd& q, Vector6d& e) noexcept {
  const Pose& X_WE = kin_.update(q);
  e.head<3>() = X_WT_.p - X_WE.p;
  if (position_only_) {
    e.tail<3>().setZero();
  } else {
    e.tail<3>() = so3::log(X_WT_.R * X_WE.R.transpose());
  }
  return 0.5 * e.squaredNorm();
}

bool GlobalIk::converged(const Vector6d& e) const noexcept {
  // target-frame error e_T = −blockdiag(R_WTᵀ, R_WTᵀ)·e (see pose_tolerance.hpp)
  const Eigen::Vector3d lin = X_WT_.R.transpose() * e.head<3>();
  const Eigen::Vector3d ang = X_WT_.R.transpose() * e.tail<3>();
  const Vector6d& b = options_.tolerance.bound;
  for (int i = 0; i < 3; ++i) {
    if (!(std::abs(lin[i]) <= b[i]) || !(std::abs(ang[i]) <= b[3 + i])) return false;
  }
  return true;
}

double GlobalIk::manipulability() noexcept {
  // √det(J Jᵀ) for n ≥ 6 (√det(JᵀJ) for shorter chains), through an in-place Cholesky factor;
  // a position target uses the translational rows only: √det(J_v J_vᵀ) for n ≥ 3
  const int n = kin_.chain().size();
  double det = 0.0;
  if (position_only_ && n >= 3) {
    const Eigen::Matrix3d JJt = J_.topRows<3>().lazyProduct(J_.topRows<3>().transpose());
    Eigen::LLT<Eigen::Matrix3d> llt(JJt);
    if (llt.info() == Eigen::Success) det = llt.matrixLLT().diagonal().prod();
  } else if (n >= 6 && !position_only_) {
    const Matrix6d JJt = J_.lazyProduct(J_.transpose());
    Eigen::LLT<Matrix6d> llt(JJt);
    if (llt.info() == Eigen::Success) det = llt.matrixLLT().diagonal().prod();
  } else {
    H_.noalias() = J_.transpose().lazyProduct(J_);
    Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(H_);
    if (llt.info() == Eigen::Success) det = H_.diagonal().prod();
  }
  return std::abs(det);  // product of the factor's diagonal = √det
}

void GlobalIk::solve(const Pose& X_WT, const Eigen::Ref<const Eigen::VectorXd>& q_seed,
                     IkResult& result) {
  detail::validate_pose(X_WT, "GlobalIk target");
  kin_.chain().check(q_seed, "seed");
  X_WT_ = X_WT;
  position_only_ = false;
  search(q_seed, result);
}

IkResult GlobalIk::solve_position(const Eigen::Vector3d& p_WT,
                                  const Eigen::Ref<const Eigen::VectorXd>& q_seed) {
  IkResult result;
  solve_position(p_WT, q_seed, result);
  return result;
}

void GlobalIk::solve_position(const Eigen::Vector3d& p_WT,
                              const Eigen::Ref<const Eigen::VectorXd>& q_seed, IkResult& result) {
  check_position_target(p_WT, "GlobalIk position target");
  kin_.chain().check(q_seed, "seed");
  // world axes: the tolerance's x, y, z bounds apply to the world components of the error
  X_WT_ = Pose{};
  X_WT_.p = p_WT;
  position_only_ = true;
  search(q_seed, result);
}

void GlobalIk::update_jacobian() noexcept {
  kin_.jacobian(J_);
  if (position_only_) J_.bottomRows<3>().setZero();
}

void GlobalIk::search(const Eigen::Ref<const Eigen::VectorXd>& q_seed, IkResult& result) {
  const Chain& chain = kin_.chain();
  const int n = chain.size();
  const auto start = Clock::now();
  const auto deadline = deadline_after(start, options_.timeout);
  rng_.seed(options_.seed);
  stats_ = GlobalIkStats{};
  q_seed_ = q_seed;
  if (result.q.size() != n) result.q.resize(n);

  double best_E = std::numeric_limits<double>::infinity();  // smallest ½‖e‖² over all iterates (for
                                                            // a failed solve)
  double best_score = -std::numeric_limits<double>::infinity();  // mode score of the kept solution
                                                                 // (larger is better)
  int iterations = 0;
  Outcome last = Outcome::stalled;
  bool any_finite = false;
  const bool analytic_found = solve_analytically();
  if (analytic_found) {
    stats_.analytic = true;
    stats_.solutions = 1;
    q_solution_ = q_;
  }
  for (int attempt = 0; !analytic_found; ++attempt) {
    const bool use_sqp = options_.methods == GlobalIkMethods::sqp ||
                         (options_.methods == GlobalIkMethods::alternate && attempt % 2 == 1);
    if (attempt == 0) {
      q_ = chain.lower().cwiseMax(q_seed).cwiseMin(chain.upper());
    } else {
      random_configuration(q_);
    }
    ++stats_.attempts;
    last = run_attempt(use_sqp, deadline, iterations);
    if (last != Outcome::invalid) {
      any_finite = true;
      if (E_ < best_E) {
        best_E = E_;
        q_best_ = q_;
      }
    }
    if (last == Outcome::converged) {
      ++stats_.solutions;
      ++(use_sqp ? stats_.sqp_solutions : stats_.lm_solutions);
      double score = 0.0;
      if (options_.mode == GlobalIkMode::distance) score = -(q_ - q_seed_).squaredNorm();
      if (options_.mode == GlobalIkMode::manipulability) score = manipulability();
      if (stats_.solutions == 1 || score > best_score) {
        best_score = score;
        q_solution_ = q_;
      }
      if (options_.mode == GlobalIkMode::speed) break;
    }
    if (last == Outcome::timeout || attempt >= options_.max_restarts) break;
    if (Clock::now() >= deadline) {
      last = Outcome::timeout;
      break;
    }
  }

  // report the kept solution, else the best iterate, else the clipped seed
  if (stats_.solutions > 0) {
    result.q = q_solution_;
    result.status = IkStatus::converged;
  } else if (any_finite) {
    result.q = q_best_;
    result.status = last == Outcome::timeout ? IkStatus::timeout : IkStatus::not_converged;
  } else {
    result.q = chain.lower().cwiseMax(q_seed_).cwiseMin(chain.upper());
    result.status = IkStatus::invalid_input;
  }
  Vector6d e;
  evaluate(result.q, e);
  result.position_error = e.head<3>().norm();
  result.orientation_error = e.tail<3>().norm();
  result.iterations = iterations;
  if (stats_.solutions > 0) {
    update_jacobian();
    stats_.manipulability = manipulability();
  }
  stats_.elapsed = std::chrono::duration<double>(Clock::now() - start).count();
}

bool GlobalIk::solve_analytically() {
  if (!analytic_ || !options_.analytic || position_only_ ||
      options_.mode == GlobalIkMode::manipulability) {
    return false;
  }
  analytic_->solve(X_WT_, analytic_solution_);
  if (analytic_->closest_to(analytic_solution_, q_seed_, q_) < 0) return false;
  E_ = evaluate(q_, e_);
  return converged(e_);
}

GlobalIk::Outcome GlobalIk::run_attempt(bool use_sqp, Clock::time_point deadline,
                                        int& iterations) noexcept {
  const Eigen::VectorXd& lower = kin_.chain().lower();
  const Eigen::VectorXd& upper = kin_.chain().upper();
  E_ = evaluate(q_, e_);
  if (!std::isfinite(E_)) return Outcome::invalid;
  update_jacobian();
  mu_ = 0.1;
  qp_.reset_warm_start();
  std::array<double, kMaxStallWindow + 1> history{};  // E at the last iterations (ring)
  const int window = options_.stall_iterations;
  for (int it = 0;; ++it) {
    if (converged(e_)) return Outcome::converged;
    if (it >= options_.max_attempt_iterations) return Outcome::stalled;
    // progress test: the error must shrink by stall_ratio every `window` iterations
    if (it >= window && E_ > options_.stall_ratio * history[(it - window) % (window + 1)]) {
      return Outcome::stalled;
    }
    history[it % (window + 1)] = E_;
    if (Clock::now() >= deadline) return Outcome::timeout;
    ++iterations;

    // damping heavy far from the target, vanishing at the solution
    const double lambda = mu_ * E_ + options_.damping;
    // the unconstrained minimizer of both methods' model: Δq = Jᵀ(JJᵀ + λI)⁻¹e (6×6 solve)
    Matrix6d A;
    A.noalias() = J_.lazyProduct(J_.transpose());  // small: no GEMM blocking
    A.diagonal().array() += lambda;
    const Vector6d y = A.llt().solve(e_);
    dq_.noalias() = J_.transpose() * y;
    if (use_sqp) {
      // the QP only differs when a bound binds: solve it then, with the limits as constraints
      lb_ = (lower - q_).cwiseMax(-options_.max_step);
      ub_ = (upper - q_).cwiseMin(options_.max_step);
      if ((dq_.array() < lb_.array()).any() || (dq_.array() > ub_.array()).any()) {
        H_.noalias() = J_.transpose().lazyProduct(J_);
        H_.diagonal().array() += lambda;
        g_.noalias() = -J_.transpose() * e_;
        qp_.set_hessian(H_);
        qp_.set_gradient(g_);
        qp_.set_bounds(lb_, ub_);
        const qp::QpResult& r = qp_.solve(qp::QpStart::warm);
        if (!r.x.allFinite()) return Outcome::invalid;
        dq_ = r.x;
      }
    } else {
      const double largest = dq_.cwiseAbs().maxCoeff();
      if (largest > options_.max_step) dq_ *= options_.max_step / largest;
    }
    q_trial_ = (q_ + dq_).cwiseMax(lower).cwiseMin(upper);

    const double E_trial = evaluate(q_trial_, e_trial_);
    if (E_trial < E_) {
      // accept: a successful step lets the damping relax
      q_.swap(q_trial_);
      e_ = e_trial_;
      E_ = E_trial;
      update_jacobian();
      mu_ = std::max(mu_ * 0.5, 1e-3);
    } else {
      // reject: keep q (its Jacobian is still in J_) and damp harder
      mu_ *= 10.0;
    }
  }
}

}  // namespace mjarm
