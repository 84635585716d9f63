"""The user's own mujoco.MjModel / mujoco.MjData in mjarm's calls: one MuJoCo library in the
process, no copies, nothing written that a call does not document; errors stay each side's."""
import ctypes
import gc
import json
import os
import shutil
import signal
import subprocess
import sys
import weakref

import mujoco
import numpy as np
import pytest

import mjarm

HERE = os.path.dirname(os.path.abspath(__file__))
GOAL = np.array([0.3, 0.4, -0.6, 0.2, 0.3, -0.2])


def build_arm():
    """A 6-joint arm with torque motors, a tool site, a floor and a free cube, built with
    mujoco.MjSpec (numbers exact in decimal, so the XML round trip compiles the same model)."""
    spec = mujoco.MjSpec()
    spec.modelname = "spec_arm"
    spec.compiler.degree = False
    spec.worldbody.add_geom(name="floor", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[2, 2, 0.1])
    links = [("shoulder_pan", [0, 0, 0.1], [0, 0, 1], 0.1),
             ("shoulder_lift", [0, 0, 0.1], [0, 1, 0], 0.3),
             ("elbow", [0, 0, 0.3], [0, 1, 0], 0.25),
             ("wrist_roll", [0, 0, 0.25], [0, 0, 1], 0.05),
             ("wrist_pitch", [0, 0, 0.05], [0, 1, 0], 0.05),
             ("flange_roll", [0, 0, 0.05], [0, 0, 1], 0.05)]
    body = spec.worldbody
    for name, pos, axis, length in links:
        body = body.add_body(name=name + "_link", pos=pos)
        body.add_joint(name=name, axis=axis, range=[-2.5, 2.5], armature=0.01)
        body.add_geom(type=mujoco.mjtGeom.mjGEOM_CAPSULE, pos=[0, 0, length / 2],
                      size=[0.03, length / 2, 0], contype=0, conaffinity=0)
    body.add_site(name="tool", pos=[0, 0, 0.1])
    for name, *_ in links:
        spec.add_actuator(name=name, target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT,
                          ctrlrange=[-50, 50])
    cube = spec.worldbody.add_body(name="cube", pos=[0.5, 0, 0.025])
    cube.add_freejoint(name="cube_free")
    cube.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.025, 0.025, 0.025])
    return spec


@pytest.fixture(scope="module")
def spec():
    return build_arm()


@pytest.fixture()
def user(spec):
    """The user's model and data, stepped by MuJoCo with some torques, then forward."""
    m = spec.compile()
    d = mujoco.MjData(m)
    d.qpos[:6] = [0.2, 0.5, -1.5, 0.8, 1.2, 0.3]  # away from singularities (the planner's start)
    d.qvel[:6] = np.linspace(-0.3, 0.3, 6)
    d.ctrl[:] = [1.0, 2.0, -1.0, 0.5, 0.2, -0.1]
    for _ in range(10):
        mujoco.mj_step(m, d)
    mujoco.mj_forward(m, d)
    return m, d


@pytest.fixture()
def copy(spec, user):
    """mjarm's own copy of the same model (loaded from the spec's XML) in the user's state."""
    m, d = user
    robot = mjarm.Robot.from_string(spec.to_xml())
    data = robot.make_data()
    data.qpos[:] = d.qpos
    data.qvel[:] = d.qvel
    data.ctrl[:] = d.ctrl
    data.forward()
    return robot, data


def snapshot(obj):
    """Every array of a mujoco struct and its scalars, copied."""
    state = {}
    for name in dir(obj):
        if name.startswith("_"):
            continue
        try:
            value = getattr(obj, name)
        except Exception:  # properties that refuse to be read on this object
            continue
        if isinstance(value, np.ndarray):
            state[name] = value.copy()
        elif isinstance(value, (int, float)):
            state[name] = value
    return state


def assert_unchanged(before, after):
    changed = [k for k in before if not np.array_equal(before[k], after[k], equal_nan=True)]
    assert not changed, f"changed: {changed}"


def joint_reference(q):
    ref = mjarm.Reference()
    ref.joint.q = q
    ref.joint.qd = np.zeros(len(q))
    ref.joint.qdd = np.zeros(len(q))
    return ref


def test_one_mujoco_library_in_the_process():
    with open("/proc/self/maps") as maps:
        libraries = {line.split()[-1] for line in maps if "libmujoco" in line}
    assert len(libraries) == 1, libraries
    assert os.path.dirname(next(iter(libraries))) == os.path.dirname(os.path.realpath(
        mujoco.__file__))


