/// @file
/// The Goldfarb–Idnani iteration of DenseQp: working-set start (cold / warm), the dual step
/// loop with partial steps and drops, and the KKT report.

#include <algorithm>
#include <cmath>
#include <limits>

#include "dense_kernels.hpp"
#include "mjarm/qp/dense_qp.hpp"

namespace mjarm::qp {

double DenseQp::slack(int id) const noexcept {
  // n_p·x − b_p with the row products of cx_ref_ (valid when x_ref_ = x_)
  const int k = id - me_;
  if (k < 2 * mi_) {
    return k % 2 == 1 ? u_[k / 2] - cx_ref_[k / 2] : cx_ref_[k / 2] - l_[k / 2];
  }
  const int kb = k - 2 * mi_;
  return kb % 2 == 1 ? ub_[kb / 2] - x_[kb / 2] : x_[kb / 2] - lb_[kb / 2];
}

bool DenseQp::start_working_set(bool warm, int max_iterations, int& steps) noexcept {
  const double dep_tol = settings_.dependence_tolerance;
  if (warm && factor_current_) {
    // same matrices as the last solved working set: keep its factorization, refresh g and limits
    factor_.set_linear_term(g_);
    for (int k = 0; k < factor_.active_count(); ++k) b_active_[k] = rhs(active_[k]);
    for (int k = factor_.active_count() - 1; k >= eq_active_; --k) {
      if (!std::isfinite(b_active_[k])) drop_active(k, nullptr);
    }
  } else {
    // build the working set from scratch: equalities first, they never leave it
    factor_.reset();
    factor_.set_linear_term(g_);
    state_.setZero();
    row_skip_.setZero();
    redundant_count_ = 0;
    for (int i = 0; i < me_; ++i) {
      normal_projection(i, d_);
      if (factor_.add(d_, dep_tol)) {
        push_active(i);
      } else {
        redundant_eq_[redundant_count_++] = i;
      }
    }
    eq_active_ = factor_.active_count();
    // warm: re-add the previous inequality working set, skipping what is now dependent
    if (warm) {
      for (int k = 0; k < warm_count_; ++k) {
        const int id = warm_[k];
        if (!std::isfinite(rhs(id))) continue;
        normal_projection(id, d_);
        if (factor_.add(d_, dep_tol)) push_active(id);
      }
    }
  }
  factor_.solve_subproblem(b_active_, x_, u_active_);

  // dual feasibility of the start: drop the most negative inequality multiplier until none is
  for (;;) {
    const int q = factor_.active_count();
    double scale = 1.0;
    for (int k = eq_active_; k < q; ++k) scale = std::max(scale, std::abs(u_active_[k]));
    int worst = -1;
    double worst_u = -1e-13 * scale;
    for (int k = eq_active_; k < q; ++k) {
      if (u_active_[k] < worst_u) {
        worst_u = u_active_[k];
        worst = k;
      }
    }
    if (worst < 0) break;
    if (++steps > max_iterations) return false;
    drop_active(worst, nullptr);
    factor_.solve_subproblem(b_active_, x_, u_active_);
  }
  for (int k = eq_active_; k < factor_.active_count(); ++k) {
    u_active_[k] = std::max(u_active_[k], 0.0);
  }

  // a dependent equality is implied by the others only if it holds at their solution
  for (int k = 0; k < redundant_count_; ++k) {
    const int i = redundant_eq_[k];
    const double residual = (a_eq_.row(i).dot(x_) - b_eq_[i]) * eq_scale_[i];
    if (!(std::abs(residual) <= settings_.primal_tolerance)) return false;
  }
  return true;
}

QpStatus DenseQp::run(bool warm, int max_iterations, int& iterations) noexcept {
  const double dep_tol = settings_.dependence_tolerance;
  int steps = 0;
  const bool started = start_working_set(warm, max_iterations, steps);
  iterations += steps;
  if (!started) return steps > max_iterations ? QpStatus::iteration_limit : QpStatus::infeasible;

  for (;;) {
    double s = 0.0;
    const int p = most_violated(s);
    if (p < 0) {
      // nan compares as satisfied: a numerical breakdown must not pass for a solution
      return x_.allFinite() ? QpStatus::solved : QpStatus::iteration_limit;
    }

    // dual steps on constraint p until it joins the working set
    normal_projection(p, d_);
    for (;;) {
      ++iterations;
      if (++steps > max_iterations) return QpStatus::iteration_limit;
      const int q = factor_.active_count();
      const bool dependent = !factor_.independent(d_, dep_tol);
      factor_.dual_direction(d_, r_);
      // partial step length: the first inequality multiplier to reach zero
      double t1 = std::numeric_limits<double>::infinity();
      int leave = -1;
      for (int k = eq_active_; k < q; ++k) {
        if (r_[k] > 0.0) {
          const double t = u_active_[k] / r_[k];
          if (t < t1) {
            t1 = t;
            leave = k;
          }
        }
      }
      // full step length: the primal step that makes p hold with equality
      const double null2 = dependent ? 0.0 : factor_.null_space_norm2(d_);
      const double t2 = dependent ? std::numeric_limits<double>::infinity() : -s / null2;
      if (leave < 0 && dependent) return QpStatus::infeasible;  // the dual is unbounded

      if (t2 <= t1) {
        // full step: the new minimizer on the enlarged working set, recomputed exactly
        factor_.add(d_, dep_tol);
        push_active(p);
        factor_.solve_subproblem(b_active_, x_, u_active_);
        for (int k = eq_active_; k <= q; ++k) u_active_[k] = std::max(u_active_[k], 0.0);
        break;
      }
      // partial step: multipliers move along -r until constraint `leave` drops out
      for (int k = 0; k < q; ++k) u_active_[k] -= t1 * r_[k];
      if (!dependent) s += t1 * null2;
      drop_active(leave, &d_);
    }
  }
}

void DenseQp::finalize(QpStatus status, int iterations, bool warm) noexcept {
  QpResult& res = result_;
  res.status = status;
  res.iterations = iterations;
  res.warm_started = warm;
  res.y_eq.setZero();
  res.y_in.setZero();
  res.y_bound.setZero();
  if (status == QpStatus::invalid_input || status == QpStatus::not_convex) {
    res.x.setZero();
    res.objective = 0.0;
    res.kkt_residual = std::numeric_limits<double>::infinity();
    return;
  }
  res.x = x_;
  // exact row products at the final x; they also screen the next warm start
  if (mi_ > 0 && !(ref_valid_ && x_ref_ == x_)) refresh_reference();

  // multipliers in the y convention: lower side y = -u, upper side y = +u
  const int q = factor_.active_count();
  double complementarity = 0.0;
  for (int k = 0; k < q; ++k) {
    const int id = active_[k];
    const double u = u_active_[k];
    if (id < me_) {
      res.y_eq[id] = -u;
      continue;
    }
    complementarity = std::max(complementarity, std::abs(u * slack(id)));
    const int m = id - me_;
    if (m < 2 * mi_) {
      res.y_in[m / 2] = m % 2 == 1 ? u : -u;
    } else {
      const int mb = m - 2 * mi_;
      res.y_bound[mb / 2] = mb % 2 == 1 ? u : -u;
    }
  }

  // stationarity H x + g + A_eqᵀ y_eq + Cᵀ y_in + y_bound and the objective
  kernels::columns_times(H_.data(), n_, n_, n_, x_.data(), hx_.data());
  res.objective = 0.5 * x_.dot(hx_) + g_.dot(x_);
  stat_ = hx_ + g_ + res.y_bound;
  for (int k = 0; k < q; ++k) {
    const int id = active_[k];
    if (id < me_) {
      stat_ += res.y_eq[id] * a_eq_.row(id).transpose();
    } else if (id - me_ < 2 * mi_) {
      const int i = (id - me_) / 2;
      stat_ += res.y_in[i] * c_.row(i).transpose();
    }
  }
  double residual = stat_.lpNorm<Eigen::Infinity>();

  // primal feasibility of every constraint
  for (int i = 0; i < me_; ++i) {
    residual = std::max(residual, std::abs(a_eq_.row(i).dot(x_) - b_eq_[i]));
  }
  for (int i = 0; i < mi_; ++i) {
    residual = std::max(residual, std::max(l_[i] - cx_ref_[i], cx_ref_[i] - u_[i]));
  }
  for (int j = 0; j < n_; ++j) {
    residual = std::max(residual, std::max(lb_[j] - x_[j], x_[j] - ub_[j]));
  }
  res.kkt_residual = std::max(residual, complementarity);
}

}  // namespace mjarm::qp
