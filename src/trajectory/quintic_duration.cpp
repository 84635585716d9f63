#include "mjarm/trajectory/quintic_duration.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "mjarm/error.hpp"
#include "polynomial.hpp"

namespace mjarm {

namespace {

using polynomial::Poly;
namespace poly = polynomial;

// relative slack when a candidate duration is verified against the limits
constexpr double kLimitSlack = 1e-9;

// One joint's quintic in τ = t/T: q(τ) = q₀ + A(τ) + T·B(τ) + T²·C(τ) (quintic.hpp formulas with
// h = q₁ − q₀, c_k = b_k/T^k).
struct JointShape {
  Poly A, B, C;
  double v_max = 0.0, a_max = 0.0;
  bool moves = false;
};

JointShape joint_shape(double h, double v0, double v1, double a0, double a1, double v_max,
                       double a_max) {
  JointShape s;
  s.A = poly::scale({0, 0, 0, 10, -15, 6}, h);
  s.B = poly::add(poly::scale({0, 1, 0, -6, 8, -3}, v0), poly::scale({0, 0, 0, -4, 7, -3}, v1));
  s.C = poly::add(poly::scale({0, 0, 0.5, -1.5, 1.5, -0.5}, a0),
                  poly::scale({0, 0, 0, 0.5, -1, 0.5}, a1));
  s.v_max = v_max;
  s.a_max = a_max;
  s.moves = h != 0.0 || v0 != 0.0 || v1 != 0.0 || a0 != 0.0 || a1 != 0.0;
  return s;
}

// max over τ ∈ [0, 1] of |p(τ)|: at the roots of p′ and at the ends
double peak_on_unit(const Poly& p) {
  double peak = std::max(std::abs(poly::evaluate(p, 0.0)), std::abs(poly::evaluate(p, 1.0)));
  for (double x : poly::real_roots(poly::derivative(p), 0.0, 1.0))
    peak = std::max(peak, std::abs(poly::evaluate(p, x)));
  return peak;
}

// d^k/dτ^k of A + T·B + T²·C
Poly shape_derivative(const JointShape& s, double T, int k) {
  Poly p = poly::add(s.A, poly::add(poly::scale(s.B, T), poly::scale(s.C, T * T)));
  for (int i = 0; i < k; ++i) p = poly::derivative(p);
  return p;
}

bool joint_feasible(const JointShape& s, double T) {
  if (!s.moves) return true;
  // q̇ = q′(τ)/T, q̈ = q″(τ)/T²
  return peak_on_unit(shape_derivative(s, T, 1)) <= s.v_max * T * (1.0 + kLimitSlack) &&
         peak_on_unit(shape_derivative(s, T, 2)) <= s.a_max * T * T * (1.0 + kLimitSlack);
}

// A candidate duration and where it came from.
struct Candidate {
  double T;
  Eigen::Index joint;
  bool velocity;
};

// g(τ, T) = g[0](τ) + T·g[1](τ) + T²·g[2](τ) and its τ-derivatives at (τ, T)
double g_at(const std::array<Poly, 3>& g, double tau, double T) {
  return poly::evaluate(g[0], tau) +
         T * (poly::evaluate(g[1], tau) + T * poly::evaluate(g[2], tau));
}

// Newton's method on g = 0, ∂g/∂τ = 0 from (tau, T); returns T or NaN when it leaves the domain
double polish_touch(const std::array<Poly, 3>& g, double tau, double T) {
  std::array<Poly, 3> d1, d2;
  for (int k = 0; k < 3; ++k) {
    d1[k] = poly::derivative(g[k]);
    d2[k] = poly::derivative(d1[k]);
  }
  for (int iteration = 0; iteration < 12; ++iteration) {
    const double f1 = g_at(g, tau, T), f2 = g_at(d1, tau, T);
    const double j11 = f2;
    const double j12 = poly::evaluate(g[1], tau) + 2.0 * T * poly::evaluate(g[2], tau);
    const double j21 = g_at(d2, tau, T);
    const double j22 = poly::evaluate(d1[1], tau) + 2.0 * T * poly::evaluate(d1[2], tau);
    const double det = j11 * j22 - j12 * j21;
    if (det == 0.0 || !std::isfinite(det)) break;
    const double dtau = (f1 * j22 - j12 * f2) / det;
    const double dT = (j11 * f2 - j21 * f1) / det;
    tau -= dtau;
    T -= dT;
    if (!(tau >= 0.0 && tau <= 1.0 && T > 0.0)) return std::nan("");
    if (std::abs(dT) <= 1e-15 * T && std::abs(dtau) <= 1e-15) break;
  }
  return T;
}

// The durations at which an interior extremum of g touches zero (plus near misses), appended.
void touching_durations(std::array<Poly, 3> g, Eigen::Index joint, bool velocity,
                        std::vector<Candidate>& out) {
  // a factor T common to all of g (no displacement): divide it out
  if (poly::is_zero(g[0])) g = {g[1], g[2], Poly{0.0}};
  int degree = poly::is_zero(g[2]) ? 1 : 2;
  if (degree == 1 && poly::is_zero(g[1])) return;  // g does not depend on T: no boundary in T
  std::array<Poly, 3> d;
  for (int k = 0; k < 3; ++k) d[k] = poly::derivative(g[k]);
  // resultant in T of g and ∂g/∂τ: a polynomial in τ that vanishes where they share a root T
  Poly resultant;
  if (degree == 1) {
    resultant = poly::subtract(poly::multiply(g[1], d[0]), poly::multiply(d[1], g[0]));
  } else {
    const Poly& a1 = g[2];
    const Poly& b1 = g[1];
    const Poly& c1 = g[0];
    const Poly& a2 = d[2];
    const Poly& b2 = d[1];
    const Poly& c2 = d[0];
    const Poly ac = poly::subtract(poly::multiply(a1, c2), poly::multiply(a2, c1));
    const Poly ab = poly::subtract(poly::multiply(a1, b2), poly::multiply(a2, b1));
    const Poly bc = poly::subtract(poly::multiply(b1, c2), poly::multiply(b2, c1));
    resultant = poly::subtract(poly::multiply(ac, ac), poly::multiply(ab, bc));
  }
  std::vector<double> taus = poly::real_roots(resultant, 0.0, 1.0);
  if (poly::is_zero(resultant)) {
    // degenerate elimination (never met in the tests): start Newton from a grid instead
    for (int k = 1; k < 64; ++k) taus.push_back(k / 64.0);
  }
  for (double tau : taus) {
    for (double T : poly::quadratic_roots(poly::evaluate(g[0], tau), poly::evaluate(g[1], tau),
                                          degree == 2 ? poly::evaluate(g[2], tau) : 0.0)) {
      if (!(T > 0.0) || !std::isfinite(T)) continue;
      out.push_back({T, joint, velocity});
      const double polished = polish_touch(g, tau, T);
      if (polished > 0.0 && std::isfinite(polished)) out.push_back({polished, joint, velocity});
    }
  }
}

void require_vector(const Eigen::VectorXd& v, Eigen::Index n, const std::string& what,
                    bool positive) {
  if (v.size() != n)
    throw Error("shortest quintic duration: " + what + " must have " + std::to_string(n) +
                " entries, got " + std::to_string(v.size()));
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!std::isfinite(v[i]) || (positive && !(v[i] > 0.0)))
      throw Error("shortest quintic duration: " + what + "[" + std::to_string(i) + "] must be " +
                  (positive ? "positive and finite" : "finite") + ", got " + std::to_string(v[i]));
  }
}

