"""hfo2d.agent2d.tackle: agent2d's Bhv_BasicTackle (version-14 path) and TackleGenerator, client side, in GF
(goal at x = -52.5). Numbers worked out by hand from the rules of HFO's bhv_basic_tackle.cpp,
tackle_generator.cpp, field_analyzer.cpp and librcsc's self_object.cpp (spec §3.7)."""

from __future__ import annotations

import math

import pytest

from hfo2d.agent2d.common import Effector, GoalieView, InterceptTable, norm_deg
from hfo2d.agent2d.tackle import (
    ball_move_step,
    basic_tackle,
    best_tackle,
    client_tackle_dir,
    evaluate_tackle,
    opponents_reach_step,
    tackle_probabilities,
)


def view(
    px: float = -48.0,
    py: float = 0.0,
    body: float = 90.0,
    bx: float = -48.0,
    by: float = 1.3,
    wx: float = 0.0,
    wy: float = 0.0,
    **kw: object,
) -> GoalieView:
    v = GoalieView(
        cycle=10,
        px=px,
        py=py,
        vx=0.0,
        vy=0.0,
        body=body,
        stamina=8000.0,
        effort=1.0,
        recovery=1.0,
        bx=bx,
        by=by,
        wx=wx,
        wy=wy,
        true_wx=wx,
        true_wy=wy,
        has_opp=False,
    )
    for key, value in kw.items():
        setattr(v, key, value)
    return v


def table(self_min: int = 3, opp_min: int = 0) -> InterceptTable:
    return InterceptTable(ball_cache=[], self_min=self_min, opp_min=opp_min)


# --- probabilities ---------------------------------------------------------------------------------------------
def test_probabilities_spec_8_6() -> None:
    tp, fp = tackle_probabilities(view(by=1.3), opp_min=0)  # body +90, ball 1.3 m ahead
    assert tp == pytest.approx(1.0 - 0.65**6, abs=1e-12)
    assert fp == pytest.approx(1.0 - 0.65**10, abs=1e-12)
    tp, _ = tackle_probabilities(view(bx=-48.9, by=1e-9), opp_min=0)  # 0.9 m sideways, a hair in front
    assert tp == pytest.approx(1.0 - (0.9 / 1.25) ** 6, abs=1e-9)
    assert tackle_probabilities(view(by=1.529), 0)[0] >= 0.8 > tackle_probabilities(view(by=1.53), 0)[0]
    assert tackle_probabilities(view(by=-0.5), 0) == (0.0, 0.0)  # behind: back distance 0
    assert tackle_probabilities(view(by=2.1), 0) == (0.0, 0.0)  # beyond 2.0


def test_foul_probability_needs_opponent_reach_zero() -> None:
    """librcsc updateKickableState: the foul probability is zeroed whenever the opponent reach cycle is > 0."""
    assert tackle_probabilities(view(by=1.3), opp_min=1)[1] == 0.0
    assert tackle_probabilities(view(by=1.3), opp_min=0)[1] > 0.0


# --- Bhv_BasicTackle gates -------------------------------------------------------------------------------------
def test_low_probability_no_tackle() -> None:
    eff = Effector()
    assert not basic_tackle(eff, view(by=1.6, kick_opp=True), table())  # 1 - 0.8^6 = 0.738 < 0.8
    assert eff.command is None


def test_not_needed_no_tackle() -> None:
    eff = Effector()
    # the attacker is not kickable, the ball is at rest in front (no goal threat), opp_min not < self_min - 3
    assert not basic_tackle(eff, view(by=1.3), table(self_min=3, opp_min=2))
    assert eff.command is None
    assert basic_tackle(eff, view(by=1.3), table(self_min=6, opp_min=2))  # opp_min < self_min - 3
    assert eff.command is not None and eff.command.kind == "tackle"


def test_kickable_opponent_tackles() -> None:
    eff = Effector()
    v = view(by=1.3, kick_opp=True)
    assert basic_tackle(eff, v, table())
    angle = best_tackle(v)[0]
    assert eff.command is not None
    assert eff.command.a == norm_deg(angle - v.body)
    assert eff.command.foul is False  # inside the penalty area


def test_ball_into_goal_tackles() -> None:
    """ballAt(self_min) behind the goal line and the ray from B along angle(W) meets it at |y| < 8.01."""
    eff = Effector()
    v = view(px=-51.0, py=0.0, body=180.0, bx=-52.0, by=0.5, wx=-0.8, wy=0.1)
    assert tackle_probabilities(v, 5)[0] >= 0.8
    assert basic_tackle(eff, v, table(self_min=2, opp_min=50))
    # the same ball moving away from the goal: not needed
    eff = Effector()
    assert not basic_tackle(eff, view(px=-51.0, body=180.0, bx=-52.0, by=0.5, wx=0.8), table(2, 50))


