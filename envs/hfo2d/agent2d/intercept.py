"""librcsc's intercept table for HFO's goalie: who reaches the ball first, and how (GF).

:func:`build_intercept_table` is the one entry point. It reproduces, for the goalie's fullstate world model,

- ``InterceptTable::update`` (librcsc ``rcsc/player/intercept_table.cpp``): the ball cache, the goalie's own
  candidates and ``self_min``, the attacker's reach ``opp_min``;
- ``SelfInterceptV13::predict`` (``rcsc/player/self_intercept_v13.cpp``): the one-step, short-step (2..5 cycles),
  long-step and final candidates of the goalie itself;
- ``PlayerIntercept::predict`` (``rcsc/player/player_intercept.cpp``): the attacker's reach cycle.

The goalie is rcssserver's default player type 0 (server defaults of rcssserver 15.2.2, which the client reads
from the ``server_param`` message) and every count is 0 (fullstate). The stamina simulation follows librcsc
``rcsc/common/stamina_model.cpp`` (``simulateWait`` / ``simulateDash``) with a stamina capacity that never runs
out within an HFO episode (130600 at the start of each episode, at most 45 used per cycle).

Noise parameters: librcsc takes ``player_rand`` and ``ball_rand`` from the server's ``server_param`` message
(``ServerParam::parse`` fills them from the message; ``PlayerAgent`` parses that message at connection).
rcssserver 15.2.2 defaults are ``player_rand`` 0.1 and ``ball_rand`` 0.05; HFO's ``--deterministic`` sets both to 0.
They enter the long-step turn model (max moment 180 * (1 - player_rand)), the long-step reach test
(factor 1 - 0.01 * player_rand, noise buffers) and several ball-noise margins.

Pure float arithmetic on Python floats in the order librcsc evaluates it (so that thresholds fall the same way);
no numpy, few allocations, the source's early exits kept.
"""

from __future__ import annotations

import math
from bisect import bisect_left
from collections.abc import Iterable

from hfo2d import accel as _accel
from hfo2d.physics import ServerParams

from . import common as _common
from .common import (
    EXHAUST,
    NORMAL,
    GoalieView,
    InterceptEntry,
    InterceptTable,
    register_binder,
)

_sqrt = math.sqrt
_cos = math.cos
_sin = math.sin
_atan2 = math.atan2
_asin = math.asin
_ceil = math.ceil
_floor = math.floor
_fmod = math.fmod

_ACCEL = _accel.ACCEL  # hfo2d._accel, or None for the pure-Python code (hfo2d.accel)
_D2R = math.pi / 180.0  # librcsc AngleDeg::DEG2RAD
_R2D = 180.0 / math.pi  # librcsc AngleDeg::RAD2DEG

# --- librcsc intercept constants (not server parameters) ------------------------------------------------------
_PITCH_HALF_LENGTH = 52.5  # rcssserver serverparam: pitch_length 105
_PITCH_HALF_WIDTH = 34.0  # rcssserver serverparam: pitch_width 68
# librcsc ServerParam::ourPenaltyAreaLineX (penalty_area_length 16.5): x = -36
_PEN_LINE_X = -_PITCH_HALF_LENGTH + 16.5
_PEN_HALF_W = 40.32 * 0.5  # librcsc ServerParam::penaltyAreaHalfWidth (penalty_area_width 40.32)
_MAX_CYCLE = 30  # intercept_table.cpp InterceptTable::MAX_CYCLE
_CACHE_X_MAX = _PITCH_HALF_LENGTH + 5.0  # intercept_table.cpp createBallCache: pitch half length + 5
_CACHE_Y_MAX = _PITCH_HALF_WIDTH + 5.0  # intercept_table.cpp createBallCache: pitch half width + 5
_CONTROL_AREA_BUF = 0.15  # self_intercept_v13.cpp control_area_buf
_MAX_SHORT_STEP = 5  # self_intercept_v13.cpp MAX_SHORT_STEP
_MIN_TURN_THR = 12.5  # self_intercept_v13.cpp MIN_TURN_THR
_BACK_DASH_THR_ANGLE = 100.0  # self_intercept_v13.cpp BACK_DASH_THR_ANGLE
_EFFORT_MAX = 1.0  # effort_max (type 0; not a server parameter hfo2d has)
# The resting-ball shortcuts (cache, frame, short-step and opponent skips, predictFinal-only table) give the same
# floats as the general code; False takes the general code everywhere (the tests compare both)
_RESTING_SHORTCUTS = True


# --- server / player-type parameters (set by _bind from the goalie's ServerParams; rcssserver 15.2.2 defaults,
# player type 0, in the comments) ------------------------------------------------------------------------------
def _bind(sp: ServerParams) -> None:
    global _BALL_DECAY, _BALL_SPEED_MAX, _BALL_SIZE, _PLAYER_SIZE, _KICKABLE_MARGIN, _KICKABLE_AREA
    global _CATCHABLE_AREA, _KICK_POWER_RATE, _MAX_POWER, _MIN_DASH_POWER, _DASH_POWER_RATE, _PLAYER_DECAY
    global _PLAYER_SPEED_MAX, _PLAYER_SPEED_MAX2, _INERTIA_MOMENT, _MAX_MOMENT, _REAL_SPEED_MAX
    global _SIDE_DASH_RATE, _BACK_DASH_RATE, _DASH_ANGLE_STEP, _TACKLE_CYCLES, _STAMINA_MAX, _STAMINA_INC_MAX
    global _RECOVER_DEC_THR_VALUE, _EFFORT_DEC_THR_VALUE, _EFFORT_INC_THR_VALUE, _RECOVER_DEC, _RECOVER_MIN
    global _EFFORT_DEC, _EFFORT_INC, _EFFORT_MIN, _SAFE_STAMINA, _SAFETY_MIN, _BEST_CTRL_FWD, _BEST_CTRL_BACK
    global _BEST_CTRL_FWD2, _BEST_CTRL_BACK2, _PF, _PD, _BF, _BD, _ONE_MINUS_PD, _FT_DEN, _RESTING_FAR
    global _RESTING_FAR2, _DASH_TABLE, _DASH_TABLE_LAST, _DASH_TABLE_LEN, _ONE_DASH_RATES, _OMNI_DIRS
    _BALL_DECAY = sp.ball_decay  # rcssserver ball_decay 0.94
    _BALL_SPEED_MAX = sp.ball_speed_max  # rcssserver serverparam.cpp BALL_SPEED_MAX 3 (v12+)
    _BALL_SIZE = sp.ball_size  # rcssserver ball_size 0.085
    _PLAYER_SIZE = sp.player_size  # rcssserver player_size 0.3
    _KICKABLE_MARGIN = sp.kickable_margin  # rcssserver kickable_margin 0.7
    _KICKABLE_AREA = _PLAYER_SIZE + _KICKABLE_MARGIN + _BALL_SIZE  # librcsc PlayerType::kickableArea (1.085)
    # librcsc ServerParam::catchableArea: the diagonal of the catch area catchable_area_l 1.2 x catchable_area_w 1
    # (std::pow(x, 2) folds to x * x)
    half_w = sp.catchable_area_w * 0.5
    _CATCHABLE_AREA = _sqrt(half_w * half_w + sp.catchable_area_l * sp.catchable_area_l)
    _KICK_POWER_RATE = sp.kick_power_rate  # rcssserver kick_power_rate 0.027
    _MAX_POWER = sp.maxpower  # rcssserver maxpower 100 (also max_dash_power)
    _MIN_DASH_POWER = sp.minpower  # rcssserver minpower / min_dash_power -100
    _DASH_POWER_RATE = sp.dash_power_rate  # rcssserver dash_power_rate 0.006 (type 0)
    _PLAYER_DECAY = sp.player_decay  # rcssserver player_decay 0.4 (type 0)
    _PLAYER_SPEED_MAX = sp.player_speed_max  # rcssserver player_speed_max 1.05 (type 0)
    _PLAYER_SPEED_MAX2 = _PLAYER_SPEED_MAX * _PLAYER_SPEED_MAX
    _INERTIA_MOMENT = sp.inertia_moment  # rcssserver inertia_moment 5 (type 0)
    _MAX_MOMENT = sp.max_moment  # rcssserver maxmoment 180
    # librcsc PlayerType::realSpeedMax: min(player_speed_max, 100 * 0.006 * effort_max / (1 - decay)) = 1.0
    _REAL_SPEED_MAX = min(
        _PLAYER_SPEED_MAX, _MAX_POWER * _DASH_POWER_RATE * _EFFORT_MAX / (1.0 - _PLAYER_DECAY)
    )
    _SIDE_DASH_RATE = sp.side_dash_rate  # rcssserver side_dash_rate 0.4 (v14)
    _BACK_DASH_RATE = sp.back_dash_rate  # rcssserver back_dash_rate 0.6 (v14)
    _DASH_ANGLE_STEP = sp.dash_angle_step  # rcssserver dash_angle_step 45 (v14)
    _TACKLE_CYCLES = int(sp.tackle_cycles)  # rcssserver tackle_cycles 10

    # stamina model (rcssserver serverparam.cpp defaults, librcsc stamina_model.cpp)
    _STAMINA_MAX = sp.stamina_max  # stamina_max 8000
    _STAMINA_INC_MAX = sp.stamina_inc_max  # stamina_inc_max 45 (type 0)
    _RECOVER_DEC_THR_VALUE = sp.recover_dec_thr * _STAMINA_MAX  # recover_dec_thr 0.3 -> 2400
    _EFFORT_DEC_THR_VALUE = sp.effort_dec_thr * _STAMINA_MAX  # effort_dec_thr 0.3 -> 2400
    _EFFORT_INC_THR_VALUE = sp.effort_inc_thr * _STAMINA_MAX  # effort_inc_thr 0.6 -> 4800
    _RECOVER_DEC = sp.recover_dec  # recover_dec 0.002
    _RECOVER_MIN = sp.recover_min  # recover_min 0.5
    _EFFORT_DEC = sp.effort_dec  # effort_dec 0.005
    _EFFORT_INC = sp.effort_inc  # effort_inc 0.01
    _EFFORT_MIN = sp.effort_min  # effort_min 0.6 (type 0)
    _SAFE_STAMINA = _RECOVER_DEC_THR_VALUE + 1.0  # self_intercept_v13.cpp: recover_dec_thr + 1 (2401)

    # self_intercept_v13.cpp safety ball distance floor: player_size + ball_size + 0.4 * kickable_margin (0.665)
    _SAFETY_MIN = _PLAYER_SIZE + _BALL_SIZE + _KICKABLE_MARGIN * 0.4
    # self_intercept_v13.cpp getOneStepDashPower: best control distances in front of / behind the body
    _BEST_CTRL_FWD = _PLAYER_SIZE + 0.5 * _KICKABLE_MARGIN + _BALL_SIZE
    _BEST_CTRL_BACK = _PLAYER_SIZE + 0.3 * _KICKABLE_MARGIN + _BALL_SIZE
    _BEST_CTRL_FWD2 = _BEST_CTRL_FWD * _BEST_CTRL_FWD
    _BEST_CTRL_BACK2 = _BEST_CTRL_BACK * _BEST_CTRL_BACK

    # inertia factors (1 - d^n) / (1 - d), decay powers d^n (librcsc soccer_math.h inertia_n_step_*); n = 0 .. 100
    _PF = tuple((1.0 - _PLAYER_DECAY**n) / (1.0 - _PLAYER_DECAY) for n in range(101))
    _PD = tuple(_PLAYER_DECAY**n for n in range(101))
    _BF = tuple((1.0 - _BALL_DECAY**n) / (1.0 - _BALL_DECAY) for n in range(101))
    _BD = tuple(_BALL_DECAY**n for n in range(101))
    _ONE_MINUS_PD = 1.0 - _PLAYER_DECAY
    # calc_first_term_geom_series denominators 1 - 0.4^n
    _FT_DEN = tuple(1.0 - _PLAYER_DECAY**n for n in range(101))

    # A resting ball farther than this (squared) from the goalie: predictOneStep's reach test (|B - P| > ball speed
    # max 3 + real speed max 1 + control area <= 1.3) and predictShortStep's (|P - B| > control area + 1 * cycle for
    # every cycle <= 5) both fail, computed as _short_step computes its bound
    _RESTING_FAR = _CATCHABLE_AREA + _REAL_SPEED_MAX * _MAX_SHORT_STEP
    _RESTING_FAR2 = _RESTING_FAR * _RESTING_FAR

    _DASH_TABLE = _common.DASH_DISTANCE_TABLE
    _DASH_TABLE_LAST = _DASH_TABLE[-1]
    _DASH_TABLE_LEN = len(_DASH_TABLE)

    # relative dash directions of predictOneDash: -180, -135, ..., 135 (dash_angle_step 45, range [-180, 179))
    _ONE_DASH_RATES = tuple(_dash_dir_rate(d) for d in _ONE_DASH_DIRS)
    # predictOmniDashShort: the same grid (step max(15, 45)) without 0
    _OMNI_DIRS = tuple((d, r) for d, r in zip(_ONE_DASH_DIRS, _ONE_DASH_RATES, strict=True) if abs(d) >= 1.0)
    if _ACCEL is not None:  # the compiled kernels read the same constants
        _ACCEL.bind_intercept(_KICKABLE_AREA, _REAL_SPEED_MAX, _TACKLE_CYCLES, _PF, _DASH_TABLE)
        _ACCEL.bind_self_final(tuple(globals()[name] for name in _SELF_FINAL_NAMES), _BF, _PD, _FT_DEN)


