#include "mjarm/qp/dense_qp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm::qp {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

int checked_variables(int n, int m_eq, int m_in) {
  if (n < 1 || m_eq < 0 || m_in < 0) {
    throw Error(
        "DenseQp: sizes must be n >= 1, m_eq >= 0, m_in >= 0; got n = " + std::to_string(n) +
        ", m_eq = " + std::to_string(m_eq) + ", m_in = " + std::to_string(m_in));
  }
  return n;
}

void check_size(const char* what, Eigen::Index rows, Eigen::Index cols, Eigen::Index want_rows,
                Eigen::Index want_cols) {
  if (rows != want_rows || cols != want_cols) {
    throw Error(std::string("DenseQp: ") + what + " must be " + std::to_string(want_rows) + "x" +
                std::to_string(want_cols) + ", got " + std::to_string(rows) + "x" +
                std::to_string(cols));
  }
}

// limits are valid when neither is nan, l <= u, l < +inf and u > -inf (every comparison with
// nan is false); branch-free so that the loop vectorizes
bool limits_valid(const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  int ok = 1;  // ints: a branch-free bitwise and
  for (Eigen::Index i = 0; i < lo.size(); ++i) {
    ok &= int(lo[i] <= hi[i]) & int(lo[i] < kInf) & int(hi[i] > -kInf);
  }
  return ok != 0;
}

}  // namespace

DenseQp::DenseQp(int n, int m_eq, int m_in)
    : n_(checked_variables(n, m_eq, m_in)), me_(m_eq), mi_(m_in), factor_(n) {
  result_.x = Eigen::VectorXd::Zero(n);
  result_.y_eq = Eigen::VectorXd::Zero(m_eq);
  result_.y_in = Eigen::VectorXd::Zero(m_in);
  result_.y_bound = Eigen::VectorXd::Zero(n);
  H_ = Eigen::MatrixXd::Zero(n, n);
  g_ = Eigen::VectorXd::Zero(n);
  a_eq_.setZero(m_eq, n);
  b_eq_ = Eigen::VectorXd::Zero(m_eq);
  eq_scale_ = Eigen::VectorXd::Ones(m_eq);
  c_.setZero(m_in, n);
  c_cols_.setZero(m_in, n);
  l_ = Eigen::VectorXd::Constant(m_in, -kInf);
  u_ = Eigen::VectorXd::Constant(m_in, kInf);
  c_scale_ = Eigen::VectorXd::Ones(m_in);
  lb_ = Eigen::VectorXd::Constant(n, -kInf);
  ub_ = Eigen::VectorXd::Constant(n, kInf);
  active_ = Eigen::VectorXi::Zero(n);
  b_active_ = Eigen::VectorXd::Zero(n);
  u_active_ = Eigen::VectorXd::Zero(n);
  state_ = Eigen::VectorXi::Zero(m_in + n);
  row_skip_ = Eigen::VectorXd::Zero(m_in);
  redundant_eq_ = Eigen::VectorXi::Zero(m_eq);
  warm_ = Eigen::VectorXi::Zero(n);
  x_ = Eigen::VectorXd::Zero(n);
  x_ref_ = Eigen::VectorXd::Zero(n);
  cx_ref_ = Eigen::VectorXd::Zero(m_in);
  near_ = Eigen::VectorXi::Zero(m_in + 1);
  near_cx_ = Eigen::VectorXd::Zero(m_in + 1);
  margin_ref_ = Eigen::VectorXd::Zero(m_in);
  d_ = Eigen::VectorXd::Zero(n);
  r_ = Eigen::VectorXd::Zero(n);
  hx_ = Eigen::VectorXd::Zero(n);
  stat_ = Eigen::VectorXd::Zero(n);
}

void DenseQp::set_hessian(const Eigen::Ref<const Eigen::MatrixXd>& H) {
  check_size("H", H.rows(), H.cols(), n_, n_);
  // mirror the lower triangle so that products with H_ match the factorized matrix; a
  // non-finite entry turns the sum of entry·0 into nan
  double probe = 0.0;
  for (int j = 0; j < n_; ++j) {
    for (int i = j; i < n_; ++i) {
      const double v = H(i, j);
      H_(i, j) = v;
      H_(j, i) = v;
      probe += v * 0.0;
    }
  }
  hessian_ok_ = probe == 0.0;
  hessian_dirty_ = true;
  factor_current_ = false;
}

void DenseQp::set_gradient(const Eigen::Ref<const Eigen::VectorXd>& g) {
  check_size("g", g.rows(), g.cols(), n_, 1);
  g_ = g;
  gradient_ok_ = g_.allFinite();
}

void DenseQp::set_equalities(const Eigen::Ref<const Eigen::MatrixXd>& A_eq,
                             const Eigen::Ref<const Eigen::VectorXd>& b_eq) {
  check_size("A_eq", A_eq.rows(), A_eq.cols(), me_, n_);
  check_size("b_eq", b_eq.rows(), b_eq.cols(), me_, 1);
  a_eq_ = A_eq;
  a_eq_ok_ = a_eq_.allFinite();
  for (int i = 0; i < me_; ++i) {
    const double norm = a_eq_.row(i).norm();
    eq_scale_[i] = norm > 0.0 ? 1.0 / norm : 1.0;
  }
  factor_current_ = false;
  set_equality_rhs(b_eq);
}

void DenseQp::set_equality_rhs(const Eigen::Ref<const Eigen::VectorXd>& b_eq) {
  check_size("b_eq", b_eq.rows(), b_eq.cols(), me_, 1);
  b_eq_ = b_eq;
  b_eq_ok_ = b_eq_.allFinite();
}

