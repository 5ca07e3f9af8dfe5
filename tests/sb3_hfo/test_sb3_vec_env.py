"""sb3_hfo.vec_env: hfo2d's batch through SB3's VecEnv interface (HFOVecEnv, make_hfo_vec_env), bit for bit
a DummyVecEnv of gym.make(id) seeded alike, in one process and sharded; PPO, VecMonitor and VecNormalize on it."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode
from stable_baselines3 import PPO
from stable_baselines3.common.vec_env import DummyVecEnv, VecMonitor, VecNormalize

import hfo2d  # noqa: F401  (registers the ids)
from hfo2d.vector import HFOVectorEnv
from sb3_hfo.vec_env import HFOVecEnv, make_hfo_vec_env

REPO = Path(__file__).resolve().parents[2]


def _assert_same(mine: Any, theirs: Any, where: str) -> None:
    if isinstance(theirs, dict):
        assert sorted(mine) == sorted(theirs), f"{where}: {sorted(mine)} != {sorted(theirs)}"
        for key in theirs:
            _assert_same(mine[key], theirs[key], f"{where}[{key!r}]")
    elif isinstance(theirs, np.ndarray):
        assert mine.dtype == theirs.dtype and mine.shape == theirs.shape, where
        assert mine.tobytes() == theirs.tobytes(), where
    else:
        assert type(mine) is type(theirs) and mine == theirs, f"{where}: {mine!r} != {theirs!r}"


@pytest.mark.parametrize("num_workers", [1, 2])
def test_hfo_vec_env_is_a_seeded_dummy_vec_env_bit_for_bit(num_workers: int) -> None:
    """Observations, float32 rewards, dones, infos (terminal_observation, TimeLimit.truncated) and reset_infos
    equal SB3's DummyVecEnv of gym.make(id) seeded with the same seed, across episode ends."""
    env_id, n_envs, seed = "HFO/Keeper-v1", 3, 11
    mine = make_hfo_vec_env(
        env_id, n_envs, seed=seed, num_workers=num_workers, monitor=False, untouched_time=30
    )
    theirs = DummyVecEnv([lambda: gym.make(env_id, untouched_time=30) for _ in range(n_envs)])
    theirs.seed(seed)
    try:
        _assert_same(mine.reset(), theirs.reset(), "reset")
        for index, (a, b) in enumerate(zip(mine.reset_infos, theirs.reset_infos, strict=True)):
            _assert_same(a, b, f"reset_infos[{index}]")
        actions = np.random.default_rng(0).random((150, n_envs, 8), dtype=np.float32)
        ends = 0
        for step, action in enumerate(actions):
            obs, rewards, dones, infos = mine.step(action)
            their_obs, their_rewards, their_dones, their_infos = theirs.step(action)
            _assert_same(obs, their_obs, f"step {step} obs")
            _assert_same(rewards, their_rewards, f"step {step} rewards")
            _assert_same(dones, their_dones, f"step {step} dones")
            for index in range(n_envs):
                _assert_same(infos[index], their_infos[index], f"step {step} infos[{index}]")
                _assert_same(mine.reset_infos[index], theirs.reset_infos[index], f"step {step} reset_infos")
            ends += int(dones.sum())
        assert ends >= 3
    finally:
        mine.close()
        theirs.close()


def test_ppo_learns_on_it_under_vec_monitor_and_vec_normalize() -> None:
    env = VecNormalize(make_hfo_vec_env("HFO/Keeper-v1", 4, seed=0, untouched_time=20))
    model = PPO(
        "MlpPolicy",
        env,
        n_steps=64,
        batch_size=64,
        n_epochs=1,
        policy_kwargs={"net_arch": [16]},
        seed=0,
        device="cpu",
    )
    model.learn(512)
    assert model.num_timesteps == 512
    assert len(model.ep_info_buffer) > 0  # VecMonitor's episodes reached SB3's logger
    assert env.obs_rms.count > 512  # VecNormalize saw every observation
    env.close()


