// `mjarm env list [--json]`: the environment tasks, their options, action spaces and
// observations.
// `mjarm env run TASK [task options] [--policy random|zero] [--episodes N] [--action-space S]
// [--envs E] [--threads T] [--seed S] [--time-limit T] [--json]`: episodes of a task, their
// returns and the steps per second (docs/env.md).

#include <time.h>

#include <chrono>
#include <iostream>
#include <limits>
#include <memory>

#include "commands.hpp"
#include "field_options.hpp"
#include "mjarm/closest_names.hpp"
#include "mjarm/env/observation_set.hpp"
#include "mjarm/env/task_registry.hpp"
#include "mjarm/env/vector_environment.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/random.hpp"
#include "mjarm/scenarios/scenario.hpp"
#include "output.hpp"
#include "parameter_options.hpp"

namespace mjarm::cli {
namespace {

Json spec_json(const ArraySpec& spec) {
  Json minimum = Json::array(), maximum = Json::array();
  for (Eigen::Index i = 0; i < spec.minimum.size(); ++i) {
    minimum.push_back(number_or_null(spec.minimum[i]));
    maximum.push_back(number_or_null(spec.maximum[i]));
  }
  return {{"name", spec.name},
          {"shape", spec.shape},
          {"dtype", to_string(spec.dtype)},
          {"minimum", minimum},
          {"maximum", maximum}};
}

void list_tasks(bool json) {
  Json tasks = Json::array();
  for (const std::string& name : env_task_names()) {
    const std::unique_ptr<EnvTask> task = make_env_task(name);
    Json spaces = Json::array();
    std::vector<std::string> space_lines;
    for (ActionSpace space : action_spaces()) {
      EnvironmentOptions o;
      o.action_space = space;
      const Environment env(task->clone(), o);
      spaces.push_back(
          {{"action_space", to_string(space)}, {"spec", spec_json(env.action_spec())}});
      space_lines.push_back(std::string(to_string(space)) + ": " + env.action_spec().describe());
    }
    const Environment env(task->clone());
    Json observations = Json::array();
    for (const ArraySpec& a : env.observation_spec().arrays()) observations.push_back(spec_json(a));
    const std::vector<std::string> available = ObservationSet::available(*task);
    if (json) {
      Json parameters = Json::array();
      for (const FieldInfo& p : env_task_parameters(name)) parameters.push_back(parameter_json(p));
      tasks.push_back({{"name", name},
                       {"description", task->description()},
                       {"options", std::move(parameters)},
                       {"model", task->robot().name()},
                       {"joints", task->chain().size()},
                       {"control_period_s", env.options().control_period},
                       {"physics_steps_per_step", env.physics_steps_per_step()},
                       {"time_limit_s", env.options().time_limit},
                       {"action_spaces", spaces},
                       {"default_observations", observations},
                       {"available_observations", available}});
      continue;
    }
    std::cout << name << " — " << task->description() << '\n';
    print_fields(
        std::cout,
        {{"model", task->robot().name() + " (" + std::to_string(task->chain().size()) + " joints)"},
         {"control step", compact(env.options().control_period) +
                              " s = " + std::to_string(env.physics_steps_per_step()) +
                              " physics steps; time limit " + compact(env.options().time_limit) +
                              " s"}},
        2);
    std::cout << "  action spaces:\n";
    for (const std::string& line : space_lines) std::cout << "    " << line << '\n';
    std::cout << "  default observations:\n";
    for (const ArraySpec& a : env.observation_spec().arrays())
      std::cout << "    " << a.describe() << '\n';
    std::cout << "  available observations: " << join(available) << "\n\n";
  }
  if (json) print_json({{"tasks", tasks}});
}

struct RunOptions {
  std::string task;
  Json task_options = Json::object();  ///< the task's own options given (`mjarm env run TASK --…`)
  std::string policy = "random";
  int episodes = 10;
  std::string action_space = "ee_pose_deltas";
  int envs = 1;
  int threads = 1;
  std::uint64_t seed = 0;
  double time_limit = 10.0;
  bool json = false;
};

struct Episode {
  int env = 0;
  std::uint64_t seed = 0;
  double episode_return = 0.0;
  int steps = 0;
  EpisodeEnd end = EpisodeEnd::running;
};

double process_cpu_seconds() noexcept {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

void run_episodes(const RunOptions& options) {
  EnvironmentOptions o;
  o.action_space = action_space(options.action_space);
  o.time_limit = options.time_limit;
  o.seed = options.seed;
  std::unique_ptr<EnvTask> task;
  try {
    task = make_env_task(options.task, options.task_options);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  VectorEnvironment batch(std::move(task), o, options.envs, options.threads);
  const ArraySpec& spec = batch.action_spec();
  const std::size_t width = static_cast<std::size_t>(spec.size());
  const std::size_t n = static_cast<std::size_t>(batch.size());
  std::vector<double> actions(width * n, 0.0);
  Random rng(options.seed);
  std::vector<double> returns(n, 0.0);
  std::vector<int> steps(n, 0);
  std::vector<Episode> episodes;
  std::int64_t env_steps = 0;
  Progress progress("episodes", options.episodes);
  const InterruptGuard interrupts;  // Ctrl-C: the episodes done so far
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = process_cpu_seconds();
  batch.reset();
  std::vector<std::uint64_t> seeds(n);
  for (std::size_t i = 0; i < n; ++i)
    seeds[i] = batch.environment(static_cast<int>(i)).episode_seed();
  while (static_cast<int>(episodes.size()) < options.episodes && !interrupt_requested()) {
    if (options.policy == "random") {
      for (std::size_t k = 0; k < actions.size(); ++k) {
        const Eigen::Index j = static_cast<Eigen::Index>(k % width);
        actions[k] = uniform(rng, spec.minimum[j], spec.maximum[j]);
      }
    }
    batch.step(actions);
    for (std::size_t i = 0; i < n; ++i) {
      const StepType type = batch.step_types()[i];
      if (type == StepType::first) {  // an automatic reset
        returns[i] = 0.0;
        steps[i] = 0;
        seeds[i] = batch.environment(static_cast<int>(i)).episode_seed();
        continue;
      }
      ++env_steps;
      returns[i] += batch.rewards()[i];
      ++steps[i];
      if (type == StepType::last && static_cast<int>(episodes.size()) < options.episodes)
        episodes.push_back({static_cast<int>(i), seeds[i], returns[i], steps[i], batch.ends()[i]});
    }
    progress.update(static_cast<std::int64_t>(episodes.size()));
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const double cpu = process_cpu_seconds() - cpu0;
  progress.finish();

  double mean = 0.0;
  int terminated = 0;
  for (const Episode& e : episodes) {
    mean += e.episode_return;
    terminated += e.end == EpisodeEnd::terminated ? 1 : 0;
  }
  if (!episodes.empty()) mean /= static_cast<double>(episodes.size());
  const double rate = static_cast<double>(env_steps) / wall;
  if (options.json) {
    Json list = Json::array();
    for (const Episode& e : episodes)
      list.push_back({{"env", e.env},
                      {"seed", e.seed},
                      {"return", e.episode_return},
                      {"steps", e.steps},
                      {"end", to_string(e.end)}});
    print_json({{"task", options.task},
                {"task_options", options.task_options},
                {"policy", options.policy},
                {"action_space", options.action_space},
                {"envs", options.envs},
                {"threads", options.threads},
                {"seed", options.seed},
                {"episodes", list},
                {"mean_return", mean},
                {"terminated", terminated},
                {"env_steps", env_steps},
                {"wall_s", wall},
                {"cpu_s", cpu},
                {"steps_per_second", rate},
                {"interrupted", interrupt_requested()}});
  } else {
    Table table(
        {{"episode"}, {"env"}, {"seed"}, {"return"}, {"steps"}, {"end", Table::Align::left}});
    for (std::size_t k = 0; k < episodes.size(); ++k) {
      const Episode& e = episodes[k];
      table.add_row({std::to_string(k + 1), std::to_string(e.env), std::to_string(e.seed),
                     fixed(e.episode_return, 3), std::to_string(e.steps), to_string(e.end)});
    }
    table.print(std::cout);
    std::cout << '\n';
    print_fields(
        std::cout,
        {{"task", options.task + ", " + options.policy + " policy, " + options.action_space},
         {"mean return", fixed(mean, 3) + " over " + std::to_string(episodes.size()) +
                             " episodes (" + std::to_string(terminated) + " terminated)"},
         {"steps per second", fixed(rate, 0) + " (wall, " + std::to_string(env_steps) +
                                  " steps; envs " + std::to_string(options.envs) + ", threads " +
                                  std::to_string(options.threads) + "; process CPU " +
                                  fixed(cpu, 2) + " s)"}});
  }
  if (interrupt_requested())
    throw InterruptedError("env run: interrupted after " + std::to_string(episodes.size()) +
                               " of " + std::to_string(options.episodes) + " episodes",
                           interrupt_signal());
}

}  // namespace

Command add_env_command(CLI::App& root) {
  CLI::App* env = root.add_subcommand(
      "env",
      "learning environments (dm_env semantics): list the tasks and their specs, run "
      "random or zero-action episodes");
  env->require_subcommand(1);
  auto list_json = std::make_shared<bool>(false);
  CLI::App* list = env->add_subcommand(
      "list", "the tasks with their model, action spaces (bounds) and observations");
  add_json_flag(*list, *list_json);

  auto options = std::make_shared<RunOptions>();
  CLI::App* run = env->add_subcommand(
      "run",
      "episodes of TASK with a random (uniform within the action bounds) or zero-action "
      "policy: the return and length of each, the steps per second; mjarm env run TASK --help "
      "for the task's own options");
  run->require_subcommand(0, 1);
  run->allow_extras();  // an unknown task or option, named with the closest below
  // one subcommand per task with its declared options; the options below fall through to run
  std::vector<std::pair<CLI::App*, std::shared_ptr<ParameterOptions>>> tasks;
  for (const std::string& name : env_task_names()) {
    CLI::App* task = run->add_subcommand(name, "the " + name + " task (mjarm env list)");
    task->fallthrough();
    tasks.emplace_back(task, std::make_shared<ParameterOptions>(
                                 *task, env_task_parameters(name),
                                 "Options of the " + name + " task (mjarm env list --json)"));
  }
  run->add_option("--policy", options->policy, "random or zero")
      ->check(CLI::IsMember({"random", "zero"}));
  run->add_option("--episodes", options->episodes, "episodes to complete")
      ->check(count_in(1, 100000));
  run->add_option("--action-space", options->action_space, "action space")
      ->check(name_of<ActionSpace>("action space"));
  run->add_option("--envs", options->envs, "environments stepped together")
      ->check(count_in(1, 4096));
  run->add_option("--threads", options->threads, "threads stepping them")->check(count_in(1, 256));
  run->add_option("--seed", options->seed, "seed of the episodes and of the random policy")
      ->check(non_negative_integer());
  run->add_option("--time-limit", options->time_limit, "episode length [s]")
      ->check(number_in(0.02, 3600.0));
  add_json_flag(*run, options->json);

  return {env, [list, list_json, run, options, tasks] {
            if (list->parsed()) return list_tasks(*list_json);
            if (!run->parsed()) return;
            const std::vector<std::string> extra = run->remaining();
            for (const auto& [task, parameters] : tasks) {
              if (!task->parsed()) continue;
              if (!extra.empty()) {
                std::vector<std::string> names;
                const CLI::App* apps[] = {task, run};
                for (const CLI::App* app : apps)
                  for (const CLI::Option* o : app->get_options())
                    for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
                const std::string word = extra.front().substr(0, extra.front().find('='));
                const std::vector<std::string> closest = closest_names(word, names);
                throw UsageError("env run " + task->get_name() + ": unexpected '" + word + "'" +
                                 (closest.empty() ? std::string() : "; closest: " + join(closest)));
              }
              options->task = task->get_name();
              options->task_options = parameters->values();
              return run_episodes(*options);
            }
            if (!extra.empty())
              throw UsageError(unknown_name_message("task", extra.front(), env_task_names()));
            throw UsageError("env run needs a TASK (" + join(env_task_names(), " | ") +
                             "); mjarm env run TASK --help");
          }};
}

}  // namespace mjarm::cli
