"""Unit tests of hfo2d.physics: one per rcssserver / librcsc rule, numbers worked out by hand from the rules
(rcssserver 15.2.2 HFO fork, librcsc; hfo_reference §3.2, §4). Noise is off unless a test says otherwise."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hfo2d.physics import (
    GOAL_POSTS,
    BallState,
    PlayerState,
    ServerParams,
    World,
    normalize_deg,
)

APPROX = 1e-9


def make_world(noise: bool = False, seed: int = 0, **overrides: float) -> tuple[World, PlayerState]:
    world = World(ServerParams.with_overrides(overrides), np.random.default_rng(seed), noise=noise)
    player = world.add_player("l", 11)
    world.place_player(player, 0.0, 0.0, 0.0)
    world.place_ball(-20.0, 20.0)  # out of the way
    return world, player


# --- parameters -------------------------------------------------------------------------------------
def test_defaults_and_kickable_area() -> None:
    sp = ServerParams()
    # 0.3 + 0.7 + 0.085
    assert sp.kickable_area == pytest.approx(1.085)
    assert sp.client_kickable_area == pytest.approx(1.03)
    assert (sp.dash_angle_step, sp.back_dash_rate, sp.minpower) == (45.0, 0.6, -100.0)


def test_with_overrides() -> None:
    sp = ServerParams.with_overrides({"kickable_margin": 0.8, "ball_decay": 0.9})
    assert sp.kickable_area == pytest.approx(1.185)
    assert sp.ball_decay == 0.9
    assert ServerParams.with_overrides(None) == ServerParams()
    with pytest.raises(ValueError, match="kickable_marginn") as err:
        ServerParams.with_overrides({"kickable_marginn": 0.8})
    assert "player_decay" in str(err.value)  # the message lists the valid names
    with pytest.raises(ValueError, match="finite"):
        ServerParams.with_overrides({"ball_decay": float("nan")})
    with pytest.raises(ValueError, match="finite"):
        ServerParams.with_overrides({"ball_speed_max": float("inf")})
    with pytest.raises(ValueError, match="wind"):
        ServerParams.with_overrides({"wind_rand": 0.1})


def test_normalize_deg() -> None:
    assert normalize_deg(180.0) == -180.0
    assert normalize_deg(190.0) == pytest.approx(-170.0)
    assert normalize_deg(-190.0) == pytest.approx(170.0)


# --- dash -------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("direction", "accel", "move_deg"),
    [
        (0.0, 0.6, 0.0),  # 100 * 0.006 * dir_rate 1.0
        (45.0, 0.42, 45.0),  # rate 0.4 + 0.6 * (1 - 45/90) = 0.7 -> 0.6 * 0.7
        (90.0, 0.24, 90.0),  # rate 0.4 -> 0.6 * 0.4
        (180.0, 0.36, 180.0),  # rate 0.6 - 0.2 * (1 - 90/90) = 0.6 (back_dash_rate) -> 0.6 * 0.6
        (-135.0, 0.30, -135.0),  # rate 0.6 - 0.2 * (1 - 45/90) = 0.5 -> 0.3
    ],
)
def test_dash_direction_rate(direction: float, accel: float, move_deg: float) -> None:
    world, p = make_world()
    world.dash(p, 100.0, direction)
    assert math.hypot(p.ax, p.ay) == pytest.approx(accel)
    world.step()
    # from rest: moves by a, then keeps a * player_decay 0.4
    assert p.x == pytest.approx(accel * math.cos(math.radians(move_deg)), abs=APPROX)
    assert p.y == pytest.approx(accel * math.sin(math.radians(move_deg)), abs=APPROX)
    assert p.vx == pytest.approx(0.4 * accel * math.cos(math.radians(move_deg)), abs=APPROX)
    assert p.vy == pytest.approx(0.4 * accel * math.sin(math.radians(move_deg)), abs=APPROX)


def test_dash_relative_to_body() -> None:
    world, p = make_world()
    world.place_player(p, 0.0, 0.0, 90.0)
    world.dash(p, 100.0, 90.0)  # body 90 + dir 90 = 180: 0.24 along -x
    assert (p.ax, p.ay) == pytest.approx((-0.24, 0.0), abs=APPROX)


@pytest.mark.parametrize(
    ("requested", "rounded"),
    [(30.0, 45.0), (20.0, 0.0), (22.5, 0.0), (67.5, 90.0), (-100.0, -90.0), (170.0, 180.0), (-180.0, -180.0)],
)
def test_dash_direction_rounded_to_45(requested: float, rounded: float) -> None:
    # 45 * rint(d / 45): 30/45 = 0.67 -> 1; 22.5/45 = 0.5 -> 0 (half to even); 67.5/45 = 1.5 -> 2
    world, p = make_world()
    world.dash(p, 100.0, requested)
    rate = (
        0.4 + 0.6 * (1 - abs(rounded) / 90)
        if abs(rounded) <= 90
        else 0.6 - 0.2 * (1 - (abs(rounded) - 90) / 90)
    )
    assert p.ax == pytest.approx(0.6 * rate * math.cos(math.radians(rounded)), abs=APPROX)
    assert p.ay == pytest.approx(0.6 * rate * math.sin(math.radians(rounded)), abs=APPROX)


def test_dash_power_clamped_at_server() -> None:
    world, p = make_world()
    world.dash(p, 250.0, 0.0)  # clamp to 100: a = 0.6, stamina 8000 - 100
    assert p.ax == pytest.approx(0.6)
    assert p.stamina == pytest.approx(7900.0)


def test_backward_dash_costs_double_and_flips() -> None:
    world, p = make_world()
    world.dash(p, -50.0, 0.0)
    # stamina need -2 * -50 = 100; edp = |1 * -50 * 1.0 * 0.006| = 0.3 along body + 0 + 180
    assert p.stamina == pytest.approx(7900.0)
    assert (p.ax, p.ay) == pytest.approx((-0.3, 0.0), abs=APPROX)
    world.step()
    assert p.stamina == pytest.approx(7945.0)  # + stamina_inc_max 45 * recovery 1


def test_dash_limited_by_stamina() -> None:
    world, p = make_world()
    p.stamina = 20.0
    world.dash(p, 100.0, 0.0)  # need min(100, 20 + 50) = 70 -> power 70 -> a 0.42
    assert p.stamina == 0.0
    assert p.ax == pytest.approx(0.42)
    p.ax = 0.0
    p.stamina = 20.0
    world.dash(p, -100.0, 0.0)  # need min(200, 70) = 70 -> power -35 -> a 0.21 backwards
    assert p.stamina == 0.0
    assert p.ax == pytest.approx(-0.21)


def test_dash_scaled_by_effort() -> None:
    world, p = make_world()
    p.effort = 0.6
    world.dash(p, 100.0, 0.0)  # 0.6 * 100 * 0.006
    assert p.ax == pytest.approx(0.36)


# --- turn -------------------------------------------------------------------------------------------
def test_turn_at_rest_and_at_speed() -> None:
    world, p = make_world()
    world.turn(p, 90.0)  # |v| = 0: body += 90 / 1
    assert p.body_deg == pytest.approx(90.0)
    world.place_player(p, 0.0, 0.0, 0.0, vx=0.4)
    world.turn(p, 90.0)  # 90 / (1 + 5 * 0.4) = 30
    assert p.body_deg == pytest.approx(30.0)
    world.place_player(p, 0.0, 0.0, 0.0)
    world.turn(p, 270.0)  # moment clamped to 180: 0 + 180 -> -180 in [-180, 180)
    assert p.body_deg == pytest.approx(-180.0)
    world.place_player(p, 0.0, 0.0, 170.0)
    world.turn(p, 20.0)  # 190 -> -170
    assert p.body_deg == pytest.approx(-170.0)


def test_client_turn_compensates_inertia() -> None:
    world, p = make_world()
    world.place_player(p, 0.0, 0.0, 0.0, vx=0.4)
    world.client_turn(p, 30.0)  # sends 30 * (1 + 5 * 0.4) = 90, the server divides by 3: turns 30
    assert p.body_deg == pytest.approx(30.0)
    world.place_player(p, 0.0, 0.0, 0.0, vx=0.4)
    world.client_turn(p, -90.0)  # -270 clamped to -180 -> -180 / 3 = -60
    assert p.body_deg == pytest.approx(-60.0)


def test_turn_noise_bounds() -> None:
    world, p = make_world(noise=True, seed=3)
    turns = []
    for _ in range(200):
        world.place_player(p, 0.0, 0.0, 0.0)
        world.turn(p, 100.0)  # (1 + U(-0.1, 0.1)) * 100
        turns.append(p.body_deg)
    assert 90.0 <= min(turns) < 92.0
    assert 108.0 < max(turns) <= 110.0


# --- kick -------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("ball_xy", "power", "direction", "eff"),
    [
        # gap = 0.7 - 0.385 = 0.315, dir_diff 0: 100 * 0.027 * (1 - 0.25 * 0.315 / 0.7) = 2.7 * 0.8875
        ((0.7, 0.0), 100.0, 0.0, 2.39625),
        # touching (gap 0) and straight behind (dir_diff pi): 2.7 * (1 - 0.25) = 2.025
        ((-0.385, 0.0), 100.0, 0.0, 2.025),
        # at the kickable edge 1.085 on the right: 2.7 * (1 - 0.25 * 0.5 - 0.25 * 0.7 / 0.7) = 2.7 * 0.625
        ((0.0, 1.085), 100.0, 0.0, 1.6875),
        # gap 0.115 in front, power 50, kicked to the right: 1.35 * (1 - 0.25 * 0.115 / 0.7)
        ((0.5, 0.0), 50.0, 90.0, 1.35 * (1.0 - 0.25 * 0.115 / 0.7)),
        # gap 0 in front, full power: exactly 2.7
        ((0.385, 0.0), 100.0, -45.0, 2.7),
    ],
)
def test_kick_effective_power(
    ball_xy: tuple[float, float], power: float, direction: float, eff: float
) -> None:
    world, p = make_world()
    world.place_ball(*ball_xy)
    assert world.kick(p, power, direction)
    assert world.ball.ax == pytest.approx(eff * math.cos(math.radians(direction)), abs=APPROX)
    assert world.ball.ay == pytest.approx(eff * math.sin(math.radians(direction)), abs=APPROX)


def test_kick_then_ball_moves() -> None:
    world, p = make_world()
    world.place_ball(0.7, 0.0)
    world.kick(p, 100.0, 0.0)
    world.step()
    # a = 2.39625 <= 2.7: x = 0.7 + 2.39625, v = 2.39625 * 0.94
    assert world.ball.x == pytest.approx(3.09625)
    assert world.ball.vx == pytest.approx(2.252475)
    assert (world.ball.ax, world.ball.ay) == (0.0, 0.0)


def test_kickable_limits_server_and_client() -> None:
    world, p = make_world()
    world.place_ball(1.085, 0.0)
    assert not world.client_kick(p, 100.0, 0.0)  # 1.085 > 1.03: librcsc refuses
    assert world.ball.ax == 0.0
    assert world.kick(p, 100.0, 0.0)  # the server accepts <= 1.085
    world.place_ball(1.0851, 0.0)
    assert not world.kick(p, 100.0, 0.0)
    assert world.ball.ax == 0.0
    world.place_ball(0.0, -1.03)
    assert world.client_kick(p, 100.0, 0.0)
    # gap 0.645, dir_diff pi/2: 2.7 * (1 - 0.125 - 0.25 * 0.645 / 0.7)
    assert world.ball.ax == pytest.approx(2.7 * (0.875 - 0.25 * 0.645 / 0.7))


def test_client_kick_power_clamped() -> None:
    world, p = make_world()
    world.place_ball(0.385, 0.0)
    assert world.client_kick(p, -50.0, 0.0)  # negative power -> 0: accepted, no acceleration
    assert (world.ball.ax, world.ball.ay) == (0.0, 0.0)
    assert world.client_kick(p, 150.0, 0.0)  # -> 100: 2.7
    assert world.ball.ax == pytest.approx(2.7)


def test_kick_noise_bounds() -> None:
    # ball 0.7 in front at rest: pos_rate = 0.5 + 0.25 * (0 + 0.45) = 0.6125, speed_rate = 0.5,
    # m = 0.1 * (100/100) * 1.1125 = 0.11125 around the noiseless 2.39625
    world, p = make_world(noise=True, seed=5)
    deviations = []
    for _ in range(300):
        world.place_ball(0.7, 0.0)
        world.kick(p, 100.0, 0.0)
        deviations.append(math.hypot(world.ball.ax - 2.39625, world.ball.ay))
    assert max(deviations) <= 0.11125 + 1e-12
    assert max(deviations) > 0.1


# --- caps and decay ---------------------------------------------------------------------------------
def test_ball_accel_cap_and_speed_cap() -> None:
    world, _ = make_world()
    world.place_ball(0.0, 10.0)
    world.ball.ax = 4.0  # |a| capped at 2.7
    world.step()
    assert world.ball.x == pytest.approx(2.7)
    assert world.ball.vx == pytest.approx(2.7 * 0.94)
    world.place_ball(0.0, 10.0, vx=2.0)
    world.ball.ax = 2.0  # v = 4.0 capped at 3.0
    world.step()
    assert world.ball.x == pytest.approx(3.0)
    assert world.ball.vx == pytest.approx(2.82)


def test_speed_not_capped_without_acceleration() -> None:
    # rcssserver caps the speed only in the branch that applies a non-zero acceleration
    world, _ = make_world()
    world.place_ball(0.0, 10.0, vx=3.5)
    world.step()
    assert world.ball.x == pytest.approx(3.5)


def test_ball_kicked_at_full_power_travels_45m() -> None:
    # sum of 2.7 * 0.94^k = 2.7 / 0.06 = 45
    world, _ = make_world()
    world.place_ball(0.0, 10.0)
    world.ball.ax = 2.7
    for _ in range(400):
        world.step()
    assert world.ball.x == pytest.approx(45.0, abs=1e-6)


def test_player_speed_and_accel_cap() -> None:
    world, p = make_world()
    world.place_player(p, 0.0, 0.0, 0.0, vx=0.6)
    world.dash(p, 100.0, 0.0)  # 0.6 + 0.6 = 1.2 capped at 1.05
    world.step()
    assert p.x == pytest.approx(1.05)
    assert p.vx == pytest.approx(0.42)
    world.place_player(p, 0.0, 0.0, 0.0)
    p.ax = 1.5  # |a| capped at player_accel_max 1.0, then |v| 1.0 <= 1.05
    world.step()
    assert p.x == pytest.approx(1.0)


def test_full_dash_steady_state() -> None:
    # v_{n+1} = 0.4 * (v_n + 0.6) -> 0.4 after decay, 1.0 m per cycle
    world, p = make_world()
    world.place_player(p, -40.0, 0.0, 0.0)
    for _ in range(30):
        world.dash(p, 100.0, 0.0)
        world.step()
    x0 = p.x
    world.dash(p, 100.0, 0.0)
    world.step()
    assert p.x - x0 == pytest.approx(1.0)
    assert p.vx == pytest.approx(0.4)


def test_decay() -> None:
    world, p = make_world()
    world.place_player(p, 0.0, 0.0, 0.0, vx=0.5, vy=-0.25)
    world.place_ball(10.0, 10.0, vx=1.0)
    world.step()
    assert (p.x, p.y) == pytest.approx((0.5, -0.25))
    assert (p.vx, p.vy) == pytest.approx((0.2, -0.1))
    assert (world.ball.x, world.ball.vx) == pytest.approx((11.0, 0.94))
    assert world.cycle == 1


def test_motion_noise_bounds() -> None:
    # v += polar(U(0, 0.1 * 0.5), U(-pi, pi)): the move deviates by at most 0.05
    world, p = make_world(noise=True, seed=11)
    deviations = []
    for _ in range(300):
        world.place_player(p, 0.0, 0.0, 0.0, vx=0.5)
        world.step()
        deviations.append(math.hypot(p.x - 0.5, p.y))
    assert max(deviations) <= 0.05 + 1e-12
    assert max(deviations) > 0.045


# --- overlaps ---------------------------------------------------------------------------------------
def test_ball_player_overlap_pushed_apart() -> None:
    world, p = make_world()
    world.place_player(p, 0.0, 0.0, 0.0, vx=0.25)
    world.place_ball(0.5, 0.0, vx=-0.1)
    world.step()
    # after moving: player 0.25 (v 0.1), ball 0.4 (v -0.094); distance 0.15 < 0.385;
    # midpoint 0.325, each ends 0.1925 from it; velocities * -0.1
    assert p.x == pytest.approx(0.325 - 0.1925)
    assert world.ball.x == pytest.approx(0.325 + 0.1925)
    assert world.ball.x - p.x >= 0.385
    assert p.vx == pytest.approx(-0.01)
    assert world.ball.vx == pytest.approx(0.0094)
    assert p.collided_ball and world.ball.collided_player and not p.collided_player


def test_player_player_overlap_pushed_apart() -> None:
    world, a = make_world()
    b = world.add_player("r", 1, goalie=True)
    world.place_player(a, 0.0, 0.0, 0.0, vx=0.1)
    world.place_player(b, 0.4, 0.3, 0.0, vx=0.1)
    world.step()
    # after moving a = (0.1, 0), b = (0.5, 0.3): distance 0.5 < 0.6; midpoint (0.3, 0.15), unit (0.8, 0.6),
    # each ends 0.3 away: a = (0.06, -0.03), b = (0.54, 0.33); v = 0.04 * -0.1
    assert (a.x, a.y) == pytest.approx((0.06, -0.03))
    assert (b.x, b.y) == pytest.approx((0.54, 0.33))
    assert math.hypot(b.x - a.x, b.y - a.y) >= 0.6
    assert a.vx == pytest.approx(-0.004) and b.vx == pytest.approx(-0.004)
    assert a.collided_player and b.collided_player and not a.collided_ball


@pytest.mark.parametrize("pymunk_contacts", [False, True])
def test_overlap_normal_float_and_pymunk_agree(pymunk_contacts: bool) -> None:
    world = World(ServerParams(), np.random.default_rng(0), noise=False, pymunk_contacts=pymunk_contacts)
    a = world.add_player("l", 11)
    b = world.add_player("r", 1)
    world.place_ball(-20.0, 20.0)
    world.place_player(a, 1.0, 2.0, 0.0)
    world.place_player(b, 1.4, 2.3, 0.0)  # 0.5 apart along (0.8, 0.6): ends at midpoint -/+ 0.3 * (0.8, 0.6)
    world.step()
    assert (a.x, a.y, b.x, b.y) == pytest.approx((0.96, 1.97, 1.44, 2.33))


def test_coincident_players_separated_at_random_angle() -> None:
    world, a = make_world()
    b = world.add_player("r", 1)
    world.place_player(a, 5.0, 5.0, 0.0)
    world.place_player(b, 5.0, 5.0, 0.0)
    world.step()
    assert math.hypot(b.x - a.x, b.y - a.y) == pytest.approx(0.6)
    assert (a.x + b.x, a.y + b.y) == pytest.approx((10.0, 10.0))


def test_no_overlap_no_change() -> None:
    world, p = make_world()
    world.place_player(p, 0.0, 0.0, 0.0)
    world.place_ball(0.386, 0.0)  # 0.386 >= 0.385: not overlapping
    world.step()
    assert (p.x, world.ball.x) == (0.0, 0.386)
    assert not p.collided_ball


# --- goal posts -------------------------------------------------------------------------------------
def test_ball_bounces_off_post_head_on() -> None:
    post_x, post_y = GOAL_POSTS[1]
    world, _ = make_world()
    world.place_ball(51.0, post_y, vx=2.0)
    world.step()
    # contact at 52.44 - (0.06 + 0.085) = 52.295 after 1.295; the remaining 0.705 goes back
    assert world.ball.x == pytest.approx(52.295 - 0.705)
    assert world.ball.y == pytest.approx(post_y)
    assert world.ball.vx == pytest.approx(-2.0 * 0.94)
    assert world.ball.collided_post


def test_ball_bounces_off_post_oblique() -> None:
    post_x, post_y = GOAL_POSTS[0]  # (52.44, -7.07)
    world, _ = make_world()
    world.place_ball(51.0, post_y + 0.1, vx=2.0)
    world.step()
    # contact where (x - 52.44)^2 + 0.1^2 = 0.145^2: x = 52.44 - 0.105 = 52.335, after 1.335 of 2.0;
    # normal n = (-0.105, 0.1) / 0.145; v' = v - 2 (v.n) n keeps |v| = 2
    nx, ny = -0.105 / 0.145, 0.1 / 0.145
    vn = 2.0 * nx
    vx, vy = 2.0 - 2.0 * vn * nx, -2.0 * vn * ny
    assert math.hypot(vx, vy) == pytest.approx(2.0)
    assert (world.ball.vx, world.ball.vy) == pytest.approx((0.94 * vx, 0.94 * vy))
    rest = (2.0 - 1.335) / 2.0
    assert world.ball.x == pytest.approx(52.335 + rest * vx)
    assert world.ball.y == pytest.approx(post_y + 0.1 + rest * vy)
    assert world.ball.collided_post


def test_ball_overlapping_post_is_pushed_out() -> None:
    post_x, post_y = GOAL_POSTS[1]
    world, _ = make_world()
    world.place_ball(post_x - 0.1, post_y, vx=0.5)
    world.step()
    # put at 52.44 - 0.145 = 52.295, velocity reflected to -0.5, then moves: 51.795, v = -0.47
    assert world.ball.x == pytest.approx(51.795)
    assert world.ball.vx == pytest.approx(-0.47)
    assert world.ball.collided_post


def test_ball_passes_between_posts() -> None:
    world, _ = make_world()
    world.place_ball(51.0, 6.9, vx=2.0)  # 7.07 - 6.9 = 0.17 > 0.145: misses the post
    world.step()
    assert world.ball.x == pytest.approx(53.0)
    assert not world.ball.collided_post


def test_player_hits_post() -> None:
    post_x, post_y = GOAL_POSTS[1]
    world, p = make_world()
    world.place_player(p, 51.5, post_y, 0.0, vx=1.0)
    world.step()
    # contact at 52.44 - 0.36 = 52.08 after 0.58; the remaining 0.42 goes back: 51.66; v = -1 * 0.4
    assert p.x == pytest.approx(51.66)
    assert p.vx == pytest.approx(-0.4)
    assert p.collided_post


# --- stamina ----------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("stamina", "effort", "recovery", "capacity", "expected"),
    [
        # <= 2400 (0.3 * 8000): recovery -0.002, effort -0.005, then stamina += 45 * 0.998
        (2400.0, 1.0, 1.0, 130600.0, (2400.0 + 45 * 0.998, 0.995, 0.998, 130600.0 - 45 * 0.998)),
        # floors: effort 0.6, recovery 0.5; stamina += 45 * 0.5
        (100.0, 0.6, 0.5, 130600.0, (122.5, 0.6, 0.5, 130600.0 - 22.5)),
        # between the thresholds: only the recovery of stamina
        (3000.0, 0.9, 0.9, 130600.0, (3040.5, 0.9, 0.9, 130600.0 - 40.5)),
        # >= 4800 (0.6 * 8000): effort +0.01
        (4800.0, 0.9, 1.0, 130600.0, (4845.0, 0.91, 1.0, 130555.0)),
        # capped at stamina_max 8000
        (7990.0, 1.0, 1.0, 130600.0, (8000.0, 1.0, 1.0, 130590.0)),
        # capped by the remaining capacity
        (5000.0, 1.0, 1.0, 10.0, (5010.0, 1.0, 1.0, 0.0)),
    ],
)
def test_stamina_update(
    stamina: float, effort: float, recovery: float, capacity: float, expected: tuple[float, ...]
) -> None:
    world, p = make_world()
    p.stamina, p.effort, p.recovery, p.capacity = stamina, effort, recovery, capacity
    world.step()
    assert (p.stamina, p.effort, p.recovery, p.capacity) == pytest.approx(expected)


def test_effort_drops_after_101_full_dashes() -> None:
    # each cycle: -100 (dash), then +45; the threshold test sees the post-dash stamina 7955 - 55k,
    # which first reaches <= 2400 on dash k = 101
    world, p = make_world()
    world.place_player(p, -50.0, 0.0, 90.0)
    for _ in range(100):
        world.dash(p, 100.0, 0.0)
        world.step()
    assert p.stamina == pytest.approx(8000.0 - 5500.0)
    assert p.effort == 1.0
    world.dash(p, 100.0, 0.0)
    world.step()
    assert p.effort == pytest.approx(0.995)
    assert p.recovery == pytest.approx(0.998)
    world.recover_players()
    assert (p.stamina, p.effort, p.recovery, p.capacity) == (8000.0, 1.0, 1.0, 130600.0)


# --- client dash ------------------------------------------------------------------------------------
def test_client_dash_rounds_and_conserves() -> None:
    world, p = make_world()
    world.client_dash(p, 150.0, 30.0)  # power 100, direction 45: 0.42 at 45 deg
    assert (p.ax, p.ay) == pytest.approx((0.42 / math.sqrt(2), 0.42 / math.sqrt(2)))
    p.ax = p.ay = 0.0
    p.stamina = 20.0
    world.client_dash(p, -100.0, 0.0)  # available 70, backward: power -35, a 0.21 backwards
    assert p.ax == pytest.approx(-0.21)
    assert p.stamina == 0.0


def test_client_dash_limits_speed() -> None:
    world, p = make_world()
    world.place_player(p, 0.0, 0.0, 0.0, vx=0.8)
    world.client_dash(p, 100.0, 0.0)  # |0.8 + 0.6| > 1.05: a cut to 0.25, power 0.25 / 0.006
    assert p.ax == pytest.approx(0.25)
    assert p.stamina == pytest.approx(8000.0 - 0.25 / 0.006)
    world.place_player(p, 0.0, 0.0, 0.0, vx=0.8)
    p.stamina = 8000.0
    world.client_dash(p, 100.0, 0.0, limit_speed=False)
    assert p.ax == pytest.approx(0.6)


# --- determinism ------------------------------------------------------------------------------------
def run_episode(noise: bool, seed: int) -> list[tuple[float, ...]]:
    world, p = make_world(noise=noise, seed=seed)
    world.place_player(p, 10.0, 0.0, 0.0)
    world.place_ball(10.6, 0.0)
    trace = []
    for t in range(60):
        if t % 3 == 0:
            world.client_kick(p, 60.0, 10.0)
        elif t % 3 == 1:
            world.client_turn(p, 20.0)
        else:
            world.client_dash(p, 80.0, 0.0)
        world.step()
        b = world.ball
        trace.append((p.x, p.y, p.vx, p.vy, p.body_deg, b.x, b.y, b.vx, b.vy))
    return trace


def test_noise_off_is_deterministic() -> None:
    assert run_episode(False, 1) == run_episode(False, 2)


def test_noise_on_is_seeded() -> None:
    assert run_episode(True, 7) == run_episode(True, 7)
    assert run_episode(True, 7) != run_episode(True, 8)
    assert run_episode(True, 7) != run_episode(False, 7)


def test_replacing_rng_discards_buffer() -> None:
    world, p = make_world(noise=True, seed=1)
    world.place_player(p, 0.0, 0.0, 0.0, vx=0.5)
    world.step()
    world.rng = np.random.default_rng(42)
    world.place_player(p, 0.0, 0.0, 0.0, vx=0.5)
    world.step()
    other, q = make_world(noise=True, seed=42)
    other.place_player(q, 0.0, 0.0, 0.0, vx=0.5)
    other.step()
    assert (p.x, p.y) == (q.x, q.y)


def test_state_types() -> None:
    world, p = make_world()
    assert isinstance(world.ball, BallState) and world.players == [p]
    assert world.ball_distance(p) == pytest.approx(math.hypot(20.0, 20.0))
    with pytest.raises(ValueError):
        world.add_player("x", 1)
