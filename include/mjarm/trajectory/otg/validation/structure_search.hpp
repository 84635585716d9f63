#pragma once
/// @file
/// An independent reference for the minimum duration of one DoF (validation: tests and
/// `mjarm bench otg`): an exhaustive search over the switching structures of
/// otg/validation/structures.hpp, each solved numerically. It shares no formula and no code with
/// the generator's step 1 (otg/min_time.hpp): no closed forms, no polynomials, no
/// profile classes; only the limits and state types.
///
/// For each structure the unknowns are its phase durations tᵢ, the equations the boundary
/// conditions: the end state equals the target (p, v, a), and each limit arc starts on its
/// limit (a hold: a = ±a_max; a cruise: a = 0 and v = ±v_max). An arc first in the structure
/// needs the start on its limit (within 1e-9 relative), an arc last the target (its end rows
/// are then those of its entry). By the count of unknowns n and equations m:
/// - n = m: the solutions are isolated; Levenberg–Marquardt (durations clamped at ≥ 0) from
///   `seeds` random starting points finds them;
/// - n > m: the solutions form a family; its shortest motions are on its faces (a duration 0:
///   a shorter structure, enumerated too) or at a stationary point of the duration on it, where
///   1 = Jᵀλ (J the Jacobian of the boundary conditions): Levenberg–Marquardt reaches the family,
///   then Newton on [conditions; 1 − Jᵀλ] (the Hessian term by finite differences of J) finds
///   the stationary point;
/// - n < m: no solution for a generic start and target; where one exists it is a solution of a
///   structure with more phases of zero duration (the 8 such structures of seven phases visit a
///   velocity limit twice).
/// The residuals are evaluated on a motion that restarts every inner limit arc exactly on its
/// limit (the same motion at a root), so that an error before a long cruise does not grow
/// along it.
/// **Starts beyond the limits** (not startable: |a| > a_max, |v| > v_max, or the settled velocity
/// f = v + a·|a|/(2 j_max) beyond ±v_max) are searched over the admissible motions of
/// docs/trajectory_otg.md ("Brake"): an acceleration beyond its limit first ramps into it at full
/// jerk (fixed, before the structure); then, until the state first becomes startable, the phases
/// follow the brake's order on the violation's side s (s = sign(f) when |f| > v_max, else
/// sign(v)): full jerk −s·j_max, a hold at −s·a_max, one release at +s·j_max — each possibly
/// empty — and s·v stays ≥ min(−v_max, s·v₀); from then on the limits hold (the state may leave
/// the startable states again, towards a target that is reachable but not startable). The brake
/// ends where s·v first comes down to v_max, inside a phase (a release that the motion continues
/// is not split: its end is free on the family of the structure's solutions) or at a phase
/// boundary where the jerk turns against the brake's order (searched with that boundary's
/// velocity on the limit as one condition more), so every member of the brake family is searched
/// with the motion after it. A brake's release may run into a cruise on its limit, so these
/// starts use braking_switching_structures().
/// A solution counts when every duration is ≥ 0, its end is on the target (|Δp|, |Δv|, |Δa| ≤
/// 1e-9·max(1, |value|)) and it keeps |v| ≤ v_max, |a| ≤ a_max (relative 1e-9) at every phase's
/// ends and where the acceleration crosses zero inside a phase. Every solution is a true motion,
/// so the search never reports a duration shorter than the true minimum by more than those
/// tolerances; it finds the minimum when some structure of at most seven phases reaches it and
/// its seeds converge there (the test suite and `mjarm bench otg` compare it with the generator).

#include <cstdint>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/trajectory/otg/profile.hpp"
#include "mjarm/trajectory/otg/validation/structures.hpp"

namespace mjarm {

/// Settings of the structure search.
struct StructureSearchOptions {
  /// Starting points per structure (≥ 1). 8 found t_min on every seeded case tried; the ends of
  /// blocked intervals (extremal motions of longer structures) need about 32.
  int seeds = 32;
  std::uint64_t seed = 0;  ///< seed of the starting points
};

constexpr auto declared_fields(const StructureSearchOptions*) {
  using S = StructureSearchOptions;
  return declare<S>("structure search",
                    field("seeds", &S::seeds, "", Range::at_least(1),
                          "starting points per structure"),
                    field("seed", &S::seed, "", Range::non_negative(), "seed of the starting points"));
}

/// One solution: a structure and its phase durations.
struct StructureSolution {
  SwitchingStructure structure;                                    ///< the arcs
  std::array<double, SwitchingStructure::kMaxPhases> durations{};  ///< per phase [s]
  /// Before the structure, from a start whose acceleration is beyond its limit: the ramp into it
  /// at full jerk [s] and its jerk (0 and 0 otherwise).
  double ramp = 0.0;
  double ramp_jerk = 0.0;
  double duration = 0.0;  ///< the ramp and the phases together [s]
};

/// Outcome of a search.
enum class StructureSearchStatus {
  found,        ///< at least one structure has a valid solution
  no_solution,  ///< none has (the start cannot reach the target within the limits)
};

constexpr auto declared_names(const StructureSearchStatus*) {
  using S = StructureSearchStatus;
  return std::array{EnumName{S::found, "found", "a structure has a valid solution"},
                    EnumName{S::no_solution, "no_solution", "no structure has one"}};
}

/// What the search found.
struct StructureSearchResult {
  StructureSearchStatus status = StructureSearchStatus::no_solution;  ///< outcome
  double duration = 0.0;   ///< the shortest solution's duration [s] (found only)
  StructureSolution best;  ///< the shortest solution (found only)
  /// The distinct durations of every solution (isolated ones and stationary points of families;
  /// 1e-10 relative apart), ascending [s].
  std::vector<double> durations;
  /// The distinct durations of every valid motion met (those above, and the points of families
  /// where Levenberg–Marquardt reached them), ascending [s]: each is a feasible duration.
  std::vector<double> feasible_durations;
  int structures_tried = 0;   ///< structures whose boundary conditions could be set up
  int structures_solved = 0;  ///< of those, structures with at least one valid solution
  int solves = 0;             ///< Levenberg–Marquardt runs
};

/// The minimum duration from @p start to @p target under @p limits by the exhaustive search
/// (see the file). Allocates; takes milliseconds: for validation, not for control.
/// @throws Error when a limit is not positive and finite, a state value is not finite, or
/// options.seeds < 1.
StructureSearchResult structure_search_min_time(const KinematicState& start,
                                                const KinematicState& target,
                                                const JerkLimits& limits,
                                                const StructureSearchOptions& options = {});

/// The state reached from @p start after the phases of @p solution under @p limits' jerk
/// (integrated here, independently of JerkProfile).
KinematicState structure_end(const KinematicState& start, const JerkLimits& limits,
                             const StructureSolution& solution) noexcept;

}  // namespace mjarm
