#include "mjarm/qp/active_set_factor.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/qp/dense_kernels.hpp"

namespace mjarm::qp {

namespace {

// length of (a, b) without underflow or overflow of a² + b² (b != 0)
inline double pythag(double a, double b) noexcept {
  const double abs_a = std::abs(a);
  const double abs_b = std::abs(b);
  if (abs_a >= abs_b) {
    const double t = abs_b / abs_a;
    return abs_a * std::sqrt(1.0 + t * t);
  }
  const double t = abs_a / abs_b;
  return abs_b * std::sqrt(1.0 + t * t);
}

inline void rotate_pair(double& a, double& b, double c, double s) noexcept {
  const double t = c * a + s * b;
  b = c * b - s * a;
  a = t;
}

}  // namespace

ActiveSetFactor::ActiveSetFactor(int n) : n_(n) {
  if (n < 1) {
    throw Error("ActiveSetFactor: number of variables must be >= 1, got " + std::to_string(n));
  }
  l_ = RowMatrix::Zero(n, n);
  j0_ = Eigen::MatrixXd::Identity(n, n);
  j_ = Eigen::MatrixXd::Identity(n, n);
  r_ = Eigen::MatrixXd::Zero(n, n);
  w_ = Eigen::VectorXd::Zero(n);
  a_ = Eigen::VectorXd::Zero(n);
  v_ = Eigen::VectorXd::Zero(n);
  cos_ = Eigen::VectorXd::Zero(n);
  sin_ = Eigen::VectorXd::Zero(n);
}

bool ActiveSetFactor::factorize(const Eigen::MatrixXd& H) noexcept {
  factorized_ = false;
  q_ = 0;
  const int n = n_;
  double max_diag = 0.0;
  for (int i = 0; i < n; ++i) max_diag = std::max(max_diag, std::abs(H(i, i)));
  const double pivot_min = 1e-14 * max_diag;

  // left-looking cholesky, one column per step (L row-major, rows contiguous):
  // L(j:n, j) = (H(j:n, j) − L(j:n, 0:j)·L(j, 0:j)ᵀ) / L(j, j)
  l_.setZero();
  for (int j = 0; j < n; ++j) {
    kernels::row_dots(&l_(j, 0), n - j, j, n, &l_(j, 0), a_.data());
    const double s = H(j, j) - a_[0];
    if (!(s > pivot_min)) return false;  // also catches nan
    const double ljj = std::sqrt(s);
    l_(j, j) = ljj;
    for (int i = j + 1; i < n; ++i) l_(i, j) = (H(i, j) - a_[i - j]) / ljj;
  }

  // j0 = L^{-T} is upper triangular; row c of L·L^{-1} = e_c gives its column c:
  // j0(0:c, c) = −j0(0:c, 0:c)·L(c, 0:c)ᵀ / L(c, c),  j0(c, c) = 1 / L(c, c)
  j0_.setZero();
  for (int c = 0; c < n; ++c) {
    const double inv = 1.0 / l_(c, c);
    kernels::columns_times(j0_.data(), c, c, n, &l_(c, 0), &j0_(0, c));
    for (int i = 0; i < c; ++i) j0_(i, c) *= -inv;
    j0_(c, c) = inv;
  }
  factorized_ = true;
  reset();
  return true;
}

void ActiveSetFactor::reset() noexcept {
  q_ = 0;
  j_ = j0_;
}

void ActiveSetFactor::set_linear_term(const Eigen::VectorXd& g) noexcept {
  kernels::row_dots(j_.data(), n_, n_, n_, g.data(), w_.data());
}

void ActiveSetFactor::project(const Eigen::Ref<const Eigen::VectorXd>& v,
                              Eigen::Ref<Eigen::VectorXd> d) const noexcept {
  kernels::row_dots(j_.data(), n_, n_, n_, v.data(), d.data());
}

void ActiveSetFactor::project_unit(int j, double sign,
                                   Eigen::Ref<Eigen::VectorXd> d) const noexcept {
  d = sign * j_.row(j).transpose();
}

double ActiveSetFactor::null_space_norm2(const Eigen::VectorXd& d) const noexcept {
  return d.tail(n_ - q_).squaredNorm();
}

void ActiveSetFactor::dual_direction(const Eigen::VectorXd& d, Eigen::VectorXd& r) const noexcept {
  // back substitution R r = d1, column oriented (R is column major)
  const int q = q_;
  for (int i = 0; i < q; ++i) r[i] = d[i];
  double* out = r.data();
  for (int j = q - 1; j >= 0; --j) {
    const double* col = &r_(0, j);
    const double rj = out[j] / col[j];
    out[j] = rj;
    for (int i = 0; i < j; ++i) out[i] -= rj * col[i];  // short: inline beats a kernel call
  }
}

bool ActiveSetFactor::independent(const Eigen::VectorXd& d, double tolerance) const noexcept {
  if (q_ >= n_) return false;
  const double null2 = d.tail(n_ - q_).squaredNorm();
  const double all2 = null2 + d.head(q_).squaredNorm();
  return null2 > tolerance * tolerance * all2 && null2 > 0.0;
}

bool ActiveSetFactor::add(Eigen::VectorXd& d, double tolerance) noexcept {
  if (!independent(d, tolerance)) return false;
  const int n = n_;
  const int q = q_;

  // zero d[q+1..n) from the bottom up; the same rotations then sweep the columns of J
  int count = 0;
  for (int k = n - 1; k > q; --k, ++count) {
    const double b = d[k];
    const double a = d[k - 1];
    double c = 1.0, s = 0.0;
    if (b != 0.0) {
      const double h = pythag(a, b);
      c = a / h;
      s = b / h;
      d[k - 1] = h;
      d[k] = 0.0;
      rotate_pair(w_[k - 1], w_[k], c, s);
    }
    cos_[count] = c;
    sin_[count] = s;
  }
  kernels::rotate_columns(j_.data(), n, n, q, count, cos_.data(), sin_.data(), true);
  for (int i = 0; i <= q; ++i) r_(i, q) = d[i];
  q_ = q + 1;
  return true;
}

void ActiveSetFactor::drop(int k, Eigen::VectorXd* d) noexcept {
  const int n = n_;
  const int q = q_;
  // shift the columns after k one to the left: R becomes upper hessenberg from column k on
  for (int j = k; j < q - 1; ++j) {
    for (int i = 0; i <= j + 1; ++i) r_(i, j) = r_(i, j + 1);
  }
  // restore the triangle with rotations of rows (j, j+1), mirrored on columns of J
  int count = 0;
  for (int j = k; j < q - 1; ++j, ++count) {
    const double a = r_(j, j);
    const double b = r_(j + 1, j);
    double c = 1.0, s = 0.0;
    if (b != 0.0) {
      const double h = pythag(a, b);
      c = a / h;
      s = b / h;
      r_(j, j) = h;
      r_(j + 1, j) = 0.0;
      for (int m = j + 1; m < q - 1; ++m) rotate_pair(r_(j, m), r_(j + 1, m), c, s);
      rotate_pair(w_[j], w_[j + 1], c, s);
      if (d != nullptr) rotate_pair((*d)[j], (*d)[j + 1], c, s);
    }
    cos_[count] = c;
    sin_[count] = s;
  }
  kernels::rotate_columns(j_.data(), n, n, k, count, cos_.data(), sin_.data(), false);
  q_ = q - 1;
}

void ActiveSetFactor::solve_subproblem(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                       Eigen::VectorXd& u) noexcept {
  const int n = n_;
  const int q = q_;
  // a = R^{-T} b by forward substitution (column i of R holds row i of R^T)
  for (int i = 0; i < q; ++i) {
    const double* col = &r_(0, i);
    double sum = b[i];
    for (int m = 0; m < i; ++m) sum -= col[m] * a_[m];
    a_[i] = sum / col[i];
  }
  // x = J1 a - J2 w2
  for (int i = 0; i < q; ++i) v_[i] = a_[i];
  for (int i = q; i < n; ++i) v_[i] = -w_[i];
  kernels::columns_times(j_.data(), n, n, n, v_.data(), x.data());
  // u = R^{-1} (a + w1)
  for (int i = 0; i < q; ++i) a_[i] += w_[i];
  dual_direction(a_, u);
}

}  // namespace mjarm::qp
