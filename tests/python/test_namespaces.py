"""Each room of the library is a namespace (mjarm.ik, mjarm.control, ...) of the names its bindings
define; the flat names stay."""
import importlib
import inspect

import mjarm
import mjarm._mjarm as native

ROOMS = ("model", "lie", "kinematics", "ik", "dynamics", "control", "sim", "state", "trajectory",
         "planning", "scene", "tasks", "render", "teleop", "web", "env", "scenario")


def public_names(module):
    return {n for n in vars(module) if not n.startswith("_")}


def test_the_rooms_are_the_library_rooms():
    assert native._rooms == ROOMS


def test_a_room_imports_like_a_module():
    ik = importlib.import_module("mjarm.ik")
    assert ik is mjarm.ik
    from mjarm.ik import PoseIk
    assert PoseIk is mjarm.PoseIk is mjarm.ik.PoseIk
    import mjarm.control as control
    assert control is mjarm.control and control.Controller is mjarm.Controller


def test_a_room_holds_the_flat_objects():
    for room in ROOMS:
        module = getattr(mjarm, room)
        assert inspect.ismodule(module), room
        assert public_names(module), f"room {room} is empty"
        for name in public_names(module):
            assert getattr(module, name) is getattr(mjarm, name), f"mjarm.{room}.{name}"


def test_every_flat_name_is_in_exactly_one_room():
    rooms_of = {}
    for room in ROOMS:
        for name in public_names(getattr(mjarm, room)):
            rooms_of.setdefault(name, []).append(room)
    # Error is the module's own; the rooms are the namespaces themselves
    flat = public_names(native) - {"Error"} - set(ROOMS)
    assert {n: r for n, r in rooms_of.items() if len(r) != 1} == {}
    assert sorted(flat - set(rooms_of)) == []
    assert sorted(set(rooms_of) - flat) == []


def test_rooms_keep_the_flat_functions():
    assert callable(mjarm.scenarios)  # the registry's function; its room is mjarm.scenario
    assert mjarm.scenario.scenarios is mjarm.scenarios
    assert mjarm.lie.so3 is mjarm.so3
