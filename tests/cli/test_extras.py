"""``pip install -e .`` is the Python API; the command-line tools' dependencies are the ``[zoo]`` and ``[render]``
extras (pyproject.toml). Without them the API still works, and each tool says in one line which extra to install.

A missing module is simulated with ``sys.modules[name] = None``: ``import name`` then raises ImportError and
``importlib.util.find_spec(name)`` returns None, as for a module that is not installed.
"""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import pytest

from sb3_hfo.cli.errors import EXTRA_MODULES, UserError, check_installed

REPO = Path(__file__).resolve().parents[2]
ZOO_MODULES = ("rl_zoo3", "optuna", "pandas", "matplotlib")


def _pythonpath() -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(REPO), str(REPO / "envs"), env.get("PYTHONPATH", "")])
    return env


def _run_python(code: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=_pythonpath(), cwd=REPO, timeout=300
    )


def _block(modules: Sequence[str]) -> str:
    """Python source that makes ``modules`` (and their submodules) unimportable, as if not installed."""
    return (
        "import sys\n"
        f"blocked = {tuple(modules)!r}\n"
        "for name in [n for n in sys.modules if n.split('.')[0] in blocked]:\n"
        "    del sys.modules[name]\n"
        "for name in blocked:\n"
        "    sys.modules[name] = None\n"
    )


def test_extras_in_pyproject_hold_the_modules_the_messages_name() -> None:
    """The modules check_installed names per extra are what pyproject.toml's extra installs, and the base
    dependencies hold none of them (nor sb3-contrib, which nothing imports)."""
    tomllib = pytest.importorskip("tomllib")  # Python >= 3.11
    project = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]
    extras = project["optional-dependencies"]

    def names(requirements: Sequence[str]) -> set[str]:
        return {
            requirement.split(">")[0].split("=")[0].split("[")[0].strip().lower().replace("-", "_")
            for requirement in requirements
        }

    base = names(project["dependencies"])
    for extra, modules in EXTRA_MODULES.items():
        assert set(modules) <= names(extras[extra]), extra
        assert not set(modules) & base, extra
    assert "sb3_contrib" not in base
    assert "pyyaml" in base  # sb3_hfo.evaluation and sb3_hfo.cli.errors import yaml
    assert {"sb3_hfo"} == names([r for r in extras["test"] if r.startswith("sb3-hfo")])
    assert "zoo,render" in "".join(extras["test"])


def test_importing_the_api_loads_none_of_the_zoo_modules() -> None:
    code = (
        "import sys\n"
        "import sb3_hfo, sb3_hfo.models, sb3_hfo.evaluation, sb3_hfo.evaluate, sb3_hfo.zoo, sb3_hfo.cli.errors\n"
        f"print(sorted(m for m in {ZOO_MODULES!r} if m in sys.modules))\n"
    )
    completed = _run_python(code)
    assert completed.returncode == 0, completed.stderr[-2000:]
    assert completed.stdout.strip() == "[]"


def test_the_python_api_works_without_the_extras() -> None:
    """Train, save, load a committed model and evaluate it with the zoo and render modules unimportable."""
    code = _block((*ZOO_MODULES, "requests", "pygame", "moviepy")) + (
        "import gymnasium as gym\n"
        "from sb3_hfo import SkillDDPG\n"
        "from sb3_hfo.cli.evaluate import main as evaluate\n"
        "from sb3_hfo.models import load_model\n"
        "model = SkillDDPG('HFOPolicy', gym.make('HFO/EmptyGoal-v0'), learning_starts=16, batch_size=8, seed=0)\n"
        "model.learn(48)\n"
        "e1 = load_model('e1_skill_pdqn')\n"
        "print('critic rate', type(e1.learning_rate_critic).__name__, e1.learning_rate_critic(0.5))\n"
        "assert evaluate(['e1', '--episodes', '2', '--seed', '0']) == 0\n"
        "print('API OK')\n"
    )
    completed = _run_python(code)
    assert completed.returncode == 0, completed.stderr[-3000:]
    assert "API OK" in completed.stdout
    # e1_skill_pdqn was trained through rl-zoo3 and pickles its schedule: without rl-zoo3 it loads as an equal one
    from sb3_hfo.models import load_model

    with_zoo = load_model("e1_skill_pdqn").learning_rate_critic
    assert type(with_zoo).__name__ == "SimpleLinearSchedule"
    assert f"critic rate LinearToZero {with_zoo(0.5)}" in completed.stdout


