#include "mjarm/planning/cartesian_path.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "mjarm/error.hpp"
#include "mjarm/ik/targets.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/trajectory/se3_interpolation.hpp"
#include "mjarm/trajectory/smoothstep.hpp"

namespace mjarm {

void check(const CartesianPathOptions& options) {
  check_fields(options);
  if (options.jump_factor > 0.0 && options.jump_factor < 1.0)
    throw Error("cartesian path: jump_factor must be 0 (off) or ≥ 1, got " +
                number_text(options.jump_factor));
  check(options.ik);
}

namespace {

/// The x in [0, 1] with smootherstep(x) = s: `Se3Interpolation` from rest to rest moves along its
/// line and slerp by smootherstep(t/T), so x·T is the time at path parameter s. Newton steps,
/// kept inside a shrinking bracket (s is monotone in x).
double cartesian_time_of(double s) noexcept {
  if (s <= 0.0) return 0.0;
  if (s >= 1.0) return 1.0;
  double low = 0.0, high = 1.0, x = s;
  for (int i = 0; i < 60; ++i) {
    const RampSample r = smootherstep(x);
    const double f = r.s - s;
    if (std::abs(f) <= 1e-15) break;
    (f < 0.0 ? low : high) = x;
    const double newton = r.ds > 0.0 ? x - f / r.ds : -1.0;
    x = (newton > low && newton < high) ? newton : 0.5 * (low + high);
  }
  return x;
}

/// The chain on a copy of its model with contacts disabled: the checker then judges joint ranges
/// and σmin only (`check_collisions` off).
Chain contact_free_chain(const Chain& chain) {
  mjModel* copy = mj_copyModel(nullptr, &chain.robot().model());
  if (copy == nullptr) throw Error("cartesian path: could not copy the model");
  copy->opt.disableflags |= mjDSBL_CONTACT;
  const Robot robot = Robot::from_model(std::shared_ptr<const mjModel>(copy, mj_deleteModel),
                                        chain.robot().source() + " (contacts disabled)");
  return Chain(robot, chain.joint_names(), chain.frame().name);
}

JointLimits unchecked_dynamics(int n) {
  // the states are at rest: velocity and acceleration limits are never read, torques not judged
  return {Eigen::VectorXd::Ones(n), Eigen::VectorXd::Ones(n),
          Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity())};
}

CartesianPathStatus path_status_of(CheckFailure failure) noexcept {
  switch (failure) {
    case CheckFailure::collision:
      return CartesianPathStatus::partial_collision;
    case CheckFailure::invalid:
      return CartesianPathStatus::invalid_input;
    default:
      return CartesianPathStatus::partial_limits;
  }
}

/// One straight segment of the path: its interpolation, its step count and the Cartesian length
/// of one step in units of the step bounds (max(Δp/max_step, Δθ/max_rotation_step) ≤ 1).
struct Segment {
  Se3Interpolation line;
  int steps = 0;
  double step_measure = 0.0;
};

}  // namespace

struct CartesianPathPlanner::Impl {
  Impl(const Chain& chain, const CartesianPathOptions& o)
      : options((check(o), o)),
        chain(chain),
        kin(chain),
        ik(chain, o.ik),
        checker(o.check_collisions ? chain : contact_free_chain(chain),
                unchecked_dynamics(chain.size()), o.checks) {
    const int n = chain.size();
    const mjModel& m = chain.robot().model();
    prismatic.resize(n);
    for (int i = 0; i < n; ++i) prismatic[i] = m.jnt_type[chain.joint_id(i)] == mjJNT_SLIDE;
    ik_result.q = Eigen::VectorXd::Zero(n);
    dq = Eigen::VectorXd::Zero(n);
    q_between = Eigen::VectorXd::Zero(n);
  }

  CartesianPathOptions options;
  Chain chain;
  ChainKinematics kin;
  PoseIk ik;
  ConfigurationChecker checker;
  std::vector<char> prismatic;
  IkResult ik_result;
  Eigen::VectorXd dq, q_between;

  CartesianPathResult follow(const Eigen::VectorXd& q_start, const std::vector<Pose>& waypoints);
  /// The segments from E's start pose through @p waypoints, and the path's step count.
  std::vector<Segment> segments(const Pose& X_start, const std::vector<Pose>& waypoints,
                                int& total) const;
  /// The jump test of a step from knot k−1 by dq; an empty string when it passes.
  std::string jump(double step_measure, double mean_rate, int steps_before, double& rate) const;
  /// Checks the joint-space segment from @p q_from by dq (its end included); false at the first
  /// failing state, whose checks are left in `failed`.
  bool check_between(const Eigen::Ref<const Eigen::VectorXd>& q_from);
  ConfigurationCheck failed;
};

