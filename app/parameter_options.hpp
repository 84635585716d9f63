// Declared parameters as command-line options: a scenario's on its `mjarm run` subcommand (every
// parameter the subcommand does not already spell its own way), an environment task's on
// `mjarm env run TASK`; each with its doc, unit, range and default in the help
// (docs/scenarios.md).
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "mjarm/error.hpp"
#include "mjarm/scenarios/declared_scenario.hpp"
#include "output.hpp"

namespace mjarm::cli {

class ParameterOptions {
 public:
  /// Adds `--NAME` for every one of @p parameters, in the help group @p group: a value for a
  /// number, name or text, one or more numbers for a vector (`--pick 0.4 0 0.3` or
  /// `0.4,0,0.3`), `--NAME` or `--NAME=false` for a flag, `none` for no value of an optional
  /// parameter. A parameter the command already has an option of that name for is left to it
  /// (`--robot`), and so is one in @p spelled: the parameters an older option of the command
  /// sets under another name (`motion.dwell-time`, set by `--dwell`; kept so that existing
  /// command lines work).
  ParameterOptions(CLI::App& app, const std::vector<FieldInfo>& parameters,
                   const std::string& group, const std::set<std::string>& spelled = {});
  /// The parameters of @p scenario, in a group named after it.
  ParameterOptions(CLI::App& app, const Scenario& scenario,
                   const std::set<std::string>& spelled = {});

  /// The parameters given on the command line, as the scenario or task reads them (empty object
  /// when none).
  /// @throws UsageError naming the option for a value of the wrong kind
  Json values() const;

 private:
  struct Given {
    FieldInfo info;
    std::vector<std::string> words;
    CLI::Option* option = nullptr;
  };
  std::vector<std::unique_ptr<Given>> given_;
};

/// Sets the registry parameters @p given (`ParameterOptions::values`) on a task's @p options:
/// through the scenario's typed parameters, each value checked as a sweep file's is.
/// @throws UsageError naming the parameter for a value the scenario refuses
template <class P, class Options, class ParametersOf>
void apply_parameters(const DeclaredScenario<P>& scenario, const Json& given, Options& options,
                      ParametersOf parameters_of) {
  if (given.empty()) return;
  P p = parameters_of(options);
  try {
    scenario.set(p, given);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  apply(p, options);
}

}  // namespace mjarm::cli
