"""Arms from DH tables, built and loaded from Python."""
import numpy as np
import pytest

import mjarm

PI = np.pi


def ur5e():
    rows = [dict(d=0.1625, alpha=PI / 2), dict(a=-0.425), dict(a=-0.3922),
            dict(d=0.1333, alpha=PI / 2), dict(d=0.0997, alpha=-PI / 2), dict(d=0.0996)]
    return mjarm.DhArm(name="ur5e_dh", links=[mjarm.DhLink(**row) for row in rows])


def test_the_ur5e_table_builds_the_bundled_arm():
    dh = mjarm.dh_robot(ur5e())
    bundled = mjarm.Robot.bundled("ur5e")
    a = mjarm.BodyPoses(dh)
    b = mjarm.BodyPoses(bundled)
    ka = mjarm.ChainKinematics(mjarm.Chain(dh, "end"))
    kb = mjarm.ChainKinematics(mjarm.Chain(bundled, "attachment_site"))
    rng = np.random.default_rng(3)
    for _ in range(50):
        q = rng.uniform(-2.5, 2.5, 6)
        Xa, Xb = ka.update(q), kb.update(q)
        assert np.linalg.norm(Xa.p - Xb.p) < 1e-9
        assert np.linalg.norm(Xa.R - Xb.R) < 1e-9
    assert len(a) == 7 and len(b) >= 7
    assert dh.nu == 6 and dh.keyframe("zero") >= 0


def test_the_mjcf_reads_back_and_bad_tables_are_refused():
    arm = ur5e()
    assert "<site name=\"end\"" in mjarm.dh_mjcf(arm)
    arm.convention = mjarm.DhConvention.modified
    mjarm.dh_robot(arm)                       # another arm, still a valid one
    bad = ur5e()
    links = bad.links
    links[2].a = float("nan")
    bad.links = links
    with pytest.raises(mjarm.Error, match="row 3"):
        mjarm.dh_robot(bad)
    with pytest.raises(mjarm.Error, match="no rows"):
        mjarm.dh_robot(mjarm.DhArm())
    with pytest.raises(ValueError):
        mjarm.DhArm(base=np.eye(3))
