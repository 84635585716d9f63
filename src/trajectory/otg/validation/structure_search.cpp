#include "mjarm/trajectory/otg/validation/structure_search.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "mjarm/error.hpp"
#include "mjarm/random.hpp"

namespace mjarm {

namespace {

constexpr int kMaxPhases = SwitchingStructure::kMaxPhases;
// the end, up to three inner cruises, and a brake's end
constexpr int kMaxConditions = 3 + 2 * 3 + 1;
constexpr int kMaxUnknowns = kMaxPhases + kMaxConditions;
constexpr double kOnLimit = 1e-9;  // a first or last arc's state on its limit, relative
constexpr double kAccept = 1e-9;   // end on target and limits kept, relative

using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxUnknowns, 1>;
using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxUnknowns, kMaxUnknowns>;

double arc_jerk(JerkArc arc, double j_max) noexcept {
  return arc == JerkArc::up ? j_max : arc == JerkArc::down ? -j_max : 0.0;
}

/// The state after @p t [s] of constant jerk @p j from @p x (Taylor series of the motion).
KinematicState advance(const KinematicState& x, double j, double t) noexcept {
  const double t2 = t * t;
  return {x.p + x.v * t + 0.5 * x.a * t2 + j * t2 * t / 6.0, x.v + x.a * t + 0.5 * j * t2,
          x.a + j * t};
}

double component(const KinematicState& x, int c) noexcept {
  return c == 0 ? x.p : (c == 1 ? x.v : x.a);
}

/// One boundary condition: component (0 p, 1 v, 2 a) of the state at the start of phase
/// `boundary` (the structure's size: its end) equals `value`; its residual is in units of
/// `scale`.
struct Condition {
  int boundary = 0;
  int component = 0;
  double value = 0.0;
  double scale = 1.0;
};

/// The longest durations a phase of each kind takes, roughly [s]: the unit of its unknown and the
/// range its seeds are drawn from.
struct PhaseScales {
  double bang = 1.0;    ///< a full-jerk ramp
  double hold = 1.0;    ///< a hold at ±a_max
  double cruise = 1.0;  ///< a cruise at ±v_max
  double total = 1.0;   ///< the whole motion (the unit of the position residual: v_max·total)

  double of(JerkArc arc) const noexcept {
    if (!is_limit_arc(arc)) return bang;
    return (arc == JerkArc::hold_up || arc == JerkArc::hold_down) ? hold : cruise;
  }
};

/// The boundary conditions of one structure for one problem, as residuals of the scaled
/// durations u (tᵢ = unitᵢ·uᵢ, unitᵢ the PhaseScales of the phase's kind) with their Jacobian.
///
/// For conditioning, the motion evaluated here restarts every inner limit arc exactly on its
/// limit (its acceleration, and a cruise's velocity, set to the level its entry conditions ask
/// for): an error before a long cruise then does not grow along it, and the Jacobian is block
/// triangular. At a root the entry conditions hold, so the motion is the true one; `accept`
/// integrates the true motion all the same.
class StructureSystem {
 public:
  /// @p brake_end > 0: the brake ends at that phase boundary, where the velocity is
  /// @p brake_velocity (side·v_max).
  StructureSystem(const SwitchingStructure& s, const KinematicState& start,
                  const KinematicState& target, const JerkLimits& limits, const PhaseScales& scales,
                  int brake_end = 0, double brake_velocity = 0.0)
      : s_(s), start_(start) {
    const double V = limits.velocity, A = limits.acceleration;
    // the acceleration a motion reaches is at most a_max and, from rest, √(v_max·j_max)
    const double scale[3] = {V * scales.total, V, std::min(A, std::sqrt(V * limits.jerk))};
    for (int i = 0; i < s.size; ++i) {
      jerk_[i] = arc_jerk(s.arcs[i], limits.jerk);
      unit_[i] = scales.of(s.arcs[i]);
    }
    const auto on_limit = [&](JerkArc arc, const KinematicState& x) {
      const double level_a = arc == JerkArc::hold_up ? A : (arc == JerkArc::hold_down ? -A : 0.0);
      if (std::abs(x.a - level_a) > kOnLimit * A) return false;
      if (arc == JerkArc::cruise_up) return std::abs(x.v - V) <= kOnLimit * V;
      if (arc == JerkArc::cruise_down) return std::abs(x.v + V) <= kOnLimit * V;
      return true;
    };
    const auto add = [&](int boundary, int c, double value) {
      conditions_[count_++] = {boundary, c, value, scale[c]};
    };
    // a first arc starts on its limit already; a last one must end there, and its entry
    // conditions are then the target's values
    if (is_limit_arc(s.arcs[0]) && !on_limit(s.arcs[0], start)) return;
    const JerkArc last = s.arcs[s.size - 1];
    if (is_limit_arc(last) && !on_limit(last, target)) return;
    for (int k = 1; k < s.size; ++k) {
      const JerkArc arc = s.arcs[k];
      if (!is_limit_arc(arc)) continue;
      const bool final_arc = k == s.size - 1;
      const bool cruise = arc == JerkArc::cruise_up || arc == JerkArc::cruise_down;
      const double a_level =
          final_arc ? target.a
                    : (arc == JerkArc::hold_up ? A : (arc == JerkArc::hold_down ? -A : 0.0));
      add(k, 2, a_level);
      snap_a_[k] = a_level;
      snaps_[k] = 1;
      if (cruise) {
        const double v_level = final_arc ? target.v : (arc == JerkArc::cruise_up ? V : -V);
        add(k, 1, v_level);
        snap_v_[k] = v_level;
        snaps_[k] = 2;
      }
    }
    if (brake_end > 0) add(brake_end, 1, brake_velocity);
    add(s.size, 0, target.p);
    if (!is_limit_arc(last)) {
      add(s.size, 1, target.v);
      add(s.size, 2, target.a);
    } else if (last == JerkArc::hold_up || last == JerkArc::hold_down) {
      add(s.size, 1, target.v);
      if (s.size == 1) add(s.size, 2, target.a);  // the start's level, checked: keeps it
    } else if (s.size == 1) {
      add(s.size, 1, target.v);
    }
    valid_ = true;
  }

