// `mjarm singularities MODEL --site S`: how close named and sampled configurations are to
// losing a direction of motion.

#include <iostream>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "field_options.hpp"
#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/kinematics/singularity.hpp"
#include "output.hpp"

namespace mjarm::cli {

namespace {

/// The kinds of a singular entry ("wrist", "elbow, shoulder", "unclassified"), empty when the
/// entry crosses neither threshold.
std::vector<std::string> kind_names(const SingularityEntry& e) {
  std::vector<std::string> names;
  for (SingularityKind k : e.kinds) names.emplace_back(to_string(k));
  return names;
}

Json entry_json(const SingularityEntry& e, const Chain& chain) {
  return {{"name", e.name},
          {"q", vector_json(e.q)},
          {"within_limits", chain.within_limits(e.q)},
          {"singular_values", vector_json(e.singular_values)},
          {"sigma_min", e.sigma_min},
          {"condition_number", number_or_null(e.condition_number)},
          {"manipulability", e.manipulability},
          {"status", to_string(e.status)},
          {"below_sigma_min", e.below_sigma_min},
          {"above_condition_number", e.above_condition_number},
          {"kinds", kind_names(e)},
          {"null_direction", vector_json(e.null_direction)}};
}

/// Where entry @p i of a report came from: the report lists qpos0, the centre of the ranges,
/// the keyframes, then the caller's configurations.
std::string origin(std::size_t i, int keyframes) {
  if (i == 0) return "qpos0";
  if (i == 1) return "mid-range";
  if (i < 2 + static_cast<std::size_t>(keyframes)) return "keyframe";
  return "--q";
}

void add_rows(Table& table, const std::vector<SingularityEntry>& entries, int keyframes) {
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const SingularityEntry& e = entries[i];
    const double sigma_max = e.singular_values.size() > 0 ? e.singular_values[0] : 0.0;
    table.add_row({e.name, keyframes < 0 ? "sampled" : origin(i, keyframes), general(e.sigma_min),
                   general(sigma_max), general(e.condition_number), general(e.manipulability),
                   to_string(e.status), e.kinds.empty() ? "-" : join(kind_names(e)),
                   e.kinds.empty() ? "" : vector_text(e.null_direction, 3), vector_text(e.q, 3)});
  }
}

Table entry_table() {
  return Table({{"configuration", Table::Align::left},
                {"source", Table::Align::left},
                {"σmin"},
                {"σmax"},
                {"cond"},
                {"w"},
                {"class", Table::Align::left},
                {"kind", Table::Align::left},
                {"lost joint motion", Table::Align::left},
                {"q [rad or m]", Table::Align::left}});
}

/// Most samples `singularities` scans: about ten minutes at the panda's rate.
constexpr std::uint64_t kMaxSingularitySamples = 100'000'000;

}  // namespace

