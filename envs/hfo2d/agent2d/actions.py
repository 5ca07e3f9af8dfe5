"""librcsc's body actions as HFO's goalie uses them, and the client-side conversions of its commands (GF).

Each action reads a :class:`~hfo2d.agent2d.common.GoalieView`, writes at most one body command into an
:class:`~hfo2d.agent2d.common.Effector` (a later write replaces an earlier one, as in librcsc's ActionEffector)
and returns whether it "acted" in librcsc's sense. Several actions write a ``turn 0`` and still return False
("not needed"); callers rely on both.

The commands in the effector are what the goalie's code asks for (a desired actual turn, a raw dash power and
direction). :func:`client_turn_moment` and :func:`client_dash` are the conversions librcsc's ActionEffector
applies before it sends them (turn moment from the desired turn, dash power conservation, rounding).

Sources (facts and numbers only): librcsc d222758 ``rcsc/action/{body_go_to_point2010, bhv_go_to_point_look_ball,
basic_actions, body_stop_dash, body_intercept2009}.cpp``, ``rcsc/player/action_effector.cpp``,
``rcsc/common/{stamina_model, player_type, server_param}.cpp``, ``rcsc/geom/{circle_2d.cpp, line_2d.h,
segment_2d.h, angle_deg.h}``; rcssserver 15.2.2 ``src/serverparam.cpp`` for the server parameters the client
receives. The goalie is player type 0 and, with fullstate, every accuracy count is 0.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from hfo2d.agent2d.tackle import client_tackle_dir
from hfo2d.physics import ServerParams

if TYPE_CHECKING:
    from hfo2d.physics import PlayerState, World

from . import common as _common
from .common import (
    EXHAUST,
    GOAL_HALF_WIDTH,
    NORMAL,
    PENALTY_AREA_HALF_WIDTH,
    PENALTY_AREA_X,
    PITCH_HALF_LENGTH,
    PITCH_HALF_WIDTH,
    Effector,
    GoalieView,
    InterceptEntry,
    InterceptTable,
    angle_of,
    dir_rate,
    norm_deg,
    register_binder,
)

# --- parameters (the server's as the client receives them, set by _bind; rcssserver 15.2.2 defaults for player
# type 0 in the comments) ----------------------------------------------------------------------------------------
GOAL_POST_RADIUS = 0.06  # rcssserver serverparam.cpp: goal_post_radius (fixed in hfo2d.physics)
# rcssserver serverparam.cpp: ball_rand 0.05, body_intercept's default; the goalie passes its view's (the world's
# ball_rand, 0 without noise as under HFO's --deterministic)
BALL_RAND = 0.05
MAX_NECK_ANGLE = 90.0  # rcssserver serverparam.cpp: maxneckang (minneckang -90)
# librcsc view_mode.cpp ViewWidth::width(NORMAL) with synch_see (HFO's player.conf): visible_angle 90 * 2 *
# simulator_step 100 / send_step 150
NORMAL_VIEW_WIDTH = 120.0

_DEG2RAD = math.pi / 180.0
_RAD2DEG = 180.0 / math.pi

# librcsc body_stop_dash.cpp / body_go_to_point2010.cpp: dash directions -180 .. 135 in steps of
# max(15, dash_angle_step); the adjust (omni) dash drops |dir| < 0.5 and |dir| > 100
_ALL_DASH_DIRS = (-180.0, -135.0, -90.0, -45.0, 0.0, 45.0, 90.0, 135.0)
_ADJUST_DASH_DIRS = (-90.0, -45.0, 45.0, 90.0)

# librcsc body_go_to_point2010.cpp checkGoalPost: posts of the own goal (the collision distances: _bind)
_POST_X = -PITCH_HALF_LENGTH + GOAL_POST_RADIUS
_POST_Y = GOAL_HALF_WIDTH + GOAL_POST_RADIUS

# librcsc body_intercept2009.cpp getBestIntercept
_MAX_PITCH_X = PITCH_HALF_LENGTH - 1.0
_MAX_PITCH_Y = PITCH_HALF_WIDTH - 1.0
_PENALTY_X = PENALTY_AREA_X  # ServerParam::ourPenaltyAreaLineX
_PENALTY_Y = PENALTY_AREA_HALF_WIDTH  # ServerParam::penaltyAreaHalfWidth
_MATE_MIN = 1000  # no teammates: InterceptTable::teammateReachCycle


# --- small helpers -------------------------------------------------------------------------------------------
def dash_dir_rate(direction: float) -> float:
    """librcsc ServerParam::dashDirRate: the dash-direction rate after clamping and rounding to 45 degrees."""
    d = -180.0 if direction < -180.0 else (180.0 if direction > 180.0 else direction)
    d = DASH_ANGLE_STEP * round(d / DASH_ANGLE_STEP)
    r = dir_rate(d)
    return 1.0e-5 if r < 1.0e-5 else (1.0 if r > 1.0 else r)


def _clamp_power(p: float) -> float:
    """librcsc ServerParam::normalizeDashPower."""
    if p < MIN_DASH_POWER:
        return MIN_DASH_POWER
    if p > MAX_DASH_POWER:
        return MAX_DASH_POWER
    return p


def _asin_deg(x: float) -> float:
    if x >= 1.0:
        return 90.0
    if x <= -1.0:
        return -90.0
    return math.asin(x) * _RAD2DEG


def _first_term(dist: float, n: int) -> float:
    """librcsc calc_first_term_geom_series with the player decay."""
    return dist * (1.0 - PLAYER_DECAY) / (1.0 - PLAYER_DECAY**n)


def _self_at(view: GoalieView, n: int) -> tuple[float, float]:
    """librcsc inertia_n_step_point for the goalie."""
    f = _SELF_AT_SUMS[n] if 0 <= n < _SELF_AT_SUMS_LEN else (1.0 - PLAYER_DECAY**n) / (1.0 - PLAYER_DECAY)
    return view.px + view.vx * f, view.py + view.vy * f


def _ball_at(view: GoalieView, n: int) -> tuple[float, float]:
    """librcsc BallObject::inertiaPoint under the world model's ball velocity."""
    f = (1.0 - BALL_DECAY**n) / (1.0 - BALL_DECAY)
    return view.bx + view.wx * f, view.by + view.wy * f


