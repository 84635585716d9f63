#include "options.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iostream>

#include "mjarm/error.hpp"
#include "mjarm/scene/scene_file.hpp"
#include "output.hpp"

namespace mjarm::cli {

CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const char* begin = text.c_str();
        char* end = nullptr;
        errno = 0;
        const double value = std::strtod(begin, &end);
        if (end == begin || *end != '\0') return "'" + text + "' is not a number";
        if (!std::isfinite(value) || errno == ERANGE)
          return "'" + text + "' is not a finite number";
        return {};
      },
      "NUMBER", "finite_number");
}

CLI::Validator non_negative_integer() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const bool digits =
            !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
        return digits ? std::string() : "'" + text + "' is not a whole number ≥ 0";
      },
      "INTEGER", "non_negative_integer");
}

CLI::Validator pixel_size(PixelSize min, bool even) {
  constexpr int kMax = 16384;
  return CLI::Validator(
      [min, even](std::string& text) -> std::string {
        const auto x = text.find_first_of("xX");
        auto whole = [](const std::string& s) {
          return !s.empty() && s.size() <= 5 &&
                 s.find_first_not_of("0123456789") == std::string::npos;
        };
        if (x == std::string::npos || !whole(text.substr(0, x)) || !whole(text.substr(x + 1)))
          return "'" + text + "' is not a size WIDTHxHEIGHT in pixels (e.g. 640x480)";
        const PixelSize size = parse_pixel_size(text);
        if (size.width < min.width || size.height < min.height || size.width > kMax ||
            size.height > kMax) {
          return "size '" + text + "' must be between " + std::to_string(min.width) + "x" +
                 std::to_string(min.height) + " and 16384x16384 pixels";
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

Robot load_model(const std::string& model) {
  if (!is_scene_file(model)) return Robot::load(model);
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

Configuration resolve_configuration(const Chain& chain, const std::vector<double>& q,
                                    const std::string& key) {
  const mjModel& m = chain.robot().model();
  Configuration config;
  if (!key.empty()) {
    const std::vector<double> qpos = chain.robot().keyframe_qpos(key);
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
  chain.check(values, "--q");
  chain.scatter(values, config.qpos.data());
  config.q = values;
  config.source = "--q";
  return config;
}

}  // namespace mjarm::cli
