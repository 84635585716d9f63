#include "mjarm/trajectory/quintic_duration.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "polynomial.hpp"

namespace mjarm {

namespace {

namespace qpoly = polynomial;

// relative slack when a candidate duration is verified against the limits
constexpr double kQuinticLimitSlack = 1e-9;

// One joint's quintic in τ = t/T: q(τ) = q₀ + A(τ) + T·B(τ) + T²·C(τ) (quintic.hpp formulas with
// h = q₁ − q₀, c_k = b_k/T^k).
struct JointShape {
  qpoly::Poly A, B, C;
  double v_max = 0.0, a_max = 0.0;
  bool moves = false;
};

JointShape joint_shape(double h, double v0, double v1, double a0, double a1, double v_max,
                       double a_max) {
  JointShape s;
  s.A = qpoly::scale({0, 0, 0, 10, -15, 6}, h);
  s.B = qpoly::add(qpoly::scale({0, 1, 0, -6, 8, -3}, v0), qpoly::scale({0, 0, 0, -4, 7, -3}, v1));
  s.C = qpoly::add(qpoly::scale({0, 0, 0.5, -1.5, 1.5, -0.5}, a0),
                   qpoly::scale({0, 0, 0, 0.5, -1, 0.5}, a1));
  s.v_max = v_max;
  s.a_max = a_max;
  s.moves = h != 0.0 || v0 != 0.0 || v1 != 0.0 || a0 != 0.0 || a1 != 0.0;
  return s;
}

// max over τ ∈ [0, 1] of |p(τ)|: at the roots of p′ and at the ends
double peak_on_unit(const qpoly::Poly& p) {
  double peak = std::max(std::abs(qpoly::evaluate(p, 0.0)), std::abs(qpoly::evaluate(p, 1.0)));
  for (double x : qpoly::real_roots(qpoly::derivative(p), 0.0, 1.0))
    peak = std::max(peak, std::abs(qpoly::evaluate(p, x)));
  return peak;
}

// d^k/dτ^k of A + T·B + T²·C
qpoly::Poly shape_derivative(const JointShape& s, double T, int k) {
  qpoly::Poly p = qpoly::add(s.A, qpoly::add(qpoly::scale(s.B, T), qpoly::scale(s.C, T * T)));
  for (int i = 0; i < k; ++i) p = qpoly::derivative(p);
  return p;
}

bool joint_feasible(const JointShape& s, double T) {
  if (!s.moves) return true;
  // q̇ = q′(τ)/T, q̈ = q″(τ)/T²
  return peak_on_unit(shape_derivative(s, T, 1)) <= s.v_max * T * (1.0 + kQuinticLimitSlack) &&
         peak_on_unit(shape_derivative(s, T, 2)) <= s.a_max * T * T * (1.0 + kQuinticLimitSlack);
}

// A candidate duration and where it came from.
struct DurationCandidate {
  double T;
  Eigen::Index joint;
  bool velocity;
};

// g(τ, T) = g[0](τ) + T·g[1](τ) + T²·g[2](τ) and its τ-derivatives at (τ, T)
double g_at(const std::array<qpoly::Poly, 3>& g, double tau, double T) {
  return qpoly::evaluate(g[0], tau) +
         T * (qpoly::evaluate(g[1], tau) + T * qpoly::evaluate(g[2], tau));
}

// Newton's method on g = 0, ∂g/∂τ = 0 from (tau, T); returns T or NaN when it leaves the domain
double polish_touch(const std::array<qpoly::Poly, 3>& g, double tau, double T) {
  std::array<qpoly::Poly, 3> d1, d2;
  for (int k = 0; k < 3; ++k) {
    d1[k] = qpoly::derivative(g[k]);
    d2[k] = qpoly::derivative(d1[k]);
  }
  for (int iteration = 0; iteration < 12; ++iteration) {
    const double f1 = g_at(g, tau, T), f2 = g_at(d1, tau, T);
    const double j11 = f2;
    const double j12 = qpoly::evaluate(g[1], tau) + 2.0 * T * qpoly::evaluate(g[2], tau);
    const double j21 = g_at(d2, tau, T);
    const double j22 = qpoly::evaluate(d1[1], tau) + 2.0 * T * qpoly::evaluate(d1[2], tau);
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

// A boundary value at its limit makes g vanish at that end of [0, 1] whatever T; feasibility then
// changes where the first τ-derivative of g there that is not identically zero in T changes
// sign. Appends the positive roots in T of those derivatives (of every order up to the first
// clearly non-zero one: extra candidates are harmless).
void endpoint_durations(const std::array<qpoly::Poly, 3>& g, Eigen::Index joint, bool velocity,
                        std::vector<DurationCandidate>& out) {
  for (const double tau : {0.0, 1.0}) {
    std::array<qpoly::Poly, 3> d = g;
    for (int order = 1; order <= 5; ++order) {
      double size = 0.0;
      std::array<double, 3> c{};
      for (std::size_t k = 0; k < 3; ++k) {
        d[k] = qpoly::derivative(d[k]);
        c[k] = qpoly::evaluate(d[k], tau);
        for (double coefficient : d[k]) size += std::abs(coefficient);
      }
      for (double T : qpoly::quadratic_roots(c[0], c[1], c[2]))
        if (T > 0.0 && std::isfinite(T)) out.push_back({T, joint, velocity});
      const bool vanishes = std::abs(c[0]) + std::abs(c[1]) + std::abs(c[2]) <= 1e-12 * size;
      if (!vanishes) break;
    }
  }
}

// The durations at which an interior extremum of g touches zero (plus near misses), appended.
void touching_durations(std::array<qpoly::Poly, 3> g, Eigen::Index joint, bool velocity,
                        std::vector<DurationCandidate>& out) {
  // a factor T common to all of g (no displacement): divide it out
  if (qpoly::is_zero(g[0])) g = {g[1], g[2], qpoly::Poly{0.0}};
  endpoint_durations(g, joint, velocity, out);
  int degree = qpoly::is_zero(g[2]) ? 1 : 2;
  if (degree == 1 && qpoly::is_zero(g[1])) return;  // g does not depend on T: no boundary in T
  std::array<qpoly::Poly, 3> d;
  for (int k = 0; k < 3; ++k) d[k] = qpoly::derivative(g[k]);
  // resultant in T of g and ∂g/∂τ: a polynomial in τ that vanishes where they share a root T
  qpoly::Poly resultant;
  if (degree == 1) {
    resultant = qpoly::subtract(qpoly::multiply(g[1], d[0]), qpoly::multiply(d[1], g[0]));
  } else {
    const qpoly::Poly& a1 = g[2];
    const qpoly::Poly& b1 = g[1];
    const qpoly::Poly& c1 = g[0];
    const qpoly::Poly& a2 = d[2];
    const qpoly::Poly& b2 = d[1];
    const qpoly::Poly& c2 = d[0];
    const qpoly::Poly ac = qpoly::subtract(qpoly::multiply(a1, c2), qpoly::multiply(a2, c1));
    const qpoly::Poly ab = qpoly::subtract(qpoly::multiply(a1, b2), qpoly::multiply(a2, b1));
    const qpoly::Poly bc = qpoly::subtract(qpoly::multiply(b1, c2), qpoly::multiply(b2, c1));
    resultant = qpoly::subtract(qpoly::multiply(ac, ac), qpoly::multiply(ab, bc));
  }
  std::vector<double> taus = qpoly::real_roots(resultant, 0.0, 1.0);
  if (qpoly::is_zero(resultant)) {
    // degenerate elimination (never met in the tests): start Newton from a grid instead
    for (int k = 1; k < 64; ++k) taus.push_back(k / 64.0);
  }
  for (double tau : taus) {
    for (double T : qpoly::quadratic_roots(qpoly::evaluate(g[0], tau), qpoly::evaluate(g[1], tau),
                                           degree == 2 ? qpoly::evaluate(g[2], tau) : 0.0)) {
      if (!(T > 0.0) || !std::isfinite(T)) continue;
      out.push_back({T, joint, velocity});
      const double polished = polish_touch(g, tau, T);
      if (polished > 0.0 && std::isfinite(polished)) out.push_back({polished, joint, velocity});
    }
  }
}

void require_duration_input(const Eigen::VectorXd& v, Eigen::Index n, const std::string& what,
                            bool positive) {
  if (v.size() != n)
    throw Error("shortest quintic duration: " + what + " must have " + std::to_string(n) +
                " entries, got " + std::to_string(v.size()));
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!std::isfinite(v[i]) || (positive && !(v[i] > 0.0)))
      throw Error("shortest quintic duration: " + what + "[" + std::to_string(i) + "] must be " +
                  (positive ? "positive and finite" : "finite") + ", got " + number_text(v[i]));
  }
}

bool beyond_limit(double value, double limit) { return std::abs(value) > limit; }

}  // namespace

QuinticDuration shortest_quintic_duration(const QuinticTrajectory::State& start,
                                          const QuinticTrajectory::State& end,
                                          const Eigen::VectorXd& max_velocity,
                                          const Eigen::VectorXd& max_acceleration,
                                          double min_duration) {
  const Eigen::Index n = start.q.size();
  if (n == 0) throw Error("shortest quintic duration: no joints (start q is empty)");
  require_duration_input(start.q, n, "start q", false);
  require_duration_input(start.qd, n, "start qd", false);
  require_duration_input(start.qdd, n, "start qdd", false);
  require_duration_input(end.q, n, "end q", false);
  require_duration_input(end.qd, n, "end qd", false);
  require_duration_input(end.qdd, n, "end qdd", false);
  require_duration_input(max_velocity, n, "max velocity", true);
  require_duration_input(max_acceleration, n, "max acceleration", true);
  if (!(min_duration >= 0.0) || !std::isfinite(min_duration))
    throw Error("shortest quintic duration: min duration must be ≥ 0 and finite, got " +
                number_text(min_duration) + " s");

  QuinticDuration result;
  for (Eigen::Index i = 0; i < n; ++i) {
    // v and a at the ends do not depend on T
    if (beyond_limit(start.qd[i], max_velocity[i]) ||
        beyond_limit(start.qdd[i], max_acceleration[i])) {
      result.status = QuinticDurationStatus::start_beyond_limits;
      result.limiting_joint = i;
      result.velocity_limited = beyond_limit(start.qd[i], max_velocity[i]);
      return result;
    }
    if (beyond_limit(end.qd[i], max_velocity[i]) || beyond_limit(end.qdd[i], max_acceleration[i])) {
      result.status = QuinticDurationStatus::end_beyond_limits;
      result.limiting_joint = i;
      result.velocity_limited = beyond_limit(end.qd[i], max_velocity[i]);
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
          return peak_on_unit(qpoly::derivative(qpoly::derivative(s.C))) <=
                 s.a_max * (1.0 + kQuinticLimitSlack);
        });
    if (accelerations_fit) {
      result.status = QuinticDurationStatus::ok;
      result.duration = 0.0;
      return result;
    }
  }

  std::vector<DurationCandidate> candidates;
  if (min_duration > 0.0) candidates.push_back({min_duration, -1, false});
  for (Eigen::Index i = 0; i < n; ++i) {
    const JointShape& s = shapes[static_cast<std::size_t>(i)];
    if (!s.moves) continue;
    const qpoly::Poly A1 = qpoly::derivative(s.A), B1 = qpoly::derivative(s.B),
                      C1 = qpoly::derivative(s.C);
    const qpoly::Poly A2 = qpoly::derivative(A1), B2 = qpoly::derivative(B1),
                      C2 = qpoly::derivative(C1);
    for (const double sign : {1.0, -1.0}) {
      // velocity: A′ + T·(B′ ∓ v_max) + T²·C′; acceleration: A″ + T·B″ + T²·(C″ ∓ a_max)
      touching_durations({A1, qpoly::add(B1, qpoly::Poly{-sign * s.v_max}), C1}, i, true,
                         candidates);
      touching_durations({A2, B2, qpoly::add(C2, qpoly::Poly{-sign * s.a_max})}, i, false,
                         candidates);
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const DurationCandidate& a, const DurationCandidate& b) { return a.T < b.T; });
  for (const DurationCandidate& c : candidates) {
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