def _exit_line(capsys: pytest.CaptureFixture[str], main: Callable[[list[str]], Any], argv: list[str]) -> str:
    code: Any
    try:
        code = main(argv)
    except SystemExit as exit_:
        code = exit_.code
    lines = capsys.readouterr().err.strip().splitlines()
    assert code == 2, (code, lines)
    assert len(lines) == 1 and lines[0].startswith("error: "), lines
    return lines[0]


@pytest.mark.parametrize(
    ("tool", "missing", "argv"),
    [
        (
            "train",
            "rl_zoo3",
            ["--env", "HFO/EmptyGoal-v0", "--conf-file", "zoo_configs/e1_empty_goal_fast.yml"],
        ),
        ("train", "optuna", ["--help"]),
        ("enjoy", "rl_zoo3", ["e1", "--no-render"]),
        ("enjoy", "requests", ["e1", "--no-render"]),
        ("record_video", "rl_zoo3", ["e1", "-n", "10"]),
        ("plot", "matplotlib", ["runs/tb"]),
    ],
)
def test_each_tool_names_the_zoo_extra_when_it_is_missing(
    tool: str,
    missing: str,
    argv: list[str],
    capsys: pytest.CaptureFixture[str],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    import importlib

    main = importlib.import_module(f"sb3_hfo.{tool}").main
    monkeypatch.setitem(sys.modules, missing, None)
    line = _exit_line(capsys, main, argv)
    assert f"python -m sb3_hfo.{tool} needs {missing}, from the [zoo] extra" in line
    assert 'pip install -e ".[zoo]"' in line


def test_check_installed_lists_every_missing_module(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "pygame", None)
    monkeypatch.setitem(sys.modules, "moviepy", None)
    with pytest.raises(
        UserError, match=r'needs pygame and moviepy, from the \[render\] extra: pip install -e "\.\[render\]"'
    ):
        check_installed("render", ("pygame", "moviepy"), "recording a video")
    check_installed("zoo", ("rl_zoo3",), "train")  # installed here: no error
    with pytest.raises(ValueError, match="not modules of the"):
        check_installed("render", ("rl_zoo3",), "train")


def test_train_without_the_zoo_extra_exits_2_in_a_real_process() -> None:
    code = _block(("rl_zoo3",)) + (
        "import runpy\n"
        "sys.argv = ['train', '--env', 'HFO/EmptyGoal-v0', '--conf-file', 'zoo_configs/e1_empty_goal_fast.yml']\n"
        "runpy.run_module('sb3_hfo.train', run_name='__main__')\n"
    )
    completed = _run_python(code)
    assert completed.returncode == 2, completed.stderr[-2000:]
    assert completed.stderr.strip().splitlines() == [
        'error: python -m sb3_hfo.train needs rl_zoo3, from the [zoo] extra: pip install -e ".[zoo]" '
        "(in the sb3-hfo folder)"
    ]


@pytest.mark.parametrize(("block", "extra"), [("main", "zoo"), ("test", "test")])
def test_readme_installs_a_cpu_torch_before_the_package(block: str, extra: str) -> None:
    """The README's own commands (the ones .ci/run runs) take torch from PyTorch's CPU index in a step of its own,
    before the package: with --extra-index-url pip would weigh both indexes for every requirement."""
    lines = (REPO / "README.md").read_text().splitlines()
    start = lines.index(f"<!-- ci:{block} -->")
    command = lines[start + 2]
    steps = [step.strip() for step in command.split("&&")]
    torch_step = "pip install torch --index-url https://download.pytorch.org/whl/cpu"
    package_step = f'pip install -e ".[{extra}]"'
    assert torch_step in steps and package_step in steps, steps
    assert steps.index(torch_step) < steps.index(package_step)
    assert "--extra-index-url" not in command
