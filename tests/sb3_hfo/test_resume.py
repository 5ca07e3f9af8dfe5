"""Resumable training (sb3_hfo.resume): a run stopped at a checkpoint and continued in a fresh process equals an
unbroken one, and a checkpoint write killed half-way leaves the previous checkpoint usable.

This file is also the worker the tests start in fresh processes: ``python test_resume.py MODE ...``.
"""

from __future__ import annotations

import io
import os
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import cloudpickle
import numpy as np
import pytest
import torch as th
from stable_baselines3.common.callbacks import BaseCallback, StopTrainingOnMaxEpisodes
from stable_baselines3.common.env_util import make_vec_env
from stable_baselines3.common.noise import NormalActionNoise
from stable_baselines3.common.save_util import load_from_zip_file

import hfo2d  # noqa: F401  (registers HFO/EmptyGoal-v0)
from sb3_hfo.callbacks import ActionNoiseDecayCallback, HFOEpisodeStatsCallback
from sb3_hfo.common.schedules import LinearToZero
from sb3_hfo.resume import (
    TrainingCheckpointCallback,
    load_training_state,
    remaining_timesteps,
    save_training_state,
)
from sb3_hfo.skill_ddpg import SkillDDPG

#: Environment steps of the short run (2 envs) and where the stopped run's checkpoint is taken.
TOTAL_STEPS = 600
CHECKPOINT_STEPS = 300
N_ENVS = 2


def build_run(tensorboard_log: str | None = None) -> tuple[SkillDDPG, list[BaseCallback]]:
    """A tiny E2-like run: two skills, updates from step 100 on, a replay buffer that wraps (400 < 600), epsilon
    and the critic's learning rate on schedules, Gaussian noise annealed by a callback, Monte Carlo mixing."""
    env = make_vec_env("HFO/EmptyGoal-v0", n_envs=N_ENVS, seed=0)
    model = SkillDDPG(
        "MlpPolicy",
        env,
        learning_rate_critic=LinearToZero(1e-3),
        buffer_size=400,
        learning_starts=100,
        batch_size=16,
        tau=0.01,
        gamma=0.95,
        exploration_initial_eps=0.5,
        exploration_final_eps=0.05,
        exploration_fraction=0.5,
        exploration_keep_parameters=True,
        mc_mixing=0.2,
        action_noise=NormalActionNoise(np.zeros(8), np.full(8, 0.2)),
        policy_kwargs={"net_arch": [16, 16], "n_skills": 2, "skill_router": "field_half", "domain": "hfo"},
        tensorboard_log=tensorboard_log,
        seed=0,
    )
    callbacks: list[BaseCallback] = [
        HFOEpisodeStatsCallback(),
        ActionNoiseDecayCallback(final_std=0.05, decay_fraction=0.7),
        StopTrainingOnMaxEpisodes(max_episodes=1000),
    ]
    return model, callbacks


class _FirstCheckpointOnly(TrainingCheckpointCallback):
    """Keeps its first checkpoint (the stopped run's), not the one written when the budget ends."""

    def save(self) -> None:
        if self._last_saved < 0:
            super().save()


def train(checkpoint: Path | None, resume: str, final: Path, tensorboard_log: str | None = None) -> None:
    """Train to :data:`TOTAL_STEPS`, then save the final training state to ``final``.

    :param resume: ``"no"``: a new run (writing ``checkpoint``, when given, at :data:`CHECKPOINT_STEPS`);
        ``"continue"``: from ``checkpoint`` with ``learn(remaining, reset_num_timesteps=False)``; ``"restart"``: from
        ``checkpoint`` with ``learn(TOTAL_STEPS)`` as the first run called it (rl-zoo3's way).
    """
    model, callbacks = build_run(tensorboard_log)
    all_callbacks = list(callbacks)
    if checkpoint is not None:
        saver = _FirstCheckpointOnly(checkpoint, save_freq=CHECKPOINT_STEPS, callbacks=callbacks)
        if resume != "no":
            saver.resume(model)
            saver._last_saved = CHECKPOINT_STEPS  # the resumed half writes no checkpoint of its own
        all_callbacks.append(saver)
    if resume == "continue":
        model.learn(
            remaining_timesteps(model, TOTAL_STEPS), callback=all_callbacks, reset_num_timesteps=False
        )
    else:
        model.learn(TOTAL_STEPS, callback=all_callbacks)
    save_training_state(final, model, callbacks)


