#include "mjarm/trajectory/otg/validation/structures.hpp"

namespace mjarm {

namespace {

constexpr std::array<JerkArc, 6> kArcs{JerkArc::up,        JerkArc::down,
                                       JerkArc::hold_up,   JerkArc::hold_down,
                                       JerkArc::cruise_up, JerkArc::cruise_down};

/// The bang arc that must come right before (and, after = true, right after) a limit arc.
JerkArc neighbour_of(JerkArc limit_arc, bool after) noexcept {
  switch (limit_arc) {
    case JerkArc::hold_up:
      return after ? JerkArc::down : JerkArc::up;
    case JerkArc::hold_down:
      return after ? JerkArc::up : JerkArc::down;
    case JerkArc::cruise_up:
      return JerkArc::down;
    default:
      return JerkArc::up;  // cruise_down
  }
}

/// Whether @p next may follow @p previous (see the file comment of the header); @p braking lets
/// a cruise follow the jerk that ends a brake on its side (+v_max after jerk up, −v_max after
/// jerk down).
bool may_follow(JerkArc previous, JerkArc next, bool braking) noexcept {
  if (previous == next) return false;
  if (braking && ((previous == JerkArc::up && next == JerkArc::cruise_up) ||
                  (previous == JerkArc::down && next == JerkArc::cruise_down)))
    return true;
  const bool limit_before = is_limit_arc(previous), limit_after = is_limit_arc(next);
  if (limit_before && limit_after) return false;
  if (limit_after) return previous == neighbour_of(next, false);
  if (limit_before) return next == neighbour_of(previous, true);
  return true;  // up after down or down after up
}

void extend(SwitchingStructure& s, std::vector<SwitchingStructure>& out, int length, bool braking) {
  if (s.size == length) {
    out.push_back(s);
    return;
  }
  for (const JerkArc arc : kArcs) {
    if (s.size > 0 && !may_follow(s.arcs[static_cast<std::size_t>(s.size - 1)], arc, braking))
      continue;
    s.arcs[static_cast<std::size_t>(s.size++)] = arc;
    extend(s, out, length, braking);
    --s.size;
  }
}

std::vector<SwitchingStructure> enumerate(bool braking) {
  std::vector<SwitchingStructure> out;
  SwitchingStructure s;
  for (int length = 1; length <= SwitchingStructure::kMaxPhases; ++length)
    extend(s, out, length, braking);
  return out;
}

}  // namespace

std::string SwitchingStructure::name() const {
  std::string out;
  for (int i = 0; i < size; ++i) {
    if (i > 0) out += ' ';
    switch (arcs[static_cast<std::size_t>(i)]) {
      case JerkArc::up:
        out += "+";
        break;
      case JerkArc::down:
        out += "−";
        break;
      case JerkArc::hold_up:
        out += "A+";
        break;
      case JerkArc::hold_down:
        out += "A−";
        break;
      case JerkArc::cruise_up:
        out += "V+";
        break;
      case JerkArc::cruise_down:
        out += "V−";
        break;
    }
  }
  return out;
}

const std::vector<SwitchingStructure>& switching_structures() {
  static const std::vector<SwitchingStructure> all = enumerate(false);
  return all;
}

const std::vector<SwitchingStructure>& braking_switching_structures() {
  static const std::vector<SwitchingStructure> all = enumerate(true);
  return all;
}

}  // namespace mjarm