def _dash_rate(view: GoalieView) -> float:
    """librcsc SelfObject::dashRate: effort * dash_power_rate."""
    return view.effort * DASH_POWER_RATE


def _simulate_dash(stamina: float, recovery: float, power: float) -> tuple[float, float]:
    """librcsc StaminaModel::simulateDash (stamina and recovery; the capacity never runs out in HFO)."""
    stamina -= power if power >= 0.0 else -2.0 * power
    if stamina < 0.0:
        stamina = 0.0
    if stamina <= RECOVER_DEC_THR_VALUE and recovery > RECOVER_MIN:
        recovery = max(recovery - RECOVER_DEC, RECOVER_MIN)
    stamina += min(STAMINA_INC_MAX * recovery, STAMINA_MAX - stamina)
    return min(stamina, STAMINA_MAX), recovery


def _bind(sp: ServerParams) -> None:
    global BALL_DECAY, CATCHABLE_AREA, EXTRA_STAMINA, INERTIA_MOMENT, KICKABLE_AREA, PLAYER_DECAY
    global PLAYER_SPEED_MAX, REAL_SPEED_MAX, STAMINA_INC_MAX, STAMINA_MAX, DASH_POWER_RATE, MIN_DASH_POWER
    global MAX_DASH_POWER, MAX_MOMENT, DASH_ANGLE_STEP, PLAYER_SPEED_MAX2, RECOVER_DEC_THR_VALUE
    global SAFETY_STAMINA_THR, RECOVER_MIN, RECOVER_DEC, PLAYER_SIZE, _POST_COLLISION_DIST, _POST_CHECK_DIST2
    global _SPEED_MAX_09, _ALL_DASH_DIR_RATES, _SELF_AT_SUMS, _SELF_AT_SUMS_LEN
    # the ones hfo2d.agent2d.common derives
    BALL_DECAY = _common.BALL_DECAY
    CATCHABLE_AREA = _common.CATCHABLE_AREA
    EXTRA_STAMINA = _common.EXTRA_STAMINA
    INERTIA_MOMENT = _common.INERTIA_MOMENT
    KICKABLE_AREA = _common.KICKABLE_AREA
    PLAYER_DECAY = _common.PLAYER_DECAY
    PLAYER_SPEED_MAX = _common.PLAYER_SPEED_MAX
    REAL_SPEED_MAX = _common.REAL_SPEED_MAX
    STAMINA_INC_MAX = _common.STAMINA_INC_MAX
    STAMINA_MAX = _common.STAMINA_MAX
    DASH_POWER_RATE = sp.dash_power_rate  # rcssserver serverparam.cpp: dash_power_rate 0.006 (player type 0)
    MIN_DASH_POWER = sp.minpower  # rcssserver serverparam.cpp: minpower -100
    MAX_DASH_POWER = sp.maxpower  # rcssserver serverparam.cpp: maxpower 100
    MAX_MOMENT = sp.max_moment  # rcssserver serverparam.cpp: maxmoment 180 (minmoment -180)
    DASH_ANGLE_STEP = sp.dash_angle_step  # rcssserver serverparam.cpp: dash_angle_step 45
    PLAYER_SPEED_MAX2 = PLAYER_SPEED_MAX * PLAYER_SPEED_MAX  # librcsc PlayerType::playerSpeedMax2
    # librcsc ServerParam::recoverDecThrValue: recover_dec_thr 0.3 * stamina_max
    RECOVER_DEC_THR_VALUE = sp.recover_dec_thr * STAMINA_MAX
    SAFETY_STAMINA_THR = RECOVER_DEC_THR_VALUE + 1.0  # librcsc stamina_model.cpp getSafetyDashPower: thr + 1
    RECOVER_MIN = sp.recover_min  # rcssserver serverparam.cpp: recover_min 0.5
    RECOVER_DEC = sp.recover_dec  # rcssserver serverparam.cpp: recover_dec 0.002
    PLAYER_SIZE = sp.player_size  # rcssserver serverparam.cpp: player_size 0.3
    # librcsc body_go_to_point2010.cpp checkGoalPost: the collision distance
    _POST_COLLISION_DIST = PLAYER_SIZE + GOAL_POST_RADIUS + 0.2
    _POST_CHECK_DIST2 = (
        _POST_COLLISION_DIST + REAL_SPEED_MAX + 0.5
    )  # (quirk) compared with a *squared* distance
    _SPEED_MAX_09 = REAL_SPEED_MAX * 0.9  # librcsc body_intercept2009.cpp getBestIntercept
    _ALL_DASH_DIR_RATES = tuple((d, dash_dir_rate(d)) for d in _ALL_DASH_DIRS)
    # _self_at's sums 1 + decay + ... + decay**(n-1) for n < 101 (Body_GoToPoint's 100 cycles and the intercept's
    # reach cycles), each by _self_at's own expression
    _SELF_AT_SUMS = tuple((1.0 - PLAYER_DECAY**n) / (1.0 - PLAYER_DECAY) for n in range(101))
    _SELF_AT_SUMS_LEN = len(_SELF_AT_SUMS)


