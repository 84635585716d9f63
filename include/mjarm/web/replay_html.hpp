#pragma once
/// @file
/// `write_replay_html`: one self-contained HTML file that replays a recording in a browser —
/// the model's geoms drawn by three.js (bundled into the file at build time), every body's
/// recorded pose played back, scrubbed and stepped, the model's cameras as presets, the
/// recording's figures plotted beside it (docs/replay.md).

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/plot/recording.hpp"

namespace mjarm {

struct ReplayHtmlOptions {
  /// Frames kept per simulated second: the state rows nearest below each frame time (the page
  /// interpolates between frames); a recording sparser than this keeps all its rows.
  double rate = 60.0;
  /// The page's title; empty: the recording's folder name.
  std::string title;
  /// Largest file [MB, 10⁶ bytes]: a run whose frames at `rate` would make a larger page keeps
  /// fewer (the rate lowered, then every k-th frame), and the page says so. 50 MB holds about
  /// 15 minutes of a bundled arm at 60 Hz (≈ 50 KB per second of run) and loads in a browser in
  /// seconds.
  double max_mb = 50.0;
};

constexpr auto declared_fields(const ReplayHtmlOptions*) {
  using S = ReplayHtmlOptions;
  return declare<S>("replay-html",
                    field("rate", &S::rate, "Hz", Range::closed(1.0, 10000.0),
                          "frames kept per simulated second"),
                    field("title", &S::title, "the page's title; empty: the recording's folder"),
                    field("max-mb", &S::max_mb, "MB", Range::closed(1.0, 4000.0),
                          "largest file; a longer run keeps fewer frames"));
}

/// What was written.
struct ReplayHtmlReport {
  std::filesystem::path path;
  std::uintmax_t bytes = 0;     ///< size of the file
  int frames = 0;               ///< frames kept
  std::int64_t state_rows = 0;  ///< rows of state.csv
  double rate = 0.0;  ///< frames per simulated second kept: about options.rate (the last row is
                      ///< kept too), lower when the cap decimated
  /// True when the size cap (`max_mb`) kept fewer frames than `options.rate` asked for.
  bool decimated = false;
  /// What the page says of the decimation ("decimated to fit 50 MB: N frames of M state rows
  /// …"); empty when not decimated.
  std::string decimation;
  /// What the page warns of: meshes drawn as boxes (their files missing: the robot's
  /// `missing_meshes()`), a replay that ends early (a qpos that is not finite).
  std::vector<std::string> warnings;
  double start_time = 0.0, end_time = 0.0;  ///< [s]
  int bodies = 0;
  int drawn_geoms = 0;  ///< geoms the page draws: MuJoCo's visible groups (0–2), alpha > 0
  int meshes = 0;       ///< mesh assets embedded
  int cameras = 0;
  int plots = 0;
  /// Largest step between two kept frames [s]: how far apart the recorded states the page
  /// interpolates between can be.
  double largest_gap = 0.0;
};

/// True when this build holds the page's script (three.js bundled at build time: MJARM_WEB).
bool replay_html_available();
/// Why this build holds no page script and how to get one; empty when it holds one (a command
/// that will write a page says this before its run, not after it).
std::string replay_html_missing();

/// Writes the replay of @p recording, recorded on @p robot's model, to @p out through a
/// `FileWriter` (the file is complete or not there). state.csv and task.csv are read from the
/// recording's folder row by row (twice for state.csv), in memory bounded by the size cap: load
/// the recording with `plot::TableRows::header_only` to hold none of their rows.
/// @throws Error when the build holds no page script (how to get one is said), when the model
///         does not match the recording (its qpos coordinates against state.csv's q.* columns,
///         the first missing one named), when an option is out of range (named), when state.csv
///         or task.csv is truncated, binary, of other columns or has no rows (named, with the
///         line), when the page without any frame is over the size cap, or when the file cannot
///         be written (named, with the reason; an older file is kept).
ReplayHtmlReport write_replay_html(const Robot& robot, const plot::Recording& recording,
                                   const std::filesystem::path& out,
                                   const ReplayHtmlOptions& options = {});

}  // namespace mjarm
