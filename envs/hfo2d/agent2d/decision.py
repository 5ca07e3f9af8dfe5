"""HFO's goalie decision tree (agent2d RoleGoalie, Bhv_GoalieChaseBall, Bhv_GoalieBasicMove), in GF.

Sources (rules and numbers, no code): HFO b8b2a1d ``src/role_goalie.cpp``, ``src/bhv_goalie_chase_ball.cpp``,
``src/bhv_goalie_basic_move.cpp``, ``src/bhv_goalie_free_kick.cpp``, ``src/bhv_set_play.cpp``; librcsc d222758
``rcsc/geom/line_2d.{h,cpp}`` (the line arithmetic is reproduced operation for operation, because the goalie's
targets come from line intersections). Frame: GF (see :mod:`hfo2d.agent2d.common`).

One decision writes at most one body command into an :class:`~hfo2d.agent2d.common.Effector`; a later command
replaces an earlier one, as in librcsc's ActionEffector.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from hfo2d.agent2d import common as _common
from hfo2d.agent2d import tackle as _tackle
from hfo2d.agent2d.actions import (
    body_go_to_point,
    body_intercept,
    body_stop_dash,
    body_turn_to_angle,
    body_turn_to_point,
    go_to_point_look_ball,
)
from hfo2d.agent2d.common import (
    GOAL_HALF_WIDTH,
    OWN_GOAL,
    PENALTY_AREA_HALF_WIDTH,
    PENALTY_AREA_X,
    PITCH_HALF_LENGTH,
    Command,
    Effector,
    GoalieView,
    InterceptTable,
    angle_of,
    ball_at,
    norm_deg,
    register_binder,
    rotate,
)
from hfo2d.agent2d.intercept import build_intercept_table
from hfo2d.agent2d.tackle import basic_tackle
from hfo2d.physics import ServerParams

# --- RoleGoalie::execute: the catch rectangle (our penalty area shrunk by 1 m: x in [-52.5, -37], |y| <= 19.16)
CATCH_RECT_MAX_X = PENALTY_AREA_X - 1.0
CATCH_RECT_HALF_WIDTH = PENALTY_AREA_HALF_WIDTH - 1.0

# --- Bhv_GoalieBasicMove (bhv_goalie_basic_move.cpp) ---------------------------------------------------------------
BASE_MOVE_X = -49.8
DANGER_MOVE_X = -51.5
LINE_ANCHOR_X_BACK = 7.0  # x_back: the positioning line runs from the ball to 7 m behind the goal centre
BALL_PRED_CYCLE = 5
Y_BUF = 0.5
X_BUF = 0.5  # doCorrectX / doMoveForDangerousState

# constant bounds of the hot rules, computed once (the same floats as written inline)
_NEAR_GOAL_X = -PITCH_HALF_LENGTH + 8.0  # is_ball_chase_situation A, getTargetPoint
_NEAR_GOAL_Y = GOAL_HALF_WIDTH + 3.0
_SIDE_Y = GOAL_HALF_WIDTH + 2.0  # getTargetPoint
_DEEP_CROSS_Y = GOAL_HALF_WIDTH - 0.8  # doPrepareDeepCross
_SHOOT_MAX_DIST = 30.0  # is_ball_shoot_moving: no shot farther than 30 m from the goalie
_DANGER_X = -PITCH_HALF_LENGTH + 11.0  # doMoveForDangerousState
_DANGER_Y = GOAL_HALF_WIDTH + 1.0
_ANCHOR_X = -PITCH_HALF_LENGTH - LINE_ANCHOR_X_BACK  # getTargetPoint's line anchor
_ANCHOR_X_MIN = _ANCHOR_X + 0.1
_MOVE_Y_MIN = -GOAL_HALF_WIDTH + Y_BUF
_MOVE_Y_MAX = GOAL_HALF_WIDTH - Y_BUF
# ballAt(n) of a resting ball without n (so without reading the table's reach cycles): the same floats; False
# takes the general code (the tests compare both)
_RESTING_SHORTCUTS = True


# --- server parameters (set by _bind; rcssserver 15.2.2 defaults in the comments) --------------------------------
def _bind(sp: ServerParams) -> None:
    global \
        BALL_DECAY, \
        CATCH_DIR_OFFSET, \
        CATCHABLE_AREA, \
        DASH_RATE, \
        EXTRA_STAMINA, \
        PLAYER_DECAY, \
        STAMINA_INC_MAX
    global STAMINA_MAX, MAX_DASH_POWER, CATCH_DIST, CATCH_BAN_CYCLE, _ONE_MINUS_PD, _TACKLE_SURE_FAR
    global _BALL_FACTORS, FREE_KICK_FACE_LINE_X
    # the ones hfo2d.agent2d.common derives
    BALL_DECAY = _common.BALL_DECAY
    CATCH_DIR_OFFSET = _common.CATCH_DIR_OFFSET
    CATCHABLE_AREA = _common.CATCHABLE_AREA
    DASH_RATE = _common.DASH_RATE
    EXTRA_STAMINA = _common.EXTRA_STAMINA
    PLAYER_DECAY = _common.PLAYER_DECAY
    STAMINA_INC_MAX = _common.STAMINA_INC_MAX
    STAMINA_MAX = _common.STAMINA_MAX
    MAX_DASH_POWER = _common.MAX_DASH_POWER
    CATCH_DIST = CATCHABLE_AREA - 0.05  # role_goalie.cpp: catchableArea() - 0.05
    # rcssserver catch_ban_cycle 5, compared by the client with its last catch time
    CATCH_BAN_CYCLE = _common.CATCH_BAN_CYCLE
    _ONE_MINUS_PD = 1.0 - PLAYER_DECAY
    # Bhv_BasicTackle (tackle.basic_tackle) sees no tackle chance beyond tackle.NO_TACKLE_DIST (2.5 m, its
    # squared-distance test); a ball measured farther than this is surely beyond it
    _TACKLE_SURE_FAR = _tackle.NO_TACKLE_DIST + 0.1
    # ball_at's factors (1 - 0.94**n) / (1 - 0.94) for the reach cycles 0 .. 1000 of the intercept table, the same
    # floats
    _BALL_FACTORS = tuple((1.0 - BALL_DECAY**n) / (1.0 - BALL_DECAY) for n in range(1001))
    # doWait: face (ourPenaltyAreaLineX - 1, 0) when beyond ourPenaltyAreaLineX - ball_size - player_size - 0.5
    # (rcssserver serverparam.cpp: ball_size 0.085, player_size 0.3)
    FREE_KICK_FACE_LINE_X = PENALTY_AREA_X - sp.ball_size - sp.player_size - 0.5


register_binder(_bind)


class Line:
    """librcsc Line2D, a x + b y + c = 0, with its exact constructors."""

    __slots__ = ("a", "b", "c")

    def __init__(self, a: float, b: float, c: float) -> None:
        self.a, self.b, self.c = a, b, c

    @classmethod
    def from_angle(cls, ox: float, oy: float, angle_deg: float) -> Line:
        r = angle_deg * (math.pi / 180.0)
        a = -math.sin(r)
        b = math.cos(r)
        return cls(a, b, -a * ox - b * oy)

    @classmethod
    def from_points(cls, x1: float, y1: float, x2: float, y2: float) -> Line:
        a = -(y2 - y1)
        b = x2 - x1
        return cls(a, b, -a * x1 - b * y1)

    def dist(self, x: float, y: float) -> float:
        return abs(self.a * x + self.b * y + self.c) / math.sqrt(self.a * self.a + self.b * self.b)

    def get_y(self, x: float) -> float | None:
        if abs(self.b) < 1.0e-10:  # Line2D::EPSILON
            return None
        return -(self.a * x + self.c) / self.b

    def intersection(self, other: Line) -> tuple[float, float] | None:
        tmp = self.a * other.b - self.b * other.a
        if abs(tmp) < 1.0e-10:
            return None
        return (
            (self.b * other.c - other.b * self.c) / tmp,
            (other.a * self.c - self.a * other.c) / tmp,
        )


def _complete(v: GoalieView, table: InterceptTable) -> InterceptTable:
    """The whole intercept table, for Body_Intercept's BestIntercept; the other rules need only its minima, which
    a table that stops at the fastest entry already has exactly (so the fast path builds that one first)."""
    if table.complete:
        return table
    return build_intercept_table(v)


def _ball_angle(v: GoalieView) -> float:
    """angle(W) as librcsc's Vector2D::th (0 for the zero vector)."""
    return angle_of(v.wx, v.wy)


