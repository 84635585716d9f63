"""Collision-aware motion from Python: differential-IK constraints, the closed-form 6R IK, Cartesian
paths; each checked against what it promises (distances, forward kinematics, fractions)."""

import numpy as np
import pytest

import mjarm
from conftest import home, rng

# a planar 3-link arm ending in a sphere hand, a wall whose near face is the plane x = 0.48
WALL_ARM = """
<mujoco model="wall_arm">
  <compiler angle="radian"/>
  <worldbody>
    <geom name="wall" type="box" pos="0.5 0 0" size="0.02 0.6 0.3"/>
    <body name="link1">
      <joint name="j1" type="hinge" axis="0 0 1" range="-3 3"/>
      <geom name="link1_geom" type="capsule" fromto="0 0 0 0.3 0 0" size="0.02"/>
      <body name="link2" pos="0.3 0 0">
        <joint name="j2" type="hinge" axis="0 0 1" range="-2.8 2.8"/>
        <geom name="link2_geom" type="capsule" fromto="0 0 0 0.3 0 0" size="0.02"/>
        <body name="hand_body" pos="0.3 0 0">
          <joint name="j3" type="hinge" axis="0 0 1" range="-2.5 2.5"/>
          <geom name="hand" type="sphere" pos="0.05 0 0" size="0.04"/>
          <site name="tip" pos="0.05 0 0"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>"""


def drive_into_wall(with_constraint):
    """Smallest hand-to-wall surface distance while the tip is driven to a target behind the wall."""
    chain = mjarm.Chain(mjarm.Robot.from_string(WALL_ARM), "tip")
    options = mjarm.DiffIkOptions()
    options.dt = 0.01
    options.velocity_limit = [2.0, 2.0, 2.0]
    ik = mjarm.DiffIk(chain, options)
    task = ik.add_position_task("tip", 1.0, 0.5)
    ik.set_target(task, [0.55, 0.15, 0.0])
    avoidance = None
    if with_constraint:
        avoid = mjarm.CollisionAvoidanceOptions()
        avoid.pairs = [("hand", "wall")]
        avoid.min_distance = 0.01
        avoid.detection_distance = 0.1
        avoidance = ik.add_collision_avoidance(avoid)
    q = np.array([-1.2, 2.0, 0.5])
    closest = np.inf
    for _ in range(300):
        q = ik.step(q).q_next
        tip = mjarm.forward_kinematics(chain, q).p
        closest = min(closest, 0.48 - tip[0] - 0.04)  # sphere of 4 cm around the tip
    return closest, ik, avoidance


def test_collision_avoidance_keeps_the_hand_off_the_wall():
    free, _, _ = drive_into_wall(False)
    assert free < -0.01  # without the rows the hand goes into the wall
    kept, ik, avoidance = drive_into_wall(True)
    assert kept >= 0.01 - 1e-3
    assert ik.constraint_count == 1 and isinstance(ik.constraint(0), mjarm.CollisionAvoidance)
    assert avoidance.pair_count == 1
    assert avoidance.min_distance_seen == pytest.approx(kept, abs=2e-3)
    C, b = ik.constraint_matrix, ik.constraint_lower
    assert C.shape == (1, 3) and b.shape == (1,)


def test_configuration_limit_and_barrier_are_added_and_validated(panda_chain):
    ik = mjarm.DiffIk(panda_chain)
    limit = mjarm.ConfigurationLimitOptions()
    limit.margin = 0.1
    assert isinstance(ik.add_configuration_limit(limit), mjarm.ConfigurationLimit)
    barrier = ik.add_manipulability_barrier(mjarm.ManipulabilityBarrierOptions())
    task = ik.add_pose_task()
    X = mjarm.forward_kinematics(panda_chain, home(panda_chain.robot, panda_chain))
    ik.set_target(task, X)
    ik.step(home(panda_chain.robot, panda_chain))
    assert barrier.manipulability > 0.0
    bad = mjarm.ConfigurationLimitOptions()
    with pytest.raises(mjarm.Error, match="gain"):
        bad.gain = 0.0
        ik.add_configuration_limit(bad)
    unknown = mjarm.CollisionAvoidanceOptions()
    unknown.pairs = [("hnad", "link0_c")]
    with pytest.raises(mjarm.Error, match="hnad"):
        ik.add_collision_avoidance(unknown)


def test_analytic_ik_returns_every_branch_of_the_ur5e():
    chain = mjarm.Chain(mjarm.Robot.bundled("ur5e"), "attachment_site")
    assert mjarm.analyze_analytic_ik(chain).solvable
    ik = mjarm.AnalyticIk(chain)
    assert ik.family == mjarm.AnalyticIkFamily.parallel_shoulder
    draw = rng(7)
    for _ in range(20):
        q = draw.uniform(-3.0, 3.0, size=6)
        X = mjarm.forward_kinematics(chain, q)
        solution = ik.solve(X)
        assert solution.status == mjarm.AnalyticIkStatus.solved
        assert 1 <= len(solution) <= 8 and len(solution.branches) == len(solution)
        for branch in solution.branches:
            pos, ang = mjarm.frame_errors(mjarm.forward_kinematics(chain, branch.q), X)
            assert pos < 1e-10 and ang < 1e-10
        k, q_best = ik.closest_to(solution, q, within_limits_only=False)
        assert np.allclose(q_best, q, atol=1e-8)  # the original is a branch