def test_foul_outside_penalty_area() -> None:
    """Outside the box + 0.5 the higher foul probability is used, with the foul flag; at 1.6 m the tackle
    probability (0.738) alone is too low but the foul one (1 - 0.8^10 = 0.893) passes."""
    eff = Effector()
    v = view(px=-30.0, py=0.0, bx=-30.0, by=1.6, kick_opp=True)
    assert basic_tackle(eff, v, table(opp_min=0))
    assert eff.command is not None and eff.command.foul is True
    eff = Effector()
    assert not basic_tackle(eff, v, table(opp_min=1))  # foul probability zeroed: 0.738 < 0.8
    eff = Effector()
    inside = view(px=-40.0, py=0.0, bx=-40.0, by=1.6, kick_opp=True)
    assert not basic_tackle(eff, inside, table(opp_min=0))


def test_cleared_generator_result_quirks() -> None:
    """A kickable goalie or a mode other than PlayOn: TackleGenerator makes no candidate and the tackle goes to
    the cleared angle 0 (global), i.e. norm(0 - body) relative."""
    for v in (view(by=1.3, kick_opp=True, self_kickable=True), view(by=1.3, kick_opp=True, play_on=False)):
        eff = Effector()
        assert basic_tackle(eff, v, table())
        assert eff.command is not None and eff.command.a == norm_deg(0.0 - v.body)


# --- TackleGenerator ---------------------------------------------------------------------------------------------
def test_candidates_and_choice() -> None:
    v = view(by=1.3, kick_opp=True, has_opp=True, ox=-48.0, oy=2.3, obody=-90.0)
    angle, vx, vy, score = best_tackle(v)
    rel = norm_deg(angle - v.body)
    assert (rel + 180.0) % 9.0 == pytest.approx(0.0, abs=1e-9)  # one of dir = -180 + 9 i
    eff_power = 100.0 * (1.0 - abs(rel) / 180.0) * 0.027 * (1.0 - 0.5 * 0.0 / 180.0)  # ball straight ahead
    assert math.hypot(vx, vy) == pytest.approx(eff_power, abs=1e-9)
    assert score == evaluate_tackle(v, vx, vy)
    # no candidate scores higher
    for i in range(40):
        d = norm_deg(v.body - 180.0 + 9.0 * i)
        p = 100.0 * (1.0 - abs(norm_deg(d - v.body)) / 180.0) * 0.027
        cvx, cvy = p * math.cos(math.radians(d)), p * math.sin(math.radians(d))
        assert evaluate_tackle(v, cvx, cvy) <= score + 1e-9


def test_speed_capped_at_ball_speed_max() -> None:
    v = view(by=1.0, wx=2.5, wy=0.0, kick_opp=False)
    _, vx, vy, _ = best_tackle(v)
    assert math.hypot(vx, vy) <= 3.0 + 1e-12


def test_evaluate_normal_by_hand() -> None:
    """No attacker: reach step 1000; final point ~ B + v / 0.06 inside the pitch."""
    v = view(bx=-40.0, by=0.0)
    score = evaluate_tackle(v, 0.0, 1.0)
    fy = 1.0 * (1.0 - 0.94**1000) / 0.06
    g = 1.0 - math.exp(-(90.0**2) / (2.0 * 40.0**2))
    y = math.exp(-((fy - 34.0) ** 2) / (2.0 * 23.8**2))
    o = 1.0 - math.exp(-(1000.0**2) / (2.0 * 30.0**2))
    assert score == pytest.approx(10000.0 * g * y * o, rel=1e-12)


def test_evaluate_own_goal_by_hand() -> None:
    v = view(bx=-50.0, by=0.0)
    vx, vy = -1.0, 0.1
    yc = 0.0 + 0.1 * (2.5 / 1.0)  # the segment B -> B + v / 0.06 meets x = -52.5 at y = 0.25
    expected = -10000.0 * math.exp(-((yc - 7.01) ** 2) / (2.0 * 7.01**2)) + 10000.0 * math.exp(
        -(vx * vx + vy * vy) / (2.0 * 1.5**2)
    )
    assert evaluate_tackle(v, vx, vy) == pytest.approx(expected, rel=1e-9)


def test_evaluate_pitch_clip_and_side_line() -> None:
    """A ball rolling out over the side line: its final point is clipped to the pitch, |F.y| > 33.9 gives
    y_rate 1, and the reach step is the ball-move step count to the line (no attacker: 1000)."""
    v = view(bx=-40.0, by=30.0)
    score = evaluate_tackle(v, 0.0, 2.0)
    goal_angle = math.degrees(math.atan2(0.0 - 30.0, -52.5 + 40.0))
    diff = abs(norm_deg(goal_angle - 90.0))
    goal_rate = 1.0 - math.exp(-(diff**2) / (2.0 * 40.0**2))
    expected = 10000.0 * goal_rate * 1.0 * (1.0 - math.exp(-(1000.0**2) / 1800.0))
    assert score == pytest.approx(expected, rel=1e-12)