def _opp_ball_dist(v: GoalieView) -> float:
    """Distance from the opponent nearest the ball to the ball (100 when there is none: doCorrectBodyDir)."""
    if not v.has_opp:
        return 100.0
    return math.hypot(v.ox - v.bx, v.oy - v.by)


# ---------------------------------------------------------------------------------------------------------------
# RoleGoalie::execute (role_goalie.cpp)
# ---------------------------------------------------------------------------------------------------------------
def can_catch(v: GoalieView, last_catch_cycle: int, d_b: float | None = None) -> bool:
    """The catch test: ban over (client side), ball closer than 1.25 m, ball inside the catch rectangle (``d_b``:
    the ball's distance when the caller has it)."""
    if not v.play_on:
        return False
    if not v.cycle > last_catch_cycle + CATCH_BAN_CYCLE:
        return False
    if not (v.ball_dist if d_b is None else d_b) < CATCH_DIST:
        return False
    return (
        -PITCH_HALF_LENGTH <= v.bx <= CATCH_RECT_MAX_X
        and -CATCH_RECT_HALF_WIDTH <= v.by <= CATCH_RECT_HALF_WIDTH
    )


def decide(
    eff: Effector,
    v: GoalieView,
    table: InterceptTable,
    last_catch_cycle: int,
    catch_command_cycle: int = 0,
    free_kick: FreeKickState | None = None,
) -> None:
    """One cycle of the goalie in PlayOn or in GoalieCatch mode after a catch (SamplePlayer::actionImpl's goalie
    part). ``catch_command_cycle`` is the cycle of the goalie's last catch command (librcsc ActionEffector's
    catch time, 0 before any), ``free_kick`` Bhv_GoalieFreeKick's flags (kept by the caller across decisions)."""
    if not v.play_on:
        # Bhv_SetPlay -> Bhv_GoalieFreeKick: its routine when the goalie is kickable (in HFO: the wait frame after
        # a catch that ended the episode with the ball within 1.03 m), else the basic move.
        if v.self_kickable:
            goalie_free_kick(eff, v, v.cycle - catch_command_cycle, free_kick or FreeKickState())
        else:
            basic_move(eff, v, table)
        return
    d_b = math.hypot(v.bx - v.px, v.by - v.py)  # v.ball_dist, read by the rules below
    # (can_catch's distance test made first: the ball is rarely that close, and the call is saved)
    if d_b < CATCH_DIST and can_catch(v, last_catch_cycle, d_b):
        eff.catch(norm_deg(angle_of(v.bx - v.px, v.by - v.py) - v.body + CATCH_DIR_OFFSET))
        return
    if v.self_kickable:
        # Body_ClearBall: unreachable in a live HFO episode (the referee ends it at 1.085 m first).
        eff.turn(0.0)
        return
    if is_ball_chase_situation(v, table, d_b):
        chase_ball(eff, v, table)
    else:
        basic_move(eff, v, table, d_b)


