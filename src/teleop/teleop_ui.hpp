#pragma once
/// @file
/// The bimanual viewer's panel: MuJoCo's UI (`ViewerUi`) bound to a `TeleopPanel` — the widgets
/// write straight into the panel state, so the window holds no second copy of it; named edits
/// (`set_teleop_value`) and keyboard nudges (`nudge`) change the same numbers.
///
/// Sections and item names (the names of `teleop_value_names`, plus the buttons):
/// - "Simulation": mode radio "mode" (Kinematic, Position, Motor), priority radio "priority"
///   (Equal, R over L, L over R), selected-hand radio "hand", slider "lift" [m] (disabled
///   without a lift), buttons "pause", "step", "reset";
/// - one per hand, "<Name> hand": sliders "<hand>.x", ".y", ".z" [m], ".roll", ".pitch", ".yaw"
///   [rad], ".gripper" (0 open … 1 closed; disabled without fingers);
/// - "Camera": sliders "camera.azimuth", "camera.elevation" [deg], "camera.distance" [m],
///   "camera.lookat_x|y|z" [m], preset radio "camera.preset" (Front, Left, Right, Top,
///   Overview).
///
/// The panel is taller than most windows: the mouse wheel over it scrolls it (mjui), and each
/// section folds with a click on its title.

#include <memory>

#include "mjarm/teleop/teleop_panel.hpp"
#include "mjarm/teleop/viewer_panel.hpp"
#include "viewer_ui.hpp"

namespace mjarm {

/// Slider ranges of each hand's section: the bounding box of a seeded workspace sample of the
/// hand's chain (@p samples configurations) plus 5 cm, and ±π (pitch ±π/2) about the initial
/// roll-pitch-yaw (as `panel_ranges`), one per hand in `session.hands()` order.
/// @throws Error when @p samples is 0.
std::vector<PanelRanges> teleop_ranges(const TeleopSession& session, std::size_t samples = 1000);

/// The panel bound to @p panel (which must outlive it and stay where it is, with as many hands
/// as @p session), slider ranges from @p ranges (one per hand).
/// @throws Error when the panel's hands or the ranges do not match the session's.
std::unique_ptr<ViewerUi> make_teleop_ui(TeleopPanel& panel, const TeleopSession& session,
                                         const std::vector<PanelRanges>& ranges);

}  // namespace mjarm
