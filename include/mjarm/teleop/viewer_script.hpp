#pragma once
/// @file
/// Scripted viewer sessions: a small text format of synthetic input (panel values, slider drags,
/// key presses, mouse drags) and screenshots, for tests, CI and reproducible demos.
///
/// One command per line; `#` starts a comment; blank lines are ignored:
///
///     wait N                 let N rendered frames pass (physics advances with them); N ≤ 10⁷
///     set NAME VALUE         set a panel value: x y z [m], roll pitch yaw [rad], gripper 0…1,
///                            mode kinematic|position|torque; with several hands the
///                            `set_teleop_value` names (left.z, lift, camera.preset, priority, …)
///     slider NAME FRACTION   press and release the mouse on slider NAME (x … gripper, or
///                            left.x …, lift, camera.azimuth …) at FRACTION ∈ [0, 1] of its
///                            length: goes through the panel's events
///     key NAME               press a key: space (pause), right (single step), backspace
///                            (reset), escape (quit); with several hands the nudges w s a d r f
///                            (shift+w … shift+f turn), g (gripper), tab (next hand)
///     drag BUTTON DX DY      drag the mouse in the 3-D view: left rotates, right moves,
///                            middle zooms; DX, DY in pixels (y down)
///     scroll DY              scroll wheel in the 3-D view (positive zooms in)
///     select DX DY           double-click at (DX, DY) pixels from the 3-D view's centre (y down):
///                            selects the body there, or clears the selection (passive viewer)
///     press BUTTON DX DY     press left|right|middle at (DX, DY) from the view's centre;
///                            ctrl+right / ctrl+left hold Ctrl: perturb the selected body
///     move DX DY             move the pointer to (DX, DY) from the view's centre (a pressed
///                            button drags)
///     release                release the pressed button
///     screenshot PATH        draw a frame and save the window as a PNG
///     quit                   end the session (also implied at the end of the script)
///
/// Scripted sessions run on a virtual clock (one render period per frame), so they are
/// deterministic whatever the machine's speed.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/fields.hpp"

namespace mjarm {

/// What a script line asks for.
enum class ScriptAction {
  wait,
  set,
  slider,
  key,
  drag,
  scroll,
  select,
  press,
  move,
  release,
  screenshot,
  quit
};

/// The names are the script keywords.
constexpr auto declared_names(const ScriptAction*) {
  using A = ScriptAction;
  return std::array{EnumName{A::wait, "wait", "wait N frames"},
                    EnumName{A::set, "set", "set a panel value"},
                    EnumName{A::slider, "slider", "move a slider to a fraction"},
                    EnumName{A::key, "key", "press a key"},
                    EnumName{A::drag, "drag", "drag the mouse"},
                    EnumName{A::scroll, "scroll", "scroll the mouse wheel"},
                    EnumName{A::select, "select", "double-click: select a body"},
                    EnumName{A::press, "press", "press a mouse button"},
                    EnumName{A::move, "move", "move the pointer"},
                    EnumName{A::release, "release", "release the mouse button"},
                    EnumName{A::screenshot, "screenshot", "save the frame as a PNG"},
                    EnumName{A::quit, "quit", "end the session"}};
}

/// One parsed script line.
struct ScriptCommand {
  ScriptAction action = ScriptAction::wait;
  int line = 0;       ///< 1-based line in the source (0 for commands built in code)
  /// set/slider: value name; key: key name; drag/press: button; screenshot: path
  std::string name;
  std::string value;  ///< set: the value as written; key: "shift" for shift+KEY; press: "ctrl"
  double x = 0.0;     ///< slider: fraction; drag/select/press/move: DX [pixels]; scroll: DY
  double y = 0.0;     ///< drag/select/press/move: DY [pixels]
  int frames = 0;     ///< wait: frame count
};

/// A parsed script.
struct ViewerScript {
  std::vector<ScriptCommand> commands;

  /// Parses @p text; @p source names it in messages.
  /// @throws Error "SOURCE:LINE: …" for an unknown command, a wrong number of arguments, an
  ///         unknown value/key/button name, or a number that is not finite (or a negative or
  ///         non-integer frame count, a fraction outside [0, 1]).
  static ViewerScript parse(std::string_view text, std::string_view source = "<script>");

  /// Reads and parses the file @p path.
  /// @throws Error naming the path when it cannot be read, or as `parse`.
  static ViewerScript load(const std::filesystem::path& path);
};

/// The mjui/GLFW key code of a script key name, or 0 when unknown.
int viewer_key_code(std::string_view name) noexcept;

}  // namespace mjarm
