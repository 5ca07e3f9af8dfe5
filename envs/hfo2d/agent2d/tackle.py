"""agent2d's tackle for the goalie: Bhv_BasicTackle (version-14 path) and TackleGenerator, client side, in GF.

Sources (facts and numbers, no code): HFO b8b2a1d ``src/bhv_basic_tackle.cpp``, ``src/chain_action/
tackle_generator.cpp``, ``src/chain_action/field_analyzer.{h,cpp}``; librcsc d222758 ``rcsc/player/
self_object.cpp`` (updateBallInfo: tackle and foul probabilities; updateKickableState: the foul probability is
zeroed unless the opponent reach cycle is 0), ``rcsc/player/action_effector.cpp`` (setTackle),
``rcsc/common/server_param.h`` (ballMoveStep), ``rcsc/math_util.h`` (calc_length_geom_series),
``rcsc/geom/{line_2d,ray_2d,segment_2d,rect_2d}`` (the intersection rules used below). Spec §3.7.

Plain float maths throughout: points are (x, y) tuples, angles degrees.
"""

from __future__ import annotations

import math

from hfo2d.agent2d import common as _common
from hfo2d.agent2d.common import (
    GOAL_HALF_WIDTH,
    OWN_GOAL,
    PENALTY_AREA_HALF_WIDTH,
    PENALTY_AREA_X,
    PITCH_HALF_LENGTH,
    PITCH_HALF_WIDTH,
    Effector,
    GoalieView,
    InterceptTable,
    angle_of,
    ball_at,
    cycles_to_reach,
    eff_turn,
    norm_deg,
    register_binder,
    rotate,
)
from hfo2d.physics import ServerParams

# TackleGenerator: ANGLE_DIVS 40 candidate directions over [min_moment, max_moment)
ANGLE_DIVS = 40

_EPS = 1.0e-10  # librcsc math_util.h EPS
_LINE_EPS = 1.0e-10  # librcsc Line2D::EPSILON
_SEGMENT_CALC_ERROR = 1.0e-9  # librcsc Segment2D::CALC_ERROR

Point = tuple[float, float]
Line = tuple[float, float, float]  # a x + b y + c = 0 (librcsc Line2D)

# the pitch as librcsc's Rect2D::from_center(0, 0, 105, 68): left, top, right, bottom
_PITCH = (-PITCH_HALF_LENGTH, -PITCH_HALF_WIDTH, PITCH_HALF_LENGTH, PITCH_HALF_WIDTH)


# --- librcsc geometry ------------------------------------------------------------------------------------------
def _line_points(x1: float, y1: float, x2: float, y2: float) -> Line:
    """Line2D(p1, p2)."""
    a = -(y2 - y1)
    b = x2 - x1
    return a, b, -a * x1 - b * y1


def _line_dir(x: float, y: float, deg: float) -> Line:
    """Line2D(origin, direction)."""
    r = math.radians(deg)
    a = -math.sin(r)
    b = math.cos(r)
    return a, b, -a * x - b * y


def _intersect(l1: Line, l2: Line) -> Point | None:
    """Line2D::intersection; None when (nearly) parallel."""
    a1, b1, c1 = l1
    a2, b2, c2 = l2
    tmp = a1 * b2 - b1 * a2
    if abs(tmp) < _LINE_EPS:
        return None
    return (b1 * c2 - b2 * c1) / tmp, (a2 * c1 - a1 * c2) / tmp


def _in_right_dir(ox: float, oy: float, deg: float, p: Point, thr: float) -> bool:
    """Ray2D::inRightDir."""
    return abs(norm_deg(angle_of(p[0] - ox, p[1] - oy) - deg)) < thr


def _segment_contains(x1: float, y1: float, x2: float, y2: float, p: Point) -> bool:
    """Segment2D::contains (with its 1e-9 calculation error)."""
    return (p[0] - x1) * (p[0] - x2) <= _SEGMENT_CALC_ERROR and (p[1] - y1) * (
        p[1] - y2
    ) <= _SEGMENT_CALC_ERROR


def _segment_line_intersection(x1: float, y1: float, x2: float, y2: float, line: Line) -> Point | None:
    """Segment2D::intersection(Line2D)."""
    p = _intersect(_line_points(x1, y1, x2, y2), line)
    if p is None or not _segment_contains(x1, y1, x2, y2, p):
        return None
    return p