register_binder(_bind)


# --- client-side conversions (librcsc ActionEffector) -------------------------------------------------------
def client_turn_moment(view: GoalieView, desired: float) -> float:
    """The turn moment librcsc sends for a desired actual turn (ActionEffector::setTurn).

    moment = norm(desired) * (1 + inertia_moment * |V|), clamped to [-180, 180], rounded to 0.001.
    """
    # norm_deg(desired), written out: the goalie turns almost every cycle
    if desired < -360.0 or desired > 360.0:
        desired = math.fmod(desired, 360.0)
    if desired < -180.0:
        desired += 360.0
    if desired > 180.0:
        desired -= 360.0
    m = desired * (1.0 + math.sqrt(view.vx * view.vx + view.vy * view.vy) * INERTIA_MOMENT)
    if m > MAX_MOMENT:
        m = MAX_MOMENT
    if m < -MAX_MOMENT:
        m = -MAX_MOMENT
    r = round(m * 1000.0)  # rint: round half to even, like Python's round
    return r * 0.001 if r != 0 else math.copysign(0.0, m)


def _conserve_dash_power(view: GoalieView, power: float, direction: float) -> float:
    """librcsc action_effector.cpp conserve_dash_power (``direction`` already rounded to 45 degrees)."""
    power = _clamp_power(power)
    back = power < 0.0
    required = -2.0 * power if back else power
    available = view.stamina + EXTRA_STAMINA
    if available < required:
        power = -0.5 * available if back else available
    rate = dash_dir_rate(direction)
    dr = _dash_rate(view)
    accel = abs(power * rate * dr)
    accel_dir = norm_deg(view.body + (direction + 180.0 if back else direction)) * _DEG2RAD
    c, s = math.cos(accel_dir), math.sin(accel_dir)
    # librcsc PlayerType::normalizeAccel: cap the resulting speed at player_speed_max
    mx = view.vx + accel * c
    my = view.vy + accel * s
    if mx * mx + my * my > PLAYER_SPEED_MAX2 + 0.0001:
        rel_x = view.vx * c + view.vy * s
        rel_y = -view.vx * s + view.vy * c
        accel = math.sqrt(PLAYER_SPEED_MAX2 - rel_y * rel_y) - rel_x
    power = accel / dr / rate
    if back:
        power = -power
    return _clamp_power(power)


def client_dash(view: GoalieView, power: float, direction: float = 0.0) -> tuple[float, float]:
    """The (power, direction) librcsc sends for a requested dash (ActionEffector::setDash).

    The power is clamped to [-100, 100] (only when more than 0.01 outside), the direction normalised and rounded
    to a multiple of 45 degrees; then the power is conserved (stamina + extra stamina, speed cap) and rounded to
    0.001.
    """
    p = power
    if p < MIN_DASH_POWER - 0.01 or p > MAX_DASH_POWER + 0.01:
        p = _clamp_power(p)
    d = DASH_ANGLE_STEP * round(norm_deg(direction) / DASH_ANGLE_STEP)
    p = _conserve_dash_power(view, p, d)
    r = round(p * 1000.0)
    return (r * 0.001 if r != 0 else math.copysign(0.0, p)), float(d)


def safety_dash_power(view: GoalieView, power: float) -> float:
    """librcsc StaminaModel::getSafetyDashPower: keep the stamina above recover_dec_thr (2400) + 1.

    The stamina use (p, or -2p backward) is limited to max(0, stamina - 2401); a backward result is halved and
    negated; the result never exceeds |p| (p clamped to [-100, 100] first).
    """
    p = _clamp_power(power)
    required = p if p > 0.0 else -2.0 * p
    available = view.stamina - SAFETY_STAMINA_THR
    if available < 0.0:
        available = 0.0
    result = required if required < available else available
    if p < 0.0:
        result *= -0.5
    if abs(result) > abs(p):
        return p
    return result


# --- turn and stop primitives (librcsc basic_actions.cpp, body_stop_dash.cpp) -----------------------------
def body_turn_to_angle(eff: Effector, view: GoalieView, angle: float) -> bool:
    """Body_TurnToAngle: turn by norm(angle - body). Always acts."""
    eff.turn(norm_deg(angle - view.body))
    return True


def body_turn_to_point(eff: Effector, view: GoalieView, x: float, y: float, cycles: int = 1) -> bool:
    """Body_TurnToPoint: turn toward (x, y) seen from selfAt(cycles). Returns False (after turning) when the
    needed turn is below 1 degree."""
    sx, sy = _self_at(view, cycles)
    rel = norm_deg(angle_of(x - sx, y - sy) - view.body)
    eff.turn(rel)
    return abs(rel) >= 1.0


def neck_body_to_ball(eff: Effector, view: GoalieView) -> bool:
    """Bhv_NeckBodyToBall (angle buffer 5): turn 0 when the neck alone can face the next ball, else turn to it."""
    nx, ny = view.px + view.vx, view.py + view.vy
    rel = norm_deg(angle_of((view.bx + view.wx) - nx, (view.by + view.wy) - ny) - view.body)
    if -MAX_NECK_ANGLE + 5.0 < rel < MAX_NECK_ANGLE - 5.0:
        eff.turn(0.0)
    else:
        eff.turn(rel)
    return True


