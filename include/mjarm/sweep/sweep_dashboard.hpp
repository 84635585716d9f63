#pragma once
/// @file
/// A sweep's dashboard: one self-contained HTML file (no network, no server) with the success
/// rate per axis value and its 95 % Wilson interval as a table and a curve, a heat map over two
/// axes chosen on the page, each metric's distribution with its median and 95th percentile, and
/// the trials as a table filtered by text, verdict and outcome, a recorded trial's row linking
/// to its replay (`replay.html` in its record folder, when one was written), recording and video
/// (`mjarm sweep report DIR --html FILE`, docs/sweep.md "Dashboard").

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "mjarm/sweep/sweep_folder.hpp"

namespace mjarm {

/// What was written.
struct SweepDashboard {
  std::filesystem::path path;
  std::int64_t trials = 0;    ///< rows in its table
  std::int64_t recorded = 0;  ///< trials with a recording linked
  std::size_t bytes = 0;
};

/// The dashboard of @p folder's merged results, its links relative to @p html's folder.
/// @throws Error as `sweep_report` and `read_trials`
std::string sweep_dashboard_html(const SweepFolder& folder, const std::filesystem::path& html);

/// Writes `sweep_dashboard_html` to @p html whole (or leaves what was there).
/// @throws Error as `sweep_dashboard_html`, or when the file cannot be written
SweepDashboard write_sweep_dashboard(const SweepFolder& folder, const std::filesystem::path& html);

}  // namespace mjarm
