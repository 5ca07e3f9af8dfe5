"""The carry reward (hfo2d.reward ``"carry"``): ball progress paid only as new records set in possession."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

from hfo2d import features as F
from hfo2d.reward import (
    CARRY_TERM_NAMES,
    CARRY_WEIGHT,
    CYCLE_COST,
    POSSESSION_RADIUS,
    REWARD_NAMES,
    CarryReward,
    make_reward,
)
from hfo2d.strikers import make_striker

ON_BALL = 0.97  # ball proximity: the ball 0.94 m from the agent, within POSSESSION_RADIUS
AWAY = 0.5  # the ball 15.6 m from the agent


def synthetic(ball_proximity: float, goal_proximity: float) -> list[float]:
    """66 features with the ball and the goal centre straight ahead: ball-to-goal = |ball_dist - goal_dist|."""
    features = [0.0] * 66
    features[F.BALL_PROXIMITY] = ball_proximity
    features[F.GOAL_CENTER_PROXIMITY] = goal_proximity
    features[F.KICKABLE] = -1.0
    features[F.BALL_ANGLE_COS] = features[F.GOAL_CENTER_COS] = 1.0
    return features


def test_possession_radius_matches_the_synthetic_ball() -> None:
    assert (1.0 - ON_BALL) * 0.5 * F.MAX_HFO_DIST < POSSESSION_RADIUS < (1.0 - AWAY) * 0.5 * F.MAX_HFO_DIST


def test_only_new_records_in_possession_pay() -> None:
    reward = make_reward("carry")
    assert isinstance(reward, CarryReward)
    reward.reset()
    # the goal 0.6 units (ball_dist 0.03) ahead: ball-to-goal = goal_dist - ball_dist
    steps = [
        (ON_BALL, 0.4, 0.0),  # first touch: the record is set, nothing paid (ball-to-goal 0.57)
        (ON_BALL, 0.5, 0.1),  # carried 0.1 closer: a record
        (AWAY, 0.9, 0.0),  # the ball 0.4 further on but far from the agent (a shot): nothing
        (ON_BALL, 0.3, 0.0),  # back on the ball further from the goal: below the record, nothing
        (ON_BALL, 0.5, 0.0),  # back to the record: nothing twice
        (ON_BALL, 0.55, 0.05),  # past it
    ]
    for ball, goal, carried in steps:
        value, terms = reward(synthetic(ball, goal), "IN_GAME")
        assert set(terms) == set(CARRY_TERM_NAMES)
        assert terms["ball_to_goal"] == pytest.approx(CARRY_WEIGHT * carried)
        assert terms["cycle_cost"] == -CYCLE_COST
        assert value == pytest.approx(sum(terms.values()))
    # the episode's end pays no carry; a goal pays 5; a new episode starts without a record
    _, terms = reward(synthetic(ON_BALL, 0.9), "GOAL")
    assert terms["ball_to_goal"] == 0.0 and terms["goal"] == 5.0
    reward.reset()
    assert reward(synthetic(ON_BALL, 0.9), "IN_GAME")[1]["ball_to_goal"] == 0.0


def episode_terms(striker_name: str, seeds: range) -> tuple[int, float, float]:
    """(goals, mean carry term, mean return) of a scripted striker on HFO/Keeper-v1 under the carry reward."""
    env = gym.make("HFO/Keeper-v1", reward="carry").unwrapped
    striker = make_striker(striker_name)
    goals, carried, returns = 0, [], []
    for seed in seeds:
        obs, _ = env.reset(seed=seed)
        striker.reset()
        carry = total = 0.0
        while True:
            obs, value, terminated, truncated, info = env.step(striker(obs))
            carry += info["reward_terms"]["ball_to_goal"]
            total += value
            if terminated or truncated:
                break
        goals += info["status"] == "GOAL"
        carried.append(carry)
        returns.append(total)
    return goals, float(np.mean(carried)), float(np.mean(returns))


def test_carrying_to_a_close_shot_earns_more_than_a_long_shot() -> None:
    # The reward's purpose (research/e6_from_reward.md Part D): the soft dribbler that beats agent2d's goalie is
    # paid more, and carries more, than the striker that shoots from 20 m, and a long shot's flight pays nothing.
    soft_goals, soft_carry, soft_return = episode_terms("soft_dribble", range(16))
    long_goals, long_carry, long_return = episode_terms("long_shot", range(16))
    assert soft_goals > long_goals
    assert soft_carry > long_carry + 0.5
    assert soft_return > long_return + 3.0


def test_the_reset_step_lists_every_term_of_the_reward_it_uses() -> None:
    """``info["reward_terms"]`` has the same keys on the reset step as on every later step, for each reward."""
    for reward in REWARD_NAMES:
        env = gym.make("HFO/Keeper-v1", reward=reward)
        _, reset_info = env.reset(seed=0)
        _, _, _, _, step_info = env.step(env.action_space.sample())
        assert set(reset_info["reward_terms"]) == set(step_info["reward_terms"]), reward
        assert all(value == 0.0 for value in reset_info["reward_terms"].values())
        env.close()
