// The closed-form 6R solver: the two families' subproblem sequences, branch wrapping and checking.
// Notation: θ are PoE angles (zero at qpos0), g = X_WT·M⁻¹ = e^{[S₁]θ₁}⋯e^{[S₆]θ₆}.

#include "mjarm/ik/analytic_ik.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "ik/paden_kahan.hpp"
#include "ik/validate_pose.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {
namespace {

using detail::Angle;
using detail::rotate_point;
using detail::rotation;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using Angles = std::array<Angle, 6>;  // PoE angles θ with their cosines and sines

constexpr double kTwoPi = 2.0 * std::numbers::pi;
/// Relative slack of a cosine beyond ±1 that still counts as the edge (rounding, not reach).
constexpr double kEdgeSlack = 1e-10;

/// Rotation angle of Rᵀ·R_target [rad], accurate near zero (from its sine and cosine).
double rotation_angle_between(const Matrix3d& R, const Matrix3d& R_target) {
  const Matrix3d D = R.transpose() * R_target;
  const Vector3d s(D(2, 1) - D(1, 2), D(0, 2) - D(2, 0), D(1, 0) - D(0, 1));
  const double sine = 0.5 * s.norm(), cosine = 0.5 * (D.trace() - 1.0);
  // a branch that passes misses by ~1e-15: asin's series to x³ is exact there (error ~x⁵/40),
  // and spares the check an atan2
  if (sine < 1e-4 && cosine > 0.0) return sine + sine * sine * sine / 6.0;
  return std::atan2(sine, cosine);
}

/// @p q moved by a multiple of 2π into [lower, upper] when one fits; unchanged otherwise.
double wrap_into(double q, double lower, double upper) {
  if (q >= lower && q <= upper) return q;
  if (q < lower) {
    const double shifted = q + kTwoPi * std::ceil((lower - q) / kTwoPi);
    return shifted <= upper ? shifted : q;
  }
  const double shifted = q - kTwoPi * std::ceil((q - upper) / kTwoPi);
  return shifted >= lower ? shifted : q;
}

/// Shoulder angles θ₁ placing the wrist point @p P (world) in the plane where joints 2.. can
/// reach it: ω₂·(e₁⁻¹P) = ω₂·wrist (the rotations about the axes parallel to ω₂ keep that
/// component). Returns the count; flags a singular shoulder (the point on axis 1).
int shoulder_angles(const AnalyticIkGeometry& g, const Vector3d& P, double singular_tol,
                    Angle theta[2], bool& singular) {
  const Vector3d& w1 = g.axis[0];
  const Vector3d& w2 = g.axis[1];
  const Vector3d n = P - g.anchor[0];
  const double d = w2.dot(g.wrist - g.anchor[0]);
  double margin = 0.0, scale = 0.0;
  int count = detail::subproblem4(w1, w2, n, d, kEdgeSlack, theta, margin, scale);
  const double floor = singular_tol * g.length;
  singular = scale <= floor || margin <= singular_tol;
  if (scale <= floor) {
    // every θ₁ moves the point by at most `scale`: one representative when the offset fits
    const double offset = d - w1.dot(w2) * w1.dot(n);
    if (std::abs(offset) > floor) return 0;
    theta[0] = count > 0 ? theta[0] : Angle{};
    return 1;
  }
  return singular && count > 0 ? 1 : count;
}

/// The PoE forward kinematics at the angles θ (their cosines and sines: no trigonometric call).
Pose poe_forward(const AnalyticIkGeometry& g, const Angle* theta) {
  Matrix3d R = Matrix3d::Identity();
  Vector3d p = Vector3d::Zero();
  for (int i = 0; i < 6; ++i) {
    const Matrix3d Ri = rotation(g.axis[i], theta[i]);
    p += R * (g.anchor[i] - Ri * g.anchor[i]);
    R = R * Ri;
  }
  Pose X;
  X.R = R * g.M.R;
  X.p = R * g.M.p + p;
  return X;
}

/// A unit vector perpendicular to @p w.
Vector3d perpendicular(const Vector3d& w) {
  const Vector3d trial = std::abs(w.x()) < 0.9 ? Vector3d::UnitX() : Vector3d::UnitY();
  return w.cross(trial).normalized();
}

}  // namespace

