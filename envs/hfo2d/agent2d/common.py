"""Shared vocabulary of the agent2d goalie port: the goalie's view of the world, commands, intercept entries.

Everything in :mod:`hfo2d.agent2d` reasons in the **goalie frame** (GF) that librcsc uses for the right-hand
team: the defended goal is at x = -52.5. The map from hfo2d's global frame G (the goalie defends x = +52.5) is a
180 degree rotation, (x, y)_GF = (-x, -y)_G and angle_GF = norm(angle_G - 180); relative angles (turn moments,
dash and catch directions) are the same in both frames.

Sources (facts and numbers, no code): HFO b8b2a1d (agent2d-3.1 goalie as extracted into HFO), librcsc d222758
and rcssserver 15.2.2 (``mhauskn`` forks), as summarised in the project's agent2d goalie specification and
checked against those sources and the real program.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

# librcsc AngleDeg::normalize_angle, re-exported for the agent2d modules; features.py is the leaf both share
from hfo2d.features import norm_deg as norm_deg
from hfo2d.physics import ServerParams

# --- constants (GF) -------------------------------------------------------------------------------------------
# The field's geometry is not a server parameter hfo2d lets one change (hfo2d.physics fixes it too).
PITCH_HALF_LENGTH = 52.5
PITCH_HALF_WIDTH = 34.0
GOAL_HALF_WIDTH = 7.01
PENALTY_AREA_X = (
    -36.0
)  # GF penalty-area line (36 m from the halfway line: rcssserver penalty_area_length 16.5)
PENALTY_AREA_HALF_WIDTH = 20.16
OWN_GOAL = (-52.5, 0.0)  # G0


# --- server parameters -----------------------------------------------------------------------------------------
# The goalie's code reads the server's parameters from module constants, as librcsc reads them from the
# server_param message: bind_server_params() sets them (here and in every module of hfo2d.agent2d) from the
# ServerParams of the world the goalie plays in; at import they hold rcssserver 15.2.2's defaults.
_BINDERS: list[Callable[[ServerParams], None]] = []
_CANONICAL: dict[ServerParams, ServerParams] = {}
#: The ServerParams the constants of hfo2d.agent2d hold now (read it, do not assign it: bind_server_params).
BOUND_PARAMS: ServerParams | None = None


def canonical_params(params: ServerParams) -> ServerParams:
    """The first ServerParams seen equal to ``params``: goalies of equal parameters share one object, so that
    :func:`bind_server_params` tells them apart by identity alone."""
    found = _CANONICAL.get(params)
    if found is None:
        found = _CANONICAL[params] = params
    return found


def bind_server_params(params: ServerParams) -> None:
    """Set the server constants of every :mod:`hfo2d.agent2d` module from ``params`` (nothing to do when they
    hold them already). Pass a :func:`canonical_params` object: the test is by identity."""
    global BOUND_PARAMS
    if params is BOUND_PARAMS:
        return
    for bind in _BINDERS:
        bind(params)
    BOUND_PARAMS = params


def register_binder(bind: Callable[[ServerParams], None]) -> None:
    """Add a module's binder (called in import order, so that a module finds this one's constants set) and
    bind it to the parameters bound now."""
    _BINDERS.append(bind)
    assert BOUND_PARAMS is not None, "common binds its defaults before any module registers"
    bind(BOUND_PARAMS)


def decimal_difference(a: float, b: float) -> float:
    """``a - b`` as the decimal it is: the server's parameters are decimals in its configuration, and this port
    uses e.g. 0.6 - 0.4 as 0.2 (floating point gives 0.19999999999999996) where it was checked so."""
    return round(a - b, 12)


def _bind(sp: ServerParams) -> None:
    global KICKABLE_AREA, SELF_KICKABLE_DIST, CATCHABLE_AREA, CATCH_DIR_OFFSET, PLAYER_DECAY, BALL_DECAY
    global DASH_RATE, PLAYER_SPEED_MAX, REAL_SPEED_MAX, INERTIA_MOMENT, STAMINA_MAX, EXTRA_STAMINA
    global STAMINA_INC_MAX, CATCH_BAN_CYCLE, TACKLE_CYCLES, SIDE_DASH_RATE, BACK_DASH_RATE, MAX_DASH_POWER
    global _BACK_SIDE_GAP, _SIDE_GAP, DASH_DISTANCE_TABLE
    # player_size 0.3 + kickable_margin 0.7 + ball_size 0.085 = 1.085
    KICKABLE_AREA = sp.player_size + sp.kickable_margin + sp.ball_size
    SELF_KICKABLE_DIST = KICKABLE_AREA - 0.055  # librcsc's fullstate kickable buffer
    # librcsc ServerParam::catchableArea(): the diagonal of catchable_area_l 1.2 x catchable_area_w / 2 0.5: 1.3
    CATCHABLE_AREA = math.hypot(sp.catchable_area_l, sp.catchable_area_w * 0.5)
    # 22.62: the direction of that diagonal
    CATCH_DIR_OFFSET = math.degrees(math.atan2(sp.catchable_area_w * 0.5, sp.catchable_area_l))
    PLAYER_DECAY = sp.player_decay  # 0.4
    BALL_DECAY = sp.ball_decay  # 0.94
    DASH_RATE = sp.dash_power_rate * sp.effort_init  # dash_power_rate 0.006 * effort (effort_init 1.0)
    PLAYER_SPEED_MAX = sp.player_speed_max  # 1.05
    MAX_DASH_POWER = sp.maxpower  # 100
    # librcsc PlayerType::realSpeedMax: min(player_speed_max 1.05, maxpower 100 * 0.006 * effort 1 / (1 - 0.4)) = 1
    REAL_SPEED_MAX = min(PLAYER_SPEED_MAX, MAX_DASH_POWER * DASH_RATE / (1.0 - PLAYER_DECAY))
    INERTIA_MOMENT = sp.inertia_moment  # 5
    STAMINA_MAX = sp.stamina_max  # 8000
    EXTRA_STAMINA = sp.extra_stamina  # 50
    STAMINA_INC_MAX = sp.stamina_inc_max  # 45
    CATCH_BAN_CYCLE = int(sp.catch_ban_cycle)  # 5
    TACKLE_CYCLES = int(sp.tackle_cycles)  # 10
    SIDE_DASH_RATE = sp.side_dash_rate  # 0.4
    BACK_DASH_RATE = sp.back_dash_rate  # 0.6
    _BACK_SIDE_GAP = decimal_difference(BACK_DASH_RATE, SIDE_DASH_RATE)  # 0.2
    _SIDE_GAP = decimal_difference(1.0, SIDE_DASH_RATE)  # 0.6
    DASH_DISTANCE_TABLE = tuple(_dash_distance_table())


# intercept entry modes (librcsc InterceptInfo)
NORMAL = 0
EXHAUST = 1


def angle_of(x: float, y: float) -> float:
    """atan2(y, x) in degrees; 0 for the zero vector (librcsc Vector2D::th)."""
    if x == 0.0 and y == 0.0:
        return 0.0
    return math.degrees(math.atan2(y, x))


def rotate(x: float, y: float, deg: float) -> tuple[float, float]:
    """(x, y) rotated by ``deg`` degrees (counter-clockwise in the usual maths sense)."""
    r = math.radians(deg)
    c, s = math.cos(r), math.sin(r)
    return x * c - y * s, x * s + y * c


def polar(length: float, deg: float) -> tuple[float, float]:
    r = math.radians(deg)
    return length * math.cos(r), length * math.sin(r)


def dir_rate(d: float) -> float:
    """rcssserver's dash-direction rate for a direction already rounded to a multiple of 45 degrees."""
    a = abs(d)
    if a > 90.0:
        return BACK_DASH_RATE - _BACK_SIDE_GAP * (1.0 - (a - 90.0) / 90.0)
    return SIDE_DASH_RATE + _SIDE_GAP * (1.0 - a / 90.0)


