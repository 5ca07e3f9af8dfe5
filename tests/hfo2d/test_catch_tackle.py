"""Server-side catch, tackle, their timers and HFO's referee in hfo2d.physics (rcssserver 15.2.2 HFO fork:
player.cpp goalieCatch / tackle / resetCommandFlags / updateCapacity, stadium.cpp ballCaught / collisions,
referee.cpp HFORef). Frame G (rcssserver's): the goalie defends x = +52.5. Noise is off unless a test says so."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hfo2d.physics import (
    HFO_CAPTURED_BY_DEFENSE,
    HFO_GOAL,
    HFO_IN_GAME,
    HFO_OUT_OF_BOUNDS,
    HFO_OUT_OF_TIME,
    HFOReferee,
    PlayerState,
    ServerParams,
    World,
    crosses_right_goal_line,
    normalize_deg,
)

CATCH_DIAGONAL = math.degrees(math.atan2(0.5, 1.2))  # librcsc setCatch: +22.62 degrees


def make_world(
    noise: bool = False, seed: int = 0, **overrides: float
) -> tuple[World, PlayerState, PlayerState]:
    world = World(ServerParams.with_overrides(overrides), np.random.default_rng(seed), noise=noise)
    agent = world.add_player("l", 11)
    goalie = world.add_player("r", 1, goalie=True)
    world.place_player(agent, 20.0, 20.0, 0.0)  # out of the way
    return world, agent, goalie


def teleport(px: float, py: float, bx: float, by: float) -> tuple[float, float, bool]:
    """Spec §5.2's four steps in rcssserver's double arithmetic: the goalie's new position, and whether the
    ball-goalie overlap test then fires."""
    nx, ny = bx - px, by - py
    r = math.sqrt(nx * nx + ny * ny)
    f = (r - (0.085 + 0.3)) / max(r, 1e-10)
    nx, ny = nx * f, ny * f
    qx, qy = px + nx, py + ny
    dx, dy = bx - qx, by - qy
    s = 0.085 + 0.3
    return qx, qy, dx * dx + dy * dy < s * s


def catch_dir(goalie: PlayerState, bx: float, by: float) -> float:
    """The client's catch direction: norm(angle(B - P) - body + 22.62)."""
    return normalize_deg(
        math.degrees(math.atan2(by - goalie.y, bx - goalie.x)) - goalie.body_deg + CATCH_DIAGONAL
    )


# --- catch ----------------------------------------------------------------------------------------------------
def test_catch_geometry_spec_8_5() -> None:
    world, _, goalie = make_world()
    world.place_player(goalie, 49.8, 0.0, 180.0)
    world.place_ball(48.6, 0.0)
    assert world.catch(goalie, catch_dir(goalie, 48.6, 0.0))
    qx, qy, hit = teleport(49.8, 0.0, 48.6, 0.0)
    assert hit  # this one registers the fp overlap: both are pushed 1e-10 m further apart
    assert goalie.x == pytest.approx(48.985, abs=1e-9) and goalie.x > qx
    assert math.hypot(world.ball.x - goalie.x, world.ball.y - goalie.y) == pytest.approx(0.385, abs=1e-9)
    assert goalie.body_deg == -180.0  # faces the ball
    assert goalie.vx == 0.0 and goalie.vy == 0.0
    assert world.ball.x == pytest.approx(48.6, abs=1e-9) and world.ball.y == 0.0
    assert goalie.catch_ban == 5
    # one that does not: the goalie lands exactly on the replica's point and the ball stays put
    px, py, bx, by = _catch_case(False)
    world.place_player(goalie, px, py, 180.0)
    goalie.catch_ban = 0
    world.place_ball(bx, by)
    assert world.catch(goalie, catch_dir(goalie, bx, by))
    assert (goalie.x, goalie.y) == teleport(px, py, bx, by)[:2]  # bit for bit
    assert (world.ball.x, world.ball.y) == (bx, by)
    assert goalie.body_deg == pytest.approx(math.degrees(math.atan2(by - py, bx - px)), abs=1e-9)


