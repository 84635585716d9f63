"""ik: every solver with its options and IkResult; observers; errors; the GIL released."""

import numpy as np
import pytest

import mjarm
from conftest import home, runs_beside


def reachable_pose(chain, seed):
    rng = np.random.default_rng(seed)
    lo, hi = chain.lower, chain.upper
    q = lo + (hi - lo) * rng.uniform(0.2, 0.8, size=chain.size)
    return mjarm.forward_kinematics(chain, q), q


def test_position_ik_with_centre_pull(panda_chain):
    options = mjarm.PositionIkOptions()
    options.limits = mjarm.LimitBias(0.05, 0.2, 0.15)
    options.tolerance = 1e-5
    ik = mjarm.PositionIk(panda_chain, options)
    assert ik.options.limits.centre_gain == 0.05
    X, _ = reachable_pose(panda_chain, 1)
    result = ik.solve(X.p, home(panda_chain.robot, panda_chain))
    assert result.ok() and result.status == mjarm.IkStatus.converged
    assert result.q.shape == (7,) and result.q.dtype == np.float64
    assert np.linalg.norm(mjarm.forward_kinematics(panda_chain, result.q).p - X.p) <= 1e-5
    assert panda_chain.within_limits(result.q)


def test_pose_ik_and_observer(panda_chain):
    seen = []
    options = mjarm.PoseIkOptions()
    options.posture.gain = 0.1
    options.on_iteration = lambda it, pe, oe, q: seen.append((it, pe, q.copy()))
    assert options.on_iteration is True
    ik = mjarm.PoseIk(panda_chain, options)
    X, _ = reachable_pose(panda_chain, 2)
    result = ik.solve(X, home(panda_chain.robot, panda_chain))
    assert result.ok()
    pos, ang = mjarm.frame_errors(mjarm.forward_kinematics(panda_chain, result.q), X)
    assert pos <= 1e-5 and ang <= 1e-5
    assert [s[0] for s in seen] == list(range(result.iterations + 1))
    np.testing.assert_array_equal(seen[-1][2], result.q)


def test_observer_exception_propagates(panda_chain):
    options = mjarm.PoseIkOptions()

    def observer(it, pe, oe, q):
        if it == 2:
            raise RuntimeError("stop at 2")

    options.on_iteration = observer
    ik = mjarm.PoseIk(panda_chain, options)
    X, _ = reachable_pose(panda_chain, 3)
    with pytest.raises(RuntimeError, match="stop at 2"):
        ik.solve(X, home(panda_chain.robot, panda_chain))
    # the solver is usable afterwards
    options.on_iteration = None
    assert mjarm.PoseIk(panda_chain, options).solve(X, home(panda_chain.robot, panda_chain)).ok()


def test_multi_target_ik(panda, panda_chain):
    X, _ = reachable_pose(panda_chain, 4)
    targets = [mjarm.FrameTarget("attachment_site", mjarm.TargetKind.position, X)]
    ik = mjarm.MultiTargetIk(panda, panda_chain.joint_names, targets)
    result = ik.solve(home(panda, panda_chain))
    assert result.ok()
    assert ik.target_errors(0)[0] <= 1e-5
    with pytest.raises(mjarm.Error):
        mjarm.MultiTargetIk(panda, panda_chain.joint_names, [mjarm.FrameTarget("nope")])


def test_diff_ik_tracks(panda_chain):
    options = mjarm.DiffIkOptions()
    options.dt = 0.01
    options.velocity_limit = np.full(7, 2.0)
    ik = mjarm.DiffIk(panda_chain, options)
    task = ik.add_pose_task("", 1.0, 0.5, 0.5)
    q = home(panda_chain.robot, panda_chain)
    target = mjarm.forward_kinematics(panda_chain, q)
    target.p = target.p + [0.0, 0.05, 0.05]
    ik.set_target(task, target)
    for _ in range(200):
        step = ik.step(q)
        assert np.all(np.abs(step.v) <= 2.0 + 1e-9)
        q = step.q_next
    pos, ang = mjarm.frame_errors(mjarm.forward_kinematics(panda_chain, q), target)
    assert pos < 1e-6 and ang < 1e-6
    with pytest.raises(ValueError, match=r"velocity_limit"):
        options.velocity_limit = np.zeros((2, 2))


def test_global_ik(panda_chain):
    options = mjarm.GlobalIkOptions()
    # the restart cap decides, never the clock: a 50 ms budget failed on a loaded machine
    options.timeout = 60.0
    options.max_restarts = 200
    options.seed = 7
    ik = mjarm.GlobalIk(panda_chain, options)
    X, _ = reachable_pose(panda_chain, 6)
    result = ik.solve(X, panda_chain.center())
    assert result.ok() and ik.stats.attempts >= 1
    result = ik.solve_position(X.p, panda_chain.center())
    assert result.ok()


def test_bad_ik_input(panda_chain):
    ik = mjarm.PositionIk(panda_chain)
    with pytest.raises(ValueError, match=r"p_WT: expected shape \(3,\)"):
        ik.solve(np.zeros(4), panda_chain.center())
    with pytest.raises(ValueError, match=r"q_seed: expected shape \(7,\)"):
        ik.solve(np.zeros(3), np.zeros(6))
    with pytest.raises(TypeError, match="q_seed"):
        ik.solve(np.zeros(3), None)
    with pytest.raises(mjarm.Error):
        ik.solve(np.array([np.nan, 0, 0]), panda_chain.center())
    bad = mjarm.PositionIkOptions()
    bad.max_iterations = 0
    with pytest.raises(mjarm.Error, match="max_iterations"):
        mjarm.PositionIk(panda_chain, bad)


def test_local_solvers_share_one_settings_struct(panda_chain):
    # each solver's options keep their names and tuning on the one shared base
    position = mjarm.PositionIkOptions()
    pose = mjarm.PoseIkOptions()
    multi = mjarm.MultiTargetIkOptions()
    for options in (position, pose, multi):
        assert isinstance(options, mjarm.LocalIkSettings)
        assert options.max_backtracks == 4 and options.stall_progress == 1e-4
    assert (position.damping, position.step, position.stall_iterations) == (0.02, 0.6, 60)
    assert (pose.damping, pose.max_iterations) == (1e-3, 200)
    assert multi.max_iterations == 300 and multi.mode == mjarm.MultiTargetMode.prioritized
    pose.posture.gain = 2.0
    with pytest.raises(mjarm.Error, match=r"pose IK: posture\.gain must be in \[0, 1\], got 2"):
        mjarm.PoseIk(panda_chain, pose)


def test_batched_ik_releases_the_gil(panda_chain):
    targets = np.array([reachable_pose(panda_chain, 100 + i)[0].p for i in range(40)])
    seed = panda_chain.center()
    ik = mjarm.PositionIk(panda_chain)
    results = ik.solve_batch(targets, seed)
    assert len(results) == 40 and sum(r.ok() for r in results) >= 38
    for r, p in zip(results[:5], targets[:5]):
        assert r.position_error == ik.solve(p, seed).position_error
    many = np.repeat(targets, 20, axis=0)
    ran, batch = runs_beside(lambda: ik.solve_batch(many, seed))
    assert ran and len(batch) == 800
