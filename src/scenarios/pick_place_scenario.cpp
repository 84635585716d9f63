#include "mjarm/scenarios/pick_place_scenario.hpp"

#include "scenarios/scenario_parts.hpp"

namespace mjarm {

PickPlaceOptions pick_place_options(const PickPlaceParameters& p) {
  PickPlaceOptions o;
  apply(p, o);
  return o;
}

PickPlaceParameters pick_place_parameters(const PickPlaceOptions& o) {
  PickPlaceParameters p;
  p.robot = o.robot;
  p.grasp = o.grasp;
  p.mode = o.mode;
  p.seed = static_cast<std::int64_t>(o.seed);
  p.object = o.object_position;
  p.target = o.target_position;
  p.object_size = o.object_half_size;
  p.classic = o.classic;
  p.ranges = o.ranges;
  p.motion = o.motion;
  p.criteria = o.criteria;
  p.weld = o.weld;
  p.grasp_force = o.grasp_force;
  p.noslip = o.noslip_iterations;
  p.impratio = o.impratio;
  p.control_period = o.control_period;
  p.max_acceleration = o.max_acceleration;
  return p;
}

void apply(const PickPlaceParameters& p, PickPlaceOptions& o) {
  o.robot = p.robot;
  o.grasp = p.grasp;
  o.mode = p.mode;
  o.seed = static_cast<std::uint64_t>(p.seed);
  o.object_position = p.object;
  o.target_position = p.target;
  o.object_half_size = p.object_size;
  o.classic = p.classic;
  o.ranges = p.ranges;
  o.motion = p.motion;
  o.criteria = p.criteria;
  o.weld = p.weld;
  o.grasp_force = p.grasp_force;
  o.noslip_iterations = p.noslip;
  o.impratio = p.impratio;
  o.control_period = p.control_period;
  o.max_acceleration = p.max_acceleration;
}

namespace {

class PickPlaceScenario final : public DeclaredScenario<PickPlaceParameters> {
 public:
  std::string_view name() const override { return "pick-place"; }
  std::string_view doc() const override {
    return "pick a cube from the table and place it on a target, judged on every criterion";
  }
  std::string_view camera() const override {
    return "the scene's 'front' camera; others: side, top, follow (several are tiled)";
  }
  const std::vector<MetricInfo>& metrics() const override {
    static const std::vector<MetricInfo> list{
        {"cycle_time", "s", Better::lower, "start to DONE"},
        {"placement_error", "m", Better::lower, "horizontal, object to target, at the end"},
        {"final_speed", "m/s", Better::lower, "object speed at the end"},
        {"tilt", "rad", Better::lower, "object tilt at the end"},
        {"max_slip", "m", Better::lower, "largest slip in the gripper during the transport"},
        {"transport_force_mean", "N", Better::higher, "mean grasp force during the transport"},
        {"weld_jump", "m", Better::lower, "how far switching the weld on moved the object"},
        {"longest_saturation", "s", Better::lower, "longest time one actuator stayed clipped"}};
    return list;
  }
  const std::vector<std::string>& verdicts() const override {
    static const std::vector<std::string> list = [] {
      std::vector<std::string> names{"placed"};
      for (const std::string& name : enum_names<PickPlaceFailure>())
        if (name != to_string(PickPlaceFailure::none)) names.push_back(name);
      return names;
    }();
    return list;
  }

  TrialOutcome run_trial(const PickPlaceParameters& p,
                         const ScenarioOutputs& outputs) const override {
    PickPlaceOptions options = pick_place_options(p);
    options.record = outputs.record;
    if (!outputs.video.empty()) {
      options.video.path = outputs.video;
      options.video.cameras = outputs.cameras;
      options.video.options = detail::video_options(outputs);
    }
    const PickPlaceReport r = run_pick_place(options);
    const PickPlaceTrace& t = r.trace;
    TrialOutcome out =
        detail::outcome_of(r.run, r.success ? "placed" : to_string(r.failure), r.success);
    if (!r.success) out.message = r.reason;
    out.metrics = {r.cycle_time,  r.placement_error,
                   r.final_speed, r.tilt,
                   t.max_slip,    t.transport_force_mean,
                   t.weld_jump,   static_cast<double>(t.longest_saturation) * r.control_period};
    detail::take_outputs(out, r.recording, r.recording_error, r.video_error);
    out.videos = r.videos_written;
    return out;
  }
};

}  // namespace

const DeclaredScenario<PickPlaceParameters>& pick_place_scenario() {
  static const PickPlaceScenario scenario;
  return scenario;
}

}  // namespace mjarm
