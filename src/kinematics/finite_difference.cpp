#include "mjarm/kinematics/finite_difference.hpp"

#include <charconv>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/lie/se3.hpp"
#include "mjarm/lie/so3.hpp"

namespace mjarm::detail {
namespace {

/// Shortest text that reads back as @p value ("1e-06", "inf", "nan").
std::string fd_number(double value) {
  char text[32];
  const std::to_chars_result r = std::to_chars(text, text + sizeof text, value);
  return std::string(text, r.ptr);
}

}  // namespace

void check_finite_difference_step(double step) {
  if (!(std::isfinite(step) && step > 0.0)) {
    throw Error("finite-difference step must be finite and > 0, got " + fd_number(step));
  }
}

void check_finite_difference_point(const Eigen::Ref<const Eigen::VectorXd>& x) {
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i])) {
      throw Error("finite-difference point x[" + std::to_string(i) + "] must be finite, got " +
                  fd_number(x[i]));
    }
  }
}

void check_finite_difference_shape(Eigen::Index rows, Eigen::Index cols, Eigen::Index n,
                                   Eigen::Index expected_rows, const char* what) {
  const bool rows_ok = expected_rows > 0 ? rows == expected_rows : rows > 0;
  if (!rows_ok || cols != n) {
    throw Error(std::string("finite-difference ") + what + " output is " + std::to_string(rows) +
                "x" + std::to_string(cols) + ", expected " +
                (expected_rows > 0 ? std::to_string(expected_rows) : std::string("m")) + "x" +
                std::to_string(n) + " (one column per entry of x)");
  }
}

void check_finite_difference_spacing(double delta, Eigen::Index i, double xi, double step) {
  if (!(delta > 0.0)) {
    throw Error("finite-difference step " + fd_number(step) + " vanishes at x[" +
                std::to_string(i) + "] = " + fd_number(xi) +
                ": x ± step rounds to x; use a step of about " + fd_number(std::abs(xi) * 6e-6));
  }
}

void check_finite_difference_value_size(Eigen::Index got, Eigen::Index expected) {
  if (got != expected) {
    throw Error("finite-difference function returned " + std::to_string(got) +
                " values where the Jacobian has " + std::to_string(expected) +
                " rows (one per value)");
  }
}

void pose_difference(const Pose& X_plus, const Pose& X_minus, double delta, JacobianFrame frame,
                     Eigen::Ref<Vector6d> column) noexcept {
  switch (frame) {
    case JacobianFrame::world:
      // spatial twist: X₊ ≈ exp(2h·V)·X₋
      column = se3::log(X_plus * X_minus.inverse()) / delta;
      return;
    case JacobianFrame::local:
      // body twist: X₊ ≈ X₋·exp(2h·V)
      column = se3::log(X_minus.inverse() * X_plus) / delta;
      return;
    case JacobianFrame::world_aligned:
      column.head<3>() = (X_plus.p - X_minus.p) / delta;
      column.tail<3>() = so3::log(X_plus.R * X_minus.R.transpose()) / delta;
      return;
  }
}

}  // namespace mjarm::detail
