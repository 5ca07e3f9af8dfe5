"""sb3_hfo.multi_agent: the learning agents of HFO team games as one SB3 VecEnv (parameter-shared training)."""

from __future__ import annotations

import warnings

import gymnasium as gym
import numpy as np
import pytest
from stable_baselines3.common.env_checker import check_env

import hfo2d  # noqa: F401  (registers HFO/HalfFieldOffense-v0)
from hfo2d.team import TeamGame
from sb3_hfo.hybrid_ppo import HybridPPO
from sb3_hfo.multi_agent import TeamVecEnv, make_team_vec_env


def test_slots_are_the_agents_of_every_game() -> None:
    env = make_team_vec_env(3, offense_agents=2, defense_npcs=1, seed=0, monitor=False)
    assert env.num_envs == 6 and env.slots[:3] == [(0, "offense_0"), (0, "offense_1"), (1, "offense_0")]
    assert env.observation_space.shape == (74,) and env.action_space.shape == (8,)
    observations = env.reset()
    assert observations.shape == (6, 74)
    # the two strikers of one game see the same ball and goalie from two places: different observations
    assert not np.array_equal(observations[0], observations[1])
    assert env.get_attr("status") == ["IN_GAME"] * 6


def test_a_game_ends_for_all_its_slots_and_restarts() -> None:
    env = make_team_vec_env(2, offense_agents=2, defense_npcs=1, seed=0, monitor=False, untouched_time=3)
    env.reset()
    idle = np.zeros((4, 8), dtype=np.float32)
    idle[:, 0] = 1.0  # DASH with power 0: nobody moves, so the untouched limit ends every game
    for _ in range(10):
        observations, rewards, dones, infos = env.step(idle)
        if dones.any():
            break
    assert dones.all() and rewards.dtype == np.float32
    for slot, info in enumerate(infos):
        assert info["status"] == "OUT_OF_TIME" and not info["TimeLimit.truncated"]
        assert not np.array_equal(info["terminal_observation"], observations[slot])  # the new episode's
    assert env.get_attr("steps") == [0, 0, 0, 0]


def test_seeds_repeat() -> None:
    traces = []
    for _ in range(2):
        env = make_team_vec_env(2, offense_agents=2, defense_npcs=1, seed=4, monitor=False)
        env.action_space.seed(0)
        trace = [env.reset()]
        for _ in range(20):
            trace.append(env.step(np.stack([env.action_space.sample() for _ in range(env.num_envs)]))[:3])
        traces.append(repr(trace))
    assert traces[0] == traces[1]


def test_errors_name_the_problem() -> None:
    with pytest.raises(ValueError, match="outside side 'offense'"):
        TeamVecEnv([TeamGame(1, 1, 0)])
    with pytest.raises(ValueError, match="share one observation"):
        TeamVecEnv([TeamGame(2, 0, 1), TeamGame(2, 0, 0)])
    with pytest.raises(ValueError, match="n_games"):
        make_team_vec_env(0)


def test_hybrid_ppo_trains_all_strikers_with_one_policy() -> None:
    env = make_team_vec_env(2, offense_agents=2, defense_npcs=1, seed=0)
    model = HybridPPO("MlpPolicy", env, n_steps=16, batch_size=32, n_epochs=1, seed=0)
    before = [p.detach().clone() for p in model.policy.parameters()]
    model.learn(128)
    assert model.num_timesteps == 128
    assert any(
        not np.array_equal(a.numpy(), b.detach().numpy())
        for a, b in zip(before, model.policy.parameters(), strict=True)
    )
    action, _ = model.predict(env.reset(), deterministic=True)
    assert action.shape == (4, 8)


def test_a_learning_goalie_against_scripted_strikers() -> None:
    env = make_team_vec_env(
        2, offense_agents=0, defense_agents=1, scripted_strikers=1, seed=0
    )  # the agent is unum 1
    assert env.num_envs == 2 and env.action_space.shape == (
        11,
    )  # the goalie's DASH, TURN, TACKLE, KICK, CATCH
    model = HybridPPO("MlpPolicy", env, n_steps=16, batch_size=32, n_epochs=1, seed=0)
    model.learn(32)
    assert model.num_timesteps == 32


@pytest.mark.parametrize(
    "kwargs",
    [
        {"offense_agents": 1, "defense_npcs": 1},
        {"offense_agents": 0, "defense_agents": 1, "scripted_strikers": 2, "feature_set": "hfo"},
    ],
)
def test_half_field_offense_passes_sb3_s_checker(kwargs: dict) -> None:
    env = gym.make("HFO/HalfFieldOffense-v0", **kwargs)
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*symmetric and normalized.*")
        check_env(env.unwrapped, warn=True)
    env.close()
