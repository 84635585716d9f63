#include "options.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>
#include <numbers>

#include "mjarm/error.hpp"
#include "mjarm/model/model_size.hpp"
#include "mjarm/model/user_file.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/scene/scene_file.hpp"
#include "mjarm/web/recorded_model.hpp"
#include "output.hpp"

namespace mjarm::cli {

CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const char* begin = text.c_str();
        char* end = nullptr;
        const double value = std::strtod(begin, &end);
        if (end == begin || *end != '\0') return "'" + text + "' is not a number";
        // strtod flags an underflow (a subnormal such as 1e-320) with ERANGE too: those are
        // finite numbers; only an overflow (±HUGE_VAL) or nan/inf is refused
        if (!std::isfinite(value)) return "'" + text + "' is not a finite number";
        return {};
      },
      "NUMBER", "finite_number");
}

namespace {

/// The whole number @p text spells with digits, or an error message. Leading zeros are refused:
/// CLI11 would read "010" as octal eight.
std::string parse_whole(const std::string& text, std::uint64_t& value) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
    return "'" + text + "' is not a whole number written with digits";
  if (text.size() > 1 && text[0] == '0')
    return "'" + text + "' starts with 0; write the number without leading zeros";
  errno = 0;
  value = std::strtoull(text.c_str(), nullptr, 10);
  if (errno == ERANGE)
    return "'" + text + "' is too large (at most " +
           std::to_string(std::numeric_limits<std::uint64_t>::max()) + ")";
  return {};
}

}  // namespace
CLI::Validator duration_at_most(double max, const std::string& unit, bool zero_allowed) {
  const std::string range = "a time in " + unit + (zero_allowed ? ", from 0" : ", more than 0") +
                            " and at most " + compact(max);
  return CLI::Validator(
      [max, zero_allowed, range](std::string& text) -> std::string {
        const char* begin = text.c_str();
        char* end = nullptr;
        const double value = std::strtod(begin, &end);
        if (end == begin || *end != '\0')
          return "'" + text + "' is not a number; expected " + range;
        // an underflow to 0 counts as 0; a denormal is > 0
        const bool above_min = zero_allowed ? value >= 0.0 : value > 0.0;
        if (!std::isfinite(value) || !above_min || value > max)
          return "'" + text + "' is out of range; expected " + range;
        return {};
      },
      unit == "s" ? "SECONDS" : "MS", "duration_at_most");
}

CLI::Validator timeout_ms() { return duration_at_most(kMaxTimeoutMs, "ms"); }

CLI::Validator non_negative_integer() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::uint64_t value = 0;
        return parse_whole(text, value);
      },
      "INTEGER", "non_negative_integer");
}

CLI::Validator count_in(std::uint64_t min, std::uint64_t max) {
  const std::string range = "from " + std::to_string(min) + " to " + std::to_string(max);
  return CLI::Validator(
      [min, max, range](std::string& text) -> std::string {
        std::uint64_t value = 0;
        if (!parse_whole(text, value).empty() || value < min || value > max)
          return "'" + text + "' is not a whole number " + range;
        return {};
      },
      "INTEGER", "count_in");
}