def _ray_line_intersection(ox: float, oy: float, deg: float, line: Line) -> Point | None:
    """Ray2D::intersection(Line2D) (direction threshold 10 degrees)."""
    p = _intersect(_line_dir(ox, oy, deg), line)
    if p is None or not _in_right_dir(ox, oy, deg, p, 10.0):
        return None
    return p


def _rect_line(line: Line) -> list[Point]:
    """Rect2D::intersection(Line2D) on the pitch: left, right, top, bottom edges, at most two points."""
    left, top, right, bottom = _PITCH
    found: list[Point] = []
    for edge, vertical in (
        (_line_points(left, top, left, bottom), True),
        (_line_points(right, top, right, bottom), True),
        (_line_points(left, top, right, top), False),
        (_line_points(left, bottom, right, bottom), False),
    ):
        if len(found) >= 2:
            break
        p = _intersect(edge, line)
        if p is None:
            continue
        if (top <= p[1] <= bottom) if vertical else (left <= p[0] <= right):
            found.append(p)
    if (
        len(found) == 2
        and abs(found[0][0] - found[1][0]) < 1.0e-5
        and abs(found[0][1] - found[1][1]) < 1.0e-5
    ):
        found.pop()
    return found


def _filter_two(found: list[Point], keep: list[bool]) -> tuple[int, Point | None]:
    """Rect2D's two-solution filter: the second is dropped if it fails, the first replaced by the second."""
    n = len(found)
    sol1 = found[0] if n > 0 else None
    sol2 = found[1] if n > 1 else None
    if n > 1 and not keep[1]:
        n -= 1
    if n > 0 and not keep[0]:
        sol1 = sol2
        n -= 1
    return n, sol1


def _rect_segment(x1: float, y1: float, x2: float, y2: float) -> tuple[int, Point | None]:
    """Rect2D::intersection(Segment2D) on the pitch: (count, first point)."""
    found = _rect_line(_line_points(x1, y1, x2, y2))
    return _filter_two(found, [_segment_contains(x1, y1, x2, y2, p) for p in found])


def _rect_ray(ox: float, oy: float, deg: float) -> tuple[int, Point | None]:
    """Rect2D::intersection(Ray2D) on the pitch (direction threshold 1 degree): (count, first point)."""
    found = _rect_line(_line_dir(ox, oy, deg))
    return _filter_two(found, [_in_right_dir(ox, oy, deg, p, 1.0) for p in found])


def _goal_line(x: float) -> Line:
    """The goal line at ``x`` as agent2d builds it: through (x, 10) and (x, -10)."""
    return _line_points(x, 10.0, x, -10.0)


def _length_geom_series(first: float, total: float, r: float) -> float:
    """librcsc calc_length_geom_series: the (real) number of terms of ratio r summing to ``total``; -1 if never."""
    if first <= _EPS or total < 0.0 or r <= _EPS:
        return -1.0
    if total <= _EPS:
        return 0.0
    tmp = 1.0 + total * (r - 1.0) / first
    if tmp <= _EPS:
        return -1.0
    return math.log(tmp) / math.log(r)


def ball_move_step(speed: float, dist: float) -> int:
    """librcsc ServerParam::ballMoveStep: int(ceil(steps) + 1e-10), truncated (so -1 becomes 0)."""
    return int(math.ceil(_length_geom_series(speed, dist, BALL_DECAY)) + 1.0e-10)


# A ball farther than NO_TACKLE_DIST (set by _bind) from the goalie lies outside the tackle rectangle: the rotated
# offset (r.x, r.y) has |r| > 2.5 > hypot(2.0, 1.25), so |r.x| > 2.0 or |r.y| > 1.25, a failure term >= 1 and both
# probabilities 0 (the rotation's rounding is far below the margin)
_NO_TACKLE_DIST_DEFAULT = 2.5


