"""The command-line tools turn a user's mistake into one line on stderr, ``error: ...``, and exit code 2.

Every case fails before any training, loading or rendering starts, so the tests call ``main(argv)`` in-process
(plus one real ``python -m`` run for the process exit status).
"""

from __future__ import annotations

import io
import os
import subprocess
import sys
import zipfile
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import pytest

REPO = Path(__file__).resolve().parents[2]
CONFIG = str(REPO / "zoo_configs" / "e1_empty_goal_fast.yml")
ENV = "HFO/EmptyGoal-v0"


def _fake_models(folder: Path) -> dict[str, Path]:
    """A non-zip file, a truncated model zip and a zip without SB3's ``data`` entry."""
    folder.mkdir(parents=True, exist_ok=True)
    not_zip = folder / "not_a_zip.zip"
    not_zip.write_text("this is not a model\n")
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as archive:
        archive.writestr("data", '{"policy_class": "x"}' * 200)
        archive.writestr("policy.pth", b"\0" * 4000)
    truncated = folder / "truncated.zip"
    truncated.write_bytes(buffer.getvalue()[: len(buffer.getvalue()) // 2])
    no_data = folder / "no_data.zip"
    with zipfile.ZipFile(no_data, "w") as archive:
        archive.writestr("policy.pth", b"\0" * 100)
    damaged = folder / "damaged.zip"  # one byte of a stored entry flipped: its CRC no longer matches
    with zipfile.ZipFile(damaged, "w") as archive:
        archive.writestr("data", "x" * 1000)
    raw = bytearray(damaged.read_bytes())
    raw[raw.index(b"x" * 1000) + 500] ^= 0xFF
    damaged.write_bytes(bytes(raw))
    return {
        "not a zip archive": not_zip,
        "not a zip archive, or cut short": truncated,
        "no 'data' entry": no_data,
        "fails the CRC check": damaged,
    }


def _one_line_error(
    capsys: pytest.CaptureFixture[str], main: Callable[[Sequence[str]], Any], argv: Sequence[str]
) -> str:
    """Run ``main(argv)``; assert exit code 2 and exactly one stderr line starting with ``error:``; return it."""
    code: Any
    try:
        code = main(list(argv))
    except SystemExit as exit_:
        code = exit_.code
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert code == 2, (code, captured.err[-2000:])
    assert len(lines) == 1 and lines[0].startswith("error: "), captured.err[-2000:]
    return lines[0]


# --- evaluate ----------------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "kind",
    [
        "missing",
        "not a zip archive",
        "not a zip archive, or cut short",
        "no 'data' entry",
        "fails the CRC check",
    ],
)
def test_evaluate_bad_model(capsys: pytest.CaptureFixture[str], tmp_path: Path, kind: str) -> None:
    from sb3_hfo.cli.evaluate import main

    models = _fake_models(tmp_path)
    model = tmp_path / "nope.zip" if kind == "missing" else models[kind]
    line = _one_line_error(capsys, main, [str(model), "--env", ENV, "--episodes", "1"])
    assert str(model) in line
    assert ("model file not found" if kind == "missing" else kind) in line


@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        (["--seed", "-1"], "argument --seed: must be >= 0, got -1"),
        (["--seed", "one"], "argument --seed: must be an integer"),
        (["--episodes", "x"], "argument --episodes"),
        (["--no-such-option"], "unrecognized arguments: --no-such-option"),
        (["--env-kwargs", "noise"], "--env-kwargs expects KEY:VALUE, got 'noise'"),
    ],
)
def test_evaluate_bad_options(capsys: pytest.CaptureFixture[str], argv: list[str], expected: str) -> None:
    from sb3_hfo.cli.evaluate import main

    assert expected in _one_line_error(capsys, main, ["m.zip", "--env", ENV, *argv])