# ---------------------------------------------------------------------------------------------------------------
# Bhv_GoalieFreeKick (bhv_goalie_free_kick.cpp): GoalieCatch mode for our side with the ball kickable
# ---------------------------------------------------------------------------------------------------------------
FREE_KICK_WAIT_CYCLES = 2  # bhv_goalie_free_kick.cpp: time_diff <= 2 -> wait (and clear the flags)
FREE_KICK_FIRST_MOVE_X = PENALTY_AREA_X - 1.5  # ourPenaltyAreaLineX - 1.5, y -13 or 13 (away from the ball)
FREE_KICK_FIRST_MOVE_Y = 13.0
FREE_KICK_MIN_WAIT = 50  # time_diff < 50 -> wait after the first move
FREE_KICK_DROP_WAIT = 100 - 15  # rcssserver serverparam.cpp drop_ball_time 100, less 15
FREE_KICK_KICK_POINTS = ((-43.0, 10.0), (-43.0, -10.0), (-43.0, 0.0))  # getKickPoint candidates, in order
FREE_KICK_SECOND_WAITS = 5  # s_second_wait_count < 5 -> wait
# doWait's FREE_KICK_FACE_LINE_X: set by _bind


@dataclass(slots=True)
class FreeKickState:
    """Bhv_GoalieFreeKick's static flags (``s_first_move``, ``s_second_move``, ``s_second_wait_count``)."""

    first_move: bool = False
    second_move: bool = False
    second_wait_count: int = 0


