#pragma once
/// @file
/// The frames of a replay, streamed from state.csv in bounded memory: the state rows kept at the
/// replay's rate, every body's world pose at each (by `mj_kinematics` on the recorded qpos), the
/// contacts at each (by `mj_forward` on the recorded qpos, qvel and ctrl: the solver's warm start
/// and switched equality constraints are not recorded, so the forces are close to, not equal to,
/// the simulated ones), and the state columns the plots show.

#include <mujoco/mujoco.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace mjarm::plot {
class CsvRowReader;
}

namespace mjarm::web_detail {

/// The current row's t (column @p column) of a recorded table.
/// @throws Error naming the file and the line when it is not a finite number or is before
///         @p previous (the row before's).
double recorded_time(const plot::CsvRowReader& table, std::size_t column, double previous);

/// What a first pass over state.csv found.
struct StateScan {
  std::int64_t rows = 0;
  double first = 0.0, last = 0.0;  ///< the first and last row's t [s]
};

/// Checks state.csv's header against @p m (its qpos coordinates as `q.*` columns) and reads every
/// row's t, row by row.
/// @throws Error when the model does not match the recording (a joint's q.* column missing,
///         named, or another number of q.* columns than the model's qpos size), when the file has
///         no rows, or as `plot::CsvRowReader` (a truncated or binary file, a row of other cells);
///         naming the line: a t that is not a finite number or goes back in time.
StateScan scan_state(const mjModel& m, const std::filesystem::path& state_csv);

struct ReplayFrames {
  std::vector<double> time;  ///< [s], one per frame
  std::vector<float> pos;    ///< frame-major, body-minor: x y z [m]
  std::vector<float> quat;   ///< frame-major, body-minor: w x y z
  /// the cameras that move (replay_cameras.hpp: `camera_moves`), and their poses at each frame,
  /// frame-major, camera-minor: x y z [m] and w x y z (as MuJoCo's cam_xpos, cam_xmat)
  std::vector<int> cameras;
  std::vector<float> camera_pos, camera_quat;
  /// frame f's contacts are [contact_offsets[f], contact_offsets[f + 1])
  std::vector<unsigned> contact_offsets{0};
  std::vector<float> contacts;  ///< per contact: x y z fx fy fz [m, N]
  /// the state columns asked for, one value per frame each
  std::map<std::string, std::vector<double>> series;
  double largest_gap = 0.0;  ///< largest time between two kept frames [s]
  /// set when a kept row's qpos is not finite (a diverged run): the frames end before it
  std::string stopped;
};

/// The rows of state.csv kept at @p rate frames per second: for each frame time t0 + k/rate the
/// last row at or before it (each row once), and the last row; read row by row.
/// @param series  state columns to sample at the frames (each must exist).
/// @throws Error as `scan_state`, or when the first row's qpos is not finite.
ReplayFrames replay_frames(const mjModel& m, const std::filesystem::path& state_csv, double rate,
                           const std::vector<std::string>& series);

/// The frames @p keep (ascending indices into @p frames).
ReplayFrames select_frames(const ReplayFrames& frames, const std::vector<std::size_t>& keep);

/// Every @p k-th of @p n frames, and the last.
std::vector<std::size_t> every_kth(std::size_t n, std::size_t k);

}  // namespace mjarm::web_detail
