#include "viewer_overlay.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

namespace mjarm {

namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;

void line(OverlayText& out, const char* label, const char* value) {
  if (!out.labels.empty()) {
    out.labels += '\n';
    out.values += '\n';
  }
  out.labels += label;
  out.values += value;
}

// the lines both overlays start with: mode (and "paused"), simulated time and speed, frame rate
void head_lines(OverlayText& out, const char* mode, double time, const OverlayInfo& info) {
  out.labels.clear();
  out.values.clear();
  char text[256];
  std::snprintf(text, sizeof(text), "%s%s", mode, info.paused ? "  (paused)" : "");
  line(out, "Mode", text);
  std::snprintf(text, sizeof(text), "%.2f s  (speed %.2fx)", time, info.speed);
  line(out, "Time", text);
  std::snprintf(text, sizeof(text), "%.1f fps", info.fps);
  line(out, "Frame rate", text);
}

}  // namespace

RateMeter::RateMeter(double window) noexcept
    : window_(std::isfinite(window) && window > 0.0 ? window : 0.5) {}

void RateMeter::add(double now, double amount) noexcept {
  if (!std::isfinite(now)) return;
  if (!started_) {  // the first call opens the window: what it reports happened before
    started_ = true;
    start_ = now;
    return;
  }
  sum_ += amount;
  if (now - start_ >= window_) {
    rate_ = sum_ / (now - start_);
    start_ = now;
    sum_ = 0.0;
  }
}

void format_overlay(const ViewerStats& stats, const OverlayInfo& info, const mjModel& m,
                    std::span<const std::uint8_t> saturated, OverlayText& out) {
  head_lines(out, to_string(stats.mode), stats.time, info);
  char text[256];
  std::snprintf(text, sizeof(text), "%.1f mm  %.2f deg", stats.tracking_position * 1000.0,
                stats.tracking_orientation * kDegrees);
  line(out, "Tracking error", text);
  std::snprintf(text, sizeof(text), "%.1f mm  %.2f deg", stats.target_position * 1000.0,
                stats.target_orientation * kDegrees);
  line(out, "To target", text);
  if (stats.ik_used) line(out, "IK", to_string(stats.ik_status));

  // saturation: the clipped actuators by name
  int clipped = 0;
  std::string names;
  for (std::size_t a = 0; a < saturated.size() && a < static_cast<std::size_t>(m.nu); ++a) {
    if (saturated[a] == 0) continue;
    ++clipped;
    if (clipped <= 4) {
      const char* name = mj_id2name(&m, mjOBJ_ACTUATOR, static_cast<int>(a));
      names += ' ';
      names += name != nullptr ? name : "?";
    }
  }
  if (stats.mode == SimulationMode::kinematic) {
    std::snprintf(text, sizeof(text), "n/a (kinematic)");
  } else if (clipped == 0) {
    std::snprintf(text, sizeof(text), "none of %d", static_cast<int>(m.nu));
  } else {
    std::snprintf(text, sizeof(text), "%d of %d:%s%s", clipped, static_cast<int>(m.nu), names.c_str(),
                  clipped > 4 ? " ..." : "");
  }
  line(out, "Saturation", text);

  const ContactSummary& c = stats.contacts;
  if (c.contacts == 0) {
    std::snprintf(text, sizeof(text), "none");
  } else if (!c.forces_valid || stats.mode == SimulationMode::kinematic) {
    std::snprintf(text, sizeof(text), "%d (forces n/a in kinematic mode)", c.contacts);
  } else {
    std::snprintf(text, sizeof(text), "%d, normal force %.1f N", c.contacts, c.normal_force);
  }
  line(out, "Contacts", text);

  if (stats.faulted) line(out, "FAULT", stats.fault.c_str());
  if (!info.note.empty()) line(out, "Note", info.note.c_str());
}

void format_teleop_overlay(const TeleopStats& stats, const std::vector<TeleopHand>& hands,
                           const TeleopPanel& panel, const OverlayInfo& info, OverlayText& common,
                           OverlayText& hands_text) {
  static constexpr const char* kPriorities[3] = {"equal", "right over left", "left over right"};
  const bool kinematic = stats.mode == SimulationMode::kinematic;
  head_lines(common, stats.mode == SimulationMode::torque ? "motor" : to_string(stats.mode),
             stats.time, info);
  char text[256];
  std::snprintf(text, sizeof(text), "%.3f m  (reference %.3f m)", stats.lift, stats.lift_reference);
  line(common, "Lift", text);
  line(common, "Priority",
       panel.priority >= 0 && panel.priority < 3 ? kPriorities[panel.priority] : "?");
  if (kinematic) {
    std::snprintf(text, sizeof(text), "%lld", static_cast<long long>(stats.rollbacks));
    line(common, "Rollbacks", text);
  }
  if (stats.faulted) line(common, "FAULT", stats.fault.c_str());
  if (!info.note.empty()) line(common, "Note", info.note.c_str());

  hands_text.labels.clear();
  hands_text.values.clear();
  for (std::size_t i = 0; i < stats.hands.size() && i < hands.size(); ++i) {
    const HandStats& h = stats.hands[i];
    const bool selected = static_cast<int>(i) == panel.selected;
    std::snprintf(text, sizeof(text), "%s hand", hands[i].name.c_str());
    line(hands_text, text, selected ? "[keys]" : "");
    std::snprintf(text, sizeof(text), "%.1f mm  %.2f deg", h.tracking_position * 1000.0,
                  h.tracking_orientation * kDegrees);
    line(hands_text, "  tracking", text);
    std::snprintf(text, sizeof(text), "%s  (%.1f mm  %.2f deg)", to_string(h.ik_status),
                  h.ik_position * 1000.0, h.ik_orientation * kDegrees);
    line(hands_text, "  IK", text);
    if (kinematic) {
      std::snprintf(text, sizeof(text), "n/a (kinematic)");
    } else {
      std::snprintf(text, sizeof(text), "%d actuator%s", h.saturated, h.saturated == 1 ? "" : "s");
    }
    line(hands_text, "  saturated", text);
    std::snprintf(text, sizeof(text), "%d", h.contacts);
    line(hands_text, "  contacts", text);
    if (kinematic) {
      std::snprintf(text, sizeof(text), "n/a (kinematic)%s", h.touching ? ", touching" : "");
    } else {
      std::snprintf(text, sizeof(text), "%.1f N%s", h.grasp_force,
                    h.touching ? "  (touching)" : "");
    }
    line(hands_text, "  grasp force", text);
    const double asked = i < panel.hands.size() ? panel.hands[i].gripper : 0.0;
    std::snprintf(text, sizeof(text), "%.2f  (asked %.2f)", h.gripper, asked);
    line(hands_text, "  gripper", text);
  }
}

}  // namespace mjarm
