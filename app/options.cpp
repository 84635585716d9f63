#include "options.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "mjarm/error.hpp"
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

CLI::Option* add_model_argument(CLI::App& command, std::string& model) {
  return command.add_option("MODEL", model,
                            "bundled model name (see `mjarm models`) or path to an MJCF/URDF file");
}

CLI::Option* add_site_option(CLI::App& command, std::string& site) {
  return command.add_option(
      "--site", site, "end-effector site (or body) name; default: the model's only named site");
}

CLI::Option* add_json_flag(CLI::App& command, bool& json) {
  return command.add_flag("--json", json, "print one JSON document to stdout instead of tables");
}

Robot load_model(const std::string& model) { return Robot::load(model); }

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
