#include "mjarm/trajectory/otg/optimal_brake.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "mjarm/trajectory/otg/brake.hpp"
#include "mjarm/trajectory/otg/min_time.hpp"
#include "mjarm/trajectory/otg/velocity.hpp"

namespace mjarm {

namespace {

constexpr int kGrid = 8;                    // members tried before the refinement
constexpr double kRefineTolerance = 1e-11;  // of the end-acceleration range
constexpr double kEndProbe = 1e-7;          // a step inwards from an end, of that range
constexpr double kEdgeTolerance = 1e-11;    // an edge's bracket, of that range
constexpr double kCountTolerance = 1e-7;    // a change of the motions' number, of that range
constexpr int kMaxEdgesPerStep = 4;         // edges located between two grid members
constexpr int kMaxMembers = kGrid + 2 * 16;  // the grid and both sides of up to 16 edges

/// The minimum of @p f on [@p a, @p b] near @p x (f(x) = @p fx, the lowest known) by Brent's
/// method: golden-section steps, parabolic ones where the last three points allow, until the
/// bracket is within 2·@p tol. @return its abscissa, the value in @p f_min.
template <class F>
double brent_minimum(F&& f, double a, double b, double x, double fx, double tol, double& f_min) {
  constexpr double kGoldenStep = 0.3819660112501051;  // (3 − √5)/2
  double w = x, v = x, fw = fx, fv = fx, d = 0.0, e = 0.0;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double m = 0.5 * (a + b), tol2 = 2.0 * tol;
    if (std::abs(x - m) <= tol2 - 0.5 * (b - a)) break;
    bool golden = true;
    if (std::abs(e) > tol) {
      // the parabola through (x, fx), (w, fw), (v, fv): its vertex x + p/q
      const double r = (x - w) * (fx - fv);
      double q = (x - v) * (fx - fw);
      double p = (x - v) * q - (x - w) * r;
      q = 2.0 * (q - r);
      if (q > 0.0) p = -p;
      q = std::abs(q);
      const double previous = e;
      e = d;
      if (std::abs(p) < std::abs(0.5 * q * previous) && p > q * (a - x) && p < q * (b - x)) {
        d = p / q;
        const double u = x + d;
        if (u - a < tol2 || b - u < tol2) d = m > x ? tol : -tol;
        golden = false;
      }
    }
    if (golden) {
      e = x >= m ? a - x : b - x;
      d = kGoldenStep * e;
    }
    const double u = std::abs(d) >= tol ? x + d : x + (d > 0.0 ? tol : -tol);
    const double fu = f(u);
    if (fu <= fx) {
      (u >= x ? a : b) = x;
      v = w, fv = fw, w = x, fw = fx, x = u, fx = fu;
    } else {
      (u < x ? a : b) = u;
      if (fu <= fw || w == x) {
        v = w, fv = fw, w = u, fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u, fv = fu;
      }
    }
  }
  f_min = fx;
  return x;
}

/// The brake in scratch.profile (from the start) and step 1 from its end: their total duration,
/// or +∞ when step 1 has no profile.
double total_after(const KinematicState& target, const JerkLimits& solve_limits,
                   OptimalBrakeScratch& scratch) noexcept {
  if (!min_time_profile(scratch.profile.end(), target, solve_limits, scratch.block))
    return std::numeric_limits<double>::infinity();
  return scratch.profile.duration() + scratch.block.t_min;
}

/// Where step 1 from a member's end can change its shortest duration abruptly: the motions of
/// the velocity alone from there (to the target's velocity and acceleration, position free: its
/// minimum, and the ends of the interval it blocks), how many, and on which side of the target
/// position each ends. Their durations are the ends of the windows of durations in which step 1
/// has any motion, and at such an end the positions step 1 can reach shrink to that motion's.
/// An island of short durations — a window whose thin band of positions holds the target for
/// some members only — opens or closes where one of those motions passes the target, inside a
/// stretch of the family where the window exists.
struct EdgeCode {
  unsigned bits = 0;             ///< 1 without a motion; else motions × 2 | sides from bit 8
  int motions = 0;               ///< the number of motions (up to 4)
  unsigned above = 0;            ///< bit k: motion k ends above the target position
  std::array<double, 4> miss{};  ///< end position − target position of each motion
};
EdgeCode edge_code(const KinematicState& end, const KinematicState& target,
                   const JerkLimits& solve_limits, JerkBlock& velocity) noexcept {
  EdgeCode code;
  code.bits = 1u;
  if (!min_time_velocity_profile(end, target.v, target.a, solve_limits, velocity)) return code;
  code.motions = std::min(velocity.duration_count, 4);
  for (int k = 0; k < code.motions; ++k) {
    code.miss[k] = velocity.profiles[k].end(end).p - target.p;
    if (code.miss[k] > 0.0) code.above |= 1u << k;
  }
  code.bits = static_cast<unsigned>(code.motions) << 1 | code.above << 8;
  return code;
}

/// The one motion whose side of the target differs between @p x and @p y, or −1 (the number of
/// motions differs, or more than one side).
int single_crossing(const EdgeCode& x, const EdgeCode& y) noexcept {
  const unsigned d = x.above ^ y.above;
  if (x.bits == 1u || y.bits == 1u || x.motions != y.motions || d == 0u || (d & (d - 1u)) != 0u)
    return -1;
  int k = 0;
  while ((d >> k) != 1u) ++k;
  return k;
}

/// A member of the family: its end acceleration, its total (brake + step 1) and its edge code.
struct Member {
  double a_end = 0.0;
  double total = 0.0;
  unsigned code = 0;
};

}  // namespace