# --- probabilities (librcsc SelfObject::updateBallInfo / updateKickableState) ------------------------------------
def tackle_probabilities(view: GoalieView, opp_min: int) -> tuple[float, float]:
    """(tackle_prob, foul_prob) as librcsc's world model has them.

    With r = (B - P) rotated by -body: fail = (|r.x| / 2.0)^e + (|r.y| / 1.25)^e, e = 6 (tackle) or 10 (foul),
    prob = 1 - fail when fail < 1, else 0; a ball behind (r.x <= 0, back distance 0) gives 0. The foul probability
    is then zeroed unless ``opp_min`` (the intercept table's opponent reach cycle) is 0.
    """
    rx, ry = rotate(view.bx - view.px, view.by - view.py, -view.body)
    tackle_dist = TACKLE_DIST if rx > 0.0 else TACKLE_BACK_DIST
    tackle_fail = 1.0
    foul_fail = 1.0
    if tackle_dist > 1.0e-5:
        ax = abs(rx) / tackle_dist
        ay = abs(ry) / TACKLE_WIDTH
        tackle_fail = ax**TACKLE_EXPONENT + ay**TACKLE_EXPONENT
        foul_fail = ax**FOUL_EXPONENT + ay**FOUL_EXPONENT
    tackle_prob = 1.0 - tackle_fail if tackle_fail < 1.0 else 0.0
    foul_prob = 1.0 - foul_fail if foul_fail < 1.0 else 0.0
    if opp_min > 0:
        foul_prob = 0.0
    return tackle_prob, foul_prob


# --- TackleGenerator -------------------------------------------------------------------------------------------
def _turn_cycles(body: float, speed: float, target_dist: float, target_angle: float) -> int:
    """FieldAnalyzer::predict_player_turn_cycle for a type-0 player, dist_thr = kickable area, back dash allowed
    (min_dash_power -100 < -max_dash_power + 1)."""
    angle_diff = abs(norm_deg(target_angle - body))
    if target_dist < 5.0 and angle_diff > 90.0:
        angle_diff = abs(angle_diff - 180.0)  # a back dash
    turn_margin = 180.0
    if target_dist > KICKABLE_AREA:
        ratio = KICKABLE_AREA / target_dist
        asin_deg = 90.0 if ratio >= 1.0 else math.degrees(math.asin(ratio))
        turn_margin = max(15.0, asin_deg)
    n_turn = 0
    while angle_diff > turn_margin:
        angle_diff -= eff_turn(speed)
        speed *= PLAYER_DECAY_OPP
        n_turn += 1
    return n_turn


def _opponent_reach_step(
    opp: tuple[float, float, float, float, float, int],
    bx: float,
    by: float,
    vx: float,
    vy: float,
    move_angle: float,
    max_cycle: int,
) -> int:
    """TackleGenerator::predictOpponentReachStep for one opponent ``opp`` = (x, y, vx, vy, body, remaining
    tackle freeze) (fullstate: pos/body counts 0)."""
    ox, oy, ux, uy, obody, frozen = opp
    speed = math.hypot(ux, uy)
    # FieldAnalyzer::estimate_min_reach_cycle (speed max = realSpeedMax 1.0)
    tx, ty = rotate(ox - bx, oy - by, -move_angle)
    min_cycle = -1 if tx < -1.0 else max(1, int(math.floor(abs(ty) / REAL_SPEED_MAX)))
    if min_cycle < 0:
        min_cycle = 10
    for cycle in range(min_cycle, max_cycle):
        # ball_at / inertia_point with their factors looked up (same floats)
        f = _ball_factor(cycle)
        px = bx + vx * f
        py = by + vy * f
        if abs(px) > PITCH_HALF_LENGTH or abs(py) > PITCH_HALF_WIDTH:
            return 1000
        g = _player_factor(cycle)
        zx = ox + ux * g
        zy = oy + uy * g
        target_dist = math.hypot(px - zx, py - zy)
        if target_dist - KICKABLE_AREA < 0.001:
            return cycle
        dash_dist = target_dist
        if cycle > 1:
            dash_dist -= KICKABLE_AREA
            dash_dist -= 0.5  # agent2d's "special bonus"
        if dash_dist > REAL_SPEED_MAX * cycle:
            continue
        n_dash = cycles_to_reach(dash_dist)
        if n_dash > cycle:
            continue
        n_turn = _turn_cycles(obody, speed, target_dist, angle_of(px - zx, py - zy))
        n_step = n_dash if n_turn == 0 else n_turn + n_dash + 1  # +1: observation delay
        if frozen > 0:
            n_step += 5
        if n_step <= cycle:
            return cycle
    return 1000


_FACTOR_CACHE = 64


