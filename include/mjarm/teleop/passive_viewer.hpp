#pragma once
/// @file
/// `PassiveViewer`: a window on the user's own loop, as `mujoco.viewer.launch_passive`. The
/// user's loop owns and steps its `mjData`; the window runs in a thread of its own and draws the
/// state the loop last handed over with `sync()`:
///
///     PassiveViewer viewer(robot, data);
///     while (viewer.running()) {
///       mj_step(&robot.model(), &data);
///       viewer.markers().add_frame(X_WE);   // drawn with the next synced state
///       viewer.sync();
///     }
///
/// `sync` copies the state (MuJoCo's `mjv_copyData`) into a buffer under a lock and returns: it
/// never waits for a frame to be drawn, only for the window thread's swap of two buffers.
///
/// The mouse perturbs bodies as in MuJoCo's simulate: a double-click in the 3-D view selects the
/// body under the pointer (a double-click on nothing clears it); Ctrl + right drag pulls the
/// selected body towards the pointer (translation), Ctrl + left drag turns it (rotation), by
/// the spring force of `mjv_applyPerturbForce` written into the body's row of the user's
/// `xfrc_applied` at each `sync` while the drag lasts, and zeroed when it ends; a mocap body is
/// moved instead (`mjv_applyPerturbPose`). The selection and the spring are drawn as simulate
/// draws them.
///
/// Figures (MuJoCo's `mjr_figure`, toggled from the panel or shown from the start): the total
/// normal contact force, each force-limited actuator's force as a percentage of its limit, and
/// the lines the loop plots (`plot`, e.g. a tracking error), over the last `figure_seconds`.
///
/// Errors of the window thread (a script's screenshot that cannot be written, …) are raised by
/// the next `sync` or by `close`; the window closing (the user, escape, a script's end) makes
/// `running()` false, after which `sync` does nothing.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/render/camera.hpp"
#include "mjarm/teleop/viewer.hpp"
#include "mjarm/teleop/viewer_script.hpp"

namespace mjarm {

/// How the passive viewer's window looks and runs.
struct PassiveViewerOptions {
  int width = 1280;             ///< window width [screen pixels]
  int height = 800;             ///< window height [screen pixels]
  double render_hz = 60.0;      ///< frames drawn per wall-clock second
  std::string title;            ///< window title ("" = "mjarm: <model name>")
  bool show_figures = false;    ///< figures shown from the start (the panel toggles them)
  double figure_seconds = 5.0;  ///< simulated time the figures span [s]
  int max_markers = 1000;       ///< markers one sync can carry
  /// The camera at the start: a free or model camera (default: a free camera framing the model).
  std::optional<CameraSpec> camera;
  /// Scripted input (tests, demos): select, press, move, release, drag, key, set, screenshot,
  /// wait; on the wall clock, since the loop it shows runs on it.
  std::optional<ViewerScript> script;
};

constexpr auto declared_fields(const PassiveViewerOptions*) {
  using S = PassiveViewerOptions;
  return declare<S>(
      "passive viewer", field("width", &S::width, "pixels", Range::at_least(320), "window width"),
      field("height", &S::height, "pixels", Range::at_least(240), "window height"),
      field("render_hz", &S::render_hz, "Hz", Range::positive(), "frames drawn per wall second"),
      field("title", &S::title, "window title (\"\" = mjarm: <model name>)"),
      field("show_figures", &S::show_figures, "figures shown from the start"),
      field("figure_seconds", &S::figure_seconds, "s", Range::positive(),
            "simulated time the figures span"),
      field("max_markers", &S::max_markers, "", Range::closed(0, 10000),
            "markers one sync can carry"));
}

/// An RGBA colour, each in [0, 1].
using Rgba = std::array<float, 4>;

/// What the loop draws into the next synced frame: frames, arrows, spheres, lines and text, in
/// world coordinates [m]. Taken (and cleared) by `PassiveViewer::sync`. Each call returns false
/// when the `max_markers` of one sync are used up (the marker is not drawn). Allocation-free.
class ViewerMarkers {
 public:
  explicit ViewerMarkers(int capacity = 1000);