# the constants of hfo2d._accel's self-intercept kernels (final_entry, turn_short, dash_short), in the order its C
# enum lists them
_SELF_FINAL_NAMES = (
    "_PEN_LINE_X",
    "_PEN_HALF_W",
    "_CATCHABLE_AREA",
    "_MIN_TURN_THR",
    "_MAX_MOMENT",
    "_INERTIA_MOMENT",
    "_PLAYER_DECAY",
    "_STAMINA_INC_MAX",
    "_EFFORT_MAX",
    "_MAX_POWER",
    "_RECOVER_DEC_THR_VALUE",
    "_STAMINA_MAX",
    "_RECOVER_MIN",
    "_RECOVER_DEC",
    "_EFFORT_DEC_THR_VALUE",
    "_EFFORT_MIN",
    "_EFFORT_DEC",
    "_EFFORT_INC_THR_VALUE",
    "_EFFORT_INC",
    "_CONTROL_AREA_BUF",
    "_ONE_MINUS_PD",
    "_DASH_POWER_RATE",
    "_SAFE_STAMINA",
    "_MIN_DASH_POWER",
)


def _norm(a: float) -> float:
    """AngleDeg::normalize."""
    if a < -360.0 or a > 360.0:
        a = _fmod(a, 360.0)
    if a < -180.0:
        a += 360.0
    if a > 180.0:
        a -= 360.0
    return a


def _th(x: float, y: float) -> float:
    """Vector2D::th().degree(): atan2 in degrees, 0 for the zero vector, normalised."""
    if x == 0.0 and y == 0.0:
        return 0.0
    a = _atan2(y, x) * _R2D
    if a > 180.0 or a < -180.0:
        a = _norm(a)
    return a


def _asin_deg(s: float) -> float:
    """AngleDeg::asin_deg."""
    if s >= 1.0:
        return 90.0
    if s <= -1.0:
        return -90.0
    return _asin(s) * _R2D


def _dash_dir_rate(d: float) -> float:
    """ServerParam::dashDirRate: clamp to [-180, 180], round to the 45-degree grid (rint), interpolate."""
    if d < -180.0:
        d = -180.0
    elif d > 180.0:
        d = 180.0
    d = _DASH_ANGLE_STEP * round(d / _DASH_ANGLE_STEP)
    a = abs(d)
    if a > 90.0:
        r = _BACK_DASH_RATE - (_BACK_DASH_RATE - _SIDE_DASH_RATE) * (1.0 - (a - 90.0) / 90.0)
    else:
        r = _SIDE_DASH_RATE + (1.0 - _SIDE_DASH_RATE) * (1.0 - a / 90.0)
    return min(max(1.0e-5, r), 1.0)


# relative dash directions of predictOneDash: -180, -135, ..., 135 (dash_angle_step 45, range [-180, 179)); their
# rates and the omni-dash grid are set by _bind
_ONE_DASH_DIRS = tuple(-180.0 + 45.0 * i for i in range(8))
register_binder(_bind)


def cycles_to_reach_distance(dist: float) -> int:
    """PlayerType::cyclesToReachDistance (lower_bound on the dash-distance table)."""
    if dist <= 0.001:
        return 0
    i = bisect_left(_DASH_TABLE, dist - 0.001)
    if i < _DASH_TABLE_LEN:
        return i + 1
    return _DASH_TABLE_LEN + int(_ceil((dist - _DASH_TABLE_LAST) / _REAL_SPEED_MAX))


# --- stamina model (StaminaModel::simulateWait / simulateDash) --------------------------------------------------
def _wait(st: float, ef: float, rec: float) -> tuple[float, float, float]:
    """One cycle of stamina recovery (StaminaModel::simulateWait); the capacity is assumed ample."""
    if st <= _RECOVER_DEC_THR_VALUE and rec > _RECOVER_MIN:
        rec -= _RECOVER_DEC
        if rec < _RECOVER_MIN:
            rec = _RECOVER_MIN
    if st <= _EFFORT_DEC_THR_VALUE:
        if ef > _EFFORT_MIN:
            ef -= _EFFORT_DEC
            if ef < _EFFORT_MIN:
                ef = _EFFORT_MIN
    elif st >= _EFFORT_INC_THR_VALUE and ef < _EFFORT_MAX:
        ef += _EFFORT_INC
        if ef > _EFFORT_MAX:
            ef = _EFFORT_MAX
    inc = _STAMINA_INC_MAX * rec
    room = _STAMINA_MAX - st
    st += inc if inc < room else room
    if st > _STAMINA_MAX:
        st = _STAMINA_MAX
    return st, ef, rec


def _dash(st: float, ef: float, rec: float, power: float) -> tuple[float, float, float]:
    """StaminaModel::simulateDash: pay the dash (twice its size for a back dash), then one wait."""
    st -= power if power >= 0.0 else power * -2.0
    if st < 0.0:
        st = 0.0
    return _wait(st, ef, rec)


def _waited(wt: list[tuple[float, float, float]], n: int) -> tuple[float, float, float]:
    """The goalie's stamina state after ``n`` waits (StaminaModel::simulateWaits), memoised in ``wt``."""
    while len(wt) <= n:
        s = wt[-1]
        wt.append(_wait(s[0], s[1], s[2]))
    return wt[n]


# The dash loops below inline simulateDash for the common case (stamina above the 2400 thresholds, effort at its
# maximum: then only the recovery step acts) and call _wait otherwise; both give the same numbers.


# --- public entry point ----------------------------------------------------------------------------------------
def build_intercept_table(
    view: GoalieView, player_rand: float | None = None, ball_rand: float | None = None, full: bool = True
) -> InterceptTable:
    """librcsc ``InterceptTable::update`` for the goalie's view (GF).

    ``player_rand`` / ``ball_rand`` are the server's noise parameters as the client receives them (rcssserver
    defaults 0.1 / 0.05 with noise on; 0 / 0 under HFO's ``--deterministic``). Left at None they come from the
    view's ``player_rand`` / ``ball_rand`` fields, or are 0.1 / 0.05 if the view has none.

    Returns the ball cache (``view.bx, by`` moved by ``view.wx, wy``), the goalie's candidates sorted by
    (reach cycle, turn cycles), ``self_min`` (0 when the goalie is kickable; 1000 when the first sorted
    candidate is an EXHAUST one) and ``opp_min`` (0 when ``view.kick_opp``, 1000 without an opponent).

    With ``full=False`` the self prediction stops at its first candidate: the cache then holds only the
    candidates up to the fastest one, so ``self_min`` and ``self_cache[0]`` are exact (each prediction stage adds
    at most one candidate per reach cycle, in increasing cycles), but it is not the cache that Body_Intercept's
    BestIntercept needs. Use it for the decisions that read only ``self_min`` and ``opp_min``. Such a table is
    also lazy: the ball cache and the goalie's part are computed when first read, the attacker's part too
    (many decisions read neither), from ``view`` as it is then, so ``view`` must not change in between.
    """
    if not full:
        t = _LazyTable.__new__(_LazyTable)
        t.complete = True
        t._view = view
        t._rands = (player_rand, ball_rand)  # None: the view's, resolved when the goalie part is computed
        t._ball = None
        t._self = None
        t._opp = None
        return t
    if player_rand is None:
        player_rand = getattr(view, "player_rand", 0.1)
    if ball_rand is None:
        ball_rand = getattr(view, "ball_rand", 0.05)
    ball = _ball_part(view)
    entries, self_min = _self_part(view, ball, player_rand, ball_rand, True)
    return InterceptTable(ball[0], entries, self_min, _opp_part(view, ball))


