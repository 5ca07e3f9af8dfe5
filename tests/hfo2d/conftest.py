"""hfo2d's tests: numpy, gymnasium and pymunk only (no torch; tests/hfo2d/test_without_torch.py checks it)."""

from __future__ import annotations

import importlib.util
import sys
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import pytest

BENCHMARKS = Path(__file__).resolve().parents[2] / "benchmarks"


def load_benchmark_script(name: str) -> ModuleType:
    """Import ``benchmarks/<name>.py`` by its path (benchmarks/ is a folder of scripts, not a package).

    A script may put its own folder on ``sys.path`` to import its helper modules; that is undone here once it is
    loaded, so that no test's imports depend on the order the tests ran in.
    """
    if name in sys.modules:
        return sys.modules[name]
    spec = importlib.util.spec_from_file_location(name, BENCHMARKS / f"{name}.py")
    assert spec is not None and spec.loader is not None, name
    module = importlib.util.module_from_spec(spec)
    saved_path = list(sys.path)
    sys.modules[name] = module  # dataclasses look their module up in sys.modules
    try:
        spec.loader.exec_module(module)
    except BaseException:
        del sys.modules[name]
        raise
    finally:
        sys.path[:] = saved_path
    return module


@pytest.fixture(scope="session")
def benchmark_script() -> Callable[[str], ModuleType]:
    """:func:`load_benchmark_script`, for tests of the benchmark scripts' helpers."""
    return load_benchmark_script
