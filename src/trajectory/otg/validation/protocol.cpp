#include "mjarm/trajectory/otg/validation/protocol.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "mjarm/benchmark_timing.hpp"
#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/random.hpp"
#include "mjarm/trajectory/otg/brake.hpp"
#include "mjarm/trajectory/otg/fixed_time.hpp"
#include "mjarm/trajectory/otg/generator.hpp"
#include "mjarm/trajectory/otg/min_time.hpp"
#include "mjarm/trajectory/otg/validation/grid_reference.hpp"
#include "mjarm/trajectory/otg/validation/structure_search.hpp"

namespace mjarm {

namespace {

/// Draws limits, a start and a target for one DoF.
struct OtgCaseSampler {
  Random rng;

  explicit OtgCaseSampler(std::uint64_t seed) : rng(seed) {}

  double unit() noexcept { return uniform(rng, -1.0, 1.0); }
  double share() noexcept { return uniform(rng); }
  double log_uniform(double lo, double hi) { return lo * std::pow(hi / lo, share()); }

  JerkLimits limits() {
    return {log_uniform(0.2, 4.0), log_uniform(0.3, 8.0), log_uniform(0.5, 40.0)};
  }

  KinematicState target(const JerkLimits& l) {
    for (;;) {
      KinematicState s{3.0 * unit(), l.velocity * unit(), l.acceleration * unit()};
      const double kind = share();
      if (kind < 0.2)
        s.v = s.a = 0.0;  // at rest
      else if (kind < 0.3)
        s.a = 0.0;
      if (is_reachable(s, l)) return s;
    }
  }

