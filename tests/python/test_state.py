"""State by name (Data.named, Simulation.named) and state snapshots that restore bit for bit, on
mjarm's data and on the user's own mujoco.MjData."""
import mujoco
import numpy as np
import pytest

import mjarm

# a ball joint, a hinge, a free body, a mocap body, a site, sensors, a filtered actuator
MIXED = """
<mujoco model="mixed">
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="ball_body" pos="0 0 1">
      <joint name="ball" type="ball"/>
      <geom type="sphere" size="0.05" mass="1"/>
      <body name="arm" pos="0 0 -0.3">
        <joint name="hinge" axis="0 1 0" damping="0.1"/>
        <geom type="capsule" fromto="0 0 0 0.2 0 0" size="0.02" mass="0.5"/>
        <site name="tip" pos="0.2 0 0"/>
      </body>
    </body>
    <body name="puck" pos="1 0 0.2">
      <freejoint name="free"/>
      <geom type="box" size="0.05 0.05 0.05" mass="0.2"/>
    </body>
    <body name="target" mocap="true" pos="0.5 0.5 0.5"/>
  </worldbody>
  <actuator>
    <general name="filtered" joint="hinge" dyntype="filter" dynprm="0.05" gainprm="2"/>
  </actuator>
  <sensor>
    <framepos name="tip_pos" objtype="site" objname="tip"/>
  </sensor>
</mujoco>
"""


def test_named_views_cover_each_element_and_write_through():
    robot = mjarm.Robot.from_string(MIXED)
    data = robot.make_data()
    named = data.named
    assert named.qpos["ball"].shape == (4,) and named.qvel["ball"].shape == (3,)
    assert named.qpos["free"].shape == (7,) and named.qvel["free"].shape == (6,)
    assert named.qpos.size("hinge") == 1 and len(named.qpos) == 3
    assert named.qpos.names == ["ball", "hinge", "free"]
    np.testing.assert_allclose(named.qpos["free"][:3], [1, 0, 0.2])
    named.qpos["hinge"] = 0.7                      # a number for a one-value element
    named.mocap_pos["target"] = [0.1, 0.2, 0.3]
    named.ctrl["filtered"][0] = 0.5                # the view writes into the data
    data.forward()
    assert data.qpos[robot.joint_info(robot.joint("hinge")).qpos_address] == 0.7
    assert data.ctrl[0] == 0.5
    np.testing.assert_array_equal(named.site_xpos["tip"], named.sensordata["tip_pos"])
    assert named.xmat["arm"].shape == (9,) and named.cvel["arm"].shape == (6,)
    assert not named.xpos["arm"].flags.writeable  # computed by mj_forward
    assert named.act["filtered"].shape == (1,)
    assert "hinge: 0.7\n" in repr(named.qpos)
    assert "target: 0.1 0.2 0.3" in repr(named.mocap_pos)   # only the mocap bodies


def test_named_refuses_unknown_names_bad_sizes_and_read_only_writes():
    robot = mjarm.Robot.from_string(MIXED)
    named = robot.make_data().named
    with pytest.raises(mjarm.Error, match="closest: hinge"):
        named.qpos["hinj"]
    with pytest.raises(ValueError):
        named.qpos["free"] = [1.0, 2.0]               # 7 values needed
    with pytest.raises(mjarm.Error, match="finite"):
        named.qpos["hinge"] = float("nan")
    with pytest.raises(mjarm.Error, match="computed by mj_forward"):
        named.xpos["arm"] = [0, 0, 0]
    with pytest.raises(mjarm.Error, match="not a mocap body"):
        named.mocap_pos["puck"]
    with pytest.raises(mjarm.Error):
        named.qpos[3]                                # three joints
    with pytest.raises(AttributeError):
        named.qpso


def test_named_on_the_users_mujoco_data():
    model = mujoco.MjModel.from_xml_string(MIXED)
    data = mujoco.MjData(model)
    named = mjarm.Data(data).named
    named.qpos["hinge"] = 0.3
    assert data.qpos[model.joint("hinge").qposadr[0]] == 0.3   # the user's own memory
    mujoco.mj_forward(model, data)
    np.testing.assert_array_equal(named.site_xpos["tip"], data.site("tip").xpos)


def test_a_simulations_named_data_reads_and_refuses_writes():
    sim = mjarm.Simulation(mjarm.Robot.bundled("panda"))
    named = sim.named
    np.testing.assert_array_equal(named.qpos["joint1"], sim.qpos[:1])
    with pytest.raises(mjarm.Error, match="read-only"):
        named.qpos["joint1"] = 0.1


def trajectory(model, data, steps):
    rows = []
    for i in range(steps):
        data.ctrl[0] = 0.5 * np.sin(0.01 * i)
        mujoco.mj_step(model, data)
        rows.append(np.concatenate([[data.time], data.qpos, data.qvel, data.act]))
    return np.array(rows)


def test_snapshot_restores_bit_for_bit_and_refuses_another_model():
    model = mujoco.MjModel.from_xml_string(MIXED)
    data = mujoco.MjData(model)
    handle = mjarm.Data(data)
    data.xfrc_applied[model.body("puck").id, 0] = 0.2
    trajectory(model, data, 200)                 # the puck lands: contacts
    assert data.ncon > 0
    snapshot = handle.snapshot()
    original = trajectory(model, data, 300)
    handle.restore(snapshot)
    assert np.array_equal(trajectory(model, data, 300), original)
    assert snapshot.time == pytest.approx(original[0, 0] - model.opt.timestep)

    panda = mjarm.Robot.bundled("panda").make_data()
    with pytest.raises(mjarm.Error, match="another model"):
        panda.restore(snapshot)


