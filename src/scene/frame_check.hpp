#pragma once
// The one check of an orientation a scene gives MuJoCo (spec fields, scene files, edits).
// Compiled from an mjSpec, MuJoCo 4.0.1 keeps a zero or non-finite quaternion as it is (the frame
// then has a zero rotation matrix) and refuses a zero xyaxes, zaxis or axisangle axis with a
// message that names the element's index, not the attribute: every such value is refused here,
// before it reaches the spec. Internal to the scene room.

#include <span>
#include <string>
#include <string_view>

namespace mjarm::scene_detail {

/// Refuses a degenerate orientation @p attribute ("quat" w x y z, "xyaxes" x then y axis,
/// "zaxis", "axisangle" axis then angle, "euler") of the element @p what ("camera 'front'"):
/// a non-finite value, a quaternion, zaxis or axisangle axis of norm below 1e-9, an xyaxes whose
/// x axis is below 1e-9 or whose y axis is zero or parallel to x (within 1e-9 rad).
/// @throws Error "camera 'front': xyaxes …" naming the attribute and what is expected.
void check_orientation(std::string_view attribute, std::span<const double> values,
                       const std::string& what);

}  // namespace mjarm::scene_detail
