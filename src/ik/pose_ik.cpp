#include "mjarm/ik/pose_ik.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/ik/targets.hpp"
#include "mjarm/lie/pose_error.hpp"

namespace mjarm {
namespace {

void require(bool ok, const char* name, double value, const char* expected) {
  if (!ok) {
    throw Error(std::string("pose IK option ") + name + " must be " + expected + ", got " +
                std::to_string(value));
  }
}

bool positive(double x) { return std::isfinite(x) && x > 0.0; }

}  // namespace

void check(const PoseIkOptions& o) {
  require(positive(o.damping), "damping", o.damping, "finite and > 0");
  require(std::isfinite(o.error_damping) && o.error_damping >= 0.0, "error_damping",
          o.error_damping, "finite and >= 0");
  require(o.step > 0.0 && o.step <= 1.0, "step", o.step, "in (0, 1]");
  require(o.max_backtracks >= 0, "max_backtracks", o.max_backtracks, ">= 0");
  require(positive(o.position_weight), "position_weight", o.position_weight, "finite and > 0");
  require(positive(o.orientation_weight), "orientation_weight", o.orientation_weight,
          "finite and > 0");
  require(std::isfinite(o.null_space_damping) && o.null_space_damping >= 0.0, "null_space_damping",
          o.null_space_damping, "finite and >= 0");
  require(positive(o.position_tolerance), "position_tolerance", o.position_tolerance,
          "finite and > 0");
  require(positive(o.orientation_tolerance), "orientation_tolerance", o.orientation_tolerance,
          "finite and > 0");
  require(positive(o.max_step), "max_step", o.max_step, "finite and > 0");
  require(std::isfinite(o.secondary_ratio) && o.secondary_ratio >= 0.0, "secondary_ratio",
          o.secondary_ratio, "finite and >= 0");
  require(o.max_iterations >= 1, "max_iterations", o.max_iterations, ">= 1");
  require(o.stall_iterations >= 1, "stall_iterations", o.stall_iterations, ">= 1");
  require(o.stall_progress >= 0.0 && o.stall_progress < 1.0, "stall_progress", o.stall_progress,
          "in [0, 1)");
  check(o.limits);
}

PoseIk::PoseIk(const Chain& chain, const PoseIkOptions& options) : options_(options), kin_(chain) {
  check(options_);
  q_pref_ = resolve_posture(chain, options_.posture);
  if (!options_.collision.empty())
    guard_ = std::make_unique<CollisionGuard>(chain, options_.collision);
  const int n = chain.size();
  J_world_.setZero(6, n);
  J_.setZero(6, n);
  q_.setZero(n);
  q_best_.setZero(n);
  q_try_.setZero(n);
  dq_.setZero(n);
  bias_.setZero(n);
  free_bias_.setZero(n);
  locked_.setZero(n);
  dq_locked_.setZero(n);
  J_free_.setZero(6, n);
}

void PoseIk::set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  kin_.set_fixed_qpos(qpos);
  if (guard_) guard_->set_fixed_qpos(qpos);
}

IkResult PoseIk::solve(const Pose& X_WT, const Eigen::Ref<const Eigen::VectorXd>& q_seed) {
  IkResult result;
  result.q.resize(chain().size());
  solve(X_WT, q_seed, result);
  return result;
}