def _catch_case(collision: bool) -> tuple[float, float, float, float]:
    """(goalie x, y, ball x, y): the ball 1.2 m in front of a goalie near (49.8, 0), a little off the x axis,
    whose teleport does (not) register the fp overlap. (Exactly along an axis it always does: d² rounds below
    0.385² every time for dy = 0.)"""
    for i in range(200):
        a = 0.03 + 0.0011 * i
        px, py = 49.8, 0.0
        bx, by = px - 1.2 * math.cos(a), py + 1.2 * math.sin(a)
        if teleport(px, py, bx, by)[2] == collision:
            return px, py, bx, by
    raise AssertionError("no such case")


@pytest.mark.parametrize("collision", [False, True])
@pytest.mark.parametrize("speed", [1.0, 2.0])
def test_catch_then_step_capture_spec_8_5(collision: bool, speed: float) -> None:
    """Without the fp overlap a ball of speed 1.0 toward the goal is captured (0.615 m), 2.0 is not (1.615 m);
    with it the ball's velocity becomes -0.1x and it is captured either way."""
    px, py, bx, by = _catch_case(collision)
    world, _, goalie = make_world()
    referee = HFOReferee(world.params)
    world.place_player(goalie, px, py, 180.0)
    world.place_ball(bx, by, speed, 0.0)
    referee.reset(world)
    assert world.catch(goalie, catch_dir(goalie, bx, by))
    assert (world.ball.vx == -0.1 * speed) is collision
    world.step()
    assert goalie.collided_ball is collision  # the catch's overlap is reported with the step
    status = referee.analyse(world)
    expected = HFO_CAPTURED_BY_DEFENSE if (collision or speed < 1.47) else HFO_IN_GAME
    assert status == expected
    if not collision:
        ux, uy = (bx - px) / 1.2, (by - py) / 1.2
        assert math.hypot(world.ball.x - goalie.x, world.ball.y - goalie.y) == pytest.approx(
            math.hypot(0.385 * ux + speed, 0.385 * uy), abs=1e-9
        )


def test_catch_faults() -> None:
    world, agent, goalie = make_world()
    world.place_player(goalie, 49.8, 0.0, 180.0)
    world.place_player(agent, 48.0, 0.0, 0.0)
    world.place_ball(48.6, 0.0)
    # not the goalie: nothing happens, no ban
    assert not world.catch(agent, 0.0)
    assert agent.catch_ban == 0 and agent.x == 48.0
    # not PlayOn
    world.play_on = False
    assert not world.catch(goalie, catch_dir(goalie, 48.6, 0.0))
    assert goalie.catch_ban == 0 and goalie.x == 49.8
    world.play_on = True
    # frozen by a tackle
    goalie.tackle_cycles = 3
    assert not world.catch(goalie, catch_dir(goalie, 48.6, 0.0))
    assert goalie.catch_ban == 0
    goalie.tackle_cycles = 0
    # outside the rectangle (ball behind the catch direction): a fault, but the ban is set
    assert not world.catch(goalie, 180.0)
    assert goalie.catch_ban == 5 and goalie.x == 49.8
    # banned: a fault that leaves the ban alone
    assert not world.catch(goalie, catch_dir(goalie, 48.6, 0.0))
    assert goalie.catch_ban == 5


def test_catch_rectangle_bounds_inclusive() -> None:
    world, _, goalie = make_world()
    for bx, by, ok in (
        (1.2, 0.5, True),
        (1.2, -0.5, True),
        (0.0, 0.5, True),
        (1.2 + 1e-12, 0.0, False),
        (0.6, 0.5 + 1e-12, False),
        (-1e-12, 0.0, False),
    ):
        world.place_player(goalie, 0.0, 0.0, 0.0)
        goalie.catch_ban = 0
        world.place_ball(bx, by)
        assert world.catch(goalie, 0.0) is ok, (bx, by)