void DenseQp::set_inequalities(const Eigen::Ref<const Eigen::MatrixXd>& C,
                               const Eigen::Ref<const Eigen::VectorXd>& l,
                               const Eigen::Ref<const Eigen::VectorXd>& u) {
  check_size("C", C.rows(), C.cols(), mi_, n_);
  check_size("l", l.rows(), l.cols(), mi_, 1);
  check_size("u", u.rows(), u.cols(), mi_, 1);
  c_ = C;
  c_cols_ = C;
  c_ok_ = c_.allFinite();
  ref_valid_ = false;
  // a zero row keeps scale 1 so that an unsatisfiable 0 >= l > 0 still shows as violated
  for (int i = 0; i < mi_; ++i) {
    const double norm = c_.row(i).norm();
    c_scale_[i] = norm > 0.0 ? 1.0 / norm : 1.0;
  }
  factor_current_ = false;
  set_inequality_limits(l, u);
}

void DenseQp::set_inequality_limits(const Eigen::Ref<const Eigen::VectorXd>& l,
                                    const Eigen::Ref<const Eigen::VectorXd>& u) {
  check_size("l", l.rows(), l.cols(), mi_, 1);
  check_size("u", u.rows(), u.cols(), mi_, 1);
  l_ = l;
  u_ = u;
  limits_ok_ = limits_valid(l_, u_);
  margins_stale_ = true;
}

void DenseQp::set_bounds(const Eigen::Ref<const Eigen::VectorXd>& lb,
                         const Eigen::Ref<const Eigen::VectorXd>& ub) {
  check_size("lb", lb.rows(), lb.cols(), n_, 1);
  check_size("ub", ub.rows(), ub.cols(), n_, 1);
  lb_ = lb;
  ub_ = ub;
  bounds_ok_ = limits_valid(lb_, ub_);
}

bool DenseQp::data_valid() const noexcept {
  return hessian_ok_ && gradient_ok_ && a_eq_ok_ && b_eq_ok_ && c_ok_ && limits_ok_ && bounds_ok_;
}

const QpResult& DenseQp::solve(QpStart start) noexcept {
  if (!data_valid()) {
    finalize(QpStatus::invalid_input, 0, false);
    return result_;
  }
  if (hessian_dirty_) {
    // the only place H is factorized: set_hessian() marks it stale
    ++factorizations_;
    hessian_dirty_ = false;
    factor_current_ = false;
    hessian_convex_ = factor_.factorize(H_);
  }
  if (!hessian_convex_) {
    finalize(QpStatus::not_convex, 0, false);
    return result_;
  }
  const int max_iterations =
      settings_.max_iterations > 0 ? settings_.max_iterations : 10 * (n_ + me_ + mi_ + n_) + 100;
  bool warm = start == QpStart::warm && (factor_current_ || warm_count_ > 0);
  if (warm && factor_current_ && ++warm_reuses_ >= kRebuildPeriod) {
    // now and then rebuild the reused factorization from J0 to bound rounding drift
    factor_current_ = false;
    warm_reuses_ = 0;
  }
  int iterations = 0;
  QpStatus status = run(warm, max_iterations, iterations);
  if (warm && status != QpStatus::solved) {
    // a failed warm start proves nothing: the cold start decides
    warm = false;
    status = run(false, max_iterations, iterations);
  }
  finalize(status, iterations, warm);
  if (status == QpStatus::solved) {
    // remember the inequality part of the working set for the next warm start
    warm_count_ = 0;
    for (int k = eq_active_; k < factor_.active_count(); ++k) warm_[warm_count_++] = active_[k];
    factor_current_ = true;
  } else {
    factor_current_ = false;
  }
  return result_;
}

void DenseQp::normal_projection(int id, Eigen::VectorXd& d) const noexcept {
  if (id < me_) {
    factor_.project(a_eq_.row(id).transpose(), d);
    return;
  }
  const int k = id - me_;
  if (k < 2 * mi_) {
    factor_.project(c_.row(k / 2).transpose(), d);
    if (k % 2 == 1) d = -d;  // upper side: normal -c_i
    return;
  }
  const int kb = k - 2 * mi_;
  factor_.project_unit(kb / 2, kb % 2 == 1 ? -1.0 : 1.0, d);
}

double DenseQp::rhs(int id) const noexcept {
  if (id < me_) return b_eq_[id];
  const int k = id - me_;
  if (k < 2 * mi_) return k % 2 == 1 ? -u_[k / 2] : l_[k / 2];
  const int kb = k - 2 * mi_;
  return kb % 2 == 1 ? -ub_[kb / 2] : lb_[kb / 2];
}

void DenseQp::set_state(int id, int value) noexcept {
  if (id < me_) return;
  const int k = id - me_;
  if (k < 2 * mi_) {
    state_[k / 2] = value == 0 ? 0 : (k % 2 == 1 ? 1 : -1);
    row_skip_[k / 2] = value == 0 ? 0.0 : kInf;
  } else {
    const int kb = k - 2 * mi_;
    state_[mi_ + kb / 2] = value == 0 ? 0 : (kb % 2 == 1 ? 1 : -1);
  }
}

void DenseQp::push_active(int id) noexcept {
  const int q = factor_.active_count() - 1;  // the factor has already grown
  active_[q] = id;
  b_active_[q] = rhs(id);
  u_active_[q] = 0.0;
  set_state(id, 1);
}

void DenseQp::drop_active(int k, Eigen::VectorXd* d) noexcept {
  const int q = factor_.active_count();
  factor_.drop(k, d);
  set_state(active_[k], 0);
  for (int m = k; m < q - 1; ++m) {
    active_[m] = active_[m + 1];
    b_active_[m] = b_active_[m + 1];
    u_active_[m] = u_active_[m + 1];
  }
}

}  // namespace mjarm::qp