def free_kick_wait(eff: Effector, v: GoalieView) -> None:
    """Bhv_GoalieFreeKick::doWait: Body_TurnToPoint toward the halfway spot (0, 0), or toward
    (ourPenaltyAreaLineX - 1, 0) when the goalie stands beyond ourPenaltyAreaLineX - 0.885."""
    fx = PENALTY_AREA_X - 1.0 if v.px > FREE_KICK_FACE_LINE_X else 0.0
    body_turn_to_point(eff, v, fx, 0.0)


def goalie_free_kick(eff: Effector, v: GoalieView, time_diff: int, state: FreeKickState) -> None:
    """Bhv_GoalieFreeKick::execute once GoalieCatch (our side) holds and the goalie is kickable; ``time_diff`` is
    the cycles since its catch command.

    A ``move`` is written as ``Command("move", x, y)``: rcssserver accepts it only in its own free-kick mode after
    a catch, which HFO's server never enters (its play mode stays PlayOn), so the server ignores it. The kick of
    the routine's end (Body_Pass / Body_ClearBall) needs six such cycles with the ball kickable and no episode
    end in between, which HFO never gives; it is written as ``turn 0`` like RoleGoalie's clear-ball branch."""
    if time_diff <= FREE_KICK_WAIT_CYCLES:
        state.first_move = state.second_move = False
        state.second_wait_count = 0
        free_kick_wait(eff, v)
        return
    if not state.first_move:
        state.first_move = True
        state.second_move = False
        state.second_wait_count = 0
        y = -FREE_KICK_FIRST_MOVE_Y if v.by > 0.0 else FREE_KICK_FIRST_MOVE_Y
        eff.command = Command("move", FREE_KICK_FIRST_MOVE_X, y)
        return
    # (the set-play count, cycles since GoalieCatch began, is >= 3 whenever time_diff >= 50; no teammates)
    if time_diff < FREE_KICK_MIN_WAIT or (time_diff < FREE_KICK_DROP_WAIT and v.stamina < STAMINA_MAX * 0.9):
        free_kick_wait(eff, v)
        return
    if not state.second_move:
        best = FREE_KICK_KICK_POINTS[0]
        best_cong = 10000.0
        for kx, ky in FREE_KICK_KICK_POINTS:
            cong = 0.0
            if v.has_opp:
                d2 = (v.ox - kx) ** 2 + (v.oy - ky) ** 2
                cong = 1.0 / d2 if d2 > 0.0 else math.inf
            if cong < best_cong:
                best, best_cong = (kx, ky), cong
        eff.command = Command("move", best[0], best[1])
        state.second_move = True
        state.second_wait_count = 0
        return
    state.second_wait_count += 1
    # (or no see this cycle: with synch_see there is one every cycle)
    if state.second_wait_count < FREE_KICK_SECOND_WAITS:
        free_kick_wait(eff, v)
        return
    state.first_move = state.second_move = False
    state.second_wait_count = 0
    eff.turn(0.0)


# ---------------------------------------------------------------------------------------------------------------
# Bhv_GoalieChaseBall (bhv_goalie_chase_ball.cpp)
# ---------------------------------------------------------------------------------------------------------------
def is_ball_shoot_moving(v: GoalieView, d_b: float | None = None) -> bool:
    """Is the ball a shot rolling into the goal? (Bhv_GoalieChaseBall::is_ball_shoot_moving; ``d_b``: the
    ball's distance when the caller has it)."""
    if (v.ball_dist if d_b is None else d_b) > _SHOOT_MAX_DIST:
        return False
    if v.bx > -34.5:
        return False
    if v.kick_opp:
        return False
    if abs(v.wx) < 0.1:
        return v.bx < -46.0 and abs(v.by) < GOAL_HALF_WIDTH + 2.0
    line = Line.from_angle(v.bx, v.by, _ball_angle(v))
    y = line.get_y(-PITCH_HALF_LENGTH)
    if (
        abs(line.b) > 0.1
        and y is not None
        and abs(y) < GOAL_HALF_WIDTH + 2.0
        and v.bx < -40.0
        and abs(v.by) < 15.0
    ):
        end_x = v.bx + v.wx / (1.0 - BALL_DECAY)
        return math.hypot(v.wx, v.wy) > 0.5 and end_x < -PITCH_HALF_LENGTH + 2.0
    return False


