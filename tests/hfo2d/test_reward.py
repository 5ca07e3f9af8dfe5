"""Hausknecht & Stone's shaped reward (DQNHFO computation), its goalie-gap variant and the sparse reward."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hfo2d import features as F
from hfo2d.heuristic import heuristic
from hfo2d.hfo_env import HFOEnv
from hfo2d.reward import (
    GapShapedReward,
    RefundedGapShapedReward,
    ShapedReward,
    SparseReward,
    ball_to_gap_distance,
    ball_to_goal_distance,
    make_reward,
)

MAX_DIST = math.hypot(52.5, 34.0)
DASH_AHEAD = np.array([1, 0, 0, 1.0, 0.5, 0.5, 0, 0.5], dtype=np.float32)  # power 100, direction 0
DASH_BACK = np.array([1, 0, 0, 1.0, 0.0, 0.5, 0, 0.5], dtype=np.float32)  # power 100, direction -180
TURN_NONE = np.array([0, 1, 0, 0, 0.5, 0.5, 0, 0.5], dtype=np.float32)  # turn by 0


def synthetic(ball_proximity: float, goal_proximity: float, kickable: float = -1.0) -> list[float]:
    """58 features with the ball and the goal centre straight ahead of the agent."""
    features = [0.0] * 58
    features[F.BALL_PROXIMITY] = ball_proximity
    features[F.GOAL_CENTER_PROXIMITY] = goal_proximity
    features[F.KICKABLE] = kickable
    features[F.BALL_ANGLE_COS] = features[F.GOAL_CENTER_COS] = 1.0
    return features


def test_ball_to_goal_distance_is_law_of_cosines() -> None:
    # ball and goal both straight ahead: |ball_dist - goal_dist| = |(1 - 0.5) - (1 - 0.2)| = 0.3
    assert ball_to_goal_distance(synthetic(0.5, 0.2)) == pytest.approx(0.3)
    # ball at 90 deg to the goal direction: sqrt(0.5^2 + 0.8^2)
    features = synthetic(0.5, 0.2)
    features[F.BALL_ANGLE_SIN], features[F.BALL_ANGLE_COS] = 1.0, 0.0
    assert ball_to_goal_distance(features) == pytest.approx(math.hypot(0.5, 0.8))


def test_ball_to_goal_distance_matches_geometry_in_feature_units() -> None:
    # Feature units: 2 units = 62.55 m. The law of cosines on exact features gives the true distance.
    env = HFOEnv()
    obs, info = env.reset(seed=0, options={"player": (20.0, -5.0, 37.0), "ball": (30.0, 12.0)})
    true_metres = math.hypot(52.5 - 30.0, 0.0 - 12.0)
    assert ball_to_goal_distance(obs.astype(np.float64)) == pytest.approx(
        2.0 * true_metres / MAX_DIST, abs=1e-5
    )


@pytest.mark.parametrize(
    ("player", "ball", "keeper_y", "target_y"),
    [
        # keeper at the centre: equal gaps, the target is the middle of the gap on the ball's side
        ((20.0, -5.0, 37.0), (30.0, 12.0), 0.0, 3.505),
        ((40.0, 10.0, -120.0), (45.0, -3.0), 0.0, -3.505),
        # keeper moved toward the top post (y < 0): the wider gap is the bottom one, whatever side the ball is on
        ((30.0, 0.0, 90.0), (44.0, -9.0), -3.0, 2.005),
        # keeper beyond the bottom post: clipped to it, the whole mouth is the gap
        ((30.0, 0.0, 0.0), (40.0, 1.0), 9.0, 0.0),
    ],
)
def test_ball_to_gap_distance_matches_geometry(
    player: tuple[float, float, float], ball: tuple[float, float], keeper_y: float, target_y: float
) -> None:
    env = HFOEnv(task="static_keeper", reward="shaped_gap")
    obs, _ = env.reset(seed=0, options={"player": player, "ball": ball, "keeper": (52.5, keeper_y, 180.0)})
    true_metres = math.hypot(52.5 - ball[0], target_y - ball[1])
    assert ball_to_gap_distance(obs.astype(np.float64)) == pytest.approx(
        2.0 * true_metres / MAX_DIST, abs=1e-4
    )


def test_gap_reward_equals_the_shaped_reward_without_a_goalie() -> None:
    env = HFOEnv(reward="shaped_gap")
    obs, _ = env.reset(seed=0, options={"player": (20.0, -5.0, 37.0), "ball": (30.0, 12.0)})
    assert ball_to_gap_distance(obs) == pytest.approx(ball_to_goal_distance(obs), abs=1e-6)
    assert isinstance(make_reward("shaped_gap"), GapShapedReward)


def test_gap_reward_pays_for_a_shot_past_the_keeper_not_at_him() -> None:
    # The same 2 m/cycle shot from 15 m, once at the keeper and once at the gap's middle: the goal-centre reward
    # pays more for the first, the gap reward for the second.
    def second_step_progress(reward: str, ball_velocity: tuple[float, float]) -> float:
        env = HFOEnv(task="static_keeper", reward=reward, noise=False)
        env.reset(seed=0, options={"player": (20.0, 20.0, 0.0), "ball": (37.5, 0.0, *ball_velocity)})
        env.step(TURN_NONE)
        _, _, terminated, _, info = env.step(TURN_NONE)
        assert not terminated
        return info["reward_terms"]["ball_to_goal"]

    speed = 2.0
    at_keeper = (speed, 0.0)
    angle = math.atan2(3.505, 15.0)
    at_gap = (speed * math.cos(angle), speed * math.sin(angle))
    assert second_step_progress("shaped", at_keeper) > second_step_progress("shaped", at_gap)
    assert second_step_progress("shaped_gap", at_gap) > second_step_progress("shaped_gap", at_keeper)


def test_first_step_deltas_are_zero_then_move_to_ball_is_the_proximity_rise() -> None:
    reward = ShapedReward()
    value, terms = reward(synthetic(0.0, 0.0), "IN_GAME")
    assert value == 0.0 and terms == {
        "move_to_ball": 0.0,
        "kick_bonus": 0.0,
        "ball_to_goal": 0.0,
        "goal": 0.0,
    }
    # ball proximity 0.0 -> 0.1 (closer), goal proximity fixed at 0: ball_dist 1.0 -> 0.9, goal_dist 1,
    # ball_to_goal |0.9 - 1.0| vs |1.0 - 1.0|: 0.1 vs 0 -> ball moved away from goal by 0.1 -> -0.3
    value, terms = reward(synthetic(0.1, 0.0), "IN_GAME")
    assert terms["move_to_ball"] == pytest.approx(0.1)
    assert terms["ball_to_goal"] == pytest.approx(-0.3)
    assert value == pytest.approx(0.1 - 0.3)


def test_kick_bonus_paid_once_per_episode() -> None:
    reward = ShapedReward()
    reward(synthetic(0.9, 0.0, kickable=-1.0), "IN_GAME")
    bonuses = [
        reward(synthetic(0.9, 0.0, kickable=k), "IN_GAME")[1]["kick_bonus"] for k in (1.0, -1.0, 1.0, 1.0)
    ]
    assert bonuses == [1.0, 0.0, 0.0, 0.0]
    reward.reset()  # a new episode makes the bonus available again, but not on its first step
    assert reward(synthetic(0.9, 0.0, kickable=1.0), "IN_GAME")[1]["kick_bonus"] == 0.0
    assert reward(synthetic(0.9, 0.0, kickable=-1.0), "IN_GAME")[1]["kick_bonus"] == 0.0
    assert reward(synthetic(0.9, 0.0, kickable=1.0), "IN_GAME")[1]["kick_bonus"] == 1.0


def test_terminal_step_zeroes_deltas_and_goal_pays_exactly_five() -> None:
    reward = ShapedReward()
    reward(synthetic(0.0, 0.0), "IN_GAME")
    value, terms = reward(synthetic(0.5, 0.5, kickable=1.0), "GOAL")
    assert value == 5.0 and terms["goal"] == 5.0 and terms["kick_bonus"] == 0.0
    for status in ("OUT_OF_BOUNDS", "CAPTURED_BY_DEFENSE", "OUT_OF_TIME"):
        reward.reset()
        reward(synthetic(0.0, 0.0), "IN_GAME")
        assert reward(synthetic(0.7, 0.3, kickable=1.0), status)[0] == 0.0


def test_sparse_reward_and_unknown_name() -> None:
    sparse = make_reward("sparse")
    assert isinstance(sparse, SparseReward)
    assert sparse(synthetic(0.0, 0.0), "IN_GAME")[0] == 0.0
    assert sparse(synthetic(0.9, 0.9, kickable=1.0), "IN_GAME")[0] == 0.0
    assert sparse(synthetic(0.0, 0.0), "GOAL")[0] == 1.0
    assert isinstance(make_reward("shaped"), ShapedReward)
    with pytest.raises(ValueError, match="shaped"):
        make_reward("dense")
    with pytest.raises(ValueError, match="unknown reward"):
        HFOEnv(reward="dense")


def shot_at_goal_env(reward: str) -> HFOEnv:
    env = HFOEnv(reward=reward, noise=False)
    # ball 2.5 m before the goal line rolling at 2 m/cycle toward the goal centre; agent far away
    env.reset(seed=0, options={"player": (40.0, 20.0, 0.0), "ball": (50.0, 0.0, 2.0, 0.0)})
    return env


@pytest.mark.parametrize(
    ("reward_name", "goal_reward"), [("shaped", 5.0), ("shaped_gap", 5.0), ("sparse", 1.0)]
)
def test_goal_step_reward_in_env(reward_name: str, goal_reward: float) -> None:
    env = shot_at_goal_env(reward_name)
    _, first, terminated, _, info = env.step(TURN_NONE)  # ball reaches x = 52.0, still in play
    assert not terminated and first == 0.0 and info["reward_terms"]["move_to_ball"] == 0.0
    _, value, terminated, _, info = env.step(TURN_NONE)  # ball crosses 52.585 -> GOAL
    assert terminated and info["status"] == "GOAL"
    assert value == goal_reward and info["reward_terms"]["goal"] == goal_reward


def test_env_first_step_is_zero_even_when_things_move() -> None:
    env = HFOEnv(noise=False)
    env.reset(seed=0, options={"player": (10.0, 0.0, 0.0, 0.3, 0.0), "ball": (20.0, 0.0, 1.0, 0.5)})
    _, value, _, _, info = env.step(DASH_AHEAD)
    assert value == 0.0 and set(info["reward_terms"].values()) == {0.0}
    _, value, _, _, info = env.step(DASH_AHEAD)
    assert value != 0.0 and info["reward_terms"]["move_to_ball"] != 0.0


def test_env_kick_bonus_once() -> None:
    # Agent 1.5 m behind the ball facing it: step 1 (first step) turns by 0; step 2 dashes into kickable range.
    env = HFOEnv(noise=False)
    env.reset(seed=0, options={"player": (10.0, 0.0, 0.0), "ball": (11.5, 0.0)})
    env.step(TURN_NONE)
    _, _, _, _, info = env.step(DASH_AHEAD)
    assert info["kickable"] and info["reward_terms"]["kick_bonus"] == 1.0
    # back off out of range, then come back: kickable again, but no second bonus
    kickable_trace, bonuses = [], []
    for action in [DASH_BACK] * 4 + [DASH_AHEAD] * 4:
        _, _, terminated, _, info = env.step(action)
        assert not terminated
        kickable_trace.append(info["kickable"])
        bonuses.append(info["reward_terms"]["kick_bonus"])
    assert False in kickable_trace and kickable_trace[-1]
    assert bonuses == [0.0] * len(bonuses)


def test_refund_takes_back_the_progress_since_the_ball_was_last_kickable() -> None:
    # ball proximity fixed; goal proximity falls step by step: the ball moves 0.1 units closer each step.
    def play(final_status: str) -> list[float]:
        reward = RefundedGapShapedReward()
        reward.reset()
        terms = [reward(synthetic(0.5, 0.0, kickable=1.0), "IN_GAME")[1]["ball_to_goal"]]  # first step: 0
        terms.append(reward(synthetic(0.5, 0.1, kickable=1.0), "IN_GAME")[1]["ball_to_goal"])  # carried
        terms.append(reward(synthetic(0.5, 0.2, kickable=-1.0), "IN_GAME")[1]["ball_to_goal"])  # kicked
        terms.append(reward(synthetic(0.5, 0.3, kickable=-1.0), "IN_GAME")[1]["ball_to_goal"])
        terms.append(reward(synthetic(0.5, 0.3, kickable=-1.0), final_status)[1]["ball_to_goal"])
        return terms

    assert play("GOAL") == pytest.approx([0.0, 0.3, 0.3, 0.3, 0.0])
    for lost in ("CAPTURED_BY_DEFENSE", "OUT_OF_BOUNDS", "OUT_OF_TIME"):
        assert play(lost) == pytest.approx([0.0, 0.3, 0.3, 0.3, -0.6])  # the carried 0.3 stays paid
    reward = RefundedGapShapedReward()
    reward(synthetic(0.5, 0.0, kickable=-1.0), "IN_GAME")
    reward(synthetic(0.5, 0.1, kickable=-1.0), "IN_GAME")
    assert reward(synthetic(0.5, 0.1), "OUT_OF_TIME", terminated=False)[1]["ball_to_goal"] == 0.0  # truncated


def test_refund_changes_only_the_last_step_of_a_lost_episode() -> None:
    # The scripted striker plays the same episodes under shaped_gap and shaped_gap_refund (the reward does not
    # steer it); the two agree step by step except a lost episode's last step, which takes back what shaped_gap
    # paid for the ball's progress since it was last kickable.
    plain = HFOEnv(task="keeper", reward="shaped_gap")
    refund = HFOEnv(task="keeper", reward="shaped_gap_refund")
    statuses = set()
    for seed in range(12):
        obs, _ = plain.reset(seed=seed)
        refund.reset(seed=seed)
        since_kickable = 0.0
        while True:
            action = heuristic(plain, obs)
            obs, value, terminated, truncated, info = plain.step(action)
            _, refund_value, _, _, refund_info = refund.step(action)
            if terminated and info["status"] != "GOAL":
                assert refund_info["reward_terms"]["ball_to_goal"] == pytest.approx(-since_kickable, abs=1e-9)
                assert refund_value == pytest.approx(value - since_kickable, abs=1e-9)
            else:
                assert refund_value == value
            since_kickable = (
                0.0 if info["kickable"] else since_kickable + info["reward_terms"]["ball_to_goal"]
            )
            if terminated or truncated:
                statuses.add(info["status"])
                break
    assert {"GOAL", "CAPTURED_BY_DEFENSE"} <= statuses
