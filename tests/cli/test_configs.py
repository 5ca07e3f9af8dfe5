"""``--conf-file NAME``: the zoo configs that come with sb3-hfo, from a checkout and from a built wheel."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from sb3_hfo.cli import configs

REPO = Path(__file__).resolve().parents[2]
CONFIGS = REPO / "zoo_configs"


def test_every_config_of_the_repository_has_a_name() -> None:
    assert configs.config_names() == sorted(path.stem for path in CONFIGS.glob("*.yml"))
    assert configs.find_config("e1_empty_goal_fast") == CONFIGS / "e1_empty_goal_fast.yml"
    assert configs.find_config("no_such_config") is None


@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        (["--conf-file", "e2_empty_goal_skills"], ["--conf-file", str(CONFIGS / "e2_empty_goal_skills.yml")]),
        (["-conf", "e2_empty_goal_skills"], ["-conf", str(CONFIGS / "e2_empty_goal_skills.yml")]),
        (["--conf-file=e2_empty_goal_skills"], [f"--conf-file={CONFIGS / 'e2_empty_goal_skills.yml'}"]),
        (["--conf-file", "my/e2_empty_goal_skills.yml"], ["--conf-file", "my/e2_empty_goal_skills.yml"]),
        (["--conf-file", "e2_empty_goal_skills.yml"], ["--conf-file", "e2_empty_goal_skills.yml"]),
        (["--conf-file", "some.python.module"], ["--conf-file", "some.python.module"]),
        (["--env", "e2_empty_goal_skills", "--conf-file"], ["--env", "e2_empty_goal_skills", "--conf-file"]),
    ],
)
def test_a_bare_name_becomes_its_path_and_anything_else_is_left_alone(
    argv: list[str], expected: list[str]
) -> None:
    assert configs.with_named_config(argv) == expected


def _train_error(capsys: pytest.CaptureFixture[str], argv: list[str]) -> str:
    from sb3_hfo.cli.train import main

    with pytest.raises(SystemExit) as exit_info:
        main(argv)
    assert exit_info.value.code == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), lines
    return lines[0]


def test_train_names_the_configs_when_none_or_a_misspelt_one_is_given(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    logs = tmp_path / "logs"
    line = _train_error(capsys, ["--env", "HFO/EmptyGoal-v0", "-n", "10", "-f", str(logs)])
    assert (
        "--conf-file is required" in line and "e1_empty_goal_fast" in line and "hybrid_ppo_empty_goal" in line
    )
    argv = ["--env", "HFO/EmptyGoal-v0", "--conf-file", "e1_empty_gaol_fast", "-n", "10", "-f", str(logs)]
    assert "did you mean e1_empty_goal_fast?" in _train_error(capsys, argv)
    assert not logs.exists()


def test_train_runs_a_config_given_by_name_from_another_folder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from sb3_hfo.cli.train import main

    monkeypatch.chdir(tmp_path)
    main(
        [
            "--env",
            "HFO/EmptyGoal-v0",
            "--conf-file",
            "e1_empty_goal_fast",
            "-n",
            "300",
            "--seed",
            "0",
            "-f",
            "logs",
        ]
    )
    run = tmp_path / "logs" / "skill_ddpg" / "HFO-EmptyGoal-v0_1"
    assert (run / "HFO-EmptyGoal-v0.zip").is_file()


def test_a_built_package_carries_every_config(tmp_path: Path) -> None:
    """setup.py's build_py copies zoo_configs/*.yml into sb3_hfo/zoo_configs/ of the build, which a wheel installs
    and :data:`sb3_hfo.cli.configs.PACKAGED_CONFIGS` reads."""
    build = tmp_path / "build"
    command = [sys.executable, "setup.py", "-q", "build_py", "--build-lib", str(build)]
    done = subprocess.run(command, cwd=REPO, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    packaged = build / "sb3_hfo" / "zoo_configs"
    assert sorted(path.name for path in packaged.glob("*.yml")) == sorted(
        path.name for path in CONFIGS.glob("*.yml")
    )
    for path in packaged.glob("*.yml"):
        assert path.read_bytes() == (CONFIGS / path.name).read_bytes()
    assert (build / "sb3_hfo" / "cli" / "configs.py").is_file()
    assert configs.PACKAGED_CONFIGS.relative_to(REPO) == Path("sb3_hfo") / "zoo_configs"
