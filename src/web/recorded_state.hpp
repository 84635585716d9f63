#pragma once
/// @file
/// A recording's state rows as the replay page reads them: the recorder's column names of the
/// model's qpos and qvel (sim/recorder.cpp).

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

}  // namespace mjarm::web_detail
