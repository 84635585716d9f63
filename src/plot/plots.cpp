#include "mjarm/plot/plots.hpp"

#include <sys/statvfs.h>

#include <cstdio>
#include <cstring>

#include "figures.hpp"
#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "mjarm/plot/gnuplot.hpp"
#include "plot_files.hpp"
#include "quoted_path.hpp"

namespace mjarm::plot {
namespace {

namespace fs = std::filesystem;

// "1.2 MB free" for the file system holding @p path: the likely cause of a cut file, measured
std::string free_space(const fs::path& path) {
  struct statvfs info {};
  if (::statvfs(path.c_str(), &info) != 0) return "free space unknown";
  const double bytes = static_cast<double>(info.f_bavail) * static_cast<double>(info.f_frsize);
  char text[48];
  std::snprintf(text, sizeof(text), "%.1f MB free there", bytes / 1e6);
  return text;
}

}  // namespace

namespace detail {

// True when @p path is a whole PNG file: the signature first and the IEND chunk last. gnuplot does
// not report a failed write (a full disk leaves an empty or cut PNG and exit status 0).
bool png_complete(const std::filesystem::path& path) {
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  static constexpr unsigned char kEnd[12] = {0,   0,   0,    0,    'I',  'E',
                                             'N', 'D', 0xae, 0x42, 0x60, 0x82};
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return false;
  unsigned char head[8] = {}, tail[12] = {};
  const bool complete = std::fread(head, 1, 8, file) == 8 && std::fseek(file, -12, SEEK_END) == 0 &&
                        std::fread(tail, 1, 12, file) == 12 &&
                        std::memcmp(head, kSignature, 8) == 0 && std::memcmp(tail, kEnd, 12) == 0;
  std::fclose(file);
  return complete;
}

}  // namespace detail

std::vector<PlotInfo> make_plots(const Recording& recording, const fs::path& out_dir,
                                 const PlotOptions& options) {
  check_fields(options);
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

  // every file written from here on is removed again if the drawing fails (plot_files.hpp)
  detail::PlotFiles files(out);
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
    for (const auto& [path, text] : figure.data) files.write(path, text);
    script += "\n# ---- " + figure.info.name + "\nreset\nset output " +
              gnuplot_string(figure.info.path.string()) + "\n" + figure.script + "unset output\n";
    infos.push_back(figure.info);
  }
  const fs::path script_path = data_dir / "plots.gp";
  files.write(script_path, script);
  for (const PlotInfo& info : infos) files.output(info.path);  // no stale figure survives
  run_gnuplot(script_path, options.timeout_s);
  for (const PlotInfo& info : infos) {
    if (detail::png_complete(info.path)) continue;
    // a whole set of figures or none: no empty or cut PNG is left behind, nor its data
    const bool exists = fs::exists(info.path, ec);
    const std::uintmax_t size = exists ? fs::file_size(info.path, ec) : 0;
    throw Error("gnuplot did not write " + quoted(info.path) +
                (exists ? " completely (" + std::to_string(size) +
                              " bytes, no PNG end chunk; is the disk full? " +
                              free_space(absolute_out) + ")"
                        : "") +
                "; no figure was kept, nor its data and script");
  }
  files.keep();
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
