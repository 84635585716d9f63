#pragma once
/// @file
/// The switching structures of a jerk-limited motion of one DoF, for the exhaustive search of
/// otg/validation/structure_search.hpp (validation only: none of the generator's code uses them).
///
/// A structure is a sequence of at most seven phases, each one of six arcs: full jerk up or
/// down (bang arcs), or zero jerk along a limit (a hold of the acceleration at ±a_max, a cruise
/// of the velocity at ±v_max with zero acceleration). Every sequence of these arcs of length
/// 1 … 7 is enumerated, except those that cannot be a motion within the limits with positive
/// phase durations:
/// - two equal arcs in a row (they are one phase), or two zero-jerk arcs in a row (the
///   acceleration would jump between them, or they are one phase);
/// - an arc on a limit next to a bang arc that would cross that limit: a hold at +a_max is
///   entered by jerk up and left by jerk down (the reverse at −a_max); a cruise at +v_max is
///   entered and left by jerk down (its acceleration falls to 0 from above, then below 0), at
///   −v_max by jerk up.
/// That leaves 678 structures.

#include <array>
#include <string>
#include <vector>

namespace mjarm {

/// One phase kind of a switching structure.
enum class JerkArc : unsigned char {
  up,           ///< jerk +j_max
  down,         ///< jerk −j_max
  hold_up,      ///< zero jerk at a = +a_max
  hold_down,    ///< zero jerk at a = −a_max
  cruise_up,    ///< zero jerk at a = 0, v = +v_max
  cruise_down,  ///< zero jerk at a = 0, v = −v_max
};

/// A switching structure: arcs[0 … size−1], in time order.
struct SwitchingStructure {
  static constexpr int kMaxPhases = 7;  ///< most phases of a structure
  std::array<JerkArc, kMaxPhases> arcs{};
  int size = 0;  ///< number of phases

  /// A compact name: "+" and "−" for the bang arcs, "A+"/"A−" for the holds, "V+"/"V−" for the
  /// cruises, separated by spaces ("+ A+ − V+ − A− +").
  std::string name() const;
};

/// True for the zero-jerk arcs (holds and cruises).
inline bool is_limit_arc(JerkArc arc) noexcept {
  return arc != JerkArc::up && arc != JerkArc::down;
}

/// Every admissible structure of 1 … 7 phases (see the file), shortest first; built once.
const std::vector<SwitchingStructure>& switching_structures();

/// The same for a start beyond the velocity limit: a brake from beyond +v_max ends on jerk up
/// (its release), which a cruise at +v_max may then follow (at −v_max: jerk down); the other
/// rules stay. A superset of switching_structures(); built once.
const std::vector<SwitchingStructure>& braking_switching_structures();

}  // namespace mjarm
