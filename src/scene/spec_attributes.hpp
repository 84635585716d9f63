#pragma once
// MJCF attributes of mjSpec elements and of <option>, read and written by their MJCF names
// ("size", "gainprm", "solreflimit", "euler", "integrator", ...). The fields come from MuJoCo's
// own field lists (mjspecmacro.h, mjxmacro.h), so every numeric, keyword or name attribute of a
// body, joint, geom, site, camera, light, actuator, sensor, tendon, equality, pair, mesh,
// material or texture is reachable. Internal to the scene room.

#include <mujoco/mujoco.h>

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace mjarm::scene_detail {

/// The value of attribute @p attribute of @p element as MJCF text (numbers in their shortest
/// round-trip form), or nullopt when the element holds none: an empty name reference, an
/// orientation written another way (the quat of a body given by euler), an unset number (a geom's
/// fromto or mass). @p what names the element in errors ("geom 'cube/geom'").
/// @throws Error for an attribute the element does not have (with the closest names).
std::optional<std::string> read_attribute(mjsElement& element, std::string_view attribute,
                                          const std::string& what);

/// Sets attribute @p attribute of @p element from MJCF text: numbers separated by spaces, a
/// keyword ("box", "true", "auto"), or the name of another element. Fewer numbers than the
/// attribute holds set the leading ones where MJCF allows it (size, friction, gainprm, solimp,
/// gear, ...); orientations (quat, euler, axisangle, xyaxes, zaxis) replace the element's one.
/// @throws Error naming the element and the attribute for an unknown attribute (closest names),
///         a value of the wrong kind or count, a non-finite number or an unknown keyword.
void write_attribute(mjsElement& element, std::string_view attribute, std::string_view text,
                     const std::string& what);
/// Sets a numeric attribute from numbers, as above, without a round trip through text.
void write_attribute(mjsElement& element, std::string_view attribute,
                     std::span<const double> values, const std::string& what);

/// Sets attribute @p attribute of `<option>` (timestep, impratio, cone, noslip_iterations, ...)
/// in @p option from MJCF text.
/// @throws Error as `write_attribute`.
void write_option(mjOption& option, std::string_view attribute, std::string_view text);
/// Copies the `<option>` attribute @p attribute from @p from to @p to (a name `write_option`
/// accepted).
void copy_option(const mjOption& from, mjOption& to, std::string_view attribute);

}  // namespace mjarm::scene_detail