def body_stop_dash(eff: Effector, view: GoalieView, save_recovery: bool) -> bool:
    """Body_StopDash: the dash (over the 8 directions) that leaves the smallest speed; nothing when |p| < 1."""
    dr = _dash_rate(view)
    vx, vy = view.vx, view.vy
    best_dir = -360.0
    best_speed = 100.0
    best_power = 0.0
    for d, d_rate in _ALL_DASH_DIR_RATES:
        rate = dr * d_rate
        a = norm_deg(view.body + d) * _DEG2RAD
        c, s = math.cos(a), math.sin(a)
        p = _clamp_power(-(vx * c + vy * s) / rate)
        if save_recovery:
            p = safety_dash_power(view, p)
        rx = vx + p * rate * c
        ry = vy + p * rate * s
        speed = math.sqrt(rx * rx + ry * ry)
        if speed < best_speed:
            best_dir, best_speed, best_power = d, speed, p
    if best_dir == -360.0 or abs(best_power) < 1.0:
        return False
    eff.dash(best_power, best_dir)
    return True


# --- Body_GoToPoint2010 ------------------------------------------------------------------------------------
def _segment_meets_circle(cx: float, cy: float, r: float, ox: float, oy: float, tx: float, ty: float) -> bool:
    """librcsc Circle2D::intersection(Segment2D) > 0: a crossing of the circle's line solutions within the
    segment's bounding box (Line2D through both ends, discriminant noise 1e-5, Segment2D::contains 1e-9)."""
    a = -(ty - oy)
    b = tx - ox
    c = -a * ox - b * oy
    sols: list[tuple[float, float]] = []
    if abs(a) < 1.0e-6:
        if abs(b) < 1.0e-6:
            return False
        y1 = -c / b
        qb = -2.0 * cx
        qc = cx * cx + (c / b + cy) ** 2 - r * r
        disc = qb * qb - 4.0 * qc
        if abs(disc) < 1.0e-5:
            sols.append((-qb / 2.0, y1))
        elif disc >= 0.0:
            sq = math.sqrt(disc)
            sols.append(((-qb + sq) / 2.0, y1))
            sols.append(((-qb - sq) / 2.0, y1))
    else:
        m = b / a
        d = c / a
        qa = 1.0 + m * m
        qb = 2.0 * (-cy + (d + cx) * m)
        qc = (d + cx) ** 2 + cy * cy - r * r
        disc = qb * qb - 4.0 * qa * qc
        ys: tuple[float, ...]
        if abs(disc) < 1.0e-5:
            ys = (-qb / (2.0 * qa),)
        elif disc < 0.0:
            ys = ()
        else:
            sq = math.sqrt(disc)
            ys = ((-qb + sq) / (2.0 * qa), (-qb - sq) / (2.0 * qa))
        for y in ys:
            sols.append((-(b * y + c) / a, y))
    return any((px - ox) * (px - tx) <= 1.0e-9 and (py - oy) * (py - ty) <= 1.0e-9 for px, py in sols)


def avoid_goal_post(view: GoalieView, x: float, y: float) -> tuple[float, float]:
    """Body_GoToPoint2010::checkGoalPost: the target, moved beside the nearest own post when the straight move
    P -> (x, y) would hit it.

    (quirk) The goalie's *squared* distance to the post is compared with 0.56 + 1.0 + 0.5 = 2.06, so only a
    goalie within 1.435 m of a post is checked.
    """
    px, py = view.px, view.py
    dl = (px - _POST_X) ** 2 + (py + _POST_Y) ** 2
    dr = (px - _POST_X) ** 2 + (py - _POST_Y) ** 2
    post_y = -_POST_Y if dl < dr else _POST_Y
    if min(dl, dr) > _POST_CHECK_DIST2:
        return x, y
    if not _segment_meets_circle(_POST_X, post_y, _POST_COLLISION_DIST, px, py, x, y):
        return x, y
    a = angle_of(_POST_X - px, post_y - py)
    diff = view.body - a  # AngleDeg::isLeftOf: raw difference of the two normalised angles
    side = 90.0 if (0.0 < diff < 180.0) or diff < -180.0 else -90.0
    r = (a + side) * _DEG2RAD
    shift = _POST_COLLISION_DIST + 0.1
    return _POST_X + shift * math.cos(r), post_y + shift * math.sin(r)


