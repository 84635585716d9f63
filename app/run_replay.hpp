// A recorded run's replay page (`mjarm run SCENARIO --record DIR --html [FILE]`, the demo):
// checked before the run, written from the finished recording as `mjarm replay-html` writes it
// (docs/replay.md).
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>

#include "mjarm/web/replay_html.hpp"

namespace mjarm::cli {

/// Adds `--html [FILE]` to @p app, needing @p record: the page goes to FILE, or without one
/// beside the recording (`replay_page_beside`). Whether it was given is the option's count().
CLI::Option* add_run_html_option(CLI::App& app, CLI::Option* record, std::string& file,
                                 const std::string& help);

/// Where the page of the recording @p recording goes when --html names no file: beside the
/// folder, with its name: `out/pick` → `out/pick.html`.
std::filesystem::path replay_page_beside(const std::filesystem::path& recording);

/// Before the run: this build holds the page (an `Error` says how to get one otherwise).
void check_replay_available(const std::string& option);
/// Before the run: the build holds the page and @p html can be written.
void check_run_replay(const std::string& option, const std::filesystem::path& html);

/// Writes the page of the recording @p recording (its model.mjb) to @p html.
/// @throws Error as `write_replay_html`, or for a missing or incomplete recording
ReplayHtmlReport write_run_replay(const std::filesystem::path& recording,
                                  const std::filesystem::path& html);

}  // namespace mjarm::cli
