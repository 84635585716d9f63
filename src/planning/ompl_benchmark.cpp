#include "mjarm/planning/ompl_benchmark.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <chrono>
#include <sstream>
#include <string>

#include "mjarm/benchmark_timing.hpp"
#include "mjarm/error.hpp"
#include "mjarm/ik/global_ik.hpp"
#include "mjarm/planning/collision_checker.hpp"
#include "mjarm/random.hpp"

namespace mjarm {

void check(const OmplBenchmarkOptions& options) { check_fields(options); }

namespace {

constexpr std::array<double, 4> kBoardHeights{0.05, 0.35, 0.65, 0.95};           // [m]
constexpr double kShelfFront = 0.45, kShelfBack = 0.75, kShelfHalfWidth = 0.45;  // [m]
constexpr std::array<double, 2> kColumnCentres{-0.225, 0.225};                   // y [m]

struct Cell {
  double y = 0.0;       // column centre
  double bottom = 0.0;  // top of the board below
  double top = 0.0;     // bottom of the board above
};

std::vector<Cell> shelf_cells() {
  std::vector<Cell> cells;
  for (std::size_t level = 0; level + 1 < kBoardHeights.size(); ++level)
    for (const double y : kColumnCentres)
      cells.push_back({y, kBoardHeights[level] + 0.01, kBoardHeights[level + 1] - 0.01});
  return cells;
}

void add_box(std::ostringstream& xml, const std::string& name, const Eigen::Vector3d& centre,
             const Eigen::Vector3d& half, const char* rgba) {
  xml << "    <geom name=\"" << name << "\" type=\"box\" pos=\"" << centre.x() << ' ' << centre.y()
      << ' ' << centre.z() << "\" size=\"" << half.x() << ' ' << half.y() << ' ' << half.z()
      << "\" rgba=\"" << rgba << "\"/>\n";
}

}  // namespace

Robot shelf_benchmark_scene() {
  std::ostringstream xml;
  xml << R"(<mujoco model="panda_shelf">
  <compiler angle="radian" autolimits="true"/>
  <include file="common/scene.xml"/>
  <include file="panda/panda_body.xml"/>
  <worldbody>
)";
  const double depth = 0.5 * (kShelfBack - kShelfFront);
  const double middle = 0.5 * (kShelfBack + kShelfFront);
  const double height = 0.5 * (kBoardHeights.back() + 0.01);
  const char* wood = "0.6 0.45 0.3 1";
  for (std::size_t b = 0; b < kBoardHeights.size(); ++b)
    add_box(xml, "shelf/board" + std::to_string(b), {middle, 0.0, kBoardHeights[b]},
            {depth, kShelfHalfWidth, 0.01}, wood);
  add_box(xml, "shelf/back", {kShelfBack + 0.01, 0.0, height}, {0.01, kShelfHalfWidth, height},
          wood);
  for (const double y : {-kShelfHalfWidth, 0.0, kShelfHalfWidth})
    add_box(xml, "shelf/side" + std::to_string(static_cast<int>(std::round(y * 100))),
            {middle, y, height}, {depth, 0.01, height}, wood);
  // clutter: in every cell two boxes behind the goal area and one beside it
  int clutter = 0;
  for (const Cell& c : shelf_cells()) {
    const char* red = "0.8 0.3 0.2 1";
    const double half_height = 0.06;
    add_box(xml, "clutter" + std::to_string(clutter++), {0.68, c.y - 0.11, c.bottom + half_height},
            {0.035, 0.035, half_height}, red);
    add_box(xml, "clutter" + std::to_string(clutter++), {0.68, c.y + 0.11, c.bottom + half_height},
            {0.035, 0.035, half_height}, red);
    add_box(xml, "clutter" + std::to_string(clutter++),
            {0.52, c.y + (c.y > 0 ? 0.17 : -0.17), c.bottom + 0.04}, {0.025, 0.025, 0.04}, red);
  }
  // the torque motors of models/panda_torque.xml, so that the scene also runs under torque control
  xml << R"(  </worldbody>
  <actuator>
)";
  for (int j = 1; j <= 7; ++j)
    xml << "    <motor name=\"joint" << j << "\" joint=\"joint" << j
        << "\" gear=\"1\" ctrllimited=\"true\" ctrlrange=\"" << (j <= 4 ? "-87 87" : "-12 12")
        << "\"/>\n";
  xml << R"(  </actuator>
  <keyframe><key name="home" qpos="0 -0.785 0 -2.356 0 1.571 0.785"/></keyframe>
</mujoco>)";
  return Robot::from_string(xml.str(), Robot::models_dir());
}