std::vector<Segment> CartesianPathPlanner::Impl::segments(const Pose& X_start,
                                                          const std::vector<Pose>& waypoints,
                                                          int& total) const {
  std::vector<Segment> out;
  out.reserve(waypoints.size());
  const Vector6d rest = Vector6d::Zero();
  double steps_needed = 0.0;  // in double: a far waypoint must not overflow an int
  const Pose* from = &X_start;
  for (const Pose& to : waypoints) {
    const double length = (to.p - from->p).norm() / options.max_step;
    const double turn = so3::angle(from->R.transpose() * to.R) / options.max_rotation_step;
    const double measure = std::max(length, turn);
    const double steps = std::ceil(measure - 1e-9);
    steps_needed += std::max(steps, 0.0);
    if (steps_needed > options.max_steps)
      throw Error("cartesian path: more than " + std::to_string(options.max_steps) +
                  " steps (max_steps) by waypoint " + std::to_string(out.size()) + " at max_step " +
                  number_text(options.max_step) + " m and max_rotation_step " +
                  number_text(options.max_rotation_step) + " rad");
    Segment s{Se3Interpolation(*from, rest, rest, to, 1.0), 0, 0.0};
    s.steps = static_cast<int>(std::max(steps, 0.0));
    s.step_measure = s.steps > 0 ? measure / s.steps : 0.0;
    out.push_back(s);
    from = &to;
  }
  total = static_cast<int>(steps_needed);
  return out;
}

std::string CartesianPathPlanner::Impl::jump(double step_measure, double mean_rate,
                                             int steps_before, double& rate) const {
  const int n = chain.size();
  for (int i = 0; i < n; ++i) {
    const double bound = prismatic[i] ? options.jump_prismatic : options.jump_revolute;
    if (bound > 0.0 && std::abs(dq[i]) > bound)
      return "joint '" + chain.joint_names()[i] + "' moves " + number_text(std::abs(dq[i]), 4) +
             (prismatic[i] ? " m" : " rad") + " in one step, more than the jump threshold " +
             number_text(bound) + (prismatic[i] ? " m" : " rad");
  }
  // joint distance per unit of Cartesian step, so segments with shorter steps compare fairly
  rate = dq.norm() / std::max(step_measure, 1e-12);
  if (options.jump_factor > 0.0 && steps_before > 0 && mean_rate > 0.0 &&
      rate > options.jump_factor * mean_rate)
    return "the joints move " + number_text(rate / mean_rate, 4) +
           " times the mean of the steps before (‖Δq‖ " + number_text(dq.norm(), 4) +
           "), more than the jump factor " + number_text(options.jump_factor);
  return {};
}

bool CartesianPathPlanner::Impl::check_between(const Eigen::Ref<const Eigen::VectorXd>& q_from) {
  const double largest = dq.cwiseAbs().maxCoeff();
  const int states = std::max(1, static_cast<int>(std::ceil(largest / options.check_step - 1e-9)));
  for (int j = 1; j <= states; ++j) {
    q_between = q_from + (static_cast<double>(j) / states) * dq;
    const ConfigurationCheck& c = checker.check(q_between);
    if (!c.ok()) {
      failed = c;
      return false;
    }
  }
  return true;
}