def full_self_cache(table: InterceptTable) -> list[InterceptEntry]:
    """The self cache of ``build_intercept_table(view)`` (full) for the view of a lazy table
    (``build_intercept_table(view, full=False)``), on the lazy table's ball cache: what Body_Intercept needs after
    a decision that read only ``self_min`` and ``opp_min``, without building the ball cache and the opponent's
    reach a second time. The same numbers as the full table's (the self part is a function of the view and of
    the ball cache, and the ball cache of the view's ball; a view whose ``self_kickable`` was set since has no
    self candidates either way)."""
    if not isinstance(table, _LazyTable):
        raise TypeError(
            f"full_self_cache needs a lazy table (build_intercept_table(..., full=False)), got {table!r}"
        )
    return _self_part(table._view, table._ball_now(), *table._resolved_rands(), True)[0]


def _ball_part(view: GoalieView) -> tuple[list[tuple[float, float]], bool, float, float]:
    """:func:`_ball_part_python`, computed by hfo2d._accel's kernel when it is in use (the same points)."""
    if _ACCEL is None:
        return _ball_part_python(view)
    return _ACCEL.ball_part(
        view.bx,
        view.by,
        view.wx,
        view.wy,
        view.self_kickable,
        _RESTING_SHORTCUTS,
        _BALL_DECAY,
        _CACHE_X_MAX,
        _CACHE_Y_MAX,
        _MAX_CYCLE,
    )


def _ball_part_python(view: GoalieView) -> tuple[list[tuple[float, float]], bool, float, float]:
    """createBallCache (empty past B for a kickable goalie), whether the ball rests, and sin, cos of -angle(W):
    the frame along the ball's velocity that the short-step, long-step and opponent predictions share."""
    bx = view.bx
    by = view.by
    wx = view.wx
    wy = view.wy
    cache: list[tuple[float, float]] = [(bx, by)]
    resting = wx == 0.0 and wy == 0.0 and _RESTING_SHORTCUTS
    if resting:
        sin_a = -0.0  # a resting ball: angle 0, rotated by -0.0
        cos_a = 1.0
    else:
        a = -_th(wx, wy) * _D2R
        sin_a = _sin(a)
        cos_a = _cos(a)
    if view.self_kickable:
        pass  # createBallCache stops at the current position
    elif resting:
        # createBallCache for a resting ball: every step adds +-0, so the position after the first step repeats
        # (B + W keeps a -0.0 only when both are -0.0, as x += v does) and the speed test ends the cache after
        # five steps, unless the first step is already off the cached area
        x = bx + wx
        y = by + wy
        p = (x, y)
        cache.append(p)
        if not (abs(x) > _CACHE_X_MAX or abs(y) > _CACHE_Y_MAX):
            cache += (p, p, p, p)
    else:
        x = bx
        y = by
        vx = wx
        vy = wy
        append = cache.append
        decay = _BALL_DECAY
        x_max = _CACHE_X_MAX
        y_max = _CACHE_Y_MAX
        for i in range(1, _MAX_CYCLE + 1):
            x += vx
            y += vy
            vx *= decay
            vy *= decay
            append((x, y))
            if i >= 5 and vx * vx + vy * vy < 0.01 * 0.01:
                break
            if abs(x) > x_max or abs(y) > y_max:
                break
    return cache, resting, sin_a, cos_a


def _self_part(
    view: GoalieView, ball: tuple, player_rand: float, ball_rand: float, full: bool
) -> tuple[list[InterceptEntry], int]:
    """predictSelf: the sorted candidates and self_min."""
    if view.self_kickable:
        return [], 0  # predictSelf answers 0 without candidates
    cache, resting, sin_a, cos_a = ball
    entries: list[InterceptEntry] = []
    bx = view.bx
    by = view.by
    max_cycle = min(_MAX_CYCLE, len(cache))
    px = view.px
    py = view.py
    if resting and (px - bx) * (px - bx) + (py - by) * (py - by) > _RESTING_FAR2:
        # the common case of a resting ball out of the short-step reach: predictOneStep and predictShortStep find
        # nothing (their distance tests fail, see _RESTING_FAR2) and predictLongStep has no cycle to try (it
        # starts after the short steps, at 6 or later, and a resting ball's cache ends at 6), so the table holds
        # predictFinal's entry alone
        vx = view.vx
        vy = view.vy
        first = _final_entry(
            px,
            py,
            vx,
            vy,
            _norm(view.body),
            _sqrt(vx * vx + vy * vy),
            view.lk_not_ours,
            bx,
            by,
            view.wx,
            view.wy,
            [(view.stamina, view.effort, view.recovery)],
            max_cycle,
            player_rand,
        )
        reach = first.turn_cycle + first.dash_cycle  # a NORMAL entry
        return [first], reach if reach < 1000 else 1000
    rel_y = (px - bx) * sin_a + (py - by) * cos_a
    _predict_self(view, max_cycle, entries, player_rand, ball_rand, full, rel_y)
    # std::sort by (reach, turns); with at most 16 entries libstdc++ sorts by insertion, i.e. stably
    if len(entries) > 1:
        entries.sort(key=_sort_key)
    self_min = 1000
    if entries:
        first = entries[0]
        if first.mode == NORMAL:
            reach = first.turn_cycle + first.dash_cycle
            if reach < 1000:
                self_min = reach
    return entries, self_min


def _opp_part(view: GoalieView, ball: tuple) -> int:
    """opp_min: 0 with a kickable attacker, 1000 without one, else PlayerIntercept's reach cycle."""
    if view.kick_opp:
        return 0
    if not view.has_opp:
        return 1000
    cache, _, sin_a, cos_a = ball
    reach = min(
        1000, _predict_opponent(view, cache, (view.ox - view.bx) * sin_a + (view.oy - view.by) * cos_a)
    )
    # InterceptTable::update takes the fastest of all opponents: a team game's goalie view lists the others
    # (hfo2d.agent2d.goalie; unset with one attacker)
    others = getattr(view, "other_opponents", None)
    if others:
        reach = fastest_reach(view, ball, others, False, reach)
    return reach


class _LazyTable(InterceptTable):
    """The ``full=False`` table: ball cache, goalie part and attacker part computed on first read (exactly what
    the eager table holds). Assigning a field fixes it."""

    __slots__ = ("_view", "_rands", "_ball", "_self", "_opp")

    def _ball_now(self) -> tuple:
        ball = self._ball
        if ball is None:
            ball = self._ball = _ball_part(self._view)
        return ball

    def ball_part(self) -> tuple:
        """The ball part (cache, resting, sin, cos of -angle(W)) that :func:`fastest_reach` reads."""
        return self._ball_now()

    def _resolved_rands(self) -> tuple[float, float]:
        """(player_rand, ball_rand): the ones given, else the view's, else rcssserver's defaults 0.1 and 0.05."""
        player_rand, ball_rand = self._rands
        if player_rand is None:
            player_rand = getattr(self._view, "player_rand", 0.1)
        if ball_rand is None:
            ball_rand = getattr(self._view, "ball_rand", 0.05)
        return player_rand, ball_rand

    def _self_now(self) -> tuple[list[InterceptEntry], int]:
        part = self._self
        if part is None:
            part = self._self = _self_part(self._view, self._ball_now(), *self._resolved_rands(), False)
        return part

    @property  # type: ignore[override]
    def ball_cache(self) -> list[tuple[float, float]]:
        return self._ball_now()[0]

    @ball_cache.setter
    def ball_cache(self, value: list[tuple[float, float]]) -> None:
        ball = self._ball_now()
        self._ball = (value, *ball[1:])

    @property  # type: ignore[override]
    def self_cache(self) -> list[InterceptEntry]:
        return self._self_now()[0]

    @self_cache.setter
    def self_cache(self, value: list[InterceptEntry]) -> None:
        self._self = (value, self._self_now()[1])

    @property  # type: ignore[override]
    def self_min(self) -> int:
        return self._self_now()[1]

    @self_min.setter
    def self_min(self, value: int) -> None:
        self._self = (self._self_now()[0], value)

    @property  # type: ignore[override]
    def opp_min(self) -> int:
        opp = self._opp
        if opp is None:
            opp = self._opp = _opp_part(self._view, self._ball_now())
        return opp

    @opp_min.setter
    def opp_min(self, value: int) -> None:
        self._opp = value


def _sort_key(e: InterceptEntry) -> tuple[int, int]:
    return (e.turn_cycle + e.dash_cycle, e.turn_cycle)


# --- SelfInterceptV13 -------------------------------------------------------------------------------------------
# ``me`` bundles the goalie and ball state every part reads:
# (px, py, vx, vy, body, speed, lk_not_ours, bx, by, wx, wy, recovery)


def _predict_self(
    view: GoalieView,
    max_cycle: int,
    out: list[InterceptEntry],
    player_rand: float,
    ball_rand: float,
    full: bool,
    rel_y: float,
) -> None:
    """SelfInterceptV13::predict (save_recovery on: the stamina capacity is never 0 in HFO).

    ``rel_y``: the goalie's offset from the ball's line of motion, (P - B) rotated by -angle(W), which the
    short-step and long-step predictions both start from.
    """
    vx = view.vx
    vy = view.vy
    me = (
        view.px,
        view.py,
        vx,
        vy,
        _norm(view.body),
        _sqrt(vx * vx + vy * vy),
        view.lk_not_ours,
        view.bx,
        view.by,
        view.wx,
        view.wy,
        view.recovery,
    )
    wt = [(view.stamina, view.effort, view.recovery)]
    _one_step(me, wt, out, ball_rand)
    if not full and out:
        return  # reach 1: nothing can be faster
    _short_step(me, wt, max_cycle, out, ball_rand, full, rel_y)
    if not full and out and out[-1].turn_cycle + out[-1].dash_cycle < max_cycle:
        return  # the long-step and final candidates all need at least max_cycle cycles
    _long_step(me, wt, max_cycle, out, player_rand, ball_rand, full, rel_y)


