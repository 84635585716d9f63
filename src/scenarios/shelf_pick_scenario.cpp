#include "mjarm/scenarios/shelf_pick_scenario.hpp"

#include "mjarm/error.hpp"
#include "scenarios/scenario_parts.hpp"

namespace mjarm {

ShelfPickOptions shelf_pick_options(const ShelfPickParameters& p) {
  ShelfPickOptions o;
  apply(p, o);
  return o;
}

ShelfPickParameters shelf_pick_parameters(const ShelfPickOptions& o) {
  ShelfPickParameters p;
  p.robot = o.request.robot;
  p.controller = o.request.controller;
  p.seed = static_cast<std::int64_t>(o.request.seed);
  p.pick = o.request.pick;
  p.criteria = o.request.criteria;
  p.control_period = o.control_period;
  p.max_acceleration = o.max_acceleration;
  p.gain_scale = o.gain_scale;
  p.settle_time = o.settle_time;
  return p;
}

void apply(const ShelfPickParameters& p, ShelfPickOptions& o) {
  o.request.robot = p.robot;
  o.request.controller = p.controller;
  o.request.seed = static_cast<std::uint64_t>(p.seed);
  o.request.pick = p.pick;
  o.request.criteria = p.criteria;
  o.control_period = p.control_period;
  o.max_acceleration = p.max_acceleration;
  o.settle_time = p.settle_time;
  o.gain_scale = p.gain_scale;
}

namespace {

class ShelfPickScenario final : public DeclaredScenario<ShelfPickParameters> {
 public:
  std::string_view name() const override { return "shelf-pick"; }
  std::string_view doc() const override {
    return "reach a point in a shelf and hold the tool there under a torque controller";
  }
  std::string_view camera() const override {
    return "a free camera framing the robot and the pick point; 'follow': the tool tip";
  }
  const std::vector<MetricInfo>& metrics() const override {
    static const std::vector<MetricInfo> list{
        {"time_to_tolerance", "s", Better::lower, "start of the stay that completed the hold"},
        {"overshoot", "m", Better::lower, "largest distance past the target"},
        {"steady_state_mean", "m", Better::lower, "mean error over the end of the hold"},
        {"steady_state_max", "m", Better::lower, "largest error over the end of the hold"},
        {"hold_mean", "m", Better::lower, "mean error over the whole hold"},
        {"orientation_error_max", "rad", Better::lower, "largest orientation error in the hold"},
        {"final_error", "m", Better::lower, "error at the end"},
        {"exits", "", Better::lower, "exits from the tolerance"},
        {"saturated_ticks", "", Better::lower, "most ticks one motor was clipped"}};
    return list;
  }
  const std::vector<std::string>& verdicts() const override {
    static const std::vector<std::string> list = enum_names<PickOutcome>();
    return list;
  }

  TrialOutcome run_trial(const ShelfPickParameters& p,
                         const ScenarioOutputs& outputs) const override {
    ShelfPickOptions options = shelf_pick_options(p);
    options.record = outputs.record;
    if (!outputs.video.empty()) {
      options.video.path = outputs.video;
      options.video.camera = detail::one_camera(outputs, name());
      options.video.options = detail::video_options(outputs);
    }
    const ShelfPickReport r = run_shelf_pick(options);
    const PickMetrics& m = r.metrics;
    TrialOutcome out = detail::outcome_of(r.run, to_string(r.outcome), r.ok());
    out.metrics = {m.time_to_tolerance,
                   m.overshoot,
                   m.steady_state_mean,
                   m.steady_state_max,
                   m.hold_mean,
                   m.orientation_error_max,
                   m.final_error,
                   static_cast<double>(m.exits),
                   static_cast<double>(r.saturated_ticks)};
    detail::take_outputs(out, r.recording, r.recording_error, r.video_error);
    if (r.video_written) out.videos.push_back(r.video);
    return out;
  }
};

}  // namespace

const DeclaredScenario<ShelfPickParameters>& shelf_pick_scenario() {
  static const ShelfPickScenario scenario;
  return scenario;
}

}  // namespace mjarm
