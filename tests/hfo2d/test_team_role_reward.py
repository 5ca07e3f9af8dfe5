"""hfo2d.team: the role-aware team reward pays the ball-pull terms to the striker nearest the ball alone."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest

from hfo2d.reward import make_reward
from hfo2d.team import BALL_PULL_TERMS, NEAREST_PULL_REWARDS, TEAM_OFFENSE_REWARDS, TeamGame

#: the conftest fixture chase_actions
Chase = Callable[[dict[str, np.ndarray], bool], dict[str, np.ndarray]]

ROLE_REWARD = "shaped_gap_refund_nearest"


def play_side_by_side(
    strikers: int, steps: int, seed: int, chase_actions: Chase
) -> list[tuple[dict, dict, dict, list[float]]]:
    """The role-aware game and the per-striker ``shaped_gap_refund`` game from one seed with the same actions:
    per cycle (role rewards, role infos, plain infos, each striker's distance to the ball)."""
    role = TeamGame(strikers, 0, 1, reward=ROLE_REWARD, seed=seed)
    plain = TeamGame(strikers, 0, 1, reward=NEAREST_PULL_REWARDS[ROLE_REWARD], seed=seed)
    observations, _ = role.reset(seed=seed)
    plain_observations, _ = plain.reset(seed=seed)
    rows = []
    for step in range(steps):
        actions = chase_actions(observations, step % 3 == 0)
        observations, rewards, terminated, truncated, infos = role.step(actions)
        plain_observations, _, _, _, plain_infos = plain.step(actions)
        for name in role.agent_names:  # same actions, same seed: the same game
            np.testing.assert_array_equal(observations[name], plain_observations[name])
        ball = role.world.ball
        distances = [math.hypot(agent.player.x - ball.x, agent.player.y - ball.y) for agent in role.agents]
        rows.append((rewards, infos, plain_infos, distances))
        if terminated or truncated:
            observations, _ = role.reset()
            plain_observations, _ = plain.reset()
    return rows


def test_the_role_reward_is_offered_and_reads_the_goalie() -> None:
    assert ROLE_REWARD in TEAM_OFFENSE_REWARDS
    assert TeamGame(2, 0, 1, reward=ROLE_REWARD)._reward_needs_goalie_view
    with pytest.raises(ValueError, match="unknown reward"):
        TeamGame(2, 0, 1, reward="shaped_nearest")


def test_one_striker_is_paid_exactly_shaped_gap_refund(chase_actions: Chase) -> None:
    rows = play_side_by_side(1, 300, seed=3, chase_actions=chase_actions)
    pulls = 0
    for rewards, infos, plain_infos, _ in rows:
        assert infos["offense_0"]["reward_terms"] == plain_infos["offense_0"]["reward_terms"]
        assert rewards["offense_0"] == pytest.approx(
            sum(plain_infos["offense_0"]["reward_terms"].values()), abs=1e-12
        )
        pulls += infos["offense_0"]["reward_terms"]["move_to_ball"] != 0.0
    assert pulls > 0  # the lone striker is paid its move to the ball


@pytest.mark.parametrize("strikers", [2, 3])
def test_only_the_striker_nearest_the_ball_is_paid_the_ball_pull(strikers: int, chase_actions: Chase) -> None:
    rows = play_side_by_side(strikers, 400, seed=5, chase_actions=chase_actions)
    withheld = 0
    for rewards, infos, plain_infos, distances in rows:
        nearest = f"offense_{int(np.argmin(distances))}"
        for name, info in infos.items():
            terms, plain_terms = info["reward_terms"], plain_infos[name]["reward_terms"]
            for term, value in terms.items():
                if name == nearest or term not in BALL_PULL_TERMS:
                    assert value == plain_terms[term], (name, term)
                else:
                    assert value == 0.0, (name, term)
                    withheld += plain_terms[term] != 0.0
            assert rewards[name] == pytest.approx(sum(terms.values()), abs=1e-12)
    assert withheld > 0  # the plain reward did pay a striker that was not the nearest


@pytest.mark.parametrize("strikers", [1, 2])
def test_carry_shot_pays_each_striker_its_own_and_the_role_variant_only_the_nearest_pulls(
    strikers: int, chase_actions: Chase
) -> None:
    """``"carry_shot"`` in a team is hfo2d.reward's carry_shot on each striker's own features (it reads the basic
    58 only, so a teammate's block changes nothing); ``"carry_shot_nearest"`` zeroes the ball-pull terms of every
    striker but the nearest and keeps the rest."""
    assert {"carry", "carry_shot", "carry_shot_nearest"} <= set(TEAM_OFFENSE_REWARDS)
    role = TeamGame(strikers, 0, 1, reward="carry_shot_nearest", seed=5)
    plain = TeamGame(strikers, 0, 1, reward="carry_shot", seed=5)
    own = {name: make_reward("carry_shot") for name in plain.agent_names}
    observations, _ = role.reset(seed=5)
    plain_observations, _ = plain.reset(seed=5)
    for name, obs in plain_observations.items():
        own[name].reset(obs)
    zeroed = paid = 0
    for step in range(400):
        actions = chase_actions(observations, step % 3 == 0)
        observations, rewards, terminated, truncated, infos = role.step(actions)
        plain_observations, plain_rewards, _, _, plain_infos = plain.step(actions)
        ball = role.world.ball
        distances = [math.hypot(agent.player.x - ball.x, agent.player.y - ball.y) for agent in role.agents]
        nearest = role.agent_names[int(np.argmin(distances))]
        for name, obs in plain_observations.items():
            expected, _ = own[name](obs, plain.status, terminated)
            assert plain_rewards[name] == pytest.approx(expected, abs=1e-5)  # float32 observations
            terms, plain_terms = infos[name]["reward_terms"], plain_infos[name]["reward_terms"]
            if name == nearest or strikers == 1:
                assert terms == plain_terms
            else:
                assert all(terms[term] == 0.0 for term in BALL_PULL_TERMS)
                assert {k: v for k, v in terms.items() if k not in BALL_PULL_TERMS} == {
                    k: v for k, v in plain_terms.items() if k not in BALL_PULL_TERMS
                }
                zeroed += any(plain_terms[term] != 0.0 for term in BALL_PULL_TERMS)
            paid += plain_terms["ball_to_goal"] != 0.0
        if terminated or truncated:
            observations, _ = role.reset()
            plain_observations, _ = plain.reset()
            for name, obs in plain_observations.items():
                own[name].reset(obs)
    assert paid > 0  # the carry record was paid
    assert zeroed > 0 or strikers == 1  # the check can tell: a non-nearest striker's pull was withheld
