// `mjarm workspace MODEL --site S --samples N --seed K`: seeded Monte-Carlo reachable workspace.

#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "output.hpp"

namespace mjarm::cli {

namespace {

double rate(const WorkspaceResult& result) {
  return result.seconds > 0.0 ? static_cast<double>(result.samples) / result.seconds : 0.0;
}

}  // namespace

void check_workspace_csv(const std::string& out, std::size_t samples) {
  if (samples > kMaxKeptWorkspacePoints) {
    throw UsageError("--samples " + std::to_string(samples) + " with --out would keep " +
                     std::to_string(samples / (std::size_t{1} << 20) * sizeof(WorkspacePoint)) +
                     " MiB of points in memory; with --out at most " +
                     std::to_string(kMaxKeptWorkspacePoints) + " samples are allowed");
  }
  check_output_file(out, "--out");
  // a CSV line holds four numbers of up to 17 significant digits: about 90 bytes
  constexpr std::uintmax_t kCsvLineBytes = 90;
  const std::filesystem::path file(out);
  std::error_code ec;
  const std::filesystem::space_info space = std::filesystem::space(
      file.has_parent_path() ? file.parent_path() : std::filesystem::path("."), ec);
  const std::uintmax_t needed = kCsvLineBytes * samples;
  if (!ec && space.available < needed) {
    // one decimal: "about 1.7 MiB …; 1.1 MiB are free", never "1 MiB …; 1 MiB are free"
    const auto mib = [](std::uintmax_t bytes) {
      return fixed(static_cast<double>(bytes) / static_cast<double>(1 << 20), 1);
    };
    throw UsageError("--out: " + out + " would need about " + mib(needed) + " MiB for " +
                     std::to_string(samples) + " samples; " + mib(space.available) +
                     " MiB are free there");
  }
}

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
  options.stop = [] { return interrupt_requested(); };  // the caller holds the InterruptGuard
  WorkspaceResult result = sample_workspace(chain, options);
  progress.finish();
  return result;
}

Json workspace_json(const Chain& chain, const WorkspaceResult& result) {
  return {{"model", chain.robot().name()},
          {"frame", chain.frame().name},
          {"joints", chain.joint_names()},
          {"status", to_string(result.status)},
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
                           ", uniform within the joint limits" +
                           (result.status == SamplingStatus::complete ? ")" : "; interrupted)")}});
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
  app->add_option("--samples", options->samples,
                  "number of joint samples (with --out at most " +
                      std::to_string(kMaxKeptWorkspacePoints) + ", kept in memory)")
      ->check(count_in(1, kMaxWorkspaceSamples))
      ->capture_default_str();
  app->add_option("--seed", options->seed, "seed of the random generator (same seed, same samples)")
      ->check(non_negative_integer())
      ->capture_default_str();
  app->add_option("--out", options->out,
                  "write every sample to this CSV file (x,y,z,manipulability)");
  add_json_flag(*app, options->json);

  return {app, [options] {
            // every argument and the output are checked before the work
            if (!options->out.empty()) check_workspace_csv(options->out, options->samples);
            const Robot robot = load_model(options->model);
            const Chain chain(robot, resolve_site(robot, options->site));
            const InterruptGuard interrupts;  // Ctrl-C: report the samples drawn so far
            const WorkspaceResult result =
                run_workspace(chain, options->samples, options->seed, !options->out.empty());
            const bool complete = result.status == SamplingStatus::complete;
            if (!options->out.empty() && complete) result.write_csv(options->out);
            if (options->json) {
              Json doc = workspace_json(chain, result);
              doc["csv"] = options->out.empty() || !complete ? Json(nullptr) : Json(options->out);
              print_json(doc);
            } else {
              print_workspace(std::cout, chain, result);
              if (!options->out.empty() && complete) {
                std::cout << "\nwrote " << result.points.size() << " samples to " << options->out
                          << '\n';
              }
            }
            // a signal after the last sample (while the CSV was written, or the report printed)
            if (complete && interrupt_requested())
              throw InterruptedError(
                  "workspace: interrupted after the sampling" +
                      (options->out.empty() ? "" : "; '" + options->out + "' was written"),
                  interrupt_signal());
            if (!complete) {
              throw InterruptedError(
                  "interrupted after " + std::to_string(result.samples) + " of " +
                      std::to_string(options->samples) + " samples" +
                      (options->out.empty() ? "" : "; " + options->out + " was not written"),
                  interrupt_signal());
            }
          }};
}

}  // namespace mjarm::cli
