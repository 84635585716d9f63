#include "mjarm/tasks/wiping/wiping.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "mjarm/control/cartesian_impedance.hpp"
#include "mjarm/control/operational_space.hpp"
#include "mjarm/error.hpp"
#include "mjarm/sim/recorder.hpp"
#include "mjarm/sim/simulation.hpp"
#include "tasks/run_outputs.hpp"
#include "tasks/torque_run_loop.hpp"

namespace mjarm {

namespace {

std::unique_ptr<Controller> wiping_controller(const WipingScene& scene, const WipingControl& c) {
  Vector6d K;
  K << c.lateral_stiffness, c.lateral_stiffness, c.normal_stiffness, c.rotational_stiffness,
      c.rotational_stiffness, c.rotational_stiffness;
  if (c.law == WipingLaw::osc) {
    OperationalSpaceOptions o;
    o.stiffness = K;
    o.damping_ratio = c.damping_ratio;
    o.inertia << Eigen::Vector3d::Constant(c.desired_inertia[0]),
        Eigen::Vector3d::Constant(c.desired_inertia[1]);
    o.nullspace_stiffness = c.nullspace_stiffness;
    return std::make_unique<OperationalSpaceController>(scene.chain, o);
  }
  CartesianImpedanceOptions o;
  o.stiffness = K;
  o.damping_ratio = c.damping_ratio;
  o.nullspace_stiffness = c.nullspace_stiffness;
  o.force.kind = WrenchSourceKind::sensor;
  o.force.site = WipingNames::ft_site;
  return std::make_unique<CartesianImpedanceController>(scene.chain, o);
}

CameraSpec wiping_camera(const WipingPlan& plan, const std::string& camera) {
  if (camera.empty()) {
    const Eigen::Vector3d middle = plan.start + 0.5 * plan.length * plan.direction;
    return CameraSpec::free_camera(middle, 0.9, 150.0, -25.0);
  }
  if (camera == "follow") return CameraSpec::follow(WipingNames::tip, 0.4, 150.0, -20.0);
  throw Error("wiping video: no camera '" + camera +
              "' in the wiping scene; use \"\" (beside the table) or \"follow\"");
}

/// Sums over the stroke's ticks, then the metrics.
class WipingMonitor {
 public:
  WipingMonitor(const WipingScene& scene, const WipingPlan& plan) : scene_(scene), plan_(plan) {}

  /// The step just taken (its contacts and constraint forces are consistent with site_xpos).
  void sample(const Simulation& sim, const WipingTask& task, bool saturated) {
    const mjModel& m = sim.model();
    const mjData& d = sim.data();
    ++ticks_;
    if (saturated) ++saturated_;
    const ContactSummary pad = contact_between(m, d, scene_.tool, scene_.table);
    m_.peak_force = std::max(m_.peak_force, pad.normal_force);
    if (contact_between(m, d, scene_.arm, scene_.table, false).contacts > 0) m_.arm_contact = true;
    if (task.phase() != WipingPhase::stroke) return;
    ++m_.samples;
    const double error = pad.normal_force - task.desired_force();
    force_squares_ += error * error;
    m_.force_max_error = std::max(m_.force_max_error, std::abs(error));
    force_sum_ += pad.normal_force;
    if (pad.contacts > 0) ++contact_;
    const Eigen::Map<const Eigen::Vector3d> p(d.site_xpos + 3 * scene_.chain.frame().id);
    const Eigen::Vector3d r = p - plan_.start;
    const double cross = std::abs(r.x() * plan_.direction.y() - r.y() * plan_.direction.x());
    path_squares_ += cross * cross;
    m_.path_max_error = std::max(m_.path_max_error, cross);
  }

  WipingMetrics metrics() const {
    WipingMetrics m = m_;
    if (m.samples > 0) {
      const double n = m.samples;
      m.force_rms_error = std::sqrt(force_squares_ / n);
      m.mean_force = force_sum_ / n;
      m.path_rms_error = std::sqrt(path_squares_ / n);
      m.contact_fraction = contact_ / n;
    }
    m.saturation = ticks_ > 0 ? static_cast<double>(saturated_) / ticks_ : 0.0;
    return m;
  }

