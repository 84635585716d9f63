"""mjarm: robot arms in MuJoCo 2.2.2 from Python.

The C++ library bound with pybind11. Vectors and matrices are float64 NumPy arrays with
documented shapes; twists and wrenches are linear first ``[v; w]``; bad input raises
:class:`mjarm.Error` (a ``ValueError``) carrying the library's message. See docs/python.md.
"""
from ._mjarm import *  # noqa: F401,F403
from ._mjarm import Error, so3, se3  # noqa: F401
from ._mjarm import __doc__ as _native_doc  # noqa: F401

__version__ = "0.1.0"
