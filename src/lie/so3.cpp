#include "mjarm/lie/so3.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "mjarm/lie/coefficients.hpp"

namespace mjarm::so3 {
namespace {

// unit quaternion (w ≥ 0) of R from Eigen's largest-pivot (Shepperd) conversion, which stays
// accurate at every angle, including θ = π where w → 0
Eigen::Quaterniond canonical_quaternion(const Eigen::Matrix3d& R) noexcept {
  Eigen::Quaterniond q(R);
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  return q;
}

}  // namespace

Eigen::Matrix3d hat(const Eigen::Vector3d& w) noexcept {
  Eigen::Matrix3d W;
  W << 0.0, -w.z(), w.y(),  //
      w.z(), 0.0, -w.x(),   //
      -w.y(), w.x(), 0.0;
  return W;
}

Eigen::Vector3d vee(const Eigen::Matrix3d& W) noexcept {
  return 0.5 * Eigen::Vector3d(W(2, 1) - W(1, 2), W(0, 2) - W(2, 0), W(1, 0) - W(0, 1));
}

Eigen::Matrix3d exp(const Eigen::Vector3d& w) noexcept {
  const lie::SeriesCoefficients k = lie::series_coefficients(w.norm());
  const Eigen::Matrix3d W = hat(w);
  return Eigen::Matrix3d::Identity() + k.sinc * W + k.a * (W * W);
}

Eigen::Vector3d log(const Eigen::Matrix3d& R) noexcept {
  const Eigen::Quaterniond q = canonical_quaternion(R);
  const double n = q.vec().norm();
  const double w = q.w();
  // ω = 2·atan2(n, w)·u with u = q.vec/n; near n = 0 use atan's series to avoid 0/0
  double scale;
  if (n < 1e-6 * w) {
    const double r2 = (n / w) * (n / w);
    scale = (2.0 / w) * (1.0 - r2 / 3.0 + r2 * r2 / 5.0);
  } else {
    scale = 2.0 * std::atan2(n, w) / n;
  }
  return scale * q.vec();
}

double angle(const Eigen::Matrix3d& R) noexcept {
  const Eigen::Quaterniond q = canonical_quaternion(R);
  return 2.0 * std::atan2(q.vec().norm(), q.w());
}

}  // namespace mjarm::so3
