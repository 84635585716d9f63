"""Docking from Python: the scene, a short peg-in-hole run (seated, its metrics and every tick's
samples as arrays), the same run twice giving the same figures, a small grid equal to its runs
alone, a docking controller in a Simulation, the tracking gate, the GIL released during a run,
and refused input. Runs use a quicker motion than the defaults (0.5 s approach, 20 mm/s
insertion, 1.2 s hold) so the file runs in seconds."""
import math

import numpy as np
import pytest

import mjarm
from conftest import runs_beside


@pytest.fixture(scope="module")
def scene():
    return mjarm.build_docking_scene()


def quick(scene, dx=0.003, dy=0.0, dyaw=0.0, **controller):
    options = mjarm.DockingOptions(scene=scene, offset=mjarm.DockingOffset(dx, dy, dyaw))
    motion = options.motion  # a view into options: edited in place
    motion.approach_time = 0.5
    motion.insertion_speed = 0.02
    motion.insertion_acceleration = 0.2
    motion.hold_time = 1.2
    for key, value in controller.items():
        setattr(options.controller, key, value)
    return options


def test_the_scene(scene):
    assert scene.chain.size == 7 and scene.robot.nu == 7
    assert scene.peg_mass > 0.1 and scene.peg_com_E.shape == (3,)
    # one convex piece per side of the 32-gon, the bottom plate and the base
    assert len(scene.peg) >= 1 and len(scene.socket) == 32 + 2
    seated = scene.seated()
    assert seated.p[2] == pytest.approx(0.2 - 0.05)
    parts = mjarm.docking_scene()
    assert parts.has("site", "iiwa/peg/tip") and parts.has("sensor", "iiwa/peg/ft_force")


def test_a_short_run_seats_the_peg_and_gives_its_samples(scene):
    report = mjarm.run_docking(quick(scene))
    assert report.ok() and report.outcome == mjarm.DockingOutcome.seated, report.metrics.failures
    m = report.metrics
    assert m.seated and m.failures == [] and m.peak_force < 40.0
    assert abs(m.steady_axial_force - 5.0) < 0.5  # the preload
    assert m.max_lateral <= 0.5e-3 and m.min_depth > 0.049
    assert report.controller == "se3" and report.source == mjarm.ForceSource.sensor
    assert report.plan.q_start.shape == (7,)
    assert report.plan.duration() == pytest.approx(report.plan.approach_time
                                                   + report.plan.insert_time + report.plan.hold_time)
    n = report.sample_count
    assert n == report.run.ticks and n > 1000
    s = report.samples()
    for name, shape in (("t", (n,)), ("p_WE", (n, 3)), ("R_WE", (n, 3, 3)), ("V_WE", (n, 6)),
                        ("p_WD", (n, 3)), ("F_peg", (n, 6)), ("F_measured", (n, 6)),
                        ("stiffness", (n, 6)), ("manipulability", (n,))):
        assert s[name].shape == shape and s[name].dtype == np.float64, name
    assert s["contacts"].dtype == np.int32 and s["saturated"].dtype == np.bool_
    assert np.all(np.diff(s["t"]) > 0)
    # the peak force over the samples is the metric's
    assert np.linalg.norm(s["F_peg"][:, :3], axis=1).max() == pytest.approx(m.peak_force)
    # the tip ends at the bottom of the true socket
    assert s["p_WE"][-1, 2] == pytest.approx(scene.seated().p[2], abs=1e-3)
    assert "seated" in report.result_line()


def test_the_same_run_gives_the_same_figures(scene):
    a = mjarm.run_docking(quick(scene, law="hqp-ac", source="observer"))
    b = mjarm.run_docking(quick(scene, law=mjarm.DockingLaw.hqp_ac,
                                source=mjarm.ForceSource.observer))
    assert a.controller == "hqp-ac" and a.source == mjarm.ForceSource.observer
    assert a.metrics.peak_force == b.metrics.peak_force
    assert np.array_equal(a.samples()["p_WE"], b.samples()["p_WE"])