  bool valid() const noexcept { return valid_; }
  int unknowns() const noexcept { return s_.size; }
  int conditions() const noexcept { return count_; }
  /// The duration [s] of phase @p i at the scaled value @p u (negative values clamped to 0).
  double duration(int i, double u) const noexcept { return unit_[i] * std::max(u, 0.0); }
  /// The unit of phase @p i's unknown [s].
  double unit(int i) const noexcept { return unit_[i]; }

  /// Residuals @p r (conditions()) and, when given, their Jacobian @p J (conditions() ×
  /// unknowns()) at the scaled durations @p u.
  void evaluate(const Vector& u, Vector& r, Matrix* J) const {
    const int n = s_.size;
    std::array<KinematicState, kMaxPhases + 1> x;  // at each boundary, before a snap
    std::array<double, kMaxPhases> t{};
    x[0] = start_;
    for (int i = 0; i < n; ++i) {
      t[i] = unit_[i] * u[i];
      x[i + 1] = advance(snapped(i, x[i]), jerk_[i], t[i]);
    }
    r.resize(count_);
    if (J) J->setZero(count_, n);
    for (int k = 0; k < count_; ++k) {
      const Condition& c = conditions_[k];
      r[k] = (component(x[c.boundary], c.component) - c.value) / c.scale;
      if (!J) continue;
      // lengthening phase i adds its end rates (v, a, j) there; the change is carried to the
      // boundary phase by phase (δp += t·δv + t²/2·δa, δv += t·δa), a snap clearing what it sets
      for (int i = 0; i < c.boundary; ++i) {
        double dp = x[i + 1].v, dv = x[i + 1].a, da = jerk_[i];
        for (int m = i + 1; m < c.boundary; ++m) {
          if (snaps_[m] >= 1) da = 0.0;
          if (snaps_[m] == 2) dv = 0.0;
          dp += t[m] * dv + 0.5 * t[m] * t[m] * da;
          dv += t[m] * da;
        }
        const double d = c.component == 0 ? dp : (c.component == 1 ? dv : da);
        (*J)(k, i) = d * unit_[i] / c.scale;
      }
    }
  }

 private:
  /// @p x at the start of phase @p i, restarted on its limit when the phase is an inner limit
  /// arc.
  KinematicState snapped(int i, KinematicState x) const noexcept {
    if (snaps_[i] >= 1) x.a = snap_a_[i];
    if (snaps_[i] == 2) x.v = snap_v_[i];
    return x;
  }

