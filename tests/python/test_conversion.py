"""The binding's conversion rules and error mapping: float64 in and out, shapes named in
ValueError, non-contiguous arrays copied (never misread), None refused, mjarm.Error keeps the
library's message and is a ValueError."""
import numpy as np
import pytest

import mjarm


def test_error_is_a_value_error_with_the_library_message(panda):
    assert issubclass(mjarm.Error, ValueError)
    with pytest.raises(mjarm.Error) as info:
        panda.site("end_efector")
    message = str(info.value)
    # the library's message: the kind, the name, the model and the closest names
    assert "site 'end_efector' not found in model 'panda'" in message
    assert "attachment_site" in message


def test_wrong_shape_names_the_argument_and_expected_shape(panda_chain):
    with pytest.raises(ValueError, match=r"q: expected shape \(7,\), got \(3,\)"):
        panda_chain.clamp(np.zeros(3))
    with pytest.raises(ValueError, match=r"q: expected shape \(7,\), got \(7, 1\)"):
        panda_chain.clamp(np.zeros((7, 1)))
    with pytest.raises(ValueError, match=r"R: expected shape \(3, 3\), got \(4, 4\)"):
        mjarm.Pose(np.eye(4), np.zeros(3))


def test_wrong_dtype_is_refused_with_the_expected_shape(panda_chain):
    with pytest.raises(ValueError, match=r"q: expected a float64 array of shape \(7,\), got dtype complex128"):
        panda_chain.clamp(np.zeros(7, dtype=complex))
    with pytest.raises(ValueError, match=r"q: expected a float64 array of shape \(7,\)"):
        panda_chain.clamp(["a"] * 7)
    with pytest.raises(ValueError, match=r"q: expected a float64 array of shape \(7,\)"):
        panda_chain.clamp([[1.0, 2.0], [3.0]])


def test_integers_lists_and_float32_are_converted(panda_chain):
    expected = panda_chain.clamp(np.arange(7, dtype=np.float64) * 0.1)
    for value in (np.arange(7, dtype=np.float32) * np.float32(0.1), list(np.arange(7) * 0.1)):
        got = panda_chain.clamp(value)
        assert got.dtype == np.float64 and got.shape == (7,)
        np.testing.assert_allclose(got, expected, atol=1e-7)
    got = panda_chain.clamp(np.zeros(7, dtype=np.int64))
    assert got.dtype == np.float64


def test_non_contiguous_arrays_are_copied_not_misread(panda_chain):
    q = np.linspace(-0.5, 0.5, 7)
    strided = np.zeros(14)
    strided[::2] = q
    view = strided[::2]
    assert not view.flags["C_CONTIGUOUS"]
    np.testing.assert_array_equal(panda_chain.clamp(view), panda_chain.clamp(q))
    # a transposed matrix (Fortran order) is read by its values, not its memory
    R = np.ascontiguousarray(mjarm.so3.exp(np.array([0.1, -0.2, 0.3])))
    RT = R.T
    assert not RT.flags["C_CONTIGUOUS"]
    np.testing.assert_allclose(mjarm.so3.log(RT), -mjarm.so3.log(R), atol=1e-14)
    np.testing.assert_allclose(mjarm.so3.log(np.ascontiguousarray(RT)), mjarm.so3.log(RT))


def test_none_is_refused(panda_chain):
    with pytest.raises(TypeError, match=r"q: expected a float64 array of shape \(7,\), got None"):
        panda_chain.clamp(None)
    with pytest.raises(TypeError, match="X_WE: expected a Pose or a 4x4 matrix, got None"):
        mjarm.log_error(None, mjarm.Pose())


def test_outputs_are_float64_arrays_of_documented_shapes(panda, panda_chain):
    assert panda_chain.lower.dtype == np.float64 and panda_chain.lower.shape == (7,)
    assert panda.keyframe_qpos("home").shape == (panda.nq,)
    X = mjarm.se3.exp(np.zeros(6))
    assert X.R.shape == (3, 3) and X.p.shape == (3,) and X.matrix().shape == (4, 4)
    assert mjarm.se3.adjoint(X).shape == (6, 6)


def test_outputs_are_copies(panda_chain):
    lower = panda_chain.lower
    lower[:] = 0.0
    assert panda_chain.lower[0] != 0.0
    X = mjarm.Pose()
    p = X.p
    p[0] = 5.0
    assert X.p[0] == 0.0