def _one_step(me: tuple, wt: list, out: list[InterceptEntry], ball_rand: float) -> None:
    """predictOneStep: predictNoDash, else predictOneDash."""
    px, py, vx, vy, body, _, lk, bx, by, wx, wy, _ = me
    nbx = bx + wx
    nby = by + wy
    goalie_mode = lk and nbx < _PEN_LINE_X and abs(nby) < _PEN_HALF_W
    ca = _CATCHABLE_AREA if goalie_mode else _KICKABLE_AREA
    dx = bx - px
    dy = by - py
    if _sqrt(dx * dx + dy * dy) > _BALL_SPEED_MAX + _REAL_SPEED_MAX + ca:
        return
    mnx = px + vx
    mny = py + vy

    # predictNoDash: the ball comes into the control area while the goalie only drifts
    rx = nbx - mnx
    ry = nby - mny
    c = _cos(-body * _D2R)
    s = _sin(-body * _D2R)
    relx = rx * c - ry * s
    rely = rx * s + ry * c
    ball_speed = _sqrt(wx * wx + wy * wy)
    next_dist = _sqrt(relx * relx + rely * rely)
    if next_dist <= ca - 0.15 - ball_speed * ball_rand:
        ok = True
        if not goalie_mode and next_dist > _PLAYER_SIZE + _BALL_SIZE:
            # a kickable (non-goalie) stop needs enough kick power to stop the ball
            kick_rate = _KICK_POWER_RATE * (
                1.0
                - 0.25 * abs(_th(relx, rely)) / 180.0
                - (0.25 * (next_dist - _BALL_SIZE - _PLAYER_SIZE) / _KICKABLE_MARGIN)
            )
            nvx = wx * _BALL_DECAY
            nvy = wy * _BALL_DECAY
            if _MAX_POWER * kick_rate <= _sqrt(nvx * nvx + nvy * nvy) * _BALL_DECAY * 1.1:
                ok = False
        if ok:
            out.append(InterceptEntry(NORMAL, 1, 0, 0.0, 0.0, mnx, mny, next_dist, _waited(wt, 1)[0]))
            return

    # predictOneDash
    st, ef, rec = wt[0]
    dash_rate0 = ef * _DASH_POWER_RATE  # SelfObject::dashRate
    avail = st - _RECOVER_DEC_THR_VALUE - 1.0
    fwd_power = min(max(0.0, avail), _MAX_POWER)
    back_power = min(max(_MIN_DASH_POWER, avail * -0.5), 0.0)
    full_powers = abs(fwd_power - _MAX_POWER) < 1.0 and abs(back_power - _MIN_DASH_POWER) < 1.0
    safety = max(ca - 0.2 - ball_speed * ball_rand, _SAFETY_MIN)
    best = None
    for k in range(8):
        dash_angle = _norm(body + _ONE_DASH_DIRS[k])
        rate = dash_rate0 * _ONE_DASH_RATES[k]
        cand = _one_dash_adjust(
            me, wt, dash_angle, fwd_power * rate, back_power * rate, nbx, nby, mnx, mny, ca
        )
        if cand is None and not full_powers:
            cand = _one_dash_adjust(
                me, wt, dash_angle, _MAX_POWER * rate, _MIN_DASH_POWER * rate, nbx, nby, mnx, mny, ca
            )
        if cand is None:
            continue
        if best is None:
            best = cand
            continue
        # the running best is replaced only by a strictly better later candidate
        if best[7] < safety and cand[7] < safety:
            if best[8] < cand[8]:
                best = cand
        elif best[7] > cand[7] or (abs(best[7] - cand[7]) < 0.001 and best[8] < cand[8]):
            best = cand
    if best is not None:
        out.append(InterceptEntry(*best))


def _normalize_accel(vx: float, vy: float, ax: float, ay: float) -> tuple[float, float]:
    """PlayerType::normalizeAccel (vector form): cap the resulting speed at player_speed_max."""
    sx = vx + ax
    sy = vy + ay
    if sx * sx + sy * sy > _PLAYER_SPEED_MAX2 + 0.0001:
        a = -_th(ax, ay) * _D2R
        c = _cos(a)
        s = _sin(a)
        rvx = vx * c - vy * s
        rvy = vx * s + vy * c
        length = _sqrt(_PLAYER_SPEED_MAX2 - rvy * rvy) - rvx
        mag = _sqrt(ax * ax + ay * ay)
        if mag >= 1.0e-6:  # Vector2D::setLength leaves tiny vectors alone
            k = length / mag
            ax *= k
            ay *= k
    return ax, ay


def _one_dash_adjust(
    me: tuple,
    wt: list,
    dash_angle: float,
    fwd_mag: float,
    back_mag: float,
    nbx: float,
    nby: float,
    mnx: float,
    mny: float,
    ca: float,
) -> tuple | None:
    """predictOneDashAdjust for one dash direction: the candidate tuple, or None."""
    px, py, vx, vy, body, _, _, _, _, _, _, _ = me
    control_buf = ca - 0.075
    c = _cos(-dash_angle * _D2R)
    s = _sin(-dash_angle * _D2R)
    rx = nbx - mnx
    ry = nby - mny
    bry = rx * s + ry * c
    if abs(bry) > control_buf:  # (librcsc normalises the accelerations first; that has no side effect)
        return None
    brx = rx * c - ry * s
    cos_a = _cos(dash_angle * _D2R)
    sin_a = _sin(dash_angle * _D2R)
    fax, fay = _normalize_accel(vx, vy, fwd_mag * cos_a, fwd_mag * sin_a)
    bax, bay = _normalize_accel(vx, vy, back_mag * cos_a, back_mag * sin_a)
    f_x = fax * c - fay * s
    f_y = fax * s + fay * c
    b_x = bax * c - bay * s
    b_y = bax * s + bay * c
    # Segment2D(forward, back).dist(ball)
    sgx = b_x - f_x
    sgy = b_y - f_y
    seg_len = _sqrt(sgx * sgx + sgy * sgy)  # Segment2D::length (a dist)
    if seg_len == 0.0:
        seg_dist = _sqrt((f_x - brx) * (f_x - brx) + (f_y - bry) * (f_y - bry))
    else:
        prod = sgx * (brx - f_x) + sgy * (bry - f_y)
        if 0.0 <= prod <= seg_len * seg_len:
            area = (f_x - brx) * (b_y - bry) + (b_x - brx) * (bry - f_y)
            seg_dist = abs(area / seg_len)
        else:
            d1 = (f_x - brx) * (f_x - brx) + (f_y - bry) * (f_y - bry)
            d2 = (b_x - brx) * (b_x - brx) + (b_y - bry) * (b_y - bry)
            seg_dist = _sqrt(d1 if d1 < d2 else d2)
    if seg_dist > control_buf:
        return None

    st, ef, rec = wt[0]
    dash_dir = _norm(dash_angle - body)
    dash_rate = ef * _DASH_POWER_RATE * _dash_dir_rate(dash_dir)
    power = -1000.0
    if b_x < brx < f_x:
        power = _one_step_power(ef, brx, bry, dash_angle, f_x, b_x)
    if (
        power < -999.0
        and f_x < brx
        and _sqrt((brx - f_x) * (brx - f_x) + (bry - f_y) * (bry - f_y)) < control_buf
    ):
        power = f_x / dash_rate
    if (
        power < -999.0
        and brx < b_x
        and _sqrt((brx - b_x) * (brx - b_x) + (bry - b_y) * (bry - b_y)) < control_buf
    ):
        power = b_x / dash_rate
    if power < -999.0 and b_x < brx < f_x:
        power = brx / dash_rate
    if power < -999.0:
        return None

    acc = power * dash_rate
    myx = px + (vx + acc * cos_a)
    myy = py + (vy + acc * sin_a)
    st, _, _ = _dash(st, ef, rec, power)
    mode = EXHAUST if st < _RECOVER_DEC_THR_VALUE else NORMAL
    return (
        mode,
        0,
        1,
        power,
        dash_dir,
        myx,
        myy,
        _sqrt((myx - nbx) * (myx - nbx) + (myy - nby) * (myy - nby)),
        st,
    )


def _one_step_power(
    ef: float, relx: float, rely: float, dash_angle: float, fwd_x: float, back_x: float
) -> float:
    """getOneStepDashPower: the smallest power that leaves the ball at a good control distance.

    (quirk) librcsc takes the dash-direction rate of the *absolute* dash angle here.
    """
    rate = ef * _DASH_POWER_RATE * _dash_dir_rate(dash_angle)
    if abs(rely) > _BEST_CTRL_FWD:
        return relx / rate
    y2 = rely * rely
    back_room = _BEST_CTRL_BACK2 - y2
    if back_room < 0.0:
        # the square root of a negative number: NaN bounds, so librcsc's trial loop never runs
        return -1000.0
    lo = relx - _sqrt(_BEST_CTRL_FWD2 - y2)
    hi = relx + _sqrt(back_room)
    step = (hi - lo) / 5.0  # > 0 here
    min_power = 10000.0
    ax = lo
    while ax < hi + 0.01:
        if (ax >= 0.0 and fwd_x > ax) or (ax < 0.0 and back_x < ax):
            p = ax / rate
            if abs(p) < abs(min_power):
                min_power = p
        ax += step
    if min_power < 1000.0:
        return min_power
    return -1000.0