bool beyond(double value, double limit) { return std::abs(value) > limit; }

}  // namespace

const char* to_string(QuinticDurationStatus status) noexcept {
  switch (status) {
    case QuinticDurationStatus::ok:
      return "ok";
    case QuinticDurationStatus::start_beyond_limits:
      return "start beyond limits";
    case QuinticDurationStatus::end_beyond_limits:
      return "end beyond limits";
    case QuinticDurationStatus::infeasible:
      return "infeasible";
  }
  return "unknown";
}

QuinticDuration shortest_quintic_duration(const QuinticTrajectory::State& start,
                                          const QuinticTrajectory::State& end,
                                          const Eigen::VectorXd& max_velocity,
                                          const Eigen::VectorXd& max_acceleration,
                                          double min_duration) {
  const Eigen::Index n = start.q.size();
  if (n == 0) throw Error("shortest quintic duration: no joints (start q is empty)");
  require_vector(start.q, n, "start q", false);
  require_vector(start.qd, n, "start qd", false);
  require_vector(start.qdd, n, "start qdd", false);
  require_vector(end.q, n, "end q", false);
  require_vector(end.qd, n, "end qd", false);
  require_vector(end.qdd, n, "end qdd", false);
  require_vector(max_velocity, n, "max velocity", true);
  require_vector(max_acceleration, n, "max acceleration", true);
  if (!(min_duration >= 0.0) || !std::isfinite(min_duration))
    throw Error("shortest quintic duration: min duration must be ≥ 0 and finite, got " +
                std::to_string(min_duration) + " s");

  QuinticDuration result;
  for (Eigen::Index i = 0; i < n; ++i) {
    // v and a at the ends do not depend on T
    if (beyond(start.qd[i], max_velocity[i]) || beyond(start.qdd[i], max_acceleration[i])) {
      result.status = QuinticDurationStatus::start_beyond_limits;
      result.limiting_joint = i;
      result.velocity_limited = beyond(start.qd[i], max_velocity[i]);
      return result;
    }
    if (beyond(end.qd[i], max_velocity[i]) || beyond(end.qdd[i], max_acceleration[i])) {
      result.status = QuinticDurationStatus::end_beyond_limits;
      result.limiting_joint = i;
      result.velocity_limited = beyond(end.qd[i], max_velocity[i]);
      return result;
    }
  }

  std::vector<JointShape> shapes;
  shapes.reserve(static_cast<std::size_t>(n));
  bool only_accelerations = true;  // no displacement, no boundary velocity: T → 0 stays bounded
  for (Eigen::Index i = 0; i < n; ++i) {
    shapes.push_back(joint_shape(end.q[i] - start.q[i], start.qd[i], end.qd[i], start.qdd[i],
                                 end.qdd[i], max_velocity[i], max_acceleration[i]));
    only_accelerations =
        only_accelerations && end.q[i] == start.q[i] && start.qd[i] == 0.0 && end.qd[i] == 0.0;
  }
  const auto feasible = [&](double T) {
    return std::all_of(shapes.begin(), shapes.end(),
                       [T](const JointShape& s) { return joint_feasible(s, T); });
  };
  if (only_accelerations && min_duration == 0.0) {
    // q̈(τ) = C″(τ) whatever T, q̇ → 0 with T: the infimum is T = 0
    const bool accelerations_fit =
        std::all_of(shapes.begin(), shapes.end(), [](const JointShape& s) {
          return peak_on_unit(poly::derivative(poly::derivative(s.C))) <=
                 s.a_max * (1.0 + kLimitSlack);
        });
    if (accelerations_fit) {
      result.status = QuinticDurationStatus::ok;
      result.duration = 0.0;
      return result;
    }
  }

  std::vector<Candidate> candidates;
  if (min_duration > 0.0) candidates.push_back({min_duration, -1, false});
  for (Eigen::Index i = 0; i < n; ++i) {
    const JointShape& s = shapes[static_cast<std::size_t>(i)];
    if (!s.moves) continue;
    const Poly A1 = poly::derivative(s.A), B1 = poly::derivative(s.B), C1 = poly::derivative(s.C);
    const Poly A2 = poly::derivative(A1), B2 = poly::derivative(B1), C2 = poly::derivative(C1);
    for (const double sign : {1.0, -1.0}) {
      // velocity: A′ + T·(B′ ∓ v_max) + T²·C′; acceleration: A″ + T·B″ + T²·(C″ ∓ a_max)
      touching_durations({A1, poly::add(B1, Poly{-sign * s.v_max}), C1}, i, true, candidates);
      touching_durations({A2, B2, poly::add(C2, Poly{-sign * s.a_max})}, i, false, candidates);
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.T < b.T; });
  for (const Candidate& c : candidates) {
    if (c.T < min_duration || !feasible(c.T)) continue;
    result.status = QuinticDurationStatus::ok;
    result.duration = c.T;
    result.limiting_joint = c.joint;
    result.velocity_limited = c.velocity;
    return result;
  }
  if (min_duration == 0.0 &&
      !std::any_of(shapes.begin(), shapes.end(), [](const JointShape& s) { return s.moves; })) {
    result.status = QuinticDurationStatus::ok;  // nothing moves
    return result;
  }
  result.status = QuinticDurationStatus::infeasible;
  return result;
}

}  // namespace mjarm
