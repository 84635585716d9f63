#include "frame_check.hpp"

#include <cmath>

#include "mjarm/error.hpp"

namespace mjarm::scene_detail {

namespace {

constexpr double kSmallestNorm = 1e-9;

double norm_of(std::span<const double> v) {
  double sum = 0.0;
  for (double x : v) sum += x * x;
  return std::sqrt(sum);
}

}  // namespace

void check_orientation(std::string_view attribute, std::span<const double> values,
                       const std::string& what) {
  const std::string where = what + ": " + std::string(attribute);
  for (double v : values)
    if (!std::isfinite(v)) throw Error(where + " holds a value that is not finite");
  if (attribute == "quat") {
    if (norm_of(values) < kSmallestNorm)
      throw Error(where + " is a zero quaternion; expected (w, x, y, z) of norm 1");
  } else if (attribute == "zaxis") {
    if (norm_of(values) < kSmallestNorm)
      throw Error(where + " is a zero vector; expected the direction of the frame's z axis");
  } else if (attribute == "axisangle") {
    if (norm_of(values.first(3)) < kSmallestNorm)
      throw Error(where + " has a zero axis; expected a rotation axis x y z, then the angle");
  } else if (attribute == "xyaxes") {
    const std::span<const double> x = values.first(3);
    const std::span<const double> y = values.subspan(3, 3);
    const double x_norm = norm_of(x);
    if (x_norm < kSmallestNorm)
      throw Error(where + " has a zero x axis; expected the frame's x axis, then its y axis");
    // y's part across x: zero when y is zero or parallel to x
    const double along = (x[0] * y[0] + x[1] * y[1] + x[2] * y[2]) / x_norm;
    double across = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double c = y[i] - along * x[i] / x_norm;
      across += c * c;
    }
    const double y_norm = norm_of(y);
    if (y_norm < kSmallestNorm || std::sqrt(across) < kSmallestNorm * y_norm)
      throw Error(where +
                  (y_norm < kSmallestNorm ? " has a zero y axis"
                                          : " has its y axis parallel to its x axis") +
                  "; expected two axes at an angle (y is made orthogonal to x)");
  }
}

}  // namespace mjarm::scene_detail
