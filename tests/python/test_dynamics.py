"""dynamics: M, h and inverse dynamics against MuJoCo's own arrays; Lambda identities."""
import numpy as np
import pytest

import mjarm
from conftest import home


@pytest.fixture()
def state(panda_torque):
    chain = mjarm.Chain(panda_torque, "attachment_site")
    data = panda_torque.make_data()
    data.qpos[:] = panda_torque.keyframe_qpos("home")
    data.qvel[:] = np.linspace(-0.3, 0.3, panda_torque.nv)
    data.forward()
    return chain, data


def test_chain_dynamics_matches_mujoco(state):
    chain, data = state
    dyn = mjarm.ChainDynamics(chain)
    dyn.update(data)
    M = dyn.mass_matrix
    assert M.shape == (7, 7)
    np.testing.assert_allclose(M, M.T, atol=1e-14)
    assert np.all(np.linalg.eigvalsh(M) > 0)
    np.testing.assert_allclose(dyn.bias, data.qfrc_bias[:7], atol=1e-12)
    np.testing.assert_allclose(dyn.jacobian @ data.qvel[:7], dyn.velocity, atol=1e-12)
    qdd = np.linspace(1.0, -1.0, 7)
    np.testing.assert_allclose(dyn.inverse_dynamics(data, qdd), M @ qdd + dyn.bias, atol=1e-10)


def test_task_space_identities(state):
    chain, data = state
    dyn = mjarm.ChainDynamics(chain)
    dyn.update(data)
    ts = mjarm.TaskSpaceDynamics(7, 6)
    status = ts.update_from(dyn)
    assert status == mjarm.TaskSpaceStatus.ok
    J, M = dyn.jacobian, dyn.mass_matrix
    np.testing.assert_allclose(ts.lambda_, np.linalg.inv(J @ np.linalg.inv(M) @ J.T), rtol=1e-8)
    np.testing.assert_allclose(J @ ts.jbar, np.eye(6), atol=1e-9)
    np.testing.assert_allclose(J @ ts.nullspace, np.zeros((6, 7)), atol=1e-9)
    with pytest.raises(ValueError, match=r"J: expected shape \(6, 7\)"):
        ts.update(M, J[:3])


def test_dynamics_refuses_data_of_another_model(state, panda):
    chain, _ = state
    with pytest.raises(mjarm.Error, match="belongs to model"):
        mjarm.ChainDynamics(chain).update(panda.make_data())


def test_friction_and_wrench_helpers(state):
    chain, _ = state
    ff = mjarm.FrictionFeedForward(chain)
    assert ff.apply(np.zeros(7), np.zeros(7)).shape == (7,)
    F = np.array([1.0, 0, 0, 0, 0, 0])
    shifted = mjarm.shift_wrench(F, np.zeros(3), np.array([0.0, 1.0, 0.0]))
    assert np.linalg.norm(shifted[3:]) == pytest.approx(1.0)
