"""kinematics: FK against MuJoCo, Jacobians against finite differences, manipulability and its
gradient, singularity reports, seeded workspace sampling."""
import numpy as np
import pytest

import mjarm
from conftest import home


def random_q(chain, rng):
    lo, hi = chain.lower, chain.upper
    return lo + (hi - lo) * rng.uniform(0.05, 0.95, size=chain.size)


def test_fk_matches_mujoco(panda, panda_chain):
    kin = mjarm.ChainKinematics(panda_chain)
    data = panda.make_data()
    rng = np.random.default_rng(5)
    for _ in range(5):
        q = random_q(panda_chain, rng)
        data.qpos[:] = panda_chain.scatter(q, data.qpos)
        data.forward()
        X_mj = mjarm.frame_pose(panda, data, "attachment_site")
        X = kin.update(q)
        np.testing.assert_allclose(X.p, X_mj.p, atol=1e-12)
        np.testing.assert_allclose(X.R, X_mj.R, atol=1e-12)
        assert mjarm.forward_kinematics(panda_chain, q).is_approx(X, 1e-14)


def test_jacobians_against_finite_differences(panda_chain):
    kin = mjarm.ChainKinematics(panda_chain)
    q = home(panda_chain.robot, panda_chain)
    X = kin.update(q)
    J = kin.jacobian()
    J_local = kin.jacobian(mjarm.JacobianFrame.local)
    assert J.shape == (6, 7)
    h = 1e-7
    for i in range(7):
        dq = np.zeros(7)
        dq[i] = h
        Xp = mjarm.forward_kinematics(panda_chain, q + dq)
        np.testing.assert_allclose((Xp.p - X.p) / h, J[:3, i], atol=1e-6)
        # body twist: log(X^-1 X+) / h
        np.testing.assert_allclose(mjarm.se3.log(X.inverse() * Xp) / h, J_local[:, i], atol=1e-6)


def test_bias_acceleration_against_finite_differences(panda_chain):
    kin = mjarm.ChainKinematics(panda_chain)
    q = home(panda_chain.robot, panda_chain)
    qd = np.linspace(-0.5, 0.5, 7)
    kin.update(q)
    Jdqd = kin.bias_acceleration(qd)
    h = 1e-6
    kin.update(q + h * qd)
    Jp = kin.jacobian()
    kin.update(q - h * qd)
    Jm = kin.jacobian()
    np.testing.assert_allclose(Jdqd, (Jp - Jm) / (2 * h) @ qd, atol=1e-6)


def test_manipulability_and_gradient(panda_chain):
    meter = mjarm.Manipulability(panda_chain)
    q = home(panda_chain.robot, panda_chain)
    result, gradient = meter.gradient(q)
    J = meter.jacobian_block
    assert result.manipulability == pytest.approx(np.sqrt(np.linalg.det(J @ J.T)), rel=1e-10)
    np.testing.assert_allclose(meter.singular_values, np.linalg.svd(J, compute_uv=False), rtol=1e-10)
    h = 1e-6
    for i in range(7):
        dq = np.zeros(7)
        dq[i] = h
        numeric = (meter.evaluate(q + dq).manipulability - meter.evaluate(q - dq).manipulability) / (2 * h)
        assert gradient[i] == pytest.approx(numeric, abs=1e-6)
    assert mjarm.manipulability(panda_chain, q).status == mjarm.SingularityStatus.regular


def test_singularities(panda_chain):
    stretched = np.zeros(7)  # every joint at zero: the panda is nearly straight up
    entries = mjarm.singularity_report(panda_chain, [("zeros", stretched)])
    names = [e.name for e in entries]
    assert "qpos0" in names and "center" in names and "zeros" in names
    scan = mjarm.scan_singularities(panda_chain, 200, seed=4, keep_worst=3)
    again = mjarm.scan_singularities(panda_chain, 200, seed=4, keep_worst=3)
    assert scan.samples == 200 and len(scan.worst) == 3
    np.testing.assert_array_equal(scan.worst[0].q, again.worst[0].q)
    with pytest.raises(ValueError, match=r"zeros: expected shape \(7,\)"):
        mjarm.singularity_report(panda_chain, [("zeros", np.zeros(6))])


def test_workspace_is_seeded(panda_chain):
    a = mjarm.sample_workspace(panda_chain, samples=300, seed=9)
    b = mjarm.sample_workspace(panda_chain, samples=300, seed=9)
    c = mjarm.sample_workspace(panda_chain, samples=300, seed=10)
    assert a.points.shape == (300, 3) and a.manipulabilities.shape == (300,)
    np.testing.assert_array_equal(a.points, b.points)
    assert not np.array_equal(a.points, c.points)
    assert np.all(a.points >= a.lower - 1e-12) and np.all(a.points <= a.upper + 1e-12)
    with pytest.raises(mjarm.Error):
        mjarm.sample_workspace(panda_chain, samples=0)
