#include "mjarm/ik/position_ik.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/ik/targets.hpp"

namespace mjarm {
namespace {

void require(bool ok, const char* name, double value, const char* expected) {
  if (!ok) {
    throw Error(std::string("position IK option ") + name + " must be " + expected + ", got " +
                std::to_string(value));
  }
}

}  // namespace

void check(const PositionIkOptions& o) {
  require(std::isfinite(o.damping) && o.damping > 0.0, "damping", o.damping, "finite and > 0");
  require(o.step > 0.0 && o.step <= 1.0, "step", o.step, "in (0, 1]");
  require(std::isfinite(o.null_space_damping) && o.null_space_damping >= 0.0, "null_space_damping",
          o.null_space_damping, "finite and >= 0");
  require(std::isfinite(o.tolerance) && o.tolerance > 0.0, "tolerance", o.tolerance,
          "finite and > 0");
  require(std::isfinite(o.max_step) && o.max_step > 0.0, "max_step", o.max_step, "finite and > 0");
  require(std::isfinite(o.secondary_ratio) && o.secondary_ratio >= 0.0, "secondary_ratio",
          o.secondary_ratio, "finite and >= 0");
  require(o.max_backtracks >= 0, "max_backtracks", o.max_backtracks, ">= 0");
  require(o.max_iterations >= 1, "max_iterations", o.max_iterations, ">= 1");
  require(o.stall_iterations >= 1, "stall_iterations", o.stall_iterations, ">= 1");
  require(o.stall_progress >= 0.0 && o.stall_progress < 1.0, "stall_progress", o.stall_progress,
          "in [0, 1)");
  check(o.limits);
}

PositionIk::PositionIk(const Chain& chain, const PositionIkOptions& options)
    : options_(options), kin_(chain) {
  check(options_);
  q_pref_ = resolve_posture(chain, options_.posture);
  if (!options_.collision.empty())
    guard_ = std::make_unique<CollisionGuard>(chain, options_.collision);
  const int n = chain.size();
  J6_.setZero(6, n);
  J_.setZero(3, n);
  q_.setZero(n);
  q_best_.setZero(n);
  q_try_.setZero(n);
  dq_.setZero(n);
  bias_.setZero(n);
  free_bias_.setZero(n);
  locked_.setZero(n);
  dq_locked_.setZero(n);
  J_free_.setZero(3, n);
}

void PositionIk::set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  kin_.set_fixed_qpos(qpos);
  if (guard_) guard_->set_fixed_qpos(qpos);
}

IkResult PositionIk::solve(const Eigen::Vector3d& p_WT,
                           const Eigen::Ref<const Eigen::VectorXd>& q_seed) {
  IkResult result;
  result.q.resize(chain().size());
  solve(p_WT, q_seed, result);
  return result;
}

void PositionIk::solve(const Eigen::Vector3d& p_WT, const Eigen::Ref<const Eigen::VectorXd>& q_seed,
                       IkResult& result) {
  const Chain& chain = kin_.chain();
  check_position_target(p_WT, "position IK target");
  chain.check(q_seed, "position IK seed");
  q_ = q_seed;
  clamp_to_limits(chain, q_);
  if (guard_ && guard_->in_contact(q_)) {
    throw Error("position IK seed is in contact: " + guard_->describe_contacts(q_));
  }
  if (result.q.size() != chain.size()) result.q.resize(chain.size());

  const PositionIkOptions& o = options_;
  const double lambda_sq = o.damping * o.damping;
  const double eps_sq = o.null_space_damping * o.null_space_damping;
  const bool has_bias =
      o.limits.centre_gain > 0.0 || o.limits.repulsion_gain > 0.0 || o.posture.gain > 0.0;
  double best = std::numeric_limits<double>::infinity();
  double stall_reference = best;
  int since_progress = 0;
  IkStatus status = IkStatus::not_converged;
  int iterations = 0;
  Eigen::Vector3d e = p_WT - kin_.update(q_).p;
  for (;; ++iterations) {
    // the NaN guard keeps the last finite iterate
    const double err = e.norm();
    if (!std::isfinite(err)) {
      status = IkStatus::invalid_input;
      break;
    }
    if (err < best) {
      best = err;
      q_best_ = q_;
    }
    if (err <= o.tolerance) {
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

    // position Jacobian and the secondary terms
    kin_.jacobian(J6_, JacobianFrame::world_aligned);
    J_ = J6_.topRows<3>();
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
      const Eigen::Vector3d r = o.step * e - J_ * dq_locked_;
      Eigen::Matrix3d A = J_free_ * J_free_.transpose();
      A.diagonal().array() += lambda_sq;
      dq_.noalias() = J_free_.transpose() * A.llt().solve(r);
      if (has_bias) {
        free_bias_ = bias_.cwiseProduct((1.0 - locked_.array()).matrix());
        Eigen::Matrix3d N = J_free_ * J_free_.transpose();
        N.diagonal().array() += eps_sq;
        const Eigen::Vector3d z = N.ldlt().solve(J_free_ * free_bias_);
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

    // line search: halve the step while it raises the error or touches a watched geom (kin_
    // ends on the accepted iterate, whose error carries over to the next iteration)
    const int halvings = std::max(o.max_backtracks, guard_ ? guard_->spec().max_halvings : 0);
    double s = 1.0;
    bool accepted = false;
    Eigen::Vector3d e_try = e;
    for (int h = 0; h <= halvings; ++h, s *= 0.5) {
      q_try_ = q_ + s * dq_;
      clamp_to_limits(chain, q_try_);
      if (!q_try_.allFinite()) break;
      if (guard_ && guard_->in_contact(q_try_)) {
        if (h >= guard_->spec().max_halvings) break;
        continue;
      }
      e_try = p_WT - kin_.update(q_try_).p;
      if (e_try.norm() < err || h >= o.max_backtracks) {
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
  }

  // invalid input returns the last finite iterate, everything else the best one
  if (status == IkStatus::invalid_input) {
    result.q = q_;
    kin_.update(q_);
  } else {
    result.q = q_best_;
    kin_.update(q_best_);
  }
  result.status = status;
  result.position_error = (p_WT - kin_.pose().p).norm();
  result.orientation_error = 0.0;
  result.iterations = iterations;
}

}  // namespace mjarm
