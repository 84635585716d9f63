"""The classic pick and place (the teaching code's 14-state machine: approach, descend, grasp,
lift, move, place, release, with a dwell between) on mjarm: the scene of the trial, then one trial
held by a weld switched on where the cube is and one held by the finger contact forces alone, IK
every control tick into the servos. Prints the scene's names and each verdict with its figures;
exits 0 only when both trials succeed (within 5 mm of the target, resting, upright, never
dropped, the table untouched, no actuator clipped for long) and the weld jumped < 0.05 mm."""
import math
import sys

import mjarm

OBJECT = [0.26, -0.08]  # cube centre on the table, x y [m]
TARGET = [0.24, 0.12]  # where it should come to rest

# the scene a trial composes: arm6 on its table, a free cube, a target site, an inactive weld
# hand -> cube, three cameras (prefixed names, see docs/scene.md)
scene_options = mjarm.PickPlaceSceneOptions(robot="arm6", target=TARGET)
scene_options.object.position = OBJECT
scene = mjarm.build_pick_place_scene(scene_options)
print(f"scene: nq {scene.model.nq}, nu {scene.model.nu}; tool {scene.tool}, hand {scene.hand}, "
      f"fingers {list(scene.fingers)}, object {scene.object}, weld {scene.weld}, "
      f"cameras {list(scene.cameras)}")

# the task: the classic constants (0.055 m approach, 0.5 s dwells, 0.6 s grip, 0.07 m/s ...)
options = mjarm.PickPlaceOptions(robot="arm6", mode="position", seed=1,
                                 object_position=OBJECT, target_position=TARGET)
motion = options.motion
print(f"motion: approach {motion.approach_height} m, lift {motion.lift_height} m, dwell "
      f"{motion.dwell_time} s, grip {motion.grip_time} s, v_max {motion.limits.max_velocity} m/s")

ok = True
for grasp in ("weld", "friction"):
    options.grasp = grasp
    report = mjarm.run_pick_place(options)  # the GIL is released while it simulates
    trace = report.trace
    print(f"{grasp} grasp: {'success' if report.success else 'FAILED: ' + report.reason}")
    print(f"  placement error  {report.placement_error * 1e3:.3f} mm (allowed 5 mm), tilt "
          f"{math.degrees(report.tilt):.2f} deg, final speed {report.final_speed * 1e3:.4f} mm/s")
    print(f"  cycle time       {report.cycle_time:.2f} s, grasp force "
          f"{trace.transport_force_mean:.2f} N (transport mean), slip {trace.max_slip * 1e3:.3f} mm")
    ok = ok and report.success
    if grasp == "weld":
        print(f"  weld jump        {trace.weld_jump * 1e3:.5f} mm")
        ok = ok and trace.weld_jump < 5e-5
print("ok" if ok else "FAILED")
sys.exit(0 if ok else 1)
