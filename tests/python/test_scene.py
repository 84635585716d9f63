"""Scenes from Python: specs built by keyword with their arrays checked, composing robots, a
gripper, objects, fixtures, sensors and welds, find and edit, compile, scene files, free poses,
and every refused input with the library's message."""
import copy
import os

import numpy as np
import pytest

import mjarm


def pick_scene():
    """docs/scene.md's scene: panda + franka_hand on a table, a cube, a sensor, a weld."""
    scene = mjarm.Scene("pick")
    scene.add_arena(table=True)
    scene.add_robot(name="panda", model="panda", pos=[0.12, 0, 0.4])
    scene.attach_gripper(robot="panda", model="franka_hand", frame="attachment_site", name="hand")
    scene.add_object(name="cube", size=[0.0075, 0.0075, 0.0075], pos=[0.5, 0.1, 0.4075])
    scene.add_sensor(name="cube_pos", type="framepos", target="cube")
    scene.add_weld(name="grasp", body1="panda/hand/hand", body2="cube")
    return scene


def test_specs_take_keywords_and_give_float64_arrays():
    spec = mjarm.ObjectSpec(name="cube", shape="cylinder", size=[0.01, 0.02], mass=0.05)
    assert spec.shape == mjarm.ObjectShape.cylinder and spec.mass == 0.05
    for name, shape in (("pos", (3,)), ("quat", (4,)), ("friction", (3,)), ("rgba", (4,)),
                        ("size", (2,))):
        value = getattr(spec, name)
        assert value.dtype == np.float64 and value.shape == shape, name
    spec.pos = (1, 2, 3)  # any array-like of numbers, ints converted
    assert spec.pos.tolist() == [1.0, 2.0, 3.0]
    spec.shape = mjarm.ObjectShape.box
    assert spec.shape == mjarm.ObjectShape.box
    assert mjarm.WeldSpec().solref.tolist() == [0.002, 1.0]
    assert mjarm.ArenaSpec().floor_half_size.shape == (2,)
    assert mjarm.SceneCameraSpec().xyaxes.shape == (6,)
    assert mjarm.FreePose().quat_WB.tolist() == [1.0, 0.0, 0.0, 0.0]


def test_spec_fields_refuse_bad_input():
    spec = mjarm.ObjectSpec()
    with pytest.raises(ValueError, match=r"pos: expected shape \(3,\), got \(2,\)"):
        spec.pos = [1.0, 2.0]
    with pytest.raises(ValueError, match=r"quat: expected shape \(4,\), got \(2, 2\)"):
        spec.quat = np.eye(2)
    with pytest.raises(TypeError, match="pos: expected a float64 array of shape \\(3,\\), got None"):
        spec.pos = None
    with pytest.raises(ValueError, match="dtype"):
        spec.rgba = np.array(["a", "b", "c", "d"])
    with pytest.raises(TypeError, match="no field 'colour'"):
        mjarm.ObjectSpec(colour=[1, 0, 0, 1])
    with pytest.raises(mjarm.Error, match="unknown object shape 'cilinder'; closest: cylinder"):
        spec.shape = "cilinder"
    with pytest.raises(TypeError, match="shape: expected a name or an enum value, got None"):
        spec.shape = None
    with pytest.raises(mjarm.Error, match="unknown sensor type"):
        mjarm.SensorSpec(type="framepoz")
    # a non-contiguous array is copied, never read with the wrong strides
    column = np.arange(12.0).reshape(3, 4)[:, 1]
    spec.pos = column
    assert spec.pos.tolist() == [1.0, 5.0, 9.0]


def test_a_composed_scene_compiles_with_prefixed_names():
    scene = pick_scene()
    travel = [0.0, 0.012]
    scene.set_attribute("actuator", "panda/hand/finger_left", "ctrlrange", travel)
    assert scene.attribute("actuator", "panda/hand/finger_left", "ctrlrange") == "0 0.012"
    robot = scene.compile()
    assert robot.nq == 7 + 2 + 7 and robot.nv == 7 + 2 + 6
    assert scene.has("joint", "panda/joint1") and scene.has("geom", "cube/geom")
    assert scene.has("site", "arena/table_surface") and scene.has("equality", "grasp")
    assert "panda/hand/tcp" in scene.names("site")
    assert robot.body("cube") >= 0 and robot.joint("cube/joint") >= 0
    assert scene.name == "pick" and isinstance(scene.warnings, list)
    assert "<mujoco" in scene.xml()
    assert "franka_hand" in mjarm.Scene.bundled_grippers()
    # the keyframe home combines the parts: the cube keeps its initial pose
    home = robot.keyframe_qpos("home")
    assert home.shape == (16,)
    assert np.allclose(home[9:12], [0.5, 0.1, 0.4075])


