#pragma once
// `PlotFiles`: what one drawing writes — the folders it makes, gnuplot's data files and script,
// the PNGs gnuplot draws — removed again unless the drawing succeeded, so that a failure at any
// step (a full disk, gnuplot failing, stopped or interrupted, an exception) leaves nothing of it.

#include <filesystem>
#include <memory>
#include <string_view>
#include <vector>

#include "folder_lock.hpp"

namespace mjarm::plot::detail {

class PlotFiles {
 public:
  /// Makes @p out_dir and its `gnuplot/` folder for the data and the script, and locks the
  /// folder while the drawing writes it (folder_lock.hpp).
  /// @throws Error naming @p out_dir when either cannot be made, or naming the other writer's
  ///         PID when another drawing holds the folder.
  explicit PlotFiles(const std::filesystem::path& out_dir);
  /// Unless `keep()` was called: removes the files written and the outputs registered, then
  /// the folders this drawing made (when empty).
  ~PlotFiles();
  PlotFiles(const PlotFiles&) = delete;
  PlotFiles& operator=(const PlotFiles&) = delete;

  /// The output folder, absolute (a file name in a script must not start with '<' or '|').
  const std::filesystem::path& out() const noexcept { return out_; }
  /// `out()/gnuplot`: the data files and the script, kept for redrawing.
  const std::filesystem::path& data_dir() const noexcept { return data_dir_; }

  /// Writes @p text to @p path (whole or not at all, file_writer.hpp) and remembers it.
  /// @throws Error naming the file and the reason.
  void write(const std::filesystem::path& path, std::string_view text);
  /// A file another program writes (a PNG gnuplot draws): an old one is removed now, so that no
  /// stale figure survives a failure, and the new one is removed unless the drawing is kept.
  void output(const std::filesystem::path& path);
  /// The drawing succeeded: everything stays.
  void keep() noexcept { kept_ = true; }

 private:
  std::filesystem::path out_;
  std::filesystem::path data_dir_;
  std::vector<std::filesystem::path> made_;  // folders that did not exist, innermost last
  std::vector<std::filesystem::path> files_;
  std::unique_ptr<FolderLock> lock_;
  bool kept_ = false;
};

}  // namespace mjarm::plot::detail
