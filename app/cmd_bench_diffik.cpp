// `mjarm bench diffik [--scene FILE] [--site S] [--steps N] [--json]`: what collision rows cost a
// differential-IK step (docs/ik.md, "Inequality constraints"). Protocol: the scene's robot
// (default: the bundled pick_table scene, the panda with its hand over a table) tracks a 10 cm
// circle (period 3 s) 6 cm above the table top with DiffIk (pose task gain 0.5, posture 1e-3,
// velocity limits 2 rad/s, dt 0.01 s); once with the box QP only, once with CollisionAvoidance
// (robot_vs_scene, min 0.01 m, detection 0.05 m, gain 0.5). Thread CPU time per step, mean over N
// steps after 100 untimed ones.

#include <cmath>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mjarm/benchmark_timing.hpp"
#include "mjarm/ik/collision_avoidance.hpp"
#include "mjarm/ik/diff_ik.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "options.hpp"
#include "output.hpp"

namespace mjarm::cli {

namespace {

struct DiffIkBenchRun {
  double us_per_step = 0.0;      // thread CPU [µs]
  double mean_rows = 0.0;        // active collision rows per step
  double mean_iterations = 0.0;  // QP iterations per step
  double closest = 0.0;          // smallest watched distance seen [m] (collision run)
  int pairs = 0;
};

DiffIkBenchRun run_diffik_bench(const Chain& chain, bool collisions, int steps) {
  DiffIkOptions options;
  options.dt = 0.01;
  options.velocity_limit = Eigen::VectorXd::Constant(chain.size(), 2.0);
  DiffIk ik(chain, options);
  const int pose = ik.add_pose_task({}, 1.0, 1.0, 0.5);
  ik.add_posture_task(chain.center(), 1e-3);
  DiffIkBenchRun run;
  CollisionAvoidance* avoid = nullptr;
  if (collisions) {
    CollisionAvoidanceOptions c;
    c.robot_vs_scene = true;
    c.min_distance = 0.01;
    c.detection_distance = 0.05;
    auto constraint = std::make_unique<CollisionAvoidance>(chain, c);
    avoid = constraint.get();
    run.pairs = constraint->pair_count();
    ik.add_constraint(std::move(constraint));
  }
  Eigen::VectorXd q(chain.size());
  q << 0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785;  // the panda's home
  q = chain.clamp(q);
  ChainKinematics kin(chain);
  Pose target = kin.update(q);
  const Eigen::Vector3d center(target.p.x(), target.p.y(), 0.4 + 0.06 + 0.1);  // table top 0.4
  const auto step = [&](int k) {
    const double phase = 2.0 * 3.141592653589793 * k * options.dt / 3.0;
    target.p = center + 0.1 * Eigen::Vector3d(std::sin(phase), 1.0 - std::cos(phase), -1.0);
    ik.set_target(pose, target);
    q = ik.step(q).q_next;
  };
  for (int k = 0; k < 100; ++k) step(k);
  double rows = 0.0, iterations = 0.0;
  run.closest = 1e9;
  const double start = thread_cpu_seconds();
  for (int k = 100; k < 100 + steps; ++k) {
    step(k);
    rows += ik.last_step().constraint_rows;
    iterations += ik.last_step().qp_iterations;
    if (avoid != nullptr) run.closest = std::min(run.closest, avoid->min_distance_seen());
  }
  run.us_per_step = 1e6 * (thread_cpu_seconds() - start) / steps;
  run.mean_rows = rows / steps;
  run.mean_iterations = iterations / steps;
  return run;
}

}  // namespace

Command add_bench_diffik_subcommand(CLI::App& bench) {
  struct Options {
    std::string scene = (Robot::models_dir() / "scenes" / "pick_table.yaml").string();
    std::string site = "panda/attachment_site";
    int steps = 2000;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* app = bench.add_subcommand(
      "diffik",
      "differential IK with collision rows: thread CPU per step of the scene's arm tracking a "
      "circle near the table, box QP alone vs robot-vs-scene collision rows (dense QP)");
  app->add_option("--scene", options->scene,
                  "scene file or model with obstacles (default: the bundled pick_table scene)");
  app->add_option("--site", options->site, "the chain's frame (site)");
  app->add_option("--steps", options->steps, "timed steps per run")->check(count_in(1, 10000000));
  add_json_flag(*app, options->json);
  return {app, [options] {
            const Robot robot = load_model(options->scene);
            const Chain chain(robot, options->site);
            const DiffIkBenchRun box = run_diffik_bench(chain, false, options->steps);
            const DiffIkBenchRun guarded = run_diffik_bench(chain, true, options->steps);
            if (options->json) {
              print_json({{"scene", options->scene},
                          {"steps", options->steps},
                          {"box_us_per_step", box.us_per_step},
                          {"collision_us_per_step", guarded.us_per_step},
                          {"pairs", guarded.pairs},
                          {"mean_active_rows", guarded.mean_rows},
                          {"mean_qp_iterations", guarded.mean_iterations},
                          {"closest_m", guarded.closest}});
              return;
            }
            print_fields(
                std::cout,
                {{"scene", options->scene},
                 {"box QP", fixed(box.us_per_step, 2) + " µs per step (thread CPU)"},
                 {"collision rows",
                  fixed(guarded.us_per_step, 2) + " µs per step, " + std::to_string(guarded.pairs) +
                      " pairs, " + fixed(guarded.mean_rows, 2) + " active rows and " +
                      fixed(guarded.mean_iterations, 1) + " QP iterations per step on average"},
                 {"closest watched distance", fixed(guarded.closest, 4) + " m"}});
          }};
}

}  // namespace mjarm::cli
