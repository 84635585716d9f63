#include "mjarm/qp/active_set_factor.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm::qp {

namespace {

// plane rotation [a; b] <- [c a + s b; -s a + c b] applied entrywise to two equal-length arrays
inline void rotate(double* a, double* b, int len, double c, double s) noexcept {
  for (int i = 0; i < len; ++i) {
    const double ai = a[i];
    const double bi = b[i];
    a[i] = c * ai + s * bi;
    b[i] = c * bi - s * ai;
  }
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
  l_ = Eigen::MatrixXd::Zero(n, n);
  j0_ = Eigen::MatrixXd::Identity(n, n);
  j_ = Eigen::MatrixXd::Identity(n, n);
  r_ = Eigen::MatrixXd::Zero(n, n);
  w_ = Eigen::VectorXd::Zero(n);
  a_ = Eigen::VectorXd::Zero(n);
  v_ = Eigen::VectorXd::Zero(n);
}

bool ActiveSetFactor::factorize(const Eigen::MatrixXd& H) noexcept {
  factorized_ = false;
  q_ = 0;
  const int n = n_;
  double max_diag = 0.0;
  for (int i = 0; i < n; ++i) max_diag = std::max(max_diag, std::abs(H(i, i)));
  const double pivot_min = 1e-14 * max_diag;

  // left-looking cholesky, column by column, reading the lower triangle only
  l_.setZero();
  for (int j = 0; j < n; ++j) {
    double s = H(j, j);
    for (int k = 0; k < j; ++k) s -= l_(j, k) * l_(j, k);
    if (!(s > pivot_min)) return false;  // also catches nan
    const double ljj = std::sqrt(s);
    l_(j, j) = ljj;
    for (int i = j + 1; i < n; ++i) l_(i, j) = H(i, j);
    for (int k = 0; k < j; ++k) {
      const double ljk = l_(j, k);
      for (int i = j + 1; i < n; ++i) l_(i, j) -= l_(i, k) * ljk;
    }
    for (int i = j + 1; i < n; ++i) l_(i, j) /= ljj;
  }

  // j0 = L^{-T}: column c of L^{-1} (forward substitution on e_c) is row c of j0
  j0_.setZero();
  for (int c = 0; c < n; ++c) {
    double* x = a_.data();
    for (int i = 0; i < n; ++i) x[i] = 0.0;
    x[c] = 1.0;
    for (int k = c; k < n; ++k) {
      x[k] /= l_(k, k);
      const double xk = x[k];
      for (int i = k + 1; i < n; ++i) x[i] -= l_(i, k) * xk;
    }
    for (int i = c; i < n; ++i) j0_(c, i) = x[i];
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
  w_.noalias() = j_.transpose() * g;
}

void ActiveSetFactor::project(const Eigen::Ref<const Eigen::VectorXd>& v,
                              Eigen::Ref<Eigen::VectorXd> d) const noexcept {
  d.noalias() = j_.transpose() * v;
}

void ActiveSetFactor::project_unit(int j, double sign, Eigen::Ref<Eigen::VectorXd> d) const
    noexcept {
  d = sign * j_.row(j).transpose();
}

double ActiveSetFactor::null_space_norm2(const Eigen::VectorXd& d) const noexcept {
  return d.tail(n_ - q_).squaredNorm();
}

void ActiveSetFactor::dual_direction(const Eigen::VectorXd& d, Eigen::VectorXd& r) const
    noexcept {
  // back substitution R r = d1, column oriented (R is column major)
  const int q = q_;
  for (int i = 0; i < q; ++i) r[i] = d[i];
  for (int j = q - 1; j >= 0; --j) {
    r[j] /= r_(j, j);
    const double rj = r[j];
    const double* col = &r_(0, j);
    for (int i = 0; i < j; ++i) r[i] -= rj * col[i];
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

  // zero d[q+1..n) from the bottom up, rotating the matching columns of J and entries of w
  for (int k = n - 1; k > q; --k) {
    const double b = d[k];
    if (b == 0.0) continue;
    const double a = d[k - 1];
    const double h = std::sqrt(a * a + b * b);
    const double c = a / h;
    const double s = b / h;
    d[k - 1] = h;
    d[k] = 0.0;
    rotate(&j_(0, k - 1), &j_(0, k), n, c, s);
    rotate_pair(w_[k - 1], w_[k], c, s);
  }
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
  for (int j = k; j < q - 1; ++j) {
    const double a = r_(j, j);
    const double b = r_(j + 1, j);
    if (b != 0.0) {
      const double h = std::sqrt(a * a + b * b);
      const double c = a / h;
      const double s = b / h;
      r_(j, j) = h;
      r_(j + 1, j) = 0.0;
      for (int m = j + 1; m < q - 1; ++m) rotate_pair(r_(j, m), r_(j + 1, m), c, s);
      rotate(&j_(0, j), &j_(0, j + 1), n, c, s);
      rotate_pair(w_[j], w_[j + 1], c, s);
      if (d != nullptr) rotate_pair((*d)[j], (*d)[j + 1], c, s);
    }
  }
  q_ = q - 1;
}

void ActiveSetFactor::solve_subproblem(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                       Eigen::VectorXd& u) noexcept {
  const int n = n_;
  const int q = q_;
  // a = R^{-T} b by forward substitution (column i of R holds row i of R^T)
  for (int i = 0; i < q; ++i) {
    const double* col = &r_(0, i);
    double s = b[i];
    for (int m = 0; m < i; ++m) s -= col[m] * a_[m];
    a_[i] = s / r_(i, i);
  }
  // x = J1 a - J2 w2
  for (int i = 0; i < q; ++i) v_[i] = a_[i];
  for (int i = q; i < n; ++i) v_[i] = -w_[i];
  x.noalias() = j_ * v_;
  // u = R^{-1} (a + w1)
  for (int i = 0; i < q; ++i) a_[i] += w_[i];
  dual_direction(a_, u);
}

}  // namespace mjarm::qp