def test_a_small_grid_equals_its_runs_alone(scene):
    grid = mjarm.DockingGridOptions(base=quick(scene), x=[0.003], y=[0.0], yaw=[0.0, 0.1], jobs=2)
    assert grid.x.dtype == np.float64 and grid.yaw.shape == (2,)
    progress = []
    result = mjarm.run_docking_grid(grid, lambda done, planned: progress.append((done, planned)))
    assert result.planned == 2 and len(result.runs) == 2 and not result.interrupted
    assert progress[-1] == (2, 2)
    for run, yaw in zip(result.runs, (0.0, 0.1)):
        alone = mjarm.run_docking(quick(scene, dyaw=yaw))
        assert run.offset.dyaw == yaw
        assert run.metrics.peak_force == alone.metrics.peak_force
    assert result.seated == sum(r.outcome == mjarm.DockingOutcome.seated for r in result.runs)
    assert result.max_peak_force == max(r.metrics.peak_force for r in result.runs)


def test_a_docking_controller_in_a_simulation(scene):
    plan = mjarm.plan_docking(scene, mjarm.DockingOffset(), mjarm.DockingMotion())
    controller = mjarm.DockingController(scene, mjarm.DockingControllerOptions(law="cic"))
    assert controller.name == "cic" and controller.command_kind == mjarm.CommandKind.torque
    sim = mjarm.Simulation(scene.robot, mjarm.SimulationOptions(mjarm.SimulationMode.torque))
    q = scene.robot.keyframe_qpos("home")
    q[:7] = plan.q_start
    sim.set_state(q, np.zeros(scene.robot.nv))
    sim.add_controller(controller)
    reference = mjarm.Reference()
    reference.task.X_WE = plan.X_start
    reference.joint.q = plan.q_start
    for _ in range(50):
        assert sim.tick(reference).ok()
    tip = mjarm.forward_kinematics(scene.chain, scene.chain.gather(sim.qpos))
    assert np.linalg.norm(tip.p - plan.X_start.p) < 1e-3  # holds the start pose
    assert controller.stiffness.shape == (6,) and controller.measured_wrench.shape == (6,)


def test_the_tracking_gate(scene):
    options = mjarm.TrackingGateOptions(scene=scene, frequency=1.0, ramp_time=0.3,
                                        settle_time=0.1)
    report = mjarm.run_tracking_gate(options)
    assert report.ok() and report.contact_ticks == 0
    assert report.total.position_rms < 2e-3 and report.loops[0].samples > 100
    assert report.passes(1.0, 1.0) and not report.passes(1e-9, 1e-9)


def test_a_run_releases_the_gil(scene):
    ran, report = runs_beside(lambda: mjarm.run_docking(quick(scene)), most=3)
    assert ran and report.ok()


def test_bad_docking_input(scene):
    with pytest.raises(mjarm.Error, match="dx"):
        mjarm.run_docking(quick(scene, dx=0.2))
    with pytest.raises(mjarm.Error, match="unknown force source 'camera'; .*force sources: sensor, observer"):
        mjarm.DockingControllerOptions(source="camera")
    with pytest.raises(mjarm.Error, match="pid"):
        mjarm.DockingControllerOptions(law="pid")
    bare = mjarm.build_docking_scene(mjarm.DockingSceneOptions(ft_sensor=False))
    with pytest.raises(mjarm.Error, match="iiwa/peg/ft"):
        mjarm.DockingController(bare, mjarm.DockingControllerOptions(source="sensor"))
    bad_gain = mjarm.DockingControllerOptions()
    with pytest.raises(ValueError, match=r"se3_stiffness: expected shape \(6,\), got \(3,\)"):
        bad_gain.se3_stiffness = [1.0, 2.0, 3.0]
    bad_gain.se3_stiffness = -np.ones(6)
    with pytest.raises(mjarm.Error, match="stiffness"):
        mjarm.DockingController(scene, bad_gain)
    with pytest.raises(mjarm.Error, match="hold_time|window"):
        mjarm.run_docking(mjarm.DockingOptions(scene=scene,
                                               motion=mjarm.DockingMotion(hold_time=-1.0)))
    with pytest.raises(ValueError, match="yaw"):
        mjarm.DockingGridOptions(yaw=[[0.0]])
    with pytest.raises(mjarm.Error):
        mjarm.run_docking_grid(mjarm.DockingGridOptions(base=quick(scene), x=[]))
    with pytest.raises(TypeError):
        mjarm.run_docking(None)
    assert math.isclose(mjarm.DockingOffset(dyaw=0.1).dyaw, 0.1)
