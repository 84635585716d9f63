#pragma once
/// @file
/// The frames of a replay: the state rows kept at the replay's rate and every body's world pose
/// at each, by `mj_kinematics` on the recorded qpos.

#include <mujoco/mujoco.h>

#include <cstddef>
#include <vector>

#include "mjarm/plot/csv_table.hpp"

namespace mjarm::web_detail {

struct ReplayFrames {
  std::vector<double> time;  ///< [s], one per frame
  std::vector<float> pos;    ///< frame-major, body-minor: x y z [m]
  std::vector<float> quat;   ///< frame-major, body-minor: w x y z
  double largest_gap = 0.0;  ///< largest time between two kept frames [s]
};

/// The rows of @p state kept at @p rate frames per second: for each frame time t0 + k/rate the
/// last row at or before it (each row once), and the last row.
/// @throws Error when @p m does not match the recording: a joint's q.* column missing (named),
///         or another number of q.* columns than the model's qpos size.
ReplayFrames replay_frames(const mjModel& m, const plot::CsvTable& state, double rate);

}  // namespace mjarm::web_detail
