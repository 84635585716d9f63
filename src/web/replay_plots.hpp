#pragma once
/// @file
/// The figures a replay page plots beside the 3D view, sampled at the replay's frame times (the
/// row of each file nearest below): tracking error, joint torques against their limits, contact
/// force, gripper force — those the recording has columns for.

#include <nlohmann/json.hpp>
#include <vector>

#include "mjarm/plot/recording.hpp"

namespace mjarm::web_detail {

struct ReplayPlots {
  nlohmann::json json;  ///< plot_time and plots: [{title, unit, series: [{label, values}]}]
  int count = 0;
};

ReplayPlots replay_plots(const plot::Recording& recording, const std::vector<double>& frame_times);

}  // namespace mjarm::web_detail
