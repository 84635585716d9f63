#pragma once
/// @file
/// `ViewerUi`: the viewer's side panel built with MuJoCo's UI framework (mjui), bound to a
/// `PanelState`, plus the window layout (panel on the left, 3-D view on the right) and the
/// pointer bookkeeping shared by real GLFW events and scripted ones.
///
/// Building the panel needs no OpenGL; `attach`, `refresh` and the item geometry do (they need
/// the `mjrContext` of the window).

#include <mujoco/mujoco.h>

#include <array>
#include <memory>
#include <optional>
#include <string_view>

#include "mjarm/teleop/viewer_panel.hpp"

namespace mjarm {

/// What a changed panel item asks the viewer to do.
enum class PanelAction {
  none,    ///< nothing (not a panel item)
  target,  ///< a target or gripper slider moved: read the panel
  mode,    ///< the mode radio changed
  pause,   ///< the pause/run button
  step,    ///< the single-step button
  reset    ///< the reset button
};

/// Rectangle indices in the `mjuiState`.
enum ViewerRect : int { rect_window = 0, rect_panel = 1, rect_view = 2 };

/// The panel and the layout. Holds pointers into @p state: the state must outlive it and stay
/// where it is.
class ViewerUi {
 public:
  /// Builds the panel's sections: "Target" (sliders x, y, z [m], roll, pitch, yaw [rad], gripper
  /// 0…1, ranges from @p ranges; the gripper slider disabled when @p gripper is false) and
  /// "Simulation" (mode radio, Pause/Run, Step, Reset buttons).
  /// @throws Error when MuJoCo rejects a definition (it should not).
  ViewerUi(PanelState& state, const PanelRanges& ranges, bool gripper);
  ~ViewerUi();
  ViewerUi(const ViewerUi&) = delete;
  ViewerUi& operator=(const ViewerUi&) = delete;

  mjUI& ui() noexcept { return *ui_; }
  const mjUI& ui() const noexcept { return *ui_; }
  mjuiState& input() noexcept { return input_; }
  const mjuiState& input() const noexcept { return input_; }

  /// The item bound to a value name of `panel_value_names()` ("x" … "gripper", "mode"), or null.
  const mjuiItem* item(std::string_view name) const noexcept;

  /// What a changed item (as `mjui_event` returns it) asks for.
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
  /// @p name, at its vertical middle; nullopt for an unknown slider or before `attach`.
  std::optional<std::array<double, 2>> slider_point(std::string_view name,
                                                    double fraction) const noexcept;

 private:
  std::unique_ptr<mjUI> ui_;  // large (about a megabyte): on the heap
  mjuiState input_{};
  PanelState& state_;
  bool attached_ = false;
  std::array<const mjuiItem*, 8> items_{};  // x … gripper, mode
  const mjuiItem* pause_ = nullptr;
  const mjuiItem* step_ = nullptr;
  const mjuiItem* reset_ = nullptr;
};

}  // namespace mjarm