  KinematicState start(const JerkLimits& l, bool beyond) {
    for (;;) {
      const double scale = beyond ? 1.6 : 1.0;
      KinematicState s{3.0 * unit(), scale * l.velocity * unit(), scale * l.acceleration * unit()};
      if (!beyond && share() < 0.2) s.v = s.a = 0.0;
      if (beyond != is_startable(s, l)) return s;
    }
  }
};

/// Worst relative excess of @p profile over @p limits from phase @p first on (0 when within).
double limit_excess(const JerkProfile& profile, const JerkLimits& limits, int first) {
  const JerkExtrema e = profile.extrema(first);
  double worst = 0.0;
  worst = std::max(worst, std::max(-e.v_min, e.v_max) / limits.velocity - 1.0);
  worst = std::max(worst, std::max(-e.a_min, e.a_max) / limits.acceleration - 1.0);
  for (int i = first; i < profile.size(); ++i)
    worst = std::max(worst, std::abs(profile.jerk(i)) / limits.jerk - 1.0);
  return worst;
}

std::string describe_otg_case(const char* what, int dof, const KinematicState& s,
                              const KinematicState& t, const JerkLimits& l) {
  char buffer[400];
  std::snprintf(buffer, sizeof buffer,
                "%s: DoF %d, limits (v %.17g, a %.17g, j %.17g), start (%.17g, %.17g, %.17g), "
                "target (%.17g, %.17g, %.17g)",
                what, dof, l.velocity, l.acceleration, l.jerk, s.p, s.v, s.a, t.p, t.v, t.a);
  return buffer;
}

/// Now in µs on the steady clock or, when @p cpu, the calling thread's CPU clock.
double otg_now_us(bool cpu) noexcept { return 1e6 * benchmark_seconds(cpu); }

/// Durations equal to 1e-9 relative (absolute below 1 s).
bool near_duration(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, b); }

/// Whether the structure search @p search misses something of @p block: t_min (its shortest
/// motion is longer) or a blocked interval's end (not among its extremal durations).
bool structure_search_misses(const StructureSearchResult& search, const JerkBlock& block) {
  if (search.status != StructureSearchStatus::found ||
      search.duration > block.t_min + 1e-9 * std::max(1.0, block.t_min))
    return true;
  for (int k = 0; k < block.blocked_count; ++k)
    for (const double end : {block.blocked[k].lower, block.blocked[k].upper})
      if (std::none_of(search.durations.begin(), search.durations.end(),
                       [&](double d) { return near_duration(d, end); }))
        return true;
  return false;
}

/// The structure-search checks of one case whose generator block is @p block (see
/// OtgValidationResult); @p search_ms accumulates the search time. A search that misses t_min or
/// an interval's end is run again with four times the seeds (other ones) before it counts.
void check_against_structures(const KinematicState& s, const KinematicState& t, const JerkLimits& l,
                              const JerkBlock& block, int seeds, OtgValidationResult& r,
                              double& search_ms) {
  if (seeds < 1) return;
  const double t0 = otg_now_us(false);
  const auto seed = static_cast<std::uint64_t>(r.structure_cases);
  StructureSearchResult search = structure_search_min_time(s, t, l, {seeds, seed});
  if (structure_search_misses(search, block)) {
    ++r.structure_retries;
    StructureSearchResult again = structure_search_min_time(s, t, l, {4 * seeds, seed + 1000003});
    // every solution of either run is a motion: the union of what they found
    if (again.status == StructureSearchStatus::found &&
        (search.status != StructureSearchStatus::found || again.duration < search.duration)) {
      search.status = again.status;
      search.duration = again.duration;
      search.best = again.best;
    }
    for (const double d : again.durations) search.durations.push_back(d);
    for (const double d : again.feasible_durations) search.feasible_durations.push_back(d);
  }
  search_ms += 1e-3 * (otg_now_us(false) - t0);
  ++r.structure_cases;
  const auto fail = [&](const char* what) {
    if (r.first_structure_failure.empty())
      r.first_structure_failure = describe_otg_case(what, 0, s, t, l);
  };
  const auto tolerance = [](double d) { return 1e-9 * std::max(1.0, d); };
  if (search.status != StructureSearchStatus::found) {
    ++r.structure_not_found;
    fail("structure search found no motion");
  } else if (search.duration < block.t_min - tolerance(block.t_min)) {
    ++r.structure_shorter;
    fail("structure search beats t_min");
  } else if (search.duration > block.t_min + tolerance(block.t_min)) {
    ++r.structure_longer;
    fail("structure search longer than t_min");
  }
  bool inside = false;
  for (int k = 0; k < block.blocked_count; ++k) {
    const JerkInterval in = block.blocked[k];
    for (const double d : search.feasible_durations)
      if (d > in.lower + tolerance(in.lower) && d < in.upper - tolerance(in.upper)) inside = true;
    for (const double end : {in.lower, in.upper}) {
      ++r.structure_blocked_ends;
      const bool found = std::any_of(search.durations.begin(), search.durations.end(),
                                     [&](double d) { return near_duration(d, end); });
      if (!found) {
        ++r.structure_blocked_ends_missing;
        fail("blocked interval end not found by the structure search");
      }
    }
  }
  if (inside) {
    ++r.structure_inside_blocked;
    fail("structure search motion inside a blocked interval");
  }
}

/// The one-DoF reference checks of one case (see OtgValidationResult).
void check_against_reference(OtgCaseSampler& sampler, int steps, int seeds, OtgValidationResult& r,
                             double& search_ms) {
  const JerkLimits l = sampler.limits();
  const KinematicState s = sampler.start(l, false);
  const KinematicState t = sampler.target(l);
  JerkBlock block;
  if (!min_time_profile(s, t, l, block)) return;  // counted by the main run's failures
  ++r.reference_cases;
  check_against_structures(s, t, l, block, seeds, r, search_ms);
  if (block.t_min <= 1e-9) return;
  bool beaten = false;
  for (const double f : {0.999, 0.99, 0.95, 0.8, 0.5})
    if (grid_motion_exists(s, t, l, f * block.t_min, steps)) beaten = true;
  if (beaten) {
    ++r.optimality_beaten;
    if (r.first_reference_failure.empty())
      r.first_reference_failure = describe_otg_case("beaten", 0, s, t, l);
  }
  // the other side needs a grid fine enough that its velocity margin (j·h²/8) is small
  const double above = 1.03 * block.t_min;
  const double h = above / steps;
  if (l.jerk * h * h / 8.0 <= 0.01 * l.velocity && !block.is_blocked(above) &&
      !grid_motion_exists(s, t, l, above, steps)) {
    ++r.reference_not_within;
    if (r.first_reference_failure.empty())
      r.first_reference_failure = describe_otg_case("no grid motion within 3 %", 0, s, t, l);
  }
  for (int k = 0; k < block.blocked_count; ++k) {
    ++r.blocked_checked;
    const double mid = 0.5 * (block.blocked[k].lower + block.blocked[k].upper);
    if (grid_motion_exists(s, t, l, mid, steps)) {
      ++r.blocked_mismatches;
      if (r.first_reference_failure.empty())
        r.first_reference_failure = describe_otg_case("blocked interval", 0, s, t, l);
    }
  }
}

/// The reference checks of one case with a blocked interval (see OtgValidationResult).
void check_blocked_against_reference(OtgCaseSampler& sampler, int steps, int seeds,
                                     OtgValidationResult& r, double& search_ms) {
  JerkLimits l;
  KinematicState s, t;
  JerkBlock block;
  for (int draw = 0;; ++draw) {
    if (draw == 100000) return;
    l = sampler.limits();
    s = sampler.start(l, false);
    t = sampler.target(l);
    if (min_time_profile(s, t, l, block) && block.blocked_count > 0) break;
  }
  ++r.blocked_cases;
  check_against_structures(s, t, l, block, seeds, r, search_ms);
  for (int k = 0; k < block.blocked_count; ++k) {
    const JerkInterval in = block.blocked[k];
    ++r.blocked_checked;
    if (grid_motion_exists(s, t, l, 0.5 * (in.lower + in.upper), steps)) {
      ++r.blocked_mismatches;
      if (r.first_reference_failure.empty())
        r.first_reference_failure = describe_otg_case("blocked interval", 0, s, t, l);
    }
    const double margin = 1e-2 * (in.upper - in.lower);
    for (const double outside : {in.lower - margin, in.upper + margin}) {
      if (block.is_blocked(outside)) continue;  // an interval of feasible durations too short
      JerkProfile p;
      if (!fixed_time_profile(s, t, l, outside, p)) {
        ++r.blocked_end_failures;
        if (r.first_reference_failure.empty())
          r.first_reference_failure = describe_otg_case("blocked interval end", 0, s, t, l);
        continue;
      }
      // a coarse grid misses motions close to an end: a grid three times finer decides
      const double h = outside / steps;
      if (l.jerk * h * h / 8.0 <= 0.01 * l.velocity &&
          !grid_motion_exists(s, t, l, outside, steps) &&
          !grid_motion_exists(s, t, l, outside, 3 * steps))
        ++r.blocked_end_not_confirmed;
    }
  }
}

}  // namespace