def test_simulation_snapshot_replays_its_ticks():
    # torque mode, no controller: the arm falls from home under gravity
    options = mjarm.SimulationOptions(mjarm.SimulationMode.torque, 0.01)
    sim = mjarm.Simulation(mjarm.Robot.bundled("panda_torque"), options)
    sim.reset("home")
    for _ in range(20):
        assert sim.tick(mjarm.Reference()).ok()
    snapshot = sim.snapshot()

    def ticks():
        rows = []
        for _ in range(50):
            assert sim.tick(mjarm.Reference()).ok()
            rows.append(sim.qpos.copy())
        return np.array(rows)

    first = ticks()
    sim.restore(snapshot)
    assert np.array_equal(ticks(), first)
    assert not np.array_equal(first[0], first[-1])  # it moved


def test_contact_records_name_the_geoms_and_split_the_force():
    model = mujoco.MjModel.from_xml_string(MIXED)
    data = mujoco.MjData(model)
    for _ in range(300):
        mujoco.mj_step(model, data)                 # the puck comes to rest on the floor
    mujoco.mj_forward(model, data)
    contacts = mjarm.Data(data).contact_forces()
    on_floor = [c for c in contacts if c.geom1_name == "floor" and c.body2_name == "puck"]
    assert on_floor and all(c.body1_name == "world" for c in on_floor)
    weight = model.body("puck").mass[0] * 9.81
    assert sum(c.normal_force for c in on_floor) == pytest.approx(weight, rel=1e-3)
    for c in contacts:
        np.testing.assert_allclose(c.normal_force * c.normal + c.friction_W, c.force_W, atol=1e-12)
        np.testing.assert_array_equal(c.frame[0], c.normal)
        assert abs(c.distance) < 1e-3


def test_ik_starts_from_the_state_it_is_given():
    robot = mjarm.Robot.bundled("panda")
    chain = mjarm.Chain(robot, "attachment_site")
    ik = mjarm.PoseIk(chain)
    sim = mjarm.Simulation(robot)
    sim.reset("home")
    goal = mjarm.ChainKinematics(chain).update(chain.clamp(sim.qpos[:7] + 0.2))
    from_sim = ik.solve(goal, sim)
    from_q = ik.solve(goal, sim.qpos[:7])
    assert from_sim.ok() and np.array_equal(from_sim.q, from_q.q)
    data = robot.make_data()
    data.qpos[:7] = sim.qpos[:7]
    assert np.array_equal(ik.solve(goal, data).q, from_q.q)
    with pytest.raises(mjarm.Error):
        ik.solve(goal, mjarm.Robot.bundled("ur5e").make_data())   # another model


def test_wrap_to_pi():
    assert mjarm.wrap_to_pi(3 * np.pi / 2) == pytest.approx(-np.pi / 2)
    np.testing.assert_allclose(mjarm.wrap_to_pi([7.0, -7.0, 0.5]),
                               [7.0 - 2 * np.pi, -7.0 + 2 * np.pi, 0.5])


def test_body_poses_place_every_link():
    robot = mjarm.Robot.bundled("panda")
    chain = mjarm.Chain(robot, "attachment_site")
    poses = mjarm.BodyPoses(robot)
    q = np.array([0.3, -0.5, 0.2, -2.0, 0.1, 1.6, 0.7])
    poses.update_chain(chain, q)
    data = robot.make_data()
    data.qpos[:7] = q
    data.forward()
    named = data.named
    for i, name in enumerate(poses.names):
        np.testing.assert_array_equal(poses.positions[i], named.xpos[i])
        np.testing.assert_array_equal(poses.rotations[i].ravel(), named.xmat[i])
    np.testing.assert_array_equal(poses.pose("link7").p, named.xpos["link7"])
    assert poses.names[0] == "world" and len(poses) == len(poses.names)


WELDED = """
<mujoco model="welded">
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="held" pos="0 0 1">
      <freejoint/>
      <geom type="sphere" size="0.05" mass="2" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
  <equality><weld name="grasp" body1="held"/></equality>
</mujoco>
"""


def test_equalities_by_name_and_the_constraint_summary():
    model = mujoco.MjModel.from_xml_string(WELDED)
    data = mujoco.MjData(model)
    state = mjarm.Data(data)
    assert state.named.eq_active["grasp"] and state.named.eq_active.names == ["grasp"]
    mujoco.mj_forward(model, data)
    held = state.constraint_summary()
    assert held.equality == 6 and held.rows == 6 and held.max_force > 1.0
    state.named.eq_active["grasp"] = False
    assert data.eq_active[0] == 0
    mujoco.mj_forward(model, data)
    assert state.constraint_summary().rows == 0
    with pytest.raises(mjarm.Error, match="closest: grasp"):
        state.named.eq_active["grap"]


def test_a_simulations_equality_switches_by_name():
    sim = mjarm.Simulation(mjarm.Robot.from_string(WELDED))
    assert sim.named.eq_active["grasp"]
    sim.named.eq_active["grasp"] = False
    assert not sim.named.eq_active["grasp"] and sim.data.named.eq_active[0] is False