def test_robot_shares_the_users_model(spec):
    m = spec.compile()
    robot = mjarm.Robot(m)
    assert (robot.name, robot.nq, robot.nv, robot.nu) == ("spec_arm", 13, 12, 6)
    assert robot.source == f"mujoco.MjModel at 0x{m._address:x}"
    assert robot.joint("elbow") == mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, "elbow")
    # the same struct, not a copy: an edit of the user's model shows in mjarm's next call
    chain = mjarm.Chain(m, "tool")
    before = mjarm.forward_kinematics(chain, np.zeros(6)).p
    m.site_pos[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_SITE, "tool")] += [0.0, 0.0, 0.05]
    after = mjarm.forward_kinematics(chain, np.zeros(6)).p
    np.testing.assert_allclose(after - before, [0.0, 0.0, 0.05], atol=1e-15)
    # shared ownership: the robot keeps the model alive, and lets it go when it goes
    alive = weakref.ref(m)
    del m
    gc.collect()
    assert alive() is not None and mjarm.Chain(robot, "tool").size == 6
    del robot, chain
    gc.collect()
    assert alive() is None


def test_data_borrows_the_users_data(spec):
    d = mujoco.MjData(spec.compile())
    data = mjarm.Data(d)
    assert data.qpos.ctypes.data == d.qpos.ctypes.data  # a view into the user's struct
    data.qpos[0] = 0.25
    assert d.qpos[0] == 0.25
    alive = weakref.ref(d)
    del d
    gc.collect()
    assert alive() is not None and data.qpos[0] == 0.25
    del data
    gc.collect()
    assert alive() is None


def test_kinematics_and_ik_on_the_users_model_match_a_copy(user, copy):
    m, d = user
    robot, data = copy
    ours, theirs = mjarm.Chain(m, "tool"), mjarm.Chain(robot, "tool")
    assert ours.joint_names == theirs.joint_names and ours.size == 6
    q = ours.gather(d.qpos)
    X = mjarm.forward_kinematics(ours, q)
    np.testing.assert_array_equal(X.matrix(), mjarm.forward_kinematics(theirs, q).matrix())
    # the frame read from the user's data is MuJoCo's own
    tool = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_SITE, "tool")
    X_d = mjarm.frame_pose(m, d, "tool")
    np.testing.assert_allclose(X_d.p, d.site_xpos[tool], atol=1e-14)
    np.testing.assert_allclose(X_d.p, X.p, atol=1e-12)

    target = mjarm.forward_kinematics(ours, GOAL)
    seed = np.zeros(6) + 0.05
    a, b = mjarm.PoseIk(ours).solve(target, seed), mjarm.PoseIk(theirs).solve(target, seed)
    assert a.ok() and b.ok()
    np.testing.assert_array_equal(a.q, b.q)
    pos, ang = mjarm.frame_errors(mjarm.forward_kinematics(ours, a.q), target)
    assert pos <= 1e-5 and ang <= 1e-5

    def track(chain):
        options = mjarm.DiffIkOptions()
        options.dt = 0.01
        ik = mjarm.DiffIk(chain, options)
        task = ik.add_pose_task("", 1.0, 0.5, 0.5)
        goal = mjarm.forward_kinematics(chain, q)
        goal.p = goal.p + [0.0, 0.03, -0.02]
        ik.set_target(task, goal)
        qs = q.copy()
        for _ in range(50):
            qs = ik.step(qs).q_next
        return qs
    np.testing.assert_array_equal(track(ours), track(theirs))


