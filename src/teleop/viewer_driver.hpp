#pragma once
// What the viewer's window drives (private to src/teleop): the shell (viewer_shell.*) owns the
// window, the GL resources, the camera, the schedule and the event routing; a driver owns the
// session, its panel state and the mjui panel bound to it, and says what to draw. Two drivers:
// one arm (`ViewerSession`, viewer_arm_driver.cpp) and several hands (`TeleopSession` with its
// recorder, teleop_viewer_driver.cpp); they share the shell, the mode switch (`apply_mode` here,
// `detail::ModeRigs` in the sessions), the panel sections (viewer_ui.hpp), the markers and the
// overlay's common lines.

#include <mujoco/mujoco.h>

#include <memory>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/teleop/viewer.hpp"
#include "viewer_overlay.hpp"
#include "viewer_ui.hpp"

namespace mjarm::detail {

class ViewerDriver {
 public:
  virtual ~ViewerDriver() = default;

  /// The model simulated in the current mode (a mode switch may change it: the shell then
  /// rebuilds its rendering resources).
  virtual const Robot& robot() const noexcept = 0;
  virtual mjData& data() noexcept = 0;
  virtual double control_period() const noexcept = 0;
  virtual ViewerUi& ui() noexcept = 0;

  /// Simulates @p ticks control ticks; returns those done.
  virtual int step(int ticks) = 0;
  /// The panel → the session (at every input poll, and after every edit).
  virtual void read_panel() = 0;
  /// A panel item changed (target, mode, priority, camera, hand; the shell handles pause, step
  /// and reset). @p camera is the shell's camera, for the camera section.
  virtual void on_panel(PanelAction action, mjvCamera& camera) = 0;
  /// A key the shell does not handle itself; true when it did something.
  virtual bool on_key(int key, bool shift) = 0;
  /// A named panel edit (scripts, --set), through the same path as the panel's events.
  /// @throws Error naming the value, or when a mode is unavailable.
  virtual void set_value(const std::string& name, const std::string& value, mjvCamera& camera) = 0;
  /// Back to the initial state (mode kept).
  virtual void reset() = 0;

  /// The camera at the start.
  virtual void initial_camera(mjvCamera& camera) = 0;
  /// The mouse moved the camera: a camera section follows it.
  virtual void camera_moved(const mjvCamera& camera) { (void)camera; }

  /// Markers drawn into @p scene after `mjv_updateScene` (targets, references).
  virtual void add_markers(mjvScene& scene) const = 0;
  /// The overlay texts of the 3-D view: a block at the top left, and one at the top right
  /// (empty when none).
  virtual void overlay(const OverlayInfo& info, OverlayText& left, OverlayText& right) const = 0;
  /// The keyboard help line at the bottom left.
  virtual const char* help() const noexcept = 0;

  /// Fills a screenshot's session fields (time, mode, positions).
  virtual void describe(ViewerScreenshot& shot) const = 0;
  /// Fills the report at the end and writes what must be written (a recorded session).
  /// @throws Error when the session file cannot be written.
  virtual void finish(ViewerReport& report) = 0;
  /// On an error: keeps what was recorded (writes the session file), never throws.
  virtual void save() noexcept {}

  // ---- a window on someone else's loop (the passive viewer) ----
  /// At every loop iteration, before events and drawing: takes the newest state handed over.
  virtual void update() {}
  /// True when the program asks the window to close.
  virtual bool finished() const noexcept { return false; }
  /// Whether a double-click selects a body and Ctrl + drag perturbs it (`set_perturbation`).
  virtual bool perturbs() const noexcept { return false; }
  /// The mouse's selection or drag changed.
  virtual void set_perturbation(const mjvPerturb& pert) { (void)pert; }
  /// Draws over the 3-D view after the overlays (figures).
  virtual void draw(const mjrRect& view, const mjrContext& con) {
    (void)view;
    (void)con;
  }
  /// Whether a script runs on a virtual clock (one render period per frame); the passive viewer
  /// shows a loop that runs on the wall clock, so its scripts do too.
  virtual bool virtual_clock() const noexcept { return true; }

  /// A note for people (a mode that could not be selected, …); empty when none.
  std::string note;

 protected:
  /// The mode switch of both drivers: the panel's mode radio @p radio asks for @p wanted; when
  /// @p session can run it, @p switch_mode(wanted) switches (the note is cleared), else the radio
  /// goes back to the session's mode and the note says why — an error too when @p strict (a named
  /// edit from a script or --set).
  template <class Session, class Switch>
  void apply_mode(int& radio, SimulationMode wanted, const Session& session, Switch&& switch_mode,
                  bool strict = false) {
    if (wanted == session.mode()) return;
    if (!session.available(wanted)) {
      note = session.unavailable_reason(wanted);
      radio = static_cast<int>(session.mode());
      if (strict) throw Error(note);
      return;
    }
    switch_mode(wanted);
    note.clear();
  }
};

std::unique_ptr<ViewerDriver> make_arm_driver(const Robot& robot, const ViewerOptions& options);
std::unique_ptr<ViewerDriver> make_teleop_driver(const Robot& robot, const ViewerOptions& options);

/// Adds a target marker to @p scene: a translucent ball of @p radius [m] at the target X_WT with
/// its axes (x red, y green, z blue), and a small ball at the reference p_WR; nothing when the
/// scene is full.
void add_target_marker(mjvScene& scene, const Pose& X_WT, const Eigen::Vector3d& p_WR,
                       const float rgba[4], double radius);

}  // namespace mjarm::detail
