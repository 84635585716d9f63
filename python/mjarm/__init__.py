"""mjarm: robot arms in MuJoCo from Python.

The C++ library bound with pybind11. Vectors and matrices are float64 NumPy arrays with
documented shapes; twists and wrenches are linear first ``[v; w]``; bad input raises
:class:`mjarm.Error` (a ``ValueError``) carrying the library's message. Every call that takes a
:class:`Robot` or a :class:`Data` also takes the user's ``mujoco.MjModel`` / ``mujoco.MjData``,
without a copy: mjarm runs on the library the ``mujoco`` package loads. See docs/python.md.
"""


def _check_mujoco_version(found: str, built: str, where: str) -> None:
    """Refuses a ``mujoco`` package of another version than the one mjarm was built against:
    the extension would fail to load with a loader error, or run on a library whose structs
    differ from those it was compiled for."""
    if found != built:
        raise ImportError(
            f"mjarm was built against MuJoCo {built} but the mujoco package imported is "
            f"{found} ({where}); install the one mjarm was built for "
            f"(pip install mujoco=={built}) or rebuild mjarm against MuJoCo {found} "
            "(configure CMake with this interpreter's environment)")


def _import_mujoco():
    """``mujoco`` first: mjarm's extension runs on the MuJoCo library this package loads."""
    try:
        from ._mujoco_version import BUILT_WITH
    except ImportError as e:
        raise ImportError(
            "mjarm's build information (mjarm/_mujoco_version.py, written by CMake) is missing: "
            "build or install mjarm with CMake") from e
    try:
        import mujoco
    except ImportError as e:
        raise ImportError(
            f"mjarm needs the mujoco package, version {BUILT_WITH} "
            f"(pip install mujoco=={BUILT_WITH}): {e}") from e
    _check_mujoco_version(str(getattr(mujoco, "__version__", "unknown")), BUILT_WITH,
                          str(getattr(mujoco, "__file__", "unknown location")))


_import_mujoco()

from ._mjarm import *  # noqa: E402,F401,F403
from ._mjarm import Error, so3, se3  # noqa: E402,F401
from ._mjarm import __doc__ as _native_doc  # noqa: E402,F401
from .env_task import EnvTask  # noqa: E402,F401


def _register_rooms() -> None:
    """Each room of the library is a namespace of the extension (``mjarm.ik``, ``mjarm.control``,
    ...) holding the names its bindings define; registered here so that ``import mjarm.ik`` and
    ``from mjarm.ik import PoseIk`` find it."""
    import sys
    from . import _mjarm
    for room in _mjarm._rooms:
        sys.modules[f"{__name__}.{room}"] = getattr(_mjarm, room)


_register_rooms()

__version__ = "0.1.0"
