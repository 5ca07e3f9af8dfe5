"""The HFO envs pass Stable-Baselines3's env checker (tests/hfo2d/test_env.py runs Gymnasium's, without torch)."""

from __future__ import annotations

import warnings

import gymnasium as gym
import pytest
from stable_baselines3.common.env_checker import check_env

import hfo2d


@pytest.mark.parametrize("env_id", hfo2d.ENV_IDS)
def test_registered_env_passes_sb3_s_checker(env_id: str) -> None:
    env = gym.make(env_id)
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*symmetric and normalized.*")
        check_env(env.unwrapped, warn=True)
    env.close()