def _short_step(
    me: tuple, wt: list, max_cycle: int, out: list[InterceptEntry], ball_rand: float, full: bool, rel_y: float
) -> None:
    """predictShortStep: reach cycles 2..5 by turn-then-dash (forward and back) and, up to 2, omni dashes.

    Each TurnDashShort variant whose turn result repeats the previous variant's is skipped: its candidates would
    be exact copies, and a copy never replaces the running best.
    """
    px, py, vx, vy, body, speed, lk, bx, by, wx, wy, _ = me
    max_loop = min(_MAX_SHORT_STEP, max_cycle)
    min_cycle = int(_ceil((abs(rel_y) - _KICKABLE_AREA) / _REAL_SPEED_MAX))
    if min_cycle >= max_loop:
        return
    if wx == 0.0 and wy == 0.0 and _RESTING_SHORTCUTS:
        # a resting ball stays at B: if even the largest control area (catchable 1.3 > kickable 1.085) plus the
        # longest run leaves it out of reach, every cycle below skips it (rounding is monotonic)
        lim = _CATCHABLE_AREA + _REAL_SPEED_MAX * max_loop
        if lim * lim < (px - bx) * (px - bx) + (py - by) * (py - by):
            return
    if min_cycle < 2:
        min_cycle = 2
    f = _BF[min_cycle - 1]
    xbx = bx + wx * f
    xby = by + wy * f
    k = _BD[min_cycle - 1]
    bvx = wx * k
    bvy = wy * k
    pen_x = _PEN_LINE_X - 0.5
    pen_y = _PEN_HALF_W - 0.5
    back_body = _norm(body + 180.0)
    tmp: list[tuple] = []
    for cycle in range(min_cycle, max_loop + 1):
        xbx += bvx
        xby += bvy
        bvx *= _BALL_DECAY
        bvy *= _BALL_DECAY
        goalie_mode = lk and xbx < pen_x and abs(xby) < pen_y
        ca = _CATCHABLE_AREA if goalie_mode else _KICKABLE_AREA
        if (ca + _REAL_SPEED_MAX * cycle) * (ca + _REAL_SPEED_MAX * cycle) < (px - xbx) * (px - xbx) + (
            py - xby
        ) * (py - xby):
            continue
        tmp.clear()
        f = _PF[cycle]
        ix = px + vx * f
        iy = py + vy * f
        tx = xbx - ix
        ty = xby - iy
        target_dist = _sqrt(tx * tx + ty * ty)
        target_angle = _th(tx, ty)
        area_far = max(0.1, ca - 0.4)
        area_near = ca - _CONTROL_AREA_BUF
        # forward: margins from max(0.1, CA - 0.4) and max(0.1, CA - 0.15)
        t1 = _turn_short(target_angle, target_dist, body, speed, area_far)
        if t1[0] <= cycle:
            _dash_short(me, wt, cycle, t1[0], t1[1], False, xbx, xby, ca, ix, iy, target_angle, tmp)
        t2 = _turn_short(target_angle, target_dist, body, speed, max(0.1, area_near))
        if t2 != t1 and t2[0] <= cycle:
            _dash_short(me, wt, cycle, t2[0], t2[1], False, xbx, xby, ca, ix, iy, target_angle, tmp)
        # back: margins from max(0.1, CA - 0.4) and CA - 0.15
        t3 = _turn_short(target_angle, target_dist, back_body, speed, area_far)
        if t3[0] <= cycle:
            _dash_short(me, wt, cycle, t3[0], t3[1], True, xbx, xby, ca, ix, iy, target_angle, tmp)
        t4 = _turn_short(target_angle, target_dist, back_body, speed, area_near)
        if t4 != t3 and t4[0] <= cycle:
            _dash_short(me, wt, cycle, t4[0], t4[1], True, xbx, xby, ca, ix, iy, target_angle, tmp)
        if cycle <= 2:
            _omni_dash_short(me, wt, cycle, xbx, xby, ca, ix, iy, target_angle, tmp)
        if not tmp:
            continue
        best = tmp[0]
        if len(tmp) > 1:
            safety = max(
                ca - 0.2 - _sqrt((bx - xbx) * (bx - xbx) + (by - xby) * (by - xby)) * ball_rand, _SAFETY_MIN
            )
            for i in range(1, len(tmp)):
                cand = tmp[i]
                if best[7] < safety and cand[7] < safety:
                    if best[1] > cand[1] or (best[1] == cand[1] and best[8] < cand[8]):
                        best = cand
                elif best[1] >= cand[1] and (
                    best[7] > cand[7] or (abs(best[7] - cand[7]) < 0.001 and best[8] < cand[8])
                ):
                    best = cand
        out.append(InterceptEntry(*best))
        if not full:
            return


def _turn_short_python(
    target_angle: float, target_dist: float, body_angle: float, speed: float, turn_area: float
) -> tuple[int, float]:
    """predictTurnCycleShort (full max moment, no player_rand): turns and the resulting dash angle.

    ``body_angle`` is the body angle, or the body angle + 180 for a back dash.
    """
    signed = _norm(target_angle - body_angle)
    diff = abs(signed)
    margin = 180.0
    if turn_area < target_dist:
        margin = _asin_deg(turn_area / target_dist)
        if margin < _MIN_TURN_THR:
            margin = _MIN_TURN_THR
    if diff <= margin:
        return 0, body_angle
    n_turn = 0
    s = speed
    while diff > margin:
        diff -= _MAX_MOMENT / (1.0 + _INERTIA_MOMENT * s)
        s *= _PLAYER_DECAY
        n_turn += 1
    if diff < 0.0:
        diff = 0.0
    return n_turn, (_norm(target_angle - diff) if signed > 0.0 else _norm(target_angle + diff))


def _dash_short(
    me: tuple,
    wt: list,
    cycle: int,
    n_turn: int,
    dash_angle: float,
    back: bool,
    xbx: float,
    xby: float,
    ca: float,
    ix: float,
    iy: float,
    target_angle: float,
    tmp: list[tuple],
) -> None:
    """:func:`_dash_short_python`, computed by hfo2d._accel's kernel when it is in use (the same candidates; the
    kernel simulates the waits from ``wt[0]`` instead of reading and extending the memo ``wt``)."""
    if _ACCEL is None:
        _dash_short_python(me, wt, cycle, n_turn, dash_angle, back, xbx, xby, ca, ix, iy, target_angle, tmp)
        return
    stamina, effort, recovery = wt[0]
    tmp += _ACCEL.dash_short(
        me[0],
        me[1],
        me[2],
        me[3],
        stamina,
        effort,
        recovery,
        cycle,
        n_turn,
        dash_angle,
        back,
        xbx,
        xby,
        ca,
        ix,
        iy,
        target_angle,
    )


def _dash_short_python(
    me: tuple,
    wt: list,
    cycle: int,
    n_turn: int,
    dash_angle: float,
    back: bool,
    xbx: float,
    xby: float,
    ca: float,
    ix: float,
    iy: float,
    target_angle: float,
    tmp: list[tuple],
) -> None:
    """predictDashCycleShort: the candidate of waiting (if the drift suffices) and of dashing after the turns."""
    px, py, vx, vy, _, _, _, _, _, _, _, _ = me
    max_dash = cycle - n_turn
    ctrl2 = (ca - _CONTROL_AREA_BUF) * (ca - _CONTROL_AREA_BUF)
    d2 = (ix - xbx) * (ix - xbx) + (iy - xby) * (iy - xby)
    if d2 < ctrl2:
        tmp.append((NORMAL, n_turn, max_dash, 0.0, 0.0, ix, iy, _sqrt(d2), _waited(wt, cycle)[0]))
    if abs(_norm(target_angle - dash_angle)) > 90.0:
        return
    st, ef, rec = _waited(wt, n_turn)
    g = _PF[n_turn]
    mx = px + vx * g
    my = py + vy * g
    d = _PD[n_turn]
    mvx = vx * d
    mvy = vy * d
    ux = _cos(dash_angle * _D2R)
    uy = _sin(dash_angle * _D2R)
    rc = _cos(-dash_angle * _D2R)
    rs = _sin(-dash_angle * _D2R)
    first_power = 0.0
    for n_dash in range(1, max_dash + 1):
        first_speed = ((xbx - mx) * rc - (xby - my) * rs) * _ONE_MINUS_PD / _FT_DEN[max_dash - n_dash + 1]
        rate = ef * _DASH_POWER_RATE
        power = (first_speed - (mvx * rc - mvy * rs)) / rate
        avail = st - _SAFE_STAMINA
        if avail < 0.0:
            avail = 0.0
        if back:
            power = -power
            if power < _MIN_DASH_POWER:
                power = _MIN_DASH_POWER
            elif power > 0.0:
                power = 0.0
            if power < avail * -0.5:
                power = avail * -0.5
            st -= power * -2.0
        else:
            if power < 0.0:
                power = 0.0
            elif power > _MAX_POWER:
                power = _MAX_POWER
            if avail < power:
                power = avail
            st -= power
        if n_dash == 1:
            first_power = power
        acc = abs(power * rate)
        mvx += ux * acc
        mvy += uy * acc
        mx += mvx
        my += mvy
        mvx *= _PLAYER_DECAY
        mvy *= _PLAYER_DECAY
        # simulateDash (the payment is above)
        if st < 0.0:
            st = 0.0
        if st > _RECOVER_DEC_THR_VALUE and ef >= _EFFORT_MAX:
            inc = _STAMINA_INC_MAX * rec
            room = _STAMINA_MAX - st
            st += inc if inc < room else room
            if st > _STAMINA_MAX:
                st = _STAMINA_MAX
        else:
            st, ef, rec = _wait(st, ef, rec)
    d2 = (mx - xbx) * (mx - xbx) + (my - xby) * (my - xby)
    if d2 < ctrl2 or (px - mx) * (px - mx) + (py - my) * (py - my) > (px - xbx) * (px - xbx) + (py - xby) * (
        py - xby
    ):
        mode = EXHAUST if st < _RECOVER_DEC_THR_VALUE else NORMAL
        tmp.append((mode, n_turn, max_dash, first_power, 0.0, mx, my, _sqrt(d2), st))


