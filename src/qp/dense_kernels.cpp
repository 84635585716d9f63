/// @file
/// The portable versions of the dense kernels and the choice, once at program start, between
/// them and the AVX2/FMA versions (dense_kernels_avx2.cpp).

#include "dense_kernels.hpp"

#include <atomic>

#include "dense_kernels_table.hpp"

namespace mjarm::qp::kernels {

namespace {

using detail::margin_row;
using detail::Table;

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

void reflect_columns_generic(double* A, int rows, int lda, int first, int count, const double* v,
                             double tau) noexcept {
  double* V = A + static_cast<long>(first) * lda;
  constexpr int kBlock = 8;
  for (int i = 0; i < rows; i += kBlock) {
    const int len = rows - i < kBlock ? rows - i : kBlock;
    double y[kBlock] = {};
    for (int k = 0; k < count; ++k) {
      const double* c = V + static_cast<long>(k) * lda + i;
      for (int r = 0; r < len; ++r) y[r] += c[r] * v[k];
    }
    for (int k = 0; k < count; ++k) {
      double* c = V + static_cast<long>(k) * lda + i;
      const double f = tau * v[k];
      for (int r = 0; r < len; ++r) c[r] -= f * y[r];
    }
  }
}

int column_margins_generic(const double* A, int rows, int cols, int lda, const double* x,
                           const double* lo, const double* hi, const double* scale,
                           const double* skip, double* cx, double* margin) noexcept {
  columns_times_generic(A, rows, cols, lda, x, cx);
  double best = __builtin_inf();
  int best_i = -1;
  for (int i = 0; i < rows; ++i) margin_row(i, cx[i], lo, hi, scale, skip, cx, margin, best, best_i);
  return best_i;
}

int select_at_most_generic(const double* v, int len, double t, int max_count,
                           int* idx) noexcept {
  int count = 0;
  for (int i = 0; i < len; ++i) {
    if (v[i] <= t) {
      idx[count++] = i;
      if (count > max_count) break;
    }
  }
  return count;
}

void indexed_row_dots_generic(const double* A, int cols, int lda, const int* idx, int count,
                              const double* x, double* out) noexcept {
  for (int k = 0; k < count; ++k) out[k] = dot_generic(A + static_cast<long>(idx[k]) * lda, x, cols);
}

constexpr Table kPortable{row_dots_generic,        columns_times_generic, rotate_generic,
                          rotate_columns_generic,  reflect_columns_generic, column_margins_generic,
                          select_at_most_generic,  indexed_row_dots_generic,
                          dot_generic,             axpy_generic,          false};

std::atomic<bool> g_force_portable{false};

Table pick() noexcept {
  const Table* avx2 = detail::avx2_table();
  return avx2 != nullptr ? *avx2 : kPortable;
}

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

void reflect_columns(double* A, int rows, int lda, int first, int count, const double* v,
                     double tau) noexcept {
  table().reflect_columns(A, rows, lda, first, count, v, tau);
}

int column_margins(const double* A, int rows, int cols, int lda, const double* x,
                   const double* lo, const double* hi, const double* scale, const double* skip,
                   double* cx, double* margin) noexcept {
  return table().column_margins(A, rows, cols, lda, x, lo, hi, scale, skip, cx, margin);
}

int select_at_most(const double* v, int len, double t, int max_count, int* idx) noexcept {
  return table().select_at_most(v, len, t, max_count, idx);
}

void indexed_row_dots(const double* A, int cols, int lda, const int* idx, int count,
                      const double* x, double* out) noexcept {
  table().indexed_row_dots(A, cols, lda, idx, count, x, out);
}

double dot(const double* a, const double* b, int len) noexcept { return table().dot(a, b, len); }

void axpy(double alpha, const double* x, double* y, int len) noexcept {
  table().axpy(alpha, x, y, len);
}

bool using_avx2() noexcept { return table().avx2; }

void force_portable(bool on) noexcept { g_force_portable.store(on); }

}  // namespace mjarm::qp::kernels