def _gtp_adjust_dash(
    eff: Effector,
    view: GoalieView,
    tx: float,
    ty: float,
    dist_thr: float,
    max_power: float,
    cycles: int,
    save_recovery: bool,
    dir_thr: float,
) -> bool:
    """Body_GoToPoint2010::doAdjustDash: a side (omni) dash for a target close by but off the body line."""
    ix, iy = _self_at(view, cycles)
    rx, ry = tx - ix, ty - iy
    if rx * rx + ry * ry > (dist_thr + 1.0) ** 2:  # adjustable_dist 1.0
        return False
    b = view.body * _DEG2RAD
    cb, sb = math.cos(b), math.sin(b)
    rbx = rx * cb + ry * sb
    rby = -rx * sb + ry * cb
    if abs(rby) < dist_thr:
        return False
    target_angle = angle_of(rbx, rby)
    if abs(target_angle) < dir_thr:
        return False
    rvx = view.vx * cb + view.vy * sb
    rvy = -view.vx * sb + view.vy * cb
    dr = _dash_rate(view)
    drift = (1.0 - PLAYER_DECAY**cycles) / (1.0 - PLAYER_DECAY)
    max_cycle = min(3, cycles)

    best_dir = -360.0
    best_dist = 1000000.0
    best_cycle = 1000
    best_power = 0.0
    best_stamina = 0.0
    for d in _ADJUST_DASH_DIRS:
        if abs(norm_deg(d - target_angle)) > 90.0:
            continue
        rate = dr * dash_dir_rate(d)
        dd = d * _DEG2RAD
        cd, sd = math.cos(dd), math.sin(dd)
        # (quirk) the start point is the velocity's drift over ``cycles``, and the same velocity is applied again
        # by the simulated dashes
        mx, my = rvx * drift, rvy * drift
        vx, vy = rvx, rvy
        stamina, recovery = view.stamina, view.recovery
        first_power: float | None = None
        k = 0
        while k < max_cycle:
            qx, qy = rbx - mx, rby - my
            need = _first_term(qx * cd + qy * sd, cycles - k)
            if need < 0.01:
                break
            available = max(0.0, stamina - SAFETY_STAMINA_THR) if save_recovery else stamina + EXTRA_STAMINA
            p = min(available, max_power, need / rate, MAX_DASH_POWER)
            if k == 0:
                first_power = p
            vx += p * rate * cd
            vy += p * rate * sd
            mx += vx
            my += vy
            vx *= PLAYER_DECAY
            vy *= PLAYER_DECAY
            stamina, recovery = _simulate_dash(stamina, recovery, p)
            k += 1
        if first_power is None:
            continue
        last = math.sqrt((mx - rbx) ** 2 + (my - rby) ** 2)
        if last < dist_thr:
            update = False
            if last < 0.1 or abs(last - best_dist) < 0.001:
                # (quirk) a close result replaces the best only with fewer dashes or more stamina left
                update = k < best_cycle or stamina > best_stamina
            elif last < best_dist:
                update = True
            if update:
                best_dir, best_dist, best_cycle, best_power, best_stamina = d, last, k, first_power, stamina
    if best_dir == -360.0:
        return False
    eff.dash(best_power, best_dir)
    return True


def body_go_to_point(
    eff: Effector,
    view: GoalieView,
    x: float,
    y: float,
    dist_thr: float,
    max_power: float,
    cycles: int = 100,
    save_recovery: bool = True,
    dir_thr: float = 15.0,
) -> bool:
    """Body_GoToPoint2010(T, dist_thr, max_power, dash_speed -1, cycles, save_recovery, dir_thr).

    Returns True when it turned or dashed toward the target; False ("not needed") after writing ``turn 0`` when
    the power is < 0.1, the inertia point selfAt(cycles) is within ``dist_thr``, or the needed dash is tiny.
    """
    max_power = abs(max_power)
    if max_power < 0.1:
        eff.turn(0.0)
        return False
    ix, iy = _self_at(view, cycles)
    if math.sqrt((x - ix) ** 2 + (y - iy) ** 2) < dist_thr:
        eff.turn(0.0)
        return False

    x, y = avoid_goal_post(view, x, y)

    if _gtp_adjust_dash(eff, view, x, y, dist_thr, max_power, cycles, save_recovery, dir_thr):
        return True

    # doTurn
    rx, ry = x - ix, y - iy
    dist = math.sqrt(rx * rx + ry * ry)
    speed = math.sqrt(view.vx * view.vx + view.vy * view.vy)
    max_turn = MAX_MOMENT / (1.0 + INERTIA_MOMENT * speed)
    moment = norm_deg(angle_of(rx, ry) - view.body)
    back = False
    # back mode; the back dash is as effective as the forward one (|-100| * rate > 0.75 * 100 * rate)
    if (
        abs(moment) > max_turn
        and abs(moment) > 90.0
        and dist < 2.0
        and view.stamina > RECOVER_DEC_THR_VALUE + 500.0
    ):
        back = True
        moment = norm_deg(moment + 180.0)
    turn_thr = 180.0
    if dist_thr < dist:
        turn_thr = _asin_deg(dist_thr / dist)
    turn_thr = max(dir_thr, turn_thr)
    if abs(moment) >= turn_thr:
        eff.turn(moment)
        return True

    # doDash
    acc = norm_deg(view.body + 180.0) if back else view.body
    a = acc * _DEG2RAD
    c, s = math.cos(a), math.sin(a)
    first = _first_term(rx * c + ry * s, cycles)
    if first > PLAYER_SPEED_MAX:
        first = PLAYER_SPEED_MAX
    elif first < -PLAYER_SPEED_MAX:
        first = -PLAYER_SPEED_MAX
    need = first - (view.vx * c + view.vy * s)
    if abs(need) < 0.05:
        eff.turn(0.0)
        return False
    p = min(need / _dash_rate(view), max_power)
    if back:
        p = -p
    p = _clamp_power(p)
    if save_recovery:
        p = safety_dash_power(view, p)
    eff.dash(p, 0.0)
    return True


# --- Bhv_GoToPointLookBall ---------------------------------------------------------------------------------
def go_to_point_look_ball(
    eff: Effector, view: GoalieView, x: float, y: float, dist_thr: float, power: float
) -> bool:
    """Bhv_GoToPointLookBall(T, dist_thr, power, back rate 0.7) for the goalie.

    Returns True when already there (``turn 0``), when Body_GoToPoint acted, or in back-dash mode; False when
    Body_GoToPoint was not needed (then Bhv_NeckBodyToBall has set the command).
    """
    fx = view.px + view.vx / (1.0 - PLAYER_DECAY)
    fy = view.py + view.vy / (1.0 - PLAYER_DECAY)
    if (fx - x) ** 2 + (fy - y) ** 2 < dist_thr * dist_thr:
        eff.turn(0.0)
        return True
    nx, ny = view.px + view.vx, view.py + view.vy
    diff = norm_deg(angle_of(x - nx, y - ny) - angle_of((view.bx + view.wx) - nx, (view.by + view.wy) - ny))
    if abs(diff) < MAX_NECK_ANGLE - 5.0:
        if body_go_to_point(eff, view, x, y, dist_thr, power):
            return True
        neck_body_to_ball(eff, view)
        return False
    # back-dash mode, front toward the ball
    reverse = angle_of(nx - x, ny - y)
    margin = max(6.0, abs(math.atan2(CATCHABLE_AREA, math.sqrt((x - nx) ** 2 + (y - ny) ** 2)) * _RAD2DEG))
    if abs(norm_deg(reverse - view.body)) > margin:
        body_turn_to_angle(eff, view, reverse)
    else:
        # the goalie uses the full power, not back rate * power
        eff.dash(safety_dash_power(view, -power), 0.0)
    return True


