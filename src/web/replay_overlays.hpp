#pragma once
/// @file
/// What the replay page draws over the scene, per frame: the tool frame and the target frame
/// (task.csv's `ee.*` and `ref.*` at the frames: sample_task), and the contacts — their points and
/// force vectors (replay_frames).

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "replay_frames.hpp"

namespace mjarm::web_detail {

/// The task.csv columns the overlays read: `ee.*` and `ref.*` (x y z qw qx qy qz).
std::vector<std::string> overlay_task_columns();

/// Writes "tool", "target" (frame-major x y z qw qx qy qz, absent when task.csv has no such
/// columns) and "contacts" ({offsets: frame f's contacts are [offsets[f], offsets[f+1]), points:
/// x y z fx fy fz per contact [m, N]}).
nlohmann::json replay_overlays(const ReplayFrames& frames,
                               const std::map<std::string, std::vector<double>>& task);

}  // namespace mjarm::web_detail
