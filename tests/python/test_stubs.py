"""Type stubs follow the bindings, and every binding explains itself in help()."""
import inspect
import os
import subprocess
import sys

import mjarm
import mjarm._mjarm as native

SOURCE = os.environ.get("MJARM_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def test_stubs_are_up_to_date():
    tool = os.path.join(SOURCE, "python", "tools", "stubgen.py")
    out = subprocess.run([sys.executable, tool, "--check"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr


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
