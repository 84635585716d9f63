#include "mjarm/scenarios/bimanual_lift_scenario.hpp"

#include <algorithm>
#include <limits>
#include <memory>

#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/render/camera.hpp"
#include "mjarm/tasks/run_video.hpp"
#include "mjarm/teleop/session_log.hpp"
#include "mjarm/teleop/teleop_session.hpp"
#include "scenarios/scenario_parts.hpp"

namespace mjarm {

namespace {

/// Thrown from the lift's tick callback to stop it on Ctrl-C.
struct LiftInterrupted {};

class BimanualLiftScenario final : public DeclaredScenario<BimanualLiftParameters> {
 public:
  std::string_view name() const override { return "bimanual-lift"; }
  std::string_view doc() const override {
    return "two hands grasp a bar by its ends, lift it and hold it, through the teleoperation "
           "session";
  }
  std::string_view camera() const override {
    return "a free camera from the front and above, looking between the hands";
  }
  const std::vector<MetricInfo>& metrics() const override {
    static const std::vector<MetricInfo> list{
        {"lifted", "m", Better::higher, "how high the bar rose"},
        {"sag", "m", Better::lower, "largest drop of the bar while held"},
        {"grasp_force_min", "N", Better::higher, "the weaker hand's finger force at the end"},
        {"end_z", "m", Better::higher, "bar height at the end"}};
    return list;
  }
  const std::vector<std::string>& verdicts() const override {
    static const std::vector<std::string> list{"lifted", "not_lifted", "sagged", "diverged",
                                               "interrupted"};
    return list;
  }

  TrialOutcome run_trial(const BimanualLiftParameters& p,
                         const ScenarioOutputs& outputs) const override {
    const Robot robot = Robot::bundled(p.model);
    TeleopOptions options;
    options.mode = p.mode;
    TeleopSession session(robot, options);
    SessionRecorder recorder(session);
    std::unique_ptr<RunVideo> video;
    if (!outputs.video.empty()) {
      if (outputs.cameras.size() > 0)
        throw Error("bimanual-lift films its own camera only, got " + outputs.cameras.front());
      // from the front and above, looking at the middle between the hands
      Eigen::Vector3d lookat = Eigen::Vector3d::Zero();
      for (const auto& h : session.stats().hands) lookat += h.X_WE.p;
      lookat /= static_cast<double>(session.stats().hands.size());
      lookat.z() -= 0.1;
      video = std::make_unique<RunVideo>(
          session.robot(), session.simulation().data(), outputs.video,
          CameraSpec::free_camera(lookat, 2.2, 155.0, -30.0), detail::video_options(outputs));
    }
    TrialOutcome out;
    BimanualLiftResult r;
    try {
      r = run_bimanual_lift(recorder, p.lift, [&](const TeleopSession& s) {
        if (video) video->on_tick(s.simulation().data());
        if (interrupt_requested()) throw LiftInterrupted{};
      });
    } catch (const LiftInterrupted&) {
      out.status = RunStatus::interrupted;
      out.verdict = "interrupted";
      out.message = "interrupted at t = " + std::to_string(session.stats().time) + " s";
    }
    const TeleopStats& stats = session.stats();
    out.end_time = stats.time;
    if (out.status != RunStatus::interrupted) {
      out.success = r.success;
      out.message = r.failure;
      if (stats.faulted) {
        out.status = RunStatus::diverged;
        out.verdict = "diverged";
      } else {
        out.status = RunStatus::finished;
        out.verdict = r.success                                          ? "lifted"
                      : r.lifted < p.lift.lift_height - p.lift.tolerance ? "not_lifted"
                                                                         : "sagged";
      }
      out.metrics = {r.lifted, r.sag, std::min(r.grasp_force[0], r.grasp_force[1]), r.end_z};
    } else {
      out.metrics.assign(metrics().size(), std::numeric_limits<double>::quiet_NaN());
    }
    if (video) {
      try {
        video->finish(session.simulation().data());
        if (video->complete()) out.videos.push_back(outputs.video);
      } catch (const Error& e) {
        out.video_error = e.what();
      }
    }
    if (!outputs.record.empty() && out.status != RunStatus::interrupted) {
      // the replayable session (mjarm replay FILE), in the recording folder
      std::error_code ec;
      std::filesystem::create_directories(outputs.record, ec);
      try {
        write_session_log(recorder.log(), outputs.record / "lift.session");
        out.recording = outputs.record;
      } catch (const Error& e) {
        out.recording_error = e.what();
      }
    }
    return out;
  }
};

}  // namespace

const DeclaredScenario<BimanualLiftParameters>& bimanual_lift_scenario() {
  static const BimanualLiftScenario scenario;
  return scenario;
}

}  // namespace mjarm
