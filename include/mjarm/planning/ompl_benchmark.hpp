#pragma once
/// @file
/// `mjarm bench ompl`: the shelf benchmark of joint-space planning in the style of the published
/// ones (MotionBenchMaker's "shelf"): the panda reaches between the cells of a three-level,
/// two-column shelf with boxes around the goals, over seeded start/goal pairs, and the cost of
/// one validity check against MuJoCo's plain `mj_forward` on the same states. docs/planning.md.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/planning/ompl_planner.hpp"

namespace mjarm {

/// The benchmark's protocol.
struct OmplBenchmarkOptions {
  int pairs = 100;         ///< start/goal pairs planned (≥ 1)
  std::uint64_t seed = 1;  ///< seed of the pairs (and of each plan: seed + pair index)
  OmplPlannerType planner = OmplPlannerType::rrtconnect;  ///< the planner
  double time_budget = 5.0;                               ///< budget of each plan [s], in (0, 3600]
  int checker_states = 20000;  ///< random states timed for the cost per check (≥ 1)
  /// Called after each plan with (plans done, plans in all); may be empty.
  std::function<void(int done, int total)> progress;
  /// Asked before each plan whether to stop (e.g. after Ctrl-C); may be empty.
  std::function<bool()> stop;
};

constexpr auto declared_fields(const OmplBenchmarkOptions*) {
  using S = OmplBenchmarkOptions;
  return declare<S>(
      "OMPL benchmark",
      field("pairs", &S::pairs, "", Range::closed(1, 100000), "start/goal pairs planned"),
      field("seed", &S::seed, "", Range::non_negative(), "seed of the pairs and the plans"),
      field("planner", &S::planner, "the OMPL planner"),
      field("time_budget", &S::time_budget, "s", Range::open_closed(0.0, 3600.0),
            "budget of each plan"),
      field("checker_states", &S::checker_states, "", Range::closed(1, 10000000),
            "random states timed for the cost per check"));
}

/// @throws Error naming the option out of range.
void check(const OmplBenchmarkOptions& options);

/// What the benchmark measured.
struct OmplBenchmarkResult {
  int pairs = 0;                 ///< pairs planned (fewer than asked when stopped)
  int successes = 0;             ///< plans with status success
  double success_rate = 0.0;     ///< successes / pairs
  double time_median = 0.0;      ///< planning time, median over all plans [s]
  double time_p95 = 0.0;         ///< planning time, 95th percentile (nearest rank) [s]
  double length_median = 0.0;    ///< joint-space path length, median over the successes [rad]
  double checks_median = 0.0;    ///< validity checks per plan, median over all plans
  double knots_median = 0.0;     ///< knots of the simplified path, median over the successes
  double duration_median = 0.0;  ///< duration of the timed trajectory, median over successes [s]
  int time_optimal = 0;          ///< successes that also have a time-optimal timing
  double time_optimal_median = 0.0;  ///< its duration, median over those [s]
  /// Its duration over the blended spline's, median and largest over those.
  double time_optimal_ratio_median = 0.0, time_optimal_ratio_max = 0.0;
  double check_us = 0.0;    ///< one `CollisionChecker::valid` (mj_kinematics + mj_collision) [µs]
  double forward_us = 0.0;  ///< one `mj_forward` (its mj_collision included) + the filter [µs]
  double collision_share = 0.0;      ///< share of the timed random states in collision
  std::vector<OmplStatus> statuses;  ///< per pair
  bool interrupted = false;          ///< stopped before the last pair
};

/// The panda (models/panda) before the shelf: boards at z = 0.05, 0.35, 0.65, 0.95 m between
/// x = 0.45 and 0.75 m, side walls at y = ±0.45 m, a divider at y = 0, a back wall, and three
/// boxes in every cell behind and beside where the goals are drawn; the torque motors of
/// models/panda_torque.xml (published torque limits).
Robot shelf_benchmark_scene();

/// The seeded start/goal pairs: each a collision-free IK solution of a pose in one cell (tool
/// pointing into the shelf, roll within ±0.5 rad) and one in another cell.
/// @throws Error when a cell yields no collision-free pose in 200 draws (a broken scene).
std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> shelf_benchmark_pairs(const Chain& chain,
                                                                               int pairs,
                                                                               std::uint64_t seed);

/// Runs the benchmark (see the file comment).
/// @throws Error for invalid options.
OmplBenchmarkResult run_ompl_benchmark(const OmplBenchmarkOptions& options);

}  // namespace mjarm
