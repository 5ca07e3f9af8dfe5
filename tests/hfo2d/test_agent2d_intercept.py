"""Tests of hfo2d.agent2d.intercept: librcsc's intercept table for HFO's goalie (GF throughout).

Hand cases follow the goalie specification (dash table of its section 2.4, the measured shot of 8.7 and the soft
ball of 8.8); the golden cases are tables that librcsc d222758 itself computed (``InterceptTable::update`` on
the same states, given here to 6 significant digits, through a small C++ harness linked against the real HFO
build's librcsc), with the results rounded to 9 significant digits.
"""

from __future__ import annotations

import math
import random

import pytest

from hfo2d.agent2d.common import EXHAUST, NORMAL, GoalieView, InterceptTable
from hfo2d.agent2d.intercept import _one_dash_adjust, build_intercept_table, cycles_to_reach_distance


def view(**kw: float | int | bool) -> GoalieView:
    base: dict = dict(
        cycle=0, px=-52.5, py=0.0, vx=0.0, vy=0.0, body=0.0, stamina=8000.0, effort=1.0, recovery=1.0
    )
    base.update(bx=-40.0, by=0.0, wx=0.0, wy=0.0, true_wx=0.0, true_wy=0.0, has_opp=False)
    base.update(kw)
    return GoalieView(**base)


def reach(e) -> int:  # noqa: ANN001
    return e.turn_cycle + e.dash_cycle


# --- section 2.4: the dash-distance table ----------------------------------------------------------------------
def test_cycles_to_reach_distance_follows_the_dash_table() -> None:
    assert cycles_to_reach_distance(0.0) == 0
    assert cycles_to_reach_distance(0.001) == 0
    assert cycles_to_reach_distance(0.6) == 1  # 0.6 after one full dash from rest
    assert cycles_to_reach_distance(0.6012) == 2  # beyond the 0.001 tolerance
    assert cycles_to_reach_distance(1.44) == 2
    assert cycles_to_reach_distance(2.376) == 3
    assert cycles_to_reach_distance(9.3334) == 10
    assert cycles_to_reach_distance(9.34) == 11  # then +1.0 per cycle
    assert cycles_to_reach_distance(20.0) == 21
    # beyond the 50-entry table: 50 + ceil(rest / 1.0)
    assert cycles_to_reach_distance(60.0) == 61


# --- section 4.5: ball cache, kickable shortcut, opp_min --------------------------------------------------------
def test_resting_ball_cache_has_six_equal_points() -> None:
    t = build_intercept_table(view(bx=-30.0, by=5.0))
    assert t.ball_cache == [(-30.0, 5.0)] * 6


def test_ball_cache_of_a_rolling_ball_and_its_pitch_bound() -> None:
    t = build_intercept_table(view(bx=-40.0, wx=1.0))  # decays below 0.01 only after 30 steps: the cap
    assert len(t.ball_cache) == 31
    assert t.ball_cache[1] == (-39.0, 0.0)
    assert t.ball_cache[2] == pytest.approx((-39.0 + 0.94, 0.0))
    t = build_intercept_table(view(bx=-50.0, wx=-2.5))  # leaves |x| > 57.5 at the 4th point
    xs = [x for x, _ in t.ball_cache]
    assert xs[-1] < -57.5 and all(x >= -57.5 for x in xs[:-1]) and len(xs) == 5


def test_kickable_goalie_gets_self_min_zero_and_no_candidates() -> None:
    t = build_intercept_table(view(bx=-51.6, by=0.2, wx=0.5, self_kickable=True))
    assert t.ball_cache == [(-51.6, 0.2)]
    assert t.self_min == 0 and t.self_cache == [] and t.opp_min == 1000


def test_opp_min_kickable_absent_on_ball_and_tackling() -> None:
    on_ball = dict(bx=-40.0, has_opp=True, ox=-39.5, oy=0.3)
    assert build_intercept_table(view(**on_ball, kick_opp=True)).opp_min == 0
    assert build_intercept_table(view(bx=-40.0)).opp_min == 1000
    assert build_intercept_table(view(**on_ball)).opp_min == 0  # within 1.085 of the resting ball
    # a tackle with 5 frozen cycles left: librcsc tackleCount 4, so 10 - 4 - 2 = 4 cycles are added
    assert build_intercept_table(view(**on_ball, opp_tackle_count=5)).opp_min == 4
    # far attacker: the fallback on the last cache point
    far = build_intercept_table(view(bx=-40.0, has_opp=True, ox=-10.0, oy=0.0, obody=180.0))
    assert far.opp_min == cycles_to_reach_distance(30.0 - 1.085 - math.hypot(42.5, 0.0) * 0.03)


