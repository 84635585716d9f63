// The viewer's driver for several hands: a `TeleopSession` behind a `SessionRecorder` (every
// input the window gives goes through the recorder, so the session file holds exactly what was
// done), the `TeleopPanel` and its mjui panel (teleop_ui.hpp).
#include <mujoco/mjui.h>

#include <memory>

#include "mjarm/file_writer.hpp"
#include "mjarm/teleop/session_log.hpp"
#include "teleop_ui.hpp"
#include "viewer_driver.hpp"

namespace mjarm::detail {

namespace {

bool same_targets(const TeleopPanel& a, const TeleopPanel& b) {
  if (a.lift != b.lift || a.hands.size() != b.hands.size()) return false;
  for (std::size_t i = 0; i < a.hands.size(); ++i) {
    if (a.hands[i].gripper != b.hands[i].gripper) return false;
    for (int k = 0; k < 6; ++k)
      if (a.hands[i].pose[k] != b.hands[i].pose[k]) return false;
  }
  return true;
}

// a file opened before the session and the window, so that an unwritable path fails first
std::unique_ptr<FileWriter> open_session_file(const std::string& path) {
  if (path.empty()) return nullptr;
  return std::make_unique<FileWriter>(path, FileWriter::Mode::replace, "teleop session");
}

class TeleopDriver final : public ViewerDriver {
 public:
  TeleopDriver(const Robot& robot, const ViewerOptions& options)
      : file_(open_session_file(options.record_session)),
        session_(robot, options.teleop),
        recorder_(session_),
        panel_(teleop_panel(session_)),
        ui_(make_teleop_ui(panel_, session_, teleop_ranges(session_))),
        applied_(panel_) {}

  const Robot& robot() const noexcept override { return session_.robot(); }
  mjData& data() noexcept override { return session_.simulation().data(); }
  double control_period() const noexcept override { return session_.control_period(); }
  ViewerUi& ui() noexcept override { return *ui_; }

  int step(int ticks) override { return recorder_.step(ticks); }

  // targets are recorded when they change, not at every poll
  void read_panel() override {
    if (same_targets(panel_, applied_)) return;
    recorder_.set_targets(panel_targets(panel_));
    applied_.hands = panel_.hands;
    applied_.lift = panel_.lift;
  }

  void on_panel(PanelAction action, mjvCamera& camera) override {
    switch (action) {
      case PanelAction::target:
        read_panel();
        break;
      case PanelAction::mode:
        apply_mode();
        break;
      case PanelAction::priority:
        apply_priority();
        break;
      case PanelAction::camera:
        to_camera(camera);
        break;
      case PanelAction::camera_preset:
        apply_camera_preset(panel_.camera, static_cast<CameraPreset>(panel_.camera.preset),
                            lookat());
        to_camera(camera);
        break;
      default:  // the selected hand: read by the nudges; pause, step, reset: the shell's
        break;
    }
  }

  bool on_key(int key, bool shift) override {
    if (!nudge(panel_, key, shift)) return false;
    read_panel();
    return true;
  }

  void set_value(const std::string& name, const std::string& value, mjvCamera& camera) override {
    set_teleop_value(panel_, session_, name, value);
    if (name == "mode") {
      apply_mode(/*strict=*/true);
    } else if (name == "priority") {
      apply_priority();
    } else if (name.rfind("camera.", 0) == 0) {
      to_camera(camera);
    } else {
      read_panel();
    }
  }

  void reset() override {
    recorder_.reset();
    const TeleopPanel initial = teleop_panel(session_);
    panel_.hands = initial.hands;
    panel_.lift = initial.lift;
    read_panel();
  }

  void initial_camera(mjvCamera& camera) override {
    mjv_defaultFreeCamera(&session_.robot().model(), &camera);
    to_camera(camera);
  }
  void camera_moved(const mjvCamera& camera) override {
    CameraPanel& c = panel_.camera;
    c.azimuth = camera.azimuth;
    c.elevation = camera.elevation;
    c.distance = camera.distance;
    for (int i = 0; i < 3; ++i) c.lookat[i] = camera.lookat[i];
  }