AnalyticIk::AnalyticIk(const Chain& chain, const AnalyticIkOptions& options)
    : chain_(chain), options_(options), structure_(analyze_analytic_ik(chain, options)) {
  if (!structure_.solvable) {
    throw Error("analytic IK on chain to '" + chain.frame().name + "': " + structure_.reason);
  }
  lower_ = chain.lower();
  upper_ = chain.upper();
  const auto& w = structure_.geometry.axis;
  const double tol = options_.geometry_tolerance;
  tool_axis_along_shoulder_ = structure_.family == AnalyticIkFamily::parallel_shoulder &&
                              w[5].cross(w[1]).norm() <= tol && std::abs(w[4].dot(w[1])) <= tol;
  // the PoE form must be the model's kinematics: compare with MuJoCo's at a few configurations
  ChainKinematics kin(chain);
  for (int k = 1; k <= 3; ++k) {
    Vector6d q = structure_.geometry.q_reference;
    for (int i = 0; i < 6; ++i) q[i] += 0.37 * k * (i + 1) - 1.1;
    const Pose& mj = kin.update(q);
    const Pose poe = forward(q);
    const double miss =
        std::max((mj.p - poe.p).norm() / structure_.geometry.length, (mj.R - poe.R).norm());
    if (!(miss <= 1e-9)) {
      throw Error("analytic IK on chain to '" + chain.frame().name +
                  "': the model's kinematics is not a product of exponentials of its joint axes "
                  "(mismatch " +
                  number_text(miss) + ")");
    }
  }
}

Pose AnalyticIk::forward(const Vector6d& q) const noexcept {
  Angles theta;
  for (int i = 0; i < 6; ++i) theta[i] = Angle::of(q[i] - structure_.geometry.q_reference[i]);
  return poe_forward(structure_.geometry, theta.data());
}

AnalyticIkSolution AnalyticIk::solve(const Pose& X_WT) const {
  AnalyticIkSolution solution;
  solve(X_WT, solution);
  return solution;
}

void AnalyticIk::solve(const Pose& X_WT, AnalyticIkSolution& solution) const {
  detail::validate_pose(X_WT, "analytic IK target");
  solution.count = 0;
  solution.dropped = 0;
  if (structure_.family == AnalyticIkFamily::spherical_wrist) {
    solve_spherical_wrist(X_WT, solution);
  } else {
    solve_parallel_shoulder(X_WT, solution);
  }
  if (solution.count > 0) {
    solution.status = AnalyticIkStatus::solved;
  } else {
    solution.status = solution.dropped > 0 ? AnalyticIkStatus::no_verified_branch
                                           : AnalyticIkStatus::out_of_reach;
  }
}

void AnalyticIk::add_branch(const Pose& X_WT, const Angle* theta, bool singular,
                            AnalyticIkSolution& solution) const noexcept {
  if (solution.count >= static_cast<int>(solution.branches.size())) return;
  AnalyticIkBranch& b = solution.branches[solution.count];
  for (int i = 0; i < 6; ++i) {
    // the subproblems' angles lie within (−2π, 2π): one turn at most brings them to (−π, π]
    double angle = theta[i].value;
    if (angle > std::numbers::pi) angle -= kTwoPi;
    if (angle <= -std::numbers::pi) angle += kTwoPi;
    b.q[i] = angle + structure_.geometry.q_reference[i];
  }
  if (options_.check_branches) {
    // the angles are atan2 of their cosines and sines (or sums of such angles): the check runs
    // on those, with no trigonometric call
    const Pose X = poe_forward(structure_.geometry, theta);
    b.position_error = (X.p - X_WT.p).norm();
    b.orientation_error = rotation_angle_between(X.R, X_WT.R);
    if (!(b.position_error <= options_.verify_tolerance) ||
        !(b.orientation_error <= options_.verify_tolerance)) {
      ++solution.dropped;
      return;
    }
  } else {
    b.position_error = b.orientation_error = std::numeric_limits<double>::quiet_NaN();
  }
  b.within_limits = true;
  for (int i = 0; i < 6; ++i) {
    b.q[i] = wrap_into(b.q[i], lower_[i], upper_[i]);
    if (!(b.q[i] >= lower_[i] && b.q[i] <= upper_[i])) b.within_limits = false;
  }
  b.singular = singular;
  ++solution.count;
}

