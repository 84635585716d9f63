#pragma once
/// @file
/// The page `mjarm view --web` serves: the bodies drawn from the streamed frames, the panel's
/// sliders and modes from the greeting, each move sent back as a message (web_viewer.hpp).

#include <mujoco/mujoco.h>

#include <nlohmann/json.hpp>
#include <string>

namespace mjarm {

/// The whole page, one self-contained HTML file (no network beyond its own server).
const std::string& web_viewer_page();

/// Every body but the world, in id order (the frames' order): {"name", "parent"}, parent 0 the
/// world; the page draws each as a segment from its parent.
nlohmann::json web_viewer_bodies(const mjModel& model);

}  // namespace mjarm