# --- server parameters the tackle uses (rcssserver serverparam.cpp defaults in the comments) --------------------
def _bind(sp: ServerParams) -> None:
    global BALL_DECAY, KICKABLE_AREA, REAL_SPEED_MAX, TACKLE_DIST, TACKLE_BACK_DIST, TACKLE_WIDTH
    global TACKLE_EXPONENT, FOUL_EXPONENT, TACKLE_POWER_RATE, MAX_TACKLE_POWER, MAX_BACK_TACKLE_POWER
    global BALL_SPEED_MAX, MIN_MOMENT, MAX_MOMENT, PLAYER_DECAY_OPP, NO_TACKLE_DIST, _NO_TACKLE_DIST2
    global _BALL_FACTORS, _PLAYER_FACTORS
    BALL_DECAY = _common.BALL_DECAY
    KICKABLE_AREA = _common.KICKABLE_AREA
    REAL_SPEED_MAX = _common.REAL_SPEED_MAX
    TACKLE_DIST = sp.tackle_dist  # 2
    TACKLE_BACK_DIST = sp.tackle_back_dist  # 0
    TACKLE_WIDTH = sp.tackle_width  # 1.25
    TACKLE_EXPONENT = sp.tackle_exponent  # 6
    FOUL_EXPONENT = sp.foul_exponent  # 10
    TACKLE_POWER_RATE = sp.tackle_power_rate  # 0.027
    MAX_TACKLE_POWER = sp.max_tackle_power  # 100
    MAX_BACK_TACKLE_POWER = sp.max_back_tackle_power  # 0
    BALL_SPEED_MAX = sp.ball_speed_max  # 3
    MIN_MOMENT = sp.min_moment  # -180
    MAX_MOMENT = sp.max_moment  # 180
    PLAYER_DECAY_OPP = sp.player_decay  # 0.4: the attacker is player type 0 too
    # beyond the tackle rectangle's far corner, with a margin (2.5 for the defaults)
    NO_TACKLE_DIST = max(
        _NO_TACKLE_DIST_DEFAULT, math.hypot(max(TACKLE_DIST, TACKLE_BACK_DIST), TACKLE_WIDTH) + 0.1
    )
    _NO_TACKLE_DIST2 = NO_TACKLE_DIST * NO_TACKLE_DIST
    # (1 - decay^n) / (1 - decay) exactly as common.ball_at / inertia_point compute them
    _BALL_FACTORS = [(1.0 - BALL_DECAY**n) / (1.0 - BALL_DECAY) for n in range(_FACTOR_CACHE)]
    _PLAYER_FACTORS = [(1.0 - PLAYER_DECAY_OPP**n) / (1.0 - PLAYER_DECAY_OPP) for n in range(_FACTOR_CACHE)]


register_binder(_bind)


def _ball_factor(n: int) -> float:
    return _BALL_FACTORS[n] if n < _FACTOR_CACHE else (1.0 - BALL_DECAY**n) / (1.0 - BALL_DECAY)


def _player_factor(n: int) -> float:
    return _PLAYER_FACTORS[n] if n < _FACTOR_CACHE else (1.0 - PLAYER_DECAY_OPP**n) / (1.0 - PLAYER_DECAY_OPP)


def opponents_reach_step(
    view: GoalieView, bx: float, by: float, vx: float, vy: float, move_angle: float
) -> int:
    """TackleGenerator::predictOpponentsReachStep: 1000 unless the attacker gets there before ``first``.

    ``first`` is 50, or, when the ball's final point leaves the pitch, the ball-move steps to where its ray
    leaves the pitch (if the ray meets the boundary exactly once).
    """
    first = 50
    ex = bx + vx / (1.0 - BALL_DECAY)
    ey = by + vy / (1.0 - BALL_DECAY)
    if abs(ex) > PITCH_HALF_LENGTH or abs(ey) > PITCH_HALF_WIDTH:
        n, sol = _rect_ray(bx, by, move_angle)
        if n == 1 and sol is not None:
            first = ball_move_step(math.hypot(vx, vy), math.hypot(bx - sol[0], by - sol[1]))
    min_step = first
    # every opponent (a field defender's view lists them, nearest to the ball first; the goalie's has one), each
    # searched only below the best step so far (predictOpponentsReachStep's max_step)
    opponents = getattr(view, "opponents", None)
    if opponents is None:
        opponents = (
            ((view.ox, view.oy, view.ux, view.uy, view.obody, view.opp_tackle_count),) if view.has_opp else ()
        )
    for opp in opponents:
        min_step = min(min_step, _opponent_reach_step(opp, bx, by, vx, vy, move_angle, min_step))
    return 1000 if min_step == first else min_step


