// 14_pick_place: the classic pick and place on the bundled six-axis arm — the 14-state machine
// (approach, descend, grasp, lift, move, place, release, with a dwell between), IK every control
// tick into the servos, the fingers closed by force control and a weld switched on where the
// cube is, the cube let go 45 mm above the table as the classic code does. Then the same trial held
// by friction alone. Prints each verdict and its figures; exits 0 only when both trials succeed
// (within 5 mm of the target, resting, upright, never dropped, the table untouched, no actuator
// clipped for long) and the weld jumped < 0.05 mm.

#include <cstdio>

#include "mjarm/tasks/pick_place/pick_place.hpp"

namespace {

bool report(const mjarm::PickPlaceReport& r) {
  const mjarm::PickPlaceTrace& t = r.trace;
  std::printf("%s grasp: %s%s%s\n", mjarm::to_string(r.grasp), r.success ? "success" : "FAILED",
              r.success ? "" : " — ", r.reason.c_str());
  std::printf("  placement error  %.3f mm (allowed 5 mm), tilt %.2f°, final speed %.4f mm/s\n",
              r.placement_error * 1e3, r.tilt * 180.0 / 3.14159265358979323846,
              r.final_speed * 1e3);
  std::printf("  cycle time       %.2f s, grasp force %.2f N (transport mean), slip %.3f mm\n",
              r.cycle_time, t.transport_force_mean, t.max_slip * 1e3);
  if (r.grasp == mjarm::GraspKind::weld)
    std::printf("  weld jump        %.5f mm\n", t.weld_jump * 1e3);
  return r.success;
}

}  // namespace

int main() {
  mjarm::PickPlaceOptions options;
  options.robot = "arm6";                          // or "panda_hand"
  options.mode = mjarm::SimulationMode::position;  // or torque (operational-space control)
  // options.classic = true: the 7.5 mm cube, finger travel [0, 0.012] m, finger servo gain 3200
  options.object_position = std::array<double, 2>{0.26, -0.08};  // on the table [m]
  options.target_position = std::array<double, 2>{0.24, 0.12};   // omit both to draw them
  options.seed = 1;  // draws the rest: the cube's size, mass, friction and yaw

  options.grasp = mjarm::GraspKind::weld;
  const mjarm::PickPlaceReport weld = mjarm::run_pick_place(options);
  bool ok = report(weld) && weld.trace.weld_jump < 5e-5;

  options.grasp = mjarm::GraspKind::friction;
  ok = report(mjarm::run_pick_place(options)) && ok;
  std::printf("%s\n", ok ? "ok" : "FAILED");
  return ok ? 0 : 1;
}
