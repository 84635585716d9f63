#include "mjarm/trajectory/otg/fixed_time.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/trajectory/otg/min_time.hpp"
#include "mjarm/trajectory/otg/reach.hpp"

namespace mjarm {

namespace {

/// One phase of a blend: the phase slots of both profiles it lies in, and its duration.
struct BlendPhase {
  int h, l;
  double duration;
};

/// The first and last slots of nonzero duration of @p p (first > last when there is none).
struct SlotRange {
  int first = JerkPhases::kSize, last = -1;
  explicit SlotRange(const JerkPhases& p) noexcept {
    for (int i = 0; i < JerkPhases::kSize; ++i)
      if (p.duration[i] > 0.0) {
        first = std::min(first, i);
        last = i;
      }
  }
};

/// Walks the phases of nonzero duration of two profiles together, from their start
/// (@p step = +1) or back from their end (−1), each merged phase lasting the smaller of what
/// remains of the two current phases: each profile's own phases are reproduced to the round-off
/// of their own lengths.
struct BlendWalk {
  const JerkPhases* hi;
  const JerkPhases* lo;
  int step;
  int h = 0, l = 0;            ///< current slots (out of range when a profile has ended)
  int last_h = 0, last_l = 0;  ///< the slots of the last phases in this direction
  double rest_h = 0.0, rest_l = 0.0;

