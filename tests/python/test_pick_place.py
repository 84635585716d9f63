"""Pick and place from Python: options (names or enums, arrays checked), a short trial with each
grasp, the same seed giving the same trial, a parallel batch equal to the trials run alone, the
GIL released while trials run, and refused input. Trials use a quicker schedule than the
defaults (short dwells, faster segments) so the file runs in seconds."""
import math

import numpy as np
import pytest

import mjarm
from conftest import runs_beside


def quick(**fields):
    """Options of a short trial on arm6 (seed 3 unless given): 0.1 s dwells, 0.2 m/s segments."""
    options = mjarm.PickPlaceOptions(**{"robot": "arm6", "seed": 3, **fields})
    motion = options.motion  # a view into options: edited in place
    motion.dwell_time = 0.1
    motion.grip_time = 0.3
    motion.release_time = 0.3
    motion.settle_time = 0.6
    motion.limits.max_velocity = 0.2
    motion.limits.max_acceleration = 2.0
    return options


def test_options_take_names_and_enums():
    o = mjarm.PickPlaceOptions(grasp="friction", mode="torque", seed=7)
    assert o.grasp == mjarm.GraspKind.friction and o.mode == mjarm.SimulationMode.torque
    o.grasp = mjarm.GraspKind.weld
    assert o.grasp == mjarm.GraspKind.weld
    assert o.object_position is None and o.object_half_size is None
    o.object_position = [0.26, -0.08]
    assert o.object_position.dtype == np.float64 and o.object_position.shape == (2,)
    o.object_position = None
    assert o.object_position is None
    assert o.ranges.mass.shape == (2,) and o.ranges.half_size.tolist() == [0.012, 0.02]
    assert o.motion.dwell_time == 0.5 and o.criteria.grasp.drop_distance == 0.015
    assert o.weld.time_constant == 0.002
    with pytest.raises(mjarm.Error, match="unknown grasp 'glue'; choices: weld .*, friction"):
        o.grasp = "glue"
    with pytest.raises(mjarm.Error, match="unknown simulation mode 'velocity'"):
        o.mode = "velocity"
    with pytest.raises(ValueError, match=r"target_position: expected shape \(2,\), got \(3,\)"):
        o.target_position = [0.1, 0.2, 0.3]
    with pytest.raises(TypeError, match="grasp: expected a name or an enum value, got None"):
        o.grasp = None
    with pytest.raises(TypeError, match="no field 'robots'"):
        mjarm.PickPlaceOptions(robots="arm6")
    names = [r.name for r in mjarm.pick_place_robots()]
    assert names == ["arm6", "panda_hand"]
    arm6 = mjarm.pick_place_robot("arm6")
    assert arm6.tool == "grip" and arm6.mount.shape == (3,)


def test_a_seed_draws_the_same_trial():
    o = mjarm.PickPlaceOptions(robot="panda_hand", seed=11)
    a, b = mjarm.draw_pick_place_trial(o), mjarm.draw_pick_place_trial(o)
    assert a.target.tolist() == b.target.tolist()
    assert a.object.position.tolist() == b.object.position.tolist() and a.object.mass == b.object.mass
    o.seed = 12
    c = mjarm.draw_pick_place_trial(o)
    assert c.object.position.tolist() != a.object.position.tolist()
    o.object_position = [0.45, 0.05]
    assert mjarm.draw_pick_place_trial(o).object.position.tolist() == [0.45, 0.05]
    lo, hi = o.ranges.mass
    assert lo <= c.object.mass <= hi


def test_weld_trial_places_the_cube_without_a_jump():
    report = mjarm.run_pick_place(quick(grasp="weld"))
    assert report.ok() and report.success and report.failure == mjarm.PickPlaceFailure.none
    assert report.reason == "" and report.run.ok()
    assert report.placement_error < 0.005 and report.final_speed < 0.001
    assert report.tilt < math.radians(5)
    assert report.trace.closed and report.trace.welded and report.trace.weld_jump < 5e-5
    assert report.trace.state == mjarm.PickPlaceState.done
    assert not report.trace.table_contact and not report.trace.dropped
    assert report.grasp == mjarm.GraspKind.weld and report.robot == "arm6"
    assert report.trial.seed == 3 and report.trial.target.shape == (2,)