  SwitchingStructure s_;
  KinematicState start_;
  std::array<double, kMaxPhases> jerk_{};
  std::array<double, kMaxPhases> unit_{};
  std::array<int, kMaxPhases> snaps_{};  ///< per phase: 0 none, 1 acceleration, 2 and velocity
  std::array<double, kMaxPhases> snap_a_{};
  std::array<double, kMaxPhases> snap_v_{};
  std::array<Condition, kMaxConditions> conditions_{};
  int count_ = 0;
  bool valid_ = false;
};

/// Levenberg–Marquardt on F(z) = 0 with z₀ … z_{clamped−1} kept ≥ 0; @p eval(z, F, J) fills F
/// and its Jacobian. Gives up after kMaxIterations, or when the cost has not halved over
/// kWindow iterations (a local minimum or a bound away from a root). True when it ends with
/// ‖F‖∞ ≤ kTolerance.
template <class Eval>
bool levenberg_marquardt(Eval&& eval, Vector& z, int clamped) {
  constexpr double kTolerance = 1e-12;
  constexpr int kMaxIterations = 200;
  constexpr int kWindow = 8;
  Vector F, F_new, z_new, step;
  Matrix J, J_new, H;
  eval(z, F, J);
  double cost = F.squaredNorm();
  H.noalias() = J.transpose() * J;
  double mu = 1e-3 * std::max(1.0, H.diagonal().maxCoeff());
  double nu = 2.0;
  double cost_before = cost;  // the cost kWindow iterations ago
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    if (iteration % kWindow == kWindow - 1) {
      if (cost > 0.5 * cost_before) break;
      cost_before = cost;
    }
    if (F.cwiseAbs().maxCoeff() <= kTolerance) return true;
    H.noalias() = J.transpose() * J;
    H.diagonal().array() += mu;
    step = H.ldlt().solve(-(J.transpose() * F));
    z_new = z + step;
    for (int i = 0; i < clamped; ++i) z_new[i] = std::max(z_new[i], 0.0);
    step = z_new - z;
    eval(z_new, F_new, J_new);
    const double cost_new = F_new.squaredNorm();
    const double predicted = cost - (F + J * step).squaredNorm();
    if (std::isfinite(cost_new) && cost_new < cost && predicted > 0.0) {
      const double rho = (cost - cost_new) / predicted;
      z = z_new;
      F = F_new;
      J = J_new;
      cost = cost_new;
      mu *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
      nu = 2.0;
    } else {
      mu *= nu;
      nu *= 2.0;
      if (mu > 1e20) break;
    }
    if (step.norm() <= 1e-16 * (1.0 + z.norm()) && cost_new >= cost) break;
  }
  return F.cwiseAbs().maxCoeff() <= kTolerance;
}

/// The stationary point of the duration Σ unitᵢ·uᵢ on the family of solutions of @p system near
/// @p u (n > m): F(u, λ) = [r(u); w − J(u)ᵀλ] = 0 with wᵢ = unitᵢ / @p total. True when found
/// (then in @p u).
bool stationary_point(const StructureSystem& system, double total, Vector& u) {
  const int n = system.unknowns(), m = system.conditions();
  Vector r, w(n);
  Matrix J;
  for (int i = 0; i < n; ++i) w[i] = system.unit(i) / total;
  system.evaluate(u, r, &J);
  Vector z(n + m);
  z.head(n) = u;
  const Matrix JJt = J * J.transpose();
  z.tail(m) = JJt.ldlt().solve(J * w);
  const auto eval = [&](const Vector& zz, Vector& F, Matrix& G) {
    const Vector uu = zz.head(n), lambda = zz.tail(m);
    Vector rr, rh;
    Matrix Ju, Jh;
    system.evaluate(uu, rr, &Ju);
    F.resize(n + m);
    F.head(m) = rr;
    F.tail(n) = w - Ju.transpose() * lambda;
    G.setZero(n + m, n + m);
    G.topLeftCorner(m, n) = Ju;
    G.bottomRightCorner(n, m) = -Ju.transpose();
    // the Hessian term ∂(Jᵀλ)/∂u by forward differences of the analytic J
    const Vector g0 = Ju.transpose() * lambda;
    for (int q = 0; q < n; ++q) {
      Vector uh = uu;
      const double h = 1e-7 * std::max(1.0, std::abs(uu[q]));
      uh[q] += h;
      system.evaluate(uh, rh, &Jh);
      G.block(m, q, n, 1) = -(Jh.transpose() * lambda - g0) / h;
    }
  };
  if (!levenberg_marquardt(eval, z, n)) return false;
  u = z.head(n);
  return true;
}

/// Whether the phases of @p s with @p durations [s] are a motion within the limits that ends on
/// the target (see the file comment of the header).
bool accept(const SwitchingStructure& s, const std::array<double, kMaxPhases>& durations,
            const KinematicState& start, const KinematicState& target, const JerkLimits& l,
            double position_scale) {
  const double V = l.velocity * (1.0 + kAccept), A = l.acceleration * (1.0 + kAccept);
  KinematicState x = start;
  const auto within = [&](const KinematicState& y) {
    return std::abs(y.v) <= V && std::abs(y.a) <= A;
  };
  if (!within(x)) return false;
  for (int i = 0; i < s.size; ++i) {
    const double t = durations[i];
    const double j = arc_jerk(s.arcs[i], l.jerk);
    const KinematicState y = advance(x, j, t);
    if (!within(y)) return false;
    if (j != 0.0 && x.a * y.a < 0.0) {  // the acceleration crosses zero inside: a velocity peak
      const double t0 = -x.a / j;
      if (std::abs(x.v + x.a * t0 + 0.5 * j * t0 * t0) > V) return false;
    }
    x = y;
  }
  return std::abs(x.p - target.p) <= kAccept * position_scale &&
         std::abs(x.v - target.v) <= kAccept * std::max(1.0, std::abs(target.v)) &&
         std::abs(x.a - target.a) <= kAccept * std::max(1.0, std::abs(target.a));
}

/// Whether a profile within the limits can start at @p x: |a| ≤ a_max, |v| ≤ v_max and the
/// velocity where the acceleration, ramped to zero at full jerk, ends is within ±v_max
/// (relative @p slack).
bool startable(const KinematicState& x, const JerkLimits& l, double slack) noexcept {
  const double V = l.velocity * (1.0 + slack);
  return std::abs(x.a) <= l.acceleration * (1.0 + slack) && std::abs(x.v) <= V &&
         std::abs(x.v + x.a * std::abs(x.a) / (2.0 * l.jerk)) <= V;
}

/// The brake's order of a phase on the side @p side of the violation: 0 full jerk down (−side),
/// 1 the hold at −side·a_max, 2 full jerk up; −1 for an arc no brake takes.
int brake_stage(JerkArc arc, double side) noexcept {
  const bool positive = side > 0.0;
  if (arc == JerkArc::down) return positive ? 0 : 2;
  if (arc == JerkArc::up) return positive ? 2 : 0;
  if (arc == (positive ? JerkArc::hold_down : JerkArc::hold_up)) return 1;
  return -1;
}

/// The first instant in [0, @p t] at which the motion from @p x under jerk @p j is startable,
/// or −1: where side·v comes down to v_max (the only way in from a brake's states), or at @p t.
double first_startable(const KinematicState& x, double j, double t, const JerkLimits& l,
                       double side) noexcept {
  if (startable(x, l, kAccept)) return 0.0;
  // 0.5·j·τ² + a·τ + (v − side·v_max) = 0
  const double c = x.v - side * l.velocity, b = x.a;
  std::array<double, 2> roots{-1.0, -1.0};
  if (j != 0.0) {
    const double disc = b * b - 2.0 * j * c;
    if (disc >= 0.0) {
      const double r = std::sqrt(disc);
      roots = {(-b - r) / j, (-b + r) / j};
      if (roots[0] > roots[1]) std::swap(roots[0], roots[1]);
    }
  } else if (b != 0.0) {
    roots[0] = -c / b;
  }
  for (const double tau : roots)
    if (tau >= 0.0 && tau <= t && startable(advance(x, j, tau), l, kAccept)) return tau;
  return startable(advance(x, j, t), l, kAccept) ? t : -1.0;
}

/// accept() for a start beyond the velocity limit on side @p side (its acceleration within):
/// until the state first becomes startable, the phases follow the brake's order (full jerk
/// against the violation, a hold at full deceleration, one release at full jerk) and the velocity
/// does not pass beyond the other side's limit (nor below its start there); from then on the
/// limits hold. Within the phase where it becomes startable they hold from that instant on: its
/// velocity then moves towards the settled velocity, which is within, or linearly.
bool accept_braking(const SwitchingStructure& s, const std::array<double, kMaxPhases>& durations,
                    const KinematicState& start, const KinematicState& target, const JerkLimits& l,
                    double position_scale, double side) {
  const double V = l.velocity * (1.0 + kAccept), A = l.acceleration * (1.0 + kAccept);
  const double floor = std::min(-V, side * start.v);  // of side·v while braking
  KinematicState x = start;
  bool braking = !startable(x, l, kAccept);
  int stage = 0;
  for (int i = 0; i < s.size; ++i) {
    const double t = durations[i];
    const double j = arc_jerk(s.arcs[i], l.jerk);
    const KinematicState y = advance(x, j, t);
    if (std::abs(y.a) > A) return false;
    const bool crosses = j != 0.0 && x.a * y.a < 0.0;  // the acceleration crosses zero inside
    const double t0 = crosses ? -x.a / j : 0.0;
    const double v_turn = x.v + x.a * t0 + 0.5 * j * t0 * t0;
    if (braking) {
      // the first instant the state is startable: where side·v comes down to v_max, or the end
      const double entry = first_startable(x, j, t, l, side);
      if (t > 0.0 && entry != 0.0) {  // a part of the brake: in its order
        const int k = brake_stage(s.arcs[i], side);
        if (k < stage) return false;
        stage = k;
      }
      if (entry < 0.0) {
        if (side * y.v < floor || (crosses && side * v_turn < floor)) return false;
        x = y;
        continue;
      }
      braking = false;
      if (crosses && t0 <= entry && side * v_turn < floor) return false;
      // from then on within the limits (the velocity's turn after it lies at the settled
      // velocity, startable; checked all the same)
      if (std::abs(y.v) > V || (crosses && t0 > entry && std::abs(v_turn) > V)) return false;
    } else if (std::abs(y.v) > V || (crosses && std::abs(v_turn) > V)) {
      return false;
    }
    x = y;
  }
  return !braking && std::abs(x.p - target.p) <= kAccept * position_scale &&
         std::abs(x.v - target.v) <= kAccept * std::max(1.0, std::abs(target.v)) &&
         std::abs(x.a - target.a) <= kAccept * std::max(1.0, std::abs(target.a));
}

/// Adds @p d to the ascending distinct @p list (1e-10 relative apart).
void record_duration(std::vector<double>& list, double d) {
  for (const double e : list)
    if (std::abs(e - d) <= 1e-10 * std::max(1.0, d)) return;
  list.insert(std::upper_bound(list.begin(), list.end(), d), d);
}

}  // namespace