  void add_markers(mjvScene& scene) const override {
    // a colour per hand; the hand the keys move is drawn more opaque and larger
    static constexpr float kColours[4][3] = {
        {0.2f, 0.5f, 1.0f}, {1.0f, 0.5f, 0.1f}, {0.2f, 0.9f, 0.3f}, {0.8f, 0.2f, 0.8f}};
    const TeleopStats& s = session_.stats();
    for (std::size_t i = 0; i < s.hands.size(); ++i) {
      const bool selected = static_cast<int>(i) == panel_.selected;
      const float* c = kColours[i % 4];
      const float rgba[4] = {c[0], c[1], c[2], selected ? 0.6f : 0.3f};
      add_target_marker(scene, s.hands[i].X_WT, s.hands[i].X_WR.p, rgba, selected ? 0.03 : 0.022);
    }
  }

  void overlay(const OverlayInfo& info, OverlayText& left, OverlayText& right) const override {
    format_teleop_overlay(session_.stats(), session_.hands(), panel_, info, left, right);
  }
  const char* help() const noexcept override {
    return "keys move the selected hand: W/S x, A/D y, R/F z (shift: pitch, roll, yaw), "
           "G gripper, TAB next hand\n"
           "drag: left rotate, right move, scroll zoom; space pause, right step, bksp reset, "
           "esc quit";
  }

  void describe(ViewerScreenshot& shot) const override {
    const TeleopStats& s = session_.stats();
    shot.time = s.time;
    shot.mode = s.mode;
    shot.lift = s.lift;
    shot.hands.clear();
    for (std::size_t i = 0; i < s.hands.size(); ++i) {
      shot.hands.push_back(
          {session_.hands()[i].name, s.hands[i].X_WE.p, s.hands[i].X_WT.p, s.hands[i].gripper});
    }
    if (!shot.hands.empty()) {
      shot.p_WE = shot.hands.front().p_WE;
      shot.p_WT = shot.hands.front().p_WT;
    }
  }

  void finish(ViewerReport& report) override {
    TeleopViewerReport r;
    r.hands = session_.hands();
    r.stats = session_.stats();
    r.panel = panel_;
    const SessionLog log = recorder_.log();
    r.session_events = log.events.size();
    r.session_ticks = log.ticks;
    r.session_digest = log.digest;
    if (file_) {
      r.session_file = file_->path().string();
      written_ = true;
      write_session_log(log, *file_);
    }
    report.teleop = std::move(r);
  }

  void save() noexcept override {
    if (!file_ || written_) return;
    written_ = true;
    try {
      write_session_log(recorder_.log(), *file_);
    } catch (...) {  // the error that ended the viewer is the one reported
    }
  }

 private:
  Eigen::Vector3d lookat() const {
    return {panel_.camera.lookat[0], panel_.camera.lookat[1], panel_.camera.lookat[2]};
  }

  void to_camera(mjvCamera& camera) const {
    camera.type = mjCAMERA_FREE;
    camera.azimuth = panel_.camera.azimuth;
    camera.elevation = panel_.camera.elevation;
    camera.distance = panel_.camera.distance;
    for (int i = 0; i < 3; ++i) camera.lookat[i] = panel_.camera.lookat[i];
  }

  // the panel's mode radio → the session (through the recorder)
  void apply_mode(bool strict = false) {
    ViewerDriver::apply_mode(
        panel_.mode, static_cast<SimulationMode>(panel_.mode), session_,
        [this](SimulationMode mode) { recorder_.set_mode(mode); }, strict);
  }

  // the panel's priority radio → each hand's task (only those that change are recorded)
  void apply_priority() {
    const auto tasks = priority_tasks(session_, static_cast<TeleopPriority>(panel_.priority));
    for (std::size_t i = 0; i < tasks.size(); ++i) {
      const HandTask& now = session_.tasks()[i];
      if (now.kind != tasks[i].kind || now.priority != tasks[i].priority)
        recorder_.set_task(static_cast<int>(i), tasks[i]);
    }
  }

  std::unique_ptr<FileWriter> file_;
  bool written_ = false;
  TeleopSession session_;
  SessionRecorder recorder_;
  TeleopPanel panel_;
  std::unique_ptr<ViewerUi> ui_;
  TeleopPanel applied_;  // the targets last given to the session
};

}  // namespace

std::unique_ptr<ViewerDriver> make_teleop_driver(const Robot& robot, const ViewerOptions& options) {
  return std::make_unique<TeleopDriver>(robot, options);
}

}  // namespace mjarm::detail
