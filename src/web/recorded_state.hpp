#pragma once
/// @file
/// A recording's state rows as the replay page reads them: the recorder's column names of the
/// model's qpos and qvel (sim/recorder.cpp), and the row shown at each frame time.

#include <mujoco/mujoco.h>

#include <cstddef>
#include <string>
#include <vector>

namespace mjarm::web_detail {

/// state.csv's columns of the model's qpos, in qpos order: "q.<joint>", "q.<joint>.k" for free
/// and ball joints, "joint<id>" for a joint without a name.
std::vector<std::string> qpos_columns(const mjModel& m);

/// state.csv's columns of the model's qvel, in qvel order ("v." as "q." above).
std::vector<std::string> qvel_columns(const mjModel& m);

/// For each of @p times, the last row of @p t (ascending) at or before it (row 0 before the first).
std::vector<std::size_t> rows_at_or_before(const std::vector<double>& t,
                                           const std::vector<double>& times);

}  // namespace mjarm::web_detail