def test_controller_planner_and_monitor_read_the_users_data(user, copy):
    m, d = user
    robot, data = copy
    before_data, before_model = snapshot(d), snapshot(m)
    ours, theirs = mjarm.Chain(m, "tool"), mjarm.Chain(robot, "tool")
    ref = joint_reference(GOAL)
    ref.task.X_WE = mjarm.forward_kinematics(ours, GOAL)
    for make in (mjarm.ComputedTorqueController, mjarm.JointPdController,
                 mjarm.OperationalSpaceController):
        np.testing.assert_array_equal(make(ours).compute(d, ref), make(theirs).compute(data, ref))

    dyn_ours, dyn_theirs = mjarm.ChainDynamics(ours), mjarm.ChainDynamics(theirs)
    dyn_ours.update(d)
    dyn_theirs.update(data)
    np.testing.assert_array_equal(dyn_ours.mass_matrix, dyn_theirs.mass_matrix)
    np.testing.assert_array_equal(dyn_ours.bias, d.qfrc_bias[:6])
    tau = np.linspace(-1.0, 1.0, 6)
    obs_ours, obs_theirs = mjarm.MomentumObserver(ours), mjarm.MomentumObserver(theirs)
    for _ in range(3):
        assert obs_ours.update(d, dyn_ours, tau, 0.002) == mjarm.ObserverStatus.ok
        obs_theirs.update(data, dyn_theirs, tau, 0.002)
    np.testing.assert_array_equal(obs_ours.residual, obs_theirs.residual)
    np.testing.assert_array_equal(mjarm.free_pose(m, d, "cube").p_WB,
                                  mjarm.free_pose(robot, data, "cube").p_WB)

    q0 = ours.gather(d.qpos)
    X0 = mjarm.forward_kinematics(ours, q0)
    waypoint = X0.copy()
    waypoint.p = X0.p + [0.02, 0.0, -0.02]
    plan_ours = mjarm.WaypointPlanner(ours).plan(q0, [waypoint])
    plan_theirs = mjarm.WaypointPlanner(theirs).plan(q0, [waypoint])
    assert plan_ours.ok(), plan_ours.message
    assert plan_ours.trajectory.duration == plan_theirs.trajectory.duration
    for t in np.linspace(0.0, plan_ours.trajectory.duration, 7):
        np.testing.assert_array_equal(plan_ours.trajectory.at(t)[0],
                                      plan_theirs.trajectory.at(t)[0])

    # none of these calls wrote the user's data or model
    assert_unchanged(before_data, snapshot(d))
    assert_unchanged(before_model, snapshot(m))


def test_writes_only_what_the_call_documents(user):
    m, d = user
    before = snapshot(d)
    mjarm.set_free_pose(m, d, "cube", [0.4, 0.1, 0.3])
    after = snapshot(d)
    cube = m.jnt_qposadr[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, "cube_free")]
    np.testing.assert_array_equal(d.qpos[cube:cube + 7], [0.4, 0.1, 0.3, 1.0, 0.0, 0.0, 0.0])
    expected_qpos = before["qpos"].copy()
    expected_qpos[cube:cube + 7] = [0.4, 0.1, 0.3, 1.0, 0.0, 0.0, 0.0]
    np.testing.assert_array_equal(after.pop("qpos"), expected_qpos)
    before.pop("qpos")
    assert_unchanged(before, after)
    # Data.forward is mj_forward on the user's struct: what MuJoCo itself computes
    reference = mujoco.MjData(m)
    reference.qpos[:], reference.qvel[:], reference.ctrl[:] = d.qpos, d.qvel, d.ctrl
    mujoco.mj_forward(m, reference)
    mjarm.Data(d).forward()
    np.testing.assert_array_equal(d.xpos, reference.xpos)
    np.testing.assert_array_equal(d.qacc, reference.qacc)


def test_data_of_another_model_is_refused(spec, user, copy):
    m, d = user
    robot, data = copy
    other = spec.compile()  # the same spec compiled again: another model, same name
    d_other = mujoco.MjData(other)
    chain = mjarm.Chain(m, "tool")
    ref = joint_reference(GOAL)
    address = f"0x{m._address:x}"
    other_address = f"0x{other._address:x}"
    calls = [
        lambda: mjarm.frame_pose(m, d_other, "tool"),
        lambda: mjarm.ComputedTorqueController(chain).compute(d_other, ref),
        lambda: mjarm.ChainDynamics(chain).update(d_other),
        lambda: mjarm.free_pose(m, d_other, "cube"),
        lambda: mjarm.set_free_pose(m, d_other, "cube", [0.0, 0.0, 0.1]),
    ]
    for call in calls:
        with pytest.raises(mjarm.Error, match="belongs to model") as error:
            call()
        text = str(error.value)
        # both models named: the user's two MjModels share a name, their addresses tell them apart
        assert other_address in text and address in text and "'spec_arm'" in text, text
    with pytest.raises(mjarm.Error, match=r"model 'spec_arm' \(<string>\)") as error:
        mjarm.ComputedTorqueController(chain).compute(data, ref)
    assert address in str(error.value)
    with pytest.raises(mjarm.Error, match=f"mujoco.MjModel at {address}"):
        mjarm.ComputedTorqueController(mjarm.Chain(robot, "tool")).compute(d, ref)
    before = snapshot(d_other)
    with pytest.raises(mjarm.Error):
        mjarm.set_free_pose(m, d_other, "cube", [0.0, 0.0, 0.1])
    assert_unchanged(before, snapshot(d_other))


class LookAlike:
    """Has what a careless check would look at (an _address, a model), and is no MuJoCo object."""

    def __init__(self, target):
        self._address = target._address
        self.model = getattr(target, "model", None)