# --- Body_Intercept2009 ------------------------------------------------------------------------------------
_NO_ENTRY = InterceptEntry(EXHAUST, 10000, 10000, 100000.0, 0.0, -10000.0, 0.0, 10000000.0, 0.0)


def best_intercept(view: GoalieView, table: InterceptTable, save_recovery: bool) -> InterceptEntry:
    """Body_Intercept2009::getBestIntercept for the goalie (GF)."""
    cache = table.self_cache
    if not cache:
        return _NO_ENTRY  # librcsc's default InterceptInfo
    opp_min = table.opp_min
    wx, wy = view.wx, view.wy
    goalie_ok = view.lk_not_ours  # the goalie branches need lastKickerSide != ourSide
    # WorldModel::offsideLineX: max(0, their defence line, ball next x); with one opponent the line is 0
    offside_x = max(0.0, view.bx + wx)

    goalie_best: InterceptEntry | None = None
    goalie_score = -10000.0
    aggressive_best: InterceptEntry | None = None
    aggressive_score = -10000.0
    attacker_best: InterceptEntry | None = None
    attacker_score = 0.0
    forward_best: InterceptEntry | None = None
    forward_score = 0.0
    noturn_best: InterceptEntry | None = None
    noturn_score = 10000.0
    nearest_best: InterceptEntry | None = None
    nearest_score = 10000.0

    b0x, b0y = view.bx, view.by
    goalie_x = _PENALTY_X - 1.0
    goalie_y = _PENALTY_Y - 1.0
    for e in cache:
        if save_recovery and e.mode != NORMAL:
            continue
        turns = e.turn_cycle
        k = turns + e.dash_cycle
        dk = BALL_DECAY**k
        fb = (1.0 - dk) / (1.0 - BALL_DECAY)
        bx = b0x + wx * fb
        by = b0y + wy * fb
        aby = by if by >= 0.0 else -by
        if bx > _MAX_PITCH_X or bx < -_MAX_PITCH_X or aby > _MAX_PITCH_Y:
            continue
        bvx, bvy = wx * dk, wy * dk

        if goalie_ok:
            ball_dist = e.ball_dist
            if (
                bx < goalie_x
                and aby < goalie_y
                and k < opp_min - 1
                and ((turns == 0 and ball_dist < CATCHABLE_AREA * 0.5) or ball_dist < 0.01)
            ):
                d = (bx + PITCH_HALF_LENGTH) ** 2 + by * by
                if d > goalie_score:
                    goalie_score, goalie_best = d, e
            if (
                k < _MATE_MIN - 3
                and k < opp_min - 5
                and (bx > goalie_x or aby > goalie_y)
                and ((turns == 0 and ball_dist < KICKABLE_AREA * 0.5) or ball_dist < 0.01)
                and bx > aggressive_score
            ):
                aggressive_score, aggressive_best = bx, e

        attacker = (
            bvx > 0.5
            and bvx * bvx + bvy * bvy > _SPEED_MAX_09 * _SPEED_MAX_09
            and e.dash_power >= 0.0
            and bx < 47.0
            and (bx > 35.0 or bx > offside_x)
        )
        if k >= opp_min * (0.95 if attacker else 0.7):
            continue
        if attacker:
            goal_dist = 100.0 - min(100.0, math.sqrt((bx - 65.0) ** 2 + by * by))
            x_diff = 47.0 - bx
            score = (goal_dist / 100.0) * math.exp(-(x_diff * x_diff) / (2.0 * 100.0))
            if score > attacker_score:
                attacker_best, attacker_score = e, score
            continue
        if turns == 0:
            if k < noturn_score:
                noturn_best, noturn_score = e, float(k)
            continue
        if bvx > 0.1 and k <= opp_min - 5 and bvx * bvx + bvy * bvy > 0.6 * 0.6:
            score = 10000.0 - min(10000.0, (bx - 65.0) ** 2 + by * by)
            if score > forward_score:
                forward_best, forward_score = e, score
            continue
        fs = (1.0 - PLAYER_DECAY**k) / (1.0 - PLAYER_DECAY)
        d = (view.px + view.vx * fs - bx) ** 2 + (view.py + view.vy * fs - by) ** 2
        if d < nearest_score:
            nearest_best, nearest_score = e, d

    if aggressive_best is not None:
        return aggressive_best
    if goalie_best is not None:
        return goalie_best
    if attacker_best is not None:
        return attacker_best
    if noturn_best is not None and forward_best is not None:
        k = noturn_best.reach_cycle
        dk = BALL_DECAY**k
        nvx, nvy = wx * dk, wy * dk
        if nvx > 0.1 and (
            math.sqrt(nvx * nvx + nvy * nvy) > _SPEED_MAX_09 or k <= forward_best.reach_cycle + 2
        ):
            return noturn_best
    if forward_best is not None:
        return forward_best

    k0 = cache[0].reach_cycle
    fx, fy = _ball_at(view, k0)
    dk = BALL_DECAY**k0
    if (fx > -33.0 or abs(fy) > 20.0) and (k0 >= 10 or math.sqrt((wx * dk) ** 2 + (wy * dk) ** 2) < 1.2):
        return cache[0]

    if noturn_best is not None and nearest_best is not None:
        kn, kr = noturn_best.reach_cycle, nearest_best.reach_cycle
        nsx, nsy = _self_at(view, kn)
        nbx, nby = _ball_at(view, kn)
        rsx, rsy = _self_at(view, kr)
        rbx, rby = _ball_at(view, kr)
        if (nsx - nbx) ** 2 + (nsy - nby) ** 2 < (rsx - rbx) ** 2 + (rsy - rby) ** 2:
            return noturn_best
        if kr <= kn + 2:
            dr = BALL_DECAY**kr
            r_speed = math.sqrt((wx * dr) ** 2 + (wy * dr) ** 2)
            if r_speed < 0.7:
                return nearest_best
            dn = BALL_DECAY**kn
            nvx, nvy = wx * dn, wy * dn
            if (
                nearest_best.ball_dist < KICKABLE_AREA - 0.4
                and nearest_best.ball_dist < noturn_best.ball_dist
                and nvx < 0.5
                and nvx * nvx + nvy * nvy > 1.0
                and nbx > rbx
            ):
                return nearest_best
            if r_speed > 0.7 and math.sqrt((rsx - rbx) ** 2 + (rsy - rby) ** 2) < KICKABLE_AREA:
                return nearest_best
        return noturn_best
    if noturn_best is not None:
        return noturn_best
    if nearest_best is not None:
        return nearest_best

    # the "chance" branch needs the goalie beyond x = 40 (never in HFO); kept for completeness
    w_speed = math.sqrt(wx * wx + wy * wy)
    if view.px > 40.0 and w_speed > 1.8 and abs(angle_of(wx, wy)) < 100.0 and k0 > 1:
        chance: InterceptEntry | None = None
        for e in cache:
            if e.reach_cycle <= k0 + 3 and e.reach_cycle <= opp_min - 2:
                chance = e
        if chance is not None:
            return chance
    return cache[0]


