#pragma once
// The element and attribute names of a URDF, checked before MuJoCo reads it: MuJoCo's URDF
// reader skips what it does not know and reads only the first of a repeated element, so
// `<axs xyz="0 1 0"/>` left a joint turning about x and `rpyy` an origin unrotated, without a
// word (MJCF has a schema that MuJoCo enforces).

#include <string>
#include <string_view>
#include <vector>

namespace mjarm {

/// Checks the links, joints and materials of the URDF @p xml: every element and attribute inside
/// them is one URDF defines (namespaced names, "drake:…", are left alone), a link's elements other
/// than visual and collision appear once, and a geometry holds one shape. Elements beside links,
/// joints and materials (gazebo, transmission, ros2_control, mujoco, …) are extensions left to
/// their readers.
/// @return load warnings for other simulators' elements in a link (Bullet's `<contact>`), which
///         MuJoCo ignores.
/// @throws Error "URDF SOURCE line 5: unknown element 'colision' in link 'arm'; closest:
///         collision; elements: inertial, visual, collision", or likewise for an attribute, a
///         repeated element or a second shape.
std::vector<std::string> check_urdf_names(std::string_view xml, const std::string& source);

}  // namespace mjarm