def is_ball_chase_situation(v: GoalieView, table: InterceptTable, d_b: float | None = None) -> bool:
    """Bhv_GoalieChaseBall::is_ball_chase_situation (PlayOn only; ``d_b``: the ball's distance when the caller
    has it)."""
    if not v.play_on:
        return False
    # (the table's reach cycles are read only where a rule needs them: a full=False table computes them then)
    wx = v.wx
    wy = v.wy
    next_x = v.bx + wx
    next_y = v.by + wy
    if d_b is None:
        d_b = v.ball_dist
    # A. the danger area in front of the goal
    if next_x < _NEAR_GOAL_X and abs(next_y) < _NEAR_GOAL_Y:
        self_min = table.self_min
        opp_min = table.opp_min
        if d_b < 3.0 and self_min <= 3:
            return True
        return not (self_min > opp_min + 3 and opp_min < 7)
    # B. a shot (is_ball_shoot_moving's distance test made first, saving the call for a far ball)
    if d_b <= _SHOOT_MAX_DIST and is_ball_shoot_moving(v, d_b) and table.self_min < table.opp_min:
        return True
    # C. the intercept point must lie inside the penalty area shrunk by pen_thr: ballAt(self_min), which for a
    # resting ball is B + W (+-0) whatever the cycle
    if wx == 0.0 and wy == 0.0 and _RESTING_SHORTCUTS:
        ix = next_x
        iy = next_y
    else:
        f = _BALL_FACTORS[table.self_min]  # ball_at(B, W, self_min)
        ix = v.bx + wx * f
        iy = v.by + wy * f
    # max(1.0, t) and the like written out as the builtin decides (its call costs more than the rule)
    pen_thr = d_b * 0.1 + 1.0
    if not pen_thr > 1.0:
        pen_thr = 1.0
    if abs(iy) > PENALTY_AREA_HALF_WIDTH - pen_thr or ix > PENALTY_AREA_X - pen_thr:
        return False
    self_min = table.self_min
    opp_min = table.opp_min
    # E. the opponent is faster by two cycles
    if opp_min <= self_min - 2:
        return False
    # F. the opponent is nearer to the intercept point by more than 2 m
    my_dist = math.hypot(v.px - ix, v.py - iy)
    opp_dist = math.hypot(v.ox - ix, v.oy - iy) if v.has_opp else 10000.0
    # getOpponentNearestTo: every opponent of a team game (the goalie's view lists the others; none in 1v1)
    for other in getattr(v, "other_opponents", ()):
        opp_dist = min(opp_dist, math.hypot(other[0] - ix, other[1] - iy))
    return not opp_dist < my_dist - 2.0


def _in_intercept_area(ix: float, iy: float, pen_thr: float, min_x: float) -> bool:
    return min_x < ix < PENALTY_AREA_X - pen_thr and abs(iy) < PENALTY_AREA_HALF_WIDTH - pen_thr


