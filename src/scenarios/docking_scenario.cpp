#include "mjarm/scenarios/docking_scenario.hpp"

#include <limits>

#include "scenarios/scenario_parts.hpp"

namespace mjarm {

DockingOptions docking_options(const DockingParameters& p) {
  DockingOptions o;
  apply(p, o);
  o.keep_samples = false;
  return o;
}

DockingParameters docking_parameters(const DockingOptions& o) {
  return {o.controller,     o.offset,   o.motion,          o.criteria,
          o.joint_friction, o.geometry, o.max_acceleration};
}

void apply(const DockingParameters& p, DockingOptions& o) {
  o.controller = p.controller;
  o.offset = p.offset;
  o.motion = p.motion;
  o.criteria = p.criteria;
  o.joint_friction = p.joint_friction;
  o.geometry = p.geometry;
  o.max_acceleration = p.max_acceleration;
}

namespace {

/// The scene of each variant and geometry, shared by the trials that use it.
std::shared_ptr<const DockingScene> scene_of(bool joint_friction, const DockingGeometry& g) {
  static detail::SceneCache<DockingScene> scenes;
  return scenes.get(
      [&](const DockingScene& s) {
        return s.options.joint_friction == joint_friction && same_geometry(s.options.geometry, g);
      },
      [&] { return shared_docking_scene(nullptr, joint_friction, g); });
}

class DockingScenario final : public DeclaredScenario<DockingParameters> {
 public:
  std::string_view name() const override { return "docking"; }
  std::string_view doc() const override {
    return "insert a peg into a chamfered socket whose believed pose is off, under compliance";
  }
  std::string_view camera() const override {
    return "a free camera close to the socket from the front right; 'follow': the peg tip";
  }
  const std::vector<MetricInfo>& metrics() const override {
    static const std::vector<MetricInfo> list{
        {"peak_force", "N", Better::lower, "largest contact force"},
        {"peak_axial_force", "N", Better::lower, "largest force pushing in"},
        {"steady_axial_force", "N", Better::lower, "mean force pushing in over the final window"},
        {"steady_lateral", "m", Better::lower, "mean tip distance to the bore axis at the end"},
        {"steady_tilt", "rad", Better::lower, "mean peg tilt to the bore axis at the end"},
        {"min_depth", "m", Better::higher, "least tip depth below the top face at the end"},
        {"first_contact_time", "s", Better::lower, "first peg-socket contact"},
        {"position_rms", "m", Better::lower, "tracking error in free motion"},
        {"saturation", "", Better::lower, "fraction of ticks with a clipped motor"}};
    return list;
  }
  const std::vector<std::string>& verdicts() const override {
    static const std::vector<std::string> list = enum_names<DockingOutcome>();
    return list;
  }

  TrialOutcome run_trial(const DockingParameters& p,
                         const ScenarioOutputs& outputs) const override {
    DockingOptions options = docking_options(p);
    options.scene = scene_of(p.joint_friction, p.geometry);
    options.record = outputs.record;
    if (!outputs.video.empty()) {
      options.video.path = outputs.video;
      options.video.camera = detail::one_camera(outputs, name());
      options.video.options = detail::video_options(outputs);
    }
    const DockingReport r = run_docking(options);
    const DockingMetrics& m = r.metrics;
    TrialOutcome out = detail::outcome_of(r.run, to_string(r.outcome), r.ok());
    if (r.outcome == DockingOutcome::not_seated) out.message = docking_result_line(r);
    out.metrics = {m.peak_force,         m.peak_axial_force, m.steady_axial_force,
                   m.steady_lateral,     m.steady_tilt,      m.min_depth,
                   m.first_contact_time, m.position_rms,     m.saturation};
    detail::take_outputs(out, r.recording, r.recording_error, r.video_error);
    if (r.video_written) out.videos.push_back(r.video);
    return out;
  }
};

}  // namespace

const DeclaredScenario<DockingParameters>& docking_scenario() {
  static const DockingScenario scenario;
  return scenario;
}

}  // namespace mjarm
