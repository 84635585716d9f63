#include "planning/ompl_goals.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/random.hpp"

namespace mjarm::ompl_detail {

namespace {

bool is_rotation_matrix(const Eigen::Matrix3d& R) {
  return R.allFinite() && (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-6 &&
         R.determinant() > 0.0;
}

void check_tolerance_value(double value, const char* what) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw Error(std::string("OMPL planner: the goal's ") + what +
                " must be positive and finite, got " + number_text(value));
}

/// A rotation within @p angle of the identity, uniform in the ball of rotation vectors.
Eigen::Matrix3d random_small_rotation(Random& rng, double angle) {
  Eigen::Vector3d axis(normal(rng), normal(rng), normal(rng));
  if (axis.norm() < 1e-12) axis = Eigen::Vector3d::UnitZ();
  const double theta = angle * std::cbrt(uniform(rng));
  return Eigen::AngleAxisd(theta, axis.normalized()).toRotationMatrix();
}

/// The n-th IK seed: the start first (its branch is the nearest), then uniform in the limits.
Eigen::VectorXd ik_seed(int index, const Eigen::VectorXd& q_start, const Chain& chain,
                        Random& rng) {
  if (index == 0) return q_start;
  Eigen::VectorXd q(chain.size());
  for (int i = 0; i < chain.size(); ++i) {
    const double lo = std::isfinite(chain.lower()[i]) ? chain.lower()[i] : -std::numbers::pi;
    const double hi = std::isfinite(chain.upper()[i]) ? chain.upper()[i] : std::numbers::pi;
    q[i] = uniform(rng, lo, hi);
  }
  return q;
}

/// Solves IK for the poses @p pose_of(k), k < options.ik_goals, and keeps the distinct
/// collision-free solutions.
template <class PoseOf>
GoalConfigurations solve_pose_goals(PoseOf pose_of, double position_tolerance,
                                    double orientation_tolerance, const Eigen::VectorXd& q_start,
                                    const OmplOptions& options, CollisionChecker& checker,
                                    GlobalIk& ik, Random& rng) {
  GoalConfigurations out;
  GlobalIkOptions ik_options = ik.options();
  ik_options.timeout = std::chrono::duration<double>(options.ik_timeout);
  ik_options.tolerance.bound << Eigen::Vector3d::Constant(position_tolerance),
      Eigen::Vector3d::Constant(orientation_tolerance);
  int converged = 0;
  std::string first_collision;
  for (int k = 0; k < options.ik_goals; ++k) {
    ik_options.seed = splitmix64(options.seed + static_cast<std::uint64_t>(k));
    ik.set_options(ik_options);
    const Pose X_WT = pose_of(k);
    const Eigen::VectorXd seed = ik_seed(k, q_start, checker.chain(), rng);
    const IkResult solved = ik.solve(X_WT, seed);
    if (solved.status != IkStatus::converged) continue;
    ++converged;
    if (!checker.valid(solved.q)) {
      if (first_collision.empty()) first_collision = checker.describe_last();
      continue;
    }
    bool repeated = false;
    for (const Eigen::VectorXd& q : out.states) repeated = repeated || (q - solved.q).norm() < 1e-3;
    if (!repeated) out.states.push_back(solved.q);
  }
  if (!out.states.empty()) return out;
  if (converged == 0) {
    out.status = OmplStatus::goal_unreachable;
    out.message = "no IK solution reaches the goal pose in " + std::to_string(options.ik_goals) +
                  " seeded attempts of " + number_text(options.ik_timeout) +
                  " s (outside the workspace?)";
  } else {
    out.status = OmplStatus::goal_in_collision;
    out.message = "every IK solution of the goal (" + std::to_string(converged) +
                  ") is in collision or outside the ranges, e.g. " + first_collision;
  }
  return out;
}

}  // namespace

GoalConfigurations goal_configurations(const OmplGoal& goal, const Eigen::VectorXd& q_start,
                                       const OmplOptions& options, CollisionChecker& checker,
                                       GlobalIk& ik) {
  const Chain& chain = checker.chain();
  Random rng(splitmix64(options.seed ^ 0x9e3779b97f4a7c15ULL));
  if (const auto* joint = std::get_if<JointGoal>(&goal)) {
    if (joint->q.size() != chain.size())
      throw Error("OMPL planner: the joint goal has " + std::to_string(joint->q.size()) +
                  " entries, the chain " + std::to_string(chain.size()));
    GoalConfigurations out;
    if (checker.valid(joint->q)) {
      out.states.push_back(joint->q);
      return out;
    }
    const bool in_ranges = joint->q.allFinite() && checker.last_limit_joint() < 0;
    out.status = in_ranges ? OmplStatus::goal_in_collision : OmplStatus::invalid_input;
    out.message = "the goal configuration: " + checker.describe_last();
    return out;
  }
  if (const auto* pose = std::get_if<PoseGoal>(&goal)) {
    if (!pose->X_WT.p.allFinite() || !is_rotation_matrix(pose->X_WT.R))
      throw Error("OMPL planner: the goal pose is not finite or its R is not a rotation");
    check_tolerance_value(pose->position_tolerance, "position tolerance [m]");
    check_tolerance_value(pose->orientation_tolerance, "orientation tolerance [rad]");
    return solve_pose_goals([&](int) { return pose->X_WT; }, pose->position_tolerance,
                            pose->orientation_tolerance, q_start, options, checker, ik, rng);
  }
  const auto& region = std::get<PoseRegionGoal>(goal);
  if (!region.lower.allFinite() || !region.upper.allFinite() || !is_rotation_matrix(region.R_WT))
    throw Error("OMPL planner: the goal region is not finite or its R_WT is not a rotation");
  if ((region.lower.array() > region.upper.array()).any())
    throw Error("OMPL planner: the goal region's lower corner is above its upper corner");
  check_tolerance_value(region.orientation_tolerance, "orientation tolerance [rad]");
  // each IK goal its own pose of the region, solved tightly: the solution lies in the region
  const auto pose_of = [&](int) {
    Pose X;
    for (int a = 0; a < 3; ++a) X.p[a] = uniform(rng, region.lower[a], region.upper[a]);
    X.R = region.R_WT *
          random_small_rotation(rng, std::max(0.0, region.orientation_tolerance - 1e-3));
    return X;
  };
  return solve_pose_goals(pose_of, 1e-4, 1e-3, q_start, options, checker, ik, rng);
}

}  // namespace mjarm::ompl_detail
