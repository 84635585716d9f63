#pragma once
/// @file
/// The figures a replay page plots beside the 3D view, sampled at the replay's frames (the row of
/// each file at or before each frame time): tracking error, joint torques against their limits,
/// contact force, gripper force — those the recording has columns for.

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mjarm/plot/recording.hpp"

namespace mjarm::web_detail {

struct ReplayPlots {
  nlohmann::json json;  ///< plot_time and plots: [{title, unit, series: [{label, values}]}]
  int count = 0;
};

/// The state.csv columns the plots read (those @p recording's state header has): the actuators'
/// `force.*` with a force range, `contact.normal_force`.
std::vector<std::string> plot_state_columns(const plot::Recording& recording);
/// The task.csv columns the plots read: `err.*`, `grasp.force`.
std::vector<std::string> plot_task_columns();

/// @p state, @p task: the columns above at the frames (replay_frames, sample_task).
ReplayPlots replay_plots(const plot::Recording& recording, const std::vector<double>& frame_times,
                         const std::map<std::string, std::vector<double>>& state,
                         const std::map<std::string, std::vector<double>>& task);

}  // namespace mjarm::web_detail