Command add_singularities_command(CLI::App& root) {
  struct Options {
    std::string model;
    std::string site;
    std::size_t samples = 10000;
    std::uint64_t seed = 1;
    std::size_t worst = 5;
    std::string block = "full";
    std::vector<double> q;
    bool allow_outside_range = false;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* app = root.add_subcommand(
      "singularities",
      "singular values, condition number and manipulability at named and sampled configurations");
  add_model_argument(*app, options->model)->required();
  add_site_option(*app, options->site);
  app->add_option("--samples", options->samples, "random configurations to scan (0: named only)")
      ->check(count_in(0, kMaxSingularitySamples))
      ->capture_default_str();
  app->add_option("--seed", options->seed, "seed of the random generator")
      ->check(non_negative_integer())
      ->capture_default_str();
  app->add_option("--worst", options->worst, "how many of the worst samples to list")
      ->check(count_in(0, 1000))
      ->capture_default_str();
  app->add_option("--block", options->block,
                  "Jacobian rows measured: full [v; ω], position or orientation")
      ->check(name_of<JacobianBlock>("block"))
      ->capture_default_str();
  app->add_option("--q", options->q, "also measure this configuration (chain order) [rad or m]")
      ->check(finite_number())
      ->expected(1, -1);
  add_allow_outside_range_flag(*app, options->allow_outside_range);
  add_json_flag(*app, options->json);

  return {app, [options] {
            const Robot robot = load_model(options->model);
            const Chain chain(robot, resolve_site(robot, options->site));
            ManipulabilityOptions measure;
            measure.block = parse_enum<JacobianBlock>(options->block, "block", "--block");
            std::vector<NamedConfiguration> extra;
            if (!options->q.empty()) {
              // a wrong count or a value outside its range is a usage error
              const Configuration config = resolve_configuration(
                  chain, options->q, "", "--q", options->allow_outside_range);
              extra.push_back({config.outside_range.empty() ? "--q"
                                                            : "--q (outside the joint ranges)",
                               config.q});
            }
            const SingularityReport report = singularity_report(chain, extra, measure);
            std::optional<SingularityScan> scan;
            if (options->samples > 0) {
              const InterruptGuard interrupts;  // Ctrl-C: report the samples scanned so far
              Progress progress("scanning", static_cast<std::int64_t>(options->samples));
              scan = scan_singularities(
                  chain, options->samples, options->seed, options->worst, measure, {},
                  [&progress](std::size_t done, std::size_t) {
                    progress.update(static_cast<std::int64_t>(done));
                  },
                  [] { return interrupt_requested(); });
              progress.finish();
            }
            const bool interrupted = scan && scan->status == SamplingStatus::interrupted;
            const std::string stopped =
                interrupted ? "interrupted after " + std::to_string(scan->samples) + " of " +
                                  std::to_string(options->samples) + " samples"
                            : "";

            if (options->json) {
              Json doc{{"model", robot.name()},
                       {"frame", chain.frame().name},
                       {"joints", chain.joint_names()},
                       {"block", to_string(measure.block)},
                       {"singular_tolerance", measure.singular_tolerance},
                       {"near_singular_threshold", measure.near_singular_threshold},
                       {"sigma_min_threshold", report.thresholds.sigma_min},
                       {"condition_number_threshold", report.thresholds.condition_number},
                       {"configurations", Json::array()}};
              for (const auto& e : report.entries) doc["configurations"].push_back(entry_json(e, chain));
              if (scan) {
                Json s{{"status", to_string(scan->status)},
                       {"samples", scan->samples},
                       {"seed", scan->seed},
                       {"singular", scan->singular_count},
                       {"near_singular", scan->near_singular_count},
                       {"flagged", scan->flagged_count},
                       {"worst", Json::array()}};
                for (const auto& e : scan->worst) s["worst"].push_back(entry_json(e, chain));
                doc["scan"] = std::move(s);
              } else {
                doc["scan"] = nullptr;
              }
              print_json(doc);
              if (interrupted) throw InterruptedError(stopped, interrupt_signal());
              return;
            }

            std::ostream& os = std::cout;
            print_fields(
                os, {{"model", robot.name()},
                     {"frame", chain.frame().name},
                     {"joints", std::to_string(chain.size()) + ": " + join(chain.joint_names())},
                     {"measured", std::string(to_string(measure.block)) +
                                      " block of the world-aligned Jacobian"},
                     {"classes",
                      "singular when σmin/σmax ≤ " + general(measure.singular_tolerance, 2) +
                          ", near_singular below " + general(measure.near_singular_threshold, 2)},
                     {"kinds", "named where σmin < " + general(report.thresholds.sigma_min, 2) +
                                   " or cond > " + general(report.thresholds.condition_number, 3) +
                                   ": wrist, elbow, shoulder, or unclassified"}});
            os << "\nnamed configurations\n";
            Table named = entry_table();
            add_rows(named, report.entries, robot.model().nkey);
            named.print(os);
            if (scan) {
              os << "\nrandom scan: " << scan->samples << " samples (seed " << scan->seed
                 << (interrupted ? "; interrupted" : "") << "): " << scan->singular_count
                 << " singular, " << scan->near_singular_count << " near-singular, "
                 << scan->flagged_count << " with σmin < "
                 << general(scan->thresholds.sigma_min, 2) << " or cond > "
                 << general(scan->thresholds.condition_number, 3) << "\n";
              if (!scan->worst.empty()) {
                os << "lowest σmin among the samples\n";
                Table worst = entry_table();
                add_rows(worst, scan->worst, -1);
                worst.print(os);
              }
            }
            if (interrupted) throw InterruptedError(stopped, interrupt_signal());
          }};
}

}  // namespace mjarm::cli
