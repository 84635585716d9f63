#pragma once
/// @file
/// What the replay page draws over the scene, per frame: the tool frame and the target frame
/// (task.csv's `ee.*` and `ref.*`, the row nearest below each frame time), and the contacts — their
/// points and force vectors, recomputed by `mj_forward` on the recorded qpos, qvel and ctrl (the
/// solver's warm start and switched equality constraints are not recorded: the forces are close
/// to, not equal to, the simulated ones).

#include <mujoco/mujoco.h>

#include <nlohmann/json.hpp>
#include <vector>

#include "mjarm/plot/recording.hpp"

namespace mjarm::web_detail {

/// @p rows: the state rows of the frames (replay_frames). Writes "tool", "target" (frame-major
/// x y z qw qx qy qz, absent when task.csv has no such columns) and "contacts" ({offsets: frame f's
/// contacts are [offsets[f], offsets[f+1]), points: x y z fx fy fz per contact [m, N]}).
nlohmann::json replay_overlays(const mjModel& m, const plot::Recording& recording,
                               const std::vector<double>& frame_times);

}  // namespace mjarm::web_detail