def _fresh_process(*args: str, wait: bool = True) -> subprocess.Popen[bytes]:
    environment = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    process = subprocess.Popen([sys.executable, __file__, *args], env=environment, stderr=subprocess.PIPE)
    if wait:
        _, stderr = process.communicate(timeout=120)
        assert process.returncode == 0, stderr.decode()
    return process


def _read(path: Path) -> dict[str, Any]:
    with path.open("rb") as file:
        return cloudpickle.load(file)


def _assert_same(left: Any, right: Any, where: str) -> None:
    if isinstance(left, th.Tensor):
        assert th.equal(left, right), where
    elif isinstance(left, np.ndarray):
        assert np.array_equal(left, right), where
    elif isinstance(left, dict):
        assert left.keys() == right.keys(), where
        for key in left:
            _assert_same(left[key], right[key], f"{where}.{key}")
    elif isinstance(left, (list, tuple)):
        assert len(left) == len(right), where
        for index, (a, b) in enumerate(zip(left, right, strict=True)):
            _assert_same(a, b, f"{where}[{index}]")
    else:
        assert left == right, where


def assert_same_training_state(left_path: Path, right_path: Path) -> dict[str, Any]:
    """The two final states have identical weights, optimizer states, counters, replay buffer, random generators
    and callback counters; returns the left one's model data."""
    left, right = _read(left_path), _read(right_path)
    left_data, left_params, _ = load_from_zip_file(io.BytesIO(left["model_zip"]))
    right_data, right_params, _ = load_from_zip_file(io.BytesIO(right["model_zip"]))
    _assert_same(left_params, right_params, "params")  # policy weights and every optimizer's state
    for key in (
        "num_timesteps",
        "_episode_num",
        "_n_updates",
        "_total_timesteps",
        "_current_progress_remaining",
        "exploration_rate",
        "_last_obs",
        "_last_episode_starts",
        "_skill_steps",
    ):
        _assert_same(left_data[key], right_data[key], key)

    # Episode returns and lengths (not their wall-clock times).
    def returns_and_lengths(data: dict[str, Any]) -> list[tuple[float, int]]:
        return [(info["r"], info["l"]) for info in data["ep_info_buffer"]]

    assert returns_and_lengths(left_data) == returns_and_lengths(right_data)
    left_noises = [noise._sigma for noise in left_data["action_noise"].noises]
    right_noises = [noise._sigma for noise in right_data["action_noise"].noises]
    _assert_same(left_noises, right_noises, "action noise sigma")
    left_buffer, right_buffer = left["replay_buffer"], right["replay_buffer"]
    assert (left_buffer.pos, left_buffer.full) == (right_buffer.pos, right_buffer.full)
    for name in (
        "observations",
        "next_observations",
        "actions",
        "rewards",
        "dones",
        "timeouts",
        "mc_returns",
    ):
        _assert_same(getattr(left_buffer, name), getattr(right_buffer, name), f"replay_buffer.{name}")
    _assert_same(
        {k: v for k, v in left["rng"].items() if k != "python"},
        {k: v for k, v in right["rng"].items() if k != "python"},
        "rng",
    )
    assert left["rng"]["python"] == right["rng"]["python"]
    for left_cb, right_cb in zip(left["callbacks"], right["callbacks"], strict=True):
        left_attributes = cloudpickle.loads(left_cb["attributes"])
        right_attributes = cloudpickle.loads(right_cb["attributes"])
        _assert_same(left_attributes, right_attributes, left_cb["class"])
    return left_data


