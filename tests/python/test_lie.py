"""lie: exp/log round trips, Adjoint, dexp family against finite differences, pose errors."""
import numpy as np
import pytest

import mjarm
from mjarm import se3, so3


def random_twists(count, seed=3):
    rng = np.random.default_rng(seed)
    for _ in range(count):
        xi = rng.normal(size=6)
        xi[3:] *= 2.5 / max(np.linalg.norm(xi[3:]), 1e-9) * rng.uniform(0.0, 1.0)
        yield xi


def test_exp_log_round_trip():
    for xi in random_twists(20):
        np.testing.assert_allclose(se3.log(se3.exp(xi)), xi, atol=1e-12)
        np.testing.assert_allclose(so3.log(so3.exp(xi[3:])), xi[3:], atol=1e-12)
        R = so3.exp(xi[3:])
        np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-14)


def test_adjoint_maps_twists_like_conjugation():
    for xi, eta in zip(random_twists(10, 1), random_twists(10, 2)):
        X = se3.exp(xi)
        M = X.matrix()
        lhs = se3.hat(se3.adjoint(X) @ eta)
        rhs = M @ se3.hat(eta) @ np.linalg.inv(M)
        np.testing.assert_allclose(lhs, rhs, atol=1e-12)
        np.testing.assert_allclose(se3.transform_twist(X, eta), se3.adjoint(X) @ eta, atol=1e-12)
        # power is frame independent
        F = eta
        assert np.isclose(se3.transform_wrench(X, F) @ se3.transform_twist(X, xi), F @ xi)


def test_left_jacobian_against_finite_differences():
    h = 1e-6
    for xi in random_twists(5, 7):
        J = se3.left_jacobian(xi)
        X = se3.exp(xi)
        for k in range(6):
            d = np.zeros(6)
            d[k] = h
            # exp(xi + d) ~ exp(Jl d) exp(xi)
            diff = se3.log(se3.exp(xi + d) * X.inverse()) / h
            np.testing.assert_allclose(diff, J[:, k], atol=1e-5)
        np.testing.assert_allclose(se3.left_jacobian_inverse(xi) @ J, np.eye(6), atol=1e-10)
        np.testing.assert_allclose(se3.right_jacobian(xi), se3.left_jacobian(-xi), atol=1e-14)


def test_jacobian_derivative_against_finite_differences():
    h = 1e-6
    for xi, xi_dot in zip(random_twists(4, 11), random_twists(4, 12)):
        numeric = (se3.left_jacobian(xi + h * xi_dot) - se3.left_jacobian(xi - h * xi_dot)) / (2 * h)
        np.testing.assert_allclose(se3.left_jacobian_derivative(xi, xi_dot), numeric, atol=1e-7)
        w, wd = xi[3:], xi_dot[3:]
        numeric = (so3.left_jacobian_inverse(w + h * wd) - so3.left_jacobian_inverse(w - h * wd)) / (2 * h)
        np.testing.assert_allclose(so3.left_jacobian_inverse_derivative(w, wd), numeric, atol=1e-7)


def test_inverse_jacobian_domain_is_checked():
    with pytest.raises(mjarm.Error, match="2"):
        so3.left_jacobian_inverse(np.array([0.0, 0.0, 7.0]))


def test_pose_api_and_errors():
    X = mjarm.Pose.from_rpy([0.1, 0.2, 0.3], [0.3, -0.2, 0.1])
    np.testing.assert_allclose(X.rpy(), [0.3, -0.2, 0.1], atol=1e-14)
    Y = mjarm.Pose.from_quaternion([0.1, 0.2, 0.3], X.quaternion())
    assert X.is_approx(Y, 1e-12)
    assert (X * X.inverse()).is_approx(mjarm.Pose.identity(), 1e-14)
    np.testing.assert_allclose(X.act([1.0, 0.0, 0.0]), X.R @ [1, 0, 0] + X.p)
    np.testing.assert_allclose(mjarm.Pose.from_matrix(X.matrix()).p, X.p)
    e = mjarm.log_error(X, X * se3.exp(np.array([0.01, 0, 0, 0, 0, 0.02])))
    np.testing.assert_allclose(e, [0.01, 0, 0, 0, 0, 0.02], atol=1e-14)
    # a 4x4 matrix is accepted wherever a Pose is
    np.testing.assert_allclose(mjarm.log_error(X.matrix(), X.matrix()), np.zeros(6), atol=1e-14)
    pos, ang = mjarm.frame_errors(X, mjarm.Pose())
    assert pos == pytest.approx(np.linalg.norm(X.p))
    with pytest.raises(mjarm.Error, match="quaternion"):
        mjarm.Pose.from_quaternion([0, 0, 0], [0, 0, 0, 0])


def test_non_finite_arguments_are_refused():
    """issue 29: se3.exp(NaN) returned a NaN pose without an error."""
    nan6 = [0.1, 0.2, float("nan"), 0.0, 0.0, 0.0]
    with pytest.raises(mjarm.Error, match="xi holds nan at entry 2; expected finite numbers"):
        se3.exp(nan6)
    with pytest.raises(mjarm.Error, match="w holds inf at entry 0"):
        so3.exp([float("inf"), 0.0, 0.0])
    with pytest.raises(mjarm.Error, match="xi holds nan"):
        se3.left_jacobian(nan6)
    bad = np.eye(4)
    bad[1, 3] = float("nan")
    with pytest.raises(mjarm.Error, match=r"X holds nan at \(1, 3\)"):
        se3.log(bad)
    with pytest.raises(mjarm.Error, match="M holds nan"):
        mjarm.Pose.from_matrix(bad)
    with pytest.raises(mjarm.Error, match="rpy holds nan"):
        mjarm.Pose.from_rpy([0, 0, 0], [0, float("nan"), 0])
    with pytest.raises(mjarm.Error, match="p holds nan"):
        mjarm.Pose(np.eye(3), [float("nan"), 0, 0])
    pose = mjarm.Pose()
    with pytest.raises(mjarm.Error, match="R holds nan"):
        pose.R = np.full((3, 3), float("nan"))
    with pytest.raises(mjarm.Error, match="q_wxyz holds nan"):
        mjarm.rotation_from_quaternion([float("nan"), 0, 0, 1])
    with pytest.raises(mjarm.Error, match="X_WT holds nan"):
        mjarm.log_error(mjarm.Pose(), bad)