def test_ball_move_step() -> None:
    # 2 + 1.88 + 1.7672 > 4 > 2 + 1.88: 3 steps
    assert ball_move_step(2.0, 4.0) == 3
    assert ball_move_step(2.0, 3.88 - 1e-9) == 2
    assert ball_move_step(1.0, 100.0) == 0  # never gets there: -1 truncates to 0 (librcsc's cast)


def test_opponent_reach_step_by_hand() -> None:
    """Attacker at rest 5 m up the ball's path, facing it: reach at step 3 (dash distance 2.003 - within 3 full
    dashes, no turn); while it is tackling (+5 steps) at step 7."""
    v = view(bx=-40.0, by=0.0, has_opp=True, ox=-35.0, oy=0.0, ux=0.0, uy=0.0, obody=180.0)
    assert opponents_reach_step(v, -40.0, 0.0, 0.5, 0.0, 0.0) == 3
    v.opp_tackle_count = 4
    assert opponents_reach_step(v, -40.0, 0.0, 0.5, 0.0, 0.0) == 7
    # no attacker: 1000
    assert opponents_reach_step(view(bx=-40.0, by=0.0), -40.0, 0.0, 0.5, 0.0, 0.0) == 1000
    # the ball rolls out (3 steps to the side line): an attacker that needs longer does not count
    far = view(bx=-40.0, by=30.0, has_opp=True, ox=-20.0, oy=30.0, obody=0.0)
    assert opponents_reach_step(far, -40.0, 30.0, 0.0, 2.0, 90.0) == 1000


def test_attacker_turn_counts() -> None:
    """An attacker facing away must turn (and pays the +1 observation step): later than one facing the ball."""
    facing = view(bx=-40.0, by=0.0, has_opp=True, ox=-35.0, oy=0.0, obody=180.0)
    away = view(bx=-40.0, by=0.0, has_opp=True, ox=-35.0, oy=0.0, obody=90.0)
    assert opponents_reach_step(away, -40.0, 0.0, 0.5, 0.0, 0.0) > opponents_reach_step(
        facing, -40.0, 0.0, 0.5, 0.0, 0.0
    )


# --- client conversion ---------------------------------------------------------------------------------------
def test_client_tackle_dir() -> None:
    assert client_tackle_dir(123.45678) == 123.457
    assert client_tackle_dir(200.0) == -160.0
    assert client_tackle_dir(-45.00049) == -45.0
    assert client_tackle_dir(12.3456789) == 12.346
    assert client_tackle_dir(0.0012345) == 0.001


def test_attacker_turn_pays_an_observation_step() -> None:
    """Facing 90 degrees off: one turn (180 / (1 + 0)) then dashes, plus 1 step: reach at 5 (dash 2 at step 5,
    1 + 2 + 1 = 4 <= 5; at step 4: 1 + 3 + 1 = 5 > 4)."""
    v = view(bx=-40.0, by=0.0, has_opp=True, ox=-35.0, oy=0.0, obody=90.0)
    assert opponents_reach_step(v, -40.0, 0.0, 0.5, 0.0, 0.0) == 5


def test_ties_go_to_the_first_candidate() -> None:
    """Facing the goal with the ball straight ahead and nobody else: dir +d and -d score exactly alike, and
    the first in TackleGenerator's order (-180 + 9 i) wins."""
    v = view(px=-45.0, py=0.0, body=180.0, bx=-46.3, by=0.0)
    angle, _, _, _ = best_tackle(v)
    assert norm_deg(angle - v.body) == -90.0


def test_pitch_corner_touch_counts_once() -> None:
    """librcsc Rect2D: two edge hits closer than 1e-5 are one intersection (a ray grazing a corner)."""
    from hfo2d.agent2d.tackle import _rect_ray

    # the line x + y = 86.5 touches the pitch only at its corner (52.5, 34): the right and bottom edges
    for ox, oy, deg in ((40.0, 46.5, -45.0), (60.0, 26.5, 135.0)):
        n, sol = _rect_ray(ox, oy, deg)
        assert n == 1 and sol is not None
        assert sol[0] == pytest.approx(52.5, abs=1e-9) and sol[1] == pytest.approx(34.0, abs=1e-9)
    assert _rect_ray(40.0, 46.5, 135.0)[0] == 0  # the corner behind the ray


def test_speed() -> None:
    import time

    v = view(by=1.3, kick_opp=True, has_opp=True, ox=-48.0, oy=2.3, ux=0.0, uy=-0.1, obody=-90.0)
    t = table()
    start = time.perf_counter()
    for _ in range(20):
        basic_tackle(Effector(), v, t)
    assert (time.perf_counter() - start) / 20 < 0.02  # ~2 ms on the dev VM
