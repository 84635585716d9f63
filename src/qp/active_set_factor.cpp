#include "mjarm/qp/active_set_factor.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "dense_kernels.hpp"
#include "mjarm/error.hpp"

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

// Σ a[k]·b[k] for the short rows of R: inline (no kernel call), two accumulators against the
// add latency
inline double short_dot(const double* a, const double* b, int len) noexcept {
  double s0 = 0.0, s1 = 0.0;
  int k = 0;
  for (; k + 2 <= len; k += 2) {
    s0 += a[k] * b[k];
    s1 += a[k + 1] * b[k + 1];
  }
  if (k < len) s0 += a[k] * b[k];
  return s0 + s1;
}

// below this length, loops run inline rather than through a kernel call
constexpr int kShort = 8;

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
  h_ = Eigen::VectorXd::Zero(n);
  inv_diag_ = Eigen::VectorXd::Zero(n);
  b_ = Eigen::VectorXd::Zero(n);
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
  // (the strict upper triangle of l_ stays zero from construction)
  for (int j = 0; j < n; ++j) {
    if (j < kShort) {
      for (int i = j; i < n; ++i) v_[i - j] = short_dot(&l_(i, 0), &l_(j, 0), j);
    } else {
      kernels::row_dots(&l_(j, 0), n - j, j, n, &l_(j, 0), v_.data());
    }
    const double s = H(j, j) - v_[0];
    if (!(s > pivot_min)) return false;  // also catches nan
    const double ljj = std::sqrt(s);
    const double inv = 1.0 / ljj;
    l_(j, j) = ljj;
    for (int i = j + 1; i < n; ++i) l_(i, j) = (H(i, j) - v_[i - j]) * inv;
  }

  // j0 = L^{-T} is upper triangular; row c of L·L^{-1} = e_c gives its column c:
  // j0(0:c, c) = −j0(0:c, 0:c)·L(c, 0:c)ᵀ / L(c, c),  j0(c, c) = 1 / L(c, c)
  // (its strict lower triangle stays zero from construction)
  for (int c = 0; c < n; ++c) {
    const double inv = 1.0 / l_(c, c);
    double* out = &j0_(0, c);
    if (c < kShort) {
      for (int i = 0; i < c; ++i) out[i] = 0.0;
      for (int k = 0; k < c; ++k) {
        const double lck = l_(c, k);
        const double* col = &j0_(0, k);
        for (int i = 0; i <= k; ++i) out[i] += col[i] * lck;  // column k is zero below row k
      }
    } else {
      kernels::columns_times(j0_.data(), c, c, n, &l_(c, 0), out);
    }
    for (int i = 0; i < c; ++i) out[i] *= -inv;
    j0_(c, c) = inv;
  }
  factorized_ = true;
  j_changed_ = true;
  reset();
  return true;
}

void ActiveSetFactor::reset() noexcept {
  q_ = 0;
  solved_ = 0;
  if (j_changed_) j_ = j0_;  // a cold start right after factorize() need not copy again
  j_changed_ = false;
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
    const double rj = out[j] * inv_diag_[j];  // no division on the dependency chain
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
  const int len = n - q;  // d₂ = d[q, n)
  if (len > 1) {
    // one Householder reflection P = I − τ·h·hᵀ with P·d₂ = ‖d₂‖·e₁ (so R keeps a positive
    // diagonal), applied to J₂ and w₂: half the flops of a Givens chain and no chain of
    // dependent square roots. h₀ = d₀ − ‖d₂‖ is formed without cancellation (Parlett).
    double* x = d.data() + q;
    double* h = h_.data();
    double sigma = 0.0;  // Σ_{k≥1} x_k²
    for (int k = 1; k < len; ++k) {
      h[k] = x[k];
      sigma += x[k] * x[k];
    }
    const double norm = std::sqrt(x[0] * x[0] + sigma);
    if (sigma > 0.0) {
      h[0] = x[0] <= 0.0 ? x[0] - norm : -sigma / (x[0] + norm);
      const double tau = 2.0 / (h[0] * h[0] + sigma);
      kernels::reflect_columns(j_.data(), n, n, q, len, h, tau);
      double* w2 = w_.data() + q;
      double hw = 0.0;
      for (int k = 0; k < len; ++k) hw += h[k] * w2[k];
      hw *= tau;
      for (int k = 0; k < len; ++k) w2[k] -= hw * h[k];
    } else if (x[0] < 0.0) {
      // d₂ = x₀·e₁ already: only the sign of the new column of J changes
      double* col = j_.data() + static_cast<long>(q) * n;
      for (int i = 0; i < n; ++i) col[i] = -col[i];
      w_[q] = -w_[q];
    }
    d[q] = norm;
    for (int k = q + 1; k < n; ++k) d[k] = 0.0;
  }
  for (int i = 0; i <= q; ++i) r_(i, q) = d[i];
  inv_diag_[q] = 1.0 / d[q];
  q_ = q + 1;
  j_changed_ = true;
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
  for (int j = k; j < q - 1; ++j) {
    inv_diag_[j] = 1.0 / r_(j, j);
    b_[j] = b_[j + 1];
  }
  solved_ = std::min(solved_, k);  // R changed from row k on
  q_ = q - 1;
  j_changed_ = true;
}

void ActiveSetFactor::solve_subproblem(const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                       Eigen::VectorXd& u) noexcept {
  const int n = n_;
  const int q = q_;
  // a = R^{-T} b by forward substitution (column i of R holds row i of R^T); its leading
  // entries are kept from the last call while R and b agree there (after an addition only the
  // new last entry is computed)
  for (int i = 0; i < q; ++i) {
    if (!(b_[i] == b[i])) {
      b_[i] = b[i];
      solved_ = std::min(solved_, i);
    }
  }
  for (int i = solved_; i < q; ++i) {
    const double dot = i < 2 * kShort ? short_dot(&r_(0, i), a_.data(), i)
                                      : kernels::dot(&r_(0, i), a_.data(), i);
    a_[i] = (b_[i] - dot) * inv_diag_[i];
  }
  solved_ = q;
  // x = J1 a - J2 w2
  for (int i = 0; i < q; ++i) v_[i] = a_[i];
  for (int i = q; i < n; ++i) v_[i] = -w_[i];
  kernels::columns_times(j_.data(), n, n, n, v_.data(), x.data());
  // u = R^{-1} (a + w1)
  for (int i = 0; i < q; ++i) v_[i] = a_[i] + w_[i];
  dual_direction(v_, u);
}

}  // namespace mjarm::qp
