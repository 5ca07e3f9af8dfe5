"""A striker against a learning goalie (a defense agent with unum 1) sees what it sees in HFO/Keeper-v1.

The adversarial keeper's loop (benchmarks/adversarial_keeper.py) plays strikers trained on HFO/Keeper-v1 against
a goalie that is a TeamGame defense agent; they must get the same observation and, with the same reward name, the
same reward from the same state.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import hfo2d  # noqa: F401  (registers the HFO/* ids)
from hfo2d.reward import make_reward
from hfo2d.strikers import make_striker
from hfo2d.team import TEAM_OFFENSE_REWARDS, TeamGame


def _copy_state(game: TeamGame, env) -> None:  # noqa: ANN001  (HFOEnv, unwrapped)
    ball = game.world.ball
    env.world.place_ball(ball.x, ball.y, ball.vx, ball.vy)
    for source, target in zip(game.world.players, env.world.players, strict=True):
        env.world.place_player(target, source.x, source.y, source.body_deg, source.vx, source.vy)
        target.stamina = source.stamina  # placing a player does not touch its stamina (a feature)


@pytest.mark.parametrize("reward", ["shaped", "shaped_gap_refund"])
def test_the_striker_sees_a_goalie_agent_as_keeper_v1_shows_agent2d_s(reward: str) -> None:
    game = TeamGame(1, 1, 0, reward=reward, seed=3)
    assert game.agent("defense_0").player.goalie  # the lone defense agent plays goalie (unum 1)
    env = gym.make("HFO/Keeper-v1").unwrapped
    env.reset(seed=3)
    striker = make_striker("soft_dribble")
    reference_reward = make_reward(reward)
    goalie_actions = np.random.default_rng(0)
    observations, _ = game.reset(seed=3)
    _copy_state(game, env)
    features = env._features()
    np.testing.assert_array_equal(observations["offense_0"], np.asarray(features, dtype=np.float32))
    reference_reward.reset(features)
    moved = 0.0
    for _ in range(150):
        goalie_action = goalie_actions.uniform(0.0, 1.0, size=11).astype(np.float32)
        observations, rewards, terminated, truncated, _ = game.step(
            {"offense_0": striker(observations["offense_0"]), "defense_0": goalie_action}
        )
        _copy_state(game, env)
        features = env._features()
        np.testing.assert_array_equal(observations["offense_0"], np.asarray(features, dtype=np.float32))
        expected, _ = reference_reward(features, game.status, terminated)
        assert rewards["offense_0"] == pytest.approx(expected, abs=1e-6)
        goalie = game.agent("defense_0").player
        moved = max(moved, abs(goalie.x - 52.5) + abs(goalie.y))
        if terminated or truncated:
            break
    assert moved > 0.5  # the goalie agent moved, so its block of the striker's features was exercised


def test_the_team_game_offers_keeper_v1_s_gap_rewards() -> None:
    assert {"shaped_gap", "shaped_gap_refund"} <= set(TEAM_OFFENSE_REWARDS)
    with pytest.raises(ValueError, match="unknown reward"):
        TeamGame(1, 1, 0, reward="shaped_gap_refunded")
