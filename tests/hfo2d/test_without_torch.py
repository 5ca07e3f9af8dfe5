"""hfo2d's tests need only numpy, gymnasium and pymunk: neither they, the scripts they load, nor hfo2d import torch,
Stable-Baselines3, sb3_hfo or rl-zoo3 (hfo2d promises to work without them)."""

from __future__ import annotations

import ast
import os
import subprocess
import sys
from pathlib import Path

TESTS = Path(__file__).resolve().parent
REPO = TESTS.parents[1]
#: Top-level modules that hfo2d and its tests must not import.
FORBIDDEN = ("torch", "stable_baselines3", "sb3_hfo", "rl_zoo3")
#: The benchmark scripts tests/hfo2d loads (by path, through its conftest's benchmark_script fixture).
BENCHMARK_SCRIPTS = ("keeper_fidelity", "real_hfo_logs", "team_features_fidelity")

#: A pytest plugin (loaded with -p before any conftest) that makes importing the forbidden modules fail.
BLOCKER = f"""
import importlib.abc
import sys

FORBIDDEN = {FORBIDDEN!r}


class Blocker(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in FORBIDDEN:
            raise ModuleNotFoundError(f"{{name}} is blocked: hfo2d's tests must run without it", name=name)
        return None


for module in list(sys.modules):
    if module.split(".")[0] in FORBIDDEN:
        raise RuntimeError(f"{{module}} was imported before the blocker")
sys.meta_path.insert(0, Blocker())
"""


def imported_top_levels(path: Path) -> set[str]:
    """The top-level modules that any ``import`` statement of ``path`` names, those inside functions included."""
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(), filename=str(path))):
        if isinstance(node, ast.Import):
            found.update(alias.name.split(".")[0] for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            found.add(node.module.split(".")[0])
    return found


def test_no_hfo2d_test_nor_hfo2d_module_imports_torch() -> None:
    sources = [
        *TESTS.glob("*.py"),
        *(REPO / "envs" / "hfo2d").rglob("*.py"),
        *(REPO / "benchmarks" / f"{name}.py" for name in BENCHMARK_SCRIPTS),
    ]
    assert len(sources) > 30
    offenders = {
        str(path.relative_to(REPO)): sorted(imported_top_levels(path) & set(FORBIDDEN)) for path in sources
    }
    assert {path: names for path, names in offenders.items() if names} == {}


def test_the_check_sees_imports_inside_functions(tmp_path: Path) -> None:
    source = tmp_path / "example.py"
    source.write_text("def f():\n    import torch.nn\n    from stable_baselines3 import PPO\n")
    assert imported_top_levels(source) == {"torch", "stable_baselines3"}


def test_hfo2d_tests_collect_with_torch_blocked(tmp_path: Path) -> None:
    """Collecting tests/hfo2d (its conftest and every test module, hence hfo2d) with the forbidden modules
    unimportable."""
    (tmp_path / "block_torch.py").write_text(BLOCKER)
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(tmp_path), *filter(None, [env.get("PYTHONPATH")])])
    command = [sys.executable, "-m", "pytest", str(TESTS), "--collect-only", "-q", "-p", "block_torch"]
    command += ["-p", "no:cacheprovider", "-p", "no:randomly", "--rootdir", str(REPO)]
    completed = subprocess.run(command, cwd=REPO, env=env, capture_output=True, text=True, timeout=300)
    assert completed.returncode == 0, (completed.stdout + completed.stderr)[-3000:]
    collected = completed.stdout  # "-q -q" (with pyproject's -q): one "path: count" line per test module
    assert all(f"tests/hfo2d/{path.name}: " in collected for path in TESTS.glob("test_*.py")), collected
    # and the blocker works: a module that imports torch fails to collect
    (tmp_path / "test_uses_torch.py").write_text("import torch\n\n\ndef test_nothing():\n    pass\n")
    command[3] = str(tmp_path / "test_uses_torch.py")
    completed = subprocess.run(command, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
    assert completed.returncode != 0 and "torch is blocked" in completed.stdout + completed.stderr
