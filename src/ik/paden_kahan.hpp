#pragma once
// Paden–Kahan subproblems on unit axes (Murray, Li & Sastry, "A Mathematical Introduction to
// Robotic Manipulation", §3.2), the building blocks of the closed-form 6R solvers. Each works on
// vectors relative to a point of the axis; each reports how far it is from its degenerate case,
// so that the solver can flag a singular branch instead of trusting a meaningless angle.

#include <Eigen/Core>
#include <cmath>

namespace mjarm::detail {

/// An angle with its cosine and sine. The subproblems find each angle from a cosine and a sine
/// (atan2 of two products, or a sum of such angles), so rotations by it need no trigonometric call.
struct Angle {
  double value = 0.0;  ///< [rad]
  double c = 1.0;      ///< cos(value)
  double s = 0.0;      ///< sin(value)

  static Angle of(double value) { return {value, std::cos(value), std::sin(value)}; }
  /// atan2(y, x) with x, y normalised (0 when both are 0).
  static Angle of_xy(double x, double y) {
    const double r = std::sqrt(x * x + y * y);  // no overflow at a robot's scale; hypot is slower
    if (!(r > 0.0)) return {};
    return {std::atan2(y, x), x / r, y / r};
  }
  Angle operator-() const { return {-value, c, -s}; }
  friend Angle operator+(const Angle& a, const Angle& b) {
    return {a.value + b.value, a.c * b.c - a.s * b.s, a.s * b.c + a.c * b.s};
  }
  friend Angle operator-(const Angle& a, const Angle& b) { return a + (-b); }
};

/// R(ω, θ)·v by Rodrigues' formula.
inline Eigen::Vector3d rotate(const Eigen::Vector3d& w, const Angle& theta,
                              const Eigen::Vector3d& v) {
  return theta.c * v + theta.s * w.cross(v) + (1.0 - theta.c) * w.dot(v) * w;
}

/// The point @p p rotated by θ about the line through @p a along @p w.
inline Eigen::Vector3d rotate_point(const Eigen::Vector3d& w, const Eigen::Vector3d& a,
                                    const Angle& theta, const Eigen::Vector3d& p) {
  return a + rotate(w, theta, p - a);
}

/// R(ω, θ) as a matrix: c·I + s·[ω]× + (1 − c)·ωωᵀ, written out (the solver's inner loop).
inline Eigen::Matrix3d rotation(const Eigen::Vector3d& w, const Angle& theta) {
  const double c = theta.c, s = theta.s, v = 1.0 - c;
  const double x = w.x(), y = w.y(), z = w.z();
  Eigen::Matrix3d R;
  R << c + v * x * x, v * x * y - s * z, v * x * z + s * y,  //
      v * x * y + s * z, c + v * y * y, v * y * z - s * x,   //
      v * x * z - s * y, v * y * z + s * x, c + v * z * z;
  return R;
}

/// Subproblem 1: the θ with R(ω, θ)·u = v (their components along ω are assumed equal).
/// @p measure is the smaller length of their parts perpendicular to ω: near 0, any θ fits.
inline Angle subproblem1(const Eigen::Vector3d& w, const Eigen::Vector3d& u,
                         const Eigen::Vector3d& v, double& measure) {
  const Eigen::Vector3d up = u - w.dot(u) * w;
  const Eigen::Vector3d vp = v - w.dot(v) * w;
  measure = std::sqrt(std::min(up.squaredNorm(), vp.squaredNorm()));
  return Angle::of_xy(up.dot(vp), w.dot(up.cross(vp)));
}

/// Solutions θ of A·cos θ + B·sin θ = C (a cosine equation with a phase); |C| beyond
/// √(A² + B²) by a relative @p slack is clamped (a double root at the edge). Returns the count
/// (0 or 2; the two coincide at the edge); @p margin is the sine of the half-gap between them.
inline int phase_equation(double A, double B, double C, double slack, Angle theta[2],
                          double& margin) {
  const double r = std::sqrt(A * A + B * B);
  margin = 0.0;
  if (!(r > 0.0)) return 0;
  double ratio = C / r;
  if (std::abs(ratio) > 1.0) {
    if (std::abs(ratio) > 1.0 + slack) return 0;
    ratio = std::copysign(1.0, ratio);
  }
  const Angle base{std::atan2(B, A), A / r, B / r};
  margin = std::sqrt(std::max(0.0, (1.0 - ratio) * (1.0 + ratio)));  // exact near ±1
  const Angle gap{std::acos(ratio), ratio, margin};
  theta[0] = base + gap;
  theta[1] = base - gap;
  return 2;
}

/// Subproblem 4 (on a direction): the θ with n·R(ω, θ)·v = d. Returns the count (0 or 2).
/// @p scale is √(A² + B²) (how strongly θ moves the product: 0 when v ∥ ω or n ∥ ω).
inline int subproblem4(const Eigen::Vector3d& w, const Eigen::Vector3d& v, const Eigen::Vector3d& n,
                       double d, double slack, Angle theta[2], double& margin, double& scale) {
  const double wv = w.dot(v), wn = w.dot(n);
  const double A = n.dot(v) - wv * wn;
  const double B = n.dot(w.cross(v));
  scale = std::sqrt(A * A + B * B);
  return phase_equation(A, B, d - wv * wn, slack, theta, margin);
}

/// Subproblem 3: the θ with ‖R(ω, θ)·u − v‖ = δ (u, v relative to a point of the axis).
/// Returns the count (0 or 2); @p margin is the sine of the half-gap (0: stretched/folded).
inline int subproblem3(const Eigen::Vector3d& w, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                       double delta, double slack, Angle theta[2], double& margin) {
  const Eigen::Vector3d up = u - w.dot(u) * w;
  const Eigen::Vector3d vp = v - w.dot(v) * w;
  const double dz = w.dot(u - v);
  const double planar2 = delta * delta - dz * dz;
  const double nu = up.norm(), nv = vp.norm();
  margin = 0.0;
  if (!(nu > 0.0) || !(nv > 0.0)) return 0;
  // R·up makes the angle φ with vp: nu² + nv² − 2·nu·nv·cos φ = planar²
  double cos_gap = (nu * nu + nv * nv - planar2) / (2.0 * nu * nv);
  if (std::abs(cos_gap) > 1.0) {
    if (std::abs(cos_gap) > 1.0 + slack) return 0;
    cos_gap = std::copysign(1.0, cos_gap);
  }
  const Angle base = Angle::of_xy(up.dot(vp), w.dot(up.cross(vp)));
  margin = std::sqrt(std::max(0.0, (1.0 - cos_gap) * (1.0 + cos_gap)));
  const Angle gap{std::acos(cos_gap), cos_gap, margin};
  theta[0] = base + gap;
  theta[1] = base - gap;
  return 2;
}

}  // namespace mjarm::detail