def _omni_dash_short(
    me: tuple,
    wt: list,
    cycle: int,
    xbx: float,
    xby: float,
    ca: float,
    ix: float,
    iy: float,
    target_angle: float,
    tmp: list[tuple],
) -> None:
    """predictOmniDashShort (forward only) with predictAdjustOmniDash: side dashes onto the ball's body line."""
    px, py, vx, vy, body, _, _, _, _, _, _, recovery = me
    # Line2D(ball point, body angle): a x + b y + c = 0
    la = -_sin(body * _D2R)
    lb = _cos(body * _D2R)
    lc = -la * xbx - lb * xby
    lnorm = _sqrt(la * la + lb * lb)
    if abs((la * ix + lb * iy + lc) / lnorm) < ca - 0.4:
        return
    ctrl = ca - _CONTROL_AREA_BUF
    ctrl2 = ctrl * ctrl
    brc = _cos(-body * _D2R)
    brs = _sin(-body * _D2R)
    max_omni = min(2, cycle)
    st0, ef0, rec0 = wt[0]
    for rel_dir, dir_rate in _OMNI_DIRS:
        dash_angle = _norm(body + rel_dir)
        if abs(_norm(dash_angle - target_angle)) > 91.0:
            continue
        mx = px
        my = py
        mvx = vx
        mvy = vy
        st = st0
        ef = ef0
        rec = rec0
        first_power = 0.0
        ux = _cos(dash_angle * _D2R)
        uy = _sin(dash_angle * _D2R)
        rc = _cos(-dash_angle * _D2R)
        rs = _sin(-dash_angle * _D2R)
        # predictAdjustOmniDash
        n_omni = -1
        for n in range(1, max_omni + 1):
            line_dist = abs((la * mx + lb * my + lc) / lnorm)
            required = line_dist * _ONE_MINUS_PD / _FT_DEN[cycle - n + 1] - (mvx * rc - mvy * rs)
            if abs(required) < 0.01:
                n_omni = n - 1
                break
            power = required / (ef * _DASH_POWER_RATE * dir_rate)
            avail = st - _SAFE_STAMINA
            if avail < 0.0:
                avail = 0.0
            power = min(max(0.0, power), _MAX_POWER)
            if avail < power:
                power = avail
            if n == 1:
                first_power = power
            acc = abs(power) * (ef * _DASH_POWER_RATE) * dir_rate
            mvx += ux * acc
            mvy += uy * acc
            mx += mvx
            my += mvy
            mvx *= _PLAYER_DECAY
            mvy *= _PLAYER_DECAY
            st, ef, rec = _dash(st, ef, rec, power)
            g = _PF[cycle - n]
            if abs((la * (mx + mvx * g) + lb * (my + mvy * g) + lc) / lnorm) < ctrl:
                n_omni = n
                break
        if n_omni <= 0:
            continue
        g = _PF[cycle - n_omni]
        tgx = xbx - (mx + mvx * g)
        tgy = xby - (my + mvy * g)
        if tgx * brc - tgy * brs < 0.0:  # the ball point lies behind the body after the side dashes
            continue
        for n_dash in range(n_omni + 1, cycle + 1):
            first_speed = ((xbx - mx) * brc - (xby - my) * brs) * _ONE_MINUS_PD / _FT_DEN[cycle - n_dash + 1]
            rate = ef * _DASH_POWER_RATE
            power = (first_speed - (mvx * brc - mvy * brs)) / rate
            avail = st - _SAFE_STAMINA
            if avail < 0.0:
                avail = 0.0
            power = min(max(0.0, power), _MAX_POWER)
            if avail < power:
                power = avail
            acc = abs(power) * rate
            mvx += lb * acc  # unit vector of the body angle: (cos, sin) = (lb, -la)
            mvy += -la * acc
            mx += mvx
            my += mvy
            mvx *= _PLAYER_DECAY
            mvy *= _PLAYER_DECAY
            st, ef, rec = _dash(st, ef, rec, power)
        movx = mx - px
        movy = my - py
        d2 = (mx - xbx) * (mx - xbx) + (my - xby) * (my - xby)
        move_len = _sqrt(movx * movx + movy * movy)
        ma = -_th(movx, movy) * _D2R
        along = (xbx - px) * _cos(ma) - (xby - py) * _sin(ma)
        if d2 < ctrl2 or move_len > abs(along):
            mode = EXHAUST if rec < recovery else NORMAL
            tmp.append((mode, 0, cycle, first_power, rel_dir, mx, my, _sqrt(d2), st))


def _long_step(
    me: tuple,
    wt: list,
    max_cycle: int,
    out: list[InterceptEntry],
    player_rand: float,
    ball_rand: float,
    full: bool,
    rel_y: float,
) -> None:
    """predictLongStep (save_recovery on), then predictFinal when nothing was reachable."""
    px, py, _, _, _, _, lk, bx, by, wx, wy, _ = me
    start = int(_ceil((abs(rel_y) - _KICKABLE_AREA - 0.2) / _REAL_SPEED_MAX))
    if start <= _MAX_SHORT_STEP:
        start = _MAX_SHORT_STEP + 1
    found = False
    if start < max_cycle:
        f = _BF[start - 1]
        xbx = bx + wx * f
        xby = by + wy * f
        k = _BD[start - 1]
        bvx = wx * k
        bvy = wy * k
        max_loop = max_cycle
        cycle = start
        while cycle < max_loop:
            xbx += bvx
            xby += bvy
            bvx *= _BALL_DECAY
            bvy *= _BALL_DECAY
            if abs(xbx) > _PITCH_HALF_LENGTH + 10.0 or abs(xby) > _PITCH_HALF_WIDTH + 10.0:
                break
            goalie_mode = lk and xbx < _PEN_LINE_X and abs(xby) < _PEN_HALF_W
            ca = _CATCHABLE_AREA if goalie_mode else _KICKABLE_AREA
            if ca + _REAL_SPEED_MAX * cycle < _sqrt((px - xbx) * (px - xbx) + (py - xby) * (py - xby)):
                cycle += 1
                continue
            n_turn, dash_angle, back = _turn_cycle(me, wt, cycle, xbx, xby, ca, player_rand)
            if n_turn <= cycle and _can_reach_after_dash(
                me, wt, n_turn, cycle - n_turn, xbx, xby, ca, dash_angle, back, out, player_rand, ball_rand
            ):
                if not found:
                    max_loop = min(max_cycle, cycle + 10) if full else cycle + 1
                found = True
            cycle += 1
    if not found or not out:
        _predict_final(me, wt, max_cycle, out, player_rand)


def _turn_cycle(
    me: tuple, wt: list, cycle: int, xbx: float, xby: float, ca: float, player_rand: float
) -> tuple[int, float, bool]:
    """predictTurnCycle: turns needed before dashing at the ball point, the dash angle, the back-dash flag."""
    px, py, vx, vy, body, speed, lk, bx, by, wx, wy, recovery = me
    f = _PF[cycle]
    tx = xbx - (px + vx * f)
    ty = xby - (py + vy * f)
    target_angle = _th(tx, ty)
    signed = _norm(target_angle - body)
    diff = abs(signed)
    target_dist = _sqrt(tx * tx + ty * ty)
    margin = 180.0
    control_buf = max(0.5, ca - 0.25)
    if control_buf < target_dist:
        margin = _asin_deg(control_buf / target_dist)
    if margin < _MIN_TURN_THR:
        margin = _MIN_TURN_THR
    dash_angle = body
    back = False
    if diff >= _BACK_DASH_THR_ANGLE:
        # canBackDashChase: a back dash only for short chases, or near the own goal for the goalie
        ok = True
        if cycle >= 5:
            if not lk or cycle >= 15:
                ok = False
            else:
                g = _BF[cycle]
                gx = -_PITCH_HALF_LENGTH - (bx + wx * g)
                gy = 0.0 - (by + wy * g)
                if _sqrt(gx * gx + gy * gy) > 21.0:
                    ok = False
        if ok:
            st0 = wt[0][0]
            result = st0 - (-_MIN_DASH_POWER * 2.0 * cycle) + _STAMINA_INC_MAX * recovery * (cycle - 1)
            if result >= _RECOVER_DEC_THR_VALUE + 205.0:
                back = True
                dash_angle = _norm(body + 180.0)
                diff = 180.0 - diff
    if diff <= margin:
        return 0, dash_angle, back
    # the long-step turn model shrinks the max moment by player_rand
    max_moment = _MAX_MOMENT * (1.0 - player_rand)
    n_turn = 0
    s = speed
    while diff > margin:
        diff -= max_moment / (1.0 + _INERTIA_MOMENT * s)
        s *= _PLAYER_DECAY
        n_turn += 1
    if diff < 0.0:
        diff = 0.0
    return n_turn, _norm(target_angle + (diff if signed > 0.0 else -diff)), back


