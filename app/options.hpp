#pragma once
/// @file
/// Command-line pieces shared by the `mjarm` commands: the MODEL argument, the frame (--site),
/// the configuration (--q / --key), validators for numbers and picture sizes, and the checks of
/// output paths made before any work starts.
///
/// The rule for counts and rates: every option that sets how much work a command does (a number
/// of samples, steps, frames or seeds; a rate in Hz or frames per second; a duration that the
/// run spends) is checked while parsing with `count_in` or `number_in`, so an absurd value is a
/// usage error (exit 2) that names the accepted range, never minutes of work or an endless loop.

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm::cli {

/// Accepts only a finite decimal number ("nan", "inf", "1e999" and trailing junk are rejected).
CLI::Validator finite_number();

/// Accepts only a whole number ≥ 0 written with digits that fits 64 bits (rejects "-1", which
/// would wrap around, and 2^64 or more, which CLI11 would clamp). A leading zero is refused:
/// CLI11 would read "010" as octal eight.
CLI::Validator non_negative_integer();

/// A count option's rule: a whole number written with digits, from @p min to @p max. The error
/// names the range ("--samples: '1e20' is not a whole number from 0 to 100000000").
CLI::Validator count_in(std::uint64_t min, std::uint64_t max);

/// A rate or duration option's rule: a finite number from @p min to @p max (both included),
/// with the bounds printed in their shortest form ("from 1 to 240").
CLI::Validator number_in(double min, double max);

/// @p value in its shortest readable form ("240", "0.001", "1e+06"), as bounds are printed.
std::string readable(double value);
/// The largest time budget a `--timeout-ms` option accepts [ms]: one minute.
inline constexpr double kMaxTimeoutMs = 60000.0;

/// Accepts a duration in @p unit ("ms" or "s"): a finite decimal number ≤ @p max and > 0 (≥ 0
/// when @p zero_allowed); the message names the accepted range. Every duration or timeout
/// option of the CLI is bounded with it: a huge value would overflow a clock or run for ever.
CLI::Validator duration_at_most(double max, const std::string& unit, bool zero_allowed = false);

/// `duration_at_most(kMaxTimeoutMs, "ms")`: every `--timeout-ms` of the CLI uses it.
CLI::Validator timeout_ms();

/// A picture's size in pixels.
struct PixelSize {
  int width = 0;
  int height = 0;
};

/// Accepts "WIDTHxHEIGHT" with whole numbers from @p min up to @p max in each direction, both
/// even when @p even (an MP4's yuv420p needs that).
CLI::Validator pixel_size(PixelSize min = {1, 1}, bool even = false,
                          PixelSize max = {16384, 16384});

/// The size a pixel_size()-checked text names.
PixelSize parse_pixel_size(const std::string& text);

/// Adds `--max-model-elements N` (the bound on a model's elements, `set_max_model_elements`)
/// to every command under @p root that loads a model: one option name everywhere.
void add_model_size_option(CLI::App& root);

/// Adds the positional MODEL argument (bundled name or file path) to @p command.
CLI::Option* add_model_argument(CLI::App& command, std::string& model);

/// Adds `--site NAME` (a site, or a body when no site has that name) to @p command.
CLI::Option* add_site_option(CLI::App& command, std::string& site);

/// Adds `--json` to @p command.
/// What a command's video options read.
struct VideoCli {
  std::string path, camera, size = "640x480";
  double fps = 30.0;
};
/// Adds `--video` ("write an MP4 of @p what …"), `--camera` when @p camera_help is not empty,
/// `--size` and `--fps` (both needing --video); returns the --video option.
CLI::Option* add_video_options(CLI::App& app, VideoCli& o, const std::string& what,
                               const std::string& camera_help = {});

CLI::Option* add_json_flag(CLI::App& command, bool& json);

/// Loads MODEL (a bundled name or a path) with `Robot::load`.
/// @throws Error when the model cannot be found or loaded.
Robot load_model(const std::string& model, const LoadOptions& options = {});

/// The frame to use: @p site when given, else the model's only named site.
/// @throws UsageError listing the sites when none was given and the model has several (or none).
std::string resolve_site(const Robot& robot, const std::string& site);

/// A configuration of a chain and where it came from.
struct Configuration {
  Eigen::VectorXd q;     ///< chain joint values (chain order) [rad or m]
  Eigen::VectorXd qpos;  ///< full qpos (nq) holding q; joints off the chain as the source says
  std::string source;    ///< "--q", "keyframe 'home'" or "qpos0"
  /// The typed values outside their joint's range, one line each (accepted only with
  /// --allow-outside-range): "joint 'joint1' = 10 rad, outside its range [-2.8973, 2.8973]".
  std::vector<std::string> outside_range;
};

/// The flag that lets a command use typed joint values outside the joint ranges.
inline constexpr const char* kAllowOutsideRangeFlag = "--allow-outside-range";
/// Adds `--allow-outside-range` to @p command (fk, singularities, render, ik).
CLI::Option* add_allow_outside_range_flag(CLI::App& command, bool& allow);

/// The one check of joint values typed on a command line (every `--q`, `--from`) against the
/// joint ranges: the hinge and slide joints among @p joints that are limited and whose value in
/// @p qpos lies outside their range. Without @p allowed they are a usage error naming the
/// option, the joint, the value, the range (and the value in degrees when it looks like one);
/// with it each is a warning on stderr. @p refusal ends the message (what to do instead).
/// @return the values outside, one line each (empty when all are inside)
/// @throws UsageError when a value is outside and not @p allowed.
std::vector<std::string> check_joint_ranges(const Robot& robot, const std::vector<int>& joints,
                                            const Eigen::Ref<const Eigen::VectorXd>& qpos,
                                            const std::string& option, bool allowed,
                                            const std::string& refusal);

/// The configuration given by @p q values (other joints at qpos0), by keyframe @p key, or qpos0
/// when both are empty. @p option is the name the user typed for the values ("--q", "--from"):
/// errors and `Configuration::source` name it. Typed values go through `check_joint_ranges`:
/// outside a joint's range they are refused unless @p allow_outside_range; @p refusal ends that
/// error (default: the hint to pass --allow-outside-range).
/// @throws UsageError when q has the wrong length, a value lies outside its joint's range (and
///         not @p allow_outside_range) or the keyframe does not exist (all mistakes on the
///         command line: exit 2).
Configuration resolve_configuration(const Chain& chain, const std::vector<double>& q,
                                    const std::string& key, const std::string& option = "--q",
                                    bool allow_outside_range = false,
                                    const std::string& refusal = "");

/// Checks, before any work, that a file can be created at @p path: its folder exists (or can be
/// made, when @p make_parents), is a folder and is writable, and @p path is not a folder. The
/// file is not created.
/// @param option the option that named the path ("--out"), for the message
/// @throws UsageError naming the option, the path and what is wrong.
void check_output_file(const std::string& path, const std::string& option,
                       bool make_parents = false);

/// Checks, before any work, that @p path is a folder that exists and is writable or can be
/// made (its nearest existing ancestor is a writable folder).
/// @throws UsageError naming the option, the path and what is wrong.
void check_output_folder(const std::string& path, const std::string& option);

}  // namespace mjarm::cli
