#include "mjarm/trajectory/path/validation/topp_protocol.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "mjarm/benchmark_timing.hpp"
#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/trajectory/path/jerk_waypoints.hpp"
#include "mjarm/trajectory/path/time_optimal_path.hpp"
#include "mjarm/trajectory/path/validation/topp_reference.hpp"

namespace mjarm {

namespace {

double topp_log_uniform(Random& rng, double lo, double hi) {
  return lo * std::pow(hi / lo, uniform(rng));
}

/// The roots of a + b·τ + c·τ² in (0, h), at most 2 (c ≈ 0: the linear root).
int topp_quadratic_roots(double a, double b, double c, double h, std::array<double, 2>& roots) {
  int count = 0;
  const auto keep = [&](double r) {
    if (r > 0.0 && r < h) roots[count++] = r;
  };
  if (std::abs(c) * h <= 1e-14 * (std::abs(b) + std::abs(a) / h)) {
    if (b != 0.0) keep(-a / b);
    return count;
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return 0;
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  if (q != 0.0) keep(a / q);
  keep(q / c);
  return count;
}

/// The worst relative excess of @p topp over its limits, max(|q̇_j|/v_j, |q̈_j|/a_j) − 1, at the
/// analytic extrema of every piece of every step (see the file comment of the header).
double topp_analytic_excess(const TimeOptimalPath& topp) {
  const JointPath& path = topp.path();
  const Eigen::Index n = path.dofs();
  const Eigen::VectorXd& grid = topp.grid();
  const Eigen::VectorXd& x = topp.squared_speeds();
  const Eigen::VectorXd& u = topp.path_accelerations();
  const Eigen::VectorXd& v_max = topp.max_velocity();
  const Eigen::VectorXd& a_max = topp.max_acceleration();
  Eigen::VectorXd q(n), d1[3] = {Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n)},
                        d2[3] = {Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n)};
  double excess = -1.0;
  Eigen::VectorXd speed_d1(n), speed_d2(n);  // scratch of speed_excess (d1, d2 are in use)
  const auto speed_excess = [&](double s, double x_s) {
    path.evaluate(s, q, speed_d1, speed_d2);
    const double ds = std::sqrt(std::max(x_s, 0.0));
    return (speed_d1.cwiseAbs() * ds).cwiseQuotient(v_max).maxCoeff() - 1.0;
  };
  const Eigen::VectorXd& knots = path.knots();
  for (Eigen::Index i = 0; i + 1 < grid.size(); ++i) {
    // the step's pieces, split at the spline's knots inside it
    std::array<double, 10> cuts{};
    int cut_count = 0;
    cuts[cut_count++] = grid[i];
    for (Eigen::Index k = 1; k + 1 < knots.size() && cut_count < 9; ++k)
      if (knots[k] > grid[i] && knots[k] < grid[i + 1]) cuts[cut_count++] = knots[k];
    cuts[cut_count++] = grid[i + 1];
    const auto X = [&](double s) { return x[i] + 2.0 * u[i] * (s - grid[i]); };
    for (int p = 0; p + 1 < cut_count; ++p) {
      const double a = cuts[p], b = cuts[p + 1], h = b - a;
      const double at[3] = {a, 0.5 * (a + b), b};
      for (int e = 0; e < 3; ++e) path.evaluate(at[e], q, d1[e], d2[e]);
      for (Eigen::Index j = 0; j < n; ++j) {
        double acc[3];
        for (int e = 0; e < 3; ++e) acc[e] = d1[e][j] * u[i] + d2[e][j] * X(at[e]);
        const double ends =
            std::max(std::max(std::abs(acc[0]) / a_max[j] - 1.0, std::abs(acc[2]) / a_max[j] - 1.0),
                     std::max(std::abs(d1[0][j]) * std::sqrt(std::max(X(a), 0.0)),
                              std::abs(d1[2][j]) * std::sqrt(std::max(X(b), 0.0))) /
                             v_max[j] -
                         1.0);
        excess = std::max(excess, ends);
        // q̈_j = A + Bτ + Cτ² on the piece (exact through three points)
        const double A = acc[0];
        const double C = 2.0 * (acc[0] - 2.0 * acc[1] + acc[2]) / (h * h);
        const double B = (acc[2] - acc[0]) / h - C * h;
        if (C != 0.0) {
          const double vertex = -B / (2.0 * C);
          if (vertex > 0.0 && vertex < h)
            excess = std::max(excess, std::abs(A + vertex * (B + C * vertex)) / a_max[j] - 1.0);
        }
        std::array<double, 2> roots{};
        const int count = topp_quadratic_roots(A, B, C, h, roots);
        for (int r = 0; r < count; ++r)
          excess = std::max(excess, speed_excess(a + roots[r], X(a + roots[r])));
      }
    }
  }
  return excess;
}

double topp_now_us(bool cpu) { return 1e6 * benchmark_seconds(cpu); }

/// The worst relative excess of every segment's profiles over their limits, at the analytic
/// extrema of every phase (velocity and acceleration) and over every phase's jerk.
double jerk_waypoint_excess(const JerkWaypointTrajectory& trajectory) {
  double worst = -1.0;
  for (int k = 0; k < trajectory.segments(); ++k) {
    const JerkLimitedGenerator& g = trajectory.segment(k);
    for (int j = 0; j < g.dofs(); ++j) {
      const JerkLimits& l = g.limits(j);
      const JerkProfile& p = g.profile(j);
      const JerkExtrema e = p.extrema();
      worst = std::max({worst, std::max(-e.v_min, e.v_max) / l.velocity - 1.0,
                        std::max(-e.a_min, e.a_max) / l.acceleration - 1.0});
      for (int phase = 0; phase < p.size(); ++phase)
        worst = std::max(worst, std::abs(p.jerk(phase)) / l.jerk - 1.0);
    }
  }
  return worst;
}

}  // namespace

