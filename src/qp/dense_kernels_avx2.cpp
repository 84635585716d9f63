/// @file
/// The AVX2/FMA versions of the dense kernels. Compiled for the baseline instruction set with
/// per-function target attributes, and only called after the CPU reported AVX2 and FMA, so the
/// library still runs on any x86-64. A tail of fewer than 4 entries goes through masked loads
/// and stores.

#include "dense_kernels_table.hpp"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>

namespace mjarm::qp::kernels::detail {

namespace {

#define MJARM_AVX2 __attribute__((target("avx2,fma")))

MJARM_AVX2 inline __m256i tail_mask(int remaining) {
  // lanes [0, remaining) enabled, remaining in 0..4
  return _mm256_cmpgt_epi64(_mm256_set1_epi64x(remaining), _mm256_set_epi64x(3, 2, 1, 0));
}

// full or masked load / store of 4 doubles
template <bool kMasked>
MJARM_AVX2 inline __m256d load(const double* p, __m256i msk) {
  if constexpr (kMasked) return _mm256_maskload_pd(p, msk);
  return _mm256_loadu_pd(p);
}

template <bool kMasked>
MJARM_AVX2 inline void store(double* p, __m256i msk, __m256d val) {
  if constexpr (kMasked) {
    _mm256_maskstore_pd(p, msk, val);
  } else {
    _mm256_storeu_pd(p, val);
  }
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

// the four products of rows r0, r1, r2, r3 with x, in one vector
MJARM_AVX2 inline __m256d four_dots(const double* r0, const double* r1, const double* r2,
                                    const double* r3, int full, bool tail, __m256i m,
                                    const double* x) {
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
  return _mm256_add_pd(lo, hi);
}

// the four products of rows r0 = A, A + lda, A + 2 lda, A + 3 lda with x, in one vector
MJARM_AVX2 inline __m256d four_row_dots(const double* r0, int lda, int full, bool tail,
                                        __m256i m, const double* x) {
  return four_dots(r0, r0 + lda, r0 + 2 * lda, r0 + 3 * lda, full, tail, m, x);
}

// byte shuffles that pack the int32 lanes selected by a 4-bit mask to the front
struct PackTable {
  alignas(16) unsigned char shuffle[16][16];
  constexpr PackTable() : shuffle() {
    for (int mask = 0; mask < 16; ++mask) {
      int out = 0;
      for (int lane = 0; lane < 4; ++lane) {
        if ((mask >> lane) & 1) {
          for (int b = 0; b < 4; ++b) shuffle[mask][4 * out + b] = static_cast<unsigned char>(4 * lane + b);
          ++out;
        }
      }
      for (; out < 4; ++out)
        for (int b = 0; b < 4; ++b) shuffle[mask][4 * out + b] = 0x80;  // zero
    }
  }
};
constexpr PackTable kPack{};

MJARM_AVX2 int select_at_most_avx2(const double* v, int len, double t, int max_count,
                                   int* idx) noexcept {
  // branch-free: each block of 4 stores its selected indices packed (and up to 3 spare lanes,
  // overwritten by the next block or left past the count)
  const __m256d tv = _mm256_set1_pd(t);
  __m128i lanes = _mm_set_epi32(3, 2, 1, 0);
  const __m128i four = _mm_set1_epi32(4);
  int count = 0;
  int i = 0;
  for (; i + 4 <= len; i += 4) {
    const int mask = _mm256_movemask_pd(_mm256_cmp_pd(_mm256_loadu_pd(v + i), tv, _CMP_LE_OQ));
    const __m128i packed = _mm_shuffle_epi8(
        lanes, _mm_load_si128(reinterpret_cast<const __m128i*>(kPack.shuffle[mask])));
    if (count + 4 <= max_count + 1) {
      _mm_storeu_si128(reinterpret_cast<__m128i*>(idx + count), packed);
      count += __builtin_popcount(static_cast<unsigned>(mask));
      if (count > max_count) return count;
    } else {
      // near the cap: one by one, never past idx[max_count]
      alignas(16) int tmp[4];
      _mm_store_si128(reinterpret_cast<__m128i*>(tmp), packed);
      const int found = __builtin_popcount(static_cast<unsigned>(mask));
      for (int k = 0; k < found; ++k) {
        idx[count++] = tmp[k];
        if (count > max_count) return count;
      }
    }
    lanes = _mm_add_epi32(lanes, four);
  }
  for (; i < len; ++i) {
    if (v[i] <= t) {
      idx[count++] = i;
      if (count > max_count) return count;
    }
  }
  return count;
}

MJARM_AVX2 void indexed_row_dots_avx2(const double* A, int cols, int lda, const int* idx,
                                      int count, const double* x, double* out) noexcept {
  const int full = cols & ~3;
  const __m256i m = tail_mask(cols - full);
  const bool tail = full < cols;
  auto row = [&](int k) { return A + static_cast<long>(idx[k]) * lda; };
  int k = 0;
  for (; k + 4 <= count; k += 4) {
    _mm256_storeu_pd(out + k, four_dots(row(k), row(k + 1), row(k + 2), row(k + 3), full, tail,
                                        m, x));
  }
  for (; k < count; ++k) out[k] = dot_avx2(row(k), x, cols);
}

MJARM_AVX2 void row_dots_avx2(const double* A, int rows, int cols, int lda, const double* x,
                              double* out) noexcept {
  const int full = cols & ~3;
  const __m256i m = tail_mask(cols - full);
  const bool tail = full < cols;
  int i = 0;
  for (; i + 4 <= rows; i += 4) {
    _mm256_storeu_pd(out + i, four_row_dots(A + static_cast<long>(i) * lda, lda, full, tail, m, x));
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

// y[0, 16) of a 16-row block: two accumulator sets (even / odd columns) keep two fmas in flight
// per vector; kMasked loads and stores only the lanes of m0..m3
template <bool kMasked>
MJARM_AVX2 inline void columns_block16(const double* A, int cols, int lda, const double* x,
                                       double* y, __m256i m0, __m256i m1, __m256i m2,
                                       __m256i m3) {
  __m256d a0 = _mm256_setzero_pd(), a1 = _mm256_setzero_pd();
  __m256d a2 = _mm256_setzero_pd(), a3 = _mm256_setzero_pd();
  __m256d b0 = _mm256_setzero_pd(), b1 = _mm256_setzero_pd();
  __m256d b2 = _mm256_setzero_pd(), b3 = _mm256_setzero_pd();
  int k = 0;
  for (; k + 2 <= cols; k += 2) {
    const double* c = A + static_cast<long>(k) * lda;
    const double* d = c + lda;
    const __m256d xa = _mm256_set1_pd(x[k]);
    const __m256d xb = _mm256_set1_pd(x[k + 1]);
    a0 = _mm256_fmadd_pd(load<kMasked>(c, m0), xa, a0);
    a1 = _mm256_fmadd_pd(load<kMasked>(c + 4, m1), xa, a1);
    a2 = _mm256_fmadd_pd(load<kMasked>(c + 8, m2), xa, a2);
    a3 = _mm256_fmadd_pd(load<kMasked>(c + 12, m3), xa, a3);
    b0 = _mm256_fmadd_pd(load<kMasked>(d, m0), xb, b0);
    b1 = _mm256_fmadd_pd(load<kMasked>(d + 4, m1), xb, b1);
    b2 = _mm256_fmadd_pd(load<kMasked>(d + 8, m2), xb, b2);
    b3 = _mm256_fmadd_pd(load<kMasked>(d + 12, m3), xb, b3);
  }
  if (k < cols) {
    const double* c = A + static_cast<long>(k) * lda;
    const __m256d xa = _mm256_set1_pd(x[k]);
    a0 = _mm256_fmadd_pd(load<kMasked>(c, m0), xa, a0);
    a1 = _mm256_fmadd_pd(load<kMasked>(c + 4, m1), xa, a1);
    a2 = _mm256_fmadd_pd(load<kMasked>(c + 8, m2), xa, a2);
    a3 = _mm256_fmadd_pd(load<kMasked>(c + 12, m3), xa, a3);
  }
  store<kMasked>(y, m0, _mm256_add_pd(a0, b0));
  store<kMasked>(y + 4, m1, _mm256_add_pd(a1, b1));
  store<kMasked>(y + 8, m2, _mm256_add_pd(a2, b2));
  store<kMasked>(y + 12, m3, _mm256_add_pd(a3, b3));
}

// y[0, 8) of an 8-row block whose lanes beyond m0, m1 are masked off (the tail of a column)
MJARM_AVX2 inline void columns_block8(const double* A, int cols, int lda, const double* x,
                                      double* y, __m256i m0, __m256i m1) {
  __m256d a0 = _mm256_setzero_pd(), a1 = _mm256_setzero_pd();
  __m256d b0 = _mm256_setzero_pd(), b1 = _mm256_setzero_pd();
  int k = 0;
  for (; k + 2 <= cols; k += 2) {
    const double* c = A + static_cast<long>(k) * lda;
    const __m256d xa = _mm256_set1_pd(x[k]);
    const __m256d xb = _mm256_set1_pd(x[k + 1]);
    a0 = _mm256_fmadd_pd(_mm256_maskload_pd(c, m0), xa, a0);
    a1 = _mm256_fmadd_pd(_mm256_maskload_pd(c + 4, m1), xa, a1);
    b0 = _mm256_fmadd_pd(_mm256_maskload_pd(c + lda, m0), xb, b0);
    b1 = _mm256_fmadd_pd(_mm256_maskload_pd(c + lda + 4, m1), xb, b1);
  }
  if (k < cols) {
    const double* c = A + static_cast<long>(k) * lda;
    const __m256d xa = _mm256_set1_pd(x[k]);
    a0 = _mm256_fmadd_pd(_mm256_maskload_pd(c, m0), xa, a0);
    a1 = _mm256_fmadd_pd(_mm256_maskload_pd(c + 4, m1), xa, a1);
  }
  _mm256_maskstore_pd(y, m0, _mm256_add_pd(a0, b0));
  _mm256_maskstore_pd(y + 4, m1, _mm256_add_pd(a1, b1));
}

MJARM_AVX2 void columns_times_avx2(const double* A, int rows, int cols, int lda, const double* x,
                                   double* y) noexcept {
  const __m256i all = _mm256_set1_epi64x(-1);
  int i = 0;
  for (; i + 16 <= rows; i += 16) {
    columns_block16<false>(A + i, cols, lda, x, y + i, all, all, all, all);
  }
  const int left = rows - i;  // 0..15
  auto lanes = [left](int from) { return left - from < 0 ? 0 : (left - from > 4 ? 4 : left - from); };
  if (left > 8) {
    columns_block16<true>(A + i, cols, lda, x, y + i, tail_mask(lanes(0)), tail_mask(lanes(4)),
                          tail_mask(lanes(8)), tail_mask(lanes(12)));
  } else if (left > 0) {
    columns_block8(A + i, cols, lda, x, y + i, tail_mask(lanes(0)), tail_mask(lanes(4)));
  }
}

// margins of rows [i, i + 4) from their products in cx, and the running smallest key per lane
MJARM_AVX2 inline void margins4(int i, const double* lo, const double* hi, const double* scale,
                                const double* skip, const double* cx, double* margin,
                                __m256d row, __m256d& best, __m256d& best_row) {
  const __m256d c = _mm256_loadu_pd(cx + i);
  const __m256d below = _mm256_sub_pd(c, _mm256_loadu_pd(lo + i));
  const __m256d above = _mm256_sub_pd(_mm256_loadu_pd(hi + i), c);
  const __m256d mv = _mm256_mul_pd(_mm256_min_pd(above, below), _mm256_loadu_pd(scale + i));
  _mm256_storeu_pd(margin + i, mv);
  const __m256d key = _mm256_add_pd(mv, _mm256_loadu_pd(skip + i));
  const __m256d less = _mm256_cmp_pd(key, best, _CMP_LT_OQ);  // strict: ties keep the first
  best = _mm256_blendv_pd(best, key, less);
  best_row = _mm256_blendv_pd(best_row, row, less);
}

MJARM_AVX2 int column_margins_avx2(const double* A, int rows, int cols, int lda, const double* x,
                                   const double* lo, const double* hi, const double* scale,
                                   const double* skip, double* cx, double* margin) noexcept {
  columns_times_avx2(A, rows, cols, lda, x, cx);
  // per lane: smallest key so far and its row (as a double)
  __m256d best = _mm256_set1_pd(__builtin_inf());
  __m256d best_row = _mm256_set1_pd(-1.0);
  __m256d row = _mm256_set_pd(3.0, 2.0, 1.0, 0.0);
  const __m256d four = _mm256_set1_pd(4.0);
  int i = 0;
  for (; i + 4 <= rows; i += 4) {
    margins4(i, lo, hi, scale, skip, cx, margin, row, best, best_row);
    row = _mm256_add_pd(row, four);
  }
  double lane[4], lane_row[4];
  _mm256_storeu_pd(lane, best);
  _mm256_storeu_pd(lane_row, best_row);
  double b = __builtin_inf();
  int best_i = -1;
  for (int l = 0; l < 4; ++l) {
    const int r = static_cast<int>(lane_row[l]);
    if (lane[l] < b || (lane[l] == b && r >= 0 && r < best_i)) {
      b = lane[l];
      best_i = r;
    }
  }
  for (; i < rows; ++i) margin_row(i, cx[i], lo, hi, scale, skip, cx, margin, b, best_i);
  return best_i;
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

// y = V·v and V −= tau·y·vᵀ for rows [0, 8) of base (columns lda apart), masked when kMasked
template <bool kMasked>
MJARM_AVX2 inline void reflect_block(double* base, int lda, int count, const double* v,
                                     __m256d tau, __m256i m0, __m256i m1) {
  // two accumulator pairs (even / odd columns) hide the fma latency
  __m256d y0 = _mm256_setzero_pd(), y1 = _mm256_setzero_pd();
  __m256d z0 = _mm256_setzero_pd(), z1 = _mm256_setzero_pd();
  int k = 0;
  for (; k + 2 <= count; k += 2) {
    const double* c = base + static_cast<long>(k) * lda;
    const __m256d va = _mm256_set1_pd(v[k]);
    const __m256d vb = _mm256_set1_pd(v[k + 1]);
    y0 = _mm256_fmadd_pd(load<kMasked>(c, m0), va, y0);
    y1 = _mm256_fmadd_pd(load<kMasked>(c + 4, m1), va, y1);
    z0 = _mm256_fmadd_pd(load<kMasked>(c + lda, m0), vb, z0);
    z1 = _mm256_fmadd_pd(load<kMasked>(c + lda + 4, m1), vb, z1);
  }
  if (k < count) {
    const double* c = base + static_cast<long>(k) * lda;
    const __m256d va = _mm256_set1_pd(v[k]);
    y0 = _mm256_fmadd_pd(load<kMasked>(c, m0), va, y0);
    y1 = _mm256_fmadd_pd(load<kMasked>(c + 4, m1), va, y1);
  }
  y0 = _mm256_mul_pd(_mm256_add_pd(y0, z0), tau);
  y1 = _mm256_mul_pd(_mm256_add_pd(y1, z1), tau);
  for (k = 0; k < count; ++k) {
    double* c = base + static_cast<long>(k) * lda;
    const __m256d vk = _mm256_set1_pd(v[k]);
    store<kMasked>(c, m0, _mm256_fnmadd_pd(y0, vk, load<kMasked>(c, m0)));
    store<kMasked>(c + 4, m1, _mm256_fnmadd_pd(y1, vk, load<kMasked>(c + 4, m1)));
  }
}

MJARM_AVX2 void reflect_columns_avx2(double* A, int rows, int lda, int first, int count,
                                     const double* v, double tau) noexcept {
  if (count <= 0) return;
  double* V = A + static_cast<long>(first) * lda;
  const __m256d tv = _mm256_set1_pd(tau);
  const __m256i all = _mm256_set1_epi64x(-1);
  int i = 0;
  for (; i + 8 <= rows; i += 8) reflect_block<false>(V + i, lda, count, v, tv, all, all);
  if (i < rows) {
    const int left = rows - i;
    reflect_block<true>(V + i, lda, count, v, tv, tail_mask(left < 4 ? left : 4),
                        tail_mask(left > 4 ? left - 4 : 0));
  }
}

#undef MJARM_AVX2

}  // namespace

const Table* avx2_table() noexcept {
  __builtin_cpu_init();
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) return nullptr;
  static constexpr Table kAvx2{row_dots_avx2,       columns_times_avx2,   rotate_avx2,
                               rotate_columns_avx2, reflect_columns_avx2, column_margins_avx2,
                               select_at_most_avx2, indexed_row_dots_avx2, dot_avx2,
                               axpy_avx2,           true};
  return &kAvx2;
}

}  // namespace mjarm::qp::kernels::detail

#else  // not x86-64 with a GNU-compatible compiler: portable kernels only

namespace mjarm::qp::kernels::detail {
const Table* avx2_table() noexcept { return nullptr; }
}  // namespace mjarm::qp::kernels::detail

#endif