def test_first_entry_exhaust_leaves_self_min_at_1000() -> None:
    # stamina 2500: the long-step dashes drop the stamina to 2400, the recovery falls, every candidate is EXHAUST
    t = build_intercept_table(view(px=-50.0, bx=-40.0, wx=-0.5, stamina=2500.0))
    assert t.self_cache and t.self_cache[0].mode == EXHAUST
    assert t.self_min == 1000
    assert reach(t.self_cache[0]) == 11


# --- section 8.7: a straight shot from 15 m (measured) -----------------------------------------------------------
def test_straight_shot_gives_the_measured_reach_4_and_5_candidates() -> None:
    # G: goalie (52.5, 0) body -90, ball (39.843, 0) moving at 2.538 towards the goal; GF: all negated, body +90
    t = build_intercept_table(view(bx=-39.843, wx=-2.538, body=90.0, has_opp=True, ox=-36.9))
    by_reach = {reach(e): e for e in t.self_cache}
    r4, r5 = by_reach[4], by_reach[5]
    assert (r4.turn_cycle, r4.dash_cycle) == (1, 3) and r4.ball_dist == pytest.approx(1.006, abs=1e-3)
    assert (r5.turn_cycle, r5.dash_cycle) == (1, 4) and r5.ball_dist < 0.01
    assert -r5.self_x == pytest.approx(51.10, abs=0.01)  # meets the ball at x 51.10 (G)
    assert t.self_min == 4
    # the next cycle (body turned to face the field): the reach-4 candidate needs no turn
    t = build_intercept_table(view(bx=-42.380, wx=-2.538 * 0.94, body=0.0, has_opp=True, ox=-37.5))
    first = t.self_cache[0]
    assert t.self_min == 3 and reach(t.self_cache[1]) == 4 and t.self_cache[1].turn_cycle == 0
    assert first.dash_power == 100.0


# --- section 8.8: the soft ball and the one-dash tie-break (measured) --------------------------------------------
SOFT = dict(px=-47.438, vx=0.383, bx=-45.724, wx=-0.175, body=0.0, stamina=7824.0)


def test_one_dash_tie_break_keeps_the_first_forward_direction() -> None:
    t = build_intercept_table(view(**SOFT))
    first = t.self_cache[0]
    # the no-dash test fails (1.156 > 1.3 - 0.15 - 0.05 * 0.175): the one-dash candidate of direction -45 wins
    assert (first.turn_cycle, first.dash_cycle) == (0, 1)
    assert first.dash_dir == -45.0 and first.dash_power == pytest.approx(100.0, abs=1e-9)
    assert first.ball_dist == pytest.approx(0.909, abs=1e-3) and first.mode == NORMAL
    assert first.stamina == 7824.0 - 100.0 + 45.0
    assert t.self_min == 1


def test_one_dash_zero_direction_would_be_closer_but_comes_later() -> None:
    # the 0-degree candidate leaves the ball at 0.556; both are within safe = 1.3 - 0.2 - 0.05 * 0.175 = 1.091
    me = (SOFT["px"], 0.0, SOFT["vx"], 0.0, 0.0, SOFT["vx"], True, SOFT["bx"], 0.0, SOFT["wx"], 0.0, 1.0)
    wt = [(SOFT["stamina"], 1.0, 1.0)]
    nbx = SOFT["bx"] + SOFT["wx"]
    mnx = SOFT["px"] + SOFT["vx"]
    cand = _one_dash_adjust(me, wt, 0.0, 0.6, -0.6, nbx, 0.0, mnx, 0.0, 1.3)
    assert cand is not None and cand[7] == pytest.approx(0.556, abs=1e-3) and cand[7] < 1.091
    back = _one_dash_adjust(me, wt, -180.0, 100 * 0.006 * 0.6, -100 * 0.006 * 0.6, nbx, 0.0, mnx, 0.0, 1.3)
    assert back is not None and back[3] < 0 and back[8] == 7824.0 - 200.0 + 45.0  # a back dash costs double