 private:
  const WipingScene& scene_;
  const WipingPlan& plan_;
  WipingMetrics m_;
  std::int64_t ticks_ = 0, saturated_ = 0;
  double force_squares_ = 0.0, force_sum_ = 0.0, path_squares_ = 0.0, contact_ = 0.0;
};

WipingOutcome wiping_outcome(const RunResult& run, const WipingMetrics& m,
                             const WipingCriteria& c) {
  switch (run.status) {
    case RunStatus::diverged:
      return WipingOutcome::diverged;
    case RunStatus::bad_command:
      return WipingOutcome::bad_command;
    case RunStatus::interrupted:
      return WipingOutcome::interrupted;
    case RunStatus::finished:
    case RunStatus::duration_reached:
      break;
  }
  if (m.arm_contact) return WipingOutcome::collided;
  if (!(m.contact_fraction >= c.min_contact_fraction)) return WipingOutcome::lost_contact;
  if (!(m.force_rms_error <= c.force_tolerance)) return WipingOutcome::force_off;
  if (!(m.path_max_error <= c.path_tolerance)) return WipingOutcome::off_path;
  return WipingOutcome::wiped;
}

}  // namespace

std::string wiping_result_line(const WipingReport& r) {
  const WipingMetrics& m = r.metrics;
  char line[320];
  std::snprintf(line, sizeof line,
                "%s: force_rms_error=%.3g N mean_force=%.4g N path_max_error=%.3g mm "
                "contact=%.1f%% peak_force=%.4g N",
                to_string(r.outcome), m.force_rms_error, m.mean_force, m.path_max_error * 1e3,
                100.0 * m.contact_fraction, m.peak_force);
  return line;
}

WipingReport run_wiping(const WipingOptions& options) {
  check_fields(options.control);
  check_fields(options.criteria);
  check_fields(options.force_loop);
  check_value(options.max_acceleration, "wiping", "max_acceleration", "rad/s²", Range::positive());
  std::shared_ptr<const WipingScene> scene = options.scene;
  if (!scene)
    scene = std::make_shared<const WipingScene>(build_wiping_scene(options.surface));
  else if (!same_surface(scene->surface, options.surface))
    throw Error("wiping: the scene given was built for another surface than the options ask for");
  WipingReport report{.plan = plan_wiping(*scene, options.path, options.motion, options.seed)};

  Simulation sim(scene->robot, torque_run::torque_simulation(options.max_acceleration));
  const std::unique_ptr<Controller> controller = wiping_controller(*scene, options.control);
  sim.add_controller(*controller);
  std::vector<double> qpos(static_cast<std::size_t>(scene->robot.nq()), 0.0);
  scene->chain.scatter(report.plan.q_start, qpos.data());
  sim.set_state(qpos, std::vector<double>(static_cast<std::size_t>(scene->robot.nv()), 0.0));
  torque_run::start_held(sim, scene->chain);

  std::optional<RunVideo> video;
  if (!options.video.empty()) {
    video.emplace(scene->robot, sim.data(), options.video,
                  wiping_camera(report.plan, options.camera), options.video_options);
    report.video = options.video;
  }
  std::optional<Recorder> recorder;
  if (!options.record.empty()) {
    recorder.emplace(sim, options.record);
    report.recording = recorder->directory();
  }
  WipingTask task(*scene, report.plan, options.motion, options.force_loop, options.seed,
                  recorder ? &*recorder : nullptr);
  if (video) task.set_observer(&*video);
  WipingMonitor monitor(*scene, report.plan);
  report.run = torque_run::run_ticks(sim, task, recorder ? &*recorder : nullptr, "wiping", [&] {
    const std::span<const std::uint8_t> saturated = sim.saturated();
    monitor.sample(sim, task, std::any_of(saturated.begin(), saturated.end(), [](std::uint8_t s) {
                     return s != 0;
                   }));
  });
  report.metrics = monitor.metrics();
  report.outcome = wiping_outcome(report.run, report.metrics, options.criteria);
  if (recorder)
    report.recording_error =
        finish_recording(*recorder, sim.time(), wiping_result_line(report), report.run);
  if (video) {
    report.video_error = finish_video(*video, sim.data());
    report.video_written = video->complete();
  }
  return report;
}

}  // namespace mjarm
