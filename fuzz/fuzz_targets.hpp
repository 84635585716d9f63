#pragma once
/// @file
/// The fuzz targets: one reader of user files each, fed arbitrary bytes (docs/hardening.md,
/// "Fuzzing"). A target returns 0 when its reader accepts the input or refuses it with
/// `mjarm::Error`; anything else escapes it: another exception, a crash, a sanitizer report.
/// libFuzzer drives each one (libfuzzer_entry.cpp, the clang build `MJARM_FUZZ=ON`) and the test
/// suite replays the seeds and regression inputs through them (tests/fuzz).

#include <cstddef>
#include <cstdint>
#include <span>

namespace mjarm::fuzz {

/// MJCF text through `Robot::from_string` (staging, MuJoCo's parser and compiler, the checks).
int fuzz_mjcf(const std::uint8_t* data, std::size_t size);
/// URDF text through `Robot::from_string` (the name and asset checks, MuJoCo's URDF parser).
int fuzz_urdf(const std::uint8_t* data, std::size_t size);
/// A scene file (YAML or JSON) through `parse_scene`, its models resolved in the models folder.
int fuzz_scene(const std::uint8_t* data, std::size_t size);
/// A waypoint file in JSON through `parse_waypoints_json`.
int fuzz_waypoints_json(const std::uint8_t* data, std::size_t size);
/// A waypoint file in CSV through `parse_waypoints_csv`.
int fuzz_waypoints_csv(const std::uint8_t* data, std::size_t size);
/// A teleop session file through `parse_session_log`.
int fuzz_session(const std::uint8_t* data, std::size_t size);
/// A viewer script through `ViewerScript::parse`.
int fuzz_viewer_script(const std::uint8_t* data, std::size_t size);
/// A recording folder through `Recording::load` (plot): the input holds its files
/// (recording_target.cpp).
int fuzz_recording(const std::uint8_t* data, std::size_t size);

/// A target and its name (the name of its corpus, dictionary and program: fuzz_NAME).
struct FuzzTarget {
  const char* name;
  int (*run)(const std::uint8_t* data, std::size_t size);
};

/// Every target, in the order `make fuzz` runs them.
std::span<const FuzzTarget> fuzz_targets();

}  // namespace mjarm::fuzz
