"""HFO's referee: judges one episode of the players it is given, after every :meth:`hfo2d.physics.World.step`.

One class, :class:`Referee`, with two sets of rules that differ in timing and in nothing the game is about:

* ``"rcssserver"``: rcssserver's ``HFORef`` exactly (referee.cpp ``HFORef::analyse``; hfo_reference §5.1, spec
  §5.4), as real HFO judges. ``HFO/Keeper-v1`` plays by it.
* ``"hfo2d_v0"``: the rules hfo2d's first envs were measured with (``HFO/EmptyGoal-v0``, ``HFO/StaticKeeper-v0``,
  ``HFO/Keeper-v0``): the same four outcomes in HFORef's order, with the cycle's possession counted before the
  checks, a goalie capturing as soon as its centre is within kickable_area of the ball's (``<=``), and the trial
  ending after ``trial_time`` cycles as a truncation. Kept so that those ids' figures repeat bit for bit.

Both generalise to teams: the offense is side "l", the defense side "r", HFO's goalie is the defense's unum 1
(HFO gives the first defender that number), and any defender on the ball for :data:`~hfo2d.protocol.TURNOVER_TIME`
cycles captures it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from hfo2d.physics import (
    GOAL_POST_RADIUS,
    PITCH_HALF_LENGTH,
    PITCH_HALF_WIDTH,
    PlayerState,
    ServerParams,
    World,
)
from hfo2d.protocol import (
    CAPTURED_BY_DEFENSE,
    DEFENSE_SIDE,
    GOAL,
    GOAL_LINE_X,
    GOAL_MOUTH_HALF_WIDTH,
    IN_GAME,
    KEEPER_UNUM,
    OFFENSE_SIDE,
    OUT_OF_BOUNDS,
    OUT_OF_TIME,
    TURNOVER_TIME,
)

__all__ = ["REFEREE_RULES", "HFOReferee", "Referee", "crosses_right_goal_line", "in_hfo_area"]

#: The rules a :class:`Referee` can play by (see the module docstring).
REFEREE_RULES: tuple[str, ...] = ("rcssserver", "hfo2d_v0")

_DEFAULT_PARAMS = ServerParams()
_hypot = math.hypot


def crosses_right_goal_line(
    prev_x: float, prev_y: float, x: float, y: float, params: ServerParams | None = None
) -> bool:
    """rcssserver ``Referee::crossGoalLine(RIGHT, prev)``: did the ball's centre cross into the right goal?

    The centre must go from |x| <= 52.5 + ball_size to x > 52.5 + ball_size, a start behind the goal line
    (|prev x| > 52.5) outside the mouth (|prev y| > goal_width/2 + post radius) never counts, and the crossing
    y, computed as gradient * line_x + offset, must satisfy |y| <= goal_width/2 + post radius (7.069999...).
    """
    sp = params if params is not None else _DEFAULT_PARAMS
    line_x = PITCH_HALF_LENGTH + sp.ball_size  # PITCH_LENGTH * 0.5 + ball_size
    if prev_x == x:
        return False
    if abs(x) <= line_x or abs(prev_x) > line_x:
        return False
    if -x >= 0.0:  # side RIGHT is -1: side * x >= 0 is the wrong half
        return False
    mouth = sp.goal_width * 0.5 + GOAL_POST_RADIUS
    if abs(prev_y) > mouth and abs(prev_x) > PITCH_HALF_LENGTH:
        return False
    gradient = (y - prev_y) / (x - prev_x)
    offset = prev_y - gradient * prev_x
    return abs(gradient * line_x + offset) <= mouth


def in_hfo_area(x: float, y: float) -> bool:
    """rcssserver ``HFORef::inHFOArea``: 0 <= x <= 52.5 and |y| <= 34 (bounds inclusive)."""
    return x >= 0.0 and x <= PITCH_HALF_LENGTH and abs(y) <= PITCH_HALF_WIDTH


class Referee:
    """HFO's referee: call :meth:`reset` after placing the field and :meth:`analyse` after every
    :meth:`World.step`; :attr:`truncated` says whether the status :meth:`analyse` returned ends the trial on time
    (a truncation, in Gymnasium's terms) rather than by the game.

    Rules ``"rcssserver"`` (HFORef): :meth:`analyse`, in PlayOn, checks in this order and returns the first that
    holds:

    1. GOAL: :func:`crosses_right_goal_line` from the previous analysed ball position;
    2. OUT_OF_BOUNDS: the *previous* ball position is outside :func:`in_hfo_area`;
    3. CAPTURED_BY_DEFENSE: ``take_time >= 2`` as counted by the earlier cycles;
    4. OUT_OF_TIME: ``untouched`` as counted by the earlier cycles exceeds ``untouched_time`` (if > 0), or more
       than ``trial_time`` (if > 0) cycles were played since the reset (the one status that is a truncation);
    5. otherwise ``untouched += 1``, then the players are walked in server order (the offense connects first).
       Each with squared centre distance to the ball ``< kickable_area²`` (strict) becomes the holder and zeroes
       ``untouched``; an offense ("l") player sets ``offense_possession``, a defence ("r") player clears it,
       adds 1 to ``take_time`` and stops the walk. ``offense_possession`` then zeroes ``take_time``. If the
       holder (kept from earlier cycles) is defence unum 1: CAPTURED_BY_DEFENSE, else IN_GAME.

    Outside PlayOn (``world.play_on`` False) nothing but the previous ball position's update happens.

    Rules ``"hfo2d_v0"``: first the cycle's possession: a player is on the ball when its centre is within
    kickable_area of the ball's (``<=``); an offense player on it zeroes ``take_time``, then a defender on it adds
    1 to it; ``untouched`` is zeroed when anyone is on it, else counts up. Then GOAL (the centre crossed x =
    52.585 between the previous and the current position, at an interpolated |y| <= 7.07), OUT_OF_BOUNDS (the
    previous position), CAPTURED_BY_DEFENSE (the goalie, defense unum 1, on the ball, or ``take_time >= 2``),
    OUT_OF_TIME (``untouched > untouched_time``); else, on cycle ``trial_time`` (if > 0), OUT_OF_TIME as a
    truncation.

    Args:
        params: server parameters (kickable_area, ball_size, goal_width).
        untouched_time: HFO's ``hfo_max_untouched_time`` (bin/HFO ``--untouched-time``, default 100); <= 0 off.
        trial_time: HFO's ``hfo_max_trial_time`` (bin/HFO ``--frames-per-trial``); <= 0 off (the default).
        rules: one of :data:`REFEREE_RULES`.
        players: the players it judges, in server order (offense first); None: every player of the world it is
            given (``World.players``, read at each call, so players added later count).
    """

    __slots__ = (
        "params",
        "untouched_time",
        "trial_time",
        "rules",
        "players",
        "truncated",
        "take_time",
        "untouched",
        "holder_side",
        "holder_unum",
        "cycles",
        "prev_ball_x",
        "prev_ball_y",
        "analyse",
        "_limit_params",
        "_kickable_limit2",
        "_capture_distance",
    )

    def __init__(
        self,
        params: ServerParams,
        untouched_time: int = 100,
        trial_time: int = 0,
        rules: str = "rcssserver",
        players: Sequence[PlayerState] | None = None,
    ) -> None:
        if rules not in REFEREE_RULES:
            raise ValueError(f"unknown referee rules {rules!r}; choose one of {REFEREE_RULES}")
        self.params = params
        self.untouched_time = int(untouched_time)
        self.trial_time = int(trial_time)
        self.rules = rules
        self.players = players
        self.truncated = False
        self.take_time = 0
        self.untouched = 0
        self.holder_side = "U"
        self.holder_unum = -1
        self.cycles = 0
        self.prev_ball_x = 0.0
        self.prev_ball_y = 0.0
        self._limit_params: ServerParams | None = None  # the params _kickable_limit2 was computed from
        self._kickable_limit2 = 0.0
        self._capture_distance = params.kickable_area
        # the rules' analysis, bound once (a call per cycle: no dispatch on the rules in it)
        self.analyse = self._analyse_rcssserver if rules == "rcssserver" else self._analyse_hfo2d_v0

    def reset(self, world: World) -> None:
        """``HFORef::resetField``'s bookkeeping: counters zeroed, no holder, previous ball = the placed ball."""
        self.truncated = False
        self.take_time = 0
        self.untouched = 0
        self.holder_side = "U"
        self.holder_unum = -1
        self.cycles = 0
        self.prev_ball_x = world.ball.x
        self.prev_ball_y = world.ball.y

    def _analyse_rcssserver(self, world: World) -> str:
        """The status after one step by HFORef's rules (see the class docstring); updates the counters."""
        ball = world.ball
        bx = ball.x
        by = ball.y
        status = IN_GAME
        if world.play_on:
            self.cycles += 1
            # (crosses_right_goal_line is False while |x| <= its line_x; that test alone first, as it fails most cycles)
            prev_x = self.prev_ball_x
            prev_y = self.prev_ball_y
            if abs(bx) > PITCH_HALF_LENGTH + self.params.ball_size and crosses_right_goal_line(
                prev_x, prev_y, bx, by, self.params
            ):
                status = GOAL
            # in_hfo_area(prev_x, prev_y), written out
            elif not (prev_x >= 0.0 and prev_x <= PITCH_HALF_LENGTH and abs(prev_y) <= PITCH_HALF_WIDTH):
                status = OUT_OF_BOUNDS
            elif self.take_time >= TURNOVER_TIME:
                status = CAPTURED_BY_DEFENSE
            elif (self.untouched_time > 0 and self.untouched > self.untouched_time) or (
                self.trial_time > 0 and self.cycles > self.trial_time
            ):
                status = OUT_OF_TIME
            else:
                self.untouched += 1
                offense_possession = False
                # ServerParam::kickableArea(): player_size + kickable_margin + ball_size, squared by std::pow
                # (remembered per params object: the property costs more than the rest of the test)
                if self._limit_params is not self.params:
                    area = self.params.kickable_area
                    self._kickable_limit2 = area * area
                    self._limit_params = self.params
                limit2 = self._kickable_limit2
                for p in world.players if self.players is None else self.players:
                    dx = p.x - bx
                    dy = p.y - by
                    if dx * dx + dy * dy < limit2:
                        self.holder_unum = p.unum
                        self.untouched = 0
                        if p.side == OFFENSE_SIDE:
                            offense_possession = True
                            self.holder_side = "L"
                        else:
                            offense_possession = False
                            self.holder_side = "R"
                            self.take_time += 1
                            break
                if offense_possession:
                    self.take_time = 0
                if self.holder_side == "R" and self.holder_unum == KEEPER_UNUM:
                    status = CAPTURED_BY_DEFENSE
        self.prev_ball_x = bx
        self.prev_ball_y = by
        self.truncated = status == OUT_OF_TIME and self.trial_time > 0 and self.cycles > self.trial_time
        return status

    def _analyse_hfo2d_v0(self, world: World) -> str:
        """The status after one step by hfo2d v0's rules (see the class docstring); updates the counters."""
        ball = world.ball
        bx = ball.x
        by = ball.y
        previous_x = self.prev_ball_x
        previous_y = self.prev_ball_y
        self.prev_ball_x = bx
        self.prev_ball_y = by
        self.cycles += 1
        self.truncated = False

        # Counters first: they record who is on the ball this cycle (offense before defense, as HFORef iterates).
        capture = self._capture_distance
        offense_on_ball = defense_on_ball = goalie_on_ball = False
        players = self.players
        if players is None:
            players = world.players
        for p in players:
            if _hypot(p.x - bx, p.y - by) <= capture:
                if p.side == DEFENSE_SIDE:
                    defense_on_ball = True
                    if p.unum == KEEPER_UNUM:
                        goalie_on_ball = True
                else:
                    offense_on_ball = True
        if offense_on_ball:
            self.take_time = 0
        if defense_on_ball:
            self.take_time += 1
        if offense_on_ball or defense_on_ball:
            self.untouched = 0
        else:
            self.untouched += 1

        if previous_x <= GOAL_LINE_X < bx:
            crossing_y = previous_y + (by - previous_y) * (GOAL_LINE_X - previous_x) / (bx - previous_x)
            if abs(crossing_y) <= GOAL_MOUTH_HALF_WIDTH:
                return GOAL
        if not (0.0 <= previous_x <= PITCH_HALF_LENGTH and abs(previous_y) <= PITCH_HALF_WIDTH):
            return OUT_OF_BOUNDS
        # The goalie being the latest player on the ball captures it at once; other defenders need TURNOVER_TIME.
        if goalie_on_ball or self.take_time >= TURNOVER_TIME:
            return CAPTURED_BY_DEFENSE
        if self.untouched > self.untouched_time:
            return OUT_OF_TIME
        if self.trial_time > 0 and self.cycles >= self.trial_time:
            self.truncated = True
            return OUT_OF_TIME
        return IN_GAME


#: The name of rcssserver's HFO referee, as hfo2d first called it (``Referee`` with rules "rcssserver").
HFOReferee = Referee
