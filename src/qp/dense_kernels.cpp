#include "mjarm/qp/dense_kernels.hpp"

#include <atomic>

#if defined(__x86_64__) && defined(__GNUC__)
#define MJARM_QP_X86 1
#include <immintrin.h>
#endif

namespace mjarm::qp::kernels {

namespace {

// ---- portable versions: independent accumulators for instruction-level parallelism ----

double dot_generic(const double* a, const double* b, int len) noexcept {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  int k = 0;
  for (; k + 4 <= len; k += 4) {
    s0 += a[k] * b[k];
    s1 += a[k + 1] * b[k + 1];
    s2 += a[k + 2] * b[k + 2];
    s3 += a[k + 3] * b[k + 3];
  }
  for (; k < len; ++k) s0 += a[k] * b[k];
  return (s0 + s1) + (s2 + s3);
}

void row_dots_generic(const double* A, int rows, int cols, int lda, const double* x,
                      double* out) noexcept {
  for (int i = 0; i < rows; ++i) out[i] = dot_generic(A + static_cast<long>(i) * lda, x, cols);
}

void axpy_generic(double alpha, const double* x, double* y, int len) noexcept {
  for (int k = 0; k < len; ++k) y[k] += alpha * x[k];
}

void columns_times_generic(const double* A, int rows, int cols, int lda, const double* x,
                           double* y) noexcept {
  for (int i = 0; i < rows; ++i) y[i] = 0.0;
  for (int k = 0; k < cols; ++k) axpy_generic(x[k], A + static_cast<long>(k) * lda, y, rows);
}

void rotate_generic(double* a, double* b, int len, double c, double s) noexcept {
  for (int i = 0; i < len; ++i) {
    const double ai = a[i];
    const double bi = b[i];
    a[i] = c * ai + s * bi;
    b[i] = c * bi - s * ai;
  }
}

void rotate_columns_generic(double* A, int rows, int lda, int first, int count, const double* c,
                            const double* s, bool descending) noexcept {
  for (int t = 0; t < count; ++t) {
    const int k = descending ? first + count - 1 - t : first + t;
    double* a = A + static_cast<long>(k) * lda;
    rotate_generic(a, a + lda, rows, c[t], s[t]);
  }
}

#ifdef MJARM_QP_X86

// ---- avx2 + fma versions; a tail of fewer than 4 entries goes through masked loads/stores ----

#define MJARM_AVX2 __attribute__((target("avx2,fma")))

MJARM_AVX2 inline __m256i tail_mask(int remaining) {
  // lanes [0, remaining) enabled, remaining in 1..3
  return _mm256_cmpgt_epi64(_mm256_set1_epi64x(remaining), _mm256_set_epi64x(3, 2, 1, 0));
}

MJARM_AVX2 inline double hsum(__m256d v) {
  const __m128d lo = _mm256_castpd256_pd128(v);
  const __m128d hi = _mm256_extractf128_pd(v, 1);
  const __m128d s = _mm_add_pd(lo, hi);
  return _mm_cvtsd_f64(_mm_add_sd(s, _mm_unpackhi_pd(s, s)));
}

MJARM_AVX2 double dot_avx2(const double* a, const double* b, int len) noexcept {
  __m256d s0 = _mm256_setzero_pd(), s1 = _mm256_setzero_pd();
  int k = 0;
  for (; k + 8 <= len; k += 8) {
    s0 = _mm256_fmadd_pd(_mm256_loadu_pd(a + k), _mm256_loadu_pd(b + k), s0);
    s1 = _mm256_fmadd_pd(_mm256_loadu_pd(a + k + 4), _mm256_loadu_pd(b + k + 4), s1);
  }
  if (k + 4 <= len) {
    s0 = _mm256_fmadd_pd(_mm256_loadu_pd(a + k), _mm256_loadu_pd(b + k), s0);
    k += 4;
  }
  if (k < len) {
    const __m256i m = tail_mask(len - k);
    s1 = _mm256_fmadd_pd(_mm256_maskload_pd(a + k, m), _mm256_maskload_pd(b + k, m), s1);
  }
  return hsum(_mm256_add_pd(s0, s1));
}

MJARM_AVX2 void row_dots_avx2(const double* A, int rows, int cols, int lda, const double* x,
                              double* out) noexcept {
  const int full = cols & ~3;
  const __m256i m = tail_mask(cols - full > 0 ? cols - full : 1);
  const bool tail = full < cols;
  int i = 0;
  for (; i + 4 <= rows; i += 4) {
    const double* r0 = A + static_cast<long>(i) * lda;
    const double* r1 = r0 + lda;
    const double* r2 = r1 + lda;
    const double* r3 = r2 + lda;
    __m256d a0 = _mm256_setzero_pd(), a1 = _mm256_setzero_pd();
    __m256d a2 = _mm256_setzero_pd(), a3 = _mm256_setzero_pd();
    for (int k = 0; k < full; k += 4) {
      const __m256d xv = _mm256_loadu_pd(x + k);
      a0 = _mm256_fmadd_pd(_mm256_loadu_pd(r0 + k), xv, a0);
      a1 = _mm256_fmadd_pd(_mm256_loadu_pd(r1 + k), xv, a1);
      a2 = _mm256_fmadd_pd(_mm256_loadu_pd(r2 + k), xv, a2);
      a3 = _mm256_fmadd_pd(_mm256_loadu_pd(r3 + k), xv, a3);
    }
    if (tail) {
      const __m256d xv = _mm256_maskload_pd(x + full, m);
      a0 = _mm256_fmadd_pd(_mm256_maskload_pd(r0 + full, m), xv, a0);
      a1 = _mm256_fmadd_pd(_mm256_maskload_pd(r1 + full, m), xv, a1);
      a2 = _mm256_fmadd_pd(_mm256_maskload_pd(r2 + full, m), xv, a2);
      a3 = _mm256_fmadd_pd(_mm256_maskload_pd(r3 + full, m), xv, a3);
    }
    // [a0, a1, a2, a3] horizontal sums in one vector
    const __m256d h01 = _mm256_hadd_pd(a0, a1);
    const __m256d h23 = _mm256_hadd_pd(a2, a3);
    const __m256d lo = _mm256_permute2f128_pd(h01, h23, 0x20);
    const __m256d hi = _mm256_permute2f128_pd(h01, h23, 0x31);
    _mm256_storeu_pd(out + i, _mm256_add_pd(lo, hi));
  }
  for (; i < rows; ++i) out[i] = dot_avx2(A + static_cast<long>(i) * lda, x, cols);
}

MJARM_AVX2 void axpy_avx2(double alpha, const double* x, double* y, int len) noexcept {
  const __m256d av = _mm256_set1_pd(alpha);
  int k = 0;
  for (; k + 4 <= len; k += 4) {
    _mm256_storeu_pd(y + k, _mm256_fmadd_pd(av, _mm256_loadu_pd(x + k), _mm256_loadu_pd(y + k)));
  }
  if (k < len) {
    const __m256i m = tail_mask(len - k);
    const __m256d r =
        _mm256_fmadd_pd(av, _mm256_maskload_pd(x + k, m), _mm256_maskload_pd(y + k, m));
    _mm256_maskstore_pd(y + k, m, r);
  }
}

MJARM_AVX2 void columns_times_avx2(const double* A, int rows, int cols, int lda, const double* x,
                                   double* y) noexcept {
  int i = 0;
  // blocks of 16 rows stay in four registers across all columns
  for (; i + 16 <= rows; i += 16) {
    __m256d y0 = _mm256_setzero_pd(), y1 = _mm256_setzero_pd();
    __m256d y2 = _mm256_setzero_pd(), y3 = _mm256_setzero_pd();
    for (int k = 0; k < cols; ++k) {
      const double* c = A + static_cast<long>(k) * lda + i;
      const __m256d xv = _mm256_set1_pd(x[k]);
      y0 = _mm256_fmadd_pd(_mm256_loadu_pd(c), xv, y0);
      y1 = _mm256_fmadd_pd(_mm256_loadu_pd(c + 4), xv, y1);
      y2 = _mm256_fmadd_pd(_mm256_loadu_pd(c + 8), xv, y2);
      y3 = _mm256_fmadd_pd(_mm256_loadu_pd(c + 12), xv, y3);
    }
    _mm256_storeu_pd(y + i, y0);
    _mm256_storeu_pd(y + i + 4, y1);
    _mm256_storeu_pd(y + i + 8, y2);
    _mm256_storeu_pd(y + i + 12, y3);
  }
  for (; i < rows; i += 4) {
    const int left = rows - i;
    const __m256i m = tail_mask(left < 4 ? left : 4);
    __m256d acc = _mm256_setzero_pd();
    for (int k = 0; k < cols; ++k) {
      const double* c = A + static_cast<long>(k) * lda + i;
      acc = _mm256_fmadd_pd(_mm256_maskload_pd(c, m), _mm256_set1_pd(x[k]), acc);
    }
    _mm256_maskstore_pd(y + i, m, acc);
  }
}

MJARM_AVX2 void rotate_avx2(double* a, double* b, int len, double c, double s) noexcept {
  const __m256d cv = _mm256_set1_pd(c);
  const __m256d sv = _mm256_set1_pd(s);
  int k = 0;
  for (; k + 4 <= len; k += 4) {
    const __m256d av = _mm256_loadu_pd(a + k);
    const __m256d bv = _mm256_loadu_pd(b + k);
    _mm256_storeu_pd(a + k, _mm256_fmadd_pd(cv, av, _mm256_mul_pd(sv, bv)));
    _mm256_storeu_pd(b + k, _mm256_fmsub_pd(cv, bv, _mm256_mul_pd(sv, av)));
  }
  if (k < len) {
    const __m256i m = tail_mask(len - k);
    const __m256d av = _mm256_maskload_pd(a + k, m);
    const __m256d bv = _mm256_maskload_pd(b + k, m);
    _mm256_maskstore_pd(a + k, m, _mm256_fmadd_pd(cv, av, _mm256_mul_pd(sv, bv)));
    _mm256_maskstore_pd(b + k, m, _mm256_fmsub_pd(cv, bv, _mm256_mul_pd(sv, av)));
  }
}

MJARM_AVX2 void rotate_columns_avx2(double* A, int rows, int lda, int first, int count,
                                    const double* c, const double* s, bool descending) noexcept {
  if (count <= 0) return;
  // per block of 4 rows, the column shared by consecutive rotations stays in a register
  for (int i = 0; i < rows; i += 4) {
    const int left = rows - i;
    const __m256i m = tail_mask(left < 4 ? left : 4);
    double* base = A + i;
    if (descending) {
      // pairs (k, k+1) for k = first+count-1 down to first: carry the upper column down
      int k = first + count - 1;
      __m256d carry = _mm256_maskload_pd(base + static_cast<long>(k + 1) * lda, m);
      for (int t = 0; t < count; ++t, --k) {
        const __m256d cv = _mm256_set1_pd(c[t]);
        const __m256d sv = _mm256_set1_pd(s[t]);
        const __m256d a = _mm256_maskload_pd(base + static_cast<long>(k) * lda, m);
        const __m256d b_new = _mm256_fmsub_pd(cv, carry, _mm256_mul_pd(sv, a));
        carry = _mm256_fmadd_pd(cv, a, _mm256_mul_pd(sv, carry));
        _mm256_maskstore_pd(base + static_cast<long>(k + 1) * lda, m, b_new);
      }
      _mm256_maskstore_pd(base + static_cast<long>(first) * lda, m, carry);
    } else {
      // pairs (k, k+1) for k = first up to first+count-1: carry the lower column up
      int k = first;
      __m256d carry = _mm256_maskload_pd(base + static_cast<long>(k) * lda, m);
      for (int t = 0; t < count; ++t, ++k) {
        const __m256d cv = _mm256_set1_pd(c[t]);
        const __m256d sv = _mm256_set1_pd(s[t]);
        const __m256d b = _mm256_maskload_pd(base + static_cast<long>(k + 1) * lda, m);
        const __m256d a_new = _mm256_fmadd_pd(cv, carry, _mm256_mul_pd(sv, b));
        carry = _mm256_fmsub_pd(cv, b, _mm256_mul_pd(sv, carry));
        _mm256_maskstore_pd(base + static_cast<long>(k) * lda, m, a_new);
      }
      _mm256_maskstore_pd(base + static_cast<long>(first + count) * lda, m, carry);
    }
  }
}

#undef MJARM_AVX2
#endif  // MJARM_QP_X86

struct Table {
  void (*row_dots)(const double*, int, int, int, const double*, double*) noexcept;
  void (*columns_times)(const double*, int, int, int, const double*, double*) noexcept;
  void (*rotate)(double*, double*, int, double, double) noexcept;
  void (*rotate_columns)(double*, int, int, int, int, const double*, const double*, bool) noexcept;
  double (*dot)(const double*, const double*, int) noexcept;
  void (*axpy)(double, const double*, double*, int) noexcept;
  bool avx2;
};

constexpr Table kPortable{
    row_dots_generic, columns_times_generic, rotate_generic, rotate_columns_generic,
    dot_generic,      axpy_generic,          false};

Table pick() noexcept {
#ifdef MJARM_QP_X86
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
    return {row_dots_avx2, columns_times_avx2, rotate_avx2, rotate_columns_avx2,
            dot_avx2,      axpy_avx2,          true};
  }
#endif
  return kPortable;
}

std::atomic<bool> g_force_portable{false};

const Table& table() noexcept {
  static const Table best = pick();
  return g_force_portable.load(std::memory_order_relaxed) ? kPortable : best;
}

}  // namespace

void row_dots(const double* A, int rows, int cols, int lda, const double* x, double* out) noexcept {
  table().row_dots(A, rows, cols, lda, x, out);
}

void columns_times(const double* A, int rows, int cols, int lda, const double* x,
                   double* y) noexcept {
  table().columns_times(A, rows, cols, lda, x, y);
}

void rotate(double* a, double* b, int len, double c, double s) noexcept {
  table().rotate(a, b, len, c, s);
}

void rotate_columns(double* A, int rows, int lda, int first, int count, const double* c,
                    const double* s, bool descending) noexcept {
  table().rotate_columns(A, rows, lda, first, count, c, s, descending);
}

double dot(const double* a, const double* b, int len) noexcept { return table().dot(a, b, len); }

void axpy(double alpha, const double* x, double* y, int len) noexcept {
  table().axpy(alpha, x, y, len);
}

bool using_avx2() noexcept { return table().avx2; }

void force_portable(bool on) noexcept { g_force_portable.store(on); }

}  // namespace mjarm::qp::kernels