def test_evaluate_bad_env_kwargs(
    capsys: pytest.CaptureFixture[str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A model that loads, with env kwargs HFOEnv refuses: the env's own message, in one line."""
    import sb3_hfo.cli.evaluate as evaluate

    model = tmp_path / "model.zip"
    with zipfile.ZipFile(model, "w") as archive:
        archive.writestr("data", "{}")

    monkeypatch.setattr("sb3_hfo.evaluation.load_model", lambda *args, **kwargs: object())
    for kwargs, expected in (
        ("noise:'no'", "noise must be True or False, got 'no'"),
        ("no_such_kwarg:1", "unexpected keyword argument 'no_such_kwarg'"),
        ("keeper_skill:0.5", "keeper_skill is for task 'keeper'"),
        (
            "task:'keeper'",
            "HFO/EmptyGoal-v0 is task='empty_goal'; task='keeper' would make another environment",
        ),
    ):
        line = _one_line_error(capsys, evaluate.main, [str(model), "--env", ENV, "--env-kwargs", kwargs])
        assert f"cannot make {ENV} with env kwargs" in line and expected in line, line


def test_evaluate_json_folder(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    from sb3_hfo.cli.evaluate import main

    assert "is a folder" in _one_line_error(capsys, main, ["m.zip", "--env", ENV, "--json", str(tmp_path)])


def test_evaluate_exits_2_as_a_process(tmp_path: Path) -> None:
    model = _fake_models(tmp_path)["not a zip archive"]
    result = subprocess.run(
        [sys.executable, "-m", "sb3_hfo.evaluate", str(model), "--env", ENV],
        cwd=tmp_path,
        env={**os.environ, "OMP_NUM_THREADS": "1"},
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert result.returncode == 2
    assert result.stderr.strip().splitlines() == [
        f"error: {model} is not a model .zip: not a zip archive, or cut short"
    ]


# --- train -------------------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        (["--env", ENV], "--conf-file is required"),
        (["--env", ENV, "--conf-file", "no/such.yml"], "--conf-file no/such.yml: no such file"),
        (
            ["--env", ENV, "--conf-file", "no_such_module"],
            "no such file, config of sb3-hfo, nor importable Python module",
        ),
        (["--conf-file", CONFIG], "--env is required (rl-zoo3 would fall back to CartPole-v1)"),
        (["--env", "HFO/NoSuchTask-v0", "--conf-file", CONFIG], "unknown env id 'HFO/NoSuchTask-v0'"),
        (["--env", "HFO/Keeper-v0", "--conf-file", CONFIG], "has no hyperparameters for HFO/Keeper-v0"),
        (["--env", ENV, "--conf-file", CONFIG, "--seed", "-1"], "--seed must be >= 0, got -1"),
        (["--env", ENV, "--conf-file", CONFIG, "--env-kwargs", "noise:maybe"], "--env-kwargs 'noise:maybe'"),
        (["--env", ENV, "--conf-file", CONFIG, "--env-kwargs", "noise"], "--env-kwargs expects KEY:VALUE"),
        (["--env", ENV, "--conf-file", CONFIG, "--env-kwargs", "noise:'no'"], "noise must be True or False"),
        (["--env", ENV, "--conf-file", CONFIG, "--env-kwargs", "reward:'dense'"], "unknown reward 'dense'"),
        (["--env", ENV, "--conf-file", CONFIG, "--eval-env-kwargs", "foo:1"], "bad --eval-env-kwargs"),
        (["--env", ENV, "--conf-file", CONFIG, "--hyperparams", "gamma:"], "--hyperparams 'gamma:'"),
        (
            ["--env", ENV, "--conf-file", CONFIG, "--no-such-option"],
            "unrecognized arguments: --no-such-option",
        ),
    ],
)
def test_train_user_errors(
    capsys: pytest.CaptureFixture[str],
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    argv: list[str],
    expected: str,
) -> None:
    from sb3_hfo.cli.train import main

    monkeypatch.chdir(tmp_path)
    # should a check let the mistake through, rl-zoo3 trains one step into tmp_path instead of a whole run
    line = _one_line_error(capsys, main, [*argv, "-n", "1", "-f", str(tmp_path)])
    assert expected in line, line


def test_train_bad_config_env_kwargs(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    config = tmp_path / "bad.yml"
    config.write_text(f"{ENV}:\n  n_timesteps: 10\n  policy: MlpPolicy\n  env_kwargs:\n    noise: 'off'\n")
    from sb3_hfo.cli.train import main

    line = _one_line_error(capsys, main, ["--env", ENV, "--conf-file", str(config), "-f", str(tmp_path)])
    assert f"bad env_kwargs in {config} for {ENV}" in line and "noise must be True or False" in line
    config.write_text("a: [unclosed\n")
    assert "is not valid YAML" in _one_line_error(capsys, main, ["--env", ENV, "--conf-file", str(config)])


# --- enjoy, record_video -----------------------------------------------------------------------------------------
def _run_folder(root: Path, content: Path | None) -> Path:
    """``root/skill_ddpg/HFO-EmptyGoal-v0_1/HFO-EmptyGoal-v0.zip`` (rl-zoo3's layout) holding ``content``."""
    run = root / "skill_ddpg" / "HFO-EmptyGoal-v0_1"
    run.mkdir(parents=True)
    if content is not None:
        (run / "HFO-EmptyGoal-v0.zip").write_bytes(content.read_bytes())
    return root


@pytest.mark.parametrize("tool", ["enjoy", "record_video"])
def test_playback_user_errors(capsys: pytest.CaptureFixture[str], tmp_path: Path, tool: str) -> None:
    import importlib

    main = importlib.import_module(f"sb3_hfo.{tool}").main
    models = _fake_models(tmp_path / "models")
    empty = _run_folder(tmp_path / "empty", None)
    cases = [
        (["-f", str(tmp_path)], "--env is required"),
        (["--env", ENV], "-f/--folder is required"),
        (["--env", ENV, "-f", str(tmp_path / "nowhere")], "folder was not found"),
        (["--env", ENV, "-f", str(empty)], "No model found for skill_ddpg on HFO-EmptyGoal-v0"),
        (["--env", ENV, "-f", str(empty), "--seed", "-3"], "--seed must be >= 0, got -3"),
        (["--env", ENV, "-f", str(empty), "--env-kwargs", "noise:'no'"], "noise must be True or False"),
        (["--env", "CartPole-v9", "-f", str(empty)], "unknown env id 'CartPole-v9'"),
    ]
    for index, (kind, model) in enumerate(models.items()):
        cases.append((["--env", ENV, "-f", str(_run_folder(tmp_path / f"run{index}", model))], kind))
    for argv, expected in cases:
        line = _one_line_error(capsys, main, [*argv, "--no-render"] if tool == "enjoy" else argv)
        assert expected in line, (argv, line)


# --- plot --------------------------------------------------------------------------------------------------------
def test_plot_user_errors(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    from sb3_hfo.cli.plot import main

    events = tmp_path / "run"
    events.mkdir()
    (events / "events.out.tfevents.1.host").write_bytes(b"")
    for argv, expected in (
        ([str(tmp_path / "nowhere")], "log folder not found"),
        ([str(events), "--labels", "a", "b"], "got 2 labels for 1 log folders"),
        ([str(events), "--out", str(tmp_path)], "is a folder"),
        ([str(events), "--out", "figure.xyz"], "unknown image format '.xyz'"),
        ([str(events), "--targets", "2"], "--targets must lie in (0, 1]"),
        ([str(events), "--smooth", "many"], "argument --smooth: invalid int value"),
    ):
        assert expected in _one_line_error(capsys, main, argv)
