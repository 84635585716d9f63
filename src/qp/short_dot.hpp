#pragma once
/// @file
/// Inline dot product for the short rows of the small triangular factors in qp/ (no kernel call:
/// below about eight entries the call costs more than the loop).

namespace mjarm::qp::detail {

/// Σ a[k]·b[k] over len entries, two accumulators against the add latency.
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

}  // namespace mjarm::qp::detail
