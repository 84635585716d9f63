#include "mjarm/planning/ompl_planner.hpp"

#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/goals/GoalStates.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>
#include <ompl/util/Exception.h>

#include <algorithm>
#include <chrono>
#include <limits>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "planning/ompl_goals.hpp"
#include "planning/ompl_state_space.hpp"
#include "planning/ompl_timing.hpp"

namespace mjarm {

namespace ob = ompl::base;
namespace og = ompl::geometric;

void check(const OmplOptions& o) {
  check_fields(o);
  check_fields(o.model_limits);
}

namespace {

/// An OMPL planner whose own generator is seeded by the plan (OMPL seeds each from a
/// process-wide sequence otherwise, so a second plan would draw other numbers).
template <class Planner>
class SeededPlanner : public Planner {
 public:
  SeededPlanner(const ob::SpaceInformationPtr& si, std::uint_fast32_t seed) : Planner(si) {
    this->rng_.setLocalSeed(seed);
  }
};

/// The shortcutting simplifier with a generator seeded by the plan, as above.
class SeededSimplifier : public og::PathSimplifier {
 public:
  SeededSimplifier(const ob::SpaceInformationPtr& si, std::uint_fast32_t seed)
      : og::PathSimplifier(si) {
    rng_.setLocalSeed(seed);
  }
};

/// OMPL's messages, kept in a list or dropped, for the duration of one plan (OMPL's handler is
/// process-wide: the previous one is put back).
class OmplMessages : public ompl::msg::OutputHandler {
 public:
  explicit OmplMessages(std::vector<std::string>* keep)
      : keep_(keep), previous_(ompl::msg::getOutputHandler()) {
    ompl::msg::useOutputHandler(this);
  }
  ~OmplMessages() override { ompl::msg::useOutputHandler(previous_); }
  OmplMessages(const OmplMessages&) = delete;
  OmplMessages& operator=(const OmplMessages&) = delete;

  void log(const std::string& text, ompl::msg::LogLevel, const char*, int) override {
    if (keep_ != nullptr) keep_->push_back(text);
  }

 private:
  std::vector<std::string>* keep_;
  ompl::msg::OutputHandler* previous_;
};

ob::PlannerPtr make_planner(OmplPlannerType type, const ob::SpaceInformationPtr& si,
                            std::uint_fast32_t seed) {
  switch (type) {
    case OmplPlannerType::rrtconnect:
      return std::make_shared<SeededPlanner<og::RRTConnect>>(si, seed);
    case OmplPlannerType::prm:
      return std::make_shared<SeededPlanner<og::PRM>>(si, seed);
    case OmplPlannerType::rrtstar:
      return std::make_shared<SeededPlanner<og::RRTstar>>(si, seed);
    case OmplPlannerType::bitstar:
      return std::make_shared<og::BITstar>(si);  // its generators are its own (not seeded)
  }
  throw Error("OMPL planner: unknown planner type");
}

/// Keeps, from each kept vertex, the farthest later vertex a straight motion reaches: a path whose
/// vertices all see each other becomes one segment, whatever the random shortcuts missed.
void keep_farthest_visible(og::PathGeometric& path, const ob::SpaceInformation& si) {
  std::vector<ob::State*>& states = path.getStates();
  std::vector<ob::State*> kept{states.front()};
  std::size_t i = 0;
  while (i + 1 < states.size()) {
    std::size_t j = states.size() - 1;
    while (j > i + 1 && !si.checkMotion(states[i], states[j])) --j;
    kept.push_back(states[j]);
    i = j;
  }
  for (ob::State* state : states)
    if (std::find(kept.begin(), kept.end(), state) == kept.end()) si.freeState(state);
  states = kept;
}

double path_length(const std::vector<Eigen::VectorXd>& path) {
  double length = 0.0;
  for (std::size_t k = 1; k < path.size(); ++k) length += (path[k] - path[k - 1]).norm();
  return length;
}

JointLimits resolve_limits(const OmplOptions& options, const Chain& chain,
                           const Eigen::VectorXd& q) {
  JointLimits limits = options.limits;
  if (limits.max_velocity.size() == 0 || limits.max_acceleration.size() == 0 ||
      limits.max_torque.size() == 0) {
    const JointLimits model = joint_limits_from_model(chain, q, options.model_limits);
    if (limits.max_velocity.size() == 0) limits.max_velocity = model.max_velocity;
    if (limits.max_acceleration.size() == 0) limits.max_acceleration = model.max_acceleration;
    if (limits.max_torque.size() == 0) limits.max_torque = model.max_torque;
  }
  check(limits, chain.size());
  return limits;
}

}  // namespace

struct OmplPlanner::Impl {
  Impl(const Chain& c, const OmplOptions& o)
      : chain(c), options(o), checker(c, o.collision_margin), ik(c) {}

