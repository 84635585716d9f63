#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "fuzz_targets.hpp"
#include "mjarm/plot/recording.hpp"
#include "refusal.hpp"

namespace mjarm::fuzz {

namespace {

// The files of a recording folder that `Recording::load` reads; the input holds each after a
// line "==> NAME <==" (as `head` prints several files), so that one input mutates them all.
constexpr std::array<std::string_view, 4> kRecordingFiles{"summary.json", "state.csv", "task.csv",
                                                          "events.csv"};

// A scratch folder of this process, removed at exit.
struct RecordingFolder {
  std::filesystem::path path = std::filesystem::temp_directory_path() /
                               ("mjarm-fuzz-recording-" + std::to_string(::getpid()));
  RecordingFolder() { std::filesystem::create_directories(path); }
  ~RecordingFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

// Writes the files the input holds (only the four names above: an input never names a path)
// and removes the others, so that a missing file is part of what is fuzzed.
void write_recording(std::string_view text, const std::filesystem::path& folder) {
  for (const auto name : kRecordingFiles) std::filesystem::remove(folder / name);
  constexpr std::string_view kOpen = "==> ", kClose = " <==\n";
  std::size_t at = text.find(kOpen);
  while (at != std::string_view::npos) {
    const std::size_t name_end = text.find(kClose, at);
    if (name_end == std::string_view::npos) break;
    const std::string_view name = text.substr(at + kOpen.size(), name_end - at - kOpen.size());
    const std::size_t body = name_end + kClose.size();
    const std::size_t next = text.find("\n" + std::string(kOpen), body);
    const std::size_t body_end = next == std::string_view::npos ? text.size() : next + 1;
    for (const auto known : kRecordingFiles) {
      if (name == known) {
        std::ofstream(folder / known, std::ios::binary | std::ios::trunc)
            .write(text.data() + body, static_cast<std::streamsize>(body_end - body));
      }
    }
    at = next == std::string_view::npos ? next : next + 1;
  }
}

}  // namespace

int fuzz_recording(const std::uint8_t* data, std::size_t size) {
  static const RecordingFolder folder;
  write_recording(as_text(data, size), folder.path);
  return accept_or_refuse([&] { plot::Recording::load(folder.path); });
}

}  // namespace mjarm::fuzz
