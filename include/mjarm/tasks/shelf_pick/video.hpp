#pragma once
/// @file
/// The video of a shelf pick: what to ask for (`ShelfPickVideo`) and the cameras it can use
/// (`shelf_pick_camera`).

#include <mujoco/mujoco.h>

#include <filesystem>
#include <string>
#include <string_view>

#include "mjarm/render/camera.hpp"
#include "mjarm/tasks/run_video.hpp"
#include "mjarm/tasks/shelf_pick/plan.hpp"

namespace mjarm {

/// A video of a shelf pick (see `RunVideo`): 640×480 at 30 frames per simulated second by
/// default, the pick point drawn as a translucent green ball.
struct ShelfPickVideo {
  std::filesystem::path path;  ///< MP4 to write (overwritten); empty: no video
  /// "" (default): a free camera framing the robot and the pick point; "follow": a camera
  /// following the tool tip; anything else: a <camera> of the model, by name.
  std::string camera;
  RunVideoOptions options;  ///< size, frame rate, encoding, render options
};

/// The camera called @p camera ("" = default, "follow" or a model camera; see `ShelfPickVideo`)
/// for @p plan, with @p start the start state (kinematics computed). The default looks at the
/// centre of the box around the robot's geoms (their bounding spheres) at the start and the pick
/// point (± 5 cm), from the closest distance at which the whole box fits a picture of
/// width/height @p aspect, and from a side that shows the motion (planar2: square onto
/// its plane; the panda: from the front right, above). "follow" keeps the tool tip at the
/// centre from the same side.
/// @throws Error for a name that is neither "", "follow" nor a camera of the model (the message
///         lists the model's cameras) or an aspect ratio that is not positive.
CameraSpec shelf_pick_camera(const ShelfPickPlan& plan, const mjData& start,
                             std::string_view camera, double aspect = 4.0 / 3.0);

}  // namespace mjarm