KinematicState structure_end(const KinematicState& start, const JerkLimits& limits,
                             const StructureSolution& solution) noexcept {
  KinematicState x = advance(start, solution.ramp_jerk, solution.ramp);
  for (int i = 0; i < solution.structure.size; ++i)
    x = advance(x, arc_jerk(solution.structure.arcs[i], limits.jerk), solution.durations[i]);
  return x;
}

StructureSearchResult structure_search_min_time(const KinematicState& start,
                                                const KinematicState& target,
                                                const JerkLimits& limits,
                                                const StructureSearchOptions& options) {
  check_fields(limits, "structure search");
  for (const double x : {start.p, start.v, start.a, target.p, target.v, target.a})
    if (!std::isfinite(x))
      throw Error("structure_search_min_time: start and target must be finite");
  check_fields(options);
  const double V = limits.velocity, A = limits.acceleration, J = limits.jerk;
  // positions relative to the start: the round-off of an offset stays out of the residuals
  KinematicState s0{0.0, start.v, start.a};
  // a start beyond the limits (see the header): an acceleration beyond its limit first ramps
  // into it at full jerk (no choice), then the structures start from there; a velocity beyond
  // (or that must pass beyond) is braked on its side
  double ramp = 0.0, ramp_jerk = 0.0, side = 0.0;
  if (!startable(s0, limits, 0.0)) {
    const double f = s0.v + s0.a * std::abs(s0.a) / (2.0 * J);
    side = std::abs(f) > V ? (f > 0.0 ? 1.0 : -1.0) : (s0.v > 0.0 ? 1.0 : -1.0);
    if (std::abs(s0.a) > A) {
      ramp_jerk = s0.a > 0.0 ? -J : J;
      ramp = (std::abs(s0.a) - A) / J;
      s0 = advance(s0, ramp_jerk, ramp);
      s0.a = s0.a > 0.0 ? A : -A;  // exactly on the limit
    }
    if (startable(s0, limits, 1e-12)) side = 0.0;
  }
  const auto accepted = [&](const SwitchingStructure& s,
                            const std::array<double, kMaxPhases>& durations,
                            const KinematicState& from, const KinematicState& to, double scale) {
    return side == 0.0 ? accept(s, durations, from, to, limits, scale)
                       : accept_braking(s, durations, from, to, limits, scale, side);
  };
  const KinematicState tf{target.p - start.p, target.v, target.a};
  const double position_scale = std::max({1.0, std::abs(start.p), std::abs(target.p)});
  // a full-jerk ramp spans at most 2·a_max and (from a = 0) 2·v_max; a hold spans at most
  // 2·v_max; a cruise covers the distance
  PhaseScales scales;
  scales.bang = side != 0.0 ? 2.0 * A / J : std::min(2.0 * A / J, 2.0 * std::sqrt(V / J));
  scales.hold = 2.0 * V / A + std::abs(s0.v) / A;
  scales.cruise = 1.5 * std::abs(tf.p) / V + V / A;
  scales.total = A / J + V / A + std::abs(tf.p) / V + std::abs(tf.v - s0.v) / A;

  StructureSearchResult result;
  const auto keep = [&](StructureSolution solution) {
    solution.ramp = ramp;
    solution.ramp_jerk = ramp_jerk;
    solution.duration += ramp;
    record_duration(result.durations, solution.duration);
    record_duration(result.feasible_durations, solution.duration);
    if (result.status == StructureSearchStatus::no_solution ||
        solution.duration < result.duration) {
      result.status = StructureSearchStatus::found;
      result.duration = solution.duration;
      result.best = solution;
    }
  };
  {  // already there: the motion of no phase
    const StructureSolution none;
    if (accepted(none.structure, none.durations, s0, tf, position_scale)) keep(none);
  }
  Random rng(options.seed);
  const auto search = [&](const SwitchingStructure& s, const StructureSystem& system) {
    if (!system.valid() || system.unknowns() < system.conditions()) return;
    ++result.structures_tried;
    bool solved = false;
    for (int k = 0; k < options.seeds; ++k) {
      Vector u(s.size);
      // in units of each phase's scale: uniform on even seeds, log-uniform over two decades on
      // odd ones
      for (int i = 0; i < s.size; ++i)
        u[i] = (k % 2 == 0) ? uniform(rng) : std::pow(10.0, -2.0 * uniform(rng));
      ++result.solves;
      const auto residuals = [&](const Vector& z, Vector& F, Matrix& G) {
        system.evaluate(z, F, &G);
      };
      if (!levenberg_marquardt(residuals, u, s.size)) continue;
      const auto solution_at = [&](const Vector& z) {
        StructureSolution solution;
        solution.structure = s;
        for (int i = 0; i < s.size; ++i) {
          solution.durations[i] = system.duration(i, z[i]);
          solution.duration += solution.durations[i];
        }
        return solution;
      };
      if (system.unknowns() > system.conditions()) {
        // a point of the family is a motion too: its duration is feasible
        const StructureSolution point = solution_at(u);
        if (accepted(s, point.durations, s0, tf, position_scale))
          record_duration(result.feasible_durations, point.duration + ramp);
        if (!stationary_point(system, scales.total, u)) continue;
      }
      const StructureSolution solution = solution_at(u);
      if (!accepted(s, solution.durations, s0, tf, position_scale)) continue;
      keep(solution);
      solved = true;
    }
    result.structures_solved += solved ? 1 : 0;
  };
  for (const SwitchingStructure& s :
       side == 0.0 ? switching_structures() : braking_switching_structures()) {
    search(s, StructureSystem(s, s0, tf, limits, scales));
    if (side == 0.0) continue;
    // the brake may also end where a phase of the brake's order meets one that is not (the
    // release, then jerk the other way): that boundary on the velocity limit, one condition more
    int stage = 0;
    for (int k = 1; k < s.size; ++k) {
      const int before = brake_stage(s.arcs[k - 1], side);
      if (before < stage) break;
      stage = before;
      const int after = brake_stage(s.arcs[k], side);
      const bool cruise = s.arcs[k] == JerkArc::cruise_up || s.arcs[k] == JerkArc::cruise_down;
      if (after >= stage || cruise) continue;
      search(s, StructureSystem(s, s0, tf, limits, scales, k, side * V));
    }
  }
  return result;
}

}  // namespace mjarm
