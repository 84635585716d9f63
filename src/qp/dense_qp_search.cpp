/// @file
/// The search of DenseQp for the most violated constraint.
///
/// Dense rows cost n multiply-adds each; the search keeps their products C·x̂ at a reference
/// point x̂ and the scaled margins there (distance to the nearer limit over the row norm). Since
/// |c·x − c·x̂|/‖c‖ ≤ ‖x − x̂‖, a row whose margin at x̂ exceeds ‖x − x̂‖ holds at x and is
/// skipped exactly; when the others are many, one fused pass over C (products, margins and the
/// most violated row) moves the reference to x instead.

#include <algorithm>
#include <cmath>
#include <limits>

#include "dense_kernels.hpp"
#include "mjarm/qp/dense_qp.hpp"

namespace mjarm::qp {

int DenseQp::refresh_reference() noexcept {
  // C·x, the margins and the most violated free row in one pass over C
  // (column-major copy of C: no horizontal sums, whole vectors of rows at a time)
  const int worst = kernels::column_margins(c_cols_.data(), mi_, n_, mi_, x_.data(), l_.data(),
                                            u_.data(), c_scale_.data(), row_skip_.data(),
                                            cx_ref_.data(), margin_ref_.data());
  x_ref_ = x_;
  ref_valid_ = true;
  margins_stale_ = false;
  return worst;
}

void DenseQp::update_margins() noexcept {
  // scaled distance of C·x_ref_ to the nearer limit (negative when violated, +inf if none)
  margin_ref_ = (cx_ref_ - l_).cwiseMin(u_ - cx_ref_).cwiseProduct(c_scale_);
  margins_stale_ = false;
}

int DenseQp::most_violated(double& slack_p) noexcept {
  const double tol = settings_.primal_tolerance;
  int p = -1;
  double worst = -tol;  // scaled violation of the best candidate so far

  // simple bounds first: exact at O(1) each
  const int bound0 = me_ + 2 * mi_;
  for (int j = 0; j < n_; ++j) {
    if (state_[mi_ + j] != 0) continue;
    const double lo = x_[j] - lb_[j];
    const double hi = ub_[j] - x_[j];
    if (lo < worst) {
      worst = lo;
      slack_p = lo;
      p = bound0 + 2 * j;
    }
    if (hi < worst) {
      worst = hi;
      slack_p = hi;
      p = bound0 + 2 * j + 1;
    }
  }
  if (mi_ == 0) return p;

  auto consider_row = [&](int i, double cx) {
    const double lo = cx - l_[i];
    const double hi = u_[i] - cx;
    if (lo * c_scale_[i] < worst) {
      worst = lo * c_scale_[i];
      slack_p = lo;
      p = me_ + 2 * i;
    }
    if (hi * c_scale_[i] < worst) {
      worst = hi * c_scale_[i];
      slack_p = hi;
      p = me_ + 2 * i + 1;
    }
  };
  if (ref_valid_ && margins_stale_) update_margins();  // the limits changed since
  const double delta = ref_valid_ ? (x_ - x_ref_).norm() : std::numeric_limits<double>::infinity();
  if (delta == 0.0) {
    // at the reference point: the margins are exact
    for (int i = 0; i < mi_; ++i) {
      if (state_[i] == 0 && margin_ref_[i] < worst) consider_row(i, cx_ref_[i]);
    }
    return p;
  }
  if (ref_valid_) {
    // rows that may be violated: margin at x_ref_ ≤ ‖x − x_ref_‖ (+ tol for rounding); the
    // selection stops once so many qualify that one full pass over C is cheaper
    const int cap = mi_ / 4;
    const int count =
        kernels::select_at_most(margin_ref_.data(), mi_, delta + tol, cap, near_.data());
    if (count <= cap) {
      int free = 0;
      for (int k = 0; k < count; ++k) {
        if (state_[near_[k]] == 0) near_[free++] = near_[k];
      }
      kernels::indexed_row_dots(c_.data(), n_, n_, near_.data(), free, x_.data(), near_cx_.data());
      for (int k = 0; k < free; ++k) consider_row(near_[k], near_cx_[k]);
      return p;
    }
  }
  const int i = refresh_reference();
  if (i >= 0 && margin_ref_[i] < worst) consider_row(i, cx_ref_[i]);
  return p;
}

}  // namespace mjarm::qp