std::string readable(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

CLI::Validator number_in(double min, double max) {
  const std::string range = "from " + readable(min) + " to " + readable(max);
  return CLI::Validator(
      [min, max, range](std::string& text) -> std::string {
        const char* begin = text.c_str();
        char* end = nullptr;
        const double value = std::strtod(begin, &end);
        if (end == begin || *end != '\0' || !std::isfinite(value) || value < min || value > max)
          return "'" + text + "' is not a number " + range;
        return {};
      },
      "NUMBER", "number_in");
}

CLI::Validator pixel_size(PixelSize min, bool even, PixelSize max) {
  return CLI::Validator(
      [min, even, max](std::string& text) -> std::string {
        const auto x = text.find_first_of("xX");
        auto whole = [](const std::string& s) {
          return !s.empty() && s.size() <= 5 &&
                 s.find_first_not_of("0123456789") == std::string::npos;
        };
        if (x == std::string::npos || !whole(text.substr(0, x)) || !whole(text.substr(x + 1)))
          return "'" + text + "' is not a size WIDTHxHEIGHT in pixels (e.g. 640x480)";
        const PixelSize size = parse_pixel_size(text);
        if (size.width < min.width || size.height < min.height || size.width > max.width ||
            size.height > max.height) {
          return "size '" + text + "' must be between " + std::to_string(min.width) + "x" +
                 std::to_string(min.height) + " and " + std::to_string(max.width) + "x" +
                 std::to_string(max.height) + " pixels";
        }
        if (even && (size.width % 2 != 0 || size.height % 2 != 0))
          return "size '" + text + "' must be even in both directions (the MP4's yuv420p), e.g. " +
                 std::to_string(size.width + size.width % 2) + "x" +
                 std::to_string(size.height + size.height % 2);
        return {};
      },
      "WxH", "pixel_size");
}

PixelSize parse_pixel_size(const std::string& text) {
  const auto x = text.find_first_of("xX");
  return {std::stoi(text.substr(0, x)), std::stoi(text.substr(x + 1))};
}

void add_model_size_option(CLI::App& root) {
  // the commands that never load a model
  static const std::vector<std::string> kModelFree{
      "models",       "plot",        "traj",         "bench otg",    "bench topp",  "bench traj",
      "sweep status", "sweep merge", "sweep export", "sweep report", "sweep cancel"};
  const auto add = [](auto& self, CLI::App& app, const std::string& path) -> void {
    const auto children = app.get_subcommands({});
    // subcommands that fall through to their command (`env run TASK`) leave it to the command
    const bool through =
        !children.empty() && std::all_of(children.begin(), children.end(),
                                         [](const CLI::App* c) { return c->get_fallthrough(); });
    if (!children.empty() && !through) {
      for (CLI::App* child : children)
        self(self, *child, (path.empty() ? "" : path + " ") + child->get_name());
      return;
    }
    if (std::find(kModelFree.begin(), kModelFree.end(), path) != kModelFree.end()) return;
    app.add_option_function<std::uint64_t>(
           "--max-model-elements", [](std::uint64_t n) { set_max_model_elements(n); },
           "load models of up to N elements (XML elements, <replicate> copies counted; default " +
               std::to_string(kDefaultMaxModelElements) +
               "): MuJoCo's compile time grows with the square of the count")
        ->check(count_in(1, kLargestMaxModelElements));
  };
  add(add, root, "");
}

CLI::Option* add_model_argument(CLI::App& command, std::string& model) {
  return command.add_option(
      "MODEL", model,
      "bundled model name (see `mjarm models`), path to an MJCF/URDF file, or a "
      "scene file (.yaml/.yml/.json, docs/scene.md)");
}

CLI::Option* add_site_option(CLI::App& command, std::string& site) {
  return command.add_option(
      "--site", site, "end-effector site (or body) name; default: the model's only named site");
}

CLI::Option* add_json_flag(CLI::App& command, bool& json) {
  return command.add_flag("--json", json, "print one JSON document to stdout instead of tables");
}

Robot load_model(const std::string& model, const LoadOptions& options) {
  // a recording's model (model.mjb, docs/replay.md)
  if (has_extension(model, ".mjb")) return load_mjb_model(model);
  if (!is_scene_file(model)) return Robot::load(model, options);
  const Scene scene = load_scene_file(model);
  for (const auto& warning : scene.warnings()) std::cerr << "mjarm: " << warning << "\n";
  return scene.compile();
}

std::string resolve_site(const Robot& robot, const std::string& site) {
  if (!site.empty()) return site;
  std::vector<std::string> named;
  for (const auto& name : robot.site_names()) {
    if (!name.empty()) named.push_back(name);
  }
  if (named.size() == 1) return named.front();
  if (named.empty()) {
    throw UsageError("model '" + robot.name() +
                     "' has no named site; pass --site with a body name");
  }
  throw UsageError("model '" + robot.name() + "' has " + std::to_string(named.size()) +
                   " sites, choose one with --site: " + join(named));
}

CLI::Option* add_allow_outside_range_flag(CLI::App& command, bool& allow) {
  return command.add_flag(kAllowOutsideRangeFlag, allow,
                          "accept joint values outside the joint ranges (each is warned about "
                          "and flagged in the output); without it they are refused");
}

std::vector<std::string> check_joint_ranges(const Robot& robot, const std::vector<int>& joints,
                                            const Eigen::Ref<const Eigen::VectorXd>& qpos,
                                            const std::string& option, bool allowed,
                                            const std::string& refusal) {
  constexpr double kPi = std::numbers::pi;
  std::vector<std::string> outside;
  for (const int id : joints) {
    const JointInfo joint = robot.joint_info(id);
    const bool hinge = joint.type == JointType::hinge;
    if (!joint.limited || !(hinge || joint.type == JointType::slide)) continue;
    const double value = qpos[joint.qpos_address];
    if (value >= joint.lower && value <= joint.upper) continue;
    const std::string unit = hinge ? " rad" : " m";
    std::string line = "joint '" + joint.name + "' = " + number_text(value) + unit +
                       ", outside its range [" + number_text(joint.lower) + ", " +
                       number_text(joint.upper) + "]" + unit;
    // a value in degrees is the usual slip: radians past a full turn rarely are meant
    if (hinge && std::abs(value) > 2.0 * kPi && std::abs(value) * kPi / 180.0 <= 2.0 * kPi)
      line += " (" + option + " takes radians: " + number_text(value) + "° would be " +
              fixed(value * kPi / 180.0, 4) + " rad)";
    outside.push_back(std::move(line));
  }
  if (outside.empty()) return outside;
  if (!allowed)
    throw UsageError(option + ": " + join(outside, "; ") + "; " + refusal);
  for (const std::string& line : outside)
    std::cerr << "mjarm: warning: " << option << ": " << line << '\n';
  return outside;
}

Configuration resolve_configuration(const Chain& chain, const std::vector<double>& q,
                                    const std::string& key, const std::string& option,
                                    bool allow_outside_range, const std::string& refusal) {
  const mjModel& m = chain.robot().model();
  Configuration config;
  if (!key.empty()) {
    std::vector<double> qpos;
    try {
      qpos = chain.robot().keyframe_qpos(key);
    } catch (const Error& e) {
      throw UsageError(std::string("--key: ") + e.what());
    }
    config.qpos =
        Eigen::Map<const Eigen::VectorXd>(qpos.data(), static_cast<Eigen::Index>(qpos.size()));
    config.q = chain.gather(config.qpos.data());
    config.source = "keyframe '" + key + "'";
    return config;
  }
  config.qpos = Eigen::Map<const Eigen::VectorXd>(m.qpos0, m.nq);
  if (q.empty()) {
    config.q = chain.gather(config.qpos.data());
    config.source = "qpos0";
    return config;
  }
  const Eigen::VectorXd values =
      Eigen::Map<const Eigen::VectorXd>(q.data(), static_cast<Eigen::Index>(q.size()));
  try {
    chain.check(values, option);
  } catch (const Error& e) {
    throw UsageError(e.what());  // a wrong count is a mistake on the command line
  }
  chain.scatter(values, config.qpos.data());
  config.q = values;
  config.source = option;
  config.outside_range =
      check_joint_ranges(chain.robot(), chain.joint_ids(), config.qpos, option,
                         allow_outside_range,
                         !refusal.empty() ? refusal
                                          : std::string("pass ") + kAllowOutsideRangeFlag +
                                                " to use it anyway");
  return config;
}

namespace {

namespace fs = std::filesystem;

/// The nearest ancestor of @p path that exists ("." for a relative path with none).
fs::path existing_ancestor(const fs::path& path) {
  std::error_code ec;
  fs::path p = path;
  while (!p.empty() && !fs::exists(p, ec)) p = p.parent_path();
  return p.empty() ? fs::path(".") : p;
}

/// Whether a file can be created in folder @p folder: tries it (root ignores permission bits, and
/// /proc or a read-only mount only shows itself on creation), then removes the probe.
std::string probe_folder(const fs::path& folder) {
  std::string probe = (folder / ".mjarm-probe-XXXXXX").string();
  const int fd = mkstemp(probe.data());
  if (fd < 0) return std::strerror(errno);
  close(fd);
  unlink(probe.c_str());
  return {};
}

std::string shown(const fs::path& path) { return "'" + path.string() + "'"; }

}  // namespace

void check_output_file(const std::string& path, const std::string& option, bool make_parents) {
  if (path.empty()) throw UsageError(option + ": the path is empty");
  const fs::path file(path);
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (ec.value() == ELOOP)
    throw UsageError(option + ": " + shown(file) +
                     " is a symbolic link loop (ELOOP: too many levels of symbolic links)");
  if (fs::is_directory(status))
    throw UsageError(option + ": " + shown(file) + " is a folder, expected a file name");
  if (fs::exists(status)) {
    // an existing file (or device, e.g. /dev/null): it must open for writing, without waiting
    // on a FIFO nobody reads and without truncating it yet
    const int fd = open(file.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
      const int error = errno;
      throw UsageError(
          option + ": cannot write " + shown(file) + ": " + std::strerror(error) +
          (fs::is_fifo(status) && error == ENXIO ? " (a FIFO that nothing reads)" : ""));
    }
    close(fd);
    return;
  }
  const fs::path parent = file.has_parent_path() ? file.parent_path() : fs::path(".");
  if (!fs::exists(parent, ec)) {
    if (!make_parents)
      throw UsageError(option + ": the folder " + shown(parent) + " of " + shown(file) +
                       " does not exist");
    return check_output_folder(parent.string(), option);
  }
  if (!fs::is_directory(parent, ec))
    throw UsageError(option + ": " + shown(parent) + " is not a folder, so " + shown(file) +
                     " cannot be created");
  // create the file itself (exclusively) and remove it: the one test that cannot be wrong. Another
  // run writing the same file may create it meanwhile (its own check, or its output): then the
  // file exists, and what counts is that it opens for writing.
  for (int attempt = 0;; ++attempt) {
    int fd = open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd >= 0) {
      close(fd);
      unlink(file.c_str());
      return;
    }
    int error = errno;
    if (error == EEXIST && attempt < 8) {
      fd = open(file.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
      if (fd >= 0) {
        close(fd);
        return;
      }
      error = errno;
      if (error == ENOENT) continue;  // gone again: try to create it once more
      throw UsageError(option + ": cannot write " + shown(file) + ": " + std::strerror(error));
    }
    throw UsageError(option + ": cannot create " + shown(file) + ": " + std::strerror(error));
  }
}

void check_output_folder(const std::string& path, const std::string& option) {
  if (path.empty()) throw UsageError(option + ": the path is empty");
  const fs::path folder(path);
  std::error_code loop;
  (void)fs::status(folder, loop);
  if (loop.value() == ELOOP)
    throw UsageError(option + ": " + shown(folder) +
                     " is a symbolic link loop (ELOOP: too many levels of symbolic links)");
  const fs::path ancestor = existing_ancestor(folder);
  std::error_code ec;
  if (!fs::is_directory(ancestor, ec)) {
    throw UsageError(option + ": " + shown(ancestor) + " is not a folder" +
                     (ancestor == folder ? "" : ", so " + shown(folder) + " cannot be made"));
  }
  const std::string why = probe_folder(ancestor);
  if (!why.empty()) {
    throw UsageError(option + ": cannot write into " + shown(ancestor) +
                     (ancestor == folder ? "" : " (to make " + shown(folder) + ")") + ": " + why);
  }
}

}  // namespace mjarm::cli

namespace mjarm::cli {

CLI::Option* add_video_options(CLI::App& app, VideoCli& o, const std::string& what,
                               const std::string& camera_help) {
  CLI::Option* video = app.add_option(
      "--video", o.path, "write an MP4 of " + what + " (rendered headless; needs Debian's ffmpeg)");
  if (!camera_help.empty()) app.add_option("--camera", o.camera, camera_help)->needs(video);
  app.add_option("--size", o.size, "video size WIDTHxHEIGHT [pixels], even")
      ->check(pixel_size({2, 2}, true, {4096, 4096}))
      ->needs(video)
      ->capture_default_str();
  app.add_option("--fps", o.fps, "video frames per simulated second")
      ->check(number_in(1.0, 240.0))
      ->needs(video)
      ->capture_default_str();
  return video;
}

}  // namespace mjarm::cli
