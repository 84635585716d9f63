#include "mjarm/ik/position_ik.hpp"

#include <cmath>
#include <limits>

#include "mjarm/ik/targets.hpp"

namespace mjarm {

void check(const PositionIkOptions& o) {
  // the shared settings, then the solver's own fields, under the name it declares
  check_fields<LocalIkSettings>(o, fields_of<PositionIkOptions>().owner);
  check_fields(o);
}

PositionIk::PositionIk(const Chain& chain, const PositionIkOptions& options)
    : options_(checked(options)), kin_(chain), local_(chain, options_) {
  const int n = chain.size();
  J6_.setZero(6, n);
  J_.setZero(3, n);
  J_free_.setZero(3, n);
}

void PositionIk::set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  kin_.set_fixed_qpos(qpos);
  local_.set_fixed_qpos(qpos);
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
  check_position_target(p_WT, "position IK target");
  local_.start(q_seed, "position IK seed", result);

  const PositionIkOptions& o = options_;
  const double lambda_sq = o.damping * o.damping;
  double best = std::numeric_limits<double>::infinity();
  StallCounter stall(o.stall_progress, o.stall_iterations);
  IkStatus status = IkStatus::not_converged;
  int iterations = 0;
  Eigen::Vector3d e = p_WT - kin_.update(local_.q()).p;
  for (;; ++iterations) {
    // the NaN guard keeps the last finite iterate
    const double err = e.norm();
    if (o.on_iteration) o.on_iteration(IkIteration{iterations, err, 0.0, &local_.q()});
    if (!std::isfinite(err)) {
      status = IkStatus::invalid_input;
      break;
    }
    if (err < best) {
      best = err;
      local_.keep_best();
    }
    if (err <= o.tolerance) {
      status = IkStatus::converged;
      break;
    }
    if (iterations == o.max_iterations || stall.stalled(best)) break;

    // damped least squares towards α·e plus the projected secondary terms, limit-aware
    kin_.jacobian(J6_, JacobianFrame::world_aligned);
    J_ = J6_.topRows<3>();
    local_.update_secondary();
    const Eigen::Vector3d target = o.step * e;
    if (!local_.damped_task_step<3>(J_, target, lambda_sq, J_free_)) {
      status = IkStatus::invalid_input;
      break;
    }

    // line search: halve the step while it raises the error or touches a watched geom (kin_
    // ends on the accepted iterate, whose error carries over to the next iteration)
    Eigen::Vector3d e_try = e;
    const LineSearchOutcome outcome = local_.line_search(1.0, [&](const Eigen::VectorXd& q_try) {
      e_try = p_WT - kin_.update(q_try).p;
      return e_try.norm() < err;
    });
    if (outcome == LineSearchOutcome::non_finite) {
      status = IkStatus::invalid_input;
      break;
    }
    if (outcome == LineSearchOutcome::blocked) break;  // every step touched a watched geom
    e = e_try;
  }

  // invalid input returns the last finite iterate, everything else the best one
  result.q = local_.returned(status == IkStatus::invalid_input);
  kin_.update(result.q);
  result.status = status;
  result.position_error = (p_WT - kin_.pose().p).norm();
  result.orientation_error = 0.0;
  result.iterations = iterations;
}

}  // namespace mjarm