def test_catch_direction_is_clamped() -> None:
    world, _, goalie = make_world()
    world.place_player(goalie, 0.0, 0.0, 0.0)
    world.place_ball(-1.0, 0.0)  # straight behind: reached by dir 180 and by the clamp of dir 250
    assert world.catch(goalie, 250.0)


def test_catch_ban_timing() -> None:
    world, _, goalie = make_world()
    world.place_player(goalie, 49.8, 0.0, 180.0)
    world.place_ball(48.6, 0.0)
    assert world.catch(goalie, catch_dir(goalie, 48.6, 0.0))
    for left in (4, 3, 2, 1):
        world.step()
        assert goalie.catch_ban == left
        world.place_player(goalie, 49.8, 0.0, 180.0)  # placing keeps the ban (Player::place)
        world.place_ball(48.6, 0.0)
        assert not world.catch(goalie, catch_dir(goalie, 48.6, 0.0))
        assert goalie.catch_ban == left
    world.step()
    assert goalie.catch_ban == 0
    world.place_player(goalie, 49.8, 0.0, 180.0)
    world.place_ball(48.6, 0.0)
    assert world.catch(goalie, catch_dir(goalie, 48.6, 0.0))  # 5 cycles after the first
    assert goalie.catch_ban == 5


def test_catch_fp_collision_fraction() -> None:
    """The teleport's rounding registers the ball-goalie overlap in about half of the catches near the goal
    (spec §5.2: ~49 %), and World agrees with the spec's four-step replica in every case."""
    rng = np.random.default_rng(7)
    world, _, goalie = make_world()
    n = 3000
    hits = 0
    for _ in range(n):
        px = rng.uniform(37.0, 52.0)
        py = rng.uniform(-19.0, 19.0)
        d = rng.uniform(1.085, 1.2)
        th = rng.uniform(-math.pi, math.pi)
        bx, by = px + d * math.cos(th), py + d * math.sin(th)
        world.place_player(goalie, px, py, rng.uniform(-180.0, 180.0))
        goalie.catch_ban = 0
        world.place_ball(bx, by, 0.5, 0.25)
        assert world.catch(goalie, catch_dir(goalie, bx, by))
        qx, qy, hit = teleport(px, py, bx, by)
        assert (goalie.x, goalie.y) == (qx, qy) or hit  # an overlap then moves both apart
        assert (world.ball.vx == -0.05) is hit
        hits += hit
    assert 0.45 < hits / n < 0.53


def test_catch_probability_and_punch() -> None:
    """catch_probability < 1 draws; a failure punches the ball (velocity mirrored about the catch direction)."""
    world, _, goalie = make_world(catch_probability=0.0)
    world.place_player(goalie, 0.0, 0.0, 0.0)
    world.place_ball(1.0, 0.0, -0.5, 0.2)
    assert not world.catch(goalie, 0.0)
    assert (goalie.x, goalie.catch_ban) == (0.0, 5)
    assert world.ball.ax == pytest.approx(1.0, abs=1e-12) and world.ball.ay == pytest.approx(0.0, abs=1e-12)
    world, _, goalie = make_world(catch_probability=0.5, seed=3)
    wins = 0
    for _ in range(1000):
        world.place_player(goalie, 0.0, 0.0, 0.0)
        goalie.catch_ban = 0
        world.place_ball(1.0, 0.0)
        wins += world.catch(goalie, 0.0)
    assert 430 < wins < 570


def test_catch_stretch_region() -> None:
    """With stretch 1.5 the area runs to 1.8 m; beyond l_min = 0.6 the chance falls linearly to 0 at 1.8."""
    world, _, goalie = make_world(catch_area_l_stretch=1.5, seed=5)
    wins = 0
    for _ in range(1000):
        world.place_player(goalie, 0.0, 0.0, 0.0)
        goalie.catch_ban = 0
        world.place_ball(1.5, 0.0)  # chance 1 - (1.5 - 0.6) / 1.2 = 0.25
        wins += world.catch(goalie, 0.0)
    assert 200 < wins < 300
    world.place_player(goalie, 0.0, 0.0, 0.0)
    goalie.catch_ban = 0
    world.place_ball(1.85, 0.0)
    assert not world.catch(goalie, 0.0)


