#include "mjarm/ik/multi_target_ik.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm {
namespace {

/// A target's kinematics on the shared joints; the frame must be moved by one of them.
ChainKinematics target_kinematics(const Robot& robot, const std::vector<std::string>& joints,
                                  const FrameTarget& target) {
  ChainKinematics kin{Chain(robot, joints, target.frame)};
  bool moved = false;
  for (int i = 0; i < kin.chain().size(); ++i) moved = moved || kin.moves_frame(i);
  if (!moved)
    throw Error("target frame '" + target.frame + "' is not moved by any of the IK joints");
  return kin;
}

}  // namespace

void check(const MultiTargetIkOptions& o) {
  // the shared settings, then the solver's own fields, under the name it declares
  check_fields<LocalIkSettings>(o, fields_of<MultiTargetIkOptions>().owner);
  check_fields(o);
}

MultiTargetIk::MultiTargetIk(const Robot& robot, const std::vector<std::string>& joints,
                             const std::vector<FrameTarget>& targets,
                             const MultiTargetIkOptions& options)
    : options_(options) {
  check(options_);
  if (targets.empty()) throw Error("multi-target IK needs at least one target");
  // priority levels in increasing order; stacked mode puts everything in one level
  std::vector<int> priorities;
  for (const FrameTarget& t : targets) {
    if (t.priority < 0) {
      throw Error("target on '" + t.frame + "' has priority " + std::to_string(t.priority) +
                  "; priorities are >= 0 (0 is the most important)");
    }
    check_weights(t);
    check_pose_target(t.X_WT, "target on '" + t.frame + "'");
    priorities.push_back(options_.mode == MultiTargetMode::stacked ? 0 : t.priority);
  }
  std::vector<int> distinct = priorities;
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  targets_.reserve(targets.size());
  levels_.reserve(distinct.size());
  std::vector<int> level_rows(distinct.size(), 0);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const int level = static_cast<int>(
        std::lower_bound(distinct.begin(), distinct.end(), priorities[i]) - distinct.begin());
    targets_.push_back(TargetSlot{targets[i],
                                  target_kinematics(robot, joints, targets[i]),
                                  level,
                                  level_rows[level],
                                  {},
                                  {},
                                  {},
                                  {}});
    level_rows[level] += task_rows(targets[i].kind);
  }
  const Chain& shared = targets_.front().kin.chain();
  const int n = shared.size();
  for (int rows : level_rows) {
    levels_.push_back(Level{rows, Eigen::MatrixXd::Zero(rows, n), Eigen::VectorXd::Zero(rows),
                            Eigen::MatrixXd::Zero(rows, n), Eigen::VectorXd::Zero(rows),
                            Eigen::VectorXd::Zero(n), DampedLeastSquares(rows, n),
                            DampedLeastSquares(rows, n)});
  }
  local_.emplace(shared, options_);
  J_scratch_.setZero(6, n);
  N_.setZero(n, n);
  P_.setZero(n, n);
  projected_bias_.setZero(n);
  for (Score* s : {&current_, &trial_, &best_}) {
    s->converged.assign(levels_.size(), 0);
    s->objective.assign(levels_.size(), 0.0);
  }
}

void MultiTargetIk::set_target(int i, const Pose& X_WT) {
  if (i < 0 || i >= target_count()) {
    throw Error("target index " + std::to_string(i) + " out of range; there are " +
                std::to_string(target_count()) + " targets");
  }
  // the message is built only on failure: moving targets must not allocate
  if (!is_valid_pose(X_WT)) check_pose_target(X_WT, "target on '" + targets_[i].target.frame + "'");
  targets_[i].target.X_WT = X_WT;
}

void MultiTargetIk::set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  for (TargetSlot& slot : targets_) slot.kin.set_fixed_qpos(qpos);
  local_->set_fixed_qpos(qpos);
}

void MultiTargetIk::evaluate(const Eigen::Ref<const Eigen::VectorXd>& q, bool trial,
                             Score& score) noexcept {
  const MultiTargetIkOptions& o = options_;
  std::fill(score.converged.begin(), score.converged.end(), 1);
  std::fill(score.objective.begin(), score.objective.end(), 0.0);
  score.total = 0.0;
  score.worst = 0.0;
  for (TargetSlot& slot : targets_) {
    const FrameTarget& t = slot.target;
    const int rows = task_rows(t.kind);
    Level& level = levels_[slot.level];
    slot.kin.update(q);
    auto e = level.e.segment(slot.row, rows);
    auto J = level.J.middleRows(slot.row, rows);
    const FrameErrors f = evaluate_target(slot.kin, t.kind, t.X_WT, e, J, J_scratch_);
    // row weights: position rows first, then orientation rows
    e.head<3>() *= t.position_weight;
    J.topRows<3>() *= t.position_weight;
    if (rows == 6) {
      e.tail<3>() *= t.orientation_weight;
      J.bottomRows<3>() *= t.orientation_weight;
    }
    (trial ? slot.trial_errors : slot.errors) = f;
    const double s =
        std::max(f.position / o.position_tolerance, f.orientation / o.orientation_tolerance);
    if (!(s <= 1.0)) score.converged[slot.level] = 0;
    score.objective[slot.level] += e.squaredNorm();
    score.total += s;
    score.worst = std::max(score.worst, s);
  }
}