def _wait_turn(
    eff: Effector, view: GoalieView, tx: float, ty: float, e: InterceptEntry, opp_min: int, ball_rand: float
) -> bool:
    """Body_Intercept2009::doWaitTurn: turn (instead of dashing) when the ball will come to the goalie anyway."""
    # WorldModel::getOpponentNearestToSelf: a field defender's view holds its distance (several opponents), the
    # goalie's view its one attacker
    near = getattr(view, "opp_self_dist", None)
    if near is None:
        near = math.sqrt((view.ox - view.px) ** 2 + (view.oy - view.py) ** 2) if view.has_opp else math.inf
    if near < 3.0:
        return False
    reach = e.reach_cycle
    if reach > opp_min - 5:
        return False
    sx, sy = _self_at(view, reach)
    b = view.body * _DEG2RAD
    cb, sb = math.cos(b), math.sin(b)
    dx, dy = tx - sx, ty - sy
    rx = dx * cb + dy * sb
    ry = -dx * sb + dy * cb
    target_dist = math.sqrt(rx * rx + ry * ry)
    w_speed = math.sqrt(view.wx * view.wx + view.wy * view.wy)
    ball_noise = w_speed * (1.0 - BALL_DECAY**reach) / (1.0 - BALL_DECAY) * ball_rand

    if reach == 1 and e.turn_cycle == 1:
        body_turn_to_point(eff, view, 50.5, view.py * 0.9)
        return True

    extra = 0.1 * min(max(reach - 1, 0), 4)
    ad = abs(norm_deg(angle_of(view.wx, view.wy) - view.body))
    if ad < 10.0 or ad > 170.0:
        extra = 0.0
    if target_dist > KICKABLE_AREA - 0.3 + extra:  # - 0.1 * seenPosCount (0 with fullstate)
        return False

    if reach > 2:
        qx, qy = view.bx - sx, view.by - sy
        c90, s90 = math.cos(90.0 * _DEG2RAD), math.sin(90.0 * _DEG2RAD)
        fx, fy = sx + qx * c90 - qy * s90, sy + qx * s90 + qy * c90  # (B - S) rotated +90 degrees
        if fx < sx:
            fx, fy = sx + qx * c90 + qy * s90, sy - qx * s90 + qy * c90  # rotated -90 degrees
    else:
        fx, fy = 50.5, view.py * 0.9
    fa = angle_of(fx - sx, fy - sy) * _DEG2RAD
    # (quirk) the target is rotated by +face_angle, not -face_angle
    faced_y = dx * math.sin(fa) + dy * math.cos(fa)
    if abs(faced_y) > KICKABLE_AREA - ball_noise - 0.2:
        return False
    body_turn_to_point(eff, view, fx, fy)
    return True


