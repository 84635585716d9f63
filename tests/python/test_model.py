"""Models: bundled, file, string; names and id maps; Data handles; newer MJCF as MuJoCo loads it."""
import os

import numpy as np
import pytest

import mjarm


def test_bundled_names_and_repr():
    names = mjarm.Robot.bundled_names()
    assert "panda" in names and "planar2" in names and names == sorted(names)
    robot = mjarm.Robot.bundled("planar2")
    assert "planar2" in repr(robot)


def test_file_and_string_agree(panda, source_dir):
    path = os.path.join(str(mjarm.Robot.models_dir()), "panda.xml")
    from_file = mjarm.Robot.from_file(path)
    with open(path) as f:
        from_string = mjarm.Robot.from_string(f.read(), os.path.dirname(path))
    for robot in (from_file, from_string):
        assert (robot.nq, robot.nv, robot.nu) == (panda.nq, panda.nv, panda.nu)
        assert robot.site_names() == panda.site_names()
    assert from_string.source == "<string>"
    assert mjarm.Robot.load("panda").name == panda.name


def test_ids_and_infos(panda):
    joints = panda.joints()
    assert len(joints) == panda.nq
    for j in joints:
        assert panda.joint(j.name) == j.id
        assert panda.joint_info(j.id).name == j.name
    for a in panda.actuators():
        assert panda.actuator(a.name) == a.id
    assert panda.site("attachment_site") >= 0
    assert panda.keyframe("home") == panda.keyframe_names().index("home")


def test_unknown_names_raise_with_close_names(panda):
    for lookup, name in ((panda.joint, "joint_1"), (panda.body, "lnk0"), (panda.actuator, "act"),
                         (panda.keyframe, "hom")):
        with pytest.raises(mjarm.Error, match="not found in model 'panda'"):
            lookup(name)
    with pytest.raises(mjarm.Error):
        mjarm.Robot.from_string("<mujoco><worldbody><body></mujoco>")
    with pytest.raises(mjarm.Error):
        mjarm.Robot.from_file("/nonexistent/model.xml")


def test_newer_mjcf_loads_as_mujoco_loads_it():
    xml = """<mujoco model="m3"><option timestep="0.002" integrator="implicitfast"/>
      <worldbody><body name="b"><joint name="j" type="hinge"/>
      <geom type="capsule" fromto="0 0 0 0 0 .3" size=".02"/><site name="tip" pos="0 0 .3"/>
      </body></worldbody>
      <actuator><position name="a" joint="j" kp="10" kv="1"/></actuator></mujoco>"""
    robot = mjarm.Robot.from_string(xml)
    assert robot.nu == 1
    assert robot.load_warnings == []
    # a position servo with kv: MuJoCo's own gains, the damping in the bias
    assert robot.actuators()[0].kind == mjarm.ActuatorKind.position


def test_owned_data_views_are_writable_and_forward_recomputes(panda):
    data = panda.make_data()
    q = data.qpos
    q[:] = panda.keyframe_qpos("home")
    np.testing.assert_array_equal(data.qpos, panda.keyframe_qpos("home"))
    data.forward()
    assert data.qfrc_bias.shape == (panda.nv,)
    assert np.abs(data.qfrc_bias).max() > 0.1  # gravity on a bent arm


def test_data_view_keeps_its_data_alive(panda):
    view = panda.make_data().qpos  # the Data handle is gone from Python; the view keeps it
    view[:] = 1.0
    assert view.sum() == panda.nq


def test_chain(panda, panda_chain):
    assert len(panda_chain) == 7 and panda_chain.frame.name == "attachment_site"
    explicit = mjarm.Chain(panda, panda_chain.joint_names[:3], "attachment_site")
    assert explicit.size == 3
    qpos = panda.keyframe_qpos("home")
    q = panda_chain.gather(qpos)
    np.testing.assert_array_equal(panda_chain.scatter(q, np.zeros(panda.nq)), qpos)
    assert panda_chain.within_limits(panda_chain.center())
    assert not panda_chain.within_limits(panda_chain.upper + 0.1)
    with pytest.raises(mjarm.Error):
        mjarm.Chain(panda, "no_such_frame")
    with pytest.raises(mjarm.Error):
        mjarm.Chain(panda, ["joint1", "joint1"], "attachment_site")


def test_the_model_size_bound_can_be_raised_and_lowered():
    """issue 29: a 400 000-geom model compiled for minutes; the bound is one setting."""
    assert mjarm.max_model_elements() == 20000
    try:
        mjarm.set_max_model_elements(3)
        with pytest.raises(mjarm.Error, match="more than the 3 a model may have"):
            mjarm.Robot.bundled("planar2")
    finally:
        mjarm.set_max_model_elements(20000)
    assert mjarm.Robot.bundled("planar2").nq == 2
    with pytest.raises(mjarm.Error, match="from 1 to 100000000, got 0"):
        mjarm.set_max_model_elements(0)