CartesianPathResult CartesianPathPlanner::Impl::follow(const Eigen::VectorXd& q_start,
                                                       const std::vector<Pose>& waypoints) {
  chain.check(q_start, "cartesian path: q_start");
  if (waypoints.empty()) throw Error("cartesian path: no waypoint");
  for (std::size_t k = 0; k < waypoints.size(); ++k)
    check_pose_target(waypoints[k], "cartesian path: waypoint " + std::to_string(k));
  const int n = chain.size();
  CartesianPathResult r;
  const Pose X_start = kin.update(q_start);
  const std::vector<Segment> path = segments(X_start, waypoints, r.steps);

  // the start is judged as every knot; a start that fails follows nothing
  r.check = checker.check(q_start);
  if (!r.check.ok()) {
    r.status = path_status_of(r.check.failure);
    r.stopped_at_step = 0;
    r.stopped_at_waypoint = 0;
    r.knots.resize(n, 0);
    r.message = "the start fails a check: " + checker.describe(r.check);
    return r;
  }
  r.knots.resize(n, r.steps + 1);
  r.knots.col(0) = q_start;
  r.poses.reserve(static_cast<std::size_t>(r.steps) + 1);
  r.poses.push_back(X_start);

  int done = 0;  // steps followed
  double rate_sum = 0.0;
  for (std::size_t w = 0; w < path.size() && r.stopped_at_step < 0; ++w) {
    const Segment& segment = path[w];
    for (int j = 1; j <= segment.steps; ++j) {
      const int step = done + 1;
      const Pose X_target =
          segment.line.at(cartesian_time_of(static_cast<double>(j) / segment.steps)).X_WE;
      const auto stop = [&](CartesianPathStatus status, const std::string& why) {
        r.status = status;
        r.stopped_at_step = step;
        r.stopped_at_waypoint = static_cast<int>(w);
        r.message = "step " + std::to_string(step) + " of " + std::to_string(r.steps) +
                    " (towards waypoint " + std::to_string(w) + "): " + why;
      };
      ik.solve(X_target, r.knots.col(done), ik_result);
      if (ik_result.status == IkStatus::invalid_input) {
        stop(CartesianPathStatus::invalid_input, "the IK met a NaN");
        break;
      }
      if (!ik_result.ok()) {
        stop(CartesianPathStatus::partial_ik_failure,
             "no IK solution near the previous knot (position error " +
                 number_text(ik_result.position_error * 1e3, 4) + " mm, orientation error " +
                 number_text(ik_result.orientation_error * 1e3, 4) + " mrad after " +
                 std::to_string(ik_result.iterations) + " iterations)");
        break;
      }
      dq = ik_result.q - r.knots.col(done);
      double rate = 0.0;
      const std::string jumped =
          jump(segment.step_measure, done > 0 ? rate_sum / done : 0.0, done, rate);
      if (!jumped.empty()) {
        stop(CartesianPathStatus::partial_jump, jumped);
        break;
      }
      if (!check_between(r.knots.col(done))) {
        r.check = failed;
        stop(path_status_of(r.check.failure), checker.describe(r.check));
        break;
      }
      ++done;
      rate_sum += rate;
      r.knots.col(done) = ik_result.q;
      r.poses.push_back(kin.update(ik_result.q));
      const FrameErrors e = frame_errors(r.poses.back(), X_target);
      r.max_position_error = std::max(r.max_position_error, e.position);
      r.max_orientation_error = std::max(r.max_orientation_error, e.orientation);
      r.max_joint_step = std::max(r.max_joint_step, dq.cwiseAbs().maxCoeff());
    }
  }
  r.knots.conservativeResize(n, done + 1);
  r.fraction = r.steps > 0 ? static_cast<double>(done) / r.steps : 1.0;
  if (r.stopped_at_step < 0) {
    r.status = CartesianPathStatus::complete;
    r.check = ConfigurationCheck{};
    r.message = "all " + std::to_string(r.steps) + " steps followed";
  }
  return r;
}

CartesianPathPlanner::CartesianPathPlanner(const Chain& chain, const CartesianPathOptions& options)
    : impl_(std::make_unique<Impl>(chain, options)) {}
CartesianPathPlanner::~CartesianPathPlanner() = default;
CartesianPathPlanner::CartesianPathPlanner(CartesianPathPlanner&&) noexcept = default;
CartesianPathPlanner& CartesianPathPlanner::operator=(CartesianPathPlanner&&) noexcept = default;

const CartesianPathOptions& CartesianPathPlanner::options() const noexcept {
  return impl_->options;
}

void CartesianPathPlanner::set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  impl_->kin.set_fixed_qpos(qpos);
  impl_->ik.set_fixed_qpos(qpos);
  impl_->checker.set_fixed_qpos(qpos);
}

CartesianPathResult CartesianPathPlanner::follow(const Eigen::VectorXd& q_start,
                                                 const std::vector<Pose>& waypoints) {
  return impl_->follow(q_start, waypoints);
}

CartesianPathResult cartesian_path(const Chain& chain, const Eigen::VectorXd& q_start,
                                   const std::vector<Pose>& waypoints,
                                   const CartesianPathOptions& options) {
  return CartesianPathPlanner(chain, options).follow(q_start, waypoints);
}

CartesianPathResult cartesian_path(const Chain& chain, const Eigen::VectorXd& q_start,
                                   const Pose& target, const CartesianPathOptions& options) {
  return cartesian_path(chain, q_start, std::vector<Pose>{target}, options);
}

}  // namespace mjarm
