// The viewer's single-arm driver: a `ViewerSession`, its `PanelState` and panel.

#include "viewer_driver.hpp"

namespace mjarm::detail {

namespace {

class ArmDriver final : public ViewerDriver {
 public:
  ArmDriver(const Robot& robot, const ViewerOptions& options)
      : session_(robot, options.session),
        panel_(session_.initial_panel()),
        ui_(panel_, session_.ranges(), session_.has_gripper()) {}

  const Robot& robot() const noexcept override { return session_.robot(); }
  mjData& data() noexcept override { return session_.simulation().data(); }
  double control_period() const noexcept override { return session_.control_period(); }
  ViewerUi& ui() noexcept override { return ui_; }

  int step(int ticks) override { return session_.step(ticks); }
  void read_panel() override { session_.set_target(panel_); }

  void on_panel(PanelAction action, mjvCamera&) override {
    if (action == PanelAction::target) session_.set_target(panel_);
    if (action == PanelAction::mode) apply_mode();
  }
  bool on_key(int, bool) override { return false; }

  void set_value(const std::string& name, const std::string& value, mjvCamera&) override {
    set_panel_value(panel_, session_.ranges(), name, value);
    if (name == "mode") apply_mode(/*strict=*/true);
    session_.set_target(panel_);
  }

  void reset() override {
    session_.reset();
    const int mode = panel_.mode;
    panel_ = session_.initial_panel();
    panel_.mode = mode;
    session_.set_target(panel_);
  }

  void initial_camera(mjvCamera& camera) override {
    mjv_defaultFreeCamera(&session_.robot().model(), &camera);
    const Eigen::Vector3d p = session_.stats().X_WE.p;
    camera.lookat[0] = 0.5 * p.x();
    camera.lookat[1] = 0.5 * p.y();
    camera.lookat[2] = 0.4;
    camera.distance = 2.0;
    camera.azimuth = 135.0;
    camera.elevation = -20.0;
  }

  void add_markers(mjvScene& scene) const override {
    const ViewerStats& s = session_.stats();
    const float green[4] = {0.2f, 0.9f, 0.3f, 0.4f};
    add_target_marker(scene, s.X_WT, s.X_WR.p, green, 0.03);
  }

  void overlay(const OverlayInfo& info, OverlayText& left, OverlayText& right) const override {
    format_overlay(session_.stats(), info, session_.robot().model(),
                   session_.simulation().saturated(), left);
    right.labels.clear();
    right.values.clear();
  }
  const char* help() const noexcept override {
    return "drag: left rotate, right move, scroll zoom\n"
           "space pause, right step, bksp reset, esc quit";
  }

  void describe(ViewerScreenshot& shot) const override {
    shot.time = session_.stats().time;
    shot.mode = session_.mode();
    shot.p_WE = session_.stats().X_WE.p;
    shot.p_WT = panel_target(panel_).p;
  }
  void finish(ViewerReport& report) override {
    report.stats = session_.stats();
    report.panel = panel_;
  }

 private:
  // the panel's mode radio → the session
  void apply_mode(bool strict = false) {
    ViewerDriver::apply_mode(
        panel_.mode, panel_mode(panel_), session_,
        [this](SimulationMode mode) { session_.set_mode(mode); }, strict);
  }

  ViewerSession session_;
  PanelState panel_;
  ViewerUi ui_;
};

}  // namespace

std::unique_ptr<ViewerDriver> make_arm_driver(const Robot& robot, const ViewerOptions& options) {
  return std::make_unique<ArmDriver>(robot, options);
}

}  // namespace mjarm::detail