def _can_reach_after_dash(
    me: tuple,
    wt: list,
    n_turn: int,
    n_dash: int,
    xbx: float,
    xby: float,
    ca: float,
    dash_angle: float,
    back: bool,
    out: list[InterceptEntry],
    player_rand: float,
    ball_rand: float,
) -> bool:
    """canReachAfterDash: full-power dashes along the dash angle, in the frame rotated by -dash_angle."""
    px, py, vx, vy, _, _, _, bx, by, _, _, recovery = me
    noise_rate = 1.0 - player_rand * 0.01
    rc = _cos(-dash_angle * _D2R)
    rs = _sin(-dash_angle * _D2R)
    dx = xbx - px
    dy = xby - py
    brx = dx * rc - dy * rs
    ball_noise = _sqrt((bx - xbx) * (bx - xbx) + (by - xby) * (by - xby)) * ball_rand * 0.5
    noised_x = brx + ball_noise
    g = _PF[n_turn]
    tx0 = vx * g
    ty0 = vy * g
    tpx = tx0 * rc - ty0 * rs
    tpy = tx0 * rs + ty0 * rc
    d = _PD[n_turn]
    tx0 = vx * d
    ty0 = vy * d
    tvx = tx0 * rc - ty0 * rs
    tvy = tx0 * rs + ty0 * rc
    st, ef, rec = _waited(wt, n_turn)
    cost = _MAX_POWER * 2.0 if back else _MAX_POWER
    if ef >= _EFFORT_MAX and st - cost * n_dash >= _RECOVER_DEC_THR_VALUE + cost:
        # The stamina cannot bind: before every dash the available power is at least 100 and after it the
        # stamina stays above the 2400 thresholds, so power, effort and recovery never change. Only the motion
        # along the dash angle decides; the lateral motion and the stamina are replayed once at the end with
        # the same operations.
        accel = _MAX_POWER * (ef * _DASH_POWER_RATE)
        n_run = n_dash
        hit = False
        inc = _STAMINA_INC_MAX * rec
        if inc < cost and st <= _STAMINA_MAX and st.is_integer() and inc.is_integer():
            # Whole numbers, and the recovery after each payment is inc (the room to the maximum is at least
            # cost > inc): every step st - cost + inc is exact, so the n_run steps are st - n_run * (cost - inc)
            for i in range(n_dash):
                tvx += accel
                tpx += tvx
                tvx *= _PLAYER_DECAY
                tpy += tvy
                tvy *= _PLAYER_DECAY
                if tpx * noise_rate + 0.1 > noised_x:
                    n_run = i + 1
                    hit = True
                    break
            st -= n_run * (cost - inc)
        else:
            # one loop for both axes and the stamina (they do not interact); it stops after the reaching dash
            for i in range(n_dash):
                tvx += accel
                tpx += tvx
                tvx *= _PLAYER_DECAY
                tpy += tvy
                tvy *= _PLAYER_DECAY
                st -= cost
                room = _STAMINA_MAX - st
                st += inc if inc < room else room
                if st > _STAMINA_MAX:
                    st = _STAMINA_MAX
                if tpx * noise_rate + 0.1 > noised_x:
                    n_run = i + 1
                    hit = True
                    break
        first_power = -_MAX_POWER if back else _MAX_POWER
        if hit:
            return _reach_entry(
                me, n_turn, n_dash, n_run, tpx, tpy, st, ef, rec, xbx, xby, dash_angle, first_power, out
            )
        return _reach_last(
            me,
            n_turn,
            n_dash,
            tpx,
            tpy,
            st,
            rec,
            xbx,
            xby,
            dx,
            dy,
            rc,
            rs,
            brx,
            ca,
            dash_angle,
            first_power,
            ball_noise,
            player_rand,
            out,
        )
    prev_ef = ef
    power = _MAX_POWER
    accel = power * (ef * _DASH_POWER_RATE)
    # PlayerType::canOverSpeedMax(power, effort) is false for type 0 (100 * 0.006 * effort <= 1.05 * 0.6), so
    # librcsc's speed-cap branch never runs and the power follows the available stamina both ways.
    first_power = -power if back else power
    for i in range(n_dash):
        avail = st - _RECOVER_DEC_THR_VALUE
        if avail < 0.0:
            avail = 0.0
        if back:
            avail *= 0.5
        if avail > _MAX_POWER:
            avail = _MAX_POWER
        if avail != power or ef < prev_ef:  # (avail < power) or (effort dropped) or (power < avail)
            power = avail
            accel = power * (ef * _DASH_POWER_RATE)
            if i == 0:
                first_power = -power if back else power
        tvx += accel
        tpx += tvx
        tpy += tvy
        tvx *= _PLAYER_DECAY
        tvy *= _PLAYER_DECAY
        # simulateDash
        st -= power * 2.0 if back else power
        if st < 0.0:
            st = 0.0
        if st > _RECOVER_DEC_THR_VALUE and ef >= _EFFORT_MAX:
            inc = _STAMINA_INC_MAX * rec
            room = _STAMINA_MAX - st
            st += inc if inc < room else room
            if st > _STAMINA_MAX:
                st = _STAMINA_MAX
        else:
            st, ef, rec = _wait(st, ef, rec)
        if tpx * noise_rate + 0.1 > noised_x:
            return _reach_entry(
                me, n_turn, n_dash, i + 1, tpx, tpy, st, ef, rec, xbx, xby, dash_angle, first_power, out
            )
    return _reach_last(
        me,
        n_turn,
        n_dash,
        tpx,
        tpy,
        st,
        rec,
        xbx,
        xby,
        dx,
        dy,
        rc,
        rs,
        brx,
        ca,
        dash_angle,
        first_power,
        ball_noise,
        player_rand,
        out,
    )


def _reach_entry(
    me: tuple,
    n_turn: int,
    n_dash: int,
    n_run: int,
    tpx: float,
    tpy: float,
    st: float,
    ef: float,
    rec: float,
    xbx: float,
    xby: float,
    dash_angle: float,
    first_power: float,
    out: list[InterceptEntry],
) -> bool:
    """canReachAfterDash's entry when the goalie passes the ball point after ``n_run`` of ``n_dash`` dashes."""
    px, py, vx, vy, _, _, _, _, _, _, _, recovery = me
    fx, fy = _rotate_back(px, py, tpx, tpy, dash_angle)
    f = _PF[n_turn + n_dash]
    inx = px + vx * f
    iny = py + vy * f
    if (inx - fx) * (inx - fx) + (iny - fy) * (iny - fy) > 0.01:
        # more than 0.1 from the drift point: the ball point projected on the line drift point -> reached point
        fx, fy = _project(inx, iny, fx, fy, xbx, xby)
    for _ in range(n_dash - n_run):
        st, ef, rec = _wait(st, ef, rec)
    mode = EXHAUST if rec < recovery else NORMAL
    dist = _sqrt((fx - xbx) * (fx - xbx) + (fy - xby) * (fy - xby))
    out.append(InterceptEntry(mode, n_turn, n_dash, first_power, 0.0, fx, fy, dist, st))
    return True


def _reach_last(
    me: tuple,
    n_turn: int,
    n_dash: int,
    tpx: float,
    tpy: float,
    st: float,
    rec: float,
    xbx: float,
    xby: float,
    dx: float,
    dy: float,
    rc: float,
    rs: float,
    brx: float,
    ca: float,
    dash_angle: float,
    first_power: float,
    ball_noise: float,
    player_rand: float,
    out: list[InterceptEntry],
) -> bool:
    """canReachAfterDash's last test when all dashes ran: close enough to the ball point after all?"""
    px, py, _, _, _, _, _, _, _, _, _, recovery = me
    bry = dx * rs + dy * rc
    travel = _sqrt(tpx * tpx + tpy * tpy)
    buf = 0.2 + travel * player_rand * 0.5 + ball_noise
    if _sqrt((brx - tpx) * (brx - tpx) + (bry - tpy) * (bry - tpy)) < max(ca - 0.225, ca - buf):
        fx, fy = _rotate_back(px, py, tpx, tpy, dash_angle)
        mode = EXHAUST if rec < recovery else NORMAL
        dist = _sqrt((fx - xbx) * (fx - xbx) + (fy - xby) * (fy - xby))
        out.append(InterceptEntry(mode, n_turn, n_dash, first_power, 0.0, fx, fy, dist, st))
        return True
    return False


def _rotate_back(px: float, py: float, x: float, y: float, angle: float) -> tuple[float, float]:
    """P + (x, y) rotated by ``angle`` degrees."""
    c = _cos(angle * _D2R)
    s = _sin(angle * _D2R)
    return px + (x * c - y * s), py + (x * s + y * c)


def _project(x1: float, y1: float, x2: float, y2: float, qx: float, qy: float) -> tuple[float, float]:
    """Line2D(p1, p2).projection(q): the intersection with the perpendicular through q."""
    a = -(y2 - y1)
    b = x2 - x1
    c = -a * x1 - b * y1
    # the perpendicular line (b, -a, a qy - b qx)
    a2 = b
    b2 = -a
    c2 = a * qy - b * qx
    den = a * b2 - b * a2
    if abs(den) < 1.0e-10:
        return x2, y2  # cannot happen: the two points are more than 0.1 apart
    return (b * c2 - b2 * c) / den, (a2 * c - a * c2) / den


def _predict_final(
    me: tuple, wt: list, max_cycle: int, out: list[InterceptEntry], player_rand: float
) -> None:
    """predictFinal: the ball's resting point, reached after the long-step horizon (:func:`_final_entry`)."""
    px, py, vx, vy, body, speed, lk, bx, by, wx, wy, _ = me
    out.append(_final_entry(px, py, vx, vy, body, speed, lk, bx, by, wx, wy, wt, max_cycle, player_rand))


def _final_entry(
    px: float,
    py: float,
    vx: float,
    vy: float,
    body: float,
    speed: float,
    lk: bool,
    bx: float,
    by: float,
    wx: float,
    wy: float,
    wt: list,
    max_cycle: int,
    player_rand: float,
) -> InterceptEntry:
    """:func:`_final_entry_python`, computed by hfo2d._accel's kernel when it is in use (the same entry; the
    kernel simulates the waits from ``wt[0]`` instead of reading and extending the memo ``wt``)."""
    if _ACCEL is None:
        return _final_entry_python(
            px, py, vx, vy, body, speed, lk, bx, by, wx, wy, wt, max_cycle, player_rand
        )
    stamina, effort, recovery = wt[0]
    n_turn, n_dash, xfx, xfy, stamina = _ACCEL.final_entry(
        px, py, vx, vy, body, speed, lk, bx, by, wx, wy, stamina, effort, recovery, max_cycle, player_rand
    )
    return InterceptEntry(NORMAL, n_turn, n_dash, _MAX_POWER, 0.0, xfx, xfy, 0.0, stamina)


def _final_entry_python(
    px: float,
    py: float,
    vx: float,
    vy: float,
    body: float,
    speed: float,
    lk: bool,
    bx: float,
    by: float,
    wx: float,
    wy: float,
    wt: list,
    max_cycle: int,
    player_rand: float,
) -> InterceptEntry:
    """predictFinal's entry (``body`` normalised, ``speed`` = |V|, ``wt`` the stamina states after 0, 1, ... waits)."""
    f = _PF[100]
    qx = px + vx * f
    qy = py + vy * f
    g = _BF[100]
    xfx = bx + wx * g
    xfy = by + wy * g
    goalie_mode = lk and xfx < _PEN_LINE_X and abs(xfy) < _PEN_HALF_W
    ca = _CATCHABLE_AREA - 0.15 if goalie_mode else _KICKABLE_AREA
    # predictTurnCycle for cycle 100 (inlined): the back dash needs a chase under 15 cycles, so it is never tried
    tx = xfx - qx
    ty = xfy - qy
    target_angle = _th(tx, ty)
    diff = abs(_norm(target_angle - body))
    target_dist = _sqrt(tx * tx + ty * ty)
    margin = 180.0
    control_buf = max(0.5, ca - 0.25)
    if control_buf < target_dist:
        margin = _asin_deg(control_buf / target_dist)
    if margin < _MIN_TURN_THR:
        margin = _MIN_TURN_THR
    n_turn = 0
    if diff > margin:
        # the long-step turn model shrinks the max moment by player_rand
        max_moment = _MAX_MOMENT * (1.0 - player_rand)
        s = speed
        while diff > margin:
            diff -= max_moment / (1.0 + _INERTIA_MOMENT * s)
            s *= _PLAYER_DECAY
            n_turn += 1
    # |Q - X| is the same float as |X - Q|
    n_dash = cycles_to_reach_distance(target_dist - ca)
    if max_cycle > n_turn + n_dash:
        n_dash = max_cycle - n_turn
    st, ef, rec = _waited(wt, n_turn)
    # StaminaModel::simulateDashes at full power
    inc = _STAMINA_INC_MAX * rec
    if ef >= _EFFORT_MAX and st - _MAX_POWER * n_dash > _RECOVER_DEC_THR_VALUE:
        # never near the thresholds and, after paying 100, never within 45 of the maximum: plain recovery
        if st.is_integer() and inc.is_integer():
            st -= (_MAX_POWER - inc) * n_dash  # whole numbers: every step of the loop below is exact
        else:
            for _ in range(n_dash):
                st = st - _MAX_POWER + inc
        n_dash_left = 0
    else:
        n_dash_left = n_dash
    for _ in range(n_dash_left):
        st -= _MAX_POWER
        if st > _RECOVER_DEC_THR_VALUE and ef >= _EFFORT_MAX:
            room = _STAMINA_MAX - st
            st += inc if inc < room else room
            if st > _STAMINA_MAX:
                st = _STAMINA_MAX
        else:
            if st < 0.0:
                st = 0.0
            st, ef, rec = _wait(st, ef, rec)
            inc = _STAMINA_INC_MAX * rec
    return InterceptEntry(NORMAL, n_turn, n_dash, _MAX_POWER, 0.0, xfx, xfy, 0.0, st)