# --- noise parameters -------------------------------------------------------------------------------------------
def test_player_rand_shrinks_the_long_step_turn() -> None:
    # the ball 176 degrees off the body, far from the goal (no back-dash chase): with the max moment 162 one turn
    # leaves 14 degrees (> 12.5), with 180 (player_rand 0, --deterministic) one turn suffices
    v = view(px=-50.0, bx=-25.0, by=3.0, body=-177.2)
    noisy = build_intercept_table(v).self_cache
    exact = build_intercept_table(v, player_rand=0.0, ball_rand=0.0).self_cache
    assert [(e.turn_cycle, e.dash_cycle) for e in noisy] == [(2, 25)]
    assert [(e.turn_cycle, e.dash_cycle) for e in exact] == [(1, 25)]


# --- invariants -------------------------------------------------------------------------------------------------
def _random_view(rng: random.Random) -> GoalieView:
    px, py = rng.uniform(-52.5, -30.0), rng.uniform(-15.0, 15.0)
    d, a = rng.choice([rng.uniform(0.5, 4.0), rng.uniform(0.0, 15.0)]), math.radians(rng.uniform(-180, 180))
    bx, by = px + d * math.cos(a), py + d * math.sin(a)
    s, w = rng.choice([0.0, rng.uniform(0.0, 2.8)]), math.radians(rng.uniform(-180, 180))
    kick_opp = rng.random() < 0.3
    wx, wy = (0.0, 0.0) if kick_opp else (s * math.cos(w), s * math.sin(w))
    return view(
        px=px,
        py=py,
        vx=rng.uniform(-0.3, 0.3),
        vy=rng.uniform(-0.3, 0.3),
        body=rng.uniform(-180, 180),
        stamina=rng.choice([8000.0, rng.uniform(2300.0, 8000.0)]),
        bx=bx,
        by=by,
        wx=wx,
        wy=wy,
        true_wx=wx,
        true_wy=wy,
        has_opp=True,
        ox=bx + rng.uniform(-4, 4),
        oy=by + rng.uniform(-4, 4),
        obody=rng.uniform(-180, 180),
        kick_opp=kick_opp,
        self_kickable=math.hypot(bx - px, by - py) <= 1.03,
    )


def test_sorted_cache_self_min_and_lazy_mode_agree() -> None:
    rng = random.Random(5)
    for _ in range(120):
        v = _random_view(rng)
        t = build_intercept_table(v)
        keys = [(reach(e), e.turn_cycle) for e in t.self_cache]
        assert keys == sorted(keys)
        assert len(t.ball_cache) <= 31
        if not v.self_kickable:
            assert t.self_cache  # Final guarantees a candidate
            first = t.self_cache[0]
            assert t.self_min == (reach(first) if first.mode == NORMAL else 1000)
            # one candidate per reach cycle, except a final candidate that may tie with the last short step
            reaches = [reach(e) for e in t.self_cache]
            assert len(set(reaches)) >= len(reaches) - 1
        lazy = build_intercept_table(v, full=False)
        assert (lazy.self_min, lazy.opp_min, lazy.ball_cache) == (t.self_min, t.opp_min, t.ball_cache)
        assert lazy.self_cache[:1] == t.self_cache[:1]
        assert 0 <= t.opp_min <= 1000 and (t.opp_min == 0) >= v.kick_opp


# --- golden tables from librcsc ---------------------------------------------------------------------------------
FIELDS = (
    "px",
    "py",
    "vx",
    "vy",
    "body",
    "stamina",
    "effort",
    "recovery",
    "bx",
    "by",
    "wx",
    "wy",
    "has_opp",
    "ox",
    "oy",
    "ux",
    "uy",
    "obody",
    "opp_tackle_count",
    "kick_opp",
    "self_kickable",
    "lk_not_ours",
)