# --- tackle ---------------------------------------------------------------------------------------------------
def test_tackle_probability_spec_8_6() -> None:
    world, _, goalie = make_world()
    world.place_player(goalie, 50.0, 0.0, -90.0)  # GF body +90
    for ahead, side, expected in (
        (1.3, 0.0, 1.0 - 0.65**6),
        (0.0 + 1e-9, 0.9, 1.0 - (0.9 / 1.25) ** 6),
    ):
        world.place_ball(50.0 + side, -ahead)
        assert world.tackle_success_probability(goalie) == pytest.approx(expected, abs=1e-9)
    assert round(1.0 - 0.65**6, 3) == 0.925
    world.place_ball(50.0, -1.529)
    assert world.tackle_success_probability(goalie) >= 0.8
    world.place_ball(50.0, -1.53)
    assert world.tackle_success_probability(goalie) < 0.8
    world.place_ball(50.0 + 0.9559, -1e-9)  # 1.25 * 0.2 ** (1 / 6) = 0.95590 (spec: 0.956)
    assert world.tackle_success_probability(goalie) >= 0.8
    world.place_ball(50.0 + 0.9560, -1e-9)
    assert world.tackle_success_probability(goalie) < 0.8
    world.place_ball(50.0, 0.5)  # behind: tackle_back_dist 0
    assert world.tackle_success_probability(goalie) == 0.0


def test_tackle_success_rate() -> None:
    world, _, goalie = make_world(seed=11)
    wins = 0
    n = 2000
    for _ in range(n):
        world.place_player(goalie, 0.0, 0.0, 0.0)
        goalie.tackle_cycles = 0
        world.place_ball(1.3, 0.0)
        wins += world.tackle(goalie, 0.0)
        world.ball.ax = world.ball.ay = 0.0
    assert wins / n == pytest.approx(1.0 - 0.65**6, abs=0.02)


def test_tackle_freeze() -> None:
    world, agent, goalie = make_world(noise=True)
    world.place_player(goalie, 0.0, 0.0, 0.0)
    world.place_ball(-1.0, 0.0)  # behind: the tackle fails, and still freezes
    assert not world.tackle(goalie, 0.0)
    assert goalie.tackle_cycles == 10
    for left in range(9, -1, -1):
        world.step()
        assert goalie.tackle_cycles == left
        if left > 0:
            state = (goalie.x, goalie.y, goalie.vx, goalie.vy, goalie.body_deg, goalie.stamina, goalie.ax)
            world.dash(goalie, 100.0)
            world.client_dash(goalie, 100.0, 0.0)
            world.turn(goalie, 90.0)
            world.client_turn(goalie, 90.0)
            world.place_ball(0.5, 0.0)
            assert not world.kick(goalie, 100.0, 0.0)
            assert not world.client_kick(goalie, 100.0, 0.0)
            assert not world.catch(goalie, 0.0)
            assert not world.tackle(goalie, 0.0)
            assert goalie.tackle_cycles == left and goalie.catch_ban == 0
            assert (
                goalie.x,
                goalie.y,
                goalie.vx,
                goalie.vy,
                goalie.body_deg,
                goalie.stamina,
                goalie.ax,
            ) == state
            assert world.ball.ax == 0.0
            world.place_ball(-1.0, 0.0)
    world.turn(goalie, 90.0)  # free again after 10 steps
    assert goalie.body_deg != 0.0
    assert agent.tackle_cycles == 0


def _successful_tackle(world: World, goalie: PlayerState, direction: float, foul: bool = False) -> None:
    for _ in range(100):
        goalie.tackle_cycles = 0
        world.ball.ax = world.ball.ay = 0.0
        if world.tackle(goalie, direction, foul):
            return
    raise AssertionError("no success in 100 tries")


