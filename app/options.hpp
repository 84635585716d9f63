#pragma once
/// @file
/// Command-line pieces shared by the `mjarm` commands: the MODEL argument, the frame (--site),
/// the configuration (--q / --key), and validators for numbers and picture sizes.

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <string>
#include <vector>

#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm::cli {

/// Accepts only a finite decimal number ("nan", "inf", "1e999" and trailing junk are rejected).
CLI::Validator finite_number();

/// Accepts only a whole number ≥ 0 written with digits (rejects "-1", which would wrap around).
CLI::Validator non_negative_integer();

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

/// Accepts "WIDTHxHEIGHT" with whole numbers from @p min up to 16384 in each direction, both
/// even when @p even (an MP4's yuv420p needs that).
CLI::Validator pixel_size(PixelSize min = {1, 1}, bool even = false);

/// The size a pixel_size()-checked text names.
PixelSize parse_pixel_size(const std::string& text);

/// Adds the positional MODEL argument (bundled name or file path) to @p command.
CLI::Option* add_model_argument(CLI::App& command, std::string& model);

/// Adds `--site NAME` (a site, or a body when no site has that name) to @p command.
CLI::Option* add_site_option(CLI::App& command, std::string& site);

/// Adds `--json` to @p command.
CLI::Option* add_json_flag(CLI::App& command, bool& json);

/// Loads MODEL (a bundled name or a path) with `Robot::load`.
/// @throws Error when the model cannot be found or loaded.
Robot load_model(const std::string& model);

/// The frame to use: @p site when given, else the model's only named site.
/// @throws UsageError listing the sites when none was given and the model has several (or none).
std::string resolve_site(const Robot& robot, const std::string& site);

/// A configuration of a chain and where it came from.
struct Configuration {
  Eigen::VectorXd q;     ///< chain joint values (chain order) [rad or m]
  Eigen::VectorXd qpos;  ///< full qpos (nq) holding q; joints off the chain as the source says
  std::string source;    ///< "--q", "keyframe 'home'" or "qpos0"
};

/// The configuration given by `--q` values (other joints at qpos0), by keyframe @p key, or qpos0
/// when both are empty.
/// @throws Error when q has the wrong length or the keyframe does not exist.
Configuration resolve_configuration(const Chain& chain, const std::vector<double>& q,
                                    const std::string& key);

}  // namespace mjarm::cli