def eff_turn(speed: float) -> float:
    """The largest actual body turn (deg) at speed ``speed``: 180 / (1 + inertia_moment * speed)."""
    return 180.0 / (1.0 + INERTIA_MOMENT * speed)


def first_term(dist: float, n: int, decay: float | None = None) -> float:
    """The first speed of a geometric series (ratio ``decay``, default the player decay) that covers ``dist`` in
    ``n`` terms."""
    if decay is None:
        decay = PLAYER_DECAY
    return dist * (1.0 - decay) / (1.0 - decay**n)


def ball_at(bx: float, by: float, wx: float, wy: float, n: int) -> tuple[float, float]:
    """Ball position after ``n`` cycles of free motion (ballAt(n) of the specification)."""
    f = (1.0 - BALL_DECAY**n) / (1.0 - BALL_DECAY)
    return bx + wx * f, by + wy * f


def inertia_point(px: float, py: float, vx: float, vy: float, n: int) -> tuple[float, float]:
    """Player position after ``n`` cycles without dashing (selfAt(n))."""
    f = (1.0 - PLAYER_DECAY**n) / (1.0 - PLAYER_DECAY)
    return px + vx * f, py + vy * f


def _dash_distance_table() -> list[float]:
    """librcsc PlayerType dash-distance table: distance covered by n full dashes from rest (50 entries)."""
    table: list[float] = []
    speed = 0.0
    dist = 0.0
    accel = MAX_DASH_POWER * DASH_RATE  # 0.6
    for _ in range(50):
        speed = min(speed + accel, REAL_SPEED_MAX)
        dist += speed
        table.append(dist)
        speed *= PLAYER_DECAY
    return table


