#pragma once
/// @file
/// A sweep file (YAML or JSON): which scenario, its fixed parameters, the axes to vary (lists,
/// linear or log ranges, zipped axes), a seeded Latin hypercube over ranges, the seeds of each
/// point and which trials to record. Keys are the scenario's parameter names as a command line
/// writes them (docs/sweep.md).
///
/// @code{.yaml}
/// scenario: pick-place
/// parameters: {robot: arm6, mode: torque}
/// axes:
///   grasp: [weld, friction]
///   object-size: {from: 0.015, to: 0.03, num: 4}
/// zip: [[grasp, mode]]      # axes that advance together (same length)
/// random: {samples: 20, seed: 7, ranges: {motion.dwell-time: {from: 0.1, to: 1, log: true}}}
/// seeds: 25                 # seeds 1..25 per point; or {first: 100, count: 25}
/// record: failures          # none | failures | all
/// @endcode

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mjarm/fields.hpp"

namespace mjarm {

/// Which trials keep a recording and a video.
enum class RecordTrials { none, failures, all };

constexpr auto declared_names(const RecordTrials*) {
  using E = RecordTrials;
  return std::array{EnumName{E::none, "none", "no trial"},
                    EnumName{E::failures, "failures", "the trials that did not succeed"},
                    EnumName{E::all, "all", "every trial"}};
}

/// One varied parameter and its values, in order.
struct SweepAxis {
  std::string name;                            ///< the parameter ("object-size")
  std::vector<nlohmann::ordered_json> values;  ///< at least one
};

/// A range a random design draws from (uniform, or uniform in log when `log`).
struct SweepRange {
  std::string name;
  double from = 0.0;
  double to = 1.0;
  bool log = false;
  bool integer = false;  ///< the parameter takes whole numbers: draws are rounded
};

/// A seeded Latin hypercube: `samples` points, each range cut into `samples` equal strata, one
/// draw per stratum, the strata of each range shuffled independently.
struct SweepRandom {
  std::int64_t samples = 0;  ///< 0: no random design
  std::uint64_t seed = 1;
  std::vector<SweepRange> ranges;
};

/// A whole sweep file, read and checked against the scenario's parameters.
struct SweepFile {
  std::string scenario;
  nlohmann::ordered_json parameters = nlohmann::ordered_json::object();  ///< fixed values
  /// The grid's axes; axes zipped together are one axis of the grid whose values are tuples
  /// (`groups`: indices into `axes`, each group advancing together; an unzipped axis is a group
  /// of its own). The grid is the product of the groups, the last group fastest.
  std::vector<SweepAxis> axes;
  std::vector<std::vector<std::size_t>> groups;
  SweepRandom random;  ///< combined with every grid point
  std::uint64_t first_seed = 1;
  std::int64_t seeds = 1;  ///< trials per point: first_seed … first_seed + seeds − 1
  RecordTrials record = RecordTrials::none;
  std::string source;  ///< where it was read from, for messages
};

/// Most trials a sweep may have: more is refused with the count before any work.
inline constexpr std::int64_t kMaxSweepTrials = 100'000'000;

/// Reads and checks the sweep file at @p path (see `parse_sweep_file`).
SweepFile read_sweep_file(const std::filesystem::path& path);

/// Reads and checks a sweep file's @p text (YAML or JSON), naming @p source in messages.
/// @throws Error "sweep.yaml:4: unknown key 'axis'; closest: axes; …", for an unknown scenario or
///         parameter (with the closest), a value the parameter refuses (every axis value is
///         checked), an empty axis, zipped axes of different lengths, an axis also fixed or
///         zipped twice, a range that is empty or not positive on a log scale, a parameter that is
///         not a number for a range, seeds for a scenario that draws nothing, and a sweep of
///         more than `kMaxSweepTrials` trials (with the count).
SweepFile parse_sweep_file(const std::string& text, const std::string& source);

/// The sweep file as JSON, every value explicit (what a plan is made from and hashed).
nlohmann::ordered_json sweep_file_json(const SweepFile& file);

/// The same sweep from `sweep_file_json`'s output (a frozen plan read back).
/// @throws Error as `parse_sweep_file`
SweepFile sweep_file_from_json(const nlohmann::ordered_json& json, const std::string& source);

}  // namespace mjarm