void AnalyticIk::solve_spherical_wrist(const Pose& X_WT,
                                       AnalyticIkSolution& solution) const noexcept {
  const AnalyticIkGeometry& g = structure_.geometry;
  const auto& w = g.axis;
  const auto& a = g.anchor;
  const double tol = options_.singularity_tolerance;
  const Matrix3d Rg = X_WT.R * g.M.R.transpose();
  const Vector3d pg = X_WT.p - Rg * g.M.p;
  const Vector3d P = Rg * g.wrist + pg;  // where the wrist centre must go

  Angle shoulder[2];
  bool shoulder_singular = false;
  const int shoulder_count = shoulder_angles(g, P, tol, shoulder, shoulder_singular);
  const Vector3d x6 = perpendicular(w[5]);
  const double k45 = w[3].dot(w[4]);
  const double den45 = 1.0 - k45 * k45;
  const Vector3d n45 = w[3].cross(w[4]);
  Angles theta;
  for (int i1 = 0; i1 < shoulder_count; ++i1) {
    theta[0] = shoulder[i1];
    const Vector3d X = rotate_point(w[0], a[0], -theta[0], P);  // e₁⁻¹·P
    Angle elbow[2];
    double elbow_margin = 0.0;
    int elbow_count = detail::subproblem3(w[2], g.wrist - a[2], a[1] - a[2], (X - a[1]).norm(),
                                          kEdgeSlack, elbow, elbow_margin);
    const bool elbow_singular = elbow_margin <= tol;
    if (elbow_singular && elbow_count > 0) elbow_count = 1;
    for (int i3 = 0; i3 < elbow_count; ++i3) {
      theta[2] = elbow[i3];
      const Vector3d C3 = rotate_point(w[2], a[2], theta[2], g.wrist);
      double m2 = 0.0;
      theta[1] = detail::subproblem1(w[1], C3 - a[1], X - a[1], m2);
      const Matrix3d R123 =
          rotation(w[0], theta[0]) * rotation(w[1], theta[1]) * rotation(w[2], theta[2]);
      const Matrix3d Rh = R123.transpose() * Rg;  // R₄R₅R₆
      // subproblem 2 on directions: c = R₅ω₆ = R₄ᵀt with ω₄·c = ω₄·t and ω₅·c = ω₅·ω₆
      const Vector3d t = Rh * w[5];
      const double alpha = (w[3].dot(t) - k45 * w[4].dot(w[5])) / den45;
      const double beta = (w[4].dot(w[5]) - k45 * w[3].dot(t)) / den45;
      // ‖c − (ω₄·c)ω₄‖ = ‖ω₄ × t‖ = (β² + γ²)·(1 − k²): a cross product keeps a small γ
      // accurate, where 1 − ‖c_plane‖² would lose it to cancellation near θ5 = 0
      const double s4 = w[3].cross(t).squaredNorm();
      const double gamma2 = s4 / den45 - beta * beta;
      const double gamma = std::sqrt(std::max(0.0, gamma2));
      const bool wrist_singular = gamma * std::sqrt(den45) <= tol;
      const int wrist_count = wrist_singular ? 1 : 2;
      for (int i5 = 0; i5 < wrist_count; ++i5) {
        const Vector3d c = alpha * w[3] + beta * w[4] + (i5 == 0 ? gamma : -gamma) * n45;
        double m5 = 0.0, m4 = 0.0, m6 = 0.0;
        theta[4] = detail::subproblem1(w[4], w[5], c, m5);
        theta[3] = detail::subproblem1(w[3], c, t, m4);
        const Matrix3d R6 = (rotation(w[3], theta[3]) * rotation(w[4], theta[4])).transpose() * Rh;
        theta[5] = detail::subproblem1(w[5], x6, R6 * x6, m6);
        const bool singular = shoulder_singular || elbow_singular || wrist_singular || m2 <= tol;
        add_branch(X_WT, theta.data(), singular, solution);
      }
    }
  }
}

