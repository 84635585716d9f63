"""Simulation (modes, ticks, sensors, contacts), Recorder, C++ controllers and a Python
Controller in a closed loop: its exception stops the run and the recording is kept."""
import json
import os

import numpy as np
import pytest

import mjarm


def make_sim(robot, period=0.01):
    sim = mjarm.Simulation(robot, mjarm.SimulationOptions(mjarm.SimulationMode.torque, period))
    sim.reset("home")
    return sim


class PythonPd(mjarm.Controller):
    """tau = kp (q_ref - q) + kd (qd_ref - qd) + h, written in Python."""

    def __init__(self, chain, kp, kd):
        mjarm.Controller.__init__(self, chain, mjarm.CommandKind.torque, "py-pd")
        self.chain_ = chain
        self.kp, self.kd = kp, kd
        self.calls = 0
        self.kept_data = None

    def compute(self, data, reference):
        self.calls += 1
        self.kept_data = data
        q = self.chain_.gather(data.qpos)
        dofs = self.chain_.dof_addresses
        return (self.kp * (reference.joint.q - q) + self.kd * (reference.joint.qd - data.qvel[dofs])
                + data.qfrc_bias[dofs])


def joint_reference(q):
    ref = mjarm.Reference()
    ref.joint.q = q
    ref.joint.qd = np.zeros(len(q))
    ref.joint.qdd = np.zeros(len(q))
    return ref


def test_python_controller_closed_loop_matches_cpp(planar2_torque):
    chain = mjarm.Chain(planar2_torque, "tip")
    goal = np.array([-0.4, -1.6])
    results = []
    for make in (lambda: PythonPd(chain, 100.0, 5.0),
                 lambda: mjarm.JointPdController(chain, pd_options(100.0, 5.0))):
        sim = make_sim(planar2_torque)
        ctl = make()
        sim.add_controller(ctl)
        run = sim.run(mjarm.ConstantReferenceSource(joint_reference(goal)), 2.0)
        assert run.ok() and run.status == mjarm.RunStatus.duration_reached
        results.append((ctl, chain.gather(sim.qpos)))
    py_ctl, q_py = results[0]
    assert py_ctl.calls == 200
    np.testing.assert_allclose(q_py, goal, atol=1e-3)
    # the same law in C++ (bias h = gravity at rest) ends at the same place
    np.testing.assert_allclose(q_py, results[1][1], atol=1e-4)
    # the data lent to compute() is dead after the call: no read of freed memory
    with pytest.raises(mjarm.Error, match="lent for one call"):
        py_ctl.kept_data.qpos


def pd_options(kp, kd):
    o = mjarm.JointPdOptions()
    o.gains = mjarm.JointPdGains.uniform(kp, kd)
    return o


class Exploding(PythonPd):
    def compute(self, data, reference):
        if data.time >= 0.05:
            raise RuntimeError("controller failed at 50 ms")
        return super().compute(data, reference)


def test_python_controller_exception_stops_run_and_keeps_recording(planar2_torque, tmp_path):
    chain = mjarm.Chain(planar2_torque, "tip")
    sim = make_sim(planar2_torque)
    sim.add_controller(Exploding(chain, 100.0, 5.0))
    source = mjarm.ConstantReferenceSource(joint_reference(np.array([-0.4, -1.6])))
    directory = tmp_path / "rec"
    with pytest.raises(RuntimeError, match="controller failed at 50 ms"):
        with mjarm.Recorder(sim, str(directory)) as recorder:
            sim.run(source, 1.0, recorder)
    # stopped at that tick, on the last good state
    assert sim.time == pytest.approx(0.05)
    assert np.all(np.isfinite(sim.qpos))
    summary = json.loads((directory / "summary.json").read_text())
    assert summary["status"] == "error"
    events = (directory / "events.csv").read_text()
    assert "controller failed at 50 ms" in events
    assert len((directory / "state.csv").read_text().splitlines()) > 20