def test_foreign_objects_are_type_errors(spec, user):
    m, d = user
    for bad in (42, m._address, LookAlike(m), d, spec, "spec_arm", None):
        with pytest.raises(TypeError, match="expected a mujoco.MjModel, got"):
            mjarm.Robot(bad)
    for bad in (42, d._address, LookAlike(d), m, None):
        with pytest.raises(TypeError, match="expected a mujoco.MjData, got"):
            mjarm.Data(bad)
    chain = mjarm.Chain(m, "tool")
    controller = mjarm.ComputedTorqueController(chain)
    with pytest.raises(TypeError, match=r"data: mjarm\._mjarm\.Data \| mujoco\.MjData"):
        controller.compute(LookAlike(d), joint_reference(GOAL))
    with pytest.raises(TypeError, match=r"robot: mjarm\._mjarm\.Robot \| mujoco\.MjModel"):
        mjarm.Chain(LookAlike(m), "tool")
    with pytest.raises(TypeError, match=r"mujoco\.MjModel"):
        mjarm.frame_pose(d, d, "tool")


def test_lent_data_is_refused_after_its_call(user):
    m, d = user
    chain = mjarm.Chain(m, "tool")
    kept = []

    class Keeper(mjarm.Controller):
        def __init__(self):
            mjarm.Controller.__init__(self, chain, mjarm.CommandKind.torque, "keeper")

        def compute(self, data, reference):
            kept.append(data)
            return np.zeros(6)

    sim = mjarm.Simulation(m)
    sim.add_controller(Keeper())
    sim.tick(joint_reference(GOAL))
    assert kept and not kept[0].valid
    with pytest.raises(mjarm.Error, match="lent for one call"):
        kept[0].qpos
    with pytest.raises(mjarm.Error, match="lent for one call"):
        mjarm.frame_pose(m, kept[0], "tool")


def test_an_error_inside_a_mujoco_call_is_mujocos(user):
    m, _ = user
    with pytest.raises(mujoco.FatalError, match="seq must contain exactly 3 characters"):
        mujoco.mju_euler2Quat(np.zeros(4), np.zeros(3), "xy")
    full = mujoco.MjData(m)
    full.pstack = full.narena
    with pytest.raises(mujoco.FatalError, match="mj_stackAlloc: out of memory"):
        mujoco.mj_forward(m, full)


def test_an_error_inside_an_mjarm_call_is_mjarm_error(user):
    m, _ = user
    full = mujoco.MjData(m)
    full.pstack = full.narena
    with pytest.raises(mjarm.Error, match="MuJoCo error: mj_stackAlloc: out of memory"):
        mjarm.Data(full).forward()
    # the handlers still tell the two apart afterwards
    full.pstack = full.narena
    with pytest.raises(mujoco.FatalError):
        mujoco.mj_forward(m, full)


def run_python(code, env=None):
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=env)


def test_an_error_mujoco_does_not_catch_ends_the_process_as_without_mjarm():
    # mujoco 4.0.1's mj_setState has no error interception: MuJoCo's default handler prints the
    # error and exits with 1. With mjarm loaded that stays so (a C++ exception thrown through
    # mujoco's extension would crash the process instead).
    code = ("import mujoco, mjarm, numpy as np\n"
            "m = mujoco.MjModel.from_xml_string('<mujoco><worldbody><body><joint/>"
            "<geom size=\".1\"/></body></worldbody></mujoco>')\n"
            "d = mujoco.MjData(m)\n"
            "sig = 2 ** mujoco.mjtState.mjNSTATE.value\n"
            "try:\n"
            "    mujoco.mj_setState(m, d, np.zeros(mujoco.mj_stateSize(m, 1)), sig)\n"
            "except mujoco.FatalError as e:\n"
            "    print('FatalError', e)\n")
    out = run_python(code)
    assert out.returncode in (0, 1), (out.returncode, out.stdout, out.stderr)
    assert "invalid state signature" in out.stdout + out.stderr
    if out.returncode == 0:  # a later mujoco that intercepts it raises its own error
        assert out.stdout.startswith("FatalError")


def test_a_mujoco_package_of_another_version_is_refused_at_import():
    code = ("import mujoco\n"
            "mujoco.__version__ = '9.9.9'\n"
            "try:\n"
            "    import mjarm\n"
            "except ImportError as e:\n"
            "    print(e)\n"
            "else:\n"
            "    print('imported')\n")
    out = run_python(code)
    assert out.returncode == 0, out.stderr
    assert "built against MuJoCo " + mujoco.__version__ in out.stdout, out.stdout
    assert "9.9.9" in out.stdout and f"pip install mujoco=={mujoco.__version__}" in out.stdout


