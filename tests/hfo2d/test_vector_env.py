"""hfo2d's batch (hfo2d.vector): gym.make_vec's vector entry point for every id, game i playing bit for bit like
gym.make(id) seeded with seed + i (against Gymnasium's SyncVectorEnv and the golden rollouts), sharding over worker
processes, action validation and clean shutdown. numpy / gymnasium only (no torch)."""

from __future__ import annotations

import copy
import hashlib
import importlib.util
import os
import pickle
import signal
import subprocess
import sys
import textwrap
import time
from collections import Counter
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode

import hfo2d
from hfo2d.strikers import make_striker
from hfo2d.vector import HFOVectorEnv, ShardedHFOVectorEnv, VectorInfo, split_games, vector_info

SAME_STEP, NEXT_STEP = AutoresetMode.SAME_STEP, AutoresetMode.NEXT_STEP


def _golden_module() -> Any:
    """tests/test_golden_rollouts.py (or tests/hfo2d/...): its cases, digests and digest recipe are reused here."""
    here = Path(__file__).resolve().parent
    for folder in (here, here.parent, here.parent / "hfo2d"):
        path = folder / "test_golden_rollouts.py"
        if path.exists():
            spec = importlib.util.spec_from_file_location("golden_rollouts_for_vector", path)
            module = importlib.util.module_from_spec(spec)
            spec.loader.exec_module(module)
            return module
    raise FileNotFoundError("test_golden_rollouts.py not found beside tests/hfo2d")


GOLDEN = _golden_module()


def _assert_same(mine: Any, theirs: Any, where: str = "info") -> None:
    """Equal values, recursively, with equal array dtypes and shapes (bit for bit for floats)."""
    if isinstance(theirs, dict):
        assert isinstance(mine, dict), where
        assert list(mine) == list(theirs), f"{where}: keys {list(mine)} != {list(theirs)}"
        for key in theirs:
            _assert_same(mine[key], theirs[key], f"{where}[{key!r}]")
    elif isinstance(theirs, np.ndarray):
        assert isinstance(mine, np.ndarray) and mine.dtype == theirs.dtype and mine.shape == theirs.shape, (
            where
        )
        if theirs.dtype == object:
            for index, (a, b) in enumerate(zip(mine, theirs, strict=True)):
                _assert_same(a, b, f"{where}[{index}]")
        else:
            assert mine.tobytes() == theirs.tobytes(), where
    else:
        assert type(mine) is type(theirs) and mine == theirs, f"{where}: {mine!r} != {theirs!r}"


def _actions(steps: int, num_envs: int, seed: int = 0) -> np.ndarray:
    """Random flat actions, with kicks favoured so that episodes also end by goals and outs."""
    actions = np.random.default_rng(seed).random((steps, num_envs, 8), dtype=np.float32)
    actions[:, :, 2] = np.maximum(actions[:, :, 2], 0.5)
    return actions


@pytest.mark.parametrize("env_id", list(hfo2d.ENV_IDS))
@pytest.mark.parametrize("mode", [SAME_STEP, NEXT_STEP], ids=["same_step", "next_step"])
def test_batch_plays_like_sync_vector_env_of_gym_make(env_id: str, mode: AutoresetMode) -> None:
    """Observations, rewards, flags and the whole vector info (final_obs / final_info included) equal Gymnasium's
    SyncVectorEnv over gym.make(id): game i is gym.make(id) reset with seed + i, across auto-resets."""
    num_envs, steps = 3, 260
    batch = gym.make_vec(env_id, num_envs, vectorization_mode="vector_entry_point", autoreset_mode=mode)
    sync = gym.make_vec(env_id, num_envs, vectorization_mode="sync", vector_kwargs={"autoreset_mode": mode})
    assert isinstance(batch, HFOVectorEnv) and batch.metadata["autoreset_mode"] is mode
    assert batch.single_observation_space == sync.single_observation_space
    assert batch.action_space == sync.action_space and batch.observation_space == sync.observation_space
    for mine, theirs in zip(batch.reset(seed=42), sync.reset(seed=42), strict=True):
        _assert_same(mine, theirs, "reset")
    ends = 0
    for actions in _actions(steps, num_envs):
        mine, theirs = batch.step(actions), sync.step(actions)
        for name, a, b in zip(
            ("obs", "reward", "terminated", "truncated", "info"), mine, theirs, strict=True
        ):
            _assert_same(a, b, name)
        ends += int(np.sum(mine[2] | mine[3]))
    assert ends >= 3  # the comparison crossed auto-resets
    batch.close()
    sync.close()