def test_analytic_ik_refuses_the_panda_with_the_reason(panda_chain):
    structure = mjarm.analyze_analytic_ik(panda_chain)
    assert not structure.solvable and "6" in structure.reason
    with pytest.raises(mjarm.Error, match="analytic IK"):
        mjarm.AnalyticIk(panda_chain)


def test_cartesian_path_follows_a_line_and_stops_out_of_reach(panda_chain):
    q0 = home(panda_chain.robot, panda_chain)
    X0 = mjarm.forward_kinematics(panda_chain, q0)
    planner = mjarm.CartesianPathPlanner(panda_chain)
    X1 = X0.copy()
    X1.p = X0.p + [0.0, 0.2, 0.0]
    line = planner.follow(q0, [X1])
    assert line.complete() and line.fraction == 1.0
    assert line.status == mjarm.CartesianPathStatus.complete
    assert line.knots.shape == (7, line.steps + 1)
    for k in range(line.knots.shape[1]):
        p = mjarm.forward_kinematics(panda_chain, line.knots[:, k]).p
        assert abs(p[0] - X0.p[0]) < 1e-4 and abs(p[2] - X0.p[2]) < 1e-4
    far = X0.copy()
    far.p = X0.p + [1.5, 0.0, 0.0]
    # stretched out, σmin falls below its floor before the IK fails: judge reach alone
    reach_only = mjarm.CartesianPathOptions()
    reach_only.checks.min_singular_value = 0.0
    partial = mjarm.CartesianPathPlanner(panda_chain, reach_only).follow(q0, [far])
    assert not partial.complete() and 0.0 < partial.fraction < 1.0
    assert partial.status == mjarm.CartesianPathStatus.partial_ik_failure
    options = mjarm.CartesianPathOptions()
    with pytest.raises(mjarm.Error, match="max_step"):
        options.max_step = 0.0
        mjarm.CartesianPathPlanner(panda_chain, options)


PANDA_WITH_BOX = """<mujoco model="panda_box">
  <compiler angle="radian" autolimits="true"/>
  <include file="common/scene.xml"/>
  <include file="panda/panda_body.xml"/>
  <worldbody><geom name="obstacle" type="box" pos="0.22 0.22 0.55" size="0.08 0.08 0.08"/></worldbody>
  <keyframe><key name="home" qpos="0 -0.785 0 -2.356 0 1.571 0.785"/></keyframe>
</mujoco>"""


def test_ompl_plans_around_a_box_and_times_the_path_optimally():
    robot = mjarm.Robot.from_string(PANDA_WITH_BOX, mjarm.Robot.models_dir())
    chain = mjarm.Chain(robot, "attachment_site")
    start = home(robot, chain)
    goal = start.copy()
    goal[0] = 1.6  # joint 1's swing to the left goes through the box
    options = mjarm.OmplOptions()
    options.planner = mjarm.OmplPlannerType.rrtconnect
    options.time_budget = 20.0
    result = mjarm.OmplPlanner(chain, options).plan(start, goal)
    assert result.ok() and result.status == mjarm.OmplStatus.success, result.message
    assert len(result.path) >= 3 and np.allclose(result.path[-1], goal)
    path = result.time_optimal
    assert isinstance(path, mjarm.TimeOptimalPath) and path.solved()
    assert path.duration < result.trajectory.duration
    q, qd, _ = path.at(path.duration)
    assert np.allclose(q, goal, atol=1e-9) and np.linalg.norm(qd) < 1e-9
    unknown = mjarm.OmplOptions()
    unknown.allowed_collisions = [("obstacel", "link3")]
    with pytest.raises(mjarm.Error, match="obstacel"):
        mjarm.OmplPlanner(chain, unknown)
    with pytest.raises(mjarm.Error, match="time_budget"):
        options.time_budget = 0.0
        mjarm.OmplPlanner(chain, options)


def test_time_optimal_path_of_a_straight_line_is_the_trapezoid():
    path = mjarm.JointPath([[0.0, 0.0], [1.0, 0.0]])
    assert path.length == pytest.approx(1.0)
    timed = mjarm.TimeOptimalPath(path, [0.5, 0.5], [1.0, 1.0])
    assert timed.status == mjarm.ToppStatus.solved
    # 1 rad at 0.5 rad/s with 1 rad/s²: 0.5 s up, 1.5 s cruise, 0.5 s down
    assert 2.5 <= timed.duration <= 2.5 * (1 + 2.0 / 100)
    with pytest.raises(mjarm.Error):
        mjarm.TimeOptimalPath(path, [0.5, -1.0], [1.0, 1.0])
