#include "mjarm/scenarios/wiping_scenario.hpp"

#include "scenarios/scenario_parts.hpp"

namespace mjarm {

WipingOptions wiping_options(const WipingParameters& p) {
  WipingOptions o;
  o.control = p.control;
  o.motion = p.motion;
  o.path = p.path;
  o.force_loop = p.force_loop;
  o.surface = p.surface;
  o.criteria = p.criteria;
  o.seed = static_cast<std::uint64_t>(p.seed);
  o.max_acceleration = p.max_acceleration;
  return o;
}

namespace {

/// The scene of each surface, shared by the trials that use it.
std::shared_ptr<const WipingScene> scene_of(const WipingSurface& surface) {
  static detail::SceneCache<WipingScene> scenes;
  return scenes.get(
      [&](const WipingScene& s) { return same_surface(s.surface, surface); },
      [&] { return std::make_shared<const WipingScene>(build_wiping_scene(surface)); });
}

class WipingScenario final : public DeclaredScenario<WipingParameters> {
 public:
  std::string_view name() const override { return "wiping"; }
  std::string_view doc() const override {
    return "wipe a straight stroke on a table at a constant normal force with a force controller";
  }
  std::string_view camera() const override {
    return "a free camera beside the table; 'follow': the tool's tip";
  }
  const std::vector<MetricInfo>& metrics() const override {
    static const std::vector<MetricInfo> list{
        {"force_rms_error", "N", Better::lower, "RMS of the normal force's error over the stroke"},
        {"force_max_error", "N", Better::lower, "largest normal force error over the stroke"},
        {"path_rms_error", "m", Better::lower, "RMS cross-track distance of the tip"},
        {"path_max_error", "m", Better::lower, "largest cross-track distance of the tip"},
        {"contact_fraction", "", Better::higher, "of the stroke's ticks with the pad on the table"},
        {"peak_force", "N", Better::lower, "largest normal force of the run"},
        {"saturation", "", Better::lower, "fraction of ticks with a clipped motor"}};
    return list;
  }
  const std::vector<std::string>& verdicts() const override {
    static const std::vector<std::string> list = enum_names<WipingOutcome>();
    return list;
  }

  TrialOutcome run_trial(const WipingParameters& p, const ScenarioOutputs& outputs) const override {
    WipingOptions options = wiping_options(p);
    options.scene = scene_of(p.surface);
    options.record = outputs.record;
    if (!outputs.video.empty()) {
      options.video = outputs.video;
      options.camera = detail::one_camera(outputs, name());
      options.video_options = detail::video_options(outputs);
    }
    const WipingReport r = run_wiping(options);
    const WipingMetrics& m = r.metrics;
    TrialOutcome out = detail::outcome_of(r.run, to_string(r.outcome), r.ok());
    if (!r.ok()) out.message = wiping_result_line(r);
    out.metrics = {m.force_rms_error,  m.force_max_error, m.path_rms_error, m.path_max_error,
                   m.contact_fraction, m.peak_force,      m.saturation};
    detail::take_outputs(out, r.recording, r.recording_error, r.video_error);
    if (r.video_written) out.videos.push_back(r.video);
    return out;
  }
};

}  // namespace

const DeclaredScenario<WipingParameters>& wiping_scenario() {
  static const WipingScenario scenario;
  return scenario;
}

}  // namespace mjarm