  OmplResult plan(const Eigen::VectorXd& q_start, const OmplGoal& goal);
  /// The search, simplification and timing once the start and the goals are known to be valid.
  void search(const Eigen::VectorXd& q_start, const std::vector<Eigen::VectorXd>& goals,
              double resolution, OmplResult& result);

  Chain chain;
  OmplOptions options;
  CollisionChecker checker;
  GlobalIk ik;
  Eigen::VectorXd fixed_qpos;
};

OmplPlanner::OmplPlanner(const Chain& chain, const OmplOptions& options) {
  check(options);
  const int n = chain.size();
  const auto fits = [n](const Eigen::VectorXd& v) { return v.size() == 0 || v.size() == n; };
  if (!fits(options.limits.max_velocity) || !fits(options.limits.max_acceleration) ||
      !fits(options.limits.max_torque))
    throw Error("OMPL planner: each limit vector needs " + std::to_string(n) +
                " entries (one per chain joint) or none (from the model)");
  impl_ = std::make_unique<Impl>(chain, options);
  for (const AllowedCollision& pair : options.allowed_collisions)
    impl_->checker.contacts().allow(pair.first, pair.second);
  const mjModel& m = chain.robot().model();
  impl_->fixed_qpos = Eigen::Map<const Eigen::VectorXd>(m.qpos0, m.nq);
}

OmplPlanner::~OmplPlanner() = default;
OmplPlanner::OmplPlanner(OmplPlanner&&) noexcept = default;
OmplPlanner& OmplPlanner::operator=(OmplPlanner&&) noexcept = default;

const Chain& OmplPlanner::chain() const noexcept { return impl_->chain; }
const OmplOptions& OmplPlanner::options() const noexcept { return impl_->options; }

void OmplPlanner::set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  impl_->checker.set_fixed_qpos(qpos);
  impl_->ik.set_fixed_qpos(qpos);
  impl_->fixed_qpos = qpos;
}