def test_fixtures_cameras_sites_and_a_compound_fixture():
    scene = mjarm.Scene("parts")
    scene.add_arena()
    scene.add_fixture(mjarm.ObjectSpec(name="bin", size=[0.08, 0.08, 0.005], pos=[0.4, 0, 0.005]))
    pieces = [mjarm.ObjectSpec(name=f"wall{i}", size=[0.01, 0.05, 0.02],
                               pos=[0.05 * (1 if i else -1), 0, 0.02]) for i in range(2)]
    scene.add_fixture(mjarm.CompoundFixtureSpec(name="slot", pos=[0, 0.5, 0], pieces=pieces))
    scene.add_site(name="target", pos=[0.4, 0, 0.02], size=0.01)
    scene.add_camera(name="front", pos=[1.5, 0, 1], xyaxes=[0, 1, 0, -0.5, 0, 0.8])
    robot = scene.compile()
    assert robot.nq == 0
    assert scene.has("geom", "slot/wall0") and scene.has("geom", "slot/wall1")
    assert robot.camera("front") >= 0 and robot.site("target") >= 0


def test_copies_are_independent():
    scene = pick_scene()
    other = scene.copy()
    other.add_object(name="ball", shape="sphere", size=[0.02])
    assert other.has("body", "ball") and not scene.has("body", "ball")
    third = copy.deepcopy(scene)
    assert third.names("body") == scene.names("body")


def test_refused_parts_name_the_problem_and_leave_the_scene_unchanged():
    scene = pick_scene()
    before = scene.names("body")
    with pytest.raises(mjarm.Error, match=r"unknown robot 'pandahand'; closest: .*panda"):
        scene.add_robot(name="arm2", model="pandahand")
    with pytest.raises(mjarm.Error, match="robot name 'panda' is used twice"):
        scene.add_robot(name="panda", model="panda")
    with pytest.raises(mjarm.Error, match="unknown attachment frame 'attachment_sit'.*closest: "
                                          "attachment_site"):
        scene.attach_gripper(robot="panda", model="franka_hand", frame="attachment_sit",
                             name="hand2")
    with pytest.raises(mjarm.Error, match="name clash"):
        scene.add_object(name="cube")
    with pytest.raises(mjarm.Error, match=r"size expects 3 value\(s\)"):
        scene.add_object(name="flat", size=[0.01, 0.02])
    with pytest.raises(mjarm.Error, match="mass must be positive"):
        scene.add_object(name="heavy", mass=-1.0)
    with pytest.raises(mjarm.Error, match="weld 'w' body2: no body named 'cub'.*closest: cube"):
        scene.add_weld(name="w", body1="panda/hand/hand", body2="cub")
    with pytest.raises(mjarm.Error, match="does not exist"):
        scene.add_object(name="mug", shape="mesh", mesh_file="no_such_dir/mug.stl")
    with pytest.raises(mjarm.Error, match="closest"):
        scene.attribute("geom", "cube/gem", "size")
    assert scene.names("body") == before
    # values are read when they are set; what only MuJoCo judges fails at compile
    with pytest.raises(mjarm.Error, match="geom 'cube/geom': size expects numbers, got 'not a"):
        scene.set_attribute("geom", "cube/geom", "size", "not a number")
    with pytest.raises(mjarm.Error, match="no attribute 'frction'; closest: friction"):
        scene.set_attribute("geom", "cube/geom", "frction", 1.0)
    scene.set_attribute("geom", "cube/geom", "size", [-0.01, 0.01, 0.01])
    with pytest.raises(mjarm.Error, match="scene 'pick' does not compile"):
        scene.compile()


def test_none_and_wrong_types_where_a_spec_is_required():
    scene = mjarm.Scene()
    with pytest.raises(TypeError, match="add_robot: expected RobotSpec or its fields as "
                                        "keywords, got None"):
        scene.add_robot(None)
    with pytest.raises(TypeError, match="add_object: expected ObjectSpec, got RobotSpec"):
        scene.add_object(mjarm.RobotSpec(name="x", model="panda"))
    with pytest.raises(TypeError):
        scene.has(None, "x")