# --- PlayerIntercept (the attacker) --------------------------------------------------------------------------
def _opp_turns(
    ox: float, oy: float, ux: float, uy: float, obody: float, n: int, xbx: float, xby: float
) -> tuple[int, float, float, float]:
    """PlayerIntercept::predictTurnCycle (at most one turn), the attacker's drift point Z after ``n`` cycles and
    the distance from Z to the ball point.

    librcsc also subtracts one effective turn from the angle difference but never reads it again, so the
    attacker's speed does not matter.
    """
    f = _PF[n]
    zx = ox + ux * f
    zy = oy + uy * f
    tx = xbx - zx
    ty = xby - zy
    target_dist = _sqrt(tx * tx + ty * ty)
    margin = 180.0
    if target_dist > _KICKABLE_AREA:
        r = _KICKABLE_AREA / target_dist
        margin = 90.0 if r >= 1.0 else _asin(r) * _R2D  # AngleDeg::asin_deg (r > 0)
    if margin < 12.0:  # player_intercept.cpp: minimum turn margin 12 degrees
        margin = 12.0
    diff = abs(_norm(_th(tx, ty) - obody))
    if target_dist < 5.0 and diff > 90.0:  # close: a back dash will do
        diff = 180.0 - diff
    return (1 if diff > margin else 0), zx, zy, target_dist


def _predict_opponent(view: GoalieView, cache: list[tuple[float, float]], rel_y: float) -> int:
    """PlayerIntercept::predict for the attacker (fullstate: counts 0; not a goalie, so control area 1.085).

    ``rel_y``: the attacker's offset from the ball's line of motion, (O - B) rotated by -angle(W).
    """
    return _predict_player(
        view.ox,
        view.oy,
        view.ux,
        view.uy,
        view.obody,
        view.opp_tackle_count,
        view.wx == 0.0 and view.wy == 0.0,
        _sqrt((view.ox - view.px) * (view.ox - view.px) + (view.oy - view.py) * (view.oy - view.py)),
        cache,
        rel_y,
    )


def predict_player_reach(
    view: GoalieView,
    cache: list[tuple[float, float]],
    player: tuple[float, float, float, float, float, int],
    teammate: bool,
) -> int:
    """PlayerIntercept::predict for any other field player (fullstate: counts 0, control area 1.085), on the ball
    cache of ``view``: ``player`` is (x, y, vx, vy, body, remaining tackle freeze) in the view's frame.

    librcsc treats the two sides alike but for one rule: the "no solution" distance to the ball's final point is
    reduced by 3 % of the player's distance from the deciding player only for an opponent
    (``rcsc/player/player_intercept.cpp``). Capped at 1000 as InterceptTable stores it.
    """
    x, y, vx, vy, body, frozen = player
    wx, wy = view.wx, view.wy
    if wx == 0.0 and wy == 0.0:
        sin_a, cos_a = -0.0, 1.0
    else:
        a = -_th(wx, wy) * _D2R
        sin_a, cos_a = _sin(a), _cos(a)
    rel_y = (x - view.bx) * sin_a + (y - view.by) * cos_a
    self_dist = 0.0 if teammate else _sqrt((x - view.px) * (x - view.px) + (y - view.py) * (y - view.py))
    reach = _predict_player(x, y, vx, vy, body, frozen, wx == 0.0 and wy == 0.0, self_dist, cache, rel_y)
    return min(1000, reach)


def fastest_reach(
    view: GoalieView,
    ball: tuple,
    players: Iterable[tuple[float, float, float, float, float, int]],
    teammate: bool,
    best: int = 1000,
) -> int:
    """``min(best, predict_player_reach(view, cache, p, teammate) for p in players)`` on a ball part of ``view``
    (:func:`_ball_part`'s (cache, resting, sin, cos)): :func:`fastest_reach_python`, computed by hfo2d._accel's
    kernel when it is in use (the same cycles)."""
    if _ACCEL is None:
        return fastest_reach_python(view, ball, players, teammate, best)
    cache, _, sin_a, cos_a = ball
    return _ACCEL.fastest_reach(
        players,
        cache,
        view.bx,
        view.by,
        view.px,
        view.py,
        view.wx == 0.0 and view.wy == 0.0 and _RESTING_SHORTCUTS,
        sin_a,
        cos_a,
        teammate,
        best,
    )


def fastest_reach_python(
    view: GoalieView,
    ball: tuple,
    players: Iterable[tuple[float, float, float, float, float, int]],
    teammate: bool,
    best: int = 1000,
) -> int:
    """:func:`fastest_reach` in pure Python (the reference): the ball's frame is the ball part's, not computed
    again for every player (the same numbers: both come from the view's W by the same operations)."""
    cache, _, sin_a, cos_a = ball
    bx = view.bx
    by = view.by
    resting = view.wx == 0.0 and view.wy == 0.0
    for player in players:
        x, y, vx, vy, body, frozen = player
        rel_y = (x - bx) * sin_a + (y - by) * cos_a
        self_dist = 0.0 if teammate else _sqrt((x - view.px) * (x - view.px) + (y - view.py) * (y - view.py))
        reach = _predict_player_python(x, y, vx, vy, body, frozen, resting, self_dist, cache, rel_y)
        if reach < best:
            best = reach
    return best


def _predict_player(
    ox: float,
    oy: float,
    ux: float,
    uy: float,
    obody: float,
    frozen: int,
    resting: bool,
    self_dist: float,
    cache: list[tuple[float, float]],
    rel_y: float,
) -> int:
    """:func:`_predict_player_python`, computed by hfo2d._accel's kernel when it is in use (the same cycle)."""
    if _ACCEL is None:
        return _predict_player_python(ox, oy, ux, uy, obody, frozen, resting, self_dist, cache, rel_y)
    return _ACCEL.predict_player(
        ox, oy, ux, uy, obody, frozen, resting and _RESTING_SHORTCUTS, self_dist, cache, rel_y
    )


def _predict_player_python(
    ox: float,
    oy: float,
    ux: float,
    uy: float,
    obody: float,
    frozen: int,
    resting: bool,
    self_dist: float,
    cache: list[tuple[float, float]],
    rel_y: float,
) -> int:
    """PlayerIntercept::predict for one player at (ox, oy) moving (ux, uy), body ``obody``, frozen for ``frozen``
    more cycles by its own tackle; ``self_dist`` is its distance from the deciding player (0: no reduction)."""
    obody = _norm(obody)
    min_cycle = int(_floor(abs(rel_y) / _REAL_SPEED_MAX))
    # librcsc PlayerObject::tackleCount counts the cycles since the tackle was first seen (0 in the first state
    # after it), where rcssserver shows a remaining freeze of tackle_cycles - 1 = 9. With the remaining freeze r
    # (frozen), tackleCount = 9 - r and isTackling() <=> tackleCount <= tackle_cycles - 2 <=> r >= 1.
    tackle_extra = 0
    if frozen > 0:
        tackle_count = _TACKLE_CYCLES - 1 - frozen
        tackle_extra = max(0, _TACKLE_CYCLES - tackle_count - 2)
        min_cycle += tackle_extra
    if min_cycle < 0:
        min_cycle = 0
    n_cache = len(cache)
    if resting and min_cycle < n_cache and _RESTING_SHORTCUTS:
        # a resting ball: every cached point has B's value, so the distance below is one number and the reach
        # bound grows with the cycle; skip the cycles it fails at once
        xbx, xby = cache[min_cycle]
        d = _sqrt((ox - xbx) * (ox - xbx) + (oy - xby) * (oy - xby))
        while min_cycle < n_cache and _KICKABLE_AREA + _REAL_SPEED_MAX * min_cycle + 0.5 < d:
            min_cycle += 1
    for cycle in range(min_cycle, n_cache):
        xbx, xby = cache[cycle]
        if _KICKABLE_AREA + _REAL_SPEED_MAX * cycle + 0.5 < _sqrt(
            (ox - xbx) * (ox - xbx) + (oy - xby) * (oy - xby)
        ):
            continue
        n_turn, _, _, target_dist = _opp_turns(ox, oy, ux, uy, obody, cycle, xbx, xby)
        n_dash = cycle - n_turn
        if n_dash < 0:
            continue
        # canReachAfterDash: the drift point after turn + dash cycles is the same inertia point, so the distance
        # is the turn prediction's |B_cycle - Z|
        dist = target_dist - _KICKABLE_AREA  # Vector2D::r
        if dist < 0.0:
            return cycle
        if cycles_to_reach_distance(dist) + tackle_extra <= n_dash:
            return cycle
    # predictFinal: the ball's last cached point
    xbx, xby = cache[-1]
    n_turn, _, _, target_dist = _opp_turns(ox, oy, ux, uy, obody, 100, xbx, xby)
    dash_dist = target_dist - _KICKABLE_AREA  # |Z - B| (the same floats as |B - Z|)
    dash_dist -= self_dist * 0.03  # distFromSelf (rpos.r()); 0 for a teammate
    if dash_dist < 0.0:
        return n_cache
    n_dash = max(1, cycles_to_reach_distance(dash_dist))
    return max(n_cache, n_turn + n_dash)


#: :func:`_turn_short_python`, computed by hfo2d._accel's kernel when it is in use (the same turns and angle)
_turn_short = _turn_short_python if _ACCEL is None else _ACCEL.turn_short
