"""HFO's features for teams: hfo2d against vectors captured from the real HFO, and the high-level set by hand.

The fixture (tests/hfo2d/data/real_hfo_team_features.json) holds states of real HFO games (2v2, 1v2, 2v1: offense
agents against agent2d's defenders; 1v1d, 2v2d: with a defense agent too) read from rcssserver's game log, each
with the vector the real HFO sent one agent in that cycle; ``benchmarks/team_features_fidelity.py capture`` made it
(see its docstring).
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

from hfo2d.features import (
    BALL_SPEED,
    BALL_VEL_ANGLE_COS,
    BALL_VEL_ANGLE_SIN,
    HFO_MASTER_MAX_DIST,
    HIGH_LEVEL_INVALID,
    hfo_feature_list,
    high_level_bounds,
    high_level_feature_list,
    high_level_num_features,
    low_level_feature_list,
    mirrored_state,
    opponent_controls_ball,
)
from hfo2d.physics import BallState, PlayerState

FIXTURE = Path(__file__).resolve().parent / "data" / "real_hfo_team_features.json"
#: Largest differences allowed: the log rounds positions and velocities to 1e-4 (angles to 1e-3 degrees), which
#: moves a feature by a few 1e-4 at most (a proximity by 2e-4 / 85.9, a speed by 2e-4 / 0.46, the bearing of a
#: landmark 0.1 m away by 1e-3); a velocity's heading is checked as heading error times speed (about 1e-4).
TOLERANCE = 1e-3
HEADING_TIMES_SPEED_TOLERANCE = 2e-4


@pytest.fixture(scope="module")
def fidelity(benchmark_script: Callable[[str], ModuleType]) -> ModuleType:
    return benchmark_script("team_features_fidelity")


@pytest.fixture(scope="module")
def records() -> list[dict[str, Any]]:
    return json.loads(FIXTURE.read_text())["records"]


def test_fixture_covers_the_teams_and_both_feature_sets(
    fidelity: ModuleType, records: list[dict[str, Any]]
) -> None:
    groups = {(record["game"], record["side"], record["feature_set"]) for record in records}
    sides = {game: ("l", "r") if counts[1] else ("l",) for game, counts in fidelity.GAMES.items()}
    assert groups == {
        (game, side, fs) for game in fidelity.GAMES for side in sides[game] for fs in ("hfo", "high_level")
    }
    assert FIXTURE.stat().st_size < 40_000


def test_hfo2d_features_equal_the_real_hfos(fidelity: ModuleType, records: list[dict[str, Any]]) -> None:
    opponent_control_mattered = 0
    for record in records:
        for layout, errors in fidelity.compare_record(record).items():
            for block, error in errors.items():
                if block == "velocity_headings":  # a slow object's heading: checked times its speed
                    continue
                if block == "velocity_headings_x_speed":
                    assert error < HEADING_TIMES_SPEED_TOLERANCE, (record["game"], layout, block, error)
                elif block == "ball_without_opponent_control":
                    opponent_control_mattered += error > 0.1
                else:
                    assert error < TOLERANCE, (record["game"], record["time"], layout, block, error)
    # the fixture holds states where the real agents saw the ball stopped under an opponent's control
    assert opponent_control_mattered >= 3


def test_a_changed_feature_is_caught(fidelity: ModuleType, records: list[dict[str, Any]]) -> None:
    record = next(r for r in records if r["feature_set"] == "high_level")
    tampered = dict(record, vector=list(record["vector"]))
    tampered["vector"][8] += 0.01  # the open goal angle
    assert fidelity.compare_record(tampered)["high_level"]["goal_and_open_angle"] > 0.009


# ---------------------------------------------------------------------------------------------------------------
# librcsc's opponent control of the ball
# ---------------------------------------------------------------------------------------------------------------
def test_opponent_control_zeroes_the_ball_velocity_for_a_distant_observer() -> None:
    ball = BallState(x=30.0, y=0.0, vx=1.0, vy=0.5)
    defender = PlayerState("r", 2, x=31.4, y=0.0)  # 1.4 m from the ball: beyond the kickable area of 1.085 m
    far = PlayerState("l", 7, x=10.0, y=0.0)  # 20 m away: librcsc's margin is 0.25 + 0.25 m
    near = PlayerState("l", 11, x=28.0, y=0.0)  # 2 m away: 0.04 + 0.068 m
    assert opponent_controls_ball(far, ball, [defender])
    assert not opponent_controls_ball(near, ball, [defender])
    features = low_level_feature_list(far, ball, 1.03, (), [defender], opponent_control=True)
    assert features[BALL_SPEED] == -1.0
    assert (features[BALL_VEL_ANGLE_SIN], features[BALL_VEL_ANGLE_COS]) == (0.0, 1.0)
    # off by default (hfo2d's registered envs keep their features), and never while the observer can kick
    assert low_level_feature_list(far, ball, 1.03, (), [defender])[BALL_SPEED] > -1.0
    kicker = PlayerState("l", 7, x=29.5, y=0.0)
    assert (
        low_level_feature_list(kicker, ball, 1.03, (), [defender], opponent_control=True)[BALL_SPEED] > -1.0
    )
    # the opponent nearest the ball decides, a tackling one skipped; 1.7 m is beyond 1.085 + 0.5 m
    tackler = PlayerState("r", 3, x=30.0, y=0.5, tackle_cycles=5)
    assert opponent_controls_ball(far, ball, [tackler, defender])
    assert not opponent_controls_ball(far, ball, [tackler])
    assert not opponent_controls_ball(far, ball, [PlayerState("r", 4, x=30.0, y=1.7)])
    master = hfo_feature_list(far, ball, 1.03, (), [defender], True, opponent_control=True)
    assert master[BALL_SPEED] == -1.0


# ---------------------------------------------------------------------------------------------------------------
# The high-level feature set
# ---------------------------------------------------------------------------------------------------------------
def _norm(value: float, low: float, high: float) -> float:
    return (min(max(value, low), high) - low) / (high - low) * 2.0 - 1.0


def test_high_level_layout_by_hand() -> None:
    me = PlayerState("l", 11, x=40.0, y=0.0, body_deg=90.0, stamina=6000.0)
    ball = BallState(x=40.5, y=0.0)
    goalie = PlayerState("r", 1, goalie=True, x=50.0, y=0.0)
    mate = PlayerState("l", 7, x=40.0, y=10.0)
    features = high_level_feature_list(me, ball, 1.03, [mate], [goalie], True)
    assert len(features) == high_level_num_features(1, 1) == 10 + 6 + 3 + 2
    x_range, y_range = (-5.25, 57.75), (-37.4, 37.4)
    top, block = math.atan2(7.01, 12.5), math.atan2(1.085 / 2.0, 10.0)
    expected = [
        _norm(40.0, *x_range),
        0.0,
        0.5,  # body 90 degrees over [-pi, pi]
        _norm(40.5, *x_range),
        0.0,
        1.0,  # kickable
        _norm(12.5, 0.0, HFO_MASTER_MAX_DIST),
        0.0,  # the goal straight ahead (a global direction)
        _norm(top - block, 0.0, math.pi),  # the goalie splits the mouth in two equal openings
        _norm(10.0, 0.0, HFO_MASTER_MAX_DIST),
    ]
    mate_goal = _open(40.0, 10.0, goalie)
    expected += [
        _norm(mate_goal, 0.0, math.pi),
        _norm(math.hypot(10.0, 10.0), 0.0, HFO_MASTER_MAX_DIST),
        _norm(math.pi / 2.0, 0.0, math.pi),  # nobody between: the whole +-45 degrees
        _norm(40.0, *x_range),
        _norm(10.0, *y_range),
        7.0,
        _norm(50.0, *x_range),
        0.0,
        1.0,
        1.0,
        _norm(6000.0, 0.0, 8000.0),
    ]
    assert features == pytest.approx(expected, abs=1e-12)
    low, high = high_level_bounds(1, 1)
    assert all(lo <= f <= hi for lo, f, hi in zip(low, features, high, strict=True))


def _open(x: float, y: float, opponent: PlayerState) -> float:
    """The widest open angle toward the goal mouth from (x, y) past one opponent (the rule of HFO's
    calcLargestOpenAngle, written out for one blocker)."""
    top = math.atan2(7.01 - y, 52.5 - x)
    bottom = math.atan2(-7.01 - y, 52.5 - x)
    bearing = math.atan2(opponent.y - y, opponent.x - x)
    half = math.atan2(1.085 / 2.0, math.hypot(opponent.x - x, opponent.y - y))
    if bearing + half < bottom or bearing - half > top:
        return top - bottom
    return max(bearing - half - bottom, top - (bearing + half), 0.0)


def test_high_level_empty_slots_and_no_opponents() -> None:
    me = PlayerState("l", 11, x=20.0, y=-5.0)
    features = high_level_feature_list(me, BallState(x=30.0, y=0.0), 1.03, [PlayerState("l", 0, x=1.0)], [])
    assert len(features) == high_level_num_features(1, 0)
    assert features[9] == HIGH_LEVEL_INVALID  # no opponent to be close to
    assert features[10:16] == [HIGH_LEVEL_INVALID] * 6  # a teammate without a uniform number is not listed
    assert features[5] == -1.0 and features[-2] == -1.0
    assert features[8] == pytest.approx(
        _norm(math.atan2(12.01, 32.5) - math.atan2(-2.01, 32.5), 0.0, math.pi)
    )


def test_high_level_for_the_defense_is_in_its_mirrored_frame() -> None:
    defender = PlayerState("r", 2, x=40.0, y=5.0, body_deg=180.0)
    attacker = PlayerState("l", 11, x=30.0, y=-5.0)
    ball = BallState(x=30.5, y=-5.0)
    features = high_level_feature_list(defender, ball, 1.03, [], [attacker], False, playing_offense=False)
    x_range = (-57.75, 5.25)
    assert features[0] == pytest.approx(_norm(-40.0, *x_range))
    assert features[1] == pytest.approx(_norm(-5.0, -37.4, 37.4))
    assert features[2] == pytest.approx(0.0)  # facing the field: body 180 in the server's frame, 0 in its own
    assert features[6] == pytest.approx(
        _norm(math.hypot(12.5, 5.0), 0.0, HFO_MASTER_MAX_DIST)
    )  # its own goal
    mirrored = mirrored_state(defender)
    assert (mirrored.x, mirrored.y, mirrored.body_deg) == (-40.0, -5.0, 0.0)
    # librcsc folds the turned body into [-180, 180] keeping 180: a body of 0 reads +1 (pi), not -1
    facing_own_goal = PlayerState("r", 1, goalie=True, x=52.5, y=0.0, body_deg=0.0)
    assert mirrored_state(facing_own_goal).body_deg == 180.0
    assert (
        high_level_feature_list(facing_own_goal, ball, 1.03, [], [attacker], playing_offense=False)[2] == 1.0
    )


def test_hfoenv_high_level_feature_set() -> None:
    from hfo2d.hfo_env import HFOEnv

    env = HFOEnv(task="keeper", feature_set="high_level")
    obs, info = env.reset(seed=3)
    assert obs.shape == (high_level_num_features(0, 1),) == env.observation_space.shape
    assert env.observation_space.contains(obs) and obs[-2] == -1.0  # HFO's last action (a NOOP) failed
    player, ball, keeper = info["player"], info["ball"], info["keeper"]
    assert obs[0] == pytest.approx(_norm(player[0], -5.25, 57.75), abs=1e-6)
    assert obs[3] == pytest.approx(_norm(ball[0], -5.25, 57.75), abs=1e-6)
    assert obs[10:13] == pytest.approx(
        [_norm(keeper[0], -5.25, 57.75), _norm(keeper[1], -37.4, 37.4), 1.0], abs=1e-6
    )
    for _ in range(20):
        obs, *_ = env.step(env.action_space.sample())
        assert env.observation_space.contains(obs)
