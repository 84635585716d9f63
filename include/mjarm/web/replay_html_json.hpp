#pragma once
/// @file
/// What `write_replay_html` wrote, as JSON: the document `mjarm replay-html --json` prints and
/// `mjarm.replay_html` returns (docs/replay.md).

#include <filesystem>
#include <nlohmann/json.hpp>

#include "mjarm/web/replay_html.hpp"

namespace mjarm {

/// `{recording, path, bytes, frames, state_rows, rate, start_time, end_time, largest_gap,
/// bodies, drawn_geoms, meshes, cameras, plots}` of the page written from @p recording.
nlohmann::ordered_json replay_html_json(const ReplayHtmlReport& report,
                                        const std::filesystem::path& recording);

}  // namespace mjarm