  /// The axes of @p X (x red, y green, z blue), @p length [m] long.
  bool add_frame(const Pose& X, double length = 0.1);
  /// An arrow from @p from to @p to, @p radius [m] thick.
  bool add_arrow(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                 const Rgba& rgba = {0.9f, 0.6f, 0.1f, 1.0f}, double radius = 0.006);
  /// A ball of @p radius [m] at @p p.
  bool add_sphere(const Eigen::Vector3d& p, double radius,
                  const Rgba& rgba = {0.2f, 0.6f, 0.9f, 0.6f});
  /// A line segment from @p a to @p b, @p width pixels wide.
  bool add_line(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                const Rgba& rgba = {1.0f, 1.0f, 1.0f, 1.0f}, double width = 2.0);
  /// @p text (at most 99 bytes are shown) at @p p.
  bool add_text(const Eigen::Vector3d& p, std::string_view text,
                const Rgba& rgba = {1.0f, 1.0f, 1.0f, 1.0f});

  int size() const noexcept { return static_cast<int>(geoms_.size()); }
  int capacity() const noexcept { return capacity_; }
  void clear() noexcept { geoms_.clear(); }
  const std::vector<mjvGeom>& geoms() const noexcept { return geoms_; }
  /// Swaps the markers with @p other's (the sync hand-over: no copy, no allocation).
  void swap(std::vector<mjvGeom>& other) noexcept { geoms_.swap(other); }

 private:
  mjvGeom* next();
  int capacity_;
  std::vector<mjvGeom> geoms_;
};

namespace detail {
struct PassiveShared;
}

/// The passive viewer. Not copyable or movable; one window per object; `sync`, `markers` and
/// `plot` are called from the user's loop (one thread).
class PassiveViewer {
 public:
  /// Opens the window on @p robot showing @p data, which the caller keeps stepping; returns when
  /// the window is up.
  /// @throws Error when there is no display (`kNoDisplayMessage`), GLFW or the window cannot be
  ///         initialised, @p data was not made for @p robot's model, or an option is out of range.
  PassiveViewer(const Robot& robot, mjData& data, const PassiveViewerOptions& options = {});
  /// Closes the window (as `close`, never throws).
  ~PassiveViewer();
  PassiveViewer(const PassiveViewer&) = delete;
  PassiveViewer& operator=(const PassiveViewer&) = delete;

  /// False once the window was closed (by the user, escape, the script's end, `close` or an
  /// error).
  bool running() const noexcept;
  /// Hands the current state, the markers and the plotted values over to the window, and writes
  /// the mouse's perturbation into the data (see the file comment). Nothing once not running.
  /// @throws Error an error of the window thread (once).
  void sync();
  /// The markers drawn with the next synced state.
  ViewerMarkers& markers() noexcept { return markers_; }
  /// Sets the value of plot line @p line (at most 8 lines, named at first use) for the next sync.
  /// @throws Error for a ninth line name or a non-finite value.
  void plot(std::string_view line, double value);
  /// Closes the window and waits for its thread.
  /// @throws Error an error of the window thread not raised yet.
  void close();
  /// What the window did (frames, screenshots, how it ended); complete once not running.
  ViewerReport report() const;
  /// States handed over so far.
  std::int64_t syncs() const noexcept;

  /// The body selected with the mouse (0 when none), and whether a drag perturbs it now.
  int selected_body() const noexcept;
  bool perturbing() const noexcept;

 private:
  Robot robot_;
  mjData* data_;
  ViewerMarkers markers_;
  std::array<double, 8> plot_values_{};
  std::vector<std::string> plot_names_;
  std::shared_ptr<detail::PassiveShared> shared_;
  std::thread thread_;
};

}  // namespace mjarm
