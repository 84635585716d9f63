"""Type stubs follow the bindings, and every binding explains itself in help()."""
import ast
import inspect
import os
import re
import subprocess
import sys

import mjarm
import mjarm._mjarm as native

SOURCE = os.environ.get("MJARM_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def test_stubs_are_up_to_date():
    tool = os.path.join(SOURCE, "python", "tools", "stubgen.py")
    out = subprocess.run([sys.executable, tool, "--check"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr


def test_stubs_are_python():
    """A stub that does not parse is no stub: editors and type checkers drop it."""
    folder = os.path.join(SOURCE, "python", "mjarm")
    for name in sorted(os.listdir(folder)):
        if name.endswith(".pyi"):
            with open(os.path.join(folder, name)) as f:
                ast.parse(f.read(), name)


def test_every_class_and_function_has_a_docstring():
    missing = []
    for name, obj in vars(native).items():
        if name.startswith("_"):
            continue
        if inspect.isclass(obj) and not hasattr(obj, "__members__"):
            doc = obj.__doc__ or ""
            # a class documents itself or, for a plain result struct, through its fields
            if not doc.strip() and not any(isinstance(v, property) for v in vars(obj).values()):
                missing.append(name)
        elif callable(obj) and not inspect.isclass(obj):
            if "(" not in (obj.__doc__ or ""):
                missing.append(name)
    assert not missing, missing


def test_help_explains_a_binding():
    text = mjarm.PositionIk.solve.__doc__
    assert "p_WT" in text and "q_seed" in text and "IkResult" in text
    assert "ValueError" in mjarm.__doc__


def says_what_it_is(doc):
    """A doc names the thing in words: a unit "[m]", a shape "(3,)" or a type name alone does not."""
    words = re.sub(r"\[[^\]]*\]|\([^)]*\)", " ", doc)
    return re.search(r"\b[a-z][a-z]+\b", words) is not None


def test_every_property_says_what_it_is():
    """help() and the stubs show each property's doc, with its unit and shape where it has them."""
    missing = []
    for name, cls in vars(native).items():
        if name.startswith("_") or not inspect.isclass(cls) or hasattr(cls, "__members__"):
            continue  # a pybind11 enum's own properties (name, value) are pybind11's
        for attr, value in vars(cls).items():
            if isinstance(value, property) and not attr.startswith("_"):
                if not says_what_it_is(value.__doc__ or ""):
                    missing.append(f"{name}.{attr}: {value.__doc__!r}")
    assert not missing, f"{len(missing)} properties without a doc saying what they are: {missing}"


def test_a_property_shows_its_unit_and_shape():
    doc = mjarm.ChainDynamics.velocity.__doc__
    assert "(6,)" in doc and "[m/s, rad/s]" in doc
    assert "[s]" in mjarm.Simulation.time.__doc__