_DEFAULT_PARAMS = ServerParams()
BOUND_PARAMS = canonical_params(_DEFAULT_PARAMS)
register_binder(_bind)


def cycles_to_reach(dist: float) -> int:
    """librcsc PlayerType::cyclesToReachDistance: full-dash cycles from rest to cover ``dist``."""
    if dist <= 0.001:
        return 0
    target = dist - 0.001
    for i, d in enumerate(DASH_DISTANCE_TABLE):
        if d >= target:
            return i + 1
    rest = dist - DASH_DISTANCE_TABLE[-1]
    return len(DASH_DISTANCE_TABLE) + math.ceil(rest / REAL_SPEED_MAX)


# --- the goalie's world model for one decision ----------------------------------------------------------------
@dataclass(slots=True)
class GoalieView:
    """What the goalie knows when it decides (fullstate: the true state), in GF.

    ``wx``, ``wy`` are the ball velocity as the goalie's world model has it: zero when ``kick_opp`` holds and the
    goalie is not kickable itself (librcsc WorldModel), the true velocity otherwise (``true_wx``, ``true_wy``).
    """

    cycle: int
    px: float
    py: float
    vx: float
    vy: float
    body: float  # deg, GF
    stamina: float
    effort: float
    recovery: float
    bx: float
    by: float
    wx: float
    wy: float
    true_wx: float
    true_wy: float
    has_opp: bool
    ox: float = 0.0
    oy: float = 0.0
    ux: float = 0.0
    uy: float = 0.0
    obody: float = 0.0  # deg, GF
    opp_tackle_count: int = 0  # cycles the attacker stays frozen by its own tackle (0: not tackling)
    kick_opp: bool = False
    self_kickable: bool = False
    lk_not_ours: bool = True  # the last kicker is not the goalie's side
    play_on: bool = True  # False only in GoalieCatch mode after a non-terminal catch
    # the server's noise parameters as the client reads them (0 under HFO's --deterministic); librcsc's
    # intercept and WaitTurn margins use them
    ball_rand: float = 0.05
    player_rand: float = 0.1

    @property
    def ball_dist(self) -> float:
        return math.hypot(self.bx - self.px, self.by - self.py)

    @property
    def speed(self) -> float:
        return math.hypot(self.vx, self.vy)


# --- intercept table ------------------------------------------------------------------------------------------
@dataclass(slots=True)
class InterceptEntry:
    """One self-intercept candidate (librcsc InterceptInfo), GF."""

    mode: int  # NORMAL or EXHAUST
    turn_cycle: int
    dash_cycle: int
    dash_power: float  # the first dash's power (negative: a back dash)
    dash_dir: float  # relative dash direction of the first dash (deg)
    self_x: float  # where the goalie ends
    self_y: float
    ball_dist: float  # the final distance to the ball
    stamina: float  # the stamina after the move

    @property
    def reach_cycle(self) -> int:
        return self.turn_cycle + self.dash_cycle


@dataclass(slots=True)
class InterceptTable:
    """librcsc InterceptTable for one decision: the ball cache, the sorted self cache and both reach cycles."""

    ball_cache: list[tuple[float, float]]  # ball positions B_0 (= B), B_1, ... under W
    self_cache: list[InterceptEntry] = field(default_factory=list)  # sorted by (reach, turns)
    self_min: int = 1000
    opp_min: int = 1000
    complete: bool = (
        True  # False: the self cache stops at its fastest entry (enough for self_min and opp_min)
    )


# --- commands -------------------------------------------------------------------------------------------------
@dataclass(slots=True)
class Command:
    """One body command as the goalie's code asks for it (before librcsc's client conversions).

    ``kind`` is "turn" (``a``: the desired actual turn, deg), "dash" (``a``: power, ``b``: relative direction),
    "catch" (``a``: relative direction) or "tackle" (``a``: relative direction, ``foul``).
    """

    kind: str
    a: float = 0.0
    b: float = 0.0
    foul: bool = False


class Effector:
    """Collects the body command of one decision: later calls replace earlier ones (librcsc ActionEffector)."""

    __slots__ = ("command",)

    def __init__(self) -> None:
        self.command: Command | None = None

    def turn(self, desired_deg: float) -> None:
        self.command = Command("turn", desired_deg)

    def dash(self, power: float, direction_deg: float = 0.0) -> None:
        self.command = Command("dash", power, direction_deg)

    def catch(self, direction_deg: float) -> None:
        self.command = Command("catch", direction_deg)

    def tackle(self, direction_deg: float, foul: bool = False) -> None:
        self.command = Command("tackle", direction_deg, foul=foul)
