// `mjarm sweep run|resume|status|merge|export|report|shard`: parameter sweeps over any scenario of
// the registry, on this machine (a pool of threads), results in SQLite (docs/sweep.md).

#include <algorithm>
#include <iostream>
#include <map>
#include <memory>
#include <thread>

#include "commands.hpp"
#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/model/user_file.hpp"
#include "mjarm/sweep/local_backend.hpp"
#include "mjarm/sweep/slurm_backend.hpp"
#include "mjarm/sweep/sweep_dashboard.hpp"
#include "mjarm/sweep/sweep_plots.hpp"
#include "mjarm/sweep/sweep_report.hpp"
#include "mjarm/version.hpp"
#include "output.hpp"

namespace mjarm::cli {

namespace {

/// A shard on a cluster should take minutes; locally, at least four shards per worker.
constexpr double kShardSeconds = 60.0;

std::string percent(double x) { return fixed(100.0 * x, 1) + " %"; }

std::string rate_text(const SuccessRate& r) {
  return std::to_string(r.successes) + "/" + std::to_string(r.trials) + " (" + percent(r.rate) +
         "; 95 % interval " + fixed(100.0 * r.low, 1) + "–" + percent(r.high) + ")";
}

Json success_json(const SuccessRate& r) {
  return {{"successes", r.successes},
          {"trials", r.trials},
          {"rate", r.rate},
          {"low", r.low},
          {"high", r.high}};
}

Json merge_json(const SweepMerge& m, const SweepFolder& folder) {
  return {{"database", folder.results().string()},
          {"shards", m.shards},
          {"trials", m.trials},
          {"missing_shards", m.missing},
          {"seconds", m.seconds}};
}

Json plan_summary_json(const SweepPlan& plan) {
  return {{"scenario", plan.file.scenario}, {"hash", plan.hash},
          {"points", plan.points},          {"seeds", plan.file.seeds},
          {"trials", plan.trials},          {"shards", plan.shards()},
          {"shard_size", plan.shard_size},  {"varied", varied_parameters(plan)}};
}

std::string plan_line(const SweepPlan& plan) {
  return "sweep " + plan.file.scenario + ": " + std::to_string(plan.trials) + " trials (" +
         std::to_string(plan.points) + " points × " + std::to_string(plan.file.seeds) +
         " seeds), " + std::to_string(plan.shards()) + " shards of " +
         std::to_string(plan.shard_size) + " (plan " + plan.hash + ")";
}

/// Runs the missing shards here, merges, prints; Ctrl-C keeps the finished shards.
void run_here(const SweepFolder& folder, const SweepPlan& plan, int jobs, bool json, Json doc) {
  const InterruptGuard interrupts;
  LocalSweepOptions options;
  options.jobs = jobs;
  Progress progress("trials", plan.trials, !json && stderr_is_terminal());
  options.progress = [&progress](std::int64_t done, std::int64_t total) {
    progress.update(done, total);
  };
  const LocalSweepResult r = run_sweep_local(folder, plan, options);
  progress.finish();
  const SweepMerge merge = merge_sweep(folder);
  const SuccessRate success = sweep_report(folder).success;
  if (json) {
    doc["run"] = {{"jobs", r.jobs},
                  {"shards_run", r.shards_run},
                  {"shards_left", r.shards_left},
                  {"trials_run", r.trials_run},
                  {"interrupted", r.interrupted},
                  {"seconds", r.seconds}};
    doc["merge"] = merge_json(merge, folder);
    doc["success"] = success_json(success);
    print_json(doc);
  } else {
    std::cout << "ran " << r.shards_run << " shards (" << r.trials_run << " trials) on " << r.jobs
              << " worker" << (r.jobs > 1 ? "s" : "") << " in " << fixed(r.seconds, 1) << " s\n"
              << "merged " << merge.trials << " trials into " << folder.results().string() << "\n"
              << "success " << rate_text(success) << "\n";
  }
  if (r.interrupted)
    throw InterruptedError("interrupted with " + std::to_string(r.shards_left) +
                               " shards left (finished shards are kept): mjarm sweep resume " +
                               folder.dir.string() + " runs them",
                           interrupt_signal());
  if (merge.missing > 0)
    throw Error(std::to_string(merge.missing) + " shards are missing: mjarm sweep resume " +
                folder.dir.string());
}

/// What `--backend slurm` reads from the command line.
struct SlurmCli {
  std::string partition, account, qos, time = "01:00:00";
  int cpus_per_task = 1, throttle = 0;
  std::vector<std::string> sbatch_args;
  bool dry_run = false, wait = false;
};

void add_slurm_options(CLI::App& app, SlurmCli& o) {
  const std::string group = "Slurm (--backend slurm)";
  app.add_option("--partition", o.partition, "the partition (default: the cluster's)")
      ->group(group);
  app.add_option("--account", o.account, "the account to charge")->group(group);
  app.add_option("--qos", o.qos, "the quality of service")->group(group);
  app.add_option("--time", o.time, "each task's time limit (sbatch --time)")
      ->capture_default_str()
      ->group(group);
  app.add_option("--cpus-per-task", o.cpus_per_task, "CPUs of each task")
      ->check(count_in(1, 1024))
      ->capture_default_str()
      ->group(group);
  app.add_option("--throttle", o.throttle, "at most this many tasks at once (0: no limit)")
      ->check(count_in(0, 1000000))
      ->group(group);
  app.add_option("--sbatch-arg", o.sbatch_args, "passed to sbatch as it is (repeat for more)")
      ->allow_extra_args(false)
      ->group(group);
  app.add_flag("--dry-run", o.dry_run, "write the sbatch scripts into DIR/slurm, submit nothing")
      ->group(group);
  app.add_flag("--wait", o.wait, "wait for the jobs (with progress), then report")->group(group);
}

/// Submits the missing shards to Slurm; with --wait, waits for them and reports like a local run.
void submit_to_slurm(const SweepFolder& folder, const SweepPlan& plan, const SlurmCli& cli,
                     bool json, Json doc) {
  SlurmOptions options;
  options.executable = std::filesystem::read_symlink("/proc/self/exe");
  options.partition = cli.partition;
  options.account = cli.account;
  options.qos = cli.qos;
  options.time_limit = cli.time;
  options.cpus_per_task = cli.cpus_per_task;
  options.throttle = cli.throttle;
  options.sbatch_args = cli.sbatch_args;
  options.dry_run = cli.dry_run;
  const SlurmSubmission s = submit_sweep_slurm(folder, plan, options);
  Json scripts = Json::array();
  for (const auto& path : s.scripts) scripts.push_back(path.string());
  doc["slurm"] = {{"scripts", scripts},
                  {"jobs", s.jobs},
                  {"merge_job", s.merge_job},
                  {"shards", s.shards},
                  {"max_array_size", s.max_array_size}};
  if (!json) {
    if (cli.dry_run) {
      std::cout << "wrote " << s.scripts.size() << " sbatch scripts for " << s.shards
                << " shards (nothing submitted):\n";
      for (const auto& path : s.scripts) std::cout << "  " << path.string() << "\n";
    } else {
      std::cout << "submitted " << s.shards << " shards as job " << join(s.jobs) << ", merge job "
                << s.merge_job << "\n";
    }
  }
  if (cli.dry_run || !cli.wait) {
    if (json) print_json(doc);
    return;
  }
  const InterruptGuard interrupts;
  Progress progress("shards", plan.shards(), !json && stderr_is_terminal());
  const bool ended =
      wait_for_slurm_jobs(folder, plan, [&progress](std::int64_t done) { progress.update(done); });
  progress.finish();
  if (!ended)
    throw InterruptedError("stopped waiting; the jobs go on (mjarm sweep status " +
                               folder.dir.string() + ", mjarm sweep cancel to stop them)",
                           interrupt_signal());
  const ShardStates states = shard_states(folder, plan);
  const std::vector<std::int64_t> failed = states.to_run();
  if (!failed.empty()) {
    std::string why = std::to_string(failed.size()) + " of " + std::to_string(plan.shards()) +
                      " shards did not finish: " + slurm_shard_failure(folder, failed.front());
    if (failed.size() > 1) why += "; …";
    throw Error(why + "; mjarm sweep resume " + folder.dir.string() + " runs them again");
  }
  const SweepMerge merge = merge_sweep(folder);
  const SuccessRate success = sweep_report(folder).success;
  if (json) {
    doc["merge"] = merge_json(merge, folder);
    doc["success"] = success_json(success);
    print_json(doc);
    return;
  }
  std::cout << "merged " << merge.trials << " trials into " << folder.results().string() << "\n"
            << "success " << rate_text(success) << "\n";
}

void add_folder_argument(CLI::App& app, std::string& dir) {
  app.add_option("DIR", dir, "the sweep's folder")->required();
}

CLI::Option* add_jobs_option(CLI::App& app, int& jobs) {
  return app.add_option("--jobs", jobs, "worker threads (0: one per core)")
      ->check(count_in(0, 1024))
      ->capture_default_str();
}

}  // namespace

Command add_sweep_command(CLI::App& root) {
  struct Options {
    std::string file, dir, backend = "local", out;
    int jobs = 0;
    std::int64_t shard_size = 0, index = -1;
    bool json = false, csv = false, export_json = false, require_complete = false;
    SlurmCli slurm;
    std::string plot;
    std::vector<std::string> heat_map;
    std::string html;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sweep = root.add_subcommand(
      "sweep",
      "parameter sweeps over a scenario: run a sweep file, resume, status, merge, export, report "
      "(docs/sweep.md)");
  sweep->require_subcommand(1);

  CLI::App* run = sweep->add_subcommand(
      "run", "expand a sweep file into trials, run them in shards, merge into DIR/results.sqlite");
  run->add_option("FILE", o->file, "sweep file (YAML or JSON)")->required();
  run->add_option("--out", o->dir, "the sweep's folder (new, empty, or holding this sweep)")
      ->required();
  run->add_option("--backend", o->backend, "where the shards run")
      ->check(CLI::IsMember({"local", "slurm"}))
      ->capture_default_str();
  add_jobs_option(*run, o->jobs);
  add_slurm_options(*run, o->slurm);
  run->add_option("--shard-size", o->shard_size,
                  "trials per shard (default: from one trial's measured time, about a minute a "
                  "shard and at least four shards per worker)")
      ->check(count_in(1, 100000000));
  add_json_flag(*run, o->json);

  CLI::App* resume = sweep->add_subcommand(
      "resume", "run the shards of DIR's sweep that have no file yet (or a damaged one), merge");
  add_folder_argument(*resume, o->dir);
  resume->add_option("--backend", o->backend, "where the shards run")
      ->check(CLI::IsMember({"local", "slurm"}))
      ->capture_default_str();
  add_jobs_option(*resume, o->jobs);
  add_slurm_options(*resume, o->slurm);
  add_json_flag(*resume, o->json);

  CLI::App* status = sweep->add_subcommand("status", "shards done, missing and damaged in DIR");
  add_folder_argument(*status, o->dir);
  add_json_flag(*status, o->json);

  CLI::App* merge =
      sweep->add_subcommand("merge", "load DIR's shard files into DIR/results.sqlite (again)");
  add_folder_argument(*merge, o->dir);
  merge->add_flag("--require-complete", o->require_complete,
                  "fail (exit 1) naming the shards without a file (the Slurm merge job)");
  add_json_flag(*merge, o->json);

  CLI::App* cancel = sweep->add_subcommand("cancel", "cancel DIR's Slurm jobs (scancel)");
  add_folder_argument(*cancel, o->dir);

  CLI::App* exporter =
      sweep->add_subcommand("export", "DIR's trials table as CSV or JSON (merged results)");
  add_folder_argument(*exporter, o->dir);
  CLI::Option* csv = exporter->add_flag("--csv", o->csv, "CSV: a header and one line per trial");
  exporter->add_flag("--json", o->export_json, "a JSON array of one object per trial")
      ->excludes(csv);
  exporter->add_option("-o,--output", o->out, "write to this file (default: standard output)");

  CLI::App* report = sweep->add_subcommand(
      "report", "success rate per axis value with 95 % Wilson intervals, metric medians and p95");
  add_folder_argument(*report, o->dir);
  report->add_option("--plot", o->plot,
                     "draw the figures into this folder: success against each varied parameter, "
                     "a success heat map, the metrics' distributions (needs gnuplot)");
  report
      ->add_option("--heat-map", o->heat_map,
                   "the heat map's axes X Y (default: the first two axes with several values)")
      ->expected(2);
  report->add_option("--html", o->html,
                     "write the dashboard, one self-contained HTML file: success per axis with "
                     "intervals, a heat map over two axes chosen on the page, the metrics' "
                     "distributions, the trials filtered, a recorded trial's replay, recording "
                     "and video linked (docs/sweep.md)");
  add_json_flag(*report, o->json);

  CLI::App* shard = sweep->add_subcommand(
      "shard", "run one shard of DIR's sweep and write its file (what a cluster task runs)");
  add_folder_argument(*shard, o->dir);
  shard->add_option("--index", o->index, "the shard, from 0")
      ->required()
      ->check(count_in(0, 100000000));

  return {sweep, [o, run, resume, status, merge, cancel, exporter, report, shard] {
            const SweepFolder folder{o->dir};
            if (run->parsed()) {
              const SweepFile file = read_sweep_file(o->file);
              const std::string text = read_user_file(o->file, "sweep file");
              std::error_code ec;
              std::int64_t size = o->shard_size;
              Json doc = Json::object();
              if (std::filesystem::exists(folder.plan(), ec)) {
                if (size == 0) size = read_sweep_plan(folder).shard_size;  // the frozen sizes
              } else if (size == 0) {
                const int jobs =
                    o->jobs > 0
                        ? o->jobs
                        : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
                // a cluster runs the shards on many nodes: a minute each; here, four a worker
                const ShardSizing sizing =
                    choose_shard_size(file, kShardSeconds, o->backend == "slurm" ? 1 : 4 * jobs);
                size = sizing.shard_size;
                doc["trial_seconds"] = sizing.trial_seconds;
                if (!o->json)
                  std::cout << "one trial took " << fixed(sizing.trial_seconds, 3)
                            << " s: shards of " << size << " trials\n";
              }
              const SweepPlan plan = make_sweep_plan(file, size);
              prepare_sweep_folder(folder, plan, text);
              doc["plan"] = plan_summary_json(plan);
              doc["folder"] = folder.dir.string();
              if (!o->json) std::cout << plan_line(plan) << "\n";
              if (o->backend == "slurm")
                return submit_to_slurm(folder, plan, o->slurm, o->json, doc);
              return run_here(folder, plan, o->jobs, o->json, doc);
            }
            if (resume->parsed()) {
              const SweepPlan plan = read_sweep_plan(folder);
              if (plan.version != version())
                throw Error("the sweep in '" + folder.dir.string() + "' was planned by mjarm " +
                            plan.version + ", this is " + version() +
                            ": its trials would not be comparable; run it with that version");
              if (!o->json) std::cout << plan_line(plan) << "\n";
              const Json doc{{"plan", plan_summary_json(plan)}, {"folder", o->dir}};
              if (o->backend == "slurm")
                return submit_to_slurm(folder, plan, o->slurm, o->json, doc);
              return run_here(folder, plan, o->jobs, o->json, doc);
            }
            if (status->parsed()) {
              const SweepPlan plan = read_sweep_plan(folder);
              const ShardStates s = shard_states(folder, plan);
              std::int64_t trials_done = 0;
              for (const std::int64_t k : s.done) trials_done += plan.shard(k).count;
              const std::vector<SlurmJob> queued = slurm_jobs(folder);  // none without Slurm jobs
              std::map<std::string, int> states;
              for (const SlurmJob& job : queued) ++states[job.state];
              if (o->json) {
                Json damaged = Json::array();
                for (const auto& [k, why] : s.damaged)
                  damaged.push_back({{"shard", k}, {"why", why}});
                print_json({{"plan", plan_summary_json(plan)},
                            {"done", s.done.size()},
                            {"missing", s.missing},
                            {"damaged", damaged},
                            {"trials_done", trials_done},
                            {"slurm", states}});
                return;
              }
              std::cout << plan_line(plan) << "\n"
                        << "done " << s.done.size() << " of " << plan.shards() << " shards ("
                        << trials_done << " of " << plan.trials << " trials), missing "
                        << s.missing.size() << ", damaged " << s.damaged.size() << "\n";
              for (const auto& [k, why] : s.damaged) std::cout << "  " << why << "\n";
              for (const auto& [state, count] : states)
                std::cout << "slurm: " << count << " " << state << "\n";
              return;
            }
            if (cancel->parsed()) {
              cancel_slurm_jobs(folder);
              if (o->json) return print_json({{"cancelled", true}});
              std::cout << "cancelled the Slurm jobs of " << folder.dir.string() << "\n";
              return;
            }
            if (merge->parsed()) {
              const SweepMerge m = merge_sweep(folder);
              if (o->json) {
                print_json(merge_json(m, folder));
              } else {
                std::cout << "merged " << m.shards << " shards, " << m.trials << " trials into "
                          << folder.results().string() << " in " << fixed(m.seconds, 3) << " s"
                          << (m.missing > 0 ? "; " + std::to_string(m.missing) + " shards missing"
                                            : std::string())
                          << "\n";
              }
              if (o->require_complete && m.missing > 0) {
                std::string list;
                for (const std::int64_t k : shard_states(folder, read_sweep_plan(folder)).missing)
                  list += (list.empty() ? "" : "; ") + slurm_shard_failure(folder, k);
                throw Error(std::to_string(m.missing) + " shards did not finish: " + list);
              }
              return;
            }
            if (exporter->parsed()) {
              if (!o->csv && !o->export_json) throw UsageError("export needs --csv or --json");
              const ResultTable table = read_trials(folder);
              const std::string text = o->csv ? table_csv(table) : table_json(table).dump(1) + "\n";
              if (o->out.empty()) {
                std::cout << text;
                return;
              }
              check_output_file(o->out, "--output");
              FileWriter out(o->out, FileWriter::Mode::replace, "export");
              out.write(text);
              out.commit();
              return;
            }
            if (report->parsed()) {
              const SweepReport r = sweep_report(folder);
              if (!o->heat_map.empty() && o->plot.empty())
                throw UsageError("--heat-map needs --plot DIR");
              if (!o->html.empty()) check_output_file(o->html, "--html");
              std::vector<plot::PlotInfo> figures;
              if (!o->plot.empty()) {
                check_output_folder(o->plot, "--plot");
                SweepPlotOptions plot_options;
                plot_options.heat_map = o->heat_map;
                figures = plot_sweep(folder, o->plot, plot_options);
              }
              std::optional<SweepDashboard> dashboard;
              if (!o->html.empty()) dashboard = write_sweep_dashboard(folder, o->html);
              if (o->json) {
                Json doc = sweep_report_json(r);
                Json paths = Json::array();
                for (const plot::PlotInfo& f : figures) paths.push_back(f.path.string());
                doc["figures"] = paths;
                if (dashboard)
                  doc["dashboard"] = {{"path", dashboard->path.string()},
                                      {"trials", dashboard->trials},
                                      {"recorded", dashboard->recorded},
                                      {"bytes", dashboard->bytes}};
                return print_json(doc);
              }
              for (const plot::PlotInfo& f : figures)
                std::cout << "figure: " << f.path.string() << "\n";
              if (dashboard)
                std::cout << "dashboard: " << dashboard->path.string() << " (" << dashboard->trials
                          << " trials, " << dashboard->recorded << " recorded, "
                          << (dashboard->bytes + 1023) / 1024 << " KiB)\n";
              std::cout << "sweep " << r.scenario << " (plan " << r.hash << "): success "
                        << rate_text(r.success)
                        << (r.success.trials < r.planned
                                ? " of " + std::to_string(r.planned) + " planned"
                                : std::string())
                        << "\n";
              std::string verdicts;
              for (const auto& [name, count] : r.verdicts)
                verdicts += (verdicts.empty() ? "" : ", ") + name + " " + std::to_string(count);
              std::cout << "verdicts: " << verdicts << "\n";
              Table groups({{"parameter", Table::Align::left},
                            {"value", Table::Align::left},
                            {"success"},
                            {"rate"},
                            {"95 % interval"}});
              for (const ReportGroup& g : r.groups)
                groups.add_row(
                    {g.parameter, g.value.is_string() ? g.value.get<std::string>() : g.value.dump(),
                     std::to_string(g.success.successes) + "/" + std::to_string(g.success.trials),
                     percent(g.success.rate),
                     fixed(100.0 * g.success.low, 1) + "–" + percent(g.success.high)});
              if (groups.rows() > 0) groups.print(std::cout, 0);
              Table metrics({{"metric", Table::Align::left},
                             {"unit", Table::Align::left},
                             {"trials"},
                             {"median"},
                             {"p95"}});
              for (const MetricSummary& m : r.metrics)
                metrics.add_row({m.name, m.unit, std::to_string(m.count),
                                 m.count > 0 ? compact(m.median) : "—",
                                 m.count > 0 ? compact(m.p95) : "—"});
              metrics.print(std::cout, 0);
              return;
            }
            if (shard->parsed()) {
              const InterruptGuard interrupts;
              const SweepPlan plan = read_sweep_plan(folder);
              if (!run_sweep_shard(folder, plan, o->index))
                throw InterruptedError(
                    "shard " + std::to_string(o->index) + " was interrupted: no file written",
                    interrupt_signal());
            }
          }};
}

}  // namespace mjarm::cli
