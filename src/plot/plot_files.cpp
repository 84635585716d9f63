#include "plot_files.hpp"

#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "quoted_path.hpp"

namespace mjarm::plot::detail {

namespace fs = std::filesystem;

PlotFiles::PlotFiles(const fs::path& out_dir) {
  std::error_code ec;
  out_ = fs::absolute(out_dir, ec);
  if (ec || !out_.is_absolute())
    throw Error("cannot resolve the plot folder " + quoted(out_dir) + ": " + ec.message());
  data_dir_ = out_ / "gnuplot";
  // the folders that do not exist yet, outermost first: removed again after a failure
  for (fs::path p = data_dir_; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    made_.insert(made_.begin(), p);
    if (p == p.parent_path()) break;
  }
  fs::create_directories(data_dir_, ec);
  if (ec || !fs::is_directory(out_, ec))
    throw Error("cannot create the plot folder " + quoted(out_dir) +
                (ec ? ": " + ec.message() : std::string(" (not a directory)")));
  try {
    lock_ = std::make_unique<FolderLock>(out_, "plot folder");
  } catch (const Error&) {
    for (auto it = made_.rbegin(); it != made_.rend(); ++it) fs::remove(*it, ec);
    throw;
  }
}

PlotFiles::~PlotFiles() {
  std::error_code ec;
  if (!kept_)
    for (const fs::path& file : files_) fs::remove(file, ec);
  lock_.reset();  // removes its file: the folders made can then be empty
  if (!kept_)     // a folder another writer has filled meanwhile is not empty, and stays
    for (auto it = made_.rbegin(); it != made_.rend(); ++it) fs::remove(*it, ec);
}

void PlotFiles::write(const fs::path& path, std::string_view text) {
  files_.push_back(path);  // before: a failed write removes its temporary file itself
  write_file(path, text);
}

void PlotFiles::output(const fs::path& path) {
  files_.push_back(path);
  std::error_code ec;
  fs::remove(path, ec);
}

}  // namespace mjarm::plot::detail