def test_tackle_ball_acceleration() -> None:
    world, _, goalie = make_world()
    world.place_player(goalie, 0.0, 0.0, 30.0)
    r = math.radians(30.0)
    world.place_ball(1.0 * math.cos(r), 1.0 * math.sin(r))  # straight ahead
    _successful_tackle(world, goalie, 0.0)
    assert goalie.tackle_cycles == 10
    assert math.hypot(world.ball.ax, world.ball.ay) == pytest.approx(2.7, abs=1e-9)
    assert math.degrees(math.atan2(world.ball.ay, world.ball.ax)) == pytest.approx(30.0, abs=1e-9)
    # dir 90: power 100 (1 - 90/180); ball 45 degrees off the body: rate (1 - 0.5 * 45/180)
    world.place_player(goalie, 0.0, 0.0, 0.0)
    world.place_ball(0.8, 0.8)
    _successful_tackle(world, goalie, 90.0)
    assert world.ball.ax == pytest.approx(0.0, abs=1e-12)
    assert world.ball.ay == pytest.approx(50.0 * 0.027 * 0.875, abs=1e-12)
    # a tackle direction beyond 180 is clamped
    world.place_player(goalie, 0.0, 0.0, 0.0)
    world.place_ball(1.0, 0.0)
    _successful_tackle(world, goalie, 250.0)
    assert math.hypot(world.ball.ax, world.ball.ay) == pytest.approx(0.0, abs=1e-12)
    # the step applies the usual caps: accel 2.7, speed 3.0
    world.place_player(goalie, 0.0, 0.0, 0.0)
    world.place_ball(1.0, 0.0, 1.0, 0.0)
    _successful_tackle(world, goalie, 0.0)
    world.step()
    assert world.ball.vx == pytest.approx(3.0 * 0.94, abs=1e-12)


def test_tackle_noise_bound() -> None:
    world, _, goalie = make_world(noise=True, seed=2)
    spread = []
    for _ in range(300):
        world.place_player(goalie, 0.0, 0.0, 0.0)
        world.place_ball(1.0, 0.0, 0.3, 0.0)
        _successful_tackle(world, goalie, 0.0)
        spread.append(math.hypot(world.ball.ax - 2.7, world.ball.ay))
    fail = 0.5**6
    max_rand = 0.1 * 2.0 * (0.5 + 0.5 * (1.0 - fail) + 0.5 + 0.5 * 0.3 / (3.0 * 0.94))
    assert max(spread) <= max_rand + 1e-12
    assert max(spread) > 0.8 * max_rand and min(spread) < 0.2 * max_rand


def test_tackle_foul() -> None:
    world, agent, goalie = make_world()
    world.place_player(goalie, 0.0, 0.0, 0.0)
    world.place_ball(1.5, 0.0)
    world.place_player(agent, 2.5, 0.0, 180.0)  # 1.0 m from the ball: kickable (<= 1.085)
    assert world.tackle_success_probability(goalie, foul=True) == pytest.approx(1.0 - 0.75**10)
    assert world.tackle_success_probability(goalie) == pytest.approx(1.0 - 0.75**6)
    _successful_tackle(world, goalie, 0.0, foul=True)
    assert goalie.tackle_cycles == 0  # an effective foul does not freeze
    world.place_player(agent, 3.0, 0.0, 180.0)  # 1.5 m: no kickable opponent, the foul flag has no effect
    assert world.tackle_success_probability(goalie, foul=True) == pytest.approx(1.0 - 0.75**6)
    _successful_tackle(world, goalie, 0.0, foul=True)
    assert goalie.tackle_cycles == 10


def test_tackle_outside_play_on_moves_nothing() -> None:
    world, _, goalie = make_world()
    world.play_on = False
    world.place_player(goalie, 0.0, 0.0, 0.0)
    world.place_ball(0.5, 0.0)
    assert not world.tackle(goalie, 0.0)
    assert goalie.tackle_cycles == 10 and world.ball.ax == 0.0