OmplResult OmplPlanner::plan(const Eigen::VectorXd& q_start, const OmplGoal& goal) {
  const auto started = std::chrono::steady_clock::now();
  OmplResult result;
  try {
    result = impl_->plan(q_start, goal);
  } catch (const ompl::Exception& e) {
    throw Error(std::string("OMPL planner: OMPL failed: ") + e.what());
  }
  result.planning_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

OmplResult OmplPlanner::Impl::plan(const Eigen::VectorXd& q_start, const OmplGoal& goal) {
  chain.check(q_start, "start configuration");
  OmplResult result;
  const OmplMessages messages(options.log ? &result.log : nullptr);
  checker.reset_checks();
  result.limits = resolve_limits(options, chain, q_start);
  if (!checker.valid(q_start)) {
    result.status = checker.last_limit_joint() >= 0 ? OmplStatus::invalid_input
                                                    : OmplStatus::start_in_collision;
    result.message = "the start configuration: " + checker.describe_last();
    result.validity_checks = checker.checks();
    return result;
  }
  const ompl_detail::GoalConfigurations goals =
      ompl_detail::goal_configurations(goal, q_start, options, checker, ik);
  result.goal_states = static_cast<int>(goals.states.size());
  if (goals.states.empty()) {
    result.status = goals.status;
    result.message = goals.message;
    result.validity_checks = checker.checks();
    return result;
  }
  // a timed path that touches something between the validator's states is searched again once
  // with a validator 4× finer (a new budget), before the status says so
  for (const double resolution : {options.resolution, options.resolution / 4.0}) {
    search(q_start, goals.states, resolution, result);
    if (result.status != OmplStatus::trajectory_in_collision) break;
  }
  result.validity_checks = checker.checks();
  return result;
}

void OmplPlanner::Impl::search(const Eigen::VectorXd& q_start,
                               const std::vector<Eigen::VectorXd>& goals, double resolution,
                               OmplResult& result) {
  const int n = chain.size();
  result.path.clear();  // nothing of an earlier search is kept
  result.path_length = 0.0;
  const ob::SpaceInformationPtr si =
      ompl_detail::make_space_information(checker, resolution, options.seed);
  auto problem = std::make_shared<ob::ProblemDefinition>(si);
  ob::ScopedState<> state(si->getStateSpace());
  ompl_detail::copy_to_state(q_start, state.get());
  problem->addStartState(state);
  auto goal_states = std::make_shared<ob::GoalStates>(si);
  for (const Eigen::VectorXd& q : goals) {
    ompl_detail::copy_to_state(q, state.get());
    goal_states->addState(state);
  }
  problem->setGoal(goal_states);
  auto objective = std::make_shared<ob::PathLengthOptimizationObjective>(si);
  // without `optimize`, any path satisfies the objective: the optimizing planners stop at their
  // first solution instead of spending the whole budget
  if (!options.optimize)
    objective->setCostThreshold(ob::Cost(std::numeric_limits<double>::infinity()));
  problem->setOptimizationObjective(objective);

  const ob::PlannerPtr planner =
      make_planner(options.planner, si, ompl_detail::generator_seed(options.seed, 1000));
  planner->setProblemDefinition(problem);
  planner->setup();
  const ob::PlannerStatus status =
      planner->solve(ob::timedPlannerTerminationCondition(options.time_budget));
  if (status != ob::PlannerStatus::EXACT_SOLUTION || !problem->hasExactSolution()) {
    result.status = OmplStatus::no_path_within_budget;
    result.message = std::string(to_string(options.planner)) + " found no path within " +
                     number_text(options.time_budget) + " s (OMPL: " + status.asString() + ")";
    return;
  }
  og::PathGeometric path(*problem->getSolutionPath()->as<og::PathGeometric>());
  if (options.simplify) {
    // shortcuts only, no B-spline smoothing: the timing stops or slows at every knot, so fewer
    // knots make the faster motion; every shortcut is checked by the motion validator
    SeededSimplifier simplifier(si, ompl_detail::generator_seed(options.seed, 1001));
    simplifier.reduceVertices(path);
    simplifier.collapseCloseVertices(path);
    simplifier.shortcutPath(path);
    simplifier.reduceVertices(path);
    keep_farthest_visible(path, *si);
  }
  result.path.clear();
  for (std::size_t k = 0; k < path.getStateCount(); ++k)
    result.path.push_back(ompl_detail::state_values(path.getState(k), n));
  if (result.path.size() < 2) result.path.push_back(result.path.back());
  result.path_length = path_length(result.path);

  // the timed trajectory, every sample checked by the full configuration check (limits and
  // contacts; σmin and torque are not this planner's to judge)
  JointLimits check_limits = result.limits;
  check_limits.max_torque.setConstant(std::numeric_limits<double>::infinity());
  CheckOptions check_options;
  check_options.min_singular_value = 0.0;
  check_options.collision_margin = options.collision_margin;
  ConfigurationChecker configuration(chain, check_limits, check_options);
  configuration.set_fixed_qpos(fixed_qpos);
  for (const AllowedCollision& pair : options.allowed_collisions)
    configuration.contacts().allow(pair.first, pair.second);
  const ompl_detail::TimedPath timed =
      ompl_detail::time_path(result.path, result.limits, options.sample_step, configuration);
  result.trajectory_samples = timed.samples;
  if (!timed.ok) {
    result.status = OmplStatus::trajectory_in_collision;
    result.message = timed.message + " (the validator at " + number_text(resolution) +
                     " rad; lower the resolution)";
    result.path.clear();  // never a path through an obstacle
    result.path_length = 0.0;
    return;
  }
  result.trajectory = timed.trajectory;
  result.status = OmplStatus::success;
  result.message = std::string(to_string(options.planner)) + ": " +
                   std::to_string(result.path.size()) + " knots, " +
                   number_text(result.path_length) + " rad, " +
                   number_text(result.trajectory.duration()) + " s";
  if (options.time_optimal) {
    std::string why;
    result.time_optimal =
        ompl_detail::time_optimally(result.path, result.limits, options.sample_step, configuration,
                                    result.trajectory_samples, why);
    result.message += result.time_optimal
                          ? ", time-optimal " + number_text(result.time_optimal->duration()) + " s"
                          : "; no time-optimal timing (" + why + ")";
  }
}

}  // namespace mjarm
