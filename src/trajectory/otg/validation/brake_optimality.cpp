#include "mjarm/trajectory/otg/validation/brake_optimality.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "mjarm/random.hpp"
#include "mjarm/trajectory/otg/brake.hpp"
#include "mjarm/trajectory/otg/generator.hpp"
#include "mjarm/trajectory/otg/min_time.hpp"
#include "mjarm/trajectory/otg/validation/structure_search.hpp"

namespace mjarm {

namespace {

constexpr double kRelative = 1e-9;  // durations compared to this, relative

/// Draws limits (the ranges of `mjarm bench otg`), a start that is not startable and a target
/// that is reachable.
struct BrakeCaseSampler {
  Random rng;
  explicit BrakeCaseSampler(std::uint64_t seed) : rng(seed) {}

  double unit() noexcept { return uniform(rng, -1.0, 1.0); }
  double log_uniform(double lo, double hi) { return lo * std::pow(hi / lo, uniform(rng)); }

  JerkLimits limits() {
    return {log_uniform(0.2, 4.0), log_uniform(0.3, 8.0), log_uniform(0.5, 40.0)};
  }
  KinematicState start(const JerkLimits& l) {
    for (;;) {
      const KinematicState s{3.0 * unit(), 1.6 * l.velocity * unit(),
                             1.6 * l.acceleration * unit()};
      if (!is_startable(s, l)) return s;
    }
  }
  KinematicState target(const JerkLimits& l) {
    for (;;) {
      KinematicState s{3.0 * unit(), l.velocity * unit(), l.acceleration * unit()};
      if (uniform(rng) < 0.2) s.v = s.a = 0.0;
      if (is_reachable(s, l)) return s;
    }
  }
};

std::string describe_brake_case(const char* what, const KinematicState& s, const KinematicState& t,
                                const JerkLimits& l) {
  char buffer[400];
  std::snprintf(buffer, sizeof buffer,
                "%s: limits (v %.17g, a %.17g, j %.17g), start (%.17g, %.17g, %.17g), target "
                "(%.17g, %.17g, %.17g)",
                what, l.velocity, l.acceleration, l.jerk, s.p, s.v, s.a, t.p, t.v, t.a);
  return buffer;
}

/// A brake and step 1 from its end, in @p profile: their total, or +∞ without a profile.
double brake_and_step1(const KinematicState& target, const JerkLimits& l,
                       const JerkProfile& profile, JerkBlock& block) {
  if (!min_time_profile(profile.end(), target, l, block))
    return std::numeric_limits<double>::infinity();
  return profile.duration() + block.t_min;
}

/// The shortest member of the brake family of @p s: a scan of @p members, half uniform in the end
/// acceleration, half in the settled velocity.
double family_scan(const KinematicState& s, const KinematicState& t, const JerkLimits& l,
                   int members) {
  const BrakeFamily family = brake_family(s, l);
  JerkProfile profile;
  JerkBlock block;
  if (family.side == 0.0) {
    profile.reset(s);
    append_brake(s, l, profile);
    return brake_and_step1(t, l, profile, block);
  }
  const double V = l.velocity, J = l.jerk;
  const double lo = -std::sqrt(2.0 * J * std::max(V - family.lowest, 0.0));
  const double hi = -std::sqrt(2.0 * J * std::max(V - family.highest, 0.0));
  const int half = std::max(members / 2, 2);
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 2 * half; ++k) {
    const double u = static_cast<double>(k % half) / (half - 1);
    const double a_end = lo + (hi - lo) * u;
    const double settled = k < half ? V - 0.5 * a_end * a_end / J
                                    : family.lowest + (family.highest - family.lowest) * u;
    profile.reset(s);
    append_brake_member(s, l, settled, profile);
    best = std::min(best, brake_and_step1(t, l, profile, block));
  }
  return best;
}

void count(BrakeDurationFigures& figures, double duration, double best) {
  figures.worst_ratio = std::max(figures.worst_ratio, duration / best);
  if (duration > best + kRelative * std::max(1.0, best)) ++figures.longer;
  if (duration < best - kRelative * std::max(1.0, best)) ++figures.shorter;
}

/// Whether the brake phases of @p p (the first @p phases, from start @p s) take the brake's
/// order and end startable: an acceleration beyond its limit does not grow; apart from its
/// forced ramp, the jerk goes −s·j, 0 (at −s·a_max), +s·j on the violation's side s; s·v does
/// not pass below min(−v_max, s·v₀).
bool brake_in_order(const JerkProfile& p, int phases, const KinematicState& s,
                    const JerkLimits& l) {
  const double A = l.acceleration * (1.0 + 1e-12);
  const double side = brake_family(s, l).side;
  const double floor = std::min(-l.velocity, side * s.v) * (1.0 + 1e-12);
  int stage = 0;
  double excess = std::max(std::abs(s.a) - A, 0.0);
  for (int k = 0; k < phases; ++k) {
    const JerkSample x = p.at(p.duration_until(k));
    const JerkSample y = p.at(p.duration_until(k + 1));
    const double e = std::max(std::abs(y.a) - A, 0.0);
    if (e > excess) return false;
    excess = e;
    if (std::abs(x.a) > A || side == 0.0) continue;  // the forced ramp
    const double j = side * p.jerk(k);
    const int kind = j < 0.0 ? 0 : (j > 0.0 ? 2 : 1);
    if (kind < stage || side * y.v < floor) return false;
    stage = kind;
  }
  const JerkSample b = p.at(p.duration_until(phases));
  return is_startable({b.p, b.v, b.a}, l);
}

}  // namespace