def test_unused_timers_leave_the_step_alone() -> None:
    """Two worlds, one never catching or tackling, the other with timers run out: identical steps."""
    states = []
    for use in (False, True):
        world, agent, goalie = make_world(noise=True, seed=4)
        if use:
            world.place_ball(-10.0, 0.0)
            world.tackle(goalie, 0.0)  # fails (ball far), draws nothing
            goalie.tackle_cycles = 0
        world.place_player(agent, 10.0, 5.0, 30.0, 0.2, 0.1)
        world.place_player(goalie, 11.0, 5.5, -60.0)
        world.place_ball(10.5, 5.2, 0.8, 0.1)
        for _ in range(20):
            world.client_dash(agent, 80.0, 0.0)
            world.turn(goalie, 20.0)
            world.step()
        states.append((agent.x, agent.y, goalie.x, goalie.y, goalie.body_deg, world.ball.x, world.ball.y))
    assert states[0] == states[1]


# --- referee ---------------------------------------------------------------------------------------------------
def _referee_world(untouched_time: int = 100, trial_time: int = 0) -> tuple[World, HFOReferee, PlayerState]:
    world, agent, goalie = make_world()
    world.place_player(agent, 10.0, 10.0, 0.0)
    world.place_player(goalie, 52.5, 0.0, 180.0)
    world.place_ball(30.0, 0.0)
    referee = HFOReferee(world.params, untouched_time=untouched_time, trial_time=trial_time)
    referee.reset(world)
    return world, referee, goalie


def test_goal_line_rule() -> None:
    assert crosses_right_goal_line(52.0, 0.0, 53.0, 0.5)
    assert crosses_right_goal_line(52.0, 7.0, 52.7, 7.0)  # 7.0 <= 7.07
    assert not crosses_right_goal_line(52.0, 7.1, 52.7, 7.1)
    assert not crosses_right_goal_line(52.0, 0.0, 52.585, 0.0)  # not past 52.5 + 0.085
    assert not crosses_right_goal_line(52.6, 0.0, 53.0, 0.0)  # already over
    # behind the goal line outside the mouth: never a goal, though the line through the two points meets
    # x = 52.585 at |y| 6.92 (hfo_env's rule counts this one)
    assert not crosses_right_goal_line(52.55, 7.2, 52.7, 6.0)
    assert crosses_right_goal_line(52.5, 7.2, 52.7, 6.0)  # |prev x| not > 52.5: counted
    # the mouth is goal_width * 0.5 + 0.06 in doubles
    mouth = 14.02 * 0.5 + 0.06
    assert mouth < 7.07
    assert crosses_right_goal_line(52.0, mouth, 53.0, mouth)
    assert not crosses_right_goal_line(52.0, 7.07, 53.0, 7.07)


def test_referee_order_and_previous_position() -> None:
    world, referee, goalie = _referee_world()
    world.place_ball(52.0, 0.0)
    referee.analyse(world)
    world.place_player(goalie, 52.9, 0.2, 180.0)  # the goalie on the ball beyond the line: the goal wins
    world.place_ball(52.9, 0.0)
    assert referee.analyse(world) == HFO_GOAL
    world, referee, _ = _referee_world()
    world.place_ball(-1.0, 0.0)
    assert referee.analyse(world) == HFO_IN_GAME  # out of bounds is judged on the previous position
    assert referee.analyse(world) == HFO_OUT_OF_BOUNDS


def test_referee_capture_strict_squared_distance() -> None:
    world, referee, goalie = _referee_world()
    world.place_ball(0.0, 5.0)
    referee.reset(world)
    world.place_player(goalie, 1.085, 5.0, 180.0)  # d = 1.085 exactly: d² == K² is not < K²
    assert math.hypot(goalie.x - world.ball.x, goalie.y - world.ball.y) == 1.085
    assert referee.analyse(world) == HFO_IN_GAME
    world.place_player(goalie, 1.08, 5.0, 180.0)
    assert referee.analyse(world) == HFO_CAPTURED_BY_DEFENSE