bool append_optimal_brake(const KinematicState& start, const KinematicState& target,
                          const JerkLimits& limits, const JerkLimits& solve_limits,
                          JerkProfile& profile, OptimalBrakeScratch& scratch) noexcept {
  const BrakeFamily family = brake_family(start, limits);
  if (family.side == 0.0 || !(family.highest > family.lowest))
    return append_brake(start, limits, profile);  // no choice
  const double V = limits.velocity, J = limits.jerk;
  // a member by its end acceleration (≤ 0 on the side of the violation): f_e = V − a_e²/(2J)
  const auto settled_of = [&](double a_end) { return V - 0.5 * a_end * a_end / J; };
  const auto set_member = [&](double a_end) {
    scratch.profile.reset(start);
    return append_brake_member(start, limits, settled_of(a_end), scratch.profile);
  };
  const auto total_at = [&](double a_end) {
    if (!set_member(a_end)) return std::numeric_limits<double>::infinity();
    return total_after(target, solve_limits, scratch);
  };
  const auto code_at = [&](double a_end) {
    if (!set_member(a_end)) return EdgeCode{};
    return edge_code(scratch.profile.end(), target, solve_limits, scratch.velocity);
  };
  const double lo = -std::sqrt(2.0 * J * std::max(V - family.lowest, 0.0));
  const double hi = -std::sqrt(2.0 * J * std::max(V - family.highest, 0.0));
  const double range = hi - lo;
  // an edge's bracket: kEdgeTolerance of the range, or a few units of round-off of the end
  // accelerations when the family is that narrow
  const double edge_tolerance =
      std::max(kEdgeTolerance * range, 8.0 * std::numeric_limits<double>::epsilon() * -lo);
  const double count_tolerance = std::max(kCountTolerance * range, edge_tolerance);
  // the grid, then both sides of every edge where the code changes between two grid members,
  // to kEdgeTolerance of the range (up to kMaxEdgesPerStep per step, each found in what is left
  // of the step after the previous one): where one motion passes the target, by the Illinois
  // method on its miss (continuous there); else by bisection
  std::array<Member, kMaxMembers> members;
  std::array<EdgeCode, kGrid> grid_codes;
  int count = 0;
  for (int k = 0; k < kGrid; ++k) {
    const double a_end = k == kGrid - 1 ? hi : lo + range * k / (kGrid - 1);
    grid_codes[k] = code_at(a_end);
    members[count++] = {a_end, 0.0, grid_codes[k].bits};
  }
  for (int k = 0; k + 1 < kGrid; ++k) {
    double left = members[k].a_end;
    EdgeCode left_code = grid_codes[k];
    const EdgeCode& right_code = grid_codes[k + 1];
    for (int edge = 0; edge < kMaxEdgesPerStep && left_code.bits != right_code.bits; ++edge) {
      double a = left, b = members[k + 1].a_end;
      EdgeCode b_code = right_code;
      int crossing = single_crossing(left_code, b_code);
      double fa = crossing >= 0 ? left_code.miss[crossing] : 0.0;
      double fb = crossing >= 0 ? b_code.miss[crossing] : 0.0;
      int kept = 0;  // the side kept by the last two steps (Illinois: its value halved)
      double root = 0.5 * (a + b);
      // a change in the number of motions (a window that opens or closes, its band a single
      // position there) is only bracketed to kCountTolerance: the edges that matter are the
      // crossings after it, located from there
      for (int iteration = 0;
           iteration < 100 && b - a > (crossing >= 0 ? edge_tolerance : count_tolerance);
           ++iteration) {
        double m = 0.5 * (a + b);
        if (crossing >= 0) {
          root = b - fb * (b - a) / (fb - fa);
          // near the root: a member on each side of it closes the bracket
          const double h = 0.5 * edge_tolerance;
          m = iteration > 0 && std::min(root - a, b - root) < 64.0 * h
                  ? (root - a < b - root ? root + h : root - h)
                  : root;
          m = std::clamp(m, a + h, b - h);
        }
        const EdgeCode c = code_at(m);
        if (c.bits == left_code.bits) {
          a = m, fa = crossing >= 0 ? c.miss[crossing] : 0.0;
          if (kept == 1) fb *= 0.5;
          kept = 1;
        } else {
          if (c.bits != b_code.bits) crossing = -1;  // another change inside: bisection
          b = m, b_code = c, fb = crossing >= 0 ? c.miss[crossing] : 0.0;
          if (kept == -1) fa *= 0.5;
          kept = -1;
        }
      }
      if (count + 2 > kMaxMembers) break;
      members[count++] = {a, 0.0, left_code.bits};
      members[count++] = {b, 0.0, b_code.bits};
      left = b, left_code = b_code;
    }
  }
  std::sort(members.begin(), members.begin() + count,
            [](const Member& x, const Member& y) { return x.a_end < y.a_end; });
  int best_k = 0;
  for (int k = 0; k < count; ++k) {
    members[k].total = total_at(members[k].a_end);
    if (members[k].total < members[best_k].total) best_k = k;
  }
  double best_a = members[best_k].a_end, best = members[best_k].total;
  // an end of the family that the total rises from (often the best: the latest or the earliest
  // release) is kept; else Brent's minimization (golden section with parabolic steps) between
  // the best member's neighbours, which lie on the same side of every edge found
  const bool at_end = best_k == 0 || best_k == count - 1;
  const double inward = best_k == 0 ? kEndProbe * range : -kEndProbe * range;
  if (!at_end || !(total_at(best_a + inward) >= best))
    best_a = brent_minimum(total_at, members[std::max(best_k - 1, 0)].a_end,
                           members[std::min(best_k + 1, count - 1)].a_end, best_a, best,
                           kRefineTolerance * range, best);
  // the standard brake (append_brake) when it is as short: its results stay as they were
  scratch.profile.reset(start);
  if (append_brake(start, limits, scratch.profile) &&
      !(total_after(target, solve_limits, scratch) > best))
    return append_brake(start, limits, profile);
  return append_brake_member(start, limits, settled_of(best_a), profile);
}

}  // namespace mjarm
