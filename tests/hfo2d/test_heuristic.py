"""Scripted striker (hfo2d.heuristic): scores on the empty goal from the observation alone."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import hfo2d  # noqa: F401  (registers the environments)
from hfo2d.demo import run_demo
from hfo2d.features import (
    BALL_ANGLE_COS,
    BALL_ANGLE_SIN,
    BALL_PROXIMITY,
    BALL_SPEED,
    GOAL_CENTER_COS,
    GOAL_CENTER_PROXIMITY,
    GOAL_CENTER_SIN,
    KICKABLE,
    MAX_HFO_DIST,
)
from hfo2d.heuristic import DASH, KICK, TURN, heuristic, heuristic_command

EPISODES = 200


def play(env: gym.Env, episodes: int, seed: int = 0) -> tuple[float, float]:
    """Scoring rate and mean episode length of the heuristic over ``episodes`` seeded episodes."""
    goals = 0
    steps = 0
    for episode in range(episodes):
        obs, _ = env.reset(seed=seed + episode)
        while True:
            action = heuristic(env, obs)
            assert env.action_space.contains(action)
            obs, _, terminated, truncated, info = env.step(action)
            steps += 1
            if terminated or truncated:
                break
        goals += info["status"] == "GOAL"
    return goals / episodes, steps / episodes


def test_scores_on_the_empty_goal() -> None:
    env = gym.make("HFO/EmptyGoal-v0")  # noise on (the default)
    rate, mean_length = play(env, EPISODES)
    env.close()
    assert rate >= 0.9
    assert mean_length < 150  # it dribbles and shoots; it does not wait for the clock


def test_parameterized_action_format() -> None:
    env = gym.make("HFO/EmptyGoal-v0", action_format="parameterized")
    rate, _ = play(env, 10, seed=1000)
    env.close()
    assert rate >= 0.8


def _observation(
    ball_bearing_deg: float,
    ball_dist: float,
    kickable: bool,
    goal_bearing_deg: float = 0.0,
    goal_dist: float = 15.0,
) -> np.ndarray:
    """A real observation with the ball (at rest) and the goal centre moved to the given body-frame polar spots."""
    obs = gym.make("HFO/EmptyGoal-v0").reset(seed=0)[0].copy()
    obs[GOAL_CENTER_SIN] = math.sin(math.radians(goal_bearing_deg))
    obs[GOAL_CENTER_COS] = math.cos(math.radians(goal_bearing_deg))
    obs[GOAL_CENTER_PROXIMITY] = 1.0 - 2.0 * goal_dist / MAX_HFO_DIST
    obs[BALL_SPEED] = -1.0
    obs[BALL_ANGLE_SIN] = math.sin(math.radians(ball_bearing_deg))
    obs[BALL_ANGLE_COS] = math.cos(math.radians(ball_bearing_deg))
    obs[BALL_PROXIMITY] = 1.0 - 2.0 * ball_dist / MAX_HFO_DIST
    obs[KICKABLE] = 1.0 if kickable else -1.0
    return obs


def test_turns_to_a_ball_far_off_the_body_direction_and_dashes_at_one_ahead() -> None:
    action, direction, _ = heuristic_command(_observation(70.0, 10.0, kickable=False))
    assert action == TURN and direction == pytest.approx(70.0, abs=1.0)
    action, power, _ = heuristic_command(_observation(2.0, 10.0, kickable=False))
    assert action == DASH and power == 100.0


def test_flat_action_encoding() -> None:
    env = gym.make("HFO/EmptyGoal-v0")
    flat = heuristic(env, _observation(70.0, 10.0, kickable=False))
    assert flat.shape == (8,) and flat.dtype == np.float32
    assert int(np.argmax(flat[:3])) == TURN
    assert flat[5] * 360.0 - 180.0 == pytest.approx(70.0, abs=1.0)


def test_kicks_toward_the_goal_when_kickable() -> None:
    # Close to goal: a full-power shot along the goal direction.
    action, power, direction = heuristic_command(_observation(0.0, 0.7, kickable=True, goal_bearing_deg=20.0))
    assert action == KICK and power == pytest.approx(100.0)
    assert 15.0 < direction < 25.0
    # Far from goal: a softer dribble kick.
    action, power, _ = heuristic_command(_observation(0.0, 0.7, kickable=True, goal_dist=45.0))
    assert action == KICK and 20.0 < power < 90.0


def test_does_not_kick_the_ball_into_its_own_body() -> None:
    # Ball ahead, goal straight behind: kicking would run the ball through the kicker, so it steps aside.
    action, _, _ = heuristic_command(_observation(0.0, 0.7, kickable=True, goal_bearing_deg=180.0))
    assert action != KICK


def test_demo_reports_the_scoring_rate(capsys: pytest.CaptureFixture[str]) -> None:
    rate = run_demo("HFO/EmptyGoal-v0", episodes=3, render_mode=None, seed=0)
    assert 0.0 <= rate <= 1.0
    assert "scored" in capsys.readouterr().out