@pytest.fixture(scope="module")
def stopped_run(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A folder with the unbroken run's final state and the checkpoint (and final state) of the same run writing a
    checkpoint at :data:`CHECKPOINT_STEPS`."""
    folder = tmp_path_factory.mktemp("stopped_run")
    # Unbroken, with no checkpoint callback at all.
    train(None, resume="no", final=folder / "unbroken.pkl")
    # The same run writing a checkpoint half-way (writing it must change nothing).
    train(
        folder / "checkpoint.pkl",
        resume="no",
        final=folder / "checkpointed.pkl",
        tensorboard_log=str(folder / "tb"),
    )
    return folder


@pytest.mark.parametrize("resume", ["continue", "restart"])
def test_a_resumed_run_in_a_fresh_process_equals_an_unbroken_one(
    stopped_run: Path, tmp_path: Path, resume: str
) -> None:
    saved_data, _, _ = load_from_zip_file(io.BytesIO(_read(stopped_run / "checkpoint.pkl")["model_zip"]))
    assert saved_data["num_timesteps"] == CHECKPOINT_STEPS
    tensorboard_log = stopped_run / "tb"  # where the checkpoint's logger writes
    event_files = len(list((tensorboard_log / "SkillDDPG_1").iterdir()))
    _fresh_process(
        resume, str(stopped_run / "checkpoint.pkl"), str(tmp_path / "resumed.pkl"), str(tensorboard_log)
    )

    data = assert_same_training_state(stopped_run / "unbroken.pkl", stopped_run / "checkpointed.pkl")
    assert_same_training_state(stopped_run / "unbroken.pkl", tmp_path / "resumed.pkl")
    # The short run is long enough to test something: updates after the checkpoint, episodes, a wrapped buffer.
    assert data["num_timesteps"] == TOTAL_STEPS
    assert data["_n_updates"] > CHECKPOINT_STEPS // N_ENVS
    assert data["_episode_num"] >= 2
    assert _read(tmp_path / "resumed.pkl")["replay_buffer"].full
    # TensorBoard continued in the same run folder.
    assert sorted(path.name for path in tensorboard_log.iterdir()) == ["SkillDDPG_1"]
    assert len(list((tensorboard_log / "SkillDDPG_1").iterdir())) == event_files + 1  # the resumed process's
    # and a checkpoint written by the resumed process resumes TensorBoard again (a run resumed twice once lost it)
    assert (
        _read(tmp_path / "resumed.pkl")["logger"]["formats"]
        == _read(stopped_run / "checkpoint.pkl")["logger"]["formats"]
    )
    assert "tensorboard" in _read(tmp_path / "resumed.pkl")["logger"]["formats"]


def test_resuming_restores_counters_into_a_fresh_model(tmp_path: Path) -> None:
    model, callbacks = build_run()
    checkpoint = tmp_path / "checkpoint.pkl"
    saver = TrainingCheckpointCallback(checkpoint, save_freq=200, callbacks=callbacks)
    model.learn(400, callback=[*callbacks, saver])
    fresh, fresh_callbacks = build_run()
    assert fresh.num_timesteps == 0
    state = TrainingCheckpointCallback(checkpoint, save_freq=200, callbacks=fresh_callbacks).resume(fresh)
    assert state.path == checkpoint
    assert fresh.num_timesteps == 400
    assert fresh._total_timesteps == 400
    assert fresh_callbacks[0].episodes == callbacks[0].episodes  # type: ignore[attr-defined]
    assert fresh_callbacks[2].n_episodes == callbacks[2].n_episodes  # type: ignore[attr-defined]
    assert fresh_callbacks[1].n_calls == callbacks[1].n_calls == 200
    assert remaining_timesteps(fresh, 1000) == 600


def test_a_checkpoint_of_another_run_is_refused_and_changes_nothing(tmp_path: Path) -> None:
    model, callbacks = build_run()
    checkpoint = tmp_path / "checkpoint.pkl"
    model.learn(100, callback=callbacks)
    save_training_state(checkpoint, model, callbacks)
    fresh, fresh_callbacks = build_run()
    with pytest.raises(ValueError, match="callbacks"):
        load_training_state(checkpoint, fresh, fresh_callbacks[:2])
    assert fresh.num_timesteps == 0
    (tmp_path / "junk.pkl").write_bytes(b"not a checkpoint")
    with pytest.raises(ValueError, match="not a"):
        load_training_state(tmp_path / "junk.pkl", fresh, fresh_callbacks)


def test_save_freq_must_be_positive() -> None:
    with pytest.raises(ValueError, match="save_freq"):
        TrainingCheckpointCallback("x.pkl", save_freq=0)
    with pytest.raises(ValueError, match="save_minutes"):
        TrainingCheckpointCallback("x.pkl", save_minutes=-1.0)
    with pytest.raises(ValueError, match="give save_freq"):
        TrainingCheckpointCallback("x.pkl")


class _CountingSaves(TrainingCheckpointCallback):
    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.saved_at: list[int] = []

    def save(self) -> None:
        super().save()
        self.saved_at.append(self.model.num_timesteps)


def test_checkpoints_on_a_wall_clock_interval(tmp_path: Path) -> None:
    model, callbacks = build_run()
    # An interval of 60 ns: every rollout of this run takes longer, so every one ends with a checkpoint.
    saver = _CountingSaves(tmp_path / "checkpoint.pkl", callbacks=callbacks, save_minutes=1e-9)
    model.learn(40, callback=[*callbacks, saver])
    assert saver.saved_at == list(range(0, 42, 2))  # each rollout (2 envs) and the end of the budget


class _HangWhenPickled:
    """Pickling it (half-way through a checkpoint) signals through a file, then hangs until the process is killed."""

    def __init__(self, signal_file: str) -> None:
        self.signal_file = signal_file

    def __reduce__(self) -> Any:
        Path(self.signal_file).write_text("writing")
        time.sleep(600)
        raise AssertionError("not killed")


def test_a_checkpoint_killed_mid_write_leaves_the_previous_one_usable(tmp_path: Path) -> None:
    checkpoint = tmp_path / "checkpoint.pkl"
    signal_file = tmp_path / "writing"
    process = _fresh_process("kill-mid-write", str(checkpoint), str(signal_file), wait=False)
    try:
        deadline = time.monotonic() + 120
        while not signal_file.exists():
            assert process.poll() is None, process.stderr.read().decode()  # type: ignore[union-attr]
            assert time.monotonic() < deadline, "the worker never started its second checkpoint"
            time.sleep(0.05)
        temporary = list(tmp_path.glob(".checkpoint.pkl.*.tmp"))
        assert len(temporary) == 1 and temporary[0].stat().st_size > 0  # the new checkpoint was half written
        process.send_signal(signal.SIGKILL)
        process.wait(timeout=30)
    finally:
        if process.poll() is None:
            process.kill()
        process.stderr.close()  # type: ignore[union-attr]
    fresh, callbacks = build_run()
    load_training_state(checkpoint, fresh, callbacks)
    assert fresh.num_timesteps == 100  # the first checkpoint, whole
    # The next save clears the killed write's leftover.
    save_training_state(checkpoint, fresh, callbacks)
    assert not list(tmp_path.glob(".checkpoint.pkl.*.tmp"))


def _worker(argv: list[str]) -> None:
    mode = argv[0]
    if mode in ("continue", "restart"):
        checkpoint, final, tensorboard_log = argv[1:]
        th.set_num_threads(1)
        train(Path(checkpoint), resume=mode, final=Path(final), tensorboard_log=tensorboard_log)
    elif mode == "kill-mid-write":
        checkpoint, signal_file = argv[1:]
        model, callbacks = build_run()
        model.learn(100, callback=callbacks)
        save_training_state(checkpoint, model, callbacks)
        save_training_state(checkpoint, model, callbacks, run_info={"hang": _HangWhenPickled(signal_file)})
    else:
        raise SystemExit(f"unknown mode {mode!r}")


if __name__ == "__main__":
    _worker(sys.argv[1:])