ToppCase random_topp_case(Random& rng, int dofs) {
  ToppCase c;
  const int count = static_cast<int>(uniform_integer(rng, 5, 8));
  Eigen::VectorXd q(dofs);
  for (int j = 0; j < dofs; ++j) q[j] = uniform(rng, -2.0, 2.0);
  c.waypoints.push_back(q);
  for (int k = 1; k < count; ++k) {
    for (int j = 0; j < dofs; ++j) q[j] += uniform(rng, -1.0, 1.0);
    c.waypoints.push_back(q);
  }
  c.max_velocity.resize(dofs);
  c.max_acceleration.resize(dofs);
  for (int j = 0; j < dofs; ++j) {
    c.max_velocity[j] = topp_log_uniform(rng, 0.5, 3.0);
    c.max_acceleration[j] = topp_log_uniform(rng, 1.0, 15.0);
  }
  return c;
}

ToppValidationResult run_topp_validation(const ToppValidationOptions& options) {
  check_fields(options);
  ToppValidationResult r;
  r.dofs = options.dofs;
  r.grid_intervals = options.grid_intervals;
  r.allocations_counted = static_cast<bool>(options.allocation_count);
  Random rng(options.seed);
  ToppOptions topp_options;
  topp_options.grid_intervals = options.grid_intervals;
  ToppOptions fine_options;
  fine_options.grid_intervals = 4 * options.grid_intervals;
  std::vector<double> times;
  times.reserve(static_cast<std::size_t>(options.paths));
  TrajectorySample sample(options.dofs);
  double reference_ms = 0.0, longer_sum = 0.0, jerk_topp_sum = 0.0, jerk_stop_sum = 0.0;
  long newton_steps = 0;
  const auto note = [&r](const std::string& what) {
    if (r.first_failure.empty()) r.first_failure = what;
  };
  for (int k = 0; k < options.paths; ++k) {
    if (k % 100 == 0) {
      if (options.stop && options.stop()) {
        r.interrupted = true;
        break;
      }
      if (options.progress) options.progress(k, options.paths);
    }
    const ToppCase c = random_topp_case(rng, options.dofs);
    const JointPath path(c.waypoints);
    const double t0 = topp_now_us(options.thread_cpu_clock);
    const TimeOptimalPath topp(path, c.max_velocity, c.max_acceleration, topp_options);
    times.push_back(topp_now_us(options.thread_cpu_clock) - t0);
    ++r.paths;
    if (options.each_path) options.each_path(k, c, topp, times.back());
    if (!topp.solved()) {
      ++r.failures;
      note("path " + std::to_string(k) + ": not solved");
      continue;
    }
    r.worst_grid_excess =
        std::max(r.worst_grid_excess, topp_grid_excess(path, c.max_velocity, c.max_acceleration,
                                                       topp.grid(), topp.squared_speeds()));
    r.worst_excess = std::max(r.worst_excess, topp_analytic_excess(topp));
    if (r.allocations_counted) {
      const std::uint64_t before = options.allocation_count();
      double sink = 0.0;
      for (int m = 0; m <= 50; ++m) {
        topp.at(topp.duration() * m / 50.0, sample);
        sink += sample.velocity[0];
      }
      r.sampling_allocations += options.allocation_count() - before;
      if (!std::isfinite(sink)) note("path " + std::to_string(k) + ": a sample is not finite");
    }
    if (k < options.reference_paths) {
      const double t1 = steady_seconds();
      const ToppReference ref =
          solve_topp_reference(path, c.max_velocity, c.max_acceleration, topp.grid(),
                               options.reference_from_topp ? &topp.squared_speeds() : nullptr);
      newton_steps += ref.newton_steps;
      reference_ms += 1e3 * (steady_seconds() - t1);
      ++r.reference_paths;
      if (!ref.solved()) {
        ++r.reference_failures;
        note("path " + std::to_string(k) + ": reference QP " + to_string(ref.status));
      } else {
        const double change = (topp.duration() - ref.duration) / ref.duration;
        r.worst_longer = std::max(r.worst_longer, change);
        r.worst_shorter = std::max(r.worst_shorter, -change);
        longer_sum += change;
        if (change > 1e-6) ++r.longer_paths;
        if (change < -1e-9)
          note("path " + std::to_string(k) + ": shorter than the reference by " +
               number_text(-change) + " (relative)");
      }
    }
    if (k < options.jerk_paths) {
      ++r.jerk_paths;
      try {
        const Eigen::VectorXd jerk = 10.0 * c.max_acceleration;
        const JerkWaypointTrajectory moving(topp, jerk);
        JerkWaypointOptions stop_options;
        stop_options.velocity_share = 0.0;
        const JerkWaypointTrajectory stopping(topp, jerk, stop_options);
        r.jerk_worst_excess = std::max(
            {r.jerk_worst_excess, jerk_waypoint_excess(moving), jerk_waypoint_excess(stopping)});
        r.jerk_reduced_waypoints += moving.reduced_waypoints();
        r.jerk_stopped_waypoints += moving.stopped_waypoints();
        jerk_topp_sum += moving.duration() / topp.duration();
        const double over_stops = moving.duration() / stopping.duration();
        jerk_stop_sum += over_stops;
        r.jerk_worst_over_stops = std::max(r.jerk_worst_over_stops, over_stops);
      } catch (const Error& e) {
        ++r.jerk_failures;
        note("path " + std::to_string(k) + ": jerk waypoints: " + e.what());
      }
    }
    if (k < options.refinement_paths) {
      const TimeOptimalPath fine(path, c.max_velocity, c.max_acceleration, fine_options);
      ++r.refinement_paths;
      if (!fine.solved())
        note("path " + std::to_string(k) + ": not solved on the finer grid");
      else
        r.worst_refinement_change =
            std::max(r.worst_refinement_change,
                     std::abs(topp.duration() - fine.duration()) / fine.duration());
    }
  }
  if (options.progress) options.progress(r.paths, options.paths);
  if (!times.empty()) {
    double sum = 0.0;
    for (const double t : times) sum += t;
    r.mean_us = sum / static_cast<double>(times.size());
    std::sort(times.begin(), times.end());
    r.median_us = nearest_rank(times, 0.5);
    r.p95_us = nearest_rank(times, 0.95);
    r.max_us = times.back();
  }
  if (r.jerk_paths > r.jerk_failures) {
    r.jerk_mean_over_topp = jerk_topp_sum / (r.jerk_paths - r.jerk_failures);
    r.jerk_mean_over_stops = jerk_stop_sum / (r.jerk_paths - r.jerk_failures);
  }
  if (r.reference_paths > 0) {
    r.reference_mean_ms = reference_ms / r.reference_paths;
    r.reference_mean_newton = static_cast<double>(newton_steps) / r.reference_paths;
    r.mean_longer = longer_sum / (r.reference_paths - r.reference_failures);
  }
  return r;
}

}  // namespace mjarm
