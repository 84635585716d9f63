#pragma once
// The four figures of `make_plots`, each as gnuplot commands plus the data files they read.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "mjarm/plot/gnuplot.hpp"  // gnuplot_string: every text that reaches a script
#include "mjarm/plot/plots.hpp"
#include "mjarm/plot/recording.hpp"
#include "plot_files.hpp"

namespace mjarm::plot::detail {

struct Figure {
  PlotInfo info;
  // data files (absolute path, whitespace-separated text) the script reads
  std::vector<std::pair<std::filesystem::path, std::string>> data;
  std::string script;  // drawing commands, after the common `set terminal` / `set output`
};

// Each figure names its data files after itself inside data_dir.
Figure tracking_error_figure(const Recording& recording, const std::filesystem::path& data_dir);
Figure joint_torques_figure(const Recording& recording, const std::filesystem::path& data_dir);
Figure contact_force_figure(const Recording& recording, const std::filesystem::path& data_dir);
Figure phases_figure(const Recording& recording, const std::filesystem::path& data_dir);

// Helpers shared by the figures (figure_style.cpp).
std::string gp_number(double value);               // shortest text gnuplot reads back; NaN as "NaN"
std::string line_color(std::size_t k);             // distinct colours for curves
std::string band_color(std::size_t k);             // light colours for phase bands
std::string describe(const Recording& recording);  // "panda_torque, osc, finished"
// [t0, t1] of the run (never empty)
std::pair<double, double> time_range(const Recording& recording);
// The run's time range as the x range, and light phase bands behind a time plot, named at the
// top.
std::string phase_background(const Recording& recording);
// Common look: fonts, grid, key frame.
std::string common_style();
// The start of a figure over the run's time: common style, phase background, title.
std::string time_figure_preamble(const Recording& recording, const std::string& title);

/// One figure in its own PNG (`plot_trajectory`, `plot_time_series`): the checks and the
/// drawing they share.
/// @throws Error when the size (at least 200 × @p min_height) or the timeout is out of range.
void check_single_figure(const PlotOptions& options, int min_height = 300);
/// `set terminal pngcairo …` at the options' size and `set output` the PNG, with the common
/// style; @p comment is the script's first line (without '#').
std::string single_figure_preamble(const std::filesystem::path& png, const PlotOptions& options,
                                   const std::string& comment);
/// Writes the data and the script through @p files, runs gnuplot and checks the PNG: a whole
/// figure with its data and script, or nothing (@p files kept only then).
/// @throws Error as `run_gnuplot`, or naming the PNG when it is incomplete.
void draw_single_figure(PlotFiles& files, const std::filesystem::path& data_file,
                        const std::string& data, const std::filesystem::path& script_file,
                        const std::string& script, const std::filesystem::path& png,
                        double timeout_s);

/// True when @p path is a whole PNG file (its signature first, the IEND chunk last): gnuplot
/// exits 0 on a full disk, leaving an empty or cut PNG.
bool png_complete(const std::filesystem::path& path);

}  // namespace mjarm::plot::detail
