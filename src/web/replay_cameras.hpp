#pragma once
/// @file
/// The cameras of a replay that move with the run other than rigidly with their body — MuJoCo's
/// modes track, trackcom, targetbody and targetbodycom — posed at every frame as MuJoCo poses them
/// (`mj_forward` on the recorded state poses them: replay_frames). A fixed camera rides its
/// body, which the frames already pose: it needs nothing per frame.

#include <mujoco/mujoco.h>

#include <nlohmann/json.hpp>
#include <vector>

namespace mjarm::web_detail {

/// True when camera @p c of @p m is posed per frame (its mode is not mjCAMLIGHT_FIXED).
bool camera_moves(const mjModel& m, int c);

struct ReplayFrames;

/// {cameras: [the ids of the moving cameras], pos: frame-major, camera-minor x y z [m],
/// quat: w x y z (the camera's frame: −z looks, +y up)} as base64 Float32, from @p frames'
/// camera poses; cameras empty and no arrays when no camera moves.
nlohmann::json replay_camera_poses(const ReplayFrames& frames);

}  // namespace mjarm::web_detail
