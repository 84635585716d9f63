#pragma once
/// @file
/// The cameras of a replay that move with the run other than rigidly with their body — MuJoCo's
/// modes track, trackcom, targetbody and targetbodycom — posed at every frame as MuJoCo poses them
/// (`mj_kinematics`, `mj_comPos`, `mj_camlight` on the recorded qpos). A fixed camera rides its
/// body, which the frames already pose: it needs nothing per frame.

#include <mujoco/mujoco.h>

#include <nlohmann/json.hpp>
#include <vector>

#include "mjarm/plot/csv_table.hpp"

namespace mjarm::web_detail {

/// True when camera @p c of @p m is posed per frame (its mode is not mjCAMLIGHT_FIXED).
bool camera_moves(const mjModel& m, int c);

/// {cameras: [the ids of the moving cameras], pos: frame-major, camera-minor x y z [m],
/// quat: w x y z (the camera's frame: −z looks, +y up)} as base64 Float32, at the state rows of
/// @p frame_times (the last row at or before each); cameras empty and no arrays when no camera
/// moves.
nlohmann::json replay_camera_poses(const mjModel& m, const plot::CsvTable& state,
                                   const std::vector<double>& frame_times);

}  // namespace mjarm::web_detail
