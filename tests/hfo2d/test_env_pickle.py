"""An HFO env pickled mid-episode (what resumable training checkpoints) plays on exactly as the original."""

from __future__ import annotations

import pickle

import gymnasium as gym
import numpy as np
import pytest

import hfo2d  # noqa: F401  (registers the HFO/* ids)


@pytest.mark.parametrize("env_id", ["HFO/EmptyGoal-v0", "HFO/Keeper-v1"])
def test_a_pickled_env_continues_as_the_original(env_id: str) -> None:
    original = gym.make(env_id)
    original.reset(seed=3)
    actions = np.random.default_rng(0)
    for _ in range(20):
        original.step(original.action_space.sample())
    copy = pickle.loads(pickle.dumps(original))
    episodes = 0
    for _ in range(400):
        action = actions.uniform(0.0, 1.0, size=original.action_space.shape).astype(np.float32)
        observation, reward, terminated, truncated, info = original.step(action)
        copied_observation, copied_reward, *copied_ends, copied_info = copy.step(action)
        assert np.array_equal(observation, copied_observation)
        assert (reward, terminated, truncated) == (copied_reward, *copied_ends)
        assert info == copied_info
        if terminated or truncated:
            episodes += 1
            # the next start positions come from the env's own np_random, pickled with it
            assert np.array_equal(original.reset()[0], copy.reset()[0])
    assert episodes >= 1


def test_an_env_pickles_after_hfo2d_is_reloaded() -> None:
    """The registry keeps the creator made at the first import; a reload must not make its envs unpicklable."""
    import importlib

    importlib.reload(hfo2d)
    env = gym.make("HFO/EmptyGoal-v0")
    env.reset(seed=1)
    copy = pickle.loads(pickle.dumps(env))
    action = np.full(env.action_space.shape, 0.5, dtype=np.float32)
    assert np.array_equal(env.step(action)[0], copy.step(action)[0])
