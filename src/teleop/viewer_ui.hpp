#pragma once
/// @file
/// `ViewerUi`: the viewer's side panel built with MuJoCo's UI framework (mjui), bound to a
/// panel state (the single-arm `PanelState` here, the bimanual `TeleopPanel` in teleop_ui.hpp),
/// plus the window layout (panel on the left, 3-D view on the right) and the pointer bookkeeping
/// shared by real GLFW events and scripted ones. Items are known by name ("x", "left.z",
/// "camera.preset", "mode", "pause", …): scripts, tests and the viewer address them that way.
///
/// Building the panel needs no OpenGL; `attach`, `refresh` and the item geometry do (they need
/// the `mjrContext` of the window).

#include <mujoco/mujoco.h>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mjarm/teleop/viewer_panel.hpp"

namespace mjarm {

/// What a changed panel item asks the viewer to do.
enum class PanelAction {
  none,           ///< nothing (not a panel item)
  target,         ///< a target or gripper slider moved: read the panel
  mode,           ///< the mode radio changed
  pause,          ///< the pause/run button
  step,           ///< the single-step button
  reset,          ///< the reset button
  priority,       ///< the task-priority radio (bimanual panel)
  camera,         ///< a camera slider (bimanual panel)
  camera_preset,  ///< the camera-preset radio (bimanual panel)
  hand            ///< the selected-hand radio (bimanual panel)
};

/// One item of a panel section: MuJoCo's item definition (`mjuiDef` fields) and the name the
/// item is known by ("" for none).
struct UiItemDef {
  int type = mjITEM_END;  ///< mjITEM_SLIDERNUM, mjITEM_RADIO, mjITEM_BUTTON, …
  std::string label;      ///< shown on the panel
  int state = 1;          ///< 1 enabled, 0 disabled
  void* data = nullptr;   ///< the bound value (double for sliders, int for radios)
  std::string other;      ///< range "lo hi", radio choices "A\nB", button shortcut " #32"
  std::string name;       ///< the item's name
};

/// Rectangle indices in the `mjuiState`.
enum ViewerRect : int { rect_window = 0, rect_panel = 1, rect_view = 2 };

/// A slider's range as mjui reads it from `UiItemDef::other`: "lower upper" (6 significant
/// digits).
std::string ui_range(double lower, double upper);

/// The items of a target section, shared by both panels: sliders "PREFIXx", "PREFIXy",
/// "PREFIXz" [m], "PREFIXroll", "PREFIXpitch", "PREFIXyaw" [rad] bound to @p pose with ranges
/// from @p ranges, and "PREFIXgripper" (0 open … 1 closed) bound to @p gripper, disabled when
/// @p has_gripper is false. @p prefix is "" for the single-arm panel, "<hand>." for a hand.
std::vector<UiItemDef> target_items(double (&pose)[6], double& gripper, const PanelRanges& ranges,
                                    bool has_gripper, const std::string& prefix);

/// The run buttons that close the "Simulation" section of both panels: Pause/Run (space),
/// Step (right arrow), Reset (backspace), named "pause", "step", "reset".
std::vector<UiItemDef> run_buttons();

/// The panel and the layout. Holds pointers into @p state: the state must outlive it and stay
/// where it is.
class ViewerUi {
 public:
  /// An empty panel: add sections with `add_section`.
  ViewerUi();
  /// The single-arm panel: sections "Target" (sliders x, y, z [m], roll, pitch, yaw [rad],
  /// gripper 0…1, ranges from @p ranges; the gripper slider disabled when @p gripper is false)
  /// and "Simulation" (mode radio, Pause/Run, Step, Reset buttons: "pause", "step", "reset").
  /// @throws Error when MuJoCo rejects a definition (it should not).
  ViewerUi(PanelState& state, const PanelRanges& ranges, bool gripper);

  /// Appends a section called @p title with @p items (bound values must outlive the panel and
  /// stay where they are).
  /// @throws Error when the panel is full (mjMAXUISECT sections, mjMAXUIITEM items each) or a
  ///         name is used twice.
  void add_section(const std::string& title, const std::vector<UiItemDef>& items);
  ~ViewerUi();
  ViewerUi(const ViewerUi&) = delete;
  ViewerUi& operator=(const ViewerUi&) = delete;

  mjUI& ui() noexcept { return *ui_; }
  const mjUI& ui() const noexcept { return *ui_; }
  mjuiState& input() noexcept { return input_; }
  const mjuiState& input() const noexcept { return input_; }

  /// The item called @p name ("x" … "gripper", "mode", "pause", … on the single-arm panel), or
  /// null.
  const mjuiItem* item(std::string_view name) const noexcept;
  /// The name of @p item ("" when it has none or is not on the panel).
  std::string_view name_of(const mjuiItem* item) const noexcept;

  /// What a changed item (as `mjui_event` returns it) asks for, from its name: "mode", "pause",
  /// "step", "reset", "priority", "hand", "camera.preset", "camera.*" as named, any other named
  /// item `target`, null or unnamed `none`.
  PanelAction action(const mjuiItem* changed) const noexcept;

  /// Sizes the panel for @p con's fonts, (re)allocates its auxiliary buffer and draws it. Call
  /// after every new `mjrContext` (the panel image lives in the context). Needs the context's
  /// OpenGL context current.
  void attach(mjrContext& con);

  /// Redraws every item from the bound state (after the state changed in code).
  void refresh(const mjrContext& con);

  /// Lays out a framebuffer of @p width × @p height pixels: the whole window, the panel on the
  /// left (its width from the theme), the 3-D view on the rest.
  void layout(int width, int height) noexcept;

  /// The 3-D view's rectangle.
  mjrRect view() const noexcept { return input_.rect[rect_view]; }

  /// Moves the pointer to framebuffer pixel (@p x, @p y) (OpenGL convention: y up from the
  /// bottom): sets position, displacement and the rectangle under the pointer.
  void move_pointer(double x, double y) noexcept;

  /// The framebuffer point (OpenGL convention) at @p fraction ∈ [0, 1] along the slider called
  /// @p name, at its vertical middle; nullopt for an unknown slider, one scrolled out of the
  /// panel's rectangle, or before `attach`.
  std::optional<std::array<double, 2>> slider_point(std::string_view name,
                                                    double fraction) const noexcept;

 private:
  std::unique_ptr<mjUI> ui_;  // large (about a megabyte): on the heap
  mjuiState input_{};
  bool attached_ = false;
  std::vector<std::pair<std::string, const mjuiItem*>> named_;
};

}  // namespace mjarm