def test_referee_goalie_capture_even_with_attacker_near() -> None:
    world, referee, goalie = _referee_world()
    agent = world.players[0]
    world.place_player(goalie, 40.0, 0.0, 180.0)
    world.place_player(agent, 38.6, 0.0, 0.0)
    world.place_ball(39.3, 0.0)
    assert referee.analyse(world) == HFO_CAPTURED_BY_DEFENSE
    assert referee.take_time == 1  # the defender's walk step cleared offense_possession


def test_referee_untouched_time_counts_earlier_cycles() -> None:
    """HFO compares the count of the earlier cycles with untouched_time before counting this one: with
    untouched_time 3 the 5th untouched cycle ends the episode (hfo_env's rule: the 4th)."""
    world, referee, goalie = _referee_world(untouched_time=3)
    results = [referee.analyse(world) for _ in range(5)]
    assert results == [HFO_IN_GAME] * 4 + [HFO_OUT_OF_TIME]
    # a touch in the cycle where the old count is already over does not save the episode
    world, referee, goalie = _referee_world(untouched_time=3)
    for _ in range(4):
        assert referee.analyse(world) == HFO_IN_GAME
    world.players[0].x, world.players[0].y = 30.5, 0.0
    assert referee.analyse(world) == HFO_OUT_OF_TIME


def test_referee_trial_time() -> None:
    world, referee, _ = _referee_world(untouched_time=0, trial_time=3)
    assert [referee.analyse(world) for _ in range(4)] == [HFO_IN_GAME] * 3 + [HFO_OUT_OF_TIME]


def test_referee_take_time_with_a_field_defender() -> None:
    """A defender that is not unum 1 needs take_time 2, checked on the following cycle; the walk stops at the
    first defender on the ball, and an offense player on the ball afterwards resets take_time."""
    world = World(ServerParams(), np.random.default_rng(0), noise=False)
    defender = world.add_player("r", 2)
    goalie = world.add_player("r", 1, goalie=True)
    agent = world.add_player("l", 11)
    world.place_player(defender, 30.5, 0.0, 0.0)
    world.place_player(goalie, 29.5, 0.0, 0.0)  # also on the ball, but after the defender in the walk
    world.place_player(agent, 10.0, 0.0, 0.0)
    world.place_ball(30.0, 0.0)
    referee = HFOReferee(world.params)
    referee.reset(world)
    assert referee.analyse(world) == HFO_IN_GAME
    assert (referee.holder_side, referee.holder_unum, referee.take_time) == ("R", 2, 1)
    world.place_player(goalie, 40.0, 0.0, 0.0)
    assert referee.analyse(world) == HFO_IN_GAME
    assert referee.take_time == 2
    assert referee.analyse(world) == HFO_CAPTURED_BY_DEFENSE
    # offense on the ball: take_time back to 0 (the agent is walked after the defender here, so move the
    # defender away)
    world2 = World(ServerParams(), np.random.default_rng(0), noise=False)
    agent2 = world2.add_player("l", 11)
    defender2 = world2.add_player("r", 2)
    world2.place_player(defender2, 30.5, 0.0, 0.0)
    world2.place_player(agent2, 10.0, 0.0, 0.0)
    world2.place_ball(30.0, 0.0)
    referee2 = HFOReferee(world2.params)
    referee2.reset(world2)
    referee2.analyse(world2)
    assert referee2.take_time == 1
    world2.place_player(defender2, 35.0, 0.0, 0.0)
    world2.place_player(agent2, 29.5, 0.0, 0.0)
    assert referee2.analyse(world2) == HFO_IN_GAME
    assert (referee2.holder_side, referee2.take_time) == ("L", 0)


def test_referee_outside_play_on_only_tracks_the_ball() -> None:
    world, referee, goalie = _referee_world()
    world.play_on = False
    world.place_player(goalie, 30.5, 0.0, 180.0)
    assert referee.analyse(world) == HFO_IN_GAME
    assert referee.untouched == 0 and referee.cycles == 0