def chase_ball(eff: Effector, v: GoalieView, table: InterceptTable) -> None:
    """Bhv_GoalieChaseBall::execute."""
    if basic_tackle(eff, v, table, 0.8, 90.0):
        return
    self_min = table.self_min
    ix, iy = ball_at(v.bx, v.by, v.wx, v.wy, self_min)
    pen_thr = max(1.0, v.ball_dist * 0.1 + 1.0)
    ball_line = Line.from_angle(v.bx, v.by, _ball_angle(v))
    defend_line = Line.from_points(v.px, -10.0, v.px, 10.0)
    if _in_intercept_area(ix, iy, pen_thr, -PITCH_HALF_LENGTH - 1.0):
        save_recovery = ball_line.dist(v.px, v.py) < CATCHABLE_AREA
        body_intercept(eff, v, _complete(v, table), save_recovery, ball_rand=v.ball_rand)
        return
    inter = ball_line.intersection(defend_line)
    line_unusable = (
        inter is None
        or ball_line.dist(v.px, v.py) < CATCHABLE_AREA * 0.8
        or abs(inter[1]) > GOAL_HALF_WIDTH + 3.0
    )
    if line_unusable and not v.kick_opp:
        if (
            self_min <= table.opp_min + 2
            and _in_intercept_area(ix, iy, pen_thr, -PITCH_HALF_LENGTH - 2.0)
            and body_intercept(eff, v, _complete(v, table), False, ball_rand=v.ball_rand)
        ):
            return
        go_to_catch_point(eff, v, v.bx, v.by)
        return
    if inter is None:
        # Only reachable with a kickable opponent and a vertical ball line: librcsc's invalidated vector has
        # huge coordinates, so the range test below fails it.
        if not body_intercept(eff, v, _complete(v, table), False, ball_rand=v.ball_rand):
            basic_move(eff, v, table)
        return
    xx, xy = inter
    if (
        abs(xx) > PITCH_HALF_LENGTH + CATCHABLE_AREA
        or xx > PENALTY_AREA_X - CATCHABLE_AREA
        or abs(xy) > PENALTY_AREA_HALF_WIDTH - CATCHABLE_AREA
    ):
        if not body_intercept(eff, v, _complete(v, table), False, ball_rand=v.ball_rand):
            basic_move(eff, v, table)
        return
    fx = v.px + v.vx / (1.0 - PLAYER_DECAY)
    fy = v.py + v.vy / (1.0 - PLAYER_DECAY)
    dist_thr = max(0.5, 0.2 + v.ball_dist * 0.1)
    if math.hypot(fx - xx, fy - xy) < dist_thr:
        body_stop_dash(eff, v, False)
        return
    if v.bx > -35.0:
        xy = 0.0 if v.by * xy < 0.0 else xy * 0.5
    go_to_catch_point(eff, v, xx, xy)


def go_to_catch_point(eff: Effector, v: GoalieView, tx: float, ty: float) -> None:
    """Bhv_GoalieChaseBall::doGoToCatchPoint: dash straight (forward or back) or turn toward the point."""
    rx, ry = rotate(tx - v.px, ty - v.py, -v.body)
    rel_angle = angle_of(rx, ry)
    angle_buf = abs(math.degrees(math.atan2(CATCHABLE_AREA * 0.9, math.hypot(rx, ry))))
    if abs(rel_angle) < angle_buf:
        eff.dash(min(v.stamina + EXTRA_STAMINA, MAX_DASH_POWER))
    elif abs(rel_angle) > 180.0 - angle_buf:
        power = -MAX_DASH_POWER
        if v.stamina + EXTRA_STAMINA < 200.0:
            power = max(-MAX_DASH_POWER, (v.stamina + EXTRA_STAMINA) * -0.5)
        eff.dash(power)
    elif abs(rel_angle) < 90.0:
        eff.turn(rel_angle)
    else:
        eff.turn(norm_deg(rel_angle - 180.0))