def evaluate_tackle(view: GoalieView, vx: float, vy: float) -> float:
    """TackleGenerator::evaluate of one resulting ball velocity (vx, vy)."""
    bx, by = view.bx, view.by
    speed = math.hypot(vx, vy)
    move_angle = angle_of(vx, vy)
    ex = bx + vx / (1.0 - BALL_DECAY)
    ey = by + vy / (1.0 - BALL_DECAY)
    # toward the opponent goal (needs the ball within 20 m of it: never for HFO's goalie)
    if ex > PITCH_HALF_LENGTH and (bx - PITCH_HALF_LENGTH) ** 2 + by**2 < 20.0**2:
        p = _segment_line_intersection(bx, by, ex, ey, _goal_line(PITCH_HALF_LENGTH))
        if p is not None and abs(p[1]) < GOAL_HALF_WIDTH:
            speed_rate = 1.0 - math.exp(-(speed**2) / (2.0 * (BALL_SPEED_MAX * 0.5) ** 2))
            y_rate = math.exp(-(abs(p[1]) ** 2) / (2.0 * (2.0 * GOAL_HALF_WIDTH) ** 2))
            return 1000000.0 * speed_rate * y_rate
    # toward the own goal
    if ex < -PITCH_HALF_LENGTH:
        p = _segment_line_intersection(bx, by, ex, ey, _goal_line(-PITCH_HALF_LENGTH))
        if p is not None and abs(p[1]) < GOAL_HALF_WIDTH + 1.0:
            y_penalty = -10000.0 * math.exp(
                -((abs(p[1]) - GOAL_HALF_WIDTH) ** 2) / (2.0 * GOAL_HALF_WIDTH**2)
            )
            speed_bonus = 10000.0 * math.exp(-(speed**2) / (2.0 * (BALL_SPEED_MAX * 0.5) ** 2))
            return y_penalty + speed_bonus
    # normal evaluation
    n = opponents_reach_step(view, bx, by, vx, vy, move_angle)
    fx, fy = ball_at(bx, by, vx, vy, n)
    count, sol = _rect_segment(bx, by, fx, fy)
    if count > 0 and sol is not None:
        fx, fy = sol
    goal_diff = abs(norm_deg(angle_of(OWN_GOAL[0] - bx, OWN_GOAL[1] - by) - move_angle))
    goal_rate = 1.0 - math.exp(-(goal_diff**2) / (2.0 * 40.0**2))
    if abs(fy) > PITCH_HALF_WIDTH - 0.1:
        y_rate = 1.0
    else:
        y_rate = math.exp(-((abs(fy) - PITCH_HALF_WIDTH) ** 2) / (2.0 * (PITCH_HALF_WIDTH * 0.7) ** 2))
    opp_rate = 1.0 - math.exp(-(float(n) ** 2) / (2.0 * 30.0**2))
    return 10000.0 * goal_rate * y_rate * opp_rate


def best_tackle(view: GoalieView) -> tuple[float, float, float, float]:
    """TackleGenerator::bestResult: (global tackle angle, ball vx, vy, score) of the best of 40 directions.

    Candidates: dir = -180 + 9 i (relative to the body), ball velocity W + polar(100 (1 - |dir|/180) * 0.027 *
    (1 - 0.5 |angle(B - P) - body| / 180), body + dir), shortened to 3.0. **(quirk)** agent2d's extra "opponent
    shot" acceleration is compiled out (its macro is defined as ``ASUUME_...``, tested as ``ASSUME_...``).
    The first best score wins ties. When the goalie is kickable or the mode is not PlayOn the generator makes
    no candidates and the cleared result, angle 0 with no velocity, is returned (score -inf).
    """
    if view.self_kickable or not view.play_on:
        return 0.0, 0.0, 0.0, -math.inf
    bx, by, body = view.bx, view.by, view.body
    ball_rel = norm_deg(angle_of(bx - view.px, by - view.py) - body)
    tackle_rate = TACKLE_POWER_RATE * (1.0 - 0.5 * abs(ball_rel) / 180.0)
    step = abs(MAX_MOMENT - MIN_MOMENT) / ANGLE_DIVS
    best = (0.0, 0.0, 0.0, -math.inf)
    for i in range(ANGLE_DIVS):
        rel = norm_deg(MIN_MOMENT + step * i)
        eff_power = (
            MAX_BACK_TACKLE_POWER + (MAX_TACKLE_POWER - MAX_BACK_TACKLE_POWER) * (1.0 - abs(rel) / 180.0)
        ) * tackle_rate
        angle = norm_deg(body + rel)
        r = math.radians(angle)
        vx = view.wx + eff_power * math.cos(r)
        vy = view.wy + eff_power * math.sin(r)
        speed = math.hypot(vx, vy)
        if speed > BALL_SPEED_MAX:
            vx *= BALL_SPEED_MAX / speed
            vy *= BALL_SPEED_MAX / speed
        score = evaluate_tackle(view, vx, vy)
        if score > best[3]:
            best = (angle, vx, vy, score)
    return best