def _inertia_dash(
    eff: Effector, view: GoalieView, tx: float, ty: float, e: InterceptEntry, save_recovery: bool
) -> bool:
    """Body_Intercept2009::doInertiaDash."""
    reach = e.reach_cycle
    if reach == 1:
        eff.dash(e.dash_power, e.dash_dir)
        return True
    b = view.body * _DEG2RAD
    cb, sb = math.cos(b), math.sin(b)
    dx, dy = tx - view.px, ty - view.py
    trx = dx * cb + dy * sb
    try_ = -dx * sb + dy * cb
    dk = BALL_DECAY**reach
    w_speed = math.sqrt(view.wx * view.wx + view.wy * view.wy)

    if not view.lk_not_ours and abs(view.body) < 50.0:
        # the buffer librcsc applies for field players; for the goalie only after its own kick or tackle
        buf = 0.3
        if reach >= 8 or abs(try_) > KICKABLE_AREA - 0.25:
            buf = 0.0
        elif trx < 0.0 or trx < 0.3:
            if reach >= 3:
                buf = 0.5
        elif abs(try_) < 0.5:
            if reach >= 3:
                buf = 0.5
            if reach == 2:
                buf = min(trx, 0.5)
        elif w_speed * dk < 1.6:
            buf = 0.4
        elif reach == 2:
            buf = min(trx, 0.3)
        trx -= buf

    dr = _dash_rate(view)
    used = e.dash_power
    if (
        w_speed * dk < KICKABLE_AREA * 1.5
        and abs(e.dash_dir) < 5.0
        and abs(trx) < KICKABLE_AREA + dr * MAX_DASH_POWER * 0.8
    ):
        first = _first_term(trx, reach)
        if first > PLAYER_SPEED_MAX:
            first = PLAYER_SPEED_MAX
        elif first < -PLAYER_SPEED_MAX:
            first = -PLAYER_SPEED_MAX
        used = (first - (view.vx * cb + view.vy * sb)) / dr
        used /= dash_dir_rate(e.dash_dir)
        used = _clamp_power(used)
        if save_recovery:
            used = safety_dash_power(view, used)

    if reach >= 4 and (abs(trx) < 0.5 or abs(used) < 5.0):
        sx, sy = _self_at(view, reach)
        fx, fy = 50.5, view.py * 0.75
        face_angle = angle_of(fx - sx, fy - sy)
        bnx, bny = view.bx + view.wx, view.by + view.wy
        if (
            abs(norm_deg(angle_of(bnx - sx, bny - sy) - face_angle))
            > MAX_NECK_ANGLE + NORMAL_VIEW_WIDTH - 10.0
        ):
            # never with synch_see (the bound is 200 degrees)
            fx = sx
            if bny > sy + 1.0:
                fy = 50.0
            elif bny < sy - 1.0:
                fy = -50.0
            else:
                fx, fy = bnx, bny
        body_turn_to_point(eff, view, fx, fy)
        return True

    eff.dash(used, e.dash_dir)
    return True


def body_intercept(
    eff: Effector, view: GoalieView, table: InterceptTable, save_recovery: bool, ball_rand: float = BALL_RAND
) -> bool:
    """Body_Intercept2009(save_recovery, face point unset) for the goalie.

    ``ball_rand`` is the server's ball_rand as the client knows it (0.05; 0 under HFO's ``--deterministic``); it
    only enters WaitTurn's ball-noise margin. Returns False only when it chose to rest (``turn 0``) to save the
    recovery; True otherwise.
    """
    # a kickable opponent close by: block its next position if it is farther from the goal than the goalie
    if view.kick_opp and view.has_opp and view.ball_dist < 2.0:
        nx, ny = view.px + view.vx, view.py + view.vy
        ax, ay = view.ox + view.ux, view.oy + view.uy
        if (ax + PITCH_HALF_LENGTH) ** 2 + ay * ay > (nx + PITCH_HALF_LENGTH) ** 2 + ny * ny:
            body_go_to_point(
                eff, view, ax, ay, 0.1, MAX_DASH_POWER, cycles=1, save_recovery=True, dir_thr=15.0
            )
            return True

    if table.self_min > 100:
        body_go_to_point(
            eff,
            view,
            view.bx + view.wx / (1.0 - BALL_DECAY),
            view.by + view.wy / (1.0 - BALL_DECAY),
            2.0,
            MAX_DASH_POWER,
        )
        return True

    e = best_intercept(view, table, save_recovery)
    reach = e.turn_cycle + e.dash_cycle
    tx, ty = _ball_at(view, reach)

    if e.dash_cycle == 0:
        body_turn_to_point(eff, view, 50.5, view.py * 0.75, reach)
        return True

    if e.turn_cycle > 0:
        sx, sy = _self_at(view, reach)
        a = angle_of(tx - sx, ty - sy)
        if e.dash_power < 0.0:
            a = norm_deg(a - 180.0)
        eff.turn(norm_deg(a - view.body))
        return True

    if _wait_turn(eff, view, tx, ty, e, table.opp_min, ball_rand):
        return True

    if save_recovery:
        consumed = e.dash_power if e.dash_power >= 0.0 else -2.0 * e.dash_power
        if view.stamina - consumed < SAFETY_STAMINA_THR:
            eff.turn(0.0)
            return False

    return _inertia_dash(eff, view, tx, ty, e, save_recovery)


def send_command(world: World, player: PlayerState, view: GoalieView, command: Any) -> bool:
    """Send an agent2d body command of kind "turn", "dash" or "tackle" through librcsc's client conversions, as
    agent2d's goalie and field defenders both do; returns False for other kinds (the caller's: the goalie's catch,
    the defender's kick)."""
    kind = command.kind
    if kind == "turn":
        world.turn(player, client_turn_moment(view, command.a))
    elif kind == "dash":
        power, direction = client_dash(view, command.a, command.b)
        world.dash(player, power, direction)
    elif kind == "tackle":
        world.tackle(player, client_tackle_dir(command.a), command.foul)
    else:
        return False
    return True
