#pragma once
// Dense kernels of TaskSpaceDynamics on column-major storage. The sizes are tiny (n ≈ 7, m ≤ 6):
// plain loops beat Eigen's blocked dynamic-size kernels several times over. Each kernel takes its
// sizes as template arguments (kN, kM > 0: compile-time, unrolled and vectorized by the compiler)
// or at run time (kN, kM = 0: the general path, any size).
//
// Triangular factors are stored with the *reciprocal* of their diagonal: L(j, j) holds 1/L_jj, so
// the solves multiply instead of dividing.

#include <cmath>

// Full unrolling of the short loops (with compile-time sizes the whole kernel then becomes
// straight-line code; with run-time sizes it only shortens the loop overhead).
#if defined(__clang__)
#define MJARM_TSK_UNROLL _Pragma("unroll 8")
#elif defined(__GNUC__)
#define MJARM_TSK_UNROLL _Pragma("GCC unroll 8")
#else
#define MJARM_TSK_UNROLL
#endif

namespace mjarm::task_space_kernels {

/// Size n: the compile-time one when given, else the run-time one.
template <int kSize>
constexpr int size_or(int runtime) noexcept {
  return kSize > 0 ? kSize : runtime;
}

/// Lower Cholesky a = L·Lᵀ of the n×n symmetric matrix @p a (its lower triangle, column-major,
/// leading dimension @p lda) into @p l (n×n, leading dimension n; upper triangle not written),
/// with 1/L_jj on the diagonal. False when a pivot is not > 0 (or NaN): not positive definite.
template <int kN>
bool cholesky(const double* a, int lda, double* l, int n_rt) noexcept {
  const int n = size_or<kN>(n_rt);
  MJARM_TSK_UNROLL
  for (int j = 0; j < n; ++j) {
    double* col_j = l + j * n;
    const double* src = a + j * lda;
    MJARM_TSK_UNROLL
    for (int i = j; i < n; ++i) col_j[i] = src[i];
    MJARM_TSK_UNROLL
    for (int k = 0; k < j; ++k) {
      // subtract column k's contribution from column j (rows j..n-1)
      const double* col_k = l + k * n;
      const double l_jk = col_k[j];
      MJARM_TSK_UNROLL
      for (int i = j; i < n; ++i) col_j[i] -= col_k[i] * l_jk;
    }
    if (!(col_j[j] > 0.0)) return false;
    const double inv = 1.0 / std::sqrt(col_j[j]);
    col_j[j] = inv;
    MJARM_TSK_UNROLL
    for (int i = j + 1; i < n; ++i) col_j[i] *= inv;
  }
  return true;
}

/// x ← L⁻¹·x for one vector x (n), L from `cholesky`.
template <int kN>
void forward_solve(const double* l, double* x, int n_rt) noexcept {
  const int n = size_or<kN>(n_rt);
  MJARM_TSK_UNROLL
  for (int k = 0; k < n; ++k) {
    const double* col_k = l + k * n;
    const double xk = x[k] * col_k[k];
    x[k] = xk;
    MJARM_TSK_UNROLL
    for (int i = k + 1; i < n; ++i) x[i] -= col_k[i] * xk;
  }
}

/// x ← L⁻ᵀ·x for one vector x (n), L from `cholesky`.
template <int kN>
void backward_solve(const double* l, double* x, int n_rt) noexcept {
  const int n = size_or<kN>(n_rt);
  MJARM_TSK_UNROLL
  for (int i = n - 1; i >= 0; --i) {
    const double* col_i = l + i * n;
    double s = x[i];
    MJARM_TSK_UNROLL
    for (int k = i + 1; k < n; ++k) s -= col_i[k] * x[k];
    x[i] = s * col_i[i];
  }
}

/// y ← L⁻¹·Jᵀ (n×m, leading dimension n) for the m×n matrix @p J (leading dimension @p ldj),
/// and @p J_copy ← J (m×n, leading dimension m).
template <int kN, int kM>
void solve_transposed(const double* l, const double* J, int ldj, double* y, double* J_copy,
                      int n_rt, int m_rt) noexcept {
  const int n = size_or<kN>(n_rt);
  const int m = size_or<kM>(m_rt);
  MJARM_TSK_UNROLL
  for (int i = 0; i < n; ++i) {
    MJARM_TSK_UNROLL
    for (int c = 0; c < m; ++c) {
      const double v = J[c + i * ldj];
      J_copy[c + i * m] = v;
      y[i + c * n] = v;
    }
  }
  MJARM_TSK_UNROLL
  for (int c = 0; c < m; ++c) forward_solve<kN>(l, y + c * n, n);
}

/// g ← yᵀ·y (m×m, exactly symmetric) for the n×m matrix y.
template <int kN, int kM>
void gram(const double* y, double* g, int n_rt, int m_rt) noexcept {
  const int n = size_or<kN>(n_rt);
  const int m = size_or<kM>(m_rt);
  MJARM_TSK_UNROLL
  for (int a = 0; a < m; ++a) {
    MJARM_TSK_UNROLL
    for (int b = a; b < m; ++b) {
      double s = 0.0;
      MJARM_TSK_UNROLL
      for (int i = 0; i < n; ++i) s += y[i + a * n] * y[i + b * n];
      g[a + b * m] = s;
      g[b + a * m] = s;
    }
  }
}

/// Λ = A⁻¹ for the m×m symmetric positive definite A = R·Rᵀ, from its factor @p r (`cholesky`):
/// X = R⁻¹ (lower triangular, in @p x, m×m) and Λ = Xᵀ·X (exactly symmetric). Returns trace(Λ).
template <int kM>
double inverse_from_factor(const double* r, double* x, double* lambda, int m_rt) noexcept {
  const int m = size_or<kM>(m_rt);
  MJARM_TSK_UNROLL
  for (int c = 0; c < m; ++c) {
    double* col = x + c * m;
    MJARM_TSK_UNROLL
    for (int i = 0; i < c; ++i) col[i] = 0.0;
    col[c] = r[c + c * m];
    MJARM_TSK_UNROLL
    for (int i = c + 1; i < m; ++i) {
      double s = 0.0;
      MJARM_TSK_UNROLL
      for (int k = c; k < i; ++k) s -= r[i + k * m] * col[k];
      col[i] = s * r[i + i * m];
    }
  }
  double trace = 0.0;
  MJARM_TSK_UNROLL
  for (int a = 0; a < m; ++a) {
    MJARM_TSK_UNROLL
    for (int b = a; b < m; ++b) {
      double s = 0.0;
      MJARM_TSK_UNROLL
      for (int k = b; k < m; ++k) s += x[k + a * m] * x[k + b * m];
      lambda[a + b * m] = s;
      lambda[b + a * m] = s;
    }
    trace += lambda[a + a * m];
  }
  return trace;
}

/// out ← in·s (n×m) for the n×m matrix @p in and the m×m matrix @p s.
template <int kN, int kM>
void multiply(const double* in, const double* s, double* out, int n_rt, int m_rt) noexcept {
  const int n = size_or<kN>(n_rt);
  const int m = size_or<kM>(m_rt);
  MJARM_TSK_UNROLL
  for (int c = 0; c < m; ++c) {
    double* o = out + c * n;
    MJARM_TSK_UNROLL
    for (int i = 0; i < n; ++i) o[i] = 0.0;
    MJARM_TSK_UNROLL
    for (int k = 0; k < m; ++k) {
      const double w = s[k + c * m];
      const double* col = in + k * n;
      MJARM_TSK_UNROLL
      for (int i = 0; i < n; ++i) o[i] += col[i] * w;
    }
  }
}

}  // namespace mjarm::task_space_kernels

#undef MJARM_TSK_UNROLL