# ---------------------------------------------------------------------------------------------------------------
# Bhv_GoalieBasicMove (bhv_goalie_basic_move.cpp)
# ---------------------------------------------------------------------------------------------------------------
def target_point(v: GoalieView, table: InterceptTable) -> tuple[float, float]:
    """Bhv_GoalieBasicMove::getTargetPoint: where the goalie stands."""
    wx = v.wx
    wy = v.wy
    # ballAt(n) of a resting ball is B + W (+-0) whatever n: then the opponent's reach is not needed
    resting = wx == 0.0 and wy == 0.0 and _RESTING_SHORTCUTS
    if resting:
        bx = v.bx + wx
        by = v.by + wy
    else:
        reach = 0 if v.kick_opp else table.opp_min  # min(teammate reach 1000, opp_min)
        f = _BALL_FACTORS[reach]  # ball_at(B, W, reach)
        bx = v.bx + wx * f
        by = v.by + wy * f
    if by > _NEAR_GOAL_Y:
        if -140.0 < angle_of(-PITCH_HALF_LENGTH - bx, GOAL_HALF_WIDTH - by) < -90.0:
            return DANGER_MOVE_X, GOAL_HALF_WIDTH + 0.001
    elif (
        by < -_NEAR_GOAL_Y  # -GOAL_HALF_WIDTH - 3.0
        and 90.0 < angle_of(-PITCH_HALF_LENGTH - bx, -GOAL_HALF_WIDTH - by) < 140.0
    ):
        return DANGER_MOVE_X, -GOAL_HALF_WIDTH - 0.001
    if bx < _NEAR_GOAL_X and abs(by) > _SIDE_Y:
        y = GOAL_HALF_WIDTH - 0.1
        return BASE_MOVE_X, -y if by < 0.0 else y
    if v.kick_opp:
        qx, qy = bx, by
    else:
        # (quirk) the current velocity is applied again on top of the predicted point
        if resting:
            qx = bx + wx
            qy = by + wy
        else:
            opp_min = table.opp_min
            f = _BALL_FACTORS[opp_min if opp_min < BALL_PRED_CYCLE else BALL_PRED_CYCLE]
            qx = bx + wx * f
            qy = by + wy * f
    # max(qx, _ANCHOR_X_MIN) and the clamp of move_y below written out as the builtins decide
    if qx < _ANCHOR_X_MIN:
        qx = _ANCHOR_X_MIN
    # Line.from_points(Q, (anchor_x, 0)).get_y(BASE_MOVE_X), inlined
    la = -(0.0 - qy)
    lb = _ANCHOR_X - qx
    # (get_y's vertical-line case, |b| < 1e-10, is unreachable: qx > anchor_x)
    move_y = 0.0 if abs(lb) < 1.0e-10 else -(la * BASE_MOVE_X + (-la * qx - lb * qy)) / lb
    if move_y < _MOVE_Y_MIN:
        move_y = _MOVE_Y_MIN
    if move_y > _MOVE_Y_MAX:
        move_y = _MOVE_Y_MAX
    return BASE_MOVE_X, move_y


def basic_dash_power(v: GoalieView, table: InterceptTable, mx: float) -> float:
    """Bhv_GoalieBasicMove::getBasicDashPower."""
    inc = STAMINA_INC_MAX * v.recovery
    if abs(v.px - mx) > 3.0:
        return 100.0
    if v.bx > -30.0:
        return inc * 0.5 if v.stamina < STAMINA_MAX * 0.9 else inc
    if v.bx > PENALTY_AREA_X:
        if abs(v.by) > 20.0:
            return inc
        if v.wx > 1.0:
            return inc * 0.5
        if table.opp_min <= 3:
            return 100.0
        if v.stamina < STAMINA_MAX * 0.7:
            return inc * 0.7
        return 60.0
    if abs(v.by) < 15.0 or v.by * v.py < 0.0:
        return 100.0
    return inc


def _go_to_point_look_ball(
    eff: Effector, v: GoalieView, tx: float, ty: float, thr: float, power: float
) -> None:
    """Bhv_GoalieBasicMove::doGoToPointLookBall: Bhv_GoToPointLookBall in PlayOn, else go-to-point then face."""
    if v.play_on:
        go_to_point_look_ball(eff, v, tx, ty, thr, power)
        return
    if not body_go_to_point(eff, v, tx, ty, thr, power):
        body_turn_to_angle(eff, v, angle_of(v.bx - v.px, v.by - v.py))


