#include "mjarm/tasks/docking/search.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

SearchPattern search_pattern(std::string_view name) {
  return parse_enum<SearchPattern>(name, "docking search pattern");
}

void check(const DockingSearchOptions& o, const DockingGeometry& g) {
  check_fields(o);
  if (o.contact_force > o.force_limit)
    throw Error("docking search: contact_force must not exceed force_limit (" +
                number_text(o.force_limit) + " N), got " + number_text(o.contact_force) + " N");
  if (o.miss_force > o.force_limit)
    throw Error("docking search: miss_force must not exceed force_limit (" +
                number_text(o.force_limit) + " N), got " + number_text(o.miss_force) + " N");
  // the peg searches on the socket's top face: its rim must stay over the socket
  const double outer = g.bore_radius + g.chamfer + g.wall;
  if (o.max_radius + g.peg_radius > outer) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "docking search: max_radius must keep the peg over the socket's top face (≤ "
                  "%.4g mm: outer radius %.4g mm − peg radius %.4g mm), got %.4g mm",
                  1e3 * (outer - g.peg_radius), 1e3 * outer, 1e3 * g.peg_radius,
                  1e3 * o.max_radius);
    throw Error(text);
  }
}

namespace {

/// Arc length of r = b·θ from 0 to θ, and its derivative.
double spiral_arc(double b, double theta) {
  return 0.5 * b * (theta * std::sqrt(1.0 + theta * theta) + std::asinh(theta));
}

}  // namespace

SearchPath::SearchPath(const DockingSearchOptions& o)
    : options_(o),
      b_(o.pitch / (2.0 * std::numbers::pi)),
      theta_(0.0),
      omega_(o.speed / (o.max_radius / std::numbers::sqrt2)),
      kappa_(0.0) {
  const double side = std::numbers::sqrt2 * o.max_radius;  // the square inside the circle
  const double lines = std::max(1.0, std::ceil(0.5 * std::numbers::pi * side / o.pitch));
  kappa_ = (lines + 1.0) / lines;
}

double SearchPath::time_to_max_radius() const noexcept {
  if (options_.pattern != SearchPattern::spiral) return std::numeric_limits<double>::infinity();
  return spiral_arc(b_, options_.max_radius / b_) / options_.speed;
}

SearchPath::Sample SearchPath::at(double t) noexcept {
  Sample s;
  t = std::max(0.0, t);
  if (options_.pattern == SearchPattern::lissajous) {
    const double R = options_.max_radius / std::numbers::sqrt2;  // corners on the circle
    const double w = omega_, k = kappa_;
    s.offset = {R * std::sin(w * t), R * std::sin(k * w * t)};
    s.velocity = {R * w * std::cos(w * t), R * k * w * std::cos(k * w * t)};
    s.radius = s.offset.norm();
    return s;
  }
  if (options_.pattern != SearchPattern::spiral) return s;
  // θ with arc length v·t: Newton from the last θ (monotone, convex: converges from below)
  const double target = options_.speed * t;
  for (int i = 0; i < 20; ++i) {
    const double step = (spiral_arc(b_, theta_) - target) / (b_ * std::sqrt(1.0 + theta_ * theta_));
    theta_ = std::max(0.0, theta_ - step);
    if (std::abs(step) < 1e-12) break;
  }
  const double c = std::cos(theta_), sn = std::sin(theta_);
  const double r = b_ * theta_;
  const double theta_dot = options_.speed / (b_ * std::sqrt(1.0 + theta_ * theta_));
  s.offset = {r * c, r * sn};
  s.velocity = theta_dot * Eigen::Vector2d(b_ * c - r * sn, b_ * sn + r * c);
  s.radius = r;
  return s;
}

}  // namespace mjarm
