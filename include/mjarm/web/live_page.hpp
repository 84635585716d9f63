#pragma once
/// @file
/// The live view's page (`mjarm view --web`, `PassiveWebViewer`): the replay page's script in live
/// mode. It builds the same scene as a replay file from the server's greeting, then poses the
/// bodies from the frames streamed over the WebSocket (docs/replay.md "Live mode", docs/viewer.md
/// "In a browser").

#include <mujoco/mujoco.h>

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace mjarm {

/// The page a `LiveServer` serves at `/`: one HTML file, the bundled script inline, in live mode
/// (it connects to `/ws` with the page's own query, so a token in the address goes along).
/// @throws Error when the build holds no page script: "@p who: " followed by the words
///         `replay-html` uses (MJARM_WEB, and how to get it)
std::string live_page_html(std::string_view who);

/// The model as the page draws it, as a replay file describes it: every body (index = body id,
/// with its parent), the drawn geoms with MuJoCo's colours, the meshes and textures they use, the
/// cameras, the joints, the model's centre and extent. A greeting's base: its sender adds the
/// layout of its frames.
nlohmann::json live_scene(const mjModel& m);

}  // namespace mjarm