  BlendWalk(const JerkPhases& a, const JerkPhases& b, const SlotRange& ra, const SlotRange& rb,
            int direction) noexcept
      : hi(&a), lo(&b), step(direction) {
    h = direction > 0 ? ra.first : ra.last;
    l = direction > 0 ? rb.first : rb.last;
    last_h = direction > 0 ? ra.last : ra.first;
    last_l = direction > 0 ? rb.last : rb.first;
    if (!valid(h)) h = last_h = -2;  // a profile of no phase: ended at once
    if (!valid(l)) l = last_l = -2;
    rest_h = valid(h) ? hi->duration[h] : 0.0;
    rest_l = valid(l) ? lo->duration[l] : 0.0;
  }
  static bool valid(int i) noexcept { return i >= 0 && i < JerkPhases::kSize; }
  int advance(const JerkPhases& p, int i) const noexcept {
    while (valid(i) && !(p.duration[i] > 0.0)) i += step;
    return i;
  }
  bool done() const noexcept { return !valid(h) && !valid(l); }
  /// The next merged phase; the walk moves past it. The last phases of both end together (the
  /// profiles' totals differ by round-off only).
  BlendPhase next() noexcept {
    BlendPhase b{h, l, 0.0};
    const bool vh = valid(h), vl = valid(l);
    if (h == last_h && l == last_l && vh && vl) {
      b.duration = std::max(rest_h, rest_l);
      h = l = step > 0 ? JerkPhases::kSize : -1;
      return b;
    }
    b.duration = vh && vl ? std::min(rest_h, rest_l) : (vh ? rest_h : rest_l);
    const bool end_h = vh && (!vl || rest_h <= rest_l), end_l = vl && (!vh || rest_l <= rest_h);
    if (vh) rest_h = end_h ? 0.0 : rest_h - b.duration;
    if (vl) rest_l = end_l ? 0.0 : rest_l - b.duration;
    if (end_h) {
      h = advance(*hi, h + step);
      rest_h = valid(h) ? hi->duration[h] : 0.0;
    }
    if (end_l) {
      l = advance(*lo, l + step);
      rest_l = valid(l) ? lo->duration[l] : 0.0;
    }
    return b;
  }
};

/// The pair of slots (@p mh of @p hi, @p ml of @p lo) whose phases both have no jerk and overlap
/// longest in time; false when no such pair overlaps.
bool longest_calm_overlap(const JerkPhases& hi, const JerkPhases& lo, int& mh, int& ml) noexcept {
  double start_h[JerkPhases::kSize], start_l[JerkPhases::kSize];
  double th = 0.0, tl = 0.0;
  for (int i = 0; i < JerkPhases::kSize; ++i) {
    start_h[i] = th;
    start_l[i] = tl;
    th += hi.duration[i];
    tl += lo.duration[i];
  }
  double best = 0.0;
  for (int i = 1; i < JerkPhases::kSize; i += 2) {  // the slots without jerk: 1, 3, 5
    if (hi.jerk[i] != 0.0 || !(hi.duration[i] > 0.0)) continue;
    for (int k = 1; k < JerkPhases::kSize; k += 2) {
      if (lo.jerk[k] != 0.0 || !(lo.duration[k] > 0.0)) continue;
      const double overlap = std::min(start_h[i] + hi.duration[i], start_l[k] + lo.duration[k]) -
                             std::max(start_h[i], start_l[k]);
      if (overlap > best) {
        best = overlap;
        mh = i;
        ml = k;
      }
    }
  }
  return best > 0.0;
}

/// Appends λ·@p hi + (1 − λ)·@p lo, both of duration @p duration, phase by phase over the union
/// of their switching times: the phases before the longest overlap of two phases without jerk
/// (holds, cruises) merged from the start, those after it back from the end, and the overlap
/// lasting what is left. The two profiles' totals agree with the duration only to its round-off;
/// merged from one end only, that difference would lengthen a ramp at the other end, and times
/// the jerk it becomes an acceleration error (10⁻⁹ after holds of hours at a jerk of 10⁴). In an
/// overlap without jerk it only moves the velocity by a·δ.
/// The phases of a run of slots (ramps and holds before or after a cruise), in walking order.
struct Run {
  double duration[3];
  double jerk[3];
  int size = 0;
  /// Slots @p first, first + step, first + 2·step of @p p, those of nonzero duration.
  Run(const JerkPhases& p, int first, int step) noexcept {
    for (int k = 0, i = first; k < 3; ++k, i += step)
      if (p.duration[i] > 0.0) {
        duration[size] = p.duration[i];
        jerk[size++] = p.jerk[i];
      }
  }
};

/// Merges the runs @p a and @p b (blended with weights λ and 1 − λ) by remainders, as BlendWalk:
/// a run that has ended is in its cruise (no jerk). Writes at most 5 phases; returns their number
/// and their total duration in @p total.
int merge_runs(const Run& a, const Run& b, double lambda, double* duration, double* jerk,
               double& total) noexcept {
  int i = 0, k = 0, n = 0;
  double ra = a.size > 0 ? a.duration[0] : 0.0, rb = b.size > 0 ? b.duration[0] : 0.0;
  total = 0.0;
  while (i < a.size || k < b.size) {
    const bool va = i < a.size, vb = k < b.size;
    const bool end_a = va && (!vb || ra <= rb), end_b = vb && (!va || rb <= ra);
    const double dt = end_a ? ra : rb;
    duration[n] = dt;
    jerk[n++] = lambda * (va ? a.jerk[i] : 0.0) + (1.0 - lambda) * (vb ? b.jerk[k] : 0.0);
    total += dt;
    if (end_a) {
      ra = ++i < a.size ? a.duration[i] : 0.0;
    } else if (va) {
      ra -= dt;
    }
    if (end_b) {
      rb = ++k < b.size ? b.duration[k] : 0.0;
    } else if (vb) {
      rb -= dt;
    }
  }
  return n;
}

bool append_blend(const JerkPhases& hi, const JerkPhases& lo, double lambda, double duration,
                  JerkProfile& profile) noexcept {
  constexpr int c = JerkPhases::kCruise;
  if (hi.duration[c] > 0.0 && lo.duration[c] > 0.0 && hi.jerk[c] == 0.0 && lo.jerk[c] == 0.0) {
    // the common case, two cruise profiles: the runs before the cruises merged from the start,
    // those after them back from the end, the overlap of the cruises (when they overlap)
    // lasting what is left
    const Run before_h(hi, 0, 1), before_l(lo, 0, 1), after_h(hi, 6, -1), after_l(lo, 6, -1);
    double front_d[6], front_j[6], back_d[6], back_j[6], t_front = 0.0, t_back = 0.0;
    const int nf = merge_runs(before_h, before_l, lambda, front_d, front_j, t_front);
    const int nb = merge_runs(after_h, after_l, lambda, back_d, back_j, t_back);
    const double middle = duration - t_front - t_back;
    if (middle >= 0.0) {
      for (int k = 0; k < nf; ++k)
        if (!profile.append(front_j[k], front_d[k])) return false;
      if (middle > 0.0 && !profile.append_cruise(middle)) return false;
      for (int k = nb - 1; k >= 0; --k)
        if (!profile.append(back_j[k], back_d[k])) return false;
      return true;
    }
  }
  const auto jerk = [&](const BlendPhase& b) {
    const double jh = BlendWalk::valid(b.h) ? hi.jerk[b.h] : 0.0;
    const double jl = BlendWalk::valid(b.l) ? lo.jerk[b.l] : 0.0;
    return lambda * jh + (1.0 - lambda) * jl;
  };
  const auto add = [&](const BlendPhase& b) {
    if (!(b.duration > 0.0)) return true;
    // both cruising: the plateau at zero acceleration (see JerkPhases)
    const bool cruise = b.h == JerkPhases::kCruise && b.l == JerkPhases::kCruise &&
                        hi.jerk[b.h] == 0.0 && lo.jerk[b.l] == 0.0;
    return cruise ? profile.append_cruise(b.duration) : profile.append(jerk(b), b.duration);
  };
  int mh = -1, ml = -1;
  const bool calm = longest_calm_overlap(hi, lo, mh, ml);
  constexpr int kMax = 2 * JerkPhases::kSize;
  BlendPhase back[kMax];
  int nb = 0;
  double t_back = 0.0;
  const SlotRange rh(hi), rl(lo);
  BlendWalk backward(hi, lo, rh, rl, -1);
  while (calm && !backward.done() && nb < kMax && !(backward.h == mh && backward.l == ml)) {
    back[nb] = backward.next();
    t_back += back[nb++].duration;
  }
  const int first = profile.size();
  double t_front = 0.0;
  BlendWalk forward(hi, lo, rh, rl, +1);
  if (calm && backward.h == mh && backward.l == ml) {
    while (!forward.done() && !(forward.h == mh && forward.l == ml)) {
      const BlendPhase b = forward.next();
      if (!add(b)) return false;
      t_front += b.duration;
    }
    if (forward.h == mh && forward.l == ml) {
      const BlendPhase middle{mh, ml, std::max(duration - t_front - t_back, 0.0)};
      if (!add(middle)) return false;
      for (int k = nb - 1; k >= 0; --k)
        if (!add(back[k])) return false;
      return true;
    }
  }
  // no such overlap (profiles of ramps only: short), or switching times equal to round-off seen
  // in another order from each end: the merge from the start
  profile.truncate(first);
  BlendWalk all(hi, lo, rh, rl, +1);
  while (!all.done())
    if (!add(all.next())) return false;
  return true;
}

}  // namespace

bool append_blended_profile(const JerkReach& reach, const KinematicState& target, double duration,
                            JerkProfile& profile) noexcept {
  if (!reach_contains(reach, target.p)) return false;
  const double span = reach.p_max - reach.p_min;
  const double lambda = span > 0.0 ? std::clamp((target.p - reach.p_min) / span, 0.0, 1.0) : 1.0;
  if (duration > 0.0 && !append_blend(reach.highest, reach.lowest, lambda, duration, profile))
    return false;
  // the limits hold by construction (a blend of two motions within them); the end is checked,
  // the position relative to the positions the blend is made of (see JerkTolerance)
  const KinematicState e = profile.end();
  const double scale_p =
      std::max({1.0, std::abs(target.p), std::abs(reach.p_min), std::abs(reach.p_max)});
  const auto near = [](double x, double y, double scale) {
    return std::abs(x - y) <= JerkTolerance::kTarget * std::max(1.0, scale);
  };
  return near(e.p, target.p, scale_p) && near(e.v, target.v, std::abs(target.v)) &&
         near(e.a, target.a, std::abs(target.a));
}

bool append_fixed_time_profile(const KinematicState& start, const KinematicState& target,
                               const JerkLimits& limits, double duration,
                               JerkProfile& profile) noexcept {
  JerkReach reach;
  return reach_range(start, target.v, target.a, limits, duration, reach) &&
         append_blended_profile(reach, target, duration, profile);
}

bool fixed_time_profile(const KinematicState& start, const KinematicState& target,
                        const JerkLimits& limits, double duration, JerkProfile& profile) noexcept {
  profile.reset(start);
  return append_fixed_time_profile(start, target, limits, duration, profile);
}

}  // namespace mjarm
