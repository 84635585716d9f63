#pragma once
/// @file
/// The figures of a recording, drawn with gnuplot as PNG files: end-effector tracking error,
/// joint torques against their limits, contact force, task phases (docs/plot.md).

#include <filesystem>
#include <string>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/plot/recording.hpp"

namespace mjarm::plot {

/// How the figures are drawn.
struct PlotOptions {
  int width = 1280;         ///< [pixels], 200 … 16384
  int height = 720;         ///< [pixels], 150 … 16384
  double timeout_s = 60.0;  ///< how long gnuplot may take for all figures [s]
};

constexpr auto declared_fields(const PlotOptions*) {
  using S = PlotOptions;
  return declare<S>(
      "plot", field("width", &S::width, "pixels", Range::closed(200, 16384), "image width"),
      field("height", &S::height, "pixels", Range::closed(150, 16384),
            "image height (a single figure: at least 300)"),
      field("timeout_s", &S::timeout_s, "s", Range::positive(),
            "how long gnuplot may take for all figures"));
}

/// One figure written, and what it shows.
struct PlotInfo {
  std::string name;            ///< "tracking_error", "joint_torques", "contact_force", "phases"
  std::filesystem::path path;  ///< the PNG file
  std::string title;           ///< the figure's title
  std::vector<std::string> series;  ///< the curves drawn, as the legend names them
  std::vector<std::string> notes;   ///< what a reader should know: peaks, saturation, "no contact"
};

/// Draws the four figures of @p recording into @p out_dir (created when missing) as
/// NAME.png; the gnuplot script and data files stay in @p out_dir/gnuplot/ for restyling.
/// @throws Error when the recording lacks a column a figure needs (file and column named),
///         when @p out_dir cannot be created or written, when the size is out of range, or when
///         gnuplot is missing (the Debian package gnuplot-nox is named) or fails.
std::vector<PlotInfo> make_plots(const Recording& recording, const std::filesystem::path& out_dir,
                                 const PlotOptions& options = {});

/// Loads the recording in @p recording and draws its figures into @p out_dir (empty:
/// RECORDING/plots). Returns the PNG paths.
/// @throws Error as `Recording::load` and `make_plots`.
std::vector<std::filesystem::path> write_plots(const std::filesystem::path& recording,
                                               const std::filesystem::path& out_dir,
                                               const PlotOptions& options = {});

}  // namespace mjarm::plot
