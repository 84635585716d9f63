#include "mjarm/tasks/shelf_pick/shelf_pick.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/sim/recorder.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/tasks/run_video.hpp"
#include "mjarm/tasks/shelf_pick/controllers.hpp"
#include "mjarm/tasks/shelf_pick/task.hpp"
#include "tasks/run_outputs.hpp"

namespace mjarm {

namespace {

PickOutcome outcome_of(const RunResult& run, bool held) {
  switch (run.status) {
    case RunStatus::finished:
      return held ? PickOutcome::held : PickOutcome::not_held;
    case RunStatus::duration_reached:
      return PickOutcome::not_held;
    case RunStatus::diverged:
      return PickOutcome::diverged;
    case RunStatus::bad_command:
      return PickOutcome::bad_command;
    case RunStatus::interrupted:
      return PickOutcome::interrupted;
  }
  return PickOutcome::not_held;
}

/// One line with the figures, for the recording's events.
std::string result_line(const ShelfPickReport& r) {
  const PickMetrics& m = r.metrics;
  char buffer[400];
  std::snprintf(buffer, sizeof buffer,
                "%s: time_to_tolerance=%.6g s overshoot=%.6g m steady_state_mean=%.6g m "
                "steady_state_max=%.6g m hold_mean=%.6g m exits=%d",
                to_string(r.outcome), m.time_to_tolerance, m.overshoot, m.steady_state_mean,
                m.steady_state_max, m.hold_mean, m.exits);
  return buffer;
}

}  // namespace

ShelfPickReport run_shelf_pick(const ShelfPickOptions& options) {
  if (!(options.settle_time > 0.0) || !std::isfinite(options.settle_time))
    throw Error("shelf pick: settle_time must be positive and finite [s], got " +
                number_text(options.settle_time));
  // designated: every other member keeps its default
  ShelfPickReport report{.plan = plan_shelf_pick(options.request)};
  const ShelfPickPlan& plan = report.plan;

  SimulationOptions sim_options;
  sim_options.mode = SimulationMode::torque;
  sim_options.control_period = options.control_period;
  sim_options.max_acceleration = options.max_acceleration;
  Simulation sim(plan.model, sim_options);
  const std::unique_ptr<Controller> controller =
      make_shelf_pick_controller(plan.controller, plan.chain, *plan.robot, options.gain_scale);
  sim.add_controller(*controller);
  const std::vector<double> qvel(static_cast<std::size_t>(plan.model.nv()), 0.0);
  sim.set_state(plan.qpos_start, qvel);
  report.control_period = sim.control_period();

  // the video and the recorder open (and fail) before the first step
  std::optional<RunVideo> video;
  if (!options.video.path.empty()) {
    const ShelfPickVideo& v = options.video;
    const CameraSpec camera =
        shelf_pick_camera(plan, sim.data(), v.camera,
                          static_cast<double>(v.options.width) / std::max(v.options.height, 1));
    RunVideoOptions video_options = v.options;
    RenderMarker pick;
    pick.position = plan.pick;
    video_options.render.markers.push_back(pick);
    video.emplace(plan.model, sim.data(), v.path, camera, video_options);
    report.video = v.path;
    report.video_camera = camera.describe();
  }
  std::optional<Recorder> recorder;
  if (!options.record.empty()) {
    RecorderOptions recorder_options;
    recorder_options.state_decimation = options.state_decimation;
    recorder_options.seed = options.request.seed;
    recorder.emplace(sim, options.record, recorder_options);
    report.recording = recorder->directory();
  }

  ShelfPickGoal goal = plan.goal;
  goal.velocity_lag = sim.uses_rk4() ? 0.0 : 0.5 * sim.timestep();
  ShelfPickTask task(plan.chain, goal, recorder ? &*recorder : nullptr);
  if (video) task.set_observer(&*video);
  report.time_limit = plan.goal.approach_time + options.settle_time + plan.goal.criteria.hold_time;
  const RunResult& run = report.run =
      sim.run(task, report.time_limit, recorder ? &*recorder : nullptr);

  report.metrics = task.metrics();
  report.final_phase = task.phase();
  report.outcome = outcome_of(run, task.metrics().held);
  for (std::int64_t count : sim.saturation_counts())
    report.saturated_ticks = std::max(report.saturated_ticks, count);
  if (recorder)
    report.recording_error = finish_recording(*recorder, sim.time(), result_line(report), run);
  if (video) {
    report.video_error = finish_video(*video, sim.data());
    report.video_frames = video->frames();
    report.video_written = video->complete();
  }
  return report;
}

}  // namespace mjarm
