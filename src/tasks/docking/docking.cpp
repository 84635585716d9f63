#include "mjarm/tasks/docking/docking.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/model/names.hpp"
#include "mjarm/sim/recorder.hpp"
#include "mjarm/sim/simulation.hpp"
#include "tasks/run_outputs.hpp"
#include "tasks/torque_run_loop.hpp"

namespace mjarm {

CameraSpec docking_camera(const DockingScene& scene, std::string_view camera) {
  const Eigen::Vector3d top = scene.options.X_WS.p;
  if (camera.empty())  // close to the socket, from the front right and above
    return CameraSpec::free_camera(top + Eigen::Vector3d(0.0, 0.0, 0.03), 0.5, 150.0, -30.0);
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

}  // namespace

DockingReport run_docking(const DockingOptions& options) {
  check(options.criteria);
  check(options.controller);
  const std::shared_ptr<const DockingScene> scene =
      shared_docking_scene(options.scene, options.joint_friction, options.geometry);
  DockingReport report{.plan = plan_docking(*scene, options.offset, options.motion)};
  report.controller = to_string(options.controller.law);
  report.source = options.controller.source;
  report.joint_friction = options.joint_friction;

  Simulation sim(scene->robot, torque_run::torque_simulation(options.max_acceleration));
  DockingControllerOptions controller_options = options.controller;
  controller_options.control_period = sim.control_period();
  DockingController controller(*scene, controller_options);
  sim.add_controller(controller);
  std::vector<double> qpos(static_cast<std::size_t>(scene->robot.nq()), 0.0);
  scene->chain.scatter(report.plan.q_start, qpos.data());
  const std::vector<double> qvel(static_cast<std::size_t>(scene->robot.nv()), 0.0);
  sim.set_state(qpos, qvel);
  torque_run::start_held(sim, scene->chain);
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

  // the centring tells the wall by the reference running ahead of the peg: with joint friction
  // the laws track to about a millimetre, more than the clearance, and it would find walls mid-bore
  DockingMotion motion = options.motion;
  if (options.joint_friction) motion.centring.enabled = false;
  DockingTask task(report.plan, motion, sim.uses_rk4() ? 0.0 : 0.5 * sim.timestep(),
                   recorder ? &*recorder : nullptr);
  if (video) task.set_observer(&*video);
  task.attach(controller, mj_name2id(&sim.model(), mjOBJ_SITE, DockingNames::tip));
  DockingProbe probe(*scene, iiwa14_max_velocity());
  std::vector<DockingSample> samples;
  samples.reserve(static_cast<std::size_t>(task.max_duration() / sim.control_period()) + 8);
  DockingSample sample;
  report.run = torque_run::run_ticks(sim, task, recorder ? &*recorder : nullptr, "docking", [&] {
    const std::span<const std::uint8_t> saturated = sim.saturated();
    const bool any =
        std::any_of(saturated.begin(), saturated.end(), [](std::uint8_t s) { return s != 0; });
    // the step just taken: its state is the one at d.time − timestep
    probe.sample(sim.model(), sim.data(), sim.time() - sim.timestep() - task.start_time(),
                 task.reference_pose(), any, sample);
    sample.F_measured = controller.measured_wrench();
    sample.stiffness = controller.stiffness();
    samples.push_back(sample);
  });

  const DockingGoal goal{report.plan.X_WS, report.plan.full_depth};
  report.metrics = evaluate_docking(samples, goal, options.criteria);
  report.bad_wrench_ticks = controller.bad_wrench_ticks();
  if (const HqpAcController* hqp = controller.hqp_ac()) {
    report.qp_least_squares = hqp->counters().least_squares;
    report.qp_null_space_dropped = hqp->counters().null_space_dropped;
  }
  report.outcome = docking_outcome_of(report.run, report.metrics.seated);
  report.searches = task.searches();
  report.search_time = task.search_time();
  report.miss_time = task.miss_time();
  report.drop_time = task.drop_time();
  report.hold_start = task.hold_start();
  report.seat_time = std::numeric_limits<double>::quiet_NaN();
  for (const DockingSample& s : samples)
    if (docking_insertion(s.X_WE, goal.X_WS).depth >=
        goal.full_depth - options.criteria.depth_tolerance) {
      report.seat_time = s.t;
      break;
    }
  if (task.search_exhausted() && report.outcome == DockingOutcome::not_seated) {
    report.outcome = DockingOutcome::search_exhausted;
    report.metrics.failures.push_back(to_string(report.outcome));
  }
  if (report.run.status != RunStatus::finished && report.run.status != RunStatus::duration_reached)
    report.metrics.failures.push_back(to_string(report.outcome));
  if (options.keep_samples) report.samples = std::move(samples);
  if (recorder)
    report.recording_error =
        finish_recording(*recorder, sim.time(), docking_result_line(report), report.run);
  if (video) {
    report.video_error = finish_video(*video, sim.data());
    report.video_frames = video->frames();
    report.video_written = video->complete();
  }
  return report;
}

}  // namespace mjarm
