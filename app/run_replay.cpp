#include "run_replay.hpp"

#include "mjarm/error.hpp"
#include "mjarm/plot/recording.hpp"
#include "mjarm/web/recorded_model.hpp"
#include "options.hpp"

namespace mjarm::cli {

namespace fs = std::filesystem;

CLI::Option* add_run_html_option(CLI::App& app, CLI::Option* record, std::string& file,
                                 const std::string& help) {
  return app.add_option("--html", file, help)->expected(0, 1)->type_name("[FILE]")->needs(record);
}

fs::path replay_page_beside(const fs::path& recording) {
  fs::path folder = recording.lexically_normal();
  if (!folder.has_filename()) folder = folder.parent_path();  // "out/pick/"
  const std::string name = folder.filename().string();
  if (name.empty() || name == "." || name == "..")  // "." names no folder: its full path does
    folder = fs::absolute(folder).lexically_normal();
  if (!folder.has_filename()) folder = folder.parent_path();
  folder += ".html";
  return folder;
}

void check_replay_available(const std::string& option) {
  const std::string missing = replay_html_missing();
  if (!missing.empty()) throw Error(option + ": " + missing);
}

void check_run_replay(const std::string& option, const fs::path& html) {
  check_replay_available(option);
  check_output_file(html.string(), option);
}

ReplayHtmlReport write_run_replay(const fs::path& recording, const fs::path& html) {
  const plot::Recording loaded = plot::Recording::load(recording, plot::TableRows::header_only);
  return write_replay_html(recorded_model(loaded), loaded, html);
}

}  // namespace mjarm::cli
