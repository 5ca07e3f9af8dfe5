"""hfo2d.team: the gap rewards of a team's strikers read the goalie where HFO/Keeper-v1 has it, not the teammate."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

from hfo2d.features import FEATURES_PER_PLAYER, NUM_BASIC_FEATURES, keeper_view_from_hfo
from hfo2d.reward import make_reward
from hfo2d.team import TEAM_OFFENSE_REWARDS, TeamGame

#: the conftest fixture chase_actions
Chase = Callable[[dict[str, np.ndarray], bool], dict[str, np.ndarray]]
TEAMMATE_BLOCK = np.s_[NUM_BASIC_FEATURES : NUM_BASIC_FEATURES + FEATURES_PER_PLAYER]


@pytest.mark.parametrize("reward", ["shaped_gap", "shaped_gap_refund"])
def test_a_striker_with_a_teammate_is_paid_as_against_the_goalie_alone(
    reward: str, chase_actions: Chase
) -> None:
    assert reward in TEAM_OFFENSE_REWARDS
    game = TeamGame(2, 0, 1, reward=reward, seed=0)
    observations, _ = game.reset(seed=11)
    # the reward as HFO/Keeper-v1 computes it: on the features without the teammate's block
    keeper_v1 = {name: make_reward(reward) for name in game.agent_names}
    naive = {name: make_reward(reward) for name in game.agent_names}  # reading the teammate as the goalie
    for name, obs in observations.items():
        keeper_v1[name].reset(np.delete(obs, TEAMMATE_BLOCK))
        naive[name].reset(obs)
    paid, naive_paid, ends = [], [], 0
    for step in range(400):
        observations, rewards, terminated, truncated, _ = game.step(
            chase_actions(observations, kick=step % 3 == 0)
        )
        status = game.status
        for name, obs in observations.items():
            paid.append(
                (rewards[name], keeper_v1[name](np.delete(obs, TEAMMATE_BLOCK), status, terminated)[0])
            )
            naive_paid.append(naive[name](obs, status, terminated)[0])
        if terminated or truncated:
            ends += 1
            observations, _ = game.reset()
            for name, obs in observations.items():
                keeper_v1[name].reset(np.delete(obs, TEAMMATE_BLOCK))
                naive[name].reset(obs)
    assert ends >= 1
    game_rewards = np.array([pair[0] for pair in paid])
    np.testing.assert_allclose(game_rewards, [pair[1] for pair in paid], rtol=0, atol=1e-6)
    # the check can tell: reading the teammate's block as the goalie's pays differently
    assert np.abs(game_rewards - np.array(naive_paid)).max() > 1e-3


def test_one_striker_against_the_goalie_reads_its_own_features() -> None:
    game = TeamGame(1, 0, 1, reward="shaped_gap_refund", seed=0)
    assert not game._reward_needs_goalie_view
    assert TeamGame(2, 0, 1, reward="shaped_gap_refund")._reward_needs_goalie_view
    assert TeamGame(1, 0, 2, reward="shaped_gap")._reward_needs_goalie_view
    assert not TeamGame(2, 0, 1, reward="shaped")._reward_needs_goalie_view  # reads the basic features only


@pytest.mark.parametrize(("offense", "npcs"), [(2, 1), (2, 2), (1, 2)])
def test_the_real_backends_keeper_view_matches_the_team_games(
    offense: int, npcs: int, chase_actions: Chase
) -> None:
    """hfo2d.real_teams reads the goalie out of HFO master's vector by its uniform number
    (features.keeper_view_from_hfo); on hfo2d's own master vectors it gives TeamGame's reward view of the same state,
    including states where the field defender, not the goalie, fills the first opponent slot."""
    game = TeamGame(offense, 0, npcs, feature_set="hfo", reward="shaped_gap_refund", seed=0)
    observations, _ = game.reset(seed=3)
    checked = goalie_not_first = 0
    for step in range(300):
        for name, obs in observations.items():
            agent = game._agents_by_name[name]
            expected = game._reward_features(agent, game._paper_features(agent))
            got = keeper_view_from_hfo(obs.tolist(), offense - 1, npcs)
            assert len(got) == NUM_BASIC_FEATURES + FEATURES_PER_PLAYER
            np.testing.assert_allclose(got, expected, rtol=0, atol=2e-6)  # the observation's float32 rounding
            first_opponent_unum = obs[
                NUM_BASIC_FEATURES + FEATURES_PER_PLAYER * (offense - 1 + npcs) + offense - 1
            ]
            goalie_not_first += npcs > 1 and round(first_opponent_unum * 100) != 1
            checked += 1
        observations, _, terminated, truncated, _ = game.step(chase_actions(observations, kick=step % 3 == 0))
        if terminated or truncated:
            observations, _ = game.reset()
    assert checked >= 300
    if npcs > 1:
        assert goalie_not_first > 0  # the unum lookup was exercised, not just "the first opponent"


def test_keeper_view_without_a_listed_goalie_is_the_basic_features() -> None:
    game = TeamGame(2, 0, 0, feature_set="hfo", seed=0)
    observations, _ = game.reset(seed=1)
    obs = observations["offense_0"].tolist()
    assert len(keeper_view_from_hfo(obs, 1, 0)) == NUM_BASIC_FEATURES
    with pytest.raises(ValueError, match="features"):
        keeper_view_from_hfo(obs[:-1], 1, 0)