# (player_rand, ball_rand, view fields, self_min, opp_min, ball cache size, self cache size,
#  the first entries as (mode, turns, dashes, power, dir, x, y, ball_dist, stamina))
# fmt: off
LIBRCSC = [
    (0.1, 0.05,
     (-41.923, 6.84793, 0.256556, -0.162615, 11.379, 8000.0, 0.875689, 0.734267, -32.1169, 6.74327, 0.0, -0.0,
      True, -28.4422, 11.5353, 0.270689, 0.128671, -12.2827, 0, False, False, True),
     9, 7, 6, 1, [(0, 0, 9, 100.0, 0.0, -32.1169, 6.74327, 0.0, 7397.37813)]),
    (0.1, 0.05,
     (-40.6354, -0.143421, -0.0, -0.0, -117.447, 8000.0, 1.0, 0.953336, -37.5778, 1.50908, 0.301236, 1.60444,
      False, -37.6973, 4.49836, -0.33493, -0.413212, 42.4033, 3, False, False, True),
     27, 1000, 31, 3,
     [(0, 1, 26, 100.0, 0.0, -30.5880155, 21.8904573, 3.20232836, 6515.40312),
      (0, 1, 27, 100.0, 0.0, -30.5219146, 22.1976773, 3.2086881, 6558.30324),
      (0, 1, 28, 100.0, 0.0, -30.4598673, 22.4863231, 3.21466626, 6601.20336)]),
    (0.1, 0.05,
     (-46.8205, -10.1582, -0.0, 0.0, -141.1, 5957.82, 1.0, 0.771704, -45.0901, -12.1606, 0.0, 0.0, True,
      -49.0631, -11.1788, 0.198326, -0.0659628, -122.623, 0, True, False, False),
     4, 0, 6, 3,
     [(0, 1, 3, 100.0, 0.0, -45.266957, -11.955943, 0.270486335, 5796.72672),
      (0, 1, 4, 100.0, 0.0, -45.0901, -12.1606, 0.0, 5843.82407),
      (0, 1, 5, 100.0, 0.0, -45.0901, -12.1606, 0.0, 5666.18008)]),
    (0.1, 0.05,
     (-37.8492, -7.11422, 0.209659, -0.473687, 145.184, 2638.25, 1.0, 1.0, -34.9422, -7.01885, 0.0, 0.0, True,
      -38.9285, -5.89635, -0.309195, 0.267251, 164.36, 3, False, False, True),
     5, 6, 6, 2,
     [(0, 1, 4, -100.0, 0.0, -35.6767382, -7.39514128, 0.825312993, 2446.0),
      (0, 2, 4, 100.0, 0.0, -34.9422, -7.01885, 0.0, 2508.25)]),
    (0.1, 0.05,
     (-49.5042, -4.10107, -0.0, 0.0, 152.817, 2172.65, 1.0, 1.0, -49.4209, -3.16778, 0.104297, 0.464973, True,
      -45.9391, 1.52123, 0.340076, 0.139994, 114.149, 0, False, True, True),
     0, 7, 1, 0, []),
    (0.1, 0.05,
     (-37.1282, -7.50701, 0.299655, -0.161317, 21.1365, 2578.13, 1.0, 1.0, -37.109, -6.25285, 0.0, 0.0, True,
      -41.7338, -4.77569, -0.180762, -0.106375, -150.973, 0, False, False, True),
     1, 6, 6, 6,
     [(0, 0, 1, 100.0, 45.0, -36.6586302, -7.28423202, 1.12542518, 2523.13),
      (0, 0, 2, 100.0, 90.0, -36.9163835, -7.19560477, 0.96223058, 2468.13),
      (0, 1, 2, 100.0, 0.0, -36.6045541, -6.319761, 0.508864148, 2513.13),
      (0, 1, 3, 100.0, 0.0, -36.5831621, -6.2733821, 0.526238553, 2591.37448)]),
    (0.1, 0.05,
     (-42.8699, 10.3624, -0.0, -0.0, -18.1141, 8000.0, 1.0, 1.0, -42.8537, 11.6581, -0.17251, -1.40069, True,
      -42.3725, 13.619, -0.107954, -0.350714, 128.262, 0, False, False, False),
     1, 18, 31, 12,
     [(0, 1, 0, 0.0, 0.0, -42.8699, 10.3624, 0.188296883, 8000.0),
      (0, 1, 1, 100.0, 0.0, -43.0010587, 9.77691099, 0.856873044, 7945.0),
      (0, 1, 11, 100.0, 0.0, -44.265113, 0.123662952, 0.706586179, 7395.0),
      (0, 1, 12, 100.0, 0.0, -44.3918293, -0.868291394, 0.378203964, 7340.0)]),
    (0.1, 0.05,
     (-50.2903, -2.58545, 0.0, 0.0, 141.559, 6794.86, 0.647519, 1.0, -47.4945, -4.02527, 0.157274, -0.496925,
      True, -48.1466, -4.25226, 0.264634, -0.382162, 103.36, 0, False, False, True),
     11, 0, 31, 10,
     [(0, 1, 10, -100.0, 0.0, -46.6405808, -7.51910671, 0.740163263, 5289.86),
      (0, 1, 11, -100.0, 0.0, -46.3154623, -8.09582959, 0.332805617, 5134.86),
      (0, 1, 12, -100.0, 0.0, -46.045915, -8.60223833, 7.94410929e-15, 4979.86),
      (0, 1, 13, -100.0, 0.0, -45.9755561, -8.82454523, 7.10542736e-15, 4824.86)]),
    (0.1, 0.05,
     (-46.081, 8.34081, -0.000874179, 0.240994, 139.214, 8000.0, 1.0, 1.0, -47.5272, 9.67715, 0.0, 0.0, True,
      -50.4634, 6.77232, 0.263278, -0.34488, 122.102, 0, True, False, True),
     1, 0, 6, 6,
     [(0, 0, 1, 100.0, 0.0, -46.536167, 8.97374537, 1.21528782, 7945.0),
      (0, 0, 2, 100.0, 0.0, -47.1725266, 9.61886089, 0.359431265, 7890.0),
      (0, 0, 3, 100.0, 0.0, -47.3856731, 9.84119151, 0.216655206, 7941.50892),
      (0, 0, 4, 100.0, 0.0, -47.3780685, 9.85000593, 0.228296722, 8000.0)]),
    (0.1, 0.05,
     (-47.9463, 8.00427, 0.382975, 0.220289, 8.60369, 2692.04, 1.0, 0.973576, -41.5925, 3.44225, -0.207788,
      -0.466674, True, -38.3585, 0.25004, -0.465483, 0.32379, -105.513, 0, False, False, True),
     1000, 4, 31, 10,
     [(1, 2, 15, 100.0, 0.0, -44.1918272, -0.621103929, 1.05609877, 2442.91092),
      (1, 2, 16, 100.0, 0.0, -44.1647413, -1.04465754, 0.777326012, 2442.82092),
      (1, 2, 17, 100.0, 0.0, -44.1386391, -1.46409159, 0.494970001, 2442.73092),
      (1, 2, 18, 100.0, 0.0, -44.1132081, -1.87949155, 0.209216975, 2442.64092)]),
    (0.1, 0.05,
     (-47.9303, -6.96762, -0.0, 0.0, -25.8583, 2681.33, 1.0, 1.0, -47.39, -9.00185, -0.950283, 1.40634, True,
      -49.058, -6.40977, 0.00492609, 0.159796, 169.822, 9, False, False, True),
     1, 18, 18, 3,
     [(0, 1, 0, 0.0, 0.0, -47.9303, -6.96762, 0.749887933, 2726.33),
      (0, 0, 2, -100.0, 0.0, -49.0245395, -6.43726964, 0.265497555, 2446.0),
      (0, 1, 26, 100.0, 0.0, -63.1955048, 14.3889858, 0.0, 1275.54)]),
    (0.0, 0.0,
     (-39.9802, 8.38046, -0.509989, -0.501789, 97.9612, 6425.78, 1.0, 0.937255, -31.9784, 10.8959, 0.0, 0.0,
      True, -28.8338, 10.1232, 0.0488694, -0.335955, 15.5685, 1, True, False, True),
     12, 0, 6, 1, [(0, 2, 10, 100.0, 0.0, -31.9784, 10.8959, 0.0, 5931.8977)]),
    (0.0, 0.0,
     (-45.8217, -4.39884, -0.0298837, 0.716228, -28.3546, 2364.74, 0.668542, 1.0, -48.1388, -6.13866,
      -0.0318456, -0.0644636, True, -44.3689, -7.30562, -0.176906, -0.217435, 152.363, 0, False, False,
      True),
     1000, 4, 31, 10,
     [(1, 2, 13, 54.56, 0.0, -47.9452766, -6.07609979, 0.878632262, 2443.74),
      (1, 2, 14, 54.56, 0.0, -48.096593, -6.29247601, 0.642654581, 2443.65),
      (1, 2, 15, 54.56, 0.0, -48.2469643, -6.50796944, 0.406264317, 2443.56),
      (1, 2, 16, 54.56, 0.0, -48.3966743, -6.72291184, 0.16912668, 2443.47)]),
    (0.0, 0.0,
     (-34.4836, 14.7122, -0.575783, 0.487519, -62.7156, 8000.0, 0.614425, 1.0, -35.3327, 13.5839, 0.0, 0.0,
      False, -32.1818, 15.1152, -0.128059, -0.133354, -101.639, 0, True, False, True),
     2, 0, 6, 5,
     [(0, 0, 2, 100.0, -90.0, -35.3014295, 14.9671182, 1.38357158, 7890.0),
      (0, 0, 3, 100.0, 0.0, -34.7032527, 14.157148, 0.851361948, 7835.0),
      (0, 0, 4, 100.0, 0.0, -34.6183734, 13.9523452, 0.803750151, 7872.30639),
      (0, 0, 5, 100.0, 0.0, -34.6249314, 13.9489626, 0.796371203, 7932.8683)]),
    (0.0, 0.0,
     (-35.7767, 1.83203, -0.0, -0.0, 82.2209, 3090.67, 0.675803, 1.0, -33.723, 0.0688295, 2.63517, 0.340742,
      True, -34.137, -2.38727, -0.12805, 0.112874, 58.0369, 9, False, False, True),
     47, 39, 31, 1, [(0, 1, 46, 100.0, 0.0, 10.1062509, 5.73619313, 0.0, 552.12)]),
    (0.0, 0.0,
     (-41.2552, 7.67681, -0.0, -0.0, -0.555199, 2724.26, 0.922515, 1.0, -41.3544, 5.79907, 1.53825, 1.71902,
      True, -43.6892, 1.07771, 0.230575, -0.348193, 157.993, 9, False, False, True),
     1, 39, 31, 2,
     [(0, 0, 1, 100.0, 0.0, -40.701717, 7.67144655, 0.898747528, 2669.26),
      (0, 1, 37, 100.0, 0.0, -15.7695819, 34.3905305, 0.0, 686.74)]),
    (0.0, 0.0,
     (-41.5692, -10.0643, 0.0, 0.0, -74.5444, 8000.0, 1.0, 1.0, -47.5773, -8.71364, -0.147546, 0.5971, True,
      -44.3716, -10.9139, -0.33815, 0.0367881, 155.724, 0, False, False, True),
     10, 8, 31, 10,
     [(0, 1, 9, -100.0, 0.0, -47.9756023, -4.73463144, 0.957772, 6605.0),
      (0, 1, 10, -100.0, 0.0, -48.6201237, -3.94900022, 0.226670605, 6450.0),
      (0, 1, 11, -100.0, 0.0, -48.8660644, -3.49817367, 7.75568463e-15, 6295.0),
      (0, 1, 12, -100.0, 0.0, -48.9362845, -3.21400165, 7.94410929e-15, 6340.0)]),
    (0.0, 0.0,
     (-39.663, -11.4403, -0.0, 0.0, 127.473, 8000.0, 1.0, 0.712444, -39.6542, -11.5311, 2.56571, 0.634457,
      False, -43.5286, -8.7286, -0.225642, -0.334577, -108.226, 0, False, True, True),
     0, 1000, 1, 0, []),
    (0.0, 0.0,
     (-40.3547, -9.52212, -0.146791, 0.742119, -27.3396, 2161.09, 0.946038, 0.766996, -41.1438, -8.17344, 0.0,
      0.0, True, -37.2741, -11.3155, -0.366393, 0.417565, -173.698, 0, False, False, True),
     1, 5, 6, 6,
     [(0, 1, 0, 0.0, 0.0, -40.501491, -8.780001, 0.883446149, 2195.51482),
      (0, 0, 2, 0.0, 0.0, -40.5602074, -8.4831534, 0.660683519, 2229.84964),
      (0, 0, 3, 0.0, 0.0, -40.583694, -8.36441436, 0.591768521, 2264.09446),
      (0, 0, 4, 0.0, 0.0, -40.5930886, -8.31691874, 0.569095083, 2298.24928)]),
    (0.0, 0.0,
     (-38.6623, -7.26518, -0.0, 0.0, -42.8057, 7918.06, 0.897346, 1.0, -37.511, -7.91298, -1.23474, 1.83493,
      True, -36.5446, -7.68811, -0.291362, 0.112878, -46.2204, 0, False, False, True),
     1, 0, 31, 2,
     [(0, 0, 1, 100.0, 180.0, -38.8993056, -7.0456666, 0.979726639, 7863.06),
      (0, 1, 36, 100.0, 0.0, -58.0477127, 22.6063441, 0.0, 5983.06)]),
    (0.0, 0.0,
     (-34.1815, 7.27098, 0.0, -0.0, 107.983, 8000.0, 1.0, 0.824811, -34.5919, 5.98705, -0.0, -0.0, True,
      -31.1881, 6.2128, -0.441069, -0.196577, -94.1453, 0, False, False, True),
     1, 4, 6, 6,
     [(0, 0, 1, -100.0, 0.0, -33.9962591, 6.7002911, 0.929247506, 7837.1165),
      (0, 0, 2, -100.0, 0.0, -33.8435889, 6.22994558, 0.786745073, 7789.39869),
      (0, 0, 3, -100.0, 0.0, -33.8435889, 6.22994558, 0.786745073, 7873.6107),
      (0, 0, 4, -100.0, 0.0, -33.8435889, 6.22994558, 0.786745073, 7922.80297)]),
    (0.0, 0.0,
     (-35.362, 2.60278, -0.722918, 0.53483, -128.376, 4726.98, 0.931069, 1.0, -35.9986, 3.62258, 0.0, 0.0,
      True, -33.1832, -0.315717, 0.171671, -0.304584, 157.991, 0, True, False, False),
     1, 0, 6, 6,
     [(0, 1, 0, 0.0, 0.0, -36.084918, 3.13761, 0.492591817, 4771.98),
      (0, 0, 2, 0.0, 0.0, -36.3740852, 3.351542, 0.463088256, 4816.98),
      (0, 0, 3, 0.0, 0.0, -36.4897521, 3.4371148, 0.525002577, 4861.98),
      (0, 0, 4, 0.0, 0.0, -36.5360188, 3.47134392, 0.55829325, 4906.98)]),
    # cases that each pin one rule (states that tell a mutated rule apart; all their entries kept):
    # noise_rate
    (0.1, 0.05,
     (-38.814, 10.0447, -0.0, 0.0, 21.3166, 3074.01, 0.632386, 1.0, -42.3954, 9.55709, 0.0247779, -0.665897,
      True, -40.9492, 7.8279, -0.155128, -0.383312, 11.2208, 0, False, False, False),
     12, 2, 31, 10,
     [(0, 1, 11, 100.0, 0.0, -41.891164, 4.27989186, 0.611192718, 2514.01),
      (0, 1, 12, 100.0, 0.0, -42.052168, 3.65088651, 0.254558986, 2459.01),
      (1, 1, 13, 100.0, 0.0, -42.138778, 3.16174455, 0.0398160322, 2444.91),
      (1, 1, 14, 100.0, 0.0, -42.1756144, 2.78117985, 0.0712790471, 2444.82),
      (1, 1, 15, 100.0, 0.0, -42.1358822, 2.58264343, 8.8817842e-16, 2444.73),
      (1, 1, 16, 100.0, 0.0, -42.1266753, 2.33521322, 1.77635684e-15, 2444.64),
      (1, 1, 17, 100.0, 0.0, -42.1180209, 2.10262883, 8.8817842e-16, 2444.55),
      (1, 1, 18, 100.0, 0.0, -42.1098858, 1.8839995, 8.8817842e-16, 2444.46),
      (1, 1, 19, 100.0, 0.0, -42.1022387, 1.67848793, 1.99840144e-15, 2488.92),
      (1, 1, 20, 100.0, 0.0, -42.0950505, 1.48530705, 7.10889596e-15, 2488.74)]),
    # nodash noise
    (0.1, 0.05,
     (-51.0511, 2.0663, -0.0, -0.0, -49.107, 2487.04, 0.877928, 1.0, -49.8151, 2.44665, -1.37698, 0.713882,
      True, -54.0574, 2.52463, 0.452222, -0.266814, -20.5902, 9, False, False, True),
     1, 8, 8, 2,
     [(0, 0, 1, 86.04, 180.0, -51.2291205, 2.2718632, 0.889440405, 2446.0),
      (0, 1, 25, 100.0, 0.0, -72.717608, 14.3202344, 0.0, 1130.04)]),
    # opp margin 12
    (0.1, 0.05,
     (-34.08, 0.661591, -0.267158, 0.639501, -45.3688, 8000.0, 1.0, 1.0, -23.4928, 25.8369, 0.0, 0.0, True,
      -25.2678, 21.6004, -0.114276, -0.142263, -101.573, 1, False, False, True),
     29, 5, 6, 1, [(0, 2, 27, 100.0, 0.0, -23.4928, 25.8369, 0.0, 6515.0)]),
    # back chase 205
    (0.1, 0.05,
     (-51.8233, 11.5179, 0.0, 0.0, -51.9432, 5370.75, 0.781104, 1.0, -45.0787, 16.9064, -1.22056, -0.0229821,
      True, -47.8613, 19.7921, 0.0474846, -0.193709, -127.618, 0, False, False, True),
     7, 3, 17, 10,
     [(0, 1, 6, -100.0, 0.0, -52.1487857, 15.7267147, 1.0481602, 4485.75),
      (0, 1, 7, -100.0, 0.0, -52.9402136, 16.4030329, 0.362948299, 4330.75),
      (0, 1, 8, -100.0, 0.0, -53.7651244, 16.7428421, 7.10542736e-15, 4175.75),
      (0, 0, 10, -100.0, 0.0, -55.3566844, 16.0311963, 1.13307781, 4020.75),
      (0, 0, 11, -100.0, 0.0, -55.6004934, 16.3426207, 0.607800898, 4065.75),
      (0, 0, 12, -100.0, 0.0, -55.8296739, 16.6353597, 0.114040597, 3910.75),
      (0, 0, 13, -100.0, 0.0, -56.0451035, 16.9105343, 0.350094086, 3955.75),
      (0, 0, 14, -100.0, 0.0, -56.2476074, 17.1691985, 0.786380688, 3800.75),
      (0, 1, 14, 100.0, 0.0, -56.4566488, 17.4019252, 1.17535823, 4945.75),
      (0, 1, 15, 100.0, 0.0, -57.2060846, 17.2790475, 0.898420441, 4990.75)]),
    # short min turn
    (0.1, 0.05,
     (-31.56, 14.8313, -0.794433, 0.196528, -98.918, 8000.0, 1.0, 0.852028, -30.3275, 12.6288, 0.0, 0.0, True,
      -31.5336, 15.1448, 0.325757, -0.317121, 32.0322, 1, False, False, True),
     6, 3, 6, 1, [(0, 2, 4, 100.0, 0.0, -30.3275, 12.6288, 0.0, 7753.36504)]),
    # omni 91
    (0.1, 0.05,
     (-43.6253, -13.4809, -0.0, -0.0, -56.5611, 8000.0, 0.696844, 1.0, -44.0201, -15.5498, -0.0, -0.0, True,
      -48.6751, -20.0031, 0.454799, -0.13939, 145.05, 3, False, False, True),
     2, 7, 6, 5,
     [(0, 0, 2, 100.0, -135.0, -44.1197875, -13.3797461, 2.1723424, 7890.0),
      (0, 1, 2, 100.0, 0.0, -43.8172153, -14.4866079, 1.08237688, 7890.0),
      (0, 1, 3, 100.0, 0.0, -43.9439283, -15.1506319, 0.406370896, 7835.0),
      (0, 1, 4, 100.0, 0.0, -44.0201, -15.5498, 7.32410688e-15, 7849.2453),
      (0, 1, 5, 100.0, 0.0, -44.0201, -15.5498, 0.0, 7725.0)]),
    # abs angle quirk
    (0.1, 0.05,
     (-40.0284, -9.21949, -0.187925, 0.00542194, -178.783, 8000.0, 1.0, 1.0, -40.7362, -8.14384, 0.0, 0.0,
      True, -38.7241, -4.52625, 0.13808, 0.491873, 60.0227, 0, True, False, True),
     1, 0, 6, 6,
     [(0, 0, 1, 100.0, -90.0, -40.2214224, -8.9741222, 0.976915826, 7945.0),
      (0, 0, 2, 50.2285846, 0.0, -40.7133199, -9.22086047, 1.07726347, 8000.0),
      (0, 0, 3, 41.8672349, 0.0, -40.7133519, -9.21935488, 1.07575754, 8000.0),
      (0, 0, 4, 38.9840108, 0.0, -40.7133647, -9.21875264, 1.07515517, 8000.0),
      (0, 0, 5, 37.8933635, 0.0, -40.7133698, -9.21851175, 1.07491422, 8000.0),
      (0, 1, 5, 100.0, 0.0, -40.7362, -8.14384, 0.0, 7725.0)]),
]
# fmt: on


@pytest.mark.parametrize("case", LIBRCSC, ids=[f"librcsc{i}" for i in range(len(LIBRCSC))])
def test_matches_librcsc(case: tuple) -> None:
    player_rand, ball_rand, values, self_min, opp_min, n_ball, n_self, entries = case
    kw = dict(zip(FIELDS, values, strict=True))
    v = view(**kw, true_wx=kw["wx"], true_wy=kw["wy"])
    t: InterceptTable = build_intercept_table(v, player_rand, ball_rand)
    assert (t.self_min, t.opp_min, len(t.ball_cache), len(t.self_cache)) == (
        self_min,
        opp_min,
        n_ball,
        n_self,
    )
    for got, want in zip(t.self_cache, entries, strict=False):
        assert (got.mode, got.turn_cycle, got.dash_cycle) == want[:3]
        numbers = (got.dash_power, got.dash_dir, got.self_x, got.self_y, got.ball_dist, got.stamina)
        assert numbers == pytest.approx(want[3:], rel=1e-7, abs=1e-7)
