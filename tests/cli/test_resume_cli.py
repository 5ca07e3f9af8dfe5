"""``python -m sb3_hfo.train --checkpoint-freq N`` / ``--resume RUN_DIR``: a run killed (SIGKILL) after a checkpoint
and resumed ends with the same model, counters, monitor files and evaluations as an unbroken one, in the same run
folder and TensorBoard run."""

from __future__ import annotations

import csv
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import torch as th
from stable_baselines3.common.save_util import load_from_zip_file

from sb3_hfo.resume import CHECKPOINT_NAME

TOTAL_STEPS = 2000
CHECKPOINT_FREQ = 400
RUN = Path("logs/skill_ddpg/HFO-EmptyGoal-v0_1")
CONFIG = Path(__file__).resolve().parents[2] / "zoo_configs" / "e1_empty_goal_fast.yml"
TRAIN = [
    *("--env", "HFO/EmptyGoal-v0", "--conf-file", str(CONFIG), "-n", str(TOTAL_STEPS), "--seed", "0"),
    *("-f", "logs", "--tensorboard-log", "tb", "--eval-freq", "800", "--eval-episodes", "2"),
    *("--checkpoint-freq", str(CHECKPOINT_FREQ), "--hyperparams", "learning_starts:200", "batch_size:16"),
    "buffer_size:1000",
    "policy_kwargs:dict(net_arch=[16,16],n_skills=1,skill_router='single',inverting_gradients=False)",
]


def _start(folder: Path, *extra: str) -> subprocess.Popen[bytes]:
    environment = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    return subprocess.Popen(
        [sys.executable, "-m", "sb3_hfo.train", *TRAIN, *extra],
        cwd=folder,
        env=environment,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )


def _run(folder: Path, *extra: str) -> None:
    process = _start(folder, *extra)
    _, stderr = process.communicate(timeout=300)
    assert process.returncode == 0, stderr.decode()[-3000:]


def _monitor_rows(run: Path) -> list[list[tuple[str, str]]]:
    """Each env's monitor rows (return, length; not the wall-clock time)."""
    rows = []
    for name in sorted(path.name for path in run.glob("*.monitor.csv")):
        lines = (run / name).read_text().splitlines()[1:]  # after the JSON header line
        rows.append([(row["r"], row["l"]) for row in csv.DictReader(lines)])
    return rows


def test_a_killed_run_resumed_from_its_checkpoint_ends_as_an_unbroken_one(tmp_path: Path) -> None:
    unbroken, broken = tmp_path / "unbroken", tmp_path / "broken"
    unbroken.mkdir()
    broken.mkdir()
    _run(unbroken)

    process = _start(broken)
    checkpoint = broken / RUN / CHECKPOINT_NAME
    try:
        deadline = time.monotonic() + 300
        while not checkpoint.exists():
            assert process.poll() is None, process.stderr.read().decode()[-3000:]  # type: ignore[union-attr]
            assert time.monotonic() < deadline
            time.sleep(0.02)
        process.send_signal(signal.SIGKILL)
        process.wait(timeout=30)
    finally:
        if process.poll() is None:
            process.kill()
        process.stderr.close()  # type: ignore[union-attr]
    assert not (broken / RUN / "HFO-EmptyGoal-v0.zip").exists(), "the run ended before it was killed"
    _run(broken, "--resume", str(RUN))

    left_data, left_params, _ = load_from_zip_file(unbroken / RUN / "HFO-EmptyGoal-v0.zip")
    right_data, right_params, _ = load_from_zip_file(broken / RUN / "HFO-EmptyGoal-v0.zip")
    for name, state in left_params.items():  # the policy's weights and every optimizer's state
        flat_left = th.nn.utils.parameters_to_vector([v for v in _tensors(state)])
        flat_right = th.nn.utils.parameters_to_vector([v for v in _tensors(right_params[name])])
        assert th.equal(flat_left, flat_right), name
    for key in ("num_timesteps", "_episode_num", "_n_updates", "exploration_rate"):
        assert left_data[key] == right_data[key], key
    assert left_data["num_timesteps"] == TOTAL_STEPS
    assert _monitor_rows(unbroken / RUN) == _monitor_rows(broken / RUN)
    left_evaluations = np.load(unbroken / RUN / "evaluations.npz")
    right_evaluations = np.load(broken / RUN / "evaluations.npz")
    for key in ("timesteps", "results", "ep_lengths"):
        assert np.array_equal(left_evaluations[key], right_evaluations[key]), key
    # One run folder and one TensorBoard run, continued.
    assert sorted(path.name for path in (broken / "logs" / "skill_ddpg").iterdir()) == [RUN.name]
    assert sorted(path.name for path in (broken / "tb" / "HFO-EmptyGoal-v0").iterdir()) == ["SkillDDPG_1"]
    # The first command line is kept.
    assert "--resume" not in (broken / RUN / "HFO-EmptyGoal-v0" / "command.txt").read_text()
    # A resume with other hyperparameters is refused in one line.
    process = _start(broken, "--resume", str(RUN), "-n", str(2 * TOTAL_STEPS))
    _, stderr = process.communicate(timeout=300)
    assert process.returncode == 2 and "its run had other n_timesteps" in stderr.decode()


def _tensors(state: object) -> list[th.Tensor]:
    """Every tensor of a (nested) state dict, in a fixed order."""
    if isinstance(state, th.Tensor):
        return [state.flatten().double()]
    if isinstance(state, dict):
        return [tensor for key in sorted(state, key=str) for tensor in _tensors(state[key])]
    if isinstance(state, (list, tuple)):
        return [tensor for item in state for tensor in _tensors(item)]
    if isinstance(state, (int, float)):
        return [th.tensor([float(state)], dtype=th.float64)]
    return []


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (("--checkpoint-freq", "0"), "--checkpoint-freq must be a positive number"),
        (("--checkpoint-freq", "ten"), "or of minutes (10min)"),
        (("--resume", "nowhere"), "no training_checkpoint.pkl"),
    ],
)
def test_bad_checkpoint_options_are_one_line_errors(
    tmp_path: Path, extra: tuple[str, ...], message: str
) -> None:
    environment = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    result = subprocess.run(
        [sys.executable, "-m", "sb3_hfo.train", *TRAIN, *extra],
        cwd=tmp_path,
        env=environment,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 2
    assert result.stderr.strip().count("\n") == 0 and message in result.stderr
