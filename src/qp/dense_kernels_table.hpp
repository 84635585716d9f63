#pragma once
/// @file
/// Internal to the dense kernels: the table of implementations chosen at program start and
/// helpers shared by the portable and the AVX2/FMA versions (dense_kernels.cpp,
/// dense_kernels_avx2.cpp). Not installed.

namespace mjarm::qp::kernels::detail {

/// One implementation of every kernel (see dense_kernels.hpp for the contracts).
struct Table {
  void (*row_dots)(const double*, int, int, int, const double*, double*) noexcept;
  void (*columns_times)(const double*, int, int, int, const double*, double*) noexcept;
  void (*rotate)(double*, double*, int, double, double) noexcept;
  void (*rotate_columns)(double*, int, int, int, int, const double*, const double*, bool) noexcept;
  void (*reflect_columns)(double*, int, int, int, int, const double*, double) noexcept;
  int (*column_margins)(const double*, int, int, int, const double*, const double*,
                        const double*, const double*, const double*, double*, double*) noexcept;
  int (*select_at_most)(const double*, int, double, int, int*) noexcept;
  void (*indexed_row_dots)(const double*, int, int, const int*, int, const double*,
                           double*) noexcept;
  double (*dot)(const double*, const double*, int) noexcept;
  void (*axpy)(double, const double*, double*, int) noexcept;
  bool avx2;
};

/// The AVX2/FMA implementations, or null if the CPU (or the build target) lacks them.
const Table* avx2_table() noexcept;

// margin of one row and the running smallest key (strict <: ties keep the lower index)
inline void margin_row(int i, double cxi, const double* lo, const double* hi, const double* scale,
                       const double* skip, double* cx, double* margin, double& best,
                       int& best_i) noexcept {
  cx[i] = cxi;
  const double a = cxi - lo[i];
  const double b = hi[i] - cxi;
  const double mi = (b < a ? b : a) * scale[i];
  margin[i] = mi;
  const double key = mi + skip[i];
  if (key < best) {
    best = key;
    best_i = i;
  }
}

}  // namespace mjarm::qp::kernels::detail
