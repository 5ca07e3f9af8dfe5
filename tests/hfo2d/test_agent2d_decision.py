"""HFO's goalie decision rules (hfo2d.agent2d.decision) on hand-computed cases.

The expected numbers are worked out by hand from HFO's ``bhv_goalie_basic_move.cpp`` / ``bhv_goalie_chase_ball.cpp``
rules (targets, dash powers, chase tests), in the global frame G where the goalie defends x = +52.5, and converted
to the goalie frame GF with (x, y)_GF = (-x, -y)_G.
"""

from __future__ import annotations

import math

import pytest

from hfo2d.agent2d.common import Effector, GoalieView, InterceptTable, norm_deg
from hfo2d.agent2d.decision import (
    Line,
    basic_dash_power,
    can_catch,
    decide,
    go_to_catch_point,
    is_ball_chase_situation,
    is_ball_shoot_moving,
    target_point,
)


def view_g(
    ball: tuple[float, float],
    ball_vel: tuple[float, float] = (0.0, 0.0),
    goalie: tuple[float, float] = (52.5, 0.0),
    body_g: float = 180.0,
    attacker: tuple[float, float] | None = (0.0, 0.0),
    kick_opp: bool = False,
    stamina: float = 8000.0,
    cycle: int = 100,
) -> GoalieView:
    """A goalie view from global-frame (G) inputs."""
    view = GoalieView(
        cycle=cycle,
        px=-goalie[0],
        py=-goalie[1],
        vx=0.0,
        vy=0.0,
        body=norm_deg(body_g - 180.0),
        stamina=stamina,
        effort=1.0,
        recovery=1.0,
        bx=-ball[0],
        by=-ball[1],
        wx=-ball_vel[0],
        wy=-ball_vel[1],
        true_wx=-ball_vel[0],
        true_wy=-ball_vel[1],
        has_opp=attacker is not None,
        kick_opp=kick_opp,
    )
    if attacker is not None:
        view.ox, view.oy = -attacker[0], -attacker[1]
    return view


def table(self_min: int = 20, opp_min: int = 10) -> InterceptTable:
    return InterceptTable(ball_cache=[], self_min=self_min, opp_min=opp_min)


def to_g(point: tuple[float, float]) -> tuple[float, float]:
    return -point[0], -point[1]


# Spec §8 item 1: target points for a ball at rest (G inputs, G outputs), from the rules by hand.
@pytest.mark.parametrize(
    ("ball", "expected"),
    [
        ((40.0, 10.0), (49.8, 4.974)),
        ((40.0, 9.0), (49.8, 4.477)),
        ((10.0, 0.0), (49.8, 0.0)),
        ((5.0, -20.0), (49.8, -3.560)),
        ((30.0, -20.0), (49.8, -6.51)),
        ((50.0, -8.0), (49.8, -6.51)),
        ((44.0, -10.0), (49.8, -6.258)),
        ((52.0, 3.0), (49.8, 3.88)),
        ((48.0, 15.0), (51.5, 7.011)),
        ((51.0, -12.0), (51.5, -7.011)),
        ((46.0, 12.0), (49.8, 6.91)),
        ((45.0, 9.5), (49.8, 6.91)),
    ],
)
def test_target_point_for_a_resting_ball(ball: tuple[float, float], expected: tuple[float, float]) -> None:
    x, y = to_g(target_point(view_g(ball), table()))
    assert x == pytest.approx(expected[0], abs=1e-9)
    assert y == pytest.approx(expected[1], abs=1e-3)


def test_target_point_of_a_moving_ball_applies_the_velocity_twice() -> None:
    """The line rule predicts the ball to the opponent's reach, then adds min(5, opp_min) cycles of the *current*
    velocity again (agent2d's quirk): ball (20, 0) moving (1.0, 0.5), opp_min 10 -> (49.8, 2.148)."""
    x, y = to_g(target_point(view_g((20.0, 0.0), ball_vel=(1.0, 0.5)), table(opp_min=10)))
    assert x == pytest.approx(49.8)
    f10 = (1 - 0.94**10) / 0.06
    f5 = (1 - 0.94**5) / 0.06
    qx, qy = 20.0 + f10 + f5, 0.5 * (f10 + f5)
    assert y == pytest.approx(qy * 9.7 / (59.5 - qx), abs=1e-9)
    assert y == pytest.approx(2.148, abs=1e-3)


def test_target_point_with_a_kickable_opponent_uses_the_ball_itself() -> None:
    x, y = to_g(target_point(view_g((40.0, 10.0), ball_vel=(0.0, 0.0), kick_opp=True), table(opp_min=0)))
    assert (x, y) == pytest.approx((49.8, 10.0 * 9.7 / 19.5))


# Spec §8 item 3: BasicDashPower.
@pytest.mark.parametrize(
    ("ball", "goalie", "stamina", "opp_min", "expected"),
    [
        ((20.0, 0.0), (52.5, 0.0), 8000.0, 10, 45.0),  # far ball, |dx| <= 3
        ((20.0, 0.0), (52.5, 0.0), 7000.0, 10, 22.5),  # same, stamina under 7200
        ((33.0, 5.0), (50.0, 0.0), 8000.0, 3, 100.0),  # 30 <= x < 36, attacker reach <= 3
        ((33.0, 5.0), (50.0, 0.0), 8000.0, 6, 60.0),
        ((40.0, 16.0), (50.0, 1.0), 8000.0, 6, 45.0),  # inside the area depth, wide, same side
        ((40.0, 16.0), (50.0, -1.0), 8000.0, 6, 100.0),  # other side
        ((20.0, 0.0), (45.0, 0.0), 8000.0, 10, 100.0),  # |dx| > 3
    ],
)
def test_basic_dash_power(
    ball: tuple[float, float], goalie: tuple[float, float], stamina: float, opp_min: int, expected: float
) -> None:
    v = view_g(ball, goalie=goalie, stamina=stamina)
    assert basic_dash_power(v, table(opp_min=opp_min), -49.8) == pytest.approx(expected)