def _golden_digest_of_game(batch: HFOVectorEnv, game: int, seed: int, steps: int, policy: str) -> tuple:
    """GOLDEN.rollout's digest of game ``game`` of a NEXT_STEP batch: the game plays the case's policy, the others
    random actions; at its episode ends the next batch step resets it (and the digest takes the reset
    observation, as the golden rollout's reset() does)."""
    env = batch.envs[game]
    digest = hashlib.sha256()
    statuses: Counter[str] = Counter()
    draws = np.random.default_rng(1000 + seed).random((steps, 8), dtype=np.float32)
    others = np.random.default_rng(seed).random((2 * steps, batch.num_envs, 8), dtype=np.float32)
    striker = make_striker(policy) if policy not in ("random", "wild") else None
    observations, _ = batch.reset(seed=seed - game)  # game i gets seed + i
    obs = observations[game]
    if striker is not None:
        striker.reset()
    digest.update(obs.tobytes())
    goalie = env._keeper_policy if env.goalie == "agent2d" else None
    index = 0
    for batch_step in range(2 * steps):
        resetting = batch._ended[game]
        if index == steps and not resetting:  # (the golden rollout resets after its last step's episode end)
            break
        actions = others[batch_step].copy()
        if not resetting:
            if striker is not None:
                actions[game] = striker(obs)
            elif policy == "wild":
                actions[game] = GOLDEN._wild_action(obs, draws[index])
            else:
                actions[game] = draws[index]
        observations, rewards, terminations, truncations, info = batch.step(actions)
        obs = observations[game]
        if resetting:
            if striker is not None:
                striker.reset()
            digest.update(obs.tobytes())
            goalie = env._keeper_policy if env.goalie == "agent2d" else None
            continue
        index += 1
        terminated, truncated = bool(terminations[game]), bool(truncations[game])
        game_info = {
            key: info[key][game] for key in info if not key.startswith("_") and key != "reward_terms"
        }
        game_info["reward_terms"] = {
            key: value[game] for key, value in info["reward_terms"].items() if not key.startswith("_")
        }
        digest.update(obs.tobytes())
        digest.update(GOLDEN._pack_floats((rewards[game],)))
        digest.update(
            bytes((terminated, truncated, bool(game_info["action_success"]), bool(game_info["kickable"])))
        )
        digest.update(game_info["status"].encode())
        digest.update(game_info["action"].encode())
        digest.update(
            GOLDEN._pack_floats(game_info["player"] + game_info["ball"] + game_info.get("keeper", ()))
        )
        digest.update(
            GOLDEN._pack_floats(tuple(game_info["reward_terms"].values()) + (game_info["kick_power"],))
        )
        digest.update(GOLDEN.struct.pack("<q", env.world._next_uniform))
        if goalie is not None:
            view = goalie.last_view
            if view is not None:
                digest.update(GOLDEN._pack_floats(tuple(getattr(view, name) for name in GOLDEN.VIEW_FIELDS)))
            command = goalie.last_command
            if command is None:
                digest.update(b"none")
            else:
                digest.update(
                    command.kind.encode() + GOLDEN._pack_floats((command.a, command.b, command.foul))
                )
        if terminated or truncated:
            statuses[game_info["status"]] += 1
    return digest.hexdigest(), dict(statuses)


@pytest.mark.parametrize("case", GOLDEN.CASES, ids=[case[0] for case in GOLDEN.CASES])
def test_game_of_batch_reproduces_golden_rollout(case: tuple) -> None:
    """Game 1 of a batch of 2 (game 0 for seed 0), seeded through the batch's seed + i, reproduces the recorded
    golden digest (every observation, reward, info, the goalie's world model and the random stream's position),
    across episodes."""
    name, kwargs, seed, steps, policy = case
    batch = HFOVectorEnv(2, autoreset_mode=NEXT_STEP, **kwargs)
    assert _golden_digest_of_game(batch, min(seed, 1), seed, steps, policy) == GOLDEN.GOLDEN[name]
    batch.close()


