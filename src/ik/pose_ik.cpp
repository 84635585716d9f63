#include "mjarm/ik/pose_ik.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mjarm/ik/targets.hpp"
#include "mjarm/lie/pose_error.hpp"

namespace mjarm {

void check(const PoseIkOptions& o) {
  // the shared settings, then the solver's own fields, under the name it declares
  check_fields<LocalIkSettings>(o, fields_of<PoseIkOptions>().owner);
  check_fields(o);
}

PoseIk::PoseIk(const Chain& chain, const PoseIkOptions& options)
    : options_(checked(options)), kin_(chain), local_(chain, options_) {
  const int n = chain.size();
  J_world_.setZero(6, n);
  J_.setZero(6, n);
  J_free_.setZero(6, n);
}

void PoseIk::set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  kin_.set_fixed_qpos(qpos);
  local_.set_fixed_qpos(qpos);
}

IkResult PoseIk::solve(const Pose& X_WT, const Eigen::Ref<const Eigen::VectorXd>& q_seed) {
  IkResult result;
  result.q.resize(chain().size());
  solve(X_WT, q_seed, result);
  return result;
}

void PoseIk::solve(const Pose& X_WT, const Eigen::Ref<const Eigen::VectorXd>& q_seed,
                   IkResult& result) {
  check_pose_target(X_WT, "pose IK target");
  local_.start(q_seed, "pose IK seed", result);

  const PoseIkOptions& o = options_;
  Vector6d w;
  w << Eigen::Vector3d::Constant(o.position_weight),
      Eigen::Vector3d::Constant(o.orientation_weight);
  // progress measure: how many tolerances away from converged
  const auto score = [&o](const FrameErrors& f) {
    return std::max(f.position / o.position_tolerance, f.orientation / o.orientation_tolerance);
  };

  Vector6d e = log_error(kin_.update(local_.q()), X_WT);
  FrameErrors errors = frame_errors(kin_.pose(), X_WT);
  double best = std::numeric_limits<double>::infinity();
  StallCounter stall(o.stall_progress, o.stall_iterations);
  IkStatus status = IkStatus::not_converged;
  int iterations = 0;
  for (;; ++iterations) {
    const double current = score(errors);
    if (o.on_iteration) {
      o.on_iteration(IkIteration{iterations, errors.position, errors.orientation, &local_.q()});
    }
    if (!std::isfinite(current) || !e.allFinite()) {
      status = IkStatus::invalid_input;
      break;
    }
    if (current < best) {
      best = current;
      local_.keep_best();
    }
    if (current <= 1.0) {
      status = IkStatus::converged;
      break;
    }
    if (iterations == o.max_iterations || stall.stalled(best)) break;

    // weighted task Jacobian W·Jlog(e)·J_E (kin_ holds the current iterate)
    kin_.jacobian(J_world_, JacobianFrame::world_aligned);
    J_.noalias() = log_jacobian_times_local(log_error_jacobian(e), kin_.pose().R) * J_world_;
    J_.topRows<3>() *= o.position_weight;
    J_.bottomRows<3>() *= o.orientation_weight;
    const Vector6d we = w.cwiseProduct(e);
    const double objective = we.squaredNorm();
    const double lambda_sq = o.damping * o.damping + o.error_damping * 0.5 * objective;

    // damped least squares plus the projected secondary terms, limit-aware
    local_.update_secondary();
    if (!local_.damped_task_step<6>(J_, we, lambda_sq, J_free_)) {
      status = IkStatus::invalid_input;
      break;
    }

    // backtracking: halve the step while it raises the error (or touches a watched geom)
    Vector6d e_try = e;
    FrameErrors errors_try = errors;
    const LineSearchOutcome outcome = local_.line_search(o.step, [&](const Eigen::VectorXd& q_try) {
      e_try = log_error(kin_.update(q_try), X_WT);
      errors_try = frame_errors(kin_.pose(), X_WT);
      return w.cwiseProduct(e_try).squaredNorm() < objective;
    });
    if (outcome == LineSearchOutcome::non_finite) {
      status = IkStatus::invalid_input;
      break;
    }
    if (outcome == LineSearchOutcome::blocked) break;  // every step touched a watched geom
    e = e_try;
    errors = errors_try;
  }

  // invalid input returns the last finite iterate, everything else the best one
  result.q = local_.returned(status == IkStatus::invalid_input);
  const FrameErrors final_errors = frame_errors(kin_.update(result.q), X_WT);
  result.status = status;
  result.position_error = final_errors.position;
  result.orientation_error = final_errors.orientation;
  result.iterations = iterations;
}

}  // namespace mjarm