def test_catch_needs_the_ball_inside_1_25_m_and_the_rectangle_and_the_ban_over() -> None:
    v = view_g((48.6, 0.0), goalie=(49.8, 0.0))
    assert can_catch(v, last_catch_cycle=0)
    assert not can_catch(v, last_catch_cycle=v.cycle - 5)  # cycle must exceed the last catch time + 5
    assert can_catch(v, last_catch_cycle=v.cycle - 6)
    assert not can_catch(view_g((48.5, 0.0), goalie=(49.8, 0.0)), 0)  # 1.3 m: too far
    assert not can_catch(view_g((36.9, 0.0), goalie=(38.0, 0.0)), 0)  # outside the rectangle (x < 37 in G)
    assert not can_catch(view_g((45.0, 19.2), goalie=(45.0, 18.2)), 0)  # |y| > 19.16


def test_the_catch_direction_points_the_rectangle_diagonal_at_the_ball() -> None:
    v = view_g((48.6, 0.0), goalie=(49.8, 0.0), body_g=90.0)
    eff = Effector()
    decide(eff, v, table(self_min=1, opp_min=10), last_catch_cycle=0)
    assert eff.command is not None and eff.command.kind == "catch"
    # the ball is straight up-field (180 deg G = 0 deg GF); the body faces 90 deg G = -90 deg GF
    assert eff.command.a == pytest.approx(norm_deg(0.0 - -90.0 + math.degrees(math.atan2(0.5, 1.2))))


def test_shot_test() -> None:
    # a ball at 44 m moving to goal at 2 m/cycle, crossing the line near the centre
    assert is_ball_shoot_moving(view_g((44.0, 2.0), ball_vel=(2.0, -0.1), goalie=(49.8, 0.0)))
    # too slow to reach beyond 50.5
    assert not is_ball_shoot_moving(view_g((44.0, 2.0), ball_vel=(0.3, 0.0), goalie=(49.8, 0.0)))
    # wide of the goal
    assert not is_ball_shoot_moving(view_g((44.0, 2.0), ball_vel=(2.0, 2.0), goalie=(49.8, 0.0)))
    # held by the attacker
    assert not is_ball_shoot_moving(
        view_g((44.0, 2.0), ball_vel=(2.0, 0.0), goalie=(49.8, 0.0), kick_opp=True)
    )


def test_chase_situation_in_the_danger_area() -> None:
    v = view_g((47.0, 0.0), ball_vel=(0.5, 0.0), goalie=(49.8, 0.0), attacker=(40.0, 0.0))
    assert is_ball_chase_situation(v, table(self_min=4, opp_min=20))
    # the opponent is much faster (self_min > opp_min + 3 and opp_min < 7)
    assert not is_ball_chase_situation(v, table(self_min=10, opp_min=6))
    # the ball within 3 m and self_min <= 3 wins over that
    near = view_g((47.5, 0.0), ball_vel=(0.5, 0.0), goalie=(49.8, 0.0), attacker=(47.0, 0.0))
    assert is_ball_chase_situation(near, table(self_min=3, opp_min=0))


def test_chase_situation_outside_the_danger_area() -> None:
    # a slow ball at 38 m rolling towards the goalie, opponent far: the intercept point is in the area
    v = view_g((38.0, 5.0), ball_vel=(0.6, 0.0), goalie=(49.8, 2.0), attacker=(20.0, 0.0))
    assert is_ball_chase_situation(v, table(self_min=8, opp_min=30))
    # the opponent reaches it two cycles earlier
    assert not is_ball_chase_situation(v, table(self_min=8, opp_min=6))
    # the intercept point outside the area
    far = view_g((20.0, 5.0), ball_vel=(0.2, 0.0), goalie=(49.8, 2.0), attacker=(0.0, 0.0))
    assert not is_ball_chase_situation(far, table(self_min=8, opp_min=30))


def test_go_to_catch_point_dashes_forward_back_or_turns() -> None:
    eff = Effector()
    ahead = view_g((40.0, 0.0), goalie=(49.8, 0.0), body_g=180.0)  # facing the field, the point ahead
    go_to_catch_point(eff, ahead, ahead.bx, ahead.by)
    assert eff.command is not None and (eff.command.kind, eff.command.a) == ("dash", 100.0)
    behind = view_g((40.0, 0.0), goalie=(49.8, 0.0), body_g=0.0)
    go_to_catch_point(eff, behind, behind.bx, behind.by)
    assert eff.command is not None and (eff.command.kind, eff.command.a) == ("dash", -100.0)
    side = view_g((40.0, 0.0), goalie=(49.8, 0.0), body_g=135.0)
    go_to_catch_point(eff, side, side.bx, side.by)
    assert eff.command is not None and eff.command.kind == "turn"
    assert eff.command.a == pytest.approx(45.0)


def test_line_matches_librcsc_line2d() -> None:
    line = Line.from_angle(1.0, 2.0, 30.0)
    assert line.dist(1.0, 2.0) == pytest.approx(0.0, abs=1e-12)
    assert line.get_y(1.0 + math.sqrt(3.0)) == pytest.approx(3.0)
    vertical = Line.from_points(5.0, -10.0, 5.0, 10.0)
    x, y = line.intersection(vertical)
    assert x == pytest.approx(5.0)
    assert y == pytest.approx(2.0 + 4.0 / math.sqrt(3.0))
    assert Line.from_angle(0.0, 0.0, 90.0).intersection(vertical) is None