def version_shim():
    path = os.environ.get("MJARM_MUJOCO_VERSION_SHIM") or os.path.join(
        os.path.dirname(os.path.dirname(os.path.dirname(mjarm.__file__))), "tests",
        "mujoco_version_shim.so")
    assert os.path.exists(path), f"{path} missing: build the target mjarm_mujoco_version_shim"
    return path


def preloading(shim):
    env = dict(os.environ)
    # after what is already preloaded (the sanitizer runtime comes first in a sanitized build)
    env["LD_PRELOAD"] = ":".join(p for p in (env.get("LD_PRELOAD"), shim) if p)
    env["ASAN_OPTIONS"] = "detect_leaks=0"
    return env


def test_a_mujoco_library_of_another_version_is_refused_at_import_and_at_start():
    env = preloading(version_shim())
    out = run_python("import mjarm", env)
    assert out.returncode != 0
    assert "ImportError" in out.stderr and "version 3.3.6" in out.stderr, out.stderr
    assert "compiled with MuJoCo " + mujoco.__version__ in out.stderr, out.stderr
    from mjarm.__main__ import cli_path
    cli = subprocess.run([cli_path(), "models"], capture_output=True, text=True, env=env)
    assert cli.returncode == 1, (cli.stdout, cli.stderr)
    assert "version 3.3.6" in cli.stderr and "compiled with MuJoCo " + mujoco.__version__ in (
        cli.stderr), cli.stderr


# ---------------------------------------------------------------------------------------------
# mujoco.viewer.launch_passive under a virtual X server of the test's own

VIEWER_LOOP = r"""
import json, sys, threading
import numpy as np
import mujoco, mujoco.viewer
import mjarm
sys.path.insert(0, {here!r})
from test_mujoco_interop import GOAL, build_arm, joint_reference

m = build_arm().compile()
d = mujoco.MjData(m)
chain = mjarm.Chain(m, "tool")
controller = mjarm.ComputedTorqueController(chain)
reference = joint_reference(GOAL)
command = np.zeros(chain.size)
actuators = [chain.actuator(i) for i in range(chain.size)]
steps = 0
with mujoco.viewer.launch_passive(m, d, show_left_ui=False, show_right_ui=False) as viewer:
    for _ in range({steps}):
        # MuJoCo's control pattern: positions and velocities first, then the command, then the rest
        mujoco.mj_step1(m, d)
        controller.compute(d, reference, command)
        d.ctrl[actuators] = command
        mujoco.mj_step2(m, d)
        viewer.sync()
        steps += 1
    running = viewer.is_running()
# closing asks the viewer's thread to stop; the process must not exit while it still renders
for thread in threading.enumerate():
    if thread is not threading.main_thread():
        thread.join()
print(json.dumps({{"steps": steps, "running": running,
                  "error": float(np.max(np.abs(chain.gather(d.qpos) - GOAL))),
                  "speed": float(np.max(np.abs(d.qvel[:6])))}}))
"""


@pytest.fixture()
def virtual_display(tmp_path):
    """Debian's Xvfb on a display it picks itself (-displayfd), stopped by its pid at the end."""
    xvfb = shutil.which("Xvfb")
    assert xvfb, "no Xvfb on PATH: scripts/setup.sh installs Debian's xvfb"
    libc = ctypes.CDLL(None, use_errno=True)

    def die_with_the_test():
        libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG

    ready_read, ready_write = os.pipe()
    log = open(tmp_path / "xvfb.log", "wb")
    server = subprocess.Popen(
        [xvfb, "-displayfd", str(ready_write), "-screen", "0", "1024x768x24", "-nolisten", "tcp"],
        pass_fds=(ready_write,), stdout=log, stderr=subprocess.STDOUT, start_new_session=True,
        preexec_fn=die_with_the_test)
    os.close(ready_write)
    try:
        with os.fdopen(ready_read, "rb") as ready:
            number = ready.readline().strip()  # written once the server accepts connections
        assert number, "Xvfb exited before reporting a display: " + (
            tmp_path / "xvfb.log").read_text(errors="replace")
        yield ":" + number.decode()
    finally:
        server.terminate()
        server.wait()
        log.close()


def test_an_mjarm_controller_drives_the_arm_in_mujocos_passive_viewer(virtual_display):
    env = dict(os.environ, DISPLAY=virtual_display, MUJOCO_GL="glfw")
    out = run_python(VIEWER_LOOP.format(here=HERE, steps=600), env)
    assert out.returncode == 0, out.stderr
    result = json.loads(out.stdout.strip().splitlines()[-1])
    assert result["steps"] == 600 and result["running"], result
    assert result["error"] < 1e-3 and result["speed"] < 1e-2, result
