"""The optional compiled kernels of hfo2d (the C extension ``hfo2d._accel``, built by setup.py at install).

The pure-Python functions they port stay the reference and the fallback: hfo2d imports and runs without the
extension (a machine without a C compiler installs without it), and ``HFO2D_PURE_PYTHON=1`` in the environment,
read once when this module is first imported, forces the pure-Python code even where the extension is built. The
kernels give the same floats as the Python, bit for bit (tests/hfo2d/test_accel_reference.py compares them).
"""

from __future__ import annotations

import importlib
import os
from types import ModuleType

#: The environment variable that forces the pure-Python code ("1"; "" or "0" leave the extension on).
PURE_PYTHON_ENV = "HFO2D_PURE_PYTHON"


def _load() -> tuple[ModuleType | None, str]:
    if os.environ.get(PURE_PYTHON_ENV, "") not in ("", "0"):
        return None, f"{PURE_PYTHON_ENV}={os.environ[PURE_PYTHON_ENV]} forces the pure-Python code"
    try:
        module = importlib.import_module("hfo2d._accel")
    except ImportError as error:  # not built (no C compiler at install), or built for another Python
        return None, f"the C extension hfo2d._accel is not available ({error}): the pure-Python code runs"
    return module, "the C extension hfo2d._accel is in use"


#: The extension module, or None when the pure-Python code runs.
ACCEL, STATUS = _load()


def in_use() -> bool:
    """Whether hfo2d's hot paths run the compiled kernels (False: the pure-Python reference)."""
    return ACCEL is not None
