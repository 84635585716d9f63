#include "mjarm/scenarios/plan_scenario.hpp"

#include <limits>

#include "mjarm/error.hpp"
#include "scenarios/scenario_parts.hpp"

namespace mjarm {

PlannedMotionOptions planned_motion_options(const PlanParameters& p) {
  PlannedMotionOptions o;
  o.robot = p.robot;
  o.waypoints = p.waypoints;
  o.scene = p.scene;
  o.seed = static_cast<std::uint64_t>(p.seed);
  o.min_sigma = p.min_sigma;
  o.tracking.controller = p.controller;
  o.tracking.settle_time = p.settle_time;
  o.tracking.control_period = p.control_period;
  o.tracking.max_acceleration = p.max_acceleration;
  return o;
}

namespace {

/// The planned motion keeps no recording or video yet: said, not refused (a sweep's failed
/// trial asks for them).
void note_outputs(TrialOutcome& out, const ScenarioOutputs& outputs) {
  if (!outputs.record.empty()) out.recording_error = "plan: no recording yet";
  if (!outputs.video.empty()) out.video_error = "plan: no video yet";
}

class PlanScenario final : public DeclaredScenario<PlanParameters> {
 public:
  std::string_view name() const override { return "plan"; }
  std::string_view doc() const override {
    return "plan through the Cartesian waypoints of a file and track the plan under a torque "
           "controller";
  }
  std::string_view camera() const override { return "none: this scenario films nothing yet"; }
  const std::vector<MetricInfo>& metrics() const override {
    static const std::vector<MetricInfo> list{
        {"duration", "s", Better::lower, "the plan's duration"},
        {"max_position_error", "m", Better::lower, "largest tool distance from the plan"},
        {"rms_position_error", "m", Better::lower, "RMS tool distance from the plan"},
        {"final_position_error", "m", Better::lower, "at the end"},
        {"max_orientation_error", "rad", Better::lower, "largest tool rotation from the plan"},
        {"final_orientation_error", "rad", Better::lower, "at the end"}};
    return list;
  }
  const std::vector<std::string>& verdicts() const override {
    static const std::vector<std::string> list{"tracked",  "not_planned", "collided",
                                               "diverged", "bad_command", "interrupted"};
    return list;
  }

  TrialOutcome run_trial(const PlanParameters& p, const ScenarioOutputs& outputs) const override {
    if (p.waypoints.empty()) throw Error("plan: the parameter waypoints names no file");
    const PlannedMotionReport r = run_planned_motion(planned_motion_options(p));
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    if (!r.planned()) {
      TrialOutcome out;
      out.verdict = "not_planned";
      out.message = r.plan.result.message;
      out.metrics.assign(metrics().size(), nan);
      note_outputs(out, outputs);
      return out;
    }
    const RunResult& run = r.tracked.run;
    const bool touched = r.tracked.contacts.any();
    const bool tracked = run.ok() && !touched;
    TrialOutcome out = detail::outcome_of(
        run, tracked ? "tracked" : (run.ok() ? "collided" : to_string(run.status)), tracked);
    if (run.ok() && touched)
      out.message = "the robot touched " + r.tracked.contacts.first_pair +
                    " at t = " + std::to_string(r.tracked.contacts.first_time) + " s";
    const TrackingError& e = r.tracked.tracking;
    out.metrics = {r.plan.result.trajectory.duration(),
                   e.max_position,
                   e.rms_position,
                   e.final_position,
                   e.max_orientation,
                   e.final_orientation};
    note_outputs(out, outputs);
    return out;
  }
};

}  // namespace

const DeclaredScenario<PlanParameters>& plan_scenario() {
  static const PlanScenario scenario;
  return scenario;
}

}  // namespace mjarm