BrakeOptimalityResult run_brake_optimality(const BrakeOptimalityOptions& options) {
  check_fields(options);
  BrakeOptimalityResult r;
  r.dofs = options.dofs;
  BrakeCaseSampler sampler(options.seed);
  const std::size_t n = static_cast<std::size_t>(options.dofs);
  std::vector<JerkLimits> limits(n);
  std::vector<KinematicState> start(n), target(n);
  JerkProfile standard;
  JerkBlock block;
  double search_ms = 0.0;
  const auto fail = [&](std::string what) {
    if (r.first_failure.empty()) r.first_failure = std::move(what);
  };
  const int total = options.cases * options.dofs;
  for (int c = 0; c < options.cases; ++c) {
    if (options.stop && options.stop()) {
      r.interrupted = true;
      break;
    }
    for (std::size_t i = 0; i < n; ++i) {
      limits[i] = sampler.limits();
      start[i] = sampler.start(limits[i]);
      target[i] = sampler.target(limits[i]);
    }
    JerkLimitedGenerator otg(limits);
    const OtgResult res = otg.calculate(start, target);
    ++r.cases;
    const bool ok = res.status == OtgStatus::working || res.status == OtgStatus::finished;
    if (!ok) {
      ++r.failures;
      const int d = std::max(res.failed_dof, 0);
      fail(describe_brake_case(to_string(res.status), start[d], target[d], limits[d]));
    }
    for (std::size_t i = 0; i < n && ok; ++i) {
      const int d = static_cast<int>(i);
      const JerkLimits& l = limits[i];
      const KinematicState& s = start[i];
      const KinematicState& t = target[i];
      ++r.braking_dofs;
      const BrakeFamily family = brake_family(s, l);
      r.with_choice += family.side != 0.0 && family.highest > family.lowest ? 1 : 0;
      // the n-DoF result: limits after the brake, the brake in order, on target, one duration
      const JerkProfile& p = otg.profile(d);
      const JerkExtrema x = p.extrema(otg.brake_phases(d));
      double excess = std::max(std::max(-x.v_min, x.v_max) / l.velocity,
                               std::max(-x.a_min, x.a_max) / l.acceleration) -
                      1.0;
      for (int k = 0; k < p.size(); ++k)
        excess = std::max(excess, std::abs(p.jerk(k)) / l.jerk - 1.0);
      const KinematicState e = p.end();
      const double miss = std::max({std::abs(e.p - t.p), std::abs(e.v - t.v), std::abs(e.a - t.a)});
      const double sync = std::abs(p.duration() - res.duration);
      r.worst_limit_excess = std::max(r.worst_limit_excess, std::max(excess, 0.0));
      r.worst_target_error = std::max(r.worst_target_error, miss);
      r.worst_sync_error = std::max(r.worst_sync_error, sync);
      if (excess > 1e-9 || miss > 1e-8 || sync > 1e-9 * std::max(1.0, res.duration) ||
          !brake_in_order(p, otg.brake_phases(d), s, l)) {
        ++r.check_failures;
        fail(describe_brake_case("check", s, t, l));
      }
      // the DoF's own minimum with each brake, against the best of its family
      const double optimal = otg.brake_duration(d) + otg.block(d).t_min;
      standard.reset(s);
      append_brake(s, l, standard);
      const double with_standard = brake_and_step1(t, l, standard, block);
      const double best =
          std::min({family_scan(s, t, l, options.family_members), optimal, with_standard});
      count(r.standard, with_standard, best);
      count(r.optimal, optimal, best);
      if (optimal > best + kRelative * std::max(1.0, best))
        fail(describe_brake_case("longer than the family's best", s, t, l));
      if (r.structure_cases < options.structure_cases) {
        ++r.structure_cases;
        StructureSearchOptions search;
        search.seeds = options.structure_seeds;
        const auto t0 = std::chrono::steady_clock::now();
        const StructureSearchResult found = structure_search_min_time(s, t, l, search);
        search_ms +=
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count();
        if (found.status != StructureSearchStatus::found) {
          ++r.structure_not_found;
          fail(describe_brake_case("structure search found no motion", s, t, l));
        } else {
          count(r.structure_standard, with_standard, found.duration);
          count(r.structure_optimal, optimal, found.duration);
          if (optimal > found.duration + kRelative * std::max(1.0, found.duration) ||
              optimal < found.duration - kRelative * std::max(1.0, found.duration))
            if (r.first_structure_mismatch.empty())
              r.first_structure_mismatch = describe_brake_case("structure search differs", s, t, l);
        }
      }
    }
    if (options.progress) options.progress(r.cases * options.dofs, total);
  }
  r.structure_mean_ms = r.structure_cases > 0 ? search_ms / r.structure_cases : 0.0;
  return r;
}

}  // namespace mjarm
