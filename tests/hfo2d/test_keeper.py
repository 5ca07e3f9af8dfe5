"""Scripted goalie (hfo2d.keeper): positioning, shot interception, the skill scale and determinism."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hfo2d.keeper import (
    BASE_MOVE_X,
    LINE_ANCHOR_X,
    POST_MOVE_ABS_Y,
    POST_MOVE_X,
    ScriptedKeeper,
    dash_reach_table,
)
from hfo2d.physics import PITCH_HALF_LENGTH, PlayerState, ServerParams, World

PARAMS = ServerParams()


def make_world(seed: int = 0, noise: bool = True) -> tuple[World, PlayerState, PlayerState]:
    """World with a striker (left, unum 11) and the goalie (right, unum 1)."""
    world = World(PARAMS, np.random.default_rng(seed), noise=noise)
    striker = world.add_player("l", 11)
    keeper = world.add_player("r", 1, goalie=True)
    return world, striker, keeper


def run_until_capture_or_line(world: World, policy: ScriptedKeeper, keeper: PlayerState, cycles: int) -> bool:
    """Step the world with only the keeper acting; True if the keeper got within kickable_area of the ball
    before it crossed the goal line."""
    for _ in range(cycles):
        policy.act(world, keeper)
        world.step()
        if world.ball_distance(keeper) <= PARAMS.kickable_area:
            return True
        if world.ball.x > PITCH_HALF_LENGTH:
            return False
    return False


def test_positions_on_the_ball_goal_line() -> None:
    world, striker, keeper = make_world(noise=False)
    ball_x, ball_y = 36.0, 15.0
    world.place_ball(ball_x, ball_y)
    world.place_player(striker, ball_x - 0.5, ball_y, 0.0)  # the striker holds the ball: no chase
    world.place_player(keeper, PITCH_HALF_LENGTH, 0.0, 180.0)
    policy = ScriptedKeeper(PARAMS, np.random.default_rng(0), skill=1.0)
    for _ in range(40):
        policy.act(world, keeper)
        world.step()
    expected_y = ball_y * (LINE_ANCHOR_X - BASE_MOVE_X) / (LINE_ANCHOR_X - ball_x)  # 6.19 m
    assert policy.last_mode in ("position", "face")
    assert math.hypot(keeper.x - BASE_MOVE_X, keeper.y - expected_y) < 0.6
    # it ends facing the ball
    ball_bearing = math.degrees(math.atan2(ball_y - keeper.y, ball_x - keeper.x))
    assert abs((ball_bearing - keeper.body_deg + 180.0) % 360.0 - 180.0) < 20.0


def test_guards_the_near_post_when_the_ball_is_wide_at_a_sharp_angle() -> None:
    world, striker, keeper = make_world(noise=False)
    world.place_ball(51.0, -15.0)
    world.place_player(striker, 50.5, -15.0, 0.0)
    world.place_player(keeper, BASE_MOVE_X, 0.0, 180.0)
    policy = ScriptedKeeper(PARAMS, np.random.default_rng(0))
    for _ in range(30):
        policy.act(world, keeper)
        world.step()
    assert math.hypot(keeper.x - POST_MOVE_X, keeper.y + POST_MOVE_ABS_Y) < 0.6


@pytest.mark.parametrize("seed", range(5))
def test_intercepts_a_shot_at_goal(seed: int) -> None:
    # A shot from (38, -6) at (52.5, 5.5): it passes x = 49.8 about 3.4 m beside the keeper's start.
    start_x, start_y, aim_y, speed = 38.0, -6.0, 5.5, 2.5
    direction = np.array([PITCH_HALF_LENGTH - start_x, aim_y - start_y])
    velocity = speed * direction / np.linalg.norm(direction)
    world, striker, keeper = make_world(seed)
    world.place_player(striker, 30.0, -20.0, 0.0)
    world.place_ball(start_x, start_y, *velocity)
    world.place_player(keeper, BASE_MOVE_X, 0.0, 180.0)
    full = ScriptedKeeper(PARAMS, np.random.default_rng(seed), skill=1.0)
    assert run_until_capture_or_line(world, full, keeper, 30)
    assert full.last_mode == "intercept"

    # The same shot beats a keeper that does not move: the save above came from the interception.
    world, striker, keeper = make_world(seed)
    world.place_player(striker, 30.0, -20.0, 0.0)
    world.place_ball(start_x, start_y, *velocity)
    world.place_player(keeper, BASE_MOVE_X, 0.0, 180.0)
    static = ScriptedKeeper(PARAMS, np.random.default_rng(seed), skill=0.0)
    assert not run_until_capture_or_line(world, static, keeper, 30)


def test_chases_a_loose_ball_in_the_penalty_area() -> None:
    world, striker, keeper = make_world(noise=False)
    world.place_player(striker, 20.0, 0.0, 0.0)  # far away: the keeper gets there first
    world.place_ball(42.0, 6.0)
    world.place_player(keeper, BASE_MOVE_X, 0.0, 180.0)
    policy = ScriptedKeeper(PARAMS, np.random.default_rng(0))
    assert run_until_capture_or_line(world, policy, keeper, 20)


def test_skill_zero_is_almost_static() -> None:
    world, striker, keeper = make_world(seed=1)
    world.place_player(striker, 30.0, 0.0, 0.0)
    world.place_ball(40.0, 3.0, 1.0, -0.2)
    world.place_player(keeper, BASE_MOVE_X, 0.0, 90.0)
    policy = ScriptedKeeper(PARAMS, np.random.default_rng(1), skill=0.0)
    for _ in range(12):
        policy.act(world, keeper)
        world.step()
    assert math.hypot(keeper.x - BASE_MOVE_X, keeper.y) < 0.05
    # it still turns to face the ball
    assert abs(keeper.body_deg - 90.0) > 45.0


def test_skill_scales_speed_reaction_and_horizon() -> None:
    rng = np.random.default_rng(0)
    keepers = [ScriptedKeeper(PARAMS, rng, skill) for skill in (0.0, 0.25, 0.5, 0.75, 1.0)]
    powers = [k.dash_power for k in keepers]
    delays = [k.reaction_delay for k in keepers]
    horizons = [k.horizon for k in keepers]
    assert powers == sorted(powers) and powers[0] == 0.0 and powers[-1] == PARAMS.maxpower
    assert delays == sorted(delays, reverse=True) and delays[-1] == 0 and delays[0] > 0
    assert horizons == sorted(horizons) and horizons[0] < horizons[-1]
    assert keepers[-1].hesitation == 0.0
    with pytest.raises(ValueError):
        ScriptedKeeper(PARAMS, rng, skill=1.5)


def test_dash_reach_table_matches_the_dash_model() -> None:
    # Full power from rest: 0.6, then 0.6 + 0.4 * 0.6 = 0.84 m, ... toward 1 m per cycle (hfo_reference §4.2).
    table = dash_reach_table(PARAMS, 100.0, 30)
    assert table[1] == pytest.approx(0.6)
    assert table[2] == pytest.approx(0.6 + 0.84)
    assert table[30] - table[29] == pytest.approx(1.0, abs=1e-6)


def _trajectory(world_seed: int, keeper_seed: int, skill: float) -> list[tuple[float, float, float]]:
    world, striker, keeper = make_world(world_seed)
    world.place_player(striker, 35.0, 8.0, 0.0)
    world.place_ball(36.0, 8.0, 1.2, -0.3)
    world.place_player(keeper, PITCH_HALF_LENGTH, 0.0, 180.0)
    policy = ScriptedKeeper(PARAMS, np.random.default_rng(keeper_seed), skill=skill)
    policy.reset()
    path = []
    for _ in range(25):
        policy.act(world, keeper)
        world.step()
        path.append((keeper.x, keeper.y, keeper.body_deg))
    return path


def test_seeded_determinism() -> None:
    assert _trajectory(3, 7, 0.5) == _trajectory(3, 7, 0.5)
    # the weakened keeper's hesitation really draws from its generator
    assert _trajectory(3, 7, 0.5) != _trajectory(3, 8, 0.5)


def test_reset_forgets_the_delayed_ball() -> None:
    world, striker, keeper = make_world(noise=False)
    world.place_player(keeper, BASE_MOVE_X, 0.0, 180.0)
    policy = ScriptedKeeper(PARAMS, np.random.default_rng(0), skill=0.5)
    assert policy.reaction_delay > 0
    world.place_ball(40.0, 0.0)
    policy.act(world, keeper)
    policy.reset()
    world.place_ball(30.0, -10.0)
    policy.act(world, keeper)
    assert policy._ball_memory[0][:2] == (30.0, -10.0)
