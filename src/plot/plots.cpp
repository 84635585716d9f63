#include "mjarm/plot/plots.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>

#include "figures.hpp"
#include "mjarm/error.hpp"
#include "mjarm/plot/gnuplot.hpp"
#include "quoted_path.hpp"

namespace mjarm::plot {
namespace {

namespace fs = std::filesystem;

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw Error("cannot write " + quoted(path) + ": " + std::strerror(errno));
  out << text;
  out.close();
  if (!out) throw Error("cannot write " + quoted(path) + ": " + std::strerror(errno));
}

// Creates @p out_dir and its subfolder @p data_dir.
void prepare_directories(const fs::path& out_dir, const fs::path& data_dir) {
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw Error("cannot create the plot folder " + quoted(out_dir) + ": " + ec.message());
  if (!fs::is_directory(out_dir, ec))
    throw Error("the plot folder " + quoted(out_dir) + " is not a directory");
  fs::create_directories(data_dir, ec);
  if (ec) throw Error("cannot write into the plot folder " + quoted(out_dir) + ": " + ec.message());
}

}  // namespace

std::vector<PlotInfo> make_plots(const Recording& recording, const fs::path& out_dir,
                                 const PlotOptions& options) {
  if (options.width < 200 || options.height < 150 || options.width > 16384 ||
      options.height > 16384)
    throw Error("plot size " + std::to_string(options.width) + "x" +
                std::to_string(options.height) + " is out of range (200x150 … 16384x16384 pixels)");
  if (!(options.timeout_s > 0.0)) throw Error("plot timeout must be positive");
  // every figure is built (and every column checked) before anything is written or run
  const fs::path out = out_dir.empty() ? recording.directory() / "plots" : out_dir;
  std::error_code ec;
  // absolute, so that no file name in the script starts with '<' or '|' (a command to gnuplot)
  const fs::path absolute_out = fs::absolute(out, ec);
  if (ec || !absolute_out.is_absolute())
    throw Error("cannot resolve the plot folder " + quoted(out) + ": " + ec.message());
  const fs::path data_dir = absolute_out / "gnuplot";
  std::vector<detail::Figure> figures;
  figures.push_back(detail::tracking_error_figure(recording, data_dir));
  figures.push_back(detail::joint_torques_figure(recording, data_dir));
  figures.push_back(detail::contact_force_figure(recording, data_dir));
  figures.push_back(detail::phases_figure(recording, data_dir));
  find_gnuplot();  // fail early, before files are written, when gnuplot is not installed

  prepare_directories(out, data_dir);
  // a font size that stays readable from 640x360 to 4K: proportional to the height
  const int font = std::max(9, options.height / 52);
  // the recording's folder is quoted like every other text: a newline in its name must not
  // end the comment and start a command
  std::string script = "# drawn by `mjarm plot` from " +
                       gnuplot_string(recording.directory().string()) +
                       "; run `gnuplot plots.gp` to redraw\n"
                       "set terminal pngcairo noenhanced size " +
                       std::to_string(options.width) + "," + std::to_string(options.height) +
                       " font 'DejaVu Sans," + std::to_string(font) +
                       "' linewidth 1\n"
                       "set encoding utf8\n";
  std::vector<PlotInfo> infos;
  for (detail::Figure& figure : figures) {
    figure.info.path = absolute_out / (figure.info.name + ".png");
    for (const auto& [path, text] : figure.data) write_text(path, text);
    script += "\n# ---- " + figure.info.name + "\nreset\nset output " +
              gnuplot_string(figure.info.path.string()) + "\n" + figure.script + "unset output\n";
    infos.push_back(figure.info);
  }
  const fs::path script_path = data_dir / "plots.gp";
  write_text(script_path, script);
  for (const PlotInfo& info : infos)
    fs::remove(info.path, ec);  // no stale figure survives a failure
  run_gnuplot(script_path, options.timeout_s);
  for (const PlotInfo& info : infos) {
    if (!fs::exists(info.path, ec) || fs::file_size(info.path, ec) == 0)
      throw Error("gnuplot did not write " + quoted(info.path) + " (script " + quoted(script_path) +
                  ")");
  }
  return infos;
}

std::vector<fs::path> write_plots(const fs::path& recording, const fs::path& out_dir,
                                  const PlotOptions& options) {
  const Recording loaded = Recording::load(recording);
  std::vector<fs::path> paths;
  for (const PlotInfo& info : make_plots(loaded, out_dir, options)) paths.push_back(info.path);
  return paths;
}

}  // namespace mjarm::plot