def basic_move(eff: Effector, v: GoalieView, table: InterceptTable, d_b: float | None = None) -> None:
    """Bhv_GoalieBasicMove::execute: nine steps, the first that acts ends the cycle (``d_b``: the ball's
    distance when the caller has it)."""
    mx, my = target_point(v, table)
    px = v.px
    py = v.py
    bx = v.bx
    by = v.by
    if d_b is None:
        d_b = math.hypot(bx - px, by - py)  # v.ball_dist
    # (a ball beyond _TACKLE_SURE_FAR fails basic_tackle's own first test: the call is saved)
    if d_b < _TACKLE_SURE_FAR and basic_tackle(eff, v, table, 0.8, 90.0):
        return
    thr = d_b * 0.1  # max(0.5, d_b * 0.1) as the builtin decides
    if not thr > 0.5:
        thr = 0.5
    fx = px + v.vx / _ONE_MINUS_PD
    fy = py + v.vy / _ONE_MINUS_PD
    # angle(B - G0), read by doPrepareDeepCross and doCorrectBodyDir
    goal_angle = None
    # 2. doPrepareDeepCross
    if abs(my) >= _DEEP_CROSS_Y:
        goal_angle = abs(angle_of(bx - OWN_GOAL[0], by - OWN_GOAL[1]))
        if goal_angle >= 60.0:
            if math.hypot(fx - mx, fy - my) > thr:
                _go_to_point_look_ball(eff, v, mx, my, thr, basic_dash_power(v, table, mx))
            else:
                body_turn_to_angle(eff, v, 10.0 if by < 0.0 else -10.0)
            return
    # 3. doStopAtMovePoint
    if math.hypot(px - mx, py - my) < thr and not math.hypot(fx - mx, fy - my) < thr:
        body_stop_dash(eff, v, True)
        return
    # 4. doMoveForDangerousState
    next_x = bx + v.wx
    next_y = by + v.wy
    if (
        abs(mx - px) > X_BUF
        and next_x < _DANGER_X
        and abs(next_y) < _DANGER_Y
        and v.has_opp
        and _opp_ball_dist(v) < 2.0
    ):
        qx = v.ox - 2.5
        if px < qx:
            qx = px
        if _go_to_move_point(eff, v, table, qx, my, d_b):
            return
        _go_to_point_look_ball(eff, v, mx, my, thr, 100.0)
        return
    # 5. doCorrectX
    if not abs(mx - px) < X_BUF and ((not v.kick_opp and table.opp_min >= 4) or d_b > 18.0):
        power = basic_dash_power(v, table, mx)
        if not v.kick_opp and d_b > 30.0:
            if not body_go_to_point(eff, v, mx, my, X_BUF, power):
                body_turn_to_angle(eff, v, 90.0 if v.body > 0.0 else -90.0)
            return
        _go_to_point_look_ball(eff, v, mx, my, X_BUF, power)
        return
    # 6.-8. doCorrectBodyDir(consider_opp), doGoToMovePoint, doCorrectBodyDir(no opponent check): both body
    # corrections share their first two tests, which read neither the opponent nor anything step 7 changes
    target = -90.0 if next_y < 0.0 else 90.0  # B.y + W.y
    if not abs(norm_deg(v.body - target)) < 5.0:
        if goal_angle is None:
            goal_angle = abs(angle_of(bx - OWN_GOAL[0], by - OWN_GOAL[1]))
        if goal_angle >= 60.0:
            target = None
    else:
        target = None
    # (pure tests: the opponent's distance, which converts its position, last)
    if target is not None and (
        d_b > 20.0 or (abs(my - py) < 1.0 and not v.kick_opp) or _opp_ball_dist(v) > 7.0
    ):
        body_turn_to_angle(eff, v, target)
        return
    if _go_to_move_point(eff, v, table, mx, my, d_b):
        return
    if target is not None:
        body_turn_to_angle(eff, v, target)
        return
    eff.turn(0.0)


def _go_to_move_point(
    eff: Effector, v: GoalieView, table: InterceptTable, mx: float, my: float, d_b: float | None = None
) -> bool:
    """Bhv_GoalieBasicMove::doGoToMovePoint: correct y, sideways dashes when standing sideways (``d_b``:
    ``v.ball_dist`` when the caller has it)."""
    thr = (v.ball_dist if d_b is None else d_b) * 0.08  # max(0.5, ...) as the builtin decides
    if not thr > 0.5:
        thr = 0.5
    y_diff = abs(my - v.py)
    if y_diff < thr:
        return False
    power = basic_dash_power(v, table, mx)
    if abs(abs(v.body) - 90.0) < 7.0:
        limit = y_diff / (DASH_RATE * v.effort)
        if limit < power:  # min(power, limit)
            power = limit
        if (my > v.py and v.body < 0.0) or (my <= v.py and v.body > 0.0):
            power = -power
        eff.dash(min(max(power, -100.0), 100.0))  # ServerParam::normalizeDashPower
    else:
        _go_to_point_look_ball(eff, v, mx, my, thr, power)
    return True