def test_python_controller_wrong_size_is_an_error(planar2_torque):
    chain = mjarm.Chain(planar2_torque, "tip")

    class Wrong(mjarm.Controller):
        def compute(self, data, reference):
            return np.zeros(3)

    sim = make_sim(planar2_torque)
    sim.add_controller(Wrong(chain))
    with pytest.raises(ValueError, match=r"Controller.compute result: expected shape \(2,\), got \(3,\)"):
        sim.tick(joint_reference(np.zeros(2)))


def test_simulation_views_and_lifetimes(planar2_torque):
    sim = make_sim(planar2_torque)
    qpos = sim.qpos
    assert not qpos.flags.writeable
    with pytest.raises(ValueError):
        qpos[0] = 1.0
    data = sim.data
    del sim  # the views keep the simulation alive
    assert qpos.shape == (planar2_torque.nq,) and np.all(np.isfinite(qpos))
    assert data.time == 0.0 and data.qvel.shape == (planar2_torque.nv,)


def test_set_state_tick_and_reproducibility(planar2_torque):
    chain = mjarm.Chain(planar2_torque, "tip")
    runs = []
    for _ in range(2):
        sim = make_sim(planar2_torque, 0.004)
        sim.add_controller(mjarm.JointPdController(chain, pd_options(50.0, 2.0)))
        ref = joint_reference(np.array([0.3, -0.3]))
        for _ in range(50):
            assert sim.tick(ref).ok()
        runs.append(sim.qpos.copy())
        assert sim.ticks == 50 and sim.physics_steps == 50 * sim.steps_per_tick
    np.testing.assert_array_equal(runs[0], runs[1])
    sim = make_sim(planar2_torque)
    with pytest.raises(ValueError, match=r"qpos: expected shape \(2,\)"):
        sim.set_state(np.zeros(3), np.zeros(2))
    with pytest.raises(mjarm.Error):
        sim.set_state(np.array([np.nan, 0.0]), np.zeros(2))


def test_modes_and_kinematic_move(panda):
    sim = mjarm.Simulation(panda, mjarm.SimulationOptions(mjarm.SimulationMode.kinematic))
    q = panda.keyframe_qpos("home")
    step = sim.move(q, 0.01)
    assert not step.rolled_back and sim.time == pytest.approx(0.01)
    np.testing.assert_array_equal(sim.qpos, q)
    with pytest.raises(mjarm.Error):
        sim.tick(mjarm.Reference())
    position = mjarm.Simulation(panda, mjarm.SimulationOptions(mjarm.SimulationMode.position, 0.01))
    with pytest.raises(mjarm.Error):
        position.add_controller(mjarm.JointPdController(mjarm.Chain(panda, "attachment_site")))
    with pytest.raises(mjarm.Error, match="multiple"):
        mjarm.Simulation(panda, mjarm.SimulationOptions(mjarm.SimulationMode.torque, 0.0033))


def test_sensors_and_contacts(panda_torque):
    sim = mjarm.Simulation(panda_torque, mjarm.SimulationOptions(mjarm.SimulationMode.torque))
    sim.reset("home")
    for info in panda_torque.sensors():
        values = sim.sensor(info.name)
        assert values.shape == (info.dimension,)
    with pytest.raises(mjarm.Error, match="not found"):
        sim.sensor("no_such_sensor")
    robot_geoms = mjarm.GeomSet.of_bodies(panda_torque, ["link0"])
    handle = sim.watch_contacts(robot_geoms, mjarm.GeomSet.of_bodies(panda_torque, ["world"], False))
    summary = sim.contacts(handle)
    assert summary.contacts >= 0 and summary.force_W.shape == (3,)