std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> shelf_benchmark_pairs(const Chain& chain,
                                                                               int pairs,
                                                                               std::uint64_t seed) {
  const std::vector<Cell> cells = shelf_cells();
  Random rng(seed);
  CollisionChecker checker(chain);
  GlobalIkOptions ik_options;
  ik_options.timeout = std::chrono::milliseconds(20);
  GlobalIk ik(chain, ik_options);
  // the tool's z axis into the shelf (+x), its y axis up to a roll of ±0.5 rad
  const Eigen::Matrix3d R_in =
      Eigen::AngleAxisd(0.5 * 3.141592653589793, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const auto draw_in_cell = [&](const Cell& c) {
    for (int attempt = 0; attempt < 200; ++attempt) {
      Pose X;
      X.p = {uniform(rng, 0.50, 0.58), c.y + uniform(rng, -0.06, 0.06),
             0.5 * (c.bottom + c.top) + uniform(rng, -0.04, 0.04)};
      X.R = R_in * Eigen::AngleAxisd(uniform(rng, -0.5, 0.5), Eigen::Vector3d::UnitZ());
      ik_options.seed = rng();
      ik.set_options(ik_options);
      Eigen::VectorXd q_seed(chain.size());
      for (int i = 0; i < chain.size(); ++i)
        q_seed[i] = uniform(rng, chain.lower()[i], chain.upper()[i]);
      const IkResult solved = ik.solve(X, q_seed);
      if (solved.status == IkStatus::converged && checker.valid(solved.q)) return solved.q;
    }
    throw Error("shelf benchmark: no collision-free pose found in a cell in 200 draws");
  };
  std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> out;
  for (int k = 0; k < pairs; ++k) {
    const std::uint64_t from = uniform_index(rng, cells.size());
    std::uint64_t to = uniform_index(rng, cells.size() - 1);
    if (to >= from) ++to;  // another cell
    Eigen::VectorXd start = draw_in_cell(cells[from]);
    Eigen::VectorXd goal = draw_in_cell(cells[to]);
    out.emplace_back(std::move(start), std::move(goal));
  }
  return out;
}

namespace {

double median_of(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return nearest_rank(values, 0.5);
}

/// µs per state of @p check over @p states.
template <class Check>
double microseconds_per_state(const std::vector<Eigen::VectorXd>& states, Check check) {
  const double t0 = steady_seconds();
  for (const Eigen::VectorXd& q : states) check(q);
  return (steady_seconds() - t0) * 1e6 / static_cast<double>(states.size());
}

}  // namespace

OmplBenchmarkResult run_ompl_benchmark(const OmplBenchmarkOptions& options) {
  check(options);
  const Robot robot = shelf_benchmark_scene();
  const Chain chain(robot, "attachment_site");
  OmplBenchmarkResult r;

  // the cost of one check against MuJoCo's plain forward pass, on the same random states
  {
    Random rng(splitmix64(options.seed));
    std::vector<Eigen::VectorXd> states(options.checker_states, Eigen::VectorXd(chain.size()));
    for (Eigen::VectorXd& q : states)
      for (int i = 0; i < chain.size(); ++i)
        q[i] = uniform(rng, chain.lower()[i], chain.upper()[i]);
    CollisionChecker checker(chain);
    int collisions = 0;
    r.check_us = microseconds_per_state(
        states, [&](const Eigen::VectorXd& q) { collisions += checker.valid(q) ? 0 : 1; });
    r.collision_share = static_cast<double>(collisions) / static_cast<double>(states.size());
    const mjModel& m = robot.model();
    const DataPtr data = robot.make_data();
    int forward_collisions = 0;
    r.forward_us = microseconds_per_state(states, [&](const Eigen::VectorXd& q) {
      chain.scatter(q, data->qpos);
      mj_forward(&m, data.get());
      forward_collisions += checker.contacts().deepest(*data, 0.0).found() ? 1 : 0;
    });
    if (forward_collisions != collisions)
      throw Error("shelf benchmark: mj_forward and the collision checker disagree on " +
                  std::to_string(std::abs(forward_collisions - collisions)) + " states");
  }

  const auto pairs = shelf_benchmark_pairs(chain, options.pairs, options.seed);
  std::vector<double> times, lengths, checks, knots, durations, optimal, ratios;
  for (int k = 0; k < options.pairs; ++k) {
    if (options.stop && options.stop()) {
      r.interrupted = true;
      break;
    }
    OmplOptions plan_options;
    plan_options.planner = options.planner;
    plan_options.time_budget = options.time_budget;
    plan_options.seed = options.seed + static_cast<std::uint64_t>(k);
    OmplPlanner planner(chain, plan_options);
    const OmplResult plan = planner.plan(pairs[k].first, JointGoal{pairs[k].second});
    r.statuses.push_back(plan.status);
    times.push_back(plan.planning_time);
    checks.push_back(static_cast<double>(plan.validity_checks));
    if (plan.ok()) {
      ++r.successes;
      lengths.push_back(plan.path_length);
      knots.push_back(static_cast<double>(plan.path.size()));
      durations.push_back(plan.trajectory.duration());
      if (plan.time_optimal) {
        optimal.push_back(plan.time_optimal->duration());
        ratios.push_back(optimal.back() / durations.back());
      }
    }
    if (options.progress) options.progress(k + 1, options.pairs);
  }
  r.pairs = static_cast<int>(r.statuses.size());
  r.success_rate = r.pairs > 0 ? static_cast<double>(r.successes) / r.pairs : 0.0;
  r.time_median = median_of(times);
  std::sort(times.begin(), times.end());
  r.time_p95 = nearest_rank(times, 0.95);
  r.length_median = median_of(lengths);
  r.checks_median = median_of(checks);
  r.knots_median = median_of(knots);
  r.duration_median = median_of(durations);
  r.time_optimal = static_cast<int>(optimal.size());
  r.time_optimal_median = median_of(optimal);
  r.time_optimal_ratio_median = median_of(ratios);
  r.time_optimal_ratio_max = ratios.empty() ? 0.0 : *std::max_element(ratios.begin(), ratios.end());
  return r;
}

}  // namespace mjarm