bool MultiTargetIk::better(const Score& a, const Score& b) const noexcept {
  // lexicographic by level; a level both scores have converged on is a tie
  for (std::size_t k = 0; k < levels_.size(); ++k) {
    if (a.converged[k] && b.converged[k]) continue;
    if (a.converged[k] != b.converged[k]) return a.converged[k] != 0;
    if (a.objective[k] != b.objective[k]) return a.objective[k] < b.objective[k];
  }
  return false;
}

bool MultiTargetIk::all_converged(const Score& s) const noexcept {
  return std::all_of(s.converged.begin(), s.converged.end(), [](char c) { return c != 0; });
}

bool MultiTargetIk::compute_step() noexcept {
  const MultiTargetIkOptions& o = options_;
  const double eps_sq = o.null_space_damping * o.null_space_damping;
  LocalIkWorkspace& local = *local_;
  const bool has_secondary = local.has_secondary();
  local.update_secondary();
  // the recursion starts from the pinned motion of saturated joints with a null space that
  // excludes them
  return local.limited_step([&](const Eigen::VectorXd& locked, const Eigen::VectorXd& dq_locked,
                                Eigen::VectorXd& dq) {
    dq = dq_locked;
    N_.setZero();
    N_.diagonal() = (1.0 - locked.array()).matrix();
    for (std::size_t k = 0; k < levels_.size(); ++k) {
      Level& L = levels_[k];
      L.J_tilde.noalias() = L.J * N_;
      L.r = L.e;
      L.r.noalias() -= L.J * dq;
      const double lambda_sq = o.damping * o.damping + o.error_damping * 0.5 * L.e.squaredNorm();
      L.step.factor(L.J_tilde, lambda_sq);
      L.step.step(L.J_tilde, L.r, L.dq);
      dq += L.dq;
      if (k + 1 < levels_.size() || has_secondary) {
        L.null.factor(L.J_tilde, eps_sq);
        L.null.row_space_projector(L.J_tilde, P_);
        N_ -= P_;
      }
    }
    if (has_secondary) {
      projected_bias_.noalias() = N_ * local.secondary();
      const double task = (dq - dq_locked).norm();
      dq += secondary_scale(task, projected_bias_.norm(), o.secondary_ratio) * projected_bias_;
    }
  });
}

void MultiTargetIk::report_iteration(int iteration) const {
  IkIteration it{iteration, 0.0, 0.0, &local_->q()};
  for (const TargetSlot& slot : targets_) {
    // std::max would drop a NaN that the callback should see
    if (!(slot.errors.position <= it.position_error)) it.position_error = slot.errors.position;
    if (!(slot.errors.orientation <= it.orientation_error)) {
      it.orientation_error = slot.errors.orientation;
    }
  }
  options_.on_iteration(it);
}

IkResult MultiTargetIk::solve(const Eigen::Ref<const Eigen::VectorXd>& q_seed) {
  IkResult result;
  result.q.resize(chain().size());
  solve(q_seed, result);
  return result;
}

void MultiTargetIk::solve(const Eigen::Ref<const Eigen::VectorXd>& q_seed, IkResult& result) {
  LocalIkWorkspace& local = *local_;
  local.start(q_seed, "multi-target IK seed", result);

  const MultiTargetIkOptions& o = options_;
  evaluate(local.q(), false, current_);
  bool have_best = false;
  StallCounter stall(o.stall_progress, o.stall_iterations);
  IkStatus status = IkStatus::not_converged;
  int iterations = 0;
  for (;; ++iterations) {
    if (o.on_iteration) report_iteration(iterations);
    if (!std::isfinite(current_.total)) {
      status = IkStatus::invalid_input;
      break;
    }
    if (!have_best || better(current_, best_)) {
      have_best = true;
      best_ = current_;
      local.keep_best();
      for (TargetSlot& slot : targets_) slot.best_errors = slot.errors;
    }
    if (all_converged(current_)) {
      status = IkStatus::converged;
      break;
    }
    if (iterations == o.max_iterations || stall.stalled(current_.total)) break;

    if (!compute_step()) {
      status = IkStatus::invalid_input;
      break;
    }

    // backtracking: halve the step while it makes the result worse (or touches a watched geom)
    const LineSearchOutcome outcome = local.line_search(o.step, [&](const Eigen::VectorXd& q_try) {
      evaluate(q_try, true, trial_);
      return better(trial_, current_);
    });
    if (outcome == LineSearchOutcome::non_finite) {
      status = IkStatus::invalid_input;
      break;
    }
    if (outcome == LineSearchOutcome::blocked) break;  // every step touched a watched geom
    current_ = trial_;
    for (TargetSlot& slot : targets_) slot.errors = slot.trial_errors;
  }

  // invalid input returns the last finite iterate, everything else the best one
  const bool last = status == IkStatus::invalid_input || !have_best;
  result.q = local.returned(last);
  result.position_error = 0.0;
  result.orientation_error = 0.0;
  for (TargetSlot& slot : targets_) {
    slot.result_errors = last ? slot.errors : slot.best_errors;
    result.position_error = std::max(result.position_error, slot.result_errors.position);
    result.orientation_error = std::max(result.orientation_error, slot.result_errors.orientation);
  }
  result.status = status;
  result.iterations = iterations;
}

}  // namespace mjarm
