#include "mjarm/qp/box_qp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "dense_kernels.hpp"
#include "mjarm/error.hpp"

namespace mjarm::qp {

namespace {

constexpr double kBoxInf = std::numeric_limits<double>::infinity();

int box_checked_size(int n) {
  if (n < 1) throw Error("BoxQp: number of variables must be >= 1, got " + std::to_string(n));
  return n;
}

void box_check_size(const char* what, Eigen::Index rows, Eigen::Index cols, Eigen::Index want_rows,
                    Eigen::Index want_cols) {
  if (rows != want_rows || cols != want_cols) {
    throw Error(std::string("BoxQp: ") + what + " must be " + std::to_string(want_rows) + "x" +
                std::to_string(want_cols) + ", got " + std::to_string(rows) + "x" +
                std::to_string(cols));
  }
}

inline double box_clamp(double v, double lo, double hi) noexcept {
  return v < lo ? lo : (v > hi ? hi : v);
}

}  // namespace

BoxQp::BoxQp(int n) : n_(box_checked_size(n)) {
  result_.x = Eigen::VectorXd::Zero(n);
  result_.y_bound = Eigen::VectorXd::Zero(n);
  H_ = Eigen::MatrixXd::Zero(n, n);
  g_ = Eigen::VectorXd::Zero(n);
  lb_ = Eigen::VectorXd::Constant(n, -kBoxInf);
  ub_ = Eigen::VectorXd::Constant(n, kBoxInf);
  state_ = Eigen::VectorXi::Zero(n);
  order_ = Eigen::VectorXi::LinSpaced(n, 0, n - 1);
  L_.setZero(n, n);
  inv_diag_ = Eigen::VectorXd::Zero(n);
  x_ = Eigen::VectorXd::Zero(n);
  z_ = Eigen::VectorXd::Zero(n);
  grad_ = Eigen::VectorXd::Zero(n);
}

void BoxQp::set_hessian(const Eigen::Ref<const Eigen::MatrixXd>& H) {
  box_check_size("H", H.rows(), H.cols(), n_, n_);
  // the lower triangle, mirrored; a non-finite entry turns the sum of entry·0 into nan
  const int n = n_;
  const double* src = H.data();
  const Eigen::Index ld = H.outerStride();
  double* dst = H_.data();
  double probe = 0.0, max_diag = 0.0;
  for (int j = 0; j < n; ++j) {
    const double* col = src + j * ld;
    max_diag = std::max(max_diag, std::abs(col[j]));
    for (int i = j; i < n; ++i) {
      const double v = col[i];
      dst[j * n + i] = v;
      dst[i * n + j] = v;
      probe += v * 0.0;
    }
  }
  hessian_ok_ = probe == 0.0;
  pivot_min_ = 1e-14 * max_diag;
}

void BoxQp::set_gradient(const Eigen::Ref<const Eigen::VectorXd>& g) {
  box_check_size("g", g.rows(), g.cols(), n_, 1);
  g_ = g;
  gradient_ok_ = g_.allFinite();
}

void BoxQp::set_bounds(const Eigen::Ref<const Eigen::VectorXd>& lb,
                       const Eigen::Ref<const Eigen::VectorXd>& ub) {
  box_check_size("lb", lb.rows(), lb.cols(), n_, 1);
  box_check_size("ub", ub.rows(), ub.cols(), n_, 1);
  lb_ = lb;
  ub_ = ub;
  // valid when neither is nan, lb <= ub, lb < +inf and ub > -inf (comparisons with nan fail)
  int ok = 1;  // ints: a branch-free bitwise and
  for (int j = 0; j < n_; ++j)
    ok &= int(lb_[j] <= ub_[j]) & int(lb_[j] < kBoxInf) & int(ub_[j] > -kBoxInf);
  bounds_ok_ = ok != 0;
}

const BoxQpResult& BoxQp::solve(QpStart start) noexcept {
  if (!(hessian_ok_ && gradient_ok_ && bounds_ok_)) {
    finalize(QpStatus::invalid_input, 0, false);
    return result_;
  }
  const bool warm = start == QpStart::warm && have_warm_;
  int iterations = 0;
  const QpStatus status = run(warm, iterations);
  finalize(status, iterations, warm);
  return result_;
}

bool BoxQp::factor_rows(int from, int to) noexcept {
  // up-looking Cholesky of H in working order: row k of L from rows 0..k−1, so rows before the
  // first changed position stay valid when the order changes after it
  const int n = n_;
  const int* order = order_.data();
  double* L = L_.data();
  double* inv_diag = inv_diag_.data();
  for (int k = from; k < to; ++k) {
    const double* h = &H_(0, order[k]);  // column order[k]: entry order[m] is H(order[m], order[k])
    double* lk = L + k * n;
    double diag = h[order[k]];
    for (int m = 0; m < k; ++m) {
      const double* lm = L + m * n;
      double s = h[order[m]];
      for (int i = 0; i < m; ++i) s -= lk[i] * lm[i];
      s *= inv_diag[m];
      lk[m] = s;
      diag -= s * s;
    }
    if (!(diag > pivot_min_)) return false;  // also catches nan
    const double d = std::sqrt(diag);
    lk[k] = d;
    inv_diag[k] = 1.0 / d;
  }
  return true;
}

void BoxQp::solve_free() noexcept {
  // z = H_FF⁻¹·(−g_F − H_FA·x_A), in working order (raw loops: a few entries each)
  const int n = n_, nf = nf_;
  const int* order = order_.data();
  const double* H = H_.data();
  const double* g = g_.data();
  const double* x = x_.data();
  const double* L = L_.data();
  const double* inv_diag = inv_diag_.data();
  double* z = z_.data();
  for (int k = 0; k < nf; ++k) z[k] = -g[order[k]];
  for (int a = nf; a < n; ++a) {
    const int j = order[a];
    const double xj = x[j];
    if (xj == 0.0) continue;
    const double* h = H + j * n;  // column j
    for (int k = 0; k < nf; ++k) z[k] -= h[order[k]] * xj;
  }
  for (int k = 0; k < nf; ++k) {  // L y = rhs
    const double* lk = L + k * n;
    double s = z[k];
    for (int m = 0; m < k; ++m) s -= lk[m] * z[m];
    z[k] = s * inv_diag[k];
  }
  for (int k = nf - 1; k >= 0; --k) {  // Lᵀ z = y, one column of Lᵀ (row of L) at a time
    const double zk = z[k] * inv_diag[k];
    z[k] = zk;
    const double* lk = L + k * n;
    for (int m = 0; m < k; ++m) z[m] -= lk[m] * zk;
  }
}

void BoxQp::gradient() noexcept {
  kernels::columns_times(H_.data(), n_, n_, n_, x_.data(), grad_.data());
  grad_ += g_;
}

QpStatus BoxQp::run(bool warm, int& iterations) noexcept {
  const int n = n_;
  int* order = order_.data();

  // first working set: the kept bound pattern where those bounds are finite, else none
  nf_ = 0;
  int bound_count = 0;
  for (int j = 0; j < n; ++j) {
    const double lo = lb_[j], hi = ub_[j];
    int s = warm ? state_[j] : 0;
    if (lo == hi) {
      s = 2;
    } else if ((s == -1 && lo == -kBoxInf) || (s == 1 && hi == kBoxInf) || s == 2) {
      s = 0;
    }
    state_[j] = s;
    if (s == 0) {
      x_[j] = box_clamp(warm ? x_[j] : 0.0, lo, hi);
      order[nf_++] = j;
    } else {
      x_[j] = s == 1 ? hi : lo;
      order[n - 1 - bound_count++] = j;
    }
  }

  // all of H in this order: the positive-definiteness check; its first nf rows factor H_FF
  if (!factor_rows(0, n)) return QpStatus::not_convex;
  int valid = nf_;

  const int max_iterations = settings_.max_iterations > 0 ? settings_.max_iterations : 10 * n + 100;
  const double tolerance = settings_.dual_tolerance;
  while (iterations < max_iterations) {
    ++iterations;
    if (valid < nf_ && !factor_rows(valid, nf_)) return QpStatus::not_convex;
    valid = nf_;
    solve_free();

    // ratio test: the first free variable to reach a bound on the way from x to z
    double alpha = 1.0;
    int block = -1;
    for (int k = 0; k < nf_; ++k) {
      const int j = order[k];
      const double d = z_[k] - x_[j];
      const double t = d < 0.0 ? (lb_[j] - x_[j]) / d : (d > 0.0 ? (ub_[j] - x_[j]) / d : kBoxInf);
      if (t < alpha) {
        alpha = t;
        block = k;
      }
    }
    if (block >= 0) {
      const int jb = order[block];
      const int side = z_[block] < x_[jb] ? -1 : 1;
      for (int k = 0; k < nf_; ++k) {
        const int j = order[k];
        x_[j] = box_clamp(x_[j] + alpha * (z_[k] - x_[j]), lb_[j], ub_[j]);
      }
      x_[jb] = side == 1 ? ub_[jb] : lb_[jb];
      state_[jb] = side;
      // jb leaves F: the free variables after it move up one place, jb heads the bound part
      for (int k = block; k + 1 < nf_; ++k) order[k] = order[k + 1];
      order[--nf_] = jb;
      valid = std::min(valid, block);
      continue;
    }
    for (int k = 0; k < nf_; ++k) {
      const int j = order[k];
      x_[j] = box_clamp(z_[k], lb_[j], ub_[j]);
    }

    // at the minimizer on the working set: the gradient entries of the bound variables are their
    // multipliers (y_j = −(H x + g)_j); release the one with the most wrong sign
    gradient();
    double worst = 0.0;
    int release = -1;
    for (int a = nf_; a < n; ++a) {
      const int j = order[a];
      const int s = state_[j];
      const double v = s == -1 ? grad_[j] : (s == 1 ? -grad_[j] : 0.0);  // −y_j at lb, y_j at ub
      if (v < worst) {
        worst = v;
        release = a;
      }
    }
    if (release >= 0) {
      // released only when clearly wrong: beyond the round-off scale of its gradient entry
      const int j = order[release];
      double scale = std::abs(g_[j]);
      for (int m = 0; m < n; ++m) scale += std::abs(H_(j, m) * x_[m]);
      if (!(worst < -tolerance * scale)) release = -1;
    }
    if (release < 0) return QpStatus::solved;
    const int j = order[release];
    state_[j] = 0;
    order[release] = order[nf_];
    order[nf_++] = j;  // appended to F: one new factor row
  }
  return QpStatus::iteration_limit;
}

void BoxQp::finalize(QpStatus status, int iterations, bool warm) noexcept {
  BoxQpResult& res = result_;
  res.iterations = iterations;
  res.warm_started = warm;
  if (status == QpStatus::invalid_input || status == QpStatus::not_convex) {
    res.status = status;
    res.x.setZero();
    res.y_bound.setZero();
    res.objective = 0.0;
    res.kkt_residual = kBoxInf;
    res.active_count = 0;
    have_warm_ = false;
    return;
  }
  if (status != QpStatus::solved) gradient();  // a solved run has just computed it at x
  res.x = x_;
  double residual = 0.0, objective = 0.0;
  for (int j = 0; j < n_; ++j) {
    const int s = state_[j];
    const double gj = grad_[j], xj = x_[j];
    objective += xj * (gj + g_[j]);  // xᵀ(Hx + g) + gᵀx = xᵀHx + 2gᵀx
    res.y_bound[j] = s == 0 ? 0.0 : -gj;
    const double dual = s == 0 ? std::abs(gj) : (s == -1 ? -gj : (s == 1 ? gj : 0.0));
    const double primal = std::max(lb_[j] - xj, xj - ub_[j]);
    residual = std::max(residual, std::max(dual, primal));
  }
  // a non-finite iterate (which makes the objective non-finite) is a numerical breakdown
  res.status =
      status == QpStatus::solved && !std::isfinite(objective) ? QpStatus::iteration_limit : status;
  res.kkt_residual = residual;
  res.objective = 0.5 * objective;
  res.active_count = n_ - nf_;
  have_warm_ = res.status == QpStatus::solved;
}

}  // namespace mjarm::qp