OtgValidationResult run_otg_validation(const OtgValidationOptions& options) {
  check_fields(options);
  OtgValidationResult r;
  r.cases = options.cases;
  r.dofs = options.dofs;
  r.allocations_counted = static_cast<bool>(options.allocation_count);
  OtgCaseSampler sampler(options.seed);
  const std::size_t n = static_cast<std::size_t>(options.dofs);
  std::vector<JerkLimits> limits(n);
  std::vector<KinematicState> start(n), target(n);
  std::vector<double> times;
  times.reserve(static_cast<std::size_t>(options.cases));
  double velocity_total_us = 0.0;
  double search_ms = 0.0;  // structure search time over the reference cases

  const int total = options.cases + options.reference_cases + options.reference_cases / 4;
  for (int c = 0; c < options.cases; ++c) {
    if (c % 1000 == 0 && options.stop && options.stop()) {
      r.interrupted = true;
      r.cases = c;
      break;
    }
    for (std::size_t i = 0; i < n; ++i) {
      limits[i] = sampler.limits();
      const JerkLimits& l = limits[i];
      const bool beyond = sampler.share() < options.brake_share;
      start[i] = sampler.start(l, beyond);
      target[i] = sampler.target(l);
      r.braking_dofs += beyond ? 1 : 0;
    }
    JerkLimitedGenerator otg(limits);
    // position interface
    const std::uint64_t a0 = r.allocations_counted ? options.allocation_count() : 0;
    const double t0 = otg_now_us(options.thread_cpu_clock);
    const OtgResult res = otg.calculate(start, target);
    const double t1 = otg_now_us(options.thread_cpu_clock);
    if (r.allocations_counted) r.allocations += options.allocation_count() - a0;
    times.push_back(t1 - t0);
    if (res.status != OtgStatus::working && res.status != OtgStatus::finished) {
      ++r.position_failures;
      if (r.first_failure.empty()) {
        const int d = std::max(res.failed_dof, 0);
        r.first_failure =
            describe_otg_case(to_string(res.status), d, start[d], target[d], limits[d]) +
            ", synchronized duration " + number_text(res.duration) + " s";
      }
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        const JerkProfile& p = otg.profile(static_cast<int>(i));
        const KinematicState e = p.end();
        const double err = std::max({std::abs(e.p - target[i].p), std::abs(e.v - target[i].v),
                                     std::abs(e.a - target[i].a)});
        const double excess = limit_excess(p, limits[i], otg.brake_phases(static_cast<int>(i)));
        const double sync = std::abs(p.duration() - res.duration);
        r.worst_target_error = std::max(r.worst_target_error, err);
        r.worst_limit_violation = std::max(r.worst_limit_violation, excess);
        r.worst_sync_error = std::max(r.worst_sync_error, sync);
        if (err > 1e-8 || excess > 1e-9 || sync > 1e-9 * std::max(1.0, res.duration)) {
          ++r.check_failures;
          if (r.first_failure.empty())
            r.first_failure =
                describe_otg_case("check", static_cast<int>(i), start[i], target[i], limits[i]);
        }
      }
      // the limiting DoF cannot be faster: no grid motion just below its share of the duration
      // (inside its blocked interval when the duration is an interval's end)
      if (c < options.reference_cases && res.limiting_dof >= 0) {
        const int d = res.limiting_dof;
        const double local = res.duration - otg.brake_duration(d);
        const JerkBlock& b = otg.block(d);
        double probe = local * (1.0 - 1e-3);
        for (int k = 0; k < b.blocked_count; ++k)
          if (std::abs(b.blocked[k].upper - local) <= 1e-9 * std::max(1.0, local))
            probe = std::max(probe, 0.5 * (b.blocked[k].lower + b.blocked[k].upper));
        if (local > 1e-6) {
          ++r.sync_reference_cases;
          const JerkSample s = otg.profile(d).at(otg.brake_duration(d));
          if (grid_motion_exists({s.p, s.v, s.a}, target[d], limits[d], probe,
                                 options.reference_steps)) {
            ++r.sync_mismatches;
            if (r.first_reference_failure.empty())
              r.first_reference_failure =
                  describe_otg_case("synchronization", d, start[d], target[d], limits[d]);
          }
        }
      }
    }
    // velocity interface (the same states; positions ignored)
    const std::uint64_t b0 = r.allocations_counted ? options.allocation_count() : 0;
    const double t2 = otg_now_us(options.thread_cpu_clock);
    const OtgResult vres = otg.calculate_velocity(start, target);
    const double t3 = otg_now_us(options.thread_cpu_clock);
    if (r.allocations_counted) r.allocations += options.allocation_count() - b0;
    velocity_total_us += t3 - t2;
    if (vres.status != OtgStatus::working && vres.status != OtgStatus::finished) {
      ++r.velocity_failures;
      if (r.first_velocity_failure.empty()) {
        const int d = std::max(vres.failed_dof, 0);
        r.first_velocity_failure =
            describe_otg_case(to_string(vres.status), d, start[d], target[d], limits[d]) +
            ", synchronized duration " + number_text(vres.duration) + " s, brake " +
            std::to_string(otg.brake_phases(d)) + " phases";
      }
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        const JerkProfile& p = otg.profile(static_cast<int>(i));
        const KinematicState e = p.end();
        const double err = std::max(std::abs(e.v - target[i].v), std::abs(e.a - target[i].a));
        const JerkExtrema x = p.extrema(otg.brake_phases(static_cast<int>(i)));
        const double excess = std::max(-x.a_min, x.a_max) / limits[i].acceleration - 1.0;
        r.worst_velocity_target_error = std::max(r.worst_velocity_target_error, err);
        r.worst_limit_violation = std::max(r.worst_limit_violation, excess);
        const double sync = std::abs(p.duration() - vres.duration);
        r.worst_sync_error = std::max(r.worst_sync_error, sync);
        if (err > 1e-8 || excess > 1e-9 || sync > 1e-9 * std::max(1.0, vres.duration)) {
          ++r.check_failures;
          if (r.first_failure.empty())
            r.first_failure = describe_otg_case("velocity check", static_cast<int>(i), start[i],
                                                target[i], limits[i]);
        }
      }
    }
    if (options.progress && (c % 1000 == 999 || c + 1 == options.cases))
      options.progress(c + 1, total);
  }
  for (int c = 0; c < options.reference_cases && !r.interrupted; ++c) {
    if (options.stop && options.stop()) {
      r.interrupted = true;
      break;
    }
    check_against_reference(sampler, options.reference_steps, options.structure_seeds, r,
                            search_ms);
    if (options.progress) options.progress(options.cases + c + 1, total);
  }
  for (int c = 0; c < options.reference_cases / 4 && !r.interrupted; ++c) {
    if (options.stop && options.stop()) {
      r.interrupted = true;
      break;
    }
    check_blocked_against_reference(sampler, options.reference_steps, options.structure_seeds, r,
                                    search_ms);
    if (options.progress) options.progress(options.cases + options.reference_cases + c + 1, total);
  }

  if (r.structure_cases > 0) r.structure_mean_ms = search_ms / r.structure_cases;
  if (times.empty()) return r;  // stopped before the first case: no figures
  double sum = 0.0;
  for (const double t : times) sum += t;
  r.mean_us = sum / static_cast<double>(times.size());
  std::sort(times.begin(), times.end());
  r.median_us = nearest_rank(times, 0.5);
  r.p99_us = nearest_rank(times, 0.99);
  r.max_us = times.back();
  r.velocity_mean_us = velocity_total_us / static_cast<double>(times.size());
  return r;
}

}  // namespace mjarm