void AnalyticIk::solve_parallel_shoulder(const Pose& X_WT,
                                         AnalyticIkSolution& solution) const noexcept {
  const AnalyticIkGeometry& g = structure_.geometry;
  const auto& w = g.axis;
  const auto& a = g.anchor;
  const double tol = options_.singularity_tolerance;
  const Matrix3d Rg = X_WT.R * g.M.R.transpose();
  const Vector3d pg = X_WT.p - Rg * g.M.p;
  const Vector3d W = Rg * g.wrist + pg;  // where the meeting point of axes 5 and 6 must go

  Angle shoulder[2];
  bool shoulder_singular = false;
  const int shoulder_count = shoulder_angles(g, W, tol, shoulder, shoulder_singular);
  const Vector3d x4 = perpendicular(w[3]);
  Angles theta;
  for (int i1 = 0; i1 < shoulder_count; ++i1) {
    theta[0] = shoulder[i1];
    const Matrix3d R1 = rotation(w[0], theta[0]);
    const Matrix3d A = R1.transpose() * Rg;  // = Rot(ω₂, θ₂+θ₃+θ₄)·R₅·R₆
    // rotations about ω₂ keep ω₂·x: ω₂·(R₅ω₆) = ω₂·(Aω₆)
    Angle wrist[2];
    double wrist_margin = 0.0, wrist_scale = 0.0;
    const Vector3d tool_axis = A * w[5];
    int wrist_count = 0;
    if (tool_axis_along_shoulder_) {
      // ω₆ = σω₂ ⟂ ω₅ (the UR's): ω₂·R₅ω₆ = σ cos θ₅ and ‖ω₂ × R₅ω₆‖ = |sin θ₅|; the cross
      // product keeps a small θ₅ accurate where an arccosine would lose half the digits
      const double sine = w[1].cross(tool_axis).norm();
      const double cosine = w[1].dot(tool_axis) * w[1].dot(w[5]);
      wrist[0] = Angle::of_xy(cosine, sine);
      wrist[1] = -wrist[0];
      wrist_margin = sine;
      wrist_count = 2;
    } else {
      wrist_count = detail::subproblem4(w[4], w[5], w[1], w[1].dot(tool_axis), kEdgeSlack, wrist,
                                        wrist_margin, wrist_scale);
    }
    const bool wrist_singular = wrist_margin <= tol;
    if (wrist_singular && wrist_count > 0) wrist_count = 1;
    for (int i5 = 0; i5 < wrist_count; ++i5) {
      theta[4] = wrist[i5];
      const Matrix3d R5 = rotation(w[4], theta[4]);
      // Aᵀω₂ = R₆ᵀR₅ᵀω₂
      double m6 = 0.0;
      theta[5] = detail::subproblem1(w[5], A.transpose() * w[1], R5.transpose() * w[1], m6);
      // axis 4's anchor under e₂e₃e₄ = e₁⁻¹·g·e₆⁻¹·e₅⁻¹
      Vector3d Q4 = rotate_point(w[4], a[4], -theta[4], a[3]);
      Q4 = rotate_point(w[5], a[5], -theta[5], Q4);
      Q4 = rotate_point(w[0], a[0], -theta[0], Rg * Q4 + pg);
      Angle elbow[2];
      double elbow_margin = 0.0;
      int elbow_count = detail::subproblem3(w[2], a[3] - a[2], a[1] - a[2], (Q4 - a[1]).norm(),
                                            kEdgeSlack, elbow, elbow_margin);
      const bool elbow_singular = elbow_margin <= tol;
      if (elbow_singular && elbow_count > 0) elbow_count = 1;
      const Matrix3d R234 = A * (R5 * rotation(w[5], theta[5])).transpose();
      for (int i3 = 0; i3 < elbow_count; ++i3) {
        theta[2] = elbow[i3];
        const Vector3d C4 = rotate_point(w[2], a[2], theta[2], a[3]);
        double m2 = 0.0, m4 = 0.0;
        theta[1] = detail::subproblem1(w[1], C4 - a[1], Q4 - a[1], m2);
        const Matrix3d R4 =
            (rotation(w[1], theta[1]) * rotation(w[2], theta[2])).transpose() * R234;
        theta[3] = detail::subproblem1(w[3], x4, R4 * x4, m4);
        const bool singular =
            shoulder_singular || wrist_singular || elbow_singular || m6 <= tol || m2 <= tol;
        add_branch(X_WT, theta.data(), singular, solution);
      }
    }
  }
}

int AnalyticIk::closest_to(const AnalyticIkSolution& solution,
                           const Eigen::Ref<const Eigen::VectorXd>& seed,
                           Eigen::Ref<Eigen::VectorXd> q, bool within_limits_only) const noexcept {
  int best = -1;
  double best_distance = 0.0;
  Vector6d shifted;
  for (int k = 0; k < solution.count; ++k) {
    const AnalyticIkBranch& b = solution.branches[k];
    if (within_limits_only && !b.within_limits) continue;
    for (int i = 0; i < 6; ++i) {
      // the 2π shift nearest the seed, then its neighbours, keeping one within the limits
      const double nearest = b.q[i] + kTwoPi * std::round((seed[i] - b.q[i]) / kTwoPi);
      shifted[i] = b.q[i];
      double shifted_gap = b.within_limits ? std::abs(b.q[i] - seed[i]) : INFINITY;
      for (const double candidate : {nearest, nearest - kTwoPi, nearest + kTwoPi}) {
        if (candidate < lower_[i] || candidate > upper_[i]) continue;
        const double gap = std::abs(candidate - seed[i]);
        if (gap < shifted_gap) {
          shifted[i] = candidate;
          shifted_gap = gap;
        }
      }
    }
    const double distance = (shifted - seed).squaredNorm();
    if (best < 0 || distance < best_distance) {
      best = k;
      best_distance = distance;
      q = shifted;
    }
  }
  return best;
}

}  // namespace mjarm
