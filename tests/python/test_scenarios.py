"""The scenario registry from Python: the scenarios listed with their parameters and metrics, a
trial run by name with keyword parameters (NumPy values too) returning the typed outcome, the
same outcome as the C++ task, and parameters refused with the library's message."""
import math

import numpy as np
import pytest

import mjarm


def test_scenarios_are_listed_with_their_parameters_and_metrics():
    names = [s.name for s in mjarm.scenarios()]
    assert names == ["shelf-pick", "pick-place", "docking", "plan", "bimanual-lift", "wiping"]
    pick_place = mjarm.find_scenario("pick-place")
    assert pick_place.verdicts[0] == "placed"
    size = next(p for p in pick_place.parameters if p["name"] == "object-size")
    assert size["unit"] == "m" and size["optional"] and size["default"] is None
    metric = next(m for m in pick_place.metrics if m["name"] == "placement_error")
    assert metric["unit"] == "m" and metric["better"] == "lower"
    assert "pick-place" in repr(pick_place)


def test_resolve_fills_in_the_defaults():
    values = mjarm.find_scenario("pick-place").resolve(object_size=np.float64(0.015),
                                                        grasp="friction")
    assert values["object-size"] == 0.015 and values["grasp"] == "friction"
    assert values["target"] is None and values["robot"] == "arm6"


def test_a_shelf_pick_by_name_returns_the_typed_outcome():
    o = mjarm.run_scenario("shelf-pick", robot="planar2", controller="ct", seed=4)
    assert isinstance(o, mjarm.TrialOutcome)
    assert o and o.success and o.verdict == "held" and o.scenario == "shelf-pick"
    assert o.status in ("finished", "duration_reached")
    assert set(o.metrics) == {m["name"] for m in mjarm.find_scenario("shelf-pick").metrics}
    assert 0.0 < o.metrics["time_to_tolerance"] < o.end_time
    assert o.parameters["seed"] == 4 and o.parameters["robot"] == "planar2"
    again = mjarm.run_scenario("shelf-pick", robot="planar2", controller="ct", seed=4)
    assert again.metrics == o.metrics  # same parameters, same trial, bit for bit


def test_a_pick_place_with_a_fixed_object_is_judged():
    o = mjarm.run_scenario(
        "pick-place", seed=3, object=np.array([0.26, -0.08]), object_size=0.015,
        **{"motion.dwell_time": 0.15, "motion.grip_time": 0.3, "motion.release_time": 0.3,
           "motion.settle_time": 0.6, "motion.limits.max_velocity": 0.25})
    assert o.success, o.message
    assert o.parameters["object"] == [0.26, -0.08] and o.parameters["object-size"] == 0.015
    assert o.metrics["placement_error"] <= 0.005
    assert math.isfinite(o.metrics["cycle_time"])


def test_a_wipe_by_name_holds_its_force():
    o = mjarm.run_scenario("wiping", **{"control.law": "osc", "path.length": 0.08,
                                        "motion.force": 12.0, "seed": 5})
    assert o.success and o.verdict == "wiped", o.message
    assert o.metrics["force_rms_error"] < 1.0 and o.metrics["contact_fraction"] == 1.0
    assert o.parameters["motion.force"] == 12.0 and o.parameters["control.law"] == "osc"


def test_bad_parameters_are_refused_with_the_librarys_message():
    with pytest.raises(mjarm.Error, match="unknown scenario 'dockng'; closest: docking"):
        mjarm.run_scenario("dockng")
    with pytest.raises(mjarm.Error, match="unknown parameter 'objct-size'; closest: object-size"):
        mjarm.run_scenario("pick-place", objct_size=0.02)
    with pytest.raises(mjarm.Error, match=r"object_size must be in \[0.005, 0.05\]"):
        mjarm.run_scenario("pick-place", object_size=0.5)
    with pytest.raises(mjarm.Error, match="parameter seed: a number"):
        mjarm.run_scenario("pick-place", seed=object())
