#include "mjarm/tasks/docking.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"
#include "mjarm/sim/interrupt.hpp"
#include "mjarm/sim/recorder.hpp"
#include "mjarm/sim/simulation.hpp"

namespace mjarm {

const char* to_string(DockingOutcome outcome) noexcept {
  switch (outcome) {
    case DockingOutcome::seated:
      return "seated";
    case DockingOutcome::not_seated:
      return "not_seated";
    case DockingOutcome::diverged:
      return "diverged";
    case DockingOutcome::bad_command:
      return "bad_command";
    case DockingOutcome::interrupted:
      return "interrupted";
  }
  return "unknown";
}

CameraSpec docking_camera(const DockingScene& scene, std::string_view camera) {
  const Eigen::Vector3d top = scene.options.X_WS.p;
  if (camera.empty())  // close to the socket, from the front right and a little above
    return CameraSpec::free_camera(top + Eigen::Vector3d(0.0, 0.0, 0.03), 0.45, 150.0, -15.0);
  if (camera == "follow") return CameraSpec::follow(DockingNames::tip, 0.35, 150.0, -15.0);
  const Robot& robot = scene.robot;
  for (int c = 0; c < robot.model().ncam; ++c)
    if (const char* name = mj_id2name(&robot.model(), mjOBJ_CAMERA, c); name && camera == name)
      return CameraSpec::model_camera(std::string(camera));
  throw Error("docking video: no camera '" + std::string(camera) +
              "' in the docking scene (it has no cameras of its own); use \"\" (the default view) "
              "or \"follow\"");
}

std::string docking_result_line(const DockingReport& r) {
  const DockingMetrics& m = r.metrics;
  std::string failures;
  for (const std::string& f : m.failures) failures += (failures.empty() ? "" : ",") + f;
  char buffer[512];
  std::snprintf(buffer, sizeof buffer,
                "%s: peak_force=%.4g N steady_axial_force=%.4g N lateral=%.4g mm tilt=%.4g deg "
                "depth=%.4g mm failures=%s",
                to_string(r.outcome), m.peak_force, m.steady_axial_force, m.max_lateral * 1e3,
                m.max_tilt * 180.0 / 3.14159265358979323846, m.min_depth * 1e3,
                failures.empty() ? "none" : failures.c_str());
  return buffer;
}

namespace {

DockingOutcome docking_outcome_of(const RunResult& run, bool seated) {
  switch (run.status) {
    case RunStatus::finished:
    case RunStatus::duration_reached:
      return seated ? DockingOutcome::seated : DockingOutcome::not_seated;
    case RunStatus::diverged:
      return DockingOutcome::diverged;
    case RunStatus::bad_command:
      return DockingOutcome::bad_command;
    case RunStatus::interrupted:
      return DockingOutcome::interrupted;
  }
  return DockingOutcome::not_seated;
}

/// The run loop: `Simulation::run` with a sample of the ground truth after every tick (the
/// contacts and constraint forces of the step just taken are consistent only then).
RunResult run_loop(Simulation& sim, DockingTask& task, DockingProbe& probe,
                   const DockingController& controller, Recorder* recorder,
                   std::vector<DockingSample>& samples) {
  RunResult run;
  run.start_time = sim.time();
  const std::int64_t ticks0 = sim.ticks();
  const std::int64_t steps0 = sim.physics_steps();
  DockingSample sample;
  for (;;) {
    if (interrupt_requested()) {
      run.status = RunStatus::interrupted;
      break;
    }
    const TickResult tick = sim.tick(task, recorder);
    if (!tick.ok()) {
      run.fault = tick.fault;
      run.status = tick.status == TickStatus::finished   ? RunStatus::finished
                   : tick.status == TickStatus::diverged ? RunStatus::diverged
                                                         : RunStatus::bad_command;
      break;
    }
    const std::span<const std::uint8_t> saturated = sim.saturated();
    const bool any =
        std::any_of(saturated.begin(), saturated.end(), [](std::uint8_t s) { return s != 0; });
    // the step's state is the one at d.time − timestep
    probe.sample(sim.model(), sim.data(), sim.time() - sim.timestep() - task.start_time(),
                 task.reference_pose(), any, sample);
    sample.F_measured = controller.measured_wrench();
    sample.stiffness = controller.stiffness();
    samples.push_back(sample);
  }
  run.end_time = sim.time();
  run.ticks = sim.ticks() - ticks0;
  run.physics_steps = sim.physics_steps() - steps0;
  char line[160];
  switch (run.status) {
    case RunStatus::finished:
    case RunStatus::duration_reached:
      std::snprintf(line, sizeof line, "docking finished at t = %.3f s (%lld control ticks)",
                    run.end_time, static_cast<long long>(run.ticks));
      run.message = line;
      break;
    case RunStatus::interrupted:
      std::snprintf(line, sizeof line, "interrupted by a signal at t = %.3f s", run.end_time);
      run.message = line;
      if (recorder != nullptr) recorder->event(run.end_time, "interrupt", run.message);
      break;
    case RunStatus::diverged:
    case RunStatus::bad_command:
      run.message = sim.describe(run.fault);
      break;
  }
  if (recorder != nullptr) recorder->on_run_end(run);
  return run;
}

}  // namespace

DockingReport run_docking(const DockingOptions& options) {
  check(options.criteria);
  check(options.controller);
  std::shared_ptr<const DockingScene> scene = options.scene;
  if (!scene) {
    DockingSceneOptions scene_options;
    scene_options.joint_friction = options.joint_friction;
    scene = std::make_shared<const DockingScene>(build_docking_scene(scene_options));
  } else if (scene->options.joint_friction != options.joint_friction) {
    throw Error("docking: the scene given was built " +
                std::string(scene->options.joint_friction ? "with" : "without") +
                " joint friction, the options ask for the other variant");
  }
  DockingReport report{.plan = plan_docking(*scene, options.offset, options.motion)};
  report.controller = to_string(options.controller.law);
  report.source = options.controller.source;
  report.joint_friction = options.joint_friction;

  SimulationOptions sim_options;
  sim_options.mode = SimulationMode::torque;
  sim_options.max_acceleration = options.max_acceleration;
  Simulation sim(scene->robot, sim_options);
  DockingControllerOptions controller_options = options.controller;
  controller_options.control_period = sim.control_period();
  DockingController controller(*scene, controller_options);
  sim.add_controller(controller);
  std::vector<double> qpos(static_cast<std::size_t>(scene->robot.nq()), 0.0);
  scene->chain.scatter(report.plan.q_start, qpos.data());
  const std::vector<double> qvel(static_cast<std::size_t>(scene->robot.nv()), 0.0);
  sim.set_state(qpos, qvel);
  report.control_period = sim.control_period();

  std::optional<RunVideo> video;
  if (!options.video.path.empty()) {
    const CameraSpec camera = docking_camera(*scene, options.video.camera);
    video.emplace(scene->robot, sim.data(), options.video.path, camera, options.video.options);
    report.video = options.video.path;
    report.video_camera = camera.describe();
  }
  std::optional<Recorder> recorder;
  if (!options.record.empty()) {
    recorder.emplace(sim, options.record);
    report.recording = recorder->directory();
  }

  DockingTask task(report.plan, options.motion, sim.uses_rk4() ? 0.0 : 0.5 * sim.timestep(),
                   recorder ? &*recorder : nullptr);
  if (video) task.set_observer(&*video);
  DockingProbe probe(*scene, iiwa14_max_velocity());
  std::vector<DockingSample> samples;
  samples.reserve(static_cast<std::size_t>(report.plan.duration() / sim.control_period()) + 8);
  report.run = run_loop(sim, task, probe, controller, recorder ? &*recorder : nullptr, samples);

  const DockingGoal goal{report.plan.X_WS, report.plan.full_depth};
  report.metrics = evaluate_docking(samples, goal, options.criteria);
  report.bad_wrench_ticks = controller.bad_wrench_ticks();
  report.outcome = docking_outcome_of(report.run, report.metrics.seated);
  if (report.run.status != RunStatus::finished && report.run.status != RunStatus::duration_reached)
    report.metrics.failures.push_back(to_string(report.outcome));
  if (options.keep_samples) report.samples = std::move(samples);
  if (recorder) {
    recorder->event(sim.time(), "result", docking_result_line(report));
    try {
      recorder->finalize(report.run);
    } catch (const Error& e) {
      report.recording_error = e.what();
    }
  }
  if (video) {
    try {
      video->finish(sim.data());
    } catch (const Error& e) {
      report.video_error = e.what();
    }
    report.video_frames = video->frames();
  }
  return report;
}

}  // namespace mjarm
