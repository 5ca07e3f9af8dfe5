"""The carry rewards (hfo2d.reward ``"carry"`` and ``"carry_shot"``): ball progress paid only as new records set in
possession, and the shot speed at the goal mouth as a record."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

from hfo2d import features as F
from hfo2d.reward import (
    CARRY_SHOT_TERM_NAMES,
    CARRY_TERM_NAMES,
    CARRY_WEIGHT,
    CYCLE_COST,
    POSSESSION_RADIUS,
    REWARD_NAMES,
    SHOT_RANGE,
    SHOT_WEIGHT,
    CarryReward,
    CarryShotReward,
    make_reward,
    shot_speed_at_goal,
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


def shot_features(
    ball_xy: tuple[float, float], velocity_xy: tuple[float, float], kickable: bool
) -> list[float]:
    """66 features of an agent at (40, 0) facing the goal (+x), the ball at ``ball_xy`` moving at ``velocity_xy``
    (global metres and m/cycle)."""
    agent_x, agent_y = 40.0, 0.0
    features = [0.0] * 66

    def landmark(index: int, x: float, y: float) -> None:
        dx, dy = x - agent_x, y - agent_y
        distance = math.hypot(dx, dy)
        features[index] = dy / distance  # body angle 0: the bearing is the global heading
        features[index + 1] = dx / distance
        features[index + 2] = 1.0 - 2.0 * distance / F.MAX_HFO_DIST

    landmark(F.GOAL_CENTER_SIN, 52.5, 0.0)
    landmark(F.GOAL_POST_TOP_SIN, 52.5, -F.GOAL_HALF_WIDTH)
    landmark(F.GOAL_POST_BOTTOM_SIN, 52.5, F.GOAL_HALF_WIDTH)
    landmark(F.BALL_ANGLE_SIN, *ball_xy)
    features[F.SELF_BODY_SIN], features[F.SELF_BODY_COS] = 0.0, 1.0
    features[F.KICKABLE] = 1.0 if kickable else -1.0
    speed = math.hypot(*velocity_xy)
    features[F.BALL_SPEED] = 2.0 * speed / F.BALL_SPEED_MAX - 1.0
    features[F.BALL_VEL_ANGLE_SIN] = velocity_xy[1] / speed if speed else 0.0
    features[F.BALL_VEL_ANGLE_COS] = velocity_xy[0] / speed if speed else 1.0
    return features


def test_shot_speed_counts_only_a_path_between_the_posts() -> None:
    ball = (41.0, 0.0)
    assert shot_speed_at_goal(shot_features(ball, (2.0, 0.0), False)) == pytest.approx(2.0, abs=1e-6)
    # 11.5 m to the goal line: 6 m aside is inside the posts (7.01 m), 9 m aside is wide, backwards never counts
    assert shot_speed_at_goal(shot_features(ball, (2.0, 2.0 * 6.0 / 11.5), False)) > 0.0
    assert shot_speed_at_goal(shot_features(ball, (2.0, 2.0 * 9.0 / 11.5), False)) == 0.0
    assert shot_speed_at_goal(shot_features(ball, (-2.0, 0.0), False)) == 0.0
    # the body angle turns the global heading into the body frame: facing +y, a ball moving +x still goes in
    turned = shot_features(ball, (2.0, 0.0), False)
    for sin_index in (F.GOAL_CENTER_SIN, F.GOAL_POST_TOP_SIN, F.GOAL_POST_BOTTOM_SIN, F.BALL_ANGLE_SIN):
        sin, cos = turned[sin_index], turned[sin_index + 1]
        turned[sin_index], turned[sin_index + 1] = -cos, sin  # bearing - 90 degrees
    turned[F.SELF_BODY_SIN], turned[F.SELF_BODY_COS] = 1.0, 0.0
    assert shot_speed_at_goal(turned) == pytest.approx(2.0, abs=1e-6)


def test_shot_record_pays_kicks_near_the_goal_once() -> None:
    reward = make_reward("carry_shot")
    assert isinstance(reward, CarryShotReward) and reward.term_names == CARRY_SHOT_TERM_NAMES
    near, far = (41.0, 0.0), (52.5 - SHOT_RANGE - 2.0, 0.0)
    reward.reset(shot_features(near, (0.0, 0.0), True))
    steps = [
        (near, (0.5, 0.0), True, 0.5),  # a soft touch at the goal after a kickable step: a record of 0.5
        (near, (0.4, 0.0), True, 0.0),  # slower: no record
        (near, (2.0, 0.0), False, 1.5),  # a hard kick: paid its speed above the record
        (near, (2.5, 0.0), False, 0.0),  # faster, but the ball was not kickable before this step: not a kick
    ]
    for ball, velocity, kickable, paid in steps:
        value, terms = reward(shot_features(ball, velocity, kickable), "IN_GAME")
        assert terms["shot"] == pytest.approx(SHOT_WEIGHT * paid, abs=1e-6)
        assert value == pytest.approx(sum(terms.values()))
    # out of range: a kick from beyond SHOT_RANGE pays nothing, however fast
    reward.reset(shot_features(far, (0.0, 0.0), True))
    assert reward(shot_features(far, (3.0, 0.0), True), "IN_GAME")[1]["shot"] == 0.0


def test_soft_dribble_is_paid_its_shot_and_long_shots_are_not() -> None:
    # soft_dribble shoots from 9.5-11.5 m (within SHOT_RANGE); long_shot from ~20 m (outside it)
    env = gym.make("HFO/Keeper-v1", reward="carry_shot").unwrapped
    shot_terms = {}
    for name in ("soft_dribble", "long_shot"):
        striker = make_striker(name)
        total = 0.0
        for seed in range(8):
            obs, _ = env.reset(seed=seed)
            striker.reset()
            while True:
                obs, _, terminated, truncated, info = env.step(striker(obs))
                total += info["reward_terms"]["shot"]
                if terminated or truncated:
                    break
        shot_terms[name] = total / 8
    assert shot_terms["soft_dribble"] > 1.5
    assert shot_terms["long_shot"] < 0.1