def test_scene_files(source_dir, tmp_path):
    scene = mjarm.load_scene_file(os.path.join(source_dir, "models", "scenes", "pick_table.yaml"))
    robot = scene.compile()
    assert robot.nq == 23 and robot.nu == 9
    assert mjarm.is_scene_file("a.yaml") and not mjarm.is_scene_file("a.xml")
    text = "name: s\nobjects:\n  - {name: cube, mass: heavy}\n"
    with pytest.raises(mjarm.Error, match=r"s.yaml:3: key 'mass' in object 'cube' expects a number"):
        mjarm.parse_scene(text, str(tmp_path), "s.yaml")
    with pytest.raises(mjarm.Error, match="unknown key 'frction'.*closest: friction"):
        mjarm.parse_scene("objects:\n  - {name: c, frction: 1}\n", str(tmp_path), "f.yaml")
    # issue 29: a second document, a degenerate frame, the extension's case
    with pytest.raises(mjarm.Error, match="s.yaml:3: a second document starts here"):
        mjarm.parse_scene("name: a\n---\nname: b\n", str(tmp_path), "s.yaml")
    with pytest.raises(mjarm.Error, match="camera 'c': xyaxes has a zero x axis"):
        mjarm.parse_scene("cameras:\n  - {name: c, xyaxes: [0, 0, 0, 0, 0, 0]}\n", str(tmp_path),
                          "s.yaml")
    with pytest.raises(mjarm.Error, match="camera 'c': xyaxes has its y axis parallel"):
        mjarm.Scene("x").add_camera(name="c", xyaxes=[0, 1, 0, 0, 2, 0])
    assert mjarm.is_scene_file("a.YAML") and mjarm.is_scene_file("a.Json")


def test_free_pose_round_trip_and_refusals(panda_torque):
    scene = pick_scene()
    robot = scene.compile()
    data = robot.make_data()
    mjarm.set_free_pose(robot, data, "cube", [0.5, 0.1, 0.45], [2.0, 0.0, 0.0, 0.0])
    data.forward()
    pose = mjarm.free_pose(robot, data, "cube")
    assert pose.p_WB.tolist() == [0.5, 0.1, 0.45]
    assert pose.quat_WB.tolist() == [1.0, 0.0, 0.0, 0.0]  # normalized
    address = mjarm.free_qpos_address(robot, "cube")
    assert np.allclose(data.qpos[address:address + 3], [0.5, 0.1, 0.45])
    with pytest.raises(mjarm.Error, match="no body or joint|closest"):
        mjarm.set_free_pose(robot, data, "cub", [0, 0, 0])
    with pytest.raises(ValueError, match=r"p_WB: expected shape \(3,\), got \(2,\)"):
        mjarm.set_free_pose(robot, data, "cube", [0, 0])
    with pytest.raises(TypeError, match="p_WB"):
        mjarm.set_free_pose(robot, data, "cube", None)
    with pytest.raises(mjarm.Error, match=r"belongs to model 'panda_torque'.*robot's model 'pick'"):
        mjarm.set_free_pose(robot, panda_torque.make_data(), "cube", [0, 0, 0])
    sim = mjarm.Simulation(robot)
    with pytest.raises(mjarm.Error, match="Simulation.set_state"):
        mjarm.set_free_pose(robot, sim.data, "cube", [0, 0, 0])


def test_any_element_is_added_by_its_tag_and_attributes():
    """The textbook two-link planar arm, element by element (dm_control's mjcf job)."""
    scene = mjarm.Scene("planar")
    scene.add("default", "link", attributes={"geom.type": "capsule", "geom.size": 0.02,
                                             "joint.axis": [0, 0, 1]})
    scene.add("body", "link1")
    scene.add("joint", "shoulder", "link1", class_name="link")
    scene.add("geom", "upper", "link1", class_name="link", fromto=[0, 0, 0, 0.3, 0, 0])
    scene.add("body", "link2", "link1", pos=[0.3, 0, 0])
    scene.add("joint", "elbow", "link2", class_name="link")
    scene.add("geom", "fore", "link2", class_name="link", fromto="0 0 0 0.3 0 0")
    scene.add("site", "tip", "link2", pos=(0.3, 0, 0))
    scene.add("motor", "shoulder_motor", joint="shoulder", gear=2, ctrlrange=[-1, 1])
    scene.add("jointpos", "elbow_angle", joint="elbow")
    robot = scene.compile()
    data = robot.make_data()
    data.qpos[:] = [0.0, np.pi / 4]
    data.forward()
    tip = data.named.site_xpos["tip"]
    np.testing.assert_allclose(tip, [0.512132, 0.212132, 0.0], atol=5e-7)
    assert data.named.sensordata["elbow_angle"][0] == pytest.approx(np.pi / 4)
    assert 'name="shoulder_motor"' in scene.xml()
    before = scene.xml()
    with pytest.raises(mjarm.Error, match="closest: geom"):
        scene.add("gemo", "x", "link1")
    with pytest.raises(mjarm.Error, match="closest: size"):
        scene.add("geom", "g", "link1", szie=0.1)
    with pytest.raises(mjarm.Error, match="closest: link1, link2"):
        scene.add("site", "s", "link3")
    assert scene.xml() == before