def test_friction_trial_holds_by_contact_forces_in_torque_mode():
    report = mjarm.run_pick_place(quick(grasp="friction", mode="torque"))
    assert report.success, report.reason
    assert report.trace.closed and not report.trace.welded and math.isnan(report.trace.weld_jump)
    assert report.trace.transport_force_mean > 1.0  # squeezed
    assert report.trace.max_slip < 0.015
    assert report.mode == mjarm.SimulationMode.torque


def test_same_seed_same_trial_and_batches_equal_the_trials_alone():
    options = quick(grasp="weld")
    alone = [mjarm.run_pick_place(quick(grasp="weld", seed=s)) for s in (3, 4)]
    done = []
    batch_options = mjarm.PickPlaceBatchOptions(base=options, trials=2, threads=2)
    batch = mjarm.run_pick_place_trials(batch_options, on_progress=done.append)
    assert sorted(done) == [1, 2] and not batch.interrupted
    assert [r.trial.seed for r in batch.reports] == [3, 4]
    for r, a in zip(batch.reports, alone):  # the same seed gives the same trial, bit for bit
        assert r.placement_error == a.placement_error and r.cycle_time == a.cycle_time
        assert r.trace.weld_jump == a.trace.weld_jump and r.final_speed == a.final_speed
    s = batch.summary
    assert s.trials == 2 and s.successes == 2 and s.success_rate() == 1.0
    assert s.failures["misplaced"] == 0 and "none" not in s.failures
    assert s.placement_error.count == 2
    assert s.placement_error.max == max(a.placement_error for a in alone)
    assert mjarm.summarize(batch.reports).successes == 2


def test_a_progress_callback_that_raises_is_raised_after_the_batch():
    def fail(done):
        raise RuntimeError(f"stop at {done}")
    with pytest.raises(RuntimeError, match="stop at 1"):
        mjarm.run_pick_place_trials(mjarm.PickPlaceBatchOptions(base=quick(), trials=1), fail)


def test_trials_release_the_gil():
    options = quick(grasp="weld")
    ran, report = runs_beside(lambda: mjarm.run_pick_place(options), most=3)
    assert ran and report.success  # the main thread ran while the trial simulated


def test_the_scene_of_a_trial():
    o = mjarm.PickPlaceSceneOptions(robot="panda_hand", target=[0.5, -0.1])
    o.object.position = [0.45, 0.1]
    scene = mjarm.build_pick_place_scene(o)
    assert scene.tool.startswith("panda") and scene.object == "object" and scene.weld == "grasp"
    assert scene.model.nq == 9 + 7 and len(scene.arm_joints) == 7
    assert set(scene.cameras) >= {"front", "side", "top"}
    assert scene.model.site("target") >= 0


def test_bad_trials_raise_with_the_library_message():
    with pytest.raises(mjarm.Error, match="unknown robot 'arm7' for the pick and place"):
        mjarm.run_pick_place(mjarm.PickPlaceOptions(robot="arm7"))
    far = quick(object_position=[0.6, 0.0])
    with pytest.raises(mjarm.Error, match=r"object at \(0.600, 0.000, .*\) m is out of reach of "
                                          r"arm6.*reaches"):
        mjarm.run_pick_place(far)
    with pytest.raises(mjarm.Error, match="trials"):
        mjarm.run_pick_place_trials(mjarm.PickPlaceBatchOptions(base=quick(), trials=0))
    bad_motion = quick()
    bad_motion.motion.grip_time = -1.0
    with pytest.raises(mjarm.Error, match="grip_time"):
        mjarm.run_pick_place(bad_motion)
    with pytest.raises(TypeError):
        mjarm.run_pick_place(None)
