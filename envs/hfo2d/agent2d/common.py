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
from dataclasses import dataclass, field

# --- constants (GF) -------------------------------------------------------------------------------------------
PITCH_HALF_LENGTH = 52.5
PITCH_HALF_WIDTH = 34.0
GOAL_HALF_WIDTH = 7.01
PENALTY_AREA_X = (
    -36.0
)  # GF penalty-area line (36 m from the halfway line: rcssserver penalty_area_length 16.5)
PENALTY_AREA_HALF_WIDTH = 20.16
OWN_GOAL = (-52.5, 0.0)  # G0
KICKABLE_AREA = 1.085  # player_size 0.3 + kickable_margin 0.7 + ball_size 0.085
SELF_KICKABLE_DIST = KICKABLE_AREA - 0.055  # librcsc's fullstate kickable buffer
CATCHABLE_AREA = math.hypot(1.2, 0.5)  # librcsc ServerParam::catchableArea(): 1.3
CATCH_DIR_OFFSET = math.degrees(math.atan2(0.5, 1.2))  # 22.62: the diagonal of the catch rectangle
PLAYER_DECAY = 0.4
BALL_DECAY = 0.94
DASH_RATE = 0.006  # dash_power_rate * effort (effort 1.0)
PLAYER_SPEED_MAX = 1.05
REAL_SPEED_MAX = 1.0  # librcsc PlayerType::realSpeedMax: min(1.05, 100 * 0.006 / (1 - 0.4))
INERTIA_MOMENT = 5.0
STAMINA_MAX = 8000.0
EXTRA_STAMINA = 50.0
STAMINA_INC_MAX = 45.0
CATCH_BAN_CYCLE = 5
TACKLE_CYCLES = 10

# intercept entry modes (librcsc InterceptInfo)
NORMAL = 0
EXHAUST = 1


def norm_deg(a: float) -> float:
    """An angle wrapped into [-180, 180] (librcsc AngleDeg::normalize_angle)."""
    if a < -360.0 or a > 360.0:
        a = math.fmod(a, 360.0)
    if a < -180.0:
        a += 360.0
    if a > 180.0:
        a -= 360.0
    return a


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
        return 0.6 - 0.2 * (1.0 - (a - 90.0) / 90.0)
    return 0.4 + 0.6 * (1.0 - a / 90.0)


def eff_turn(speed: float) -> float:
    """The largest actual body turn (deg) at speed ``speed``: 180 / (1 + inertia_moment * speed)."""
    return 180.0 / (1.0 + INERTIA_MOMENT * speed)


def first_term(dist: float, n: int, decay: float = PLAYER_DECAY) -> float:
    """The first speed of a geometric series (ratio ``decay``) that covers ``dist`` in ``n`` terms."""
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
    accel = 100.0 * DASH_RATE  # 0.6
    for _ in range(50):
        speed = min(speed + accel, REAL_SPEED_MAX)
        dist += speed
        table.append(dist)
        speed *= PLAYER_DECAY
    return table


DASH_DISTANCE_TABLE: tuple[float, ...] = tuple(_dash_distance_table())


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
