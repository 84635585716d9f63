// Structure detection of the closed-form 6R solver: the chain's PoE geometry read off MuJoCo's
// forward kinematics at qpos0, and the tests that place it in a family (or say why not).

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/ik/analytic_ik.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {
namespace {

using Eigen::Vector3d;

/// Sine of the angle between two unit axes (0: parallel or anti-parallel).
double axis_sine(const Vector3d& a, const Vector3d& b) { return a.cross(b).norm(); }

/// Distance of point @p p from the line through @p a along unit @p w.
double point_line_distance(const Vector3d& p, const Vector3d& a, const Vector3d& w) {
  const Vector3d d = p - a;
  return (d - w.dot(d) * w).norm();
}

/// Distance between two non-parallel lines, and the midpoint of their closest points.
double line_line_distance(const Vector3d& a1, const Vector3d& w1, const Vector3d& a2,
                          const Vector3d& w2, Vector3d& midpoint) {
  const Vector3d d = a2 - a1;
  const double b = w1.dot(w2);
  const double den = 1.0 - b * b;
  const double s = (w1.dot(d) - b * w2.dot(d)) / den;
  const double t = (b * w1.dot(d) - w2.dot(d)) / den;
  const Vector3d p1 = a1 + s * w1, p2 = a2 + t * w2;
  midpoint = 0.5 * (p1 + p2);
  return (p1 - p2).norm();
}

std::string joint_pair(int i, int j) {
  return "joints " + std::to_string(i + 1) + " and " + std::to_string(j + 1);
}

/// Empty when the geometry is a spherical-wrist arm; otherwise what fails. Sets the wrist centre.
std::string spherical_wrist_failure(AnalyticIkGeometry& g, double tol) {
  const auto& w = g.axis;
  const auto& a = g.anchor;
  if (axis_sine(w[3], w[4]) <= tol) return joint_pair(3, 4) + " are parallel";
  Vector3d centre;
  const double gap45 = line_line_distance(a[3], w[3], a[4], w[4], centre);
  if (gap45 > tol) return joint_pair(3, 4) + " do not meet (" + number_text(gap45) + " m apart)";
  const double gap6 = point_line_distance(centre, a[5], w[5]);
  if (gap6 > tol) {
    return "axes 4, 5, 6 do not meet at one point (axis 6 passes " + number_text(gap6) +
           " m from the meeting point of axes 4 and 5)";
  }
  if (axis_sine(w[4], w[5]) <= tol) return joint_pair(4, 5) + " are parallel";
  if (axis_sine(w[1], w[2]) > tol) {
    return "spherical wrist, but " + joint_pair(1, 2) +
           " are not parallel (only arms with parallel shoulder and elbow axes are solved)";
  }
  if (axis_sine(w[0], w[1]) <= tol) return joint_pair(0, 1) + " are parallel";
  if (point_line_distance(centre, a[2], w[2]) <= tol) return "the wrist centre lies on axis 3";
  if (point_line_distance(a[2], a[1], w[1]) <= tol) return "axes 2 and 3 coincide";
  g.wrist = centre;
  return {};
}

/// Empty when the geometry is a UR-like arm; otherwise what fails. Sets the 5–6 meeting point.
std::string parallel_shoulder_failure(AnalyticIkGeometry& g, double tol) {
  const auto& w = g.axis;
  const auto& a = g.anchor;
  for (int i : {2, 3}) {
    const double sine = axis_sine(w[1], w[i]);
    if (sine > tol) {
      return "axes 2, 3, 4 are not parallel (" + joint_pair(1, i) + " at sine " +
             number_text(sine) + ")";
    }
  }
  if (axis_sine(w[0], w[1]) <= tol) return "axis 1 is parallel to axes 2, 3, 4";
  if (axis_sine(w[4], w[1]) <= tol) return "axis 5 is parallel to axes 2, 3, 4";
  if (axis_sine(w[4], w[5]) <= tol) return joint_pair(4, 5) + " are parallel";
  Vector3d meet;
  const double gap56 = line_line_distance(a[4], w[4], a[5], w[5], meet);
  if (gap56 > tol) return joint_pair(4, 5) + " do not meet (" + number_text(gap56) + " m apart)";
  if (point_line_distance(a[2], a[1], w[1]) <= tol) return "axes 2 and 3 coincide";
  if (point_line_distance(a[3], a[2], w[2]) <= tol) return "axes 3 and 4 coincide";
  g.wrist = meet;
  return {};
}

}  // namespace

void check(const AnalyticIkOptions& options) { check_fields(options); }

AnalyticIkStructure analyze_analytic_ik(const Chain& chain, const AnalyticIkOptions& options) {
  check(options);
  AnalyticIkStructure s;
  if (chain.size() != 6) {
    s.reason = "the chain has " + std::to_string(chain.size()) +
               " joints; the closed-form solver needs exactly 6 revolute joints";
    return s;
  }
  const mjModel& m = chain.robot().model();
  for (int i = 0; i < 6; ++i) {
    if (m.jnt_type[chain.joint_id(i)] != mjJNT_HINGE) {
      s.reason = "joint " + std::to_string(i + 1) + " ('" + chain.joint_names()[i] +
                 "') is not revolute (a slide joint); the closed-form solver needs 6 hinges";
      return s;
    }
  }
  ChainKinematics kin(chain);
  const Eigen::VectorXd q0 = chain.gather(m.qpos0);
  kin.update(q0);
  AnalyticIkGeometry& g = s.geometry;
  g.M = kin.pose();
  g.q_reference = q0;
  double length = (g.M.p - kin.anchor(0)).norm();
  for (int i = 0; i < 6; ++i) {
    if (!kin.moves_frame(i)) {
      s.reason = "joint " + std::to_string(i + 1) + " ('" + chain.joint_names()[i] +
                 "') does not move the frame";
      return s;
    }
    g.axis[i] = kin.axis(i).normalized();
    g.anchor[i] = kin.anchor(i);
    length = std::max(length, (g.anchor[i] - kin.anchor(0)).norm());
  }
  g.length = std::max(length, 1e-3);

  const double tol = options.geometry_tolerance;
  const std::string spherical = spherical_wrist_failure(g, tol);
  if (spherical.empty()) {
    s.solvable = true;
    s.family = AnalyticIkFamily::spherical_wrist;
    return s;
  }
  const std::string parallel = parallel_shoulder_failure(g, tol);
  if (parallel.empty()) {
    s.solvable = true;
    s.family = AnalyticIkFamily::parallel_shoulder;
    return s;
  }
  s.reason = "no closed-form family fits (tolerance " + number_text(tol) +
             "): not a spherical wrist (" + spherical + "); not a UR-like arm (" + parallel + ")";
  return s;
}

}  // namespace mjarm
