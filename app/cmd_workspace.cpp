// `mjarm workspace MODEL --site S --samples N --seed K`: seeded Monte-Carlo reachable workspace.

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "output.hpp"

namespace mjarm::cli {

namespace {

double rate(const WorkspaceResult& result) {
  return result.seconds > 0.0 ? static_cast<double>(result.samples) / result.seconds : 0.0;
}

}  // namespace

WorkspaceResult run_workspace(const Chain& chain, std::size_t samples, std::uint64_t seed,
                              bool keep_points) {
  WorkspaceOptions options;
  options.samples = samples;
  options.seed = seed;
  options.keep_points = keep_points;
  Progress progress("sampling", static_cast<std::int64_t>(samples));
  options.progress = [&progress](std::size_t done, std::size_t) {
    progress.update(static_cast<std::int64_t>(done));
  };
  WorkspaceResult result = sample_workspace(chain, options);
  progress.finish();
  return result;
}

Json workspace_json(const Chain& chain, const WorkspaceResult& result) {
  return {{"model", chain.robot().name()},
          {"frame", chain.frame().name},
          {"joints", chain.joint_names()},
          {"samples", result.samples},
          {"seed", result.seed},
          {"lower", vector_json(result.lower)},
          {"upper", vector_json(result.upper)},
          {"extent", vector_json(result.upper - result.lower)},
          {"centroid", vector_json(result.centroid)},
          {"base", vector_json(result.p_WB)},
          {"max_reach_from_base", result.max_reach_from_base},
          {"max_reach_from_origin", result.max_reach_from_origin},
          {"manipulability",
           {{"block", "position"},
            {"min", result.min_manipulability},
            {"mean", result.mean_manipulability},
            {"max", result.max_manipulability}}},
          {"seconds", result.seconds},
          {"samples_per_second", rate(result)}};
}

void print_workspace(std::ostream& os, const Chain& chain, const WorkspaceResult& result) {
  print_fields(
      os, {{"model", chain.robot().name()},
           {"frame", chain.frame().name},
           {"joints", std::to_string(chain.size()) + ": " + join(chain.joint_names())},
           {"samples", std::to_string(result.samples) + " (seed " + std::to_string(result.seed) +
                           ", uniform within the joint limits)"}});
  os << "\nreachable positions of the frame, world axes\n";
  Table box({{"", Table::Align::left}, {"min [m]"}, {"max [m]"}, {"extent [m]"}, {"centroid [m]"}});
  const char* axes[] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    box.add_row({axes[i], fixed(result.lower[i]), fixed(result.upper[i]),
                 fixed(result.upper[i] - result.lower[i]), fixed(result.centroid[i])});
  }
  box.print(os);
  os << '\n';
  print_fields(
      os,
      {{"base (first joint anchor) [m]", vector_text(result.p_WB)},
       {"max reach from base [m]", fixed(result.max_reach_from_base)},
       {"max reach from world origin [m]", fixed(result.max_reach_from_origin)},
       {"position manipulability w [m^3]", "min " + general(result.min_manipulability) + ", mean " +
                                               general(result.mean_manipulability) + ", max " +
                                               general(result.max_manipulability)},
       {"time [s]", fixed(result.seconds, 3) + "  (" + general(rate(result), 3) + " samples/s)"}});
}

Command add_workspace_command(CLI::App& root) {
  struct Options {
    std::string model;
    std::string site;
    std::size_t samples = 20000;
    std::uint64_t seed = 1;
    std::string out;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* app = root.add_subcommand(
      "workspace", "reachable workspace of a site: seeded uniform joint samples within the limits");
  add_model_argument(*app, options->model)->required();
  add_site_option(*app, options->site);
  app->add_option("--samples", options->samples, "number of joint samples")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1000000000}))
      ->capture_default_str();
  app->add_option("--seed", options->seed, "seed of the random generator (same seed, same samples)")
      ->check(non_negative_integer())
      ->capture_default_str();
  app->add_option("--out", options->out,
                  "write every sample to this CSV file (x,y,z,manipulability)");
  add_json_flag(*app, options->json);

  return {app, [options] {
            const Robot robot = load_model(options->model);
            const Chain chain(robot, resolve_site(robot, options->site));
            const WorkspaceResult result =
                run_workspace(chain, options->samples, options->seed, !options->out.empty());
            if (!options->out.empty()) result.write_csv(options->out);
            if (options->json) {
              Json doc = workspace_json(chain, result);
              doc["csv"] = options->out.empty() ? Json(nullptr) : Json(options->out);
              return print_json(doc);
            }
            print_workspace(std::cout, chain, result);
            if (!options->out.empty()) {
              std::cout << "\nwrote " << result.points.size() << " samples to " << options->out
                        << '\n';
            }
          }};
}

}  // namespace mjarm::cli