void PoseIk::solve(const Pose& X_WT, const Eigen::Ref<const Eigen::VectorXd>& q_seed,
                   IkResult& result) {
  const Chain& chain = kin_.chain();
  check_pose_target(X_WT, "pose IK target");
  chain.check(q_seed, "pose IK seed");
  q_ = q_seed;
  clamp_to_limits(chain, q_);
  if (guard_ && guard_->in_contact(q_)) {
    throw Error("pose IK seed is in contact: " + guard_->describe_contacts(q_));
  }
  if (result.q.size() != chain.size()) result.q.resize(chain.size());

  const PoseIkOptions& o = options_;
  Vector6d w;
  w << Eigen::Vector3d::Constant(o.position_weight),
      Eigen::Vector3d::Constant(o.orientation_weight);
  const double eps_sq = o.null_space_damping * o.null_space_damping;
  const bool has_bias =
      o.limits.centre_gain > 0.0 || o.limits.repulsion_gain > 0.0 || o.posture.gain > 0.0;
  // progress measure: how many tolerances away from converged
  const auto score = [&o](const FrameErrors& f) {
    return std::max(f.position / o.position_tolerance, f.orientation / o.orientation_tolerance);
  };

  Vector6d e = log_error(kin_.update(q_), X_WT);
  FrameErrors errors = frame_errors(kin_.pose(), X_WT);
  double best = std::numeric_limits<double>::infinity();
  double stall_reference = best;
  int since_progress = 0;
  IkStatus status = IkStatus::not_converged;
  int iterations = 0;
  for (;; ++iterations) {
    const double current = score(errors);
    if (!std::isfinite(current) || !e.allFinite()) {
      status = IkStatus::invalid_input;
      break;
    }
    if (current < best) {
      best = current;
      q_best_ = q_;
    }
    if (current <= 1.0) {
      status = IkStatus::converged;
      break;
    }
    if (iterations == o.max_iterations) break;
    if (best < stall_reference * (1.0 - o.stall_progress)) {
      stall_reference = best;
      since_progress = 0;
    } else if (++since_progress >= o.stall_iterations) {
      break;
    }

    // weighted task Jacobian W·Jlog(e)·J_E (kin_ holds the current iterate)
    kin_.jacobian(J_world_, JacobianFrame::world_aligned);
    J_.noalias() = log_jacobian_times_local(log_error_jacobian(e), kin_.pose().R) * J_world_;
    J_.topRows<3>() *= o.position_weight;
    J_.bottomRows<3>() *= o.orientation_weight;
    const Vector6d we = w.cwiseProduct(e);
    const double objective = we.squaredNorm();
    const double lambda_sq = o.damping * o.damping + o.error_damping * 0.5 * objective;

    // secondary terms
    if (has_bias) {
      bias_.setZero();
      add_limit_bias(chain, o.limits, q_, bias_);
      add_posture_pull(q_pref_, o.posture.gain, q_, bias_);
    }

    // damped least squares plus the projected secondary terms; joints the step would carry past
    // a bound are pinned on it and the others solve again (one more joint per pass)
    locked_.setZero();
    dq_locked_.setZero();
    for (int pass = 0; pass <= chain.size(); ++pass) {
      J_free_ = J_;
      for (int i = 0; i < chain.size(); ++i) {
        if (locked_[i] != 0.0) J_free_.col(i).setZero();
      }
      const Vector6d r = we - J_ * dq_locked_;
      Matrix6d A = J_free_ * J_free_.transpose();
      A.diagonal().array() += lambda_sq;
      dq_.noalias() = J_free_.transpose() * A.llt().solve(r);
      if (has_bias) {
        free_bias_ = bias_.cwiseProduct((1.0 - locked_.array()).matrix());
        Matrix6d N = J_free_ * J_free_.transpose();
        N.diagonal().array() += eps_sq;
        const Vector6d z = N.ldlt().solve(J_free_ * free_bias_);
        free_bias_.noalias() -= J_free_.transpose() * z;
        dq_ += secondary_scale(dq_.norm(), free_bias_.norm(), o.secondary_ratio) * free_bias_;
      }
      dq_ += dq_locked_;
      if (saturate_step(chain, q_, dq_, locked_, dq_locked_) == 0) break;
    }
    // a trust region against the huge steps next to singularities
    const double largest = dq_.cwiseAbs().maxCoeff();
    if (largest > o.max_step) dq_ *= o.max_step / largest;
    if (!dq_.allFinite()) {
      status = IkStatus::invalid_input;
      break;
    }

    // backtracking: halve the step while it raises the error (or touches a watched geom)
    double s = o.step;
    bool accepted = false;
    Vector6d e_try = e;
    FrameErrors errors_try = errors;
    for (int h = 0; h <= std::max(o.max_backtracks, guard_ ? guard_->spec().max_halvings : 0);
         ++h, s *= 0.5) {
      q_try_ = q_ + s * dq_;
      clamp_to_limits(chain, q_try_);
      if (!q_try_.allFinite()) break;
      const bool contact = guard_ && guard_->in_contact(q_try_);
      if (contact) {
        if (h >= guard_->spec().max_halvings) break;
        continue;
      }
      e_try = log_error(kin_.update(q_try_), X_WT);
      errors_try = frame_errors(kin_.pose(), X_WT);
      if (w.cwiseProduct(e_try).squaredNorm() < objective || h >= o.max_backtracks) {
        accepted = true;
        break;
      }
    }
    if (!q_try_.allFinite()) {
      status = IkStatus::invalid_input;
      break;
    }
    if (!accepted) break;  // every shortened step touched a watched geom
    q_ = q_try_;
    e = e_try;
    errors = errors_try;
  }

  // invalid input returns the last finite iterate, everything else the best one
  result.q = status == IkStatus::invalid_input ? q_ : q_best_;
  const FrameErrors final_errors = frame_errors(kin_.update(result.q), X_WT);
  result.status = status;
  result.position_error = final_errors.position;
  result.orientation_error = final_errors.orientation;
  result.iterations = iterations;
}

}  // namespace mjarm
