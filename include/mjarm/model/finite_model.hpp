#pragma once
/// @file
/// The load-time check that a compiled model holds only finite numbers.

#include <mujoco/mujoco.h>

#include <string_view>

namespace mjarm {

/// Checks every real-valued array of @p m (poses, masses, inertias, ranges, gains, solver
/// parameters, keyframes, mesh vertices, ... — all of MuJoCo's `MJMODEL_POINTERS` except the
/// free-form user data) and every real-valued field of `m.opt` for NaN and ±inf. Arrays the
/// compiler fills in itself (qpos0, dof_M0, invweight0, ...) are checked after those the MJCF
/// gives, so the error names where the bad number came from rather than what it spread to.
/// @param source  how the error names the model ("'arm.xml'", "XML string").
/// @throws Error naming the model, the element kind and name (e.g. "body 'link3'"), the
///         attribute and the mjModel array, with the offending values.
void check_model_finite(const mjModel& m, std::string_view source);

}  // namespace mjarm