# --- Bhv_BasicTackle ---------------------------------------------------------------------------------------------
def basic_tackle(
    eff: Effector, view: GoalieView, table: InterceptTable, min_prob: float = 0.8, body_thr: float = 90.0
) -> bool:
    """Bhv_BasicTackle(min_prob, body_thr).execute, protocol version >= 14 (spec §3.7); True = tackle sent.

    1. prob = tackle_prob; outside the penalty area + 0.5 (B.x > -35.5 or |B.y| > 20.66) a higher foul_prob is
       used instead, with the foul flag (the goalie has no card).
    2. prob < ``min_prob``: no tackle.
    3. Needed: the attacker kickable (``kick_opp``), or the ball heading into the goal (ballAt(self_min) behind
       the goal line and the ray from B along angle(W) meeting it at |y| < 8.01), or opp_min < self_min - 3
       (and < teammate reach 1000 - 3), or self_min >= 5 with the ball within 10 m of the opponent goal and
       that goal within 45 degrees of the body.
    4. The direction is :func:`best_tackle`'s angle; ``eff.tackle(norm(angle - body), foul)``.

    ``body_thr`` only matters on the pre-v12 path and is unused here.
    """
    del body_thr  # the version >= 12 paths do not use it
    dx = view.bx - view.px
    dy = view.by - view.py
    if min_prob > 0.0 and dx * dx + dy * dy > _NO_TACKLE_DIST2:
        # the ball is out of the tackle rectangle (2 m ahead, 1.25 m aside): both probabilities are 0
        return False
    tackle_prob, foul_prob = tackle_probabilities(view, table.opp_min)
    prob = tackle_prob
    use_foul = False
    if (
        view.bx > PENALTY_AREA_X + 0.5 or abs(view.by) > PENALTY_AREA_HALF_WIDTH + 0.5
    ) and tackle_prob < foul_prob:
        prob = foul_prob
        use_foul = True
    if prob < min_prob:
        return False
    self_min = table.self_min
    opp_min = table.opp_min
    # the non-goalie teammates' reach (InterceptTable::teammateReachCycle); 1000 without any (the goalie's table)
    mate_min = getattr(table, "mate_min", 1000)
    bx, by, wx, wy = view.bx, view.by, view.wx, view.wy
    into_goal = False
    reach_x, _ = ball_at(bx, by, wx, wy, self_min)
    if reach_x < -PITCH_HALF_LENGTH:
        p = _ray_line_intersection(bx, by, angle_of(wx, wy), _goal_line(-PITCH_HALF_LENGTH))
        if p is not None and abs(p[1]) < GOAL_HALF_WIDTH + 1.0:
            into_goal = True
    needed = (
        view.kick_opp
        or into_goal
        or (opp_min < self_min - 3 and opp_min < mate_min - 3)
        or (
            self_min >= 5
            and (bx - PITCH_HALF_LENGTH) ** 2 + by**2 < 10.0**2
            and abs(norm_deg(angle_of(PITCH_HALF_LENGTH - view.px, -view.py) - view.body)) < 45.0
        )
    )
    if not needed:
        return False
    angle, _, _, _ = best_tackle(view)
    eff.tackle(norm_deg(angle - view.body), use_foul)
    return True


def client_tackle_dir(direction_deg: float) -> float:
    """The tackle direction as librcsc sends it: normalised (setTackle, version >= 12), rounded to 0.001
    (``rint``), then written with the 6 significant digits of a default C++ stream."""
    d = round(norm_deg(float(direction_deg)) * 1000.0) * 0.001
    return float(f"{d:.6g}")