def test_function_reference_source_and_its_exception(planar2_torque):
    chain = mjarm.Chain(planar2_torque, "tip")
    sim = make_sim(planar2_torque)
    sim.add_controller(mjarm.JointPdController(chain, pd_options(100.0, 5.0)))
    goal = np.array([-0.4, -1.6])

    def reference(data):
        if data.time >= 0.5:
            return None  # complete
        return joint_reference(goal)

    run = sim.run(mjarm.FunctionReferenceSource(planar2_torque, reference), 2.0)
    assert run.status == mjarm.RunStatus.finished and run.end_time == pytest.approx(0.5)

    def broken(data):
        raise KeyError("no reference")

    with pytest.raises(KeyError, match="no reference"):
        sim.run(mjarm.FunctionReferenceSource(planar2_torque, broken), 1.0)


def test_every_cpp_controller_steps(panda_torque, panda):
    chain = mjarm.Chain(panda_torque, "attachment_site")
    data = panda_torque.make_data()
    data.qpos[:] = panda_torque.keyframe_qpos("home")
    data.forward()
    ref = joint_reference(chain.gather(data.qpos))
    ref.task.X_WE = mjarm.forward_kinematics(chain, chain.gather(data.qpos))
    controllers = [
        mjarm.JointPdController(chain), mjarm.GravityHoldController(chain),
        mjarm.ComputedTorqueController(chain), mjarm.TaskPdController(chain),
        mjarm.AccelerationController(chain), mjarm.OperationalSpaceController(chain),
        mjarm.Se3ImpedanceController(chain), mjarm.CartesianImpedanceController(chain),
        mjarm.HqpAcController(chain),
    ]
    g = data.qfrc_bias[:7]
    for c in controllers:
        tau = c.compute(data, ref)
        assert tau.shape == (7,) and np.all(np.isfinite(tau)), c.name
        # at rest on the reference, every torque law holds the arm against gravity
        np.testing.assert_allclose(tau, g, atol=0.5, err_msg=c.name)
        assert len(c.internal_names) == len(c.internal_values)
    servo = mjarm.GravityCompensationController(mjarm.Chain(panda, "attachment_site"))
    assert servo.command_kind == mjarm.CommandKind.position and servo.compensates_bias


def test_compute_into_a_preallocated_array(panda_torque, panda):
    chain = mjarm.Chain(panda_torque, "attachment_site")
    data = panda_torque.make_data()
    data.qpos[:] = panda_torque.keyframe_qpos("home")
    data.forward()
    ref = joint_reference(chain.gather(data.qpos) + 0.1)
    ref.task.X_WE = mjarm.forward_kinematics(chain, chain.gather(data.qpos))
    for c in (mjarm.JointPdController(chain), mjarm.OperationalSpaceController(chain)):
        fresh = c.compute(data, ref)
        assert fresh.dtype == np.float64 and fresh.shape == (7,) and fresh.flags.writeable
        out = np.full(7, np.nan)
        assert c.compute(data, ref, out) is out
        np.testing.assert_array_equal(out, fresh)
        assert c.compute(data, ref, out=out) is out
        # each call's array is its own: a later call does not change an earlier result
        before = fresh.copy()
        c.compute(data, joint_reference(chain.gather(data.qpos)))
        np.testing.assert_array_equal(fresh, before)
        for bad in (np.zeros(6), np.zeros(7, dtype=np.float32), np.zeros((7, 1)), np.zeros(14)[::2],
                    [0.0] * 7):
            with pytest.raises(ValueError, match=r"out: expected a writable contiguous float64 "
                                                 r"array of shape \(7,\)"):
                c.compute(data, ref, bad)
        frozen = np.zeros(7)
        frozen.flags.writeable = False
        with pytest.raises(ValueError, match="out: expected a writable"):
            c.compute(data, ref, frozen)
        with pytest.raises(TypeError):
            c.compute(None, ref)
        with pytest.raises(mjarm.Error, match=r"belongs to model 'panda' .*model 'panda_torque'"):
            c.compute(panda.make_data(), ref)