@pytest.mark.parametrize("cpus", [1, 64])
def test_the_spinning_hand_over_plays_the_same_games_and_spins_only_with_a_core_each(
    cpus: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Workers and parent hand commands over by shared counters (spinning) only while every stepping process has a
    core of its own; either way game i plays bit for bit as in the one-process batch."""
    import hfo2d.vector as vector

    monkeypatch.setattr(vector, "_available_cpus", lambda: cpus)
    num_envs = 4
    single = gym.make_vec("HFO/Keeper-v1", num_envs, vectorization_mode="vector_entry_point")
    sharded = ShardedHFOVectorEnv("HFO/Keeper-v1", num_envs, 2)
    try:
        assert (sharded._spin_seconds > 0) == (cpus >= 2)
        for mine, theirs in zip(sharded.reset(seed=5), single.reset(seed=5), strict=True):
            _assert_same(mine, theirs, "reset")
        for actions in _actions(60, num_envs, seed=1):
            for name, a, b in zip(
                ("o", "r", "te", "tr", "info"), sharded.step(actions), single.step(actions), strict=True
            ):
                _assert_same(a, b, name)
        # every command was announced and answered once: the counters agree with the pipes
        assert sharded._sent[1] == sharded._answered[1] == 61
    finally:
        sharded.close()


def test_all_shards_in_workers_on_two_cores_do_not_spin(monkeypatch: pytest.MonkeyPatch) -> None:
    """Two workers and a waiting parent are three processes: on two cores none of them spins."""
    import hfo2d.vector as vector

    monkeypatch.setattr(vector, "_available_cpus", lambda: 2)
    sharded = ShardedHFOVectorEnv("HFO/EmptyGoal-v0", 4, 2, in_process_shard=False)
    try:
        assert sharded._spin_seconds == 0.0
    finally:
        sharded.close()


@pytest.mark.parametrize(
    ("num_workers", "in_process_shard"), [(1, False), (2, True), (2, False), (3, True)], ids=str
)
def test_sharded_batch_is_the_unsharded_batch(num_workers: int, in_process_shard: bool) -> None:
    """Whatever the sharding, game i gets seed + i and every step is bit for bit the unsharded batch's: float32
    actions through shared memory, float64 actions and lists through the pipes."""
    num_envs, steps = 5, 150
    single = gym.make_vec(
        "HFO/Keeper-v1", num_envs, vectorization_mode="vector_entry_point", keeper_skill=0.8
    )
    sharded = ShardedHFOVectorEnv(
        "HFO/Keeper-v1", num_envs, num_workers, in_process_shard=in_process_shard, keeper_skill=0.8
    )
    assert len(sharded._processes) == num_workers - in_process_shard
    try:
        assert sharded.get_attr("keeper_skill") == (0.8,) * num_envs
        for mine, theirs in zip(sharded.reset(seed=7), single.reset(seed=7), strict=True):
            _assert_same(mine, theirs, "reset")
        for step, actions in enumerate(_actions(steps, num_envs, seed=3)):
            given: Any = actions
            if step % 3 == 1:
                given = actions.astype(np.float64)
            elif step % 3 == 2:
                given = [list(row) for row in actions.tolist()]
            for name, a, b in zip(
                ("o", "r", "te", "tr", "info"), sharded.step(given), single.step(given), strict=True
            ):
                _assert_same(a, b, name)
    finally:
        sharded.close()
    assert all(not process.is_alive() for process in sharded._processes) and sharded.closed


def test_parameterized_actions_batch_like_single_envs() -> None:
    num_envs = 3
    batch = gym.make_vec(
        "HFO/Keeper-v0", num_envs, vectorization_mode="vector_entry_point", action_format="parameterized"
    )
    sync = gym.make_vec(
        "HFO/Keeper-v0",
        num_envs,
        vectorization_mode="sync",
        vector_kwargs={"autoreset_mode": SAME_STEP},
        action_format="parameterized",
    )
    sharded = ShardedHFOVectorEnv("HFO/Keeper-v0", num_envs, 2, action_format="parameterized")
    batch.action_space.seed(5)
    for mine, theirs in zip(batch.reset(seed=1), sync.reset(seed=1), strict=True):
        _assert_same(mine, theirs, "reset")
    sharded.reset(seed=1)
    for _ in range(120):
        actions = batch.action_space.sample()
        expected = sync.step(actions)
        for a, b, c in zip(batch.step(actions), sharded.step(actions), expected, strict=True):
            _assert_same(a, c)
            _assert_same(b, c)
    sharded.close()
    with pytest.raises(ValueError, match="game 2: parameterized action kind must be 0"):
        kinds, dash, turn, kick = batch.action_space.sample()
        kinds[2] = 7
        batch.step((kinds, dash, turn, kick))


def test_registration_covers_every_hfo2d_id_with_make_kwargs_rules() -> None:
    for env_id in hfo2d.ENV_IDS:
        spec = gym.spec(env_id)
        assert spec.vector_entry_point is not None
        batch = gym.make_vec(env_id, 2, vectorization_mode="vector_entry_point", reward="sparse")
        assert batch.num_envs == 2 and batch.get_attr("reward_name") == ("sparse", "sparse")
        assert batch.get_attr("task") == (gym.make(env_id).unwrapped.task,) * 2
        batch.close()
    assert gym.make_vec("HFO/Keeper-v1", 2).envs[0].goalie == "agent2d"  # the default mode is the batch
    with pytest.raises(ValueError, match="make HFO/Keeper-v0"):
        gym.make_vec("HFO/Keeper-v1", 2, vectorization_mode="vector_entry_point", goalie="hfo2d")
    with pytest.raises(ValueError, match="task='keeper' would make another environment"):
        gym.make_vec("HFO/EmptyGoal-v0", 2, vectorization_mode="vector_entry_point", task="keeper")
    with pytest.raises(ValueError, match="keeper_skill must lie in"):
        gym.make_vec("HFO/Keeper-v1", 2, vectorization_mode="vector_entry_point", keeper_skill=2.0)
    with pytest.raises(ValueError, match="num_envs must be a positive integer"):
        gym.make_vec("HFO/Keeper-v1", 0, vectorization_mode="vector_entry_point")
    with pytest.raises(ValueError, match="autoreset_mode must be one of"):
        gym.make_vec("HFO/Keeper-v1", 2, vectorization_mode="vector_entry_point", autoreset_mode="Disabled")
    with pytest.raises(ValueError, match="would make another environment"):
        ShardedHFOVectorEnv("HFO/StaticKeeper-v0", 2, 1, task="empty_goal")
    with pytest.raises(ValueError, match="unknown hfo2d id"):
        ShardedHFOVectorEnv("HFO/RealKeeper-v0", 2, 1)


def _state(batch: Any) -> list[tuple]:
    return [e for e in batch.get_attr("steps")] + [p for p in batch.call("_status")]


@pytest.mark.parametrize("sharded", [False, True], ids=["one_process", "sharded"])
def test_bad_action_names_the_game_and_changes_nothing(sharded: bool) -> None:
    num_envs = 4
    batch: Any = (
        ShardedHFOVectorEnv("HFO/Keeper-v1", num_envs, 2)
        if sharded
        else gym.make_vec("HFO/Keeper-v1", num_envs, vectorization_mode="vector_entry_point")
    )
    reference = gym.make_vec("HFO/Keeper-v1", num_envs, vectorization_mode="vector_entry_point")
    try:
        with pytest.raises(RuntimeError, match="reset"):
            batch.step(np.zeros((num_envs, 8), np.float32))
        batch.reset(seed=0)
        reference.reset(seed=0)
        actions = _actions(2, num_envs)
        batch.step(actions[0])
        reference.step(actions[0])
        bad = actions[1].copy()
        bad[2, 4] = np.nan
        with pytest.raises(ValueError, match=r"game 2: flat action element 4 is not finite"):
            batch.step(bad)
        bad[2, 4] = 1.5
        with pytest.raises(ValueError, match=r"game 2: flat action element 4 is outside \[0, 1\]"):
            batch.step(bad)
        with pytest.raises(ValueError, match=r"game 3: flat action must have shape \(8,\)"):
            batch.step([list(row) for row in actions[1][:3]] + [[0.5] * 7])
        with pytest.raises(ValueError, match=r"actions must be one per game: shape \(4, 8\), got 3"):
            batch.step(actions[1][:3])
        with pytest.raises(ValueError, match="game 0: flat action must be real numbers"):
            batch.step(np.ones((num_envs, 8), dtype=bool))
        # nothing moved: the next valid step is the reference's
        for a, b in zip(batch.step(actions[1]), reference.step(actions[1]), strict=True):
            _assert_same(a, b)
    finally:
        batch.close()


def test_reset_mask_options_and_seed_lists() -> None:
    batch = HFOVectorEnv(3, task="keeper", goalie="agent2d")
    with pytest.raises(RuntimeError, match="first reset"):
        batch.reset(seed=0, options={"reset_mask": np.array([True, False, True])})
    with pytest.raises(ValueError, match="reset option 'ball' at \\(99, 0\\) is off the pitch"):
        batch.reset(seed=0, options={"ball": (99.0, 0.0)})
    observations, info = batch.reset(seed=[5, None, 9], options={"ball": (30.0, 5.0)})
    single = gym.make("HFO/Keeper-v1")
    first, _ = single.reset(seed=5, options={"ball": (30.0, 5.0)})
    assert observations[0].tobytes() == first.tobytes()
    assert [ball[:2] for ball in info["ball"]] == [(30.0, 5.0)] * 3
    batch.step(_actions(1, 3)[0])
    steps_before = batch.get_attr("steps")
    observations, info = batch.reset(options={"reset_mask": np.array([False, True, False])})
    assert batch.get_attr("steps") == (steps_before[0], 0, steps_before[2])
    assert list(info["_status"]) == [False, True, False]
    with pytest.raises(ValueError, match="seed must be None, an int or a sequence of 3 seeds"):
        batch.reset(seed=[1, 2])


def test_vector_info_is_a_lazy_dict_equal_to_gymnasiums() -> None:
    batch = HFOVectorEnv(4, task="empty_goal")
    batch.reset(seed=3)
    for actions in _actions(120, 4):
        *_, info = batch.step(actions)
    games = batch.step_games(_actions(1, 4, seed=9)[0])
    info = VectorInfo(games)
    assert isinstance(info, dict) and info._games is games  # nothing built yet
    eager = vector_info(games, 4)
    _assert_same(dict(info), eager)
    assert info._games is None  # built once, on the first read
    assert VectorInfo([{"a": 1}]) == {"a": np.array([1]), "_a": np.array([True])}
    _assert_same(pickle.loads(pickle.dumps(VectorInfo(games))), eager)
    _assert_same(copy.deepcopy(VectorInfo(games)), eager)
    fresh = VectorInfo(games)
    fresh["extra"] = 1
    assert "status" in fresh and fresh["extra"] == 1 and len(fresh) == len(eager) + 1
    assert list(VectorInfo(games)) == list(eager) and "status" in VectorInfo(games)
    # a key only some games have: gymnasium's masks and fill values
    mixed = vector_info([{"a": 1.5}, {}, {"a": 2.5, "b": "x"}], 3)
    assert mixed["a"].tolist() == [1.5, 0.0, 2.5] and mixed["_a"].tolist() == [True, False, True]
    assert mixed["b"].tolist() == [None, None, "x"] and mixed["_b"].tolist() == [False, False, True]


def test_split_games() -> None:
    assert split_games(16, 2) == [range(0, 8), range(8, 16)]
    assert split_games(5, 3) == [range(0, 2), range(2, 4), range(4, 5)]


def _pids_alive(pids: list[int]) -> list[int]:
    alive = []
    for pid in pids:
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            continue
        # a zombie (dead, not yet reaped) counts as gone
        status_path = Path(f"/proc/{pid}/status")
        if status_path.exists() and "zombie" in status_path.read_text():
            continue
        alive.append(pid)
    return alive


@pytest.mark.skipif(sys.platform != "linux", reason="reads /proc and sends SIGKILL")
def test_workers_leave_when_their_parent_dies() -> None:
    script = textwrap.dedent(
        """
        import os, signal
        from hfo2d.vector import ShardedHFOVectorEnv
        if __name__ == "__main__":
            env = ShardedHFOVectorEnv("HFO/EmptyGoal-v0", 4, 2, in_process_shard=False)
            env.reset(seed=0)
            print(" ".join(str(process.pid) for process in env._processes), flush=True)
            os.kill(os.getpid(), signal.SIGKILL)
        """
    )
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert result.returncode == -signal.SIGKILL, result.stderr
    pids = [int(pid) for pid in result.stdout.split()]
    assert len(pids) == 2
    deadline = time.monotonic() + 10.0
    while _pids_alive(pids) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not _pids_alive(pids), "orphaned hfo2d workers"
