#pragma once
/// @file
/// The load-time check that a compiled model holds only finite numbers, and lengths, masses and
/// inertias MuJoCo can simulate.

#include <mujoco/mujoco.h>

#include <string_view>

namespace mjarm {

/// The largest magnitude of a position, size, mass or inertia in a model: MuJoCo's mjMAXVAL
/// (1e10), beyond which its own checks call a qpos, qvel or qacc diverged. A body at 1e300 m or
/// of 1e308 kg loads in MuJoCo and fails at the first step ("Nan, Inf or huge value in QACC").
inline constexpr double kMaxModelMagnitude = mjMAXVAL;

/// Checks every real-valued array of @p m (poses, masses, inertias, ranges, gains, solver
/// parameters, keyframes, mesh vertices, ... — all of MuJoCo's `MJMODEL_POINTERS` except the
/// free-form user data) and every real-valued field of `m.opt`, `m.stat` (<statistic>) and
/// `m.vis` (<visual>) for NaN and ±inf, then the positions, sizes, masses, inertias and keyframe
/// positions for magnitudes beyond `kMaxModelMagnitude`. Arrays the
/// compiler fills in itself (qpos0, dof_M0, invweight0, ...) are checked after those the MJCF
/// gives, so the error names where the bad number came from rather than what it spread to.
/// @param source  how the error names the model ("'arm.xml'", "XML string").
/// @throws Error naming the model, the element kind and name (e.g. "body 'link3'"), the
///         attribute and the mjModel array, with the offending values (shortest round-trip
///         form, `number_text`).
void check_model_finite(const mjModel& m, std::string_view source);

}  // namespace mjarm