def test_env_method_get_attr_set_attr_with_indices_and_options() -> None:
    for num_workers in (1, 2):
        env = make_hfo_vec_env("HFO/Keeper-v1", 4, seed=1, num_workers=num_workers, monitor=False)
        assert isinstance(env, HFOVecEnv)
        env.env_method("set_keeper_skill", 0.5, indices=[1, 3])
        assert env.get_attr("keeper_skill") == [1.0, 0.5, 1.0, 0.5]
        assert env.get_attr("keeper_skill", indices=2) == [1.0]
        env.set_attr("untouched_time", 40, indices=[0])
        assert env.get_attr("untouched_time") == [40, 100, 100, 100]
        assert env.env_is_wrapped(gym.Wrapper) == [False] * 4
        env.set_options([{"ball": (30.0, 1.0)}, None, {"ball": (20.0, -3.0)}, None])
        env.reset()
        balls = [info["ball"][:2] for info in env.reset_infos]
        assert balls[0] == (30.0, 1.0) and balls[2] == (20.0, -3.0) and balls[1] != balls[3]
        with pytest.raises(ValueError, match="game index 4 is not one of 0 ... 3"):
            env.get_attr("keeper_skill", indices=[4])
        env.close()


def test_adapter_rules() -> None:
    with pytest.raises(ValueError, match="autoreset_mode SAME_STEP"):
        HFOVecEnv(HFOVectorEnv(2, autoreset_mode=AutoresetMode.NEXT_STEP))
    with pytest.raises(ValueError, match="wraps an hfo2d.vector.HFOVectorEnv"):
        HFOVecEnv(gym.make_vec("HFO/EmptyGoal-v0", 2, vectorization_mode="sync"))
    with pytest.raises(ValueError, match="takes an hfo2d id"):
        make_hfo_vec_env("CartPole-v1", 2)
    with pytest.raises(ValueError, match="would make another environment"):
        make_hfo_vec_env("HFO/Keeper-v1", 2, goalie="hfo2d")
    assert isinstance(make_hfo_vec_env("HFO/EmptyGoal-v0", 2), VecMonitor)


def test_images_from_rgb_array_games() -> None:
    pytest.importorskip("pygame")
    env = make_hfo_vec_env("HFO/EmptyGoal-v0", 2, seed=0, monitor=False, render_mode="rgb_array")
    env.reset()
    images = env.get_images()
    assert len(images) == 2 and images[0].ndim == 3 and images[0].dtype == np.uint8
    assert env.render().ndim == 3  # SB3 tiles them
    env.close()


def test_vector_throughput_benchmark_smoke(tmp_path: Path) -> None:
    """benchmarks/vector_throughput.py runs every contestant and writes its ratios (a tiny run)."""
    out = tmp_path / "vector.json"
    command = [sys.executable, str(REPO / "benchmarks" / "vector_throughput.py"), "--ids", "HFO/EmptyGoal-v0"]
    command += ["--steps", "64", "--rounds", "1", "--num-envs", "4", "--out", str(out)]
    subprocess.run(command, check=True, capture_output=True, timeout=300)
    rows = json.loads(out.read_text())["results"][0]["rows"]
    names = [row["contestant"] for row in rows]
    assert names[0] == "single" and "batch x4" in names and "sb3 sharded x4/2" in names
    assert all(row["steps_per_s_median"] > 0 and row["ratio_to_single_median"] > 0 for row in rows)


def test_vec_monitor_writes_the_env_id_into_its_header(tmp_path) -> None:  # noqa: ANN001
    """VecMonitor reads ``spec.id`` for the monitor.csv header (it wrote "env_id": "None" before)."""
    import json

    from stable_baselines3.common.vec_env import VecMonitor

    from sb3_hfo.vec_env import make_hfo_vec_env

    env = VecMonitor(
        make_hfo_vec_env("HFO/EmptyGoal-v0", 2, seed=0, monitor=False), filename=str(tmp_path / "run")
    )
    assert env.venv.spec.id == "HFO/EmptyGoal-v0"
    env.close()
    header = (tmp_path / "run.monitor.csv").read_text().splitlines()[0]
    assert json.loads(header.lstrip("#"))["env_id"] == "HFO/EmptyGoal-v0"
