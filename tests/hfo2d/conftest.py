"""hfo2d's tests: numpy, gymnasium and pymunk only (no torch; tests/hfo2d/test_without_torch.py checks it)."""

from __future__ import annotations

import importlib.util
import os
import sys
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import numpy as np
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


# --- the real HFO (hfo2d.real, hfo2d.real_teams) ------------------------------------------------------------------
@pytest.fixture
def real_hfo_build() -> Path:
    """The HFO build in ``$HFO_DIR``, for tests that start real servers. They skip without one, and outside a
    loopback-only network namespace (``tools/real_hfo/loopback.sh``) unless ``HFO_TESTS=1``."""
    from hfo2d import real

    build = None
    candidate = os.environ.get(real.HFO_DIR_ENV)
    if candidate:
        try:
            build = real.find_hfo_dir(candidate)
        except FileNotFoundError:
            build = None
    if build is None or not (os.environ.get("HFO_TESTS") == "1" or real.in_loopback_namespace()):
        pytest.skip(
            "needs an HFO build ($HFO_DIR) and a loopback-only network namespace (tools/real_hfo/loopback.sh) or "
            "HFO_TESTS=1"
        )
    return build


@pytest.fixture
def make_stand_in_build(tmp_path: Path) -> Callable[[str, str], Path]:
    """Writes a stand-in HFO build into ``tmp_path``: ``bin/HFO`` is the given launcher script, ``hfo`` the given
    Python binding (with an empty ``libhfo_c.so``, so that :func:`hfo2d.real.find_hfo_dir` accepts it)."""

    def make(launcher: str, binding: str) -> Path:
        (tmp_path / "bin").mkdir()
        (tmp_path / "hfo").mkdir()
        (tmp_path / "bin" / "HFO").write_text(launcher)
        (tmp_path / "hfo" / "__init__.py").write_text("from .hfo import *\n")
        (tmp_path / "hfo" / "hfo.py").write_text(binding)
        (tmp_path / "hfo" / "libhfo_c.so").write_text("")
        return tmp_path

    return make


def _process_group_gone(pid: int) -> bool:
    try:
        os.killpg(pid, 0)
    except ProcessLookupError:
        return True
    return False


@pytest.fixture(scope="session")
def group_gone() -> Callable[[int], bool]:
    """Whether the process group led by a pid has no process left (a session's clean-up killed it)."""
    return _process_group_gone


def _chase_actions(observations: dict[str, np.ndarray], kick: bool) -> dict[str, np.ndarray]:
    """Every striker dashes at the ball, and when ``kick`` kicks it (if kickable) at the goal centre with power
    60: both strikers of a team chase, the ball moves, and the gap rewards pay and refund."""
    actions = {}
    for name, obs in observations.items():
        action = np.zeros(8, dtype=np.float32)
        if kick and obs[12] > 0:  # kickable
            action[2], action[6] = 1.0, 0.6  # KICK, power 60
            action[7] = (np.degrees(np.arctan2(obs[13], obs[14])) + 180.0) / 360.0  # at the goal centre
        else:
            action[0], action[3] = 1.0, 1.0  # DASH at full power
            action[4] = (np.degrees(np.arctan2(obs[51], obs[52])) + 180.0) / 360.0  # at the ball
        actions[name] = action
    return actions


@pytest.fixture(scope="session")
def chase_actions() -> Callable[[dict[str, np.ndarray], bool], dict[str, np.ndarray]]:
    """Flat offense actions of strikers that chase the ball and shoot at the goal (``_chase_actions``)."""
    return _chase_actions
