"""Soccer physics of HFO's rcssserver, one 100 ms server cycle per :meth:`World.step`.

Sources (numbers and rules, no code): rcssserver 15.2.2 as forked by HFO (``mhauskn/rcssserver``:
``serverparam.cpp``, ``player.cpp``, ``object.cpp``, ``stadium.cpp``) and the client library HFO agents
use, librcsc (``mhauskn/librcsc``: ``action_effector.cpp``), both via hfo_reference §1, §3.2, §4 and §9.

Units and frame are rcssserver's: metres, metres per cycle, degrees; 0 deg faces +x (the attacked goal),
+90 deg faces +y (down on screen), so a positive relative angle means "on the agent's right".

Order of one cycle (rcssserver ``Stadium::step``, hfo_reference §4.1):

1. Commands act as they arrive, i.e. when :meth:`World.dash`, :meth:`World.turn`, :meth:`World.kick`,
   :meth:`World.catch` or :meth:`World.tackle` is called: a turn changes the body angle at once, a dash adds
   to the player's acceleration, a kick or a tackle adds to the ball's acceleration, a successful catch moves
   the goalie next to the ball and resolves the overlaps at once. A player frozen by its own tackle ignores
   every body command. :meth:`World.step` first counts the freezes down (``Player::resetCommandFlags``).
2. :meth:`World.step` moves every object (``MPObject::_inc``): cap |a| at accel_max, v += a, cap |v| at
   speed_max (only when a != 0); v += polar(U(0, rand*|v|), U(-pi, pi)); goal-post overlap and path
   intersection are resolved by reflecting the velocity about the post normal (elastic); pos += v;
   v *= decay; a = 0.
3. Overlaps (``Stadium::collisions``): ball-player pairs closer than player_size + ball_size, player-player
   pairs closer than 2 * player_size are pushed apart symmetrically about their midpoint until just
   touching (each object moves to the mean of the positions its pairs ask for), for up to 10 passes; every
   object that collided then gets v *= -0.1.
4. Stamina, effort and recovery of every player are updated (``Player::updateStamina``), then the goalie
   catch bans count down (``Player::updateCapacity``).

rcssserver shuffles the objects before step 2; the moves of different objects are independent, so the order
only changes which random number goes to which object and a fixed order (players, then the ball) is used.

pymunk holds one kinematic body + circle shape per player and for the ball, and static circle shapes for the
four goal posts. It answers the goal-post questions (does the object overlap a post: ``Shape.point_query``;
where does its path enter one, with which normal: swept ``Shape.segment_query``) and, with
``pymunk_contacts=True``, the contact normal of two overlapping objects (``Shape.shapes_collide``). It never
integrates or resolves contacts: rcssserver's rules decide what happens. Each pymunk query costs about 3 us
(measured, pymunk 7.3) against ~0.1 us for the same few float operations, so a float pre-test runs first and
pymunk is asked only when an object can reach a post this cycle; the object-object overlap test itself is
rcssserver's squared-distance comparison in floats.
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from collections.abc import Mapping
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import pymunk

from hfo2d import accel as _accel

# --- geometry (rcssserver 15.2.2 constants, hfo_reference §1) ---------------------------------------
PITCH_HALF_LENGTH: float = 52.5
PITCH_HALF_WIDTH: float = 34.0
GOAL_HALF_WIDTH: float = 7.01
GOAL_POST_RADIUS: float = 0.06
GOAL_POSTS: tuple[tuple[float, float], tuple[float, float]] = ((52.44, -7.07), (52.44, 7.07))
PENALTY_AREA_X: float = 36.0
PENALTY_AREA_HALF_WIDTH: float = 20.16

# librcsc treats the ball as kickable only this far inside the server's kickable_area when the ball
# position is fully known (fullstate, seenPosCount = 0); hfo_reference §3.2 and §8 item 4.
CLIENT_KICKABLE_BUFFER: float = 0.055

# rcssserver's EPS, added when separating overlapping objects so that they end just apart.
_EPS: float = 1.0e-10
_DEG = math.pi / 180.0
_TWO_PI = 2.0 * math.pi
# hfo2d._accel's kernel of World._move, or None for the pure-Python code (hfo2d.accel)
_ACCEL = _accel.ACCEL
_ACCEL_MOVE = None if _ACCEL is None else _ACCEL.move_object
_RANDOM_BLOCK = 1024  # uniforms drawn from the numpy Generator at a time (one call ~1 us, per-float ~10 ns)
_POST_CATEGORY = 0b1
_OBJECT_CATEGORY = 0b10


@dataclass(frozen=True)
class ServerParams:
    """rcssserver parameters of the default player type, by rcssserver name, with HFO's defaults.

    Values: rcssserver 15.2.2 ``serverparam.cpp`` as HFO builds it (hfo_reference §4, §9). Units: metres,
    m/cycle, m/cycle², degrees, stamina units. Thresholds ``*_thr`` are fractions of ``stamina_max``.
    Catch and tackle parameters are used by :meth:`World.catch` and :meth:`World.tackle`; the wind ones are
    kept for completeness (wind is not simulated).
    """

    player_size: float = 0.3
    ball_size: float = 0.085
    player_decay: float = 0.4
    ball_decay: float = 0.94
    player_rand: float = 0.1
    ball_rand: float = 0.05
    kick_rand: float = 0.1
    player_speed_max: float = 1.05
    ball_speed_max: float = 3.0
    player_accel_max: float = 1.0
    ball_accel_max: float = 2.7
    dash_power_rate: float = 0.006
    kick_power_rate: float = 0.027
    kickable_margin: float = 0.7
    inertia_moment: float = 5.0
    min_moment: float = -180.0
    max_moment: float = 180.0
    minpower: float = -100.0
    maxpower: float = 100.0
    min_dash_angle: float = -180.0
    max_dash_angle: float = 180.0
    dash_angle_step: float = 45.0
    side_dash_rate: float = 0.4
    back_dash_rate: float = 0.6
    stamina_max: float = 8000.0
    stamina_inc_max: float = 45.0
    extra_stamina: float = 50.0
    stamina_capacity: float = 130600.0
    effort_init: float = 1.0
    effort_min: float = 0.6
    effort_dec_thr: float = 0.3
    effort_dec: float = 0.005
    effort_inc_thr: float = 0.6
    effort_inc: float = 0.01
    recover_init: float = 1.0
    recover_dec_thr: float = 0.3
    recover_dec: float = 0.002
    recover_min: float = 0.5
    wind_force: float = 0.0
    wind_rand: float = 0.0
    catchable_area_l: float = 1.2
    catchable_area_w: float = 1.0
    catch_probability: float = 1.0
    catch_ban_cycle: float = 5.0
    tackle_dist: float = 2.0
    tackle_back_dist: float = 0.0
    tackle_width: float = 1.25
    tackle_exponent: float = 6.0
    tackle_cycles: float = 10.0
    tackle_power_rate: float = 0.027
    max_tackle_power: float = 100.0
    max_back_tackle_power: float = 0.0
    slowness_on_top_for_left_team: float = 1.0
    slowness_on_top_for_right_team: float = 1.0
    goal_width: float = 2.0 * GOAL_HALF_WIDTH
    # rcssserver player_type.cpp: the default type's catchable_area_l_stretch is 1.0 (heterogeneous-type parameter)
    catch_area_l_stretch: float = 1.0
    # rcssserver serverparam.cpp: FOUL_EXPONENT 10.0, TACKLE_RAND_FACTOR 2.0
    foul_exponent: float = 10.0
    tackle_rand_factor: float = 2.0

    @property
    def kickable_area(self) -> float:
        """Server-side kick range in metres: player_size + kickable_margin + ball_size (= 1.085)."""
        return self.player_size + self.kickable_margin + self.ball_size

    @property
    def client_kickable_area(self) -> float:
        """Range (m) within which librcsc lets an agent kick: kickable_area - 0.055 (= 1.03)."""
        return self.kickable_area - CLIENT_KICKABLE_BUFFER

    @classmethod
    def field_names(cls) -> tuple[str, ...]:
        """All parameter names, in declaration order."""
        return tuple(f.name for f in dataclasses.fields(cls))

    @classmethod
    def with_overrides(cls, overrides: Mapping[str, float] | None = None) -> ServerParams:
        """HFO's defaults with some parameters replaced, each named by its rcssserver name.

        Raises:
            ValueError: for overrides that are not a mapping, an unknown name (the message lists the valid
                ones), a value that is not a finite real number, a value outside its range
                (:data:`SERVER_PARAM_RANGES`), or a non-zero wind (wind is not simulated).
        """
        if overrides is not None and not isinstance(overrides, Mapping):
            raise ValueError(
                "server_params must be a mapping of rcssserver names to numbers, e.g. {'ball_decay': 0.9}; "
                f"got {type(overrides).__name__} {overrides!r}"
            )
        if not overrides:
            return cls()
        valid = cls.field_names()
        unknown = sorted(str(k) for k in overrides if k not in valid)
        if unknown:
            raise ValueError(f"unknown server parameter(s) {unknown}; valid names: {', '.join(valid)}")
        values: dict[str, float] = {}
        for name, value in overrides.items():
            if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
                raise ValueError(f"server parameter {name!r} must be a real number, got {value!r}")
            number = float(value)
            if not math.isfinite(number):
                raise ValueError(f"server parameter {name!r} must be finite, got {value!r}")
            values[name] = number
        if values.get("wind_force", 0.0) != 0.0 or values.get("wind_rand", 0.0) != 0.0:
            raise ValueError("wind_force and wind_rand must stay 0: HFO runs without wind and so does hfo2d")
        for name, number in values.items():
            allowed = SERVER_PARAM_RANGES[name]
            if not allowed.contains(number):
                raise ValueError(f"server parameter {name!r} must be {allowed.describe()}, got {number!r}")
        return cls(**values)


class ParamRange(NamedTuple):
    """The values a server parameter may take: ``low <= value <= high`` (``low < value`` when ``low_open``)."""

    low: float
    high: float
    low_open: bool = False

    def contains(self, value: float) -> bool:
        """Whether ``value`` lies in the range (NaN never does)."""
        above = value > self.low if self.low_open else value >= self.low
        return above and value <= self.high

    def describe(self) -> str:
        """The range in words: "in [0, 1]", "> 0", ">= 0", "<= 0", "any number"."""
        low_finite, high_finite = math.isfinite(self.low), math.isfinite(self.high)
        if low_finite and high_finite:
            return f"in {'(' if self.low_open else '['}{self.low:g}, {self.high:g}]"
        if low_finite:
            return f"{'>' if self.low_open else '>='} {self.low:g}"
        return f"<= {self.high:g}" if high_finite else "any number"


_INF = math.inf
_POSITIVE = ParamRange(0.0, _INF, low_open=True)
_NON_NEGATIVE = ParamRange(0.0, _INF)
_FRACTION = ParamRange(0.0, 1.0)
#: The range of every :class:`ServerParams` field, checked by :meth:`ServerParams.with_overrides`. Not
#: rcssserver's (it checks almost nothing): the values for which the rules hfo2d simulates stay meaningful
#: (sizes, speeds and widths > 0; decays, rands, rates and stamina thresholds fractions; lower limits <= 0 <=
#: upper ones; no wind).
SERVER_PARAM_RANGES: dict[str, ParamRange] = {
    "player_size": _POSITIVE,
    "ball_size": _POSITIVE,
    "player_decay": _FRACTION,
    "ball_decay": _FRACTION,
    "player_rand": _FRACTION,
    "ball_rand": _FRACTION,
    "kick_rand": _FRACTION,
    "player_speed_max": _POSITIVE,
    "ball_speed_max": _POSITIVE,
    "player_accel_max": _POSITIVE,
    "ball_accel_max": _POSITIVE,
    "dash_power_rate": _NON_NEGATIVE,
    "kick_power_rate": _NON_NEGATIVE,
    "kickable_margin": _NON_NEGATIVE,
    "inertia_moment": _NON_NEGATIVE,
    "min_moment": ParamRange(-180.0, 0.0),
    "max_moment": ParamRange(0.0, 180.0),
    "minpower": ParamRange(-_INF, 0.0),
    "maxpower": _POSITIVE,
    "min_dash_angle": ParamRange(-180.0, 0.0),
    "max_dash_angle": ParamRange(0.0, 180.0),
    # dash directions are rounded to multiples of dash_angle_step
    "dash_angle_step": ParamRange(0.0, 360.0, low_open=True),
    "side_dash_rate": _FRACTION,
    "back_dash_rate": _FRACTION,
    "stamina_max": _POSITIVE,
    "stamina_inc_max": _NON_NEGATIVE,
    "extra_stamina": _NON_NEGATIVE,
    # rcssserver player.cpp (updateStamina): a negative stamina_capacity means no capacity limit
    "stamina_capacity": ParamRange(-_INF, _INF),
    "effort_init": _FRACTION,
    "effort_min": _FRACTION,
    "effort_dec_thr": _FRACTION,
    "effort_dec": _NON_NEGATIVE,
    "effort_inc_thr": _FRACTION,
    "effort_inc": _NON_NEGATIVE,
    "recover_init": _FRACTION,
    "recover_dec_thr": _FRACTION,
    "recover_dec": _NON_NEGATIVE,
    "recover_min": _FRACTION,
    "wind_force": ParamRange(0.0, 0.0),
    "wind_rand": ParamRange(0.0, 0.0),
    "catchable_area_l": _POSITIVE,
    "catchable_area_w": _POSITIVE,
    "catch_probability": _FRACTION,
    "catch_ban_cycle": _NON_NEGATIVE,
    "tackle_dist": _NON_NEGATIVE,
    "tackle_back_dist": _NON_NEGATIVE,
    "tackle_width": _POSITIVE,
    "tackle_exponent": _NON_NEGATIVE,
    "tackle_cycles": _NON_NEGATIVE,
    "tackle_power_rate": _NON_NEGATIVE,
    "max_tackle_power": _NON_NEGATIVE,
    "max_back_tackle_power": _NON_NEGATIVE,
    "slowness_on_top_for_left_team": _NON_NEGATIVE,
    "slowness_on_top_for_right_team": _NON_NEGATIVE,
    "goal_width": _POSITIVE,
    # rcssserver playerparam.cpp: catchable_area_l_stretch_min 1.0 (heterogeneous types stretch, never shrink)
    "catch_area_l_stretch": ParamRange(1.0, _INF),
    "foul_exponent": _NON_NEGATIVE,
    "tackle_rand_factor": _NON_NEGATIVE,
}


@dataclass(slots=True)
class PlayerState:
    """One player. Positions in m, velocities in m/cycle as held between cycles (after decay).

    ``body_deg`` is in [-180, 180). ``ax``, ``ay`` hold the acceleration of a dash issued this cycle.
    The ``collided_*`` flags describe the last :meth:`World.step`, including the overlaps a catch resolved just
    before it (rcssserver's sense_body reports those with the step).
    ``catch_ban``: cycles before this goalie may catch again (rcssserver ``M_goalie_catch_ban``).
    ``tackle_cycles``: cycles this player stays frozen by its own tackle (``M_tackle_cycles``); while it is > 0
    every body command is ignored. Placing a player resets neither (rcssserver ``Player::place``).
    """

    side: str  # "l" offense, "r" defense
    unum: int
    goalie: bool = False
    x: float = 0.0
    y: float = 0.0
    vx: float = 0.0
    vy: float = 0.0
    body_deg: float = 0.0
    ax: float = 0.0
    ay: float = 0.0
    stamina: float = 8000.0
    effort: float = 1.0
    recovery: float = 1.0
    capacity: float = 130600.0
    collided_ball: bool = False
    collided_player: bool = False
    collided_post: bool = False
    catch_ban: int = 0
    tackle_cycles: int = 0


@dataclass(slots=True)
class BallState:
    """The ball: position (m), velocity (m/cycle, after decay), pending acceleration (m/cycle²).

    ``collided_post`` / ``collided_player`` describe the last :meth:`World.step` (``collided_player`` is an
    addition to the contract: the ball overlapped some player and was pushed away).
    """

    x: float = 0.0
    y: float = 0.0
    vx: float = 0.0
    vy: float = 0.0
    ax: float = 0.0
    ay: float = 0.0
    collided_post: bool = False
    collided_player: bool = False


def normalize_deg(angle_deg: float) -> float:
    """Angle folded into [-180, 180) degrees."""
    return (angle_deg + 180.0) % 360.0 - 180.0


class World:
    """The ball, the players and the goal posts, advanced one rcssserver cycle at a time.

    Args:
        params: server parameters (use :meth:`ServerParams.with_overrides` to change them).
        rng: source of all randomness (noise and rare tie-breaks). Uniforms are drawn from it in blocks of
            1024, so results are reproducible for a given generator state and call sequence. Assigning
            ``world.rng`` replaces it and discards the buffered draws.
        noise: False turns off the three noise sources (player_rand, ball_rand, kick_rand), like HFO's
            ``--deterministic`` (which also zeroes the tackle noise, a multiple of kick_rand). The success draws
            of a tackle, and of a catch when catch_probability < 1, stay random, as in HFO.
        pymunk_contacts: take the separation direction of two overlapping objects from pymunk's
            ``Shape.shapes_collide`` contact normal instead of the centre line computed in floats. Both give
            the same unit vector (tested); the pymunk path syncs two bodies and costs about 13 us per
            overlapping cycle against under 1 us, and an agent pushing the ball overlaps it most cycles,
            so the float path is the default.

    Attributes:
        play_on: whether the server's play mode is PlayOn (default True; HFO episodes always are). A catch
            outside PlayOn is a fault, a successful tackle outside PlayOn leaves the ball alone.
    """

    def __init__(
        self,
        params: ServerParams,
        rng: np.random.Generator,
        noise: bool = True,
        *,
        pymunk_contacts: bool = False,
    ) -> None:
        self.params = params
        self.noise = noise
        self.pymunk_contacts = pymunk_contacts
        self._rng = rng
        self._uniforms: list[float] = []
        self._next_uniform = 0
        self.ball = BallState()
        self.players: list[PlayerState] = []
        self.cycle = 0
        self.play_on = True
        # collision flags raised by a catch's overlap resolution, reported with the next step
        self._catch_contacts: list[tuple[PlayerState | BallState, bool, bool]] = []

        self._post_x = PITCH_HALF_LENGTH - GOAL_POST_RADIUS
        self._post_y = 0.5 * params.goal_width + GOAL_POST_RADIUS

        self.space = pymunk.Space()
        # posts by (x > 0, y > 0), as rcssserver's nearestPost picks them
        self._posts_by_quadrant: dict[tuple[bool, bool], pymunk.Circle] = {}
        for sx in (1.0, -1.0):
            for sy in (-1.0, 1.0):
                post = pymunk.Circle(
                    self.space.static_body, GOAL_POST_RADIUS, (sx * self._post_x, sy * self._post_y)
                )
                post.filter = pymunk.ShapeFilter(categories=_POST_CATEGORY)
                self.space.add(post)
                self._posts_by_quadrant[(sx > 0.0, sy > 0.0)] = post
        self._derived: tuple = ()
        self._derive()
        self._ball_body, self._ball_shape = self._new_body(params.ball_size)
        self._player_bodies: list[pymunk.Body] = []
        self._player_shapes: list[pymunk.Circle] = []

    # --- set-up ------------------------------------------------------------------------------------
    def _derive(self) -> tuple:
        """Products of parameters that step() would otherwise recompute every cycle, each formed with the same
        operation as in the rule that uses it (so the floats are the same); recomputed if ``params`` is replaced."""
        sp = self.params
        smax = sp.stamina_max
        bp_limit = sp.ball_size + sp.player_size
        pp_limit = 2.0 * sp.player_size
        self._derived = (
            sp,
            (sp.player_size, sp.player_decay, sp.player_rand, sp.player_speed_max, sp.player_accel_max),
            (sp.ball_size, sp.ball_decay, sp.ball_rand, sp.ball_speed_max, sp.ball_accel_max),
            (bp_limit * bp_limit, pp_limit * pp_limit),
            (sp.recover_dec_thr * smax, sp.effort_dec_thr * smax, sp.effort_inc_thr * smax),
            sp.kickable_area - CLIENT_KICKABLE_BUFFER,  # client_kick's reach
        )
        return self._derived

    @property
    def rng(self) -> np.random.Generator:
        """The generator all random numbers come from."""
        return self._rng

    @rng.setter
    def rng(self, rng: np.random.Generator) -> None:
        self._rng = rng
        self._uniforms = []
        self._next_uniform = 0

    def _new_body(self, radius: float) -> tuple[pymunk.Body, pymunk.Circle]:
        body = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        shape = pymunk.Circle(body, radius)
        shape.filter = pymunk.ShapeFilter(categories=_OBJECT_CATEGORY, mask=0)
        self.space.add(body, shape)
        return body, shape

    def add_player(self, side: str, unum: int, goalie: bool = False) -> PlayerState:
        """Add a player at the origin with full stamina; returns its state (also in ``players``)."""
        if side not in ("l", "r"):
            raise ValueError(f"side must be 'l' or 'r', got {side!r}")
        p = self.params
        player = PlayerState(
            side=side,
            unum=unum,
            goalie=goalie,
            stamina=p.stamina_max,
            effort=p.effort_init,
            recovery=p.recover_init,
            capacity=p.stamina_capacity,
        )
        body, shape = self._new_body(p.player_size)
        self.players.append(player)
        self._player_bodies.append(body)
        self._player_shapes.append(shape)
        return player

    def place_player(
        self, p: PlayerState, x: float, y: float, body_deg: float, vx: float = 0.0, vy: float = 0.0
    ) -> None:
        """Move a player (m), set its body angle (deg) and velocity (m/cycle); clears its acceleration."""
        p.x, p.y, p.vx, p.vy = float(x), float(y), float(vx), float(vy)
        p.body_deg = normalize_deg(float(body_deg))
        p.ax = p.ay = 0.0

    def place_ball(self, x: float, y: float, vx: float = 0.0, vy: float = 0.0) -> None:
        """Move the ball (m) and set its velocity (m/cycle); clears its acceleration."""
        b = self.ball
        b.x, b.y, b.vx, b.vy = float(x), float(y), float(vx), float(vy)
        b.ax = b.ay = 0.0

    def recover_players(self) -> None:
        """Full stamina, effort, recovery and capacity for everyone (HFO ``resetField`` -> recoveryPlayers)."""
        p = self.params
        for player in self.players:
            player.stamina = p.stamina_max
            player.effort = p.effort_init
            player.recovery = p.recover_init
            player.capacity = p.stamina_capacity

    def sync_pymunk(self) -> None:
        """Copy positions and velocities into the pymunk bodies (for tools that read ``space``).

        Not needed by the simulation itself, which syncs only the bodies it queries.
        """
        self._ball_body.position = (self.ball.x, self.ball.y)
        self._ball_body.velocity = (self.ball.vx, self.ball.vy)
        for player, body in zip(self.players, self._player_bodies, strict=True):
            body.position = (player.x, player.y)
            body.velocity = (player.vx, player.vy)
            body.angle = player.body_deg * _DEG
        self.space.reindex_shapes_for_body(self._ball_body)
        for body in self._player_bodies:
            self.space.reindex_shapes_for_body(body)

    # --- random numbers ----------------------------------------------------------------------------
    def _uniform(self) -> float:
        """One U[0, 1) draw from the buffered block."""
        i = self._next_uniform
        if i >= len(self._uniforms):
            self._uniforms = self._rng.random(_RANDOM_BLOCK).tolist()
            i = 0
        self._next_uniform = i + 1
        return self._uniforms[i]

    # --- queries -----------------------------------------------------------------------------------
    def ball_distance(self, p: PlayerState) -> float:
        """Centre distance (m) from player ``p`` to the ball."""
        return math.hypot(self.ball.x - p.x, self.ball.y - p.y)

    # --- server-side commands (rcssserver Player::dash / turn / kick, hfo_reference §4.2-4.4) ------
    # The clamps of the commands are min(hi, max(lo, v)) written out as the builtins decide them (max keeps lo
    # unless v > lo, min keeps hi unless the value < hi; NaN gives lo): a builtin call costs more than the rest.
    def _dash_dir_rate(self, dir_deg: float) -> float:
        p = self.params
        a = abs(dir_deg)
        if a > 90.0:
            rate = p.back_dash_rate - (p.back_dash_rate - p.side_dash_rate) * (1.0 - (a - 90.0) / 90.0)
        else:
            rate = p.side_dash_rate + (1.0 - p.side_dash_rate) * (1.0 - a / 90.0)
        rate = rate if rate > 0.0 else 0.0
        return rate if rate < 1.0 else 1.0

    def _discretize_dash_dir(self, direction_deg: float) -> float:
        p = self.params
        d = float(direction_deg)
        d = d if d > p.min_dash_angle else p.min_dash_angle
        d = d if d < p.max_dash_angle else p.max_dash_angle
        if p.dash_angle_step > 1.0e-10:
            # round() is round-half-to-even like C's rint() in the default rounding mode
            d = p.dash_angle_step * round(d / p.dash_angle_step)
        return d

    def dash(self, p: PlayerState, power: float, direction_deg: float = 0.0) -> None:
        """Server dash: power in [minpower, maxpower], direction (deg, relative to body) rounded to 45.

        Consumes stamina (power forward, -2*power backward, at most stamina + extra_stamina) and adds
        ``polar(|effort * power * dir_rate * dash_power_rate|, body + dir (+180 if power < 0))`` to the
        player's acceleration.
        """
        sp = self.params
        power = float(power)
        power = power if power > sp.minpower else sp.minpower
        power = power if power < sp.maxpower else sp.maxpower
        d = self._discretize_dash_dir(direction_deg)
        self._push_dash(p, power, d, self._dash_dir_rate(d))

    def _push_dash(self, p: PlayerState, power: float, d: float, dir_rate: float) -> None:
        """The stamina and acceleration part of ``Player::dash`` for a clamped power and rounded direction."""
        if p.tackle_cycles > 0:  # frozen by its own tackle: rcssserver ignores the command (M_command_done)
            return
        sp = self.params
        back = power < 0.0
        need = -2.0 * power if back else power
        available = p.stamina + sp.extra_stamina
        need = available if available < need else need  # min(need, available)
        left = p.stamina - need
        p.stamina = left if left > 0.0 else 0.0  # max(0.0, left)
        power = -0.5 * need if back else need
        edp = abs(p.effort * power * dir_rate * sp.dash_power_rate)
        if back:
            d += 180.0
        ang = (p.body_deg + d) * _DEG
        p.ax += edp * math.cos(ang)
        p.ay += edp * math.sin(ang)

    def turn(self, p: PlayerState, moment_deg: float) -> None:
        """Server turn: body += (1 + U(-player_rand, player_rand)) * clamp(moment) / (1 + inertia*|v|).

        Ignored (no random draw) while the player is frozen by its own tackle.
        """
        if p.tackle_cycles > 0:
            return
        sp = self.params
        moment = float(moment_deg)
        moment = moment if moment > sp.min_moment else sp.min_moment
        moment = moment if moment < sp.max_moment else sp.max_moment
        factor = 1.0
        if self.noise and sp.player_rand > 0.0:
            # self._uniform() and normalize_deg below written out: a turn is issued almost every cycle
            i = self._next_uniform
            if i >= len(self._uniforms):
                self._uniforms = self._rng.random(_RANDOM_BLOCK).tolist()
                i = 0
            self._next_uniform = i + 1
            factor += sp.player_rand * (2.0 * self._uniforms[i] - 1.0)
        speed = math.hypot(p.vx, p.vy)
        p.body_deg = (
            p.body_deg + factor * moment / (1.0 + sp.inertia_moment * speed) + 180.0
        ) % 360.0 - 180.0

    def kick(self, p: PlayerState, power: float, direction_deg: float) -> bool:
        """Server kick; returns False (no effect) unless the ball is within kickable_area (1.085 m) and the
        player is not frozen by its own tackle.

        The ball's acceleration gets ``polar(eff, body + dir)`` with
        ``eff = power * kick_power_rate * (1 - 0.25 * dir_diff/pi - 0.25 * gap/kickable_margin)`` plus, with
        noise, ``polar(U(0, m), U(-pi, pi))``, ``m = kick_rand * (|power|/maxpower) * (pos_rate + speed_rate)``.
        """
        if p.tackle_cycles > 0:
            return False
        sp = self.params
        power = min(sp.maxpower, max(sp.minpower, float(power)))
        direction = min(sp.max_moment, max(sp.min_moment, float(direction_deg)))
        ball = self.ball
        dx = ball.x - p.x
        dy = ball.y - p.y
        dist = math.hypot(dx, dy)
        if dist > sp.kickable_area:
            return False
        bearing = math.atan2(dy, dx) if dist > 0.0 else 0.0
        dir_diff = abs(math.remainder(bearing - p.body_deg * _DEG, _TWO_PI))
        gap = dist - sp.player_size - sp.ball_size
        eff = power * sp.kick_power_rate * (1.0 - 0.25 * dir_diff / math.pi - 0.25 * gap / sp.kickable_margin)
        ang = (p.body_deg + direction) * _DEG
        ax = eff * math.cos(ang)
        ay = eff * math.sin(ang)
        if self.noise and sp.kick_rand > 0.0:
            pos_rate = 0.5 + 0.25 * (dir_diff / math.pi + gap / sp.kickable_margin)
            speed_rate = 0.5 + 0.5 * math.hypot(ball.vx, ball.vy) / (sp.ball_speed_max * sp.ball_decay)
            max_rand = sp.kick_rand * (abs(power) / sp.maxpower) * (pos_rate + speed_rate)
            r = max_rand * self._uniform()
            th = math.pi * (2.0 * self._uniform() - 1.0)
            ax += r * math.cos(th)
            ay += r * math.sin(th)
        ball.ax += ax
        ball.ay += ay
        return True

    # --- client side (librcsc ActionEffector, hfo_reference §3.2) ----------------------------------
    def client_turn(self, p: PlayerState, desired_turn_deg: float) -> None:
        """HFO TURN: the argument is the desired actual turn; sends clamp(θ(1 + inertia*|v|), ±180)."""
        sp = self.params
        speed = math.hypot(p.vx, p.vy)
        moment = float(desired_turn_deg) * (1.0 + sp.inertia_moment * speed)
        moment = moment if moment > sp.min_moment else sp.min_moment
        self.turn(p, moment if moment < sp.max_moment else sp.max_moment)

    def client_dash(
        self, p: PlayerState, power: float, direction_deg: float = 0.0, limit_speed: bool = True
    ) -> None:
        """HFO DASH as librcsc sends it.

        Power clamped to [-100, 100]; direction rounded to dash_angle_step; power cut to the available
        stamina (stamina + extra_stamina; half of it for a backward dash); with ``limit_speed`` the
        acceleration is shrunk so that |v + a| <= player_speed_max.
        """
        sp = self.params
        power = float(power)
        power = power if power > sp.minpower else sp.minpower
        power = power if power < sp.maxpower else sp.maxpower
        d = self._discretize_dash_dir(direction_deg)
        available = p.stamina + sp.extra_stamina
        # librcsc conserveDashPower: a backward dash costs twice its power
        if power >= 0.0:
            power = available if available < power else power  # min(power, available)
        else:
            half = -0.5 * available
            power = half if half > power else power  # max(power, half)
        dir_rate = self._dash_dir_rate(d)
        if limit_speed and power != 0.0:
            rate = dir_rate * p.effort * sp.dash_power_rate
            accel = abs(power) * rate
            vmax = sp.player_speed_max
            # |v + a| <= |v| + |a|: the exact test below is needed only when that bound exceeds the cap
            if math.hypot(p.vx, p.vy) + accel > vmax and rate > 0.0:
                ang = (p.body_deg + d + (180.0 if power < 0.0 else 0.0)) * _DEG
                ux, uy = math.cos(ang), math.sin(ang)
                if (p.vx + accel * ux) ** 2 + (p.vy + accel * uy) ** 2 > vmax * vmax:
                    # largest t >= 0 with |v + t*u| = vmax
                    b = p.vx * ux + p.vy * uy
                    c = p.vx * p.vx + p.vy * p.vy - vmax * vmax
                    disc = b * b - c
                    if disc >= 0.0:
                        accel = min(accel, max(0.0, -b + math.sqrt(disc)))
                        power = math.copysign(accel / rate, power)
        self._push_dash(p, power, d, dir_rate)

    def client_kick(self, p: PlayerState, power: float, direction_deg: float) -> bool:
        """HFO KICK as librcsc sends it: power clamped to [0, 100]; refused (False, no effect) when the ball
        is farther than kickable_area - 0.055 (= 1.03 m)."""
        sp = self.params
        derived = self._derived
        if derived[0] is not sp:
            derived = self._derive()
        ball = self.ball
        if math.hypot(ball.x - p.x, ball.y - p.y) > derived[5]:  # self.ball_distance(p), client's kickable
            return False
        power = min(sp.maxpower, max(0.0, float(power)))
        return self.kick(p, power, normalize_deg(float(direction_deg)))

    # --- goalie catch and tackle (rcssserver Player::goalieCatch / Player::tackle, spec §5.1-5.3) ----------
    def catch(self, p: PlayerState, direction_deg: float) -> bool:
        """Server catch (``Player::goalieCatch``), executed as the command arrives; True when the ball is caught.

        Ignored while ``p`` is frozen by its own tackle. A fault (False, nothing else happens) when ``p`` is not
        the goalie, its ``catch_ban`` is > 0 or the play mode is not PlayOn. Otherwise the ban becomes
        catch_ban_cycle (5) whether or not the catch succeeds; it counts down at the end of every step.

        The ball, relative to the goalie and rotated by -(body + clamp(dir, +-180)), must lie in the rectangle
        0 <= x <= l_max, |y| <= w/2 (l_max = catchable_area_l * stretch = 1.2, w = catchable_area_w = 1.0),
        else a fault. Inside x <= l_min (= 1.2 at stretch 1) it succeeds with catch_probability, beyond it with
        a probability falling linearly to 0 at l_max; probability 1 draws no random number. A probabilistic
        failure punches the ball (its velocity mirrored about the catch direction, as an acceleration).

        On success the goalie moves straight toward the ball until the centres are ball_size + player_size
        (0.385 m) apart, in rcssserver's operation order (``PVector::normalize``: the offset is scaled by
        (r - 0.385) / max(r, 1e-10)), its body faces along that move, its velocity becomes 0, the ball is left
        alone, and the overlaps are resolved at once (``Stadium::ballCaught`` -> ``collisions``). The rounding
        of that move registers a ball-goalie overlap about half the time (then both velocities get -0.1x).
        """
        if p.tackle_cycles > 0:
            return False
        sp = self.params
        if not p.goalie or p.catch_ban > 0 or not self.play_on:
            return False
        p.catch_ban = int(sp.catch_ban_cycle)
        # rcssserver player.cpp goalieCatch: stretched (heterogeneous) catch area; RArea bounds centre +- size/2
        delta = sp.catchable_area_l * (sp.catch_area_l_stretch - 1.0)
        l_max = sp.catchable_area_l + delta
        l_min = sp.catchable_area_l - delta
        half_w = sp.catchable_area_w * 0.5
        catch_angle = p.body_deg * _DEG + min(sp.max_moment, max(sp.min_moment, float(direction_deg))) * _DEG
        ball = self.ball
        c = math.cos(-catch_angle)
        s = math.sin(-catch_angle)
        dx = ball.x - p.x
        dy = ball.y - p.y
        rx = dx * c - dy * s
        ry = dx * s + dy * c
        # RArea(centre (l/2, 0), size (l, w)).inArea, bounds inclusive: l/2 - l/2 = 0 and l/2 + l/2 = l exactly
        if not (0.0 <= rx <= l_max and -half_w <= ry <= half_w):
            return False
        if 0.0 <= rx <= l_min and -half_w <= ry <= half_w:
            prob = sp.catch_probability
        else:
            prob = sp.catch_probability - sp.catch_probability * ((rx - l_min) / (l_max - l_min))
            prob = min(max(0.0, prob), 1.0)
        # boost::bernoulli_distribution: p >= 1 always succeeds, p == 0 never (neither needs a draw here)
        if not (prob >= 1.0 or (prob > 0.0 and self._uniform() < prob)):
            # ballPunched: the ball's velocity mirrored about the catch direction, pushed as an acceleration
            vx0, vy0 = ball.vx, ball.vy
            ux = vx0 * c - vy0 * s
            uy = vx0 * s + vy0 * c
            ux = -ux
            c2 = math.cos(catch_angle)
            s2 = math.sin(catch_angle)
            ball.ax += (ux * c2 - uy * s2) - vx0
            ball.ay += (ux * s2 + uy * c2) - vy0
            return False
        # the teleport, in rcssserver's IEEE operation order (spec §5.2)
        r = math.sqrt(dx * dx + dy * dy)
        mag = r - (sp.ball_size + sp.player_size)
        scale = mag / max(r, _EPS)
        nx = dx * scale
        ny = dy * scale
        p.x += nx
        p.y += ny
        p.body_deg = normalize_deg(math.degrees(math.atan2(ny, nx))) if (nx != 0.0 or ny != 0.0) else 0.0
        p.vx = p.vy = 0.0
        self._resolve_catch_overlaps()
        return True

    def _resolve_catch_overlaps(self) -> None:
        """``Stadium::collisions`` run by ``ballCaught``; the flags it raises are reported with the next step."""
        ball = self.ball
        players = self.players
        saved = [(q.collided_ball, q.collided_player) for q in players]
        saved_ball = ball.collided_player
        for q in players:
            q.collided_ball = q.collided_player = False
        ball.collided_player = False
        self._collisions()
        for q, (was_ball, was_player) in zip(players, saved, strict=True):
            if q.collided_ball or q.collided_player:
                self._catch_contacts.append((q, q.collided_ball, q.collided_player))
            q.collided_ball, q.collided_player = was_ball, was_player
        if ball.collided_player:
            self._catch_contacts.append((ball, False, True))
        ball.collided_player = saved_ball

    def server_kickable(self, p: PlayerState) -> bool:
        """rcssserver ``Player::ballKickable``: squared centre distance <= (player + ball size + margin)²."""
        sp = self.params
        dx = p.x - self.ball.x
        dy = p.y - self.ball.y
        area = sp.player_size + sp.ball_size + sp.kickable_margin
        return dx * dx + dy * dy <= area * area

    def tackle_success_probability(self, p: PlayerState, foul: bool = False) -> float:
        """1 - the failure probability :meth:`tackle` would draw against now (0 when it cannot succeed)."""
        fail = self._tackle_failure(p, foul)[0]
        return 1.0 - fail if fail < 1.0 else 0.0

    def _tackle_failure(self, p: PlayerState, foul: bool) -> tuple[float, float, float, bool]:
        """``Player::tackle``'s failure probability, the ball relative to the body (r.x, r.y) and whether the
        foul is effective; failure 1.0 for a ball behind (tackle_back_dist 0)."""
        sp = self.params
        ball = self.ball
        body = p.body_deg * _DEG
        c = math.cos(-body)
        s = math.sin(-body)
        dx = ball.x - p.x
        dy = ball.y - p.y
        rx = dx * c - dy * s
        ry = dx * s + dy * c
        tackle_dist = sp.tackle_dist if rx > 0.0 else sp.tackle_back_dist
        if abs(tackle_dist) <= 1.0e-5:  # rcssserver player.cpp: no tackle at a zero distance
            return 1.0, rx, ry, False
        exponent = sp.tackle_exponent
        if foul:
            foul = False
            for q in self.players:
                if q.side != p.side and self.server_kickable(q):
                    foul = True
                    exponent = sp.foul_exponent
                    break
        fail = (abs(rx) / tackle_dist) ** exponent + (abs(ry) / sp.tackle_width) ** exponent
        return fail, rx, ry, foul

    def tackle(self, p: PlayerState, direction_deg: float, foul: bool = False) -> bool:
        """Server tackle, protocol version >= 12 (``Player::tackle``); True when the ball was pushed.

        Ignored while ``p`` is already frozen. Otherwise ``p.tackle_cycles`` becomes tackle_cycles (10) before
        anything is tested, so a failed tackle freezes too: the player ignores every body command until
        :meth:`step` has counted it down to 0 (10 steps). With the ball at r = (ball - player) rotated by
        -body, the failure probability is (|r.x| / tackle_dist)^e + (|r.y| / tackle_width)^e, e = tackle_exponent
        (6), or foul_exponent (10) when ``foul`` is asked for and some opponent can kick the ball (server
        test, :meth:`server_kickable`); a ball behind (r.x <= 0, tackle_back_dist 0) always fails. The success
        draw is made whenever the probability is < 1, noise or not. On success outside PlayOn nothing more
        happens; in PlayOn an effective foul ends the freeze at once, and the ball gets the acceleration
        polar((max_back + (max - max_back)(1 - |dir|/180)) * tackle_power_rate * (1 - 0.5 |angle(r)|/180),
        body + dir) plus, with noise, polar(U(0, kick_rand * tackle_rand_factor * (pos_rate + speed_rate)),
        U(-pi, pi)), pos_rate = 0.5 + 0.5 (1 - prob_fail), speed_rate = 0.5 + 0.5 |v_ball| / (3.0 * 0.94).
        The ball's acceleration and speed caps of :meth:`step` apply.
        """
        if p.tackle_cycles > 0:
            return False
        sp = self.params
        p.tackle_cycles = int(sp.tackle_cycles)
        ball = self.ball
        body = p.body_deg * _DEG
        fail, rx, ry, foul = self._tackle_failure(p, foul)
        if fail >= 1.0:
            return False
        if not self._uniform() < 1.0 - fail:
            return False
        if not self.play_on:
            return False
        if foul:
            p.tackle_cycles = 0
        angle = min(sp.max_moment, max(sp.min_moment, float(direction_deg))) * _DEG
        eff = (
            sp.max_back_tackle_power
            + (sp.max_tackle_power - sp.max_back_tackle_power) * (1.0 - abs(angle) / math.pi)
        ) * sp.tackle_power_rate
        ball_angle = math.atan2(ry, rx) if (rx != 0.0 or ry != 0.0) else 0.0
        eff *= 1.0 - 0.5 * (abs(ball_angle) / math.pi)
        ax = eff * math.cos(angle + body)
        ay = eff * math.sin(angle + body)
        if self.noise and sp.kick_rand > 0.0:
            pos_rate = 0.5 + 0.5 * (1.0 - fail)
            speed_rate = 0.5 + 0.5 * (math.hypot(ball.vx, ball.vy) / (sp.ball_speed_max * sp.ball_decay))
            # the v12+ tackle keeps power_rate at 1.0
            max_rand = sp.kick_rand * sp.tackle_rand_factor * 1.0 * (pos_rate + speed_rate)
            rr = max_rand * self._uniform()
            th = math.pi * (2.0 * self._uniform() - 1.0)
            ax += rr * math.cos(th)
            ay += rr * math.sin(th)
        ball.ax += ax
        ball.ay += ay
        return True

    # --- one cycle ---------------------------------------------------------------------------------
    def step(self) -> None:
        """Advance one cycle (see the module docstring for the order) and increment ``cycle``."""
        derived = self._derived
        if derived[0] is not self.params:
            derived = self._derive()
        p_size, p_decay, p_rand, p_speed_max, p_accel_max = derived[1]
        b_size, b_decay, b_rand, b_speed_max, b_accel_max = derived[2]
        if not self.noise:
            p_rand = b_rand = 0.0
        kernel = _ACCEL_MOVE
        if kernel is None:
            move = self._move_python
            for player in self.players:
                if player.tackle_cycles > 0:  # Player::resetCommandFlags, at the start of Stadium::step
                    player.tackle_cycles -= 1
                player.collided_ball = player.collided_player = False
                move(player, p_size, p_decay, p_rand, p_speed_max, p_accel_max)
            ball = self.ball
            ball.collided_player = False
            move(ball, b_size, b_decay, b_rand, b_speed_max, b_accel_max)
        else:
            # the same moves through hfo2d._accel's kernel, called here without _move's frame (see _move)
            post_x = self._post_x
            post_y = self._post_y
            for player in self.players:
                if player.tackle_cycles > 0:  # Player::resetCommandFlags, at the start of Stadium::step
                    player.tackle_cycles -= 1
                player.collided_ball = player.collided_player = False
                done = kernel(
                    player,
                    p_size,
                    p_decay,
                    p_rand,
                    p_speed_max,
                    p_accel_max,
                    self._uniforms,
                    self._next_uniform,
                    post_x,
                    post_y,
                    GOAL_POST_RADIUS,
                )
                if done.__class__ is int:
                    self._next_uniform = done
                else:
                    self._finish_move(player, done, p_size, p_decay, p_rand, p_speed_max, p_accel_max)
            ball = self.ball
            ball.collided_player = False
            done = kernel(
                ball,
                b_size,
                b_decay,
                b_rand,
                b_speed_max,
                b_accel_max,
                self._uniforms,
                self._next_uniform,
                post_x,
                post_y,
                GOAL_POST_RADIUS,
            )
            if done.__class__ is int:
                self._next_uniform = done
            else:
                self._finish_move(ball, done, b_size, b_decay, b_rand, b_speed_max, b_accel_max)
        if self._catch_contacts:
            for obj, with_ball, with_player in self._catch_contacts:
                if isinstance(obj, BallState):
                    obj.collided_player = obj.collided_player or with_player
                else:
                    obj.collided_ball = obj.collided_ball or with_ball
                    obj.collided_player = obj.collided_player or with_player
            self._catch_contacts = []
        # (_collisions' own first test, made here: most cycles nothing overlaps and the call is saved)
        if _any_overlap(self.players, ball, *derived[3]):
            self._collisions()
        # Player::updateStamina for every player (hfo_reference §4.5), its parameters read once for all
        sp = self.params
        recover_dec_thr, effort_dec_thr, effort_inc_thr = derived[4]  # each thr * stamina_max
        (_update_stamina_python if _ACCEL is None else _ACCEL.update_stamina)(
            self.players,
            recover_dec_thr,
            effort_dec_thr,
            effort_inc_thr,
            sp.stamina_max,
            sp.recover_min,
            sp.recover_dec,
            sp.effort_min,
            sp.effort_dec,
            sp.effort_init,
            sp.effort_inc,
            sp.stamina_inc_max,
            sp.stamina_capacity >= 0.0,
        )
        self.cycle += 1

    def _move(
        self,
        obj: PlayerState | BallState,
        size: float,
        decay: float,
        rand: float,
        speed_max: float,
        accel_max: float,
    ) -> None:
        """``MPObject::_inc``: accelerate with caps, noise, goal posts, move, decay. :meth:`_move_python`, by
        hfo2d._accel's kernel when it is in use (the same floats and the same draws; the post rule in Python)."""
        if _ACCEL_MOVE is None:
            self._move_python(obj, size, decay, rand, speed_max, accel_max)
            return
        done = _ACCEL_MOVE(
            obj,
            size,
            decay,
            rand,
            speed_max,
            accel_max,
            self._uniforms,
            self._next_uniform,
            self._post_x,
            self._post_y,
            GOAL_POST_RADIUS,
        )
        if done.__class__ is int:
            self._next_uniform = done
        else:
            self._finish_move(obj, done, size, decay, rand, speed_max, accel_max)

    def _finish_move(
        self,
        obj: PlayerState | BallState,
        done: tuple[float, float, int] | None,
        size: float,
        decay: float,
        rand: float,
        speed_max: float,
        accel_max: float,
    ) -> None:
        """The rest of a move that hfo2d._accel's kernel handed back: a draw past the buffer (None: the next block,
        as _move_python draws it, then the kernel again) or a move that may reach a post ((vx, vy, next uniform):
        the post rule here)."""
        if done is None:
            self._uniforms = self._rng.random(_RANDOM_BLOCK).tolist()
            self._next_uniform = 0
            done = _ACCEL_MOVE(
                obj,
                size,
                decay,
                rand,
                speed_max,
                accel_max,
                self._uniforms,
                0,
                self._post_x,
                self._post_y,
                GOAL_POST_RADIUS,
            )
            if done.__class__ is int:
                self._next_uniform = done
                return
        vx, vy, self._next_uniform = done
        x, y, vx, vy, hit = self._posts(obj.x, obj.y, vx, vy, size)
        obj.collided_post = hit
        obj.x = x
        obj.y = y
        obj.vx = vx * decay
        obj.vy = vy * decay
        obj.ax = 0.0
        obj.ay = 0.0

    def _move_python(
        self,
        obj: PlayerState | BallState,
        size: float,
        decay: float,
        rand: float,
        speed_max: float,
        accel_max: float,
    ) -> None:
        """:meth:`_move` in pure Python (the reference of hfo2d._accel's move_object)."""
        vx = obj.vx
        vy = obj.vy
        ax = obj.ax
        ay = obj.ay
        if ax != 0.0 or ay != 0.0:
            a = math.hypot(ax, ay)
            if a > accel_max:
                ax *= accel_max / a
                ay *= accel_max / a
            vx += ax
            vy += ay
            v = math.hypot(vx, vy)
            if v > speed_max:
                vx *= speed_max / v
                vy *= speed_max / v
        if rand > 0.0 and (vx != 0.0 or vy != 0.0):
            i = self._next_uniform
            if i + 2 > len(self._uniforms):
                self._uniforms = self._rng.random(_RANDOM_BLOCK).tolist()
                i = 0
            self._next_uniform = i + 2
            r = rand * math.hypot(vx, vy) * self._uniforms[i]
            th = math.pi * (2.0 * self._uniforms[i + 1] - 1.0)
            vx += r * math.cos(th)
            vy += r * math.sin(th)
        x = obj.x
        y = obj.y
        # Float pre-test: pymunk is asked only when the object could reach a post this cycle.
        reach = size + GOAL_POST_RADIUS + abs(vx) + abs(vy)
        if abs(abs(x) - self._post_x) < reach and abs(abs(y) - self._post_y) < reach:
            x, y, vx, vy, hit = self._posts(x, y, vx, vy, size)
            obj.collided_post = hit
        else:
            obj.collided_post = False
            x += vx
            y += vy
        obj.x = x
        obj.y = y
        obj.vx = vx * decay
        obj.vy = vy * decay
        obj.ax = 0.0
        obj.ay = 0.0

    def _posts(
        self, x: float, y: float, vx: float, vy: float, size: float
    ) -> tuple[float, float, float, float, bool]:
        """Goal-post rule of ``MPObject::_inc``: returns the position after the move, the velocity
        (before decay) and whether a post was hit.

        An object overlapping a post is put just outside it and its velocity reflected about the post normal;
        a path that enters a post stops at the contact, the rest of the path and the velocity are reflected
        (elastic: speed kept). pymunk finds the overlap (point query) and the contact (swept circle query).
        """
        # The shapes are queried one by one, not through Space.segment_query: Chipmunk's spatial index
        # tests the thin segment against each shape's bounding box, so a thick (radius > 0) query misses a
        # post that the path grazes without its centre line crossing the post's box.
        hit = False
        touching = GOAL_POST_RADIUS + size
        post = self._posts_by_quadrant[(x > 0.0, y > 0.0)]
        info = post.point_query((x, y))  # distance from the centre to the post's surface
        if info.distance < size:
            cx, cy = post.offset
            dx, dy = x - cx, y - cy
            d = math.hypot(dx, dy)
            if d == 0.0:
                th = math.pi * (2.0 * self._uniform() - 1.0)
                nx, ny = math.cos(th), math.sin(th)
            else:
                nx, ny = dx / d, dy / d
            x = cx + nx * touching * (1.0 + 1.0e-9)
            y = cy + ny * touching * (1.0 + 1.0e-9)
            vn = vx * nx + vy * ny
            vx -= 2.0 * vn * nx
            vy -= 2.0 * vn * ny
            hit = True
        ex, ey = x + vx, y + vy
        for _ in range(4):
            if ex == x and ey == y:
                break
            q = None
            first = self._posts_by_quadrant[(x > 0.0, y > 0.0)]
            second = self._posts_by_quadrant[(ex > 0.0, ey > 0.0)]
            for post in (first,) if first is second else (first, second):
                candidate = post.segment_query((x, y), (ex, ey), size)  # None when the path misses
                if candidate is not None and (q is None or candidate.alpha < q.alpha):
                    q = candidate
            if q is None:
                break
            nx, ny = q.normal
            rx, ry = ex - x, ey - y
            # contact point of the object's centre along its path
            cx = x + q.alpha * rx
            cy = y + q.alpha * ry
            remx, remy = ex - cx, ey - cy
            rn = remx * nx + remy * ny
            if rn >= 0.0:
                break  # touching and moving away: not a collision (rcssserver's "fake collision")
            remx -= 2.0 * rn * nx
            remy -= 2.0 * rn * ny
            x, y = cx, cy
            ex, ey = cx + remx, cy + remy
            speed = math.hypot(vx, vy)
            rem = math.hypot(remx, remy)
            if rem > 0.0:
                vx, vy = speed * remx / rem, speed * remy / rem
            else:
                vn = vx * nx + vy * ny
                vx -= 2.0 * vn * nx
                vy -= 2.0 * vn * ny
            hit = True
        return ex, ey, vx, vy, hit

    def _collisions(self) -> None:
        """``Stadium::collisions``: push overlapping pairs apart (up to 10 passes), then v *= -0.1."""
        players = self.players
        n = len(players)
        if n == 0:
            return
        sp = self.params
        ball = self.ball
        derived = self._derived
        if derived[0] is not sp:
            derived = self._derive()
        bp_limit2, pp_limit2 = derived[3]
        # Most cycles nothing overlaps: then the first pass below would change nothing and stop, so the pairs
        # are tested alone first (the same comparisons) and the bookkeeping is skipped.
        if not _any_overlap(players, ball, bp_limit2, pp_limit2):
            return
        bp_limit = sp.ball_size + sp.player_size
        pp_limit = 2.0 * sp.player_size
        ball_hit = False
        player_hit = [False] * n
        for _ in range(10):
            # per object: summed target positions and their count; index n is the ball
            targets: dict[int, list[float]] = {}
            for i, p in enumerate(players):
                dx = p.x - ball.x
                dy = p.y - ball.y
                if dx * dx + dy * dy < bp_limit2:
                    p.collided_ball = True
                    player_hit[i] = True
                    ball_hit = True
                    self._separate(n, ball, self._ball_body, self._ball_shape, i, p, bp_limit, targets)
            for i in range(n - 1):
                a = players[i]
                for j in range(i + 1, n):
                    b = players[j]
                    dx = b.x - a.x
                    dy = b.y - a.y
                    if dx * dx + dy * dy < pp_limit2:
                        a.collided_player = b.collided_player = True
                        player_hit[i] = player_hit[j] = True
                        self._separate(
                            i, a, self._player_bodies[i], self._player_shapes[i], j, b, pp_limit, targets
                        )
            if not targets:
                break
            for k, (sx, sy, count) in targets.items():
                obj = ball if k == n else players[k]
                obj.x = sx / count
                obj.y = sy / count
        if ball_hit:
            ball.collided_player = True
            ball.vx *= -0.1
            ball.vy *= -0.1
        for i, p in enumerate(players):
            if player_hit[i]:
                p.vx *= -0.1
                p.vy *= -0.1

    def _separate(
        self,
        ka: int,
        a: PlayerState | BallState,
        body_a: pymunk.Body,
        shape_a: pymunk.Circle,
        kb: int,
        b: PlayerState,
        touching: float,
        targets: dict[int, list[float]],
    ) -> None:
        """``Stadium::calcCollisionPos``: targets for a and b at (touching/2 + EPS) either side of their
        midpoint, along the centre line a -> b (pymunk's contact normal with ``pymunk_contacts``; a random
        direction when the centres coincide)."""
        mx = 0.5 * (a.x + b.x)
        my = 0.5 * (a.y + b.y)
        half = 0.5 * touching + _EPS
        if math.hypot(a.x - mx, a.y - my) < _EPS and math.hypot(b.x - mx, b.y - my) < _EPS:
            th = math.pi * (2.0 * self._uniform() - 1.0)
            nx, ny = math.cos(th), math.sin(th)
        elif self.pymunk_contacts:
            body_b = self._player_bodies[kb]
            body_a.position = (a.x, a.y)
            body_b.position = (b.x, b.y)
            shape_a.cache_bb()
            shape_b = self._player_shapes[kb]
            shape_b.cache_bb()
            contact = shape_a.shapes_collide(shape_b)
            if contact.points:
                nx, ny = contact.normal  # unit vector from a towards b
            else:  # exactly touching in floating point: fall back to the centre line
                d = math.hypot(b.x - a.x, b.y - a.y)
                nx, ny = (b.x - a.x) / d, (b.y - a.y) / d
        else:
            d = math.hypot(b.x - a.x, b.y - a.y)
            nx, ny = (b.x - a.x) / d, (b.y - a.y) / d
        ax_, ay_ = mx - nx * half, my - ny * half
        bx_, by_ = mx + nx * half, my + ny * half
        for _ in range(10):
            if (bx_ - ax_) ** 2 + (by_ - ay_) ** 2 >= touching * touching:
                break
            half *= 1.0001
            ax_, ay_ = mx - nx * half, my - ny * half
            bx_, by_ = mx + nx * half, my + ny * half
        for k, tx, ty in ((ka, ax_, ay_), (kb, bx_, by_)):
            t = targets.get(k)
            if t is None:
                targets[k] = [tx, ty, 1.0]
            else:
                t[0] += tx
                t[1] += ty
                t[2] += 1.0


def _update_stamina_python(
    players: list[PlayerState],
    recover_dec_thr: float,
    effort_dec_thr: float,
    effort_inc_thr: float,
    smax: float,
    recover_min: float,
    recover_dec: float,
    effort_min: float,
    effort_dec: float,
    effort_init: float,
    effort_inc: float,
    stamina_inc_max: float,
    limited_capacity: bool,
) -> None:
    """Player::updateStamina for every player (hfo_reference §4.5), then Player::updateCapacity's catch ban: the
    end of World.step (the reference of hfo2d._accel's update_stamina; the thresholds are thr * stamina_max)."""
    for player in players:
        # thresholds on the current stamina, then recover
        stamina = player.stamina
        if stamina <= recover_dec_thr and player.recovery > recover_min:
            player.recovery = max(recover_min, player.recovery - recover_dec)
        if stamina <= effort_dec_thr and player.effort > effort_min:
            player.effort = max(effort_min, player.effort - effort_dec)
        if stamina >= effort_inc_thr and player.effort < effort_init:
            player.effort = min(effort_init, player.effort + effort_inc)
        # min(a, b) and max(a, b) written out as the builtins decide them (b only if strictly smaller / larger)
        inc = stamina_inc_max * player.recovery
        room = smax - stamina
        if room < inc:
            inc = room
        if limited_capacity:
            if player.capacity >= inc:
                player.capacity -= inc
            else:
                inc = player.capacity
                player.capacity = 0.0
        stamina += inc if inc > 0.0 else 0.0
        player.stamina = stamina if stamina < smax else smax
        if player.catch_ban > 0:  # Player::updateCapacity, after updateStamina
            player.catch_ban -= 1


def _any_overlap_python(
    players: list[PlayerState], ball: BallState, bp_limit2: float, pp_limit2: float
) -> bool:
    """Whether any ball-player pair is closer than ``sqrt(bp_limit2)`` or any player pair than ``sqrt(pp_limit2)``
    (the first-pass tests of :meth:`World._collisions`; the reference of hfo2d._accel's any_overlap)."""
    bx = ball.x
    by = ball.y
    for p in players:
        dx = p.x - bx
        dy = p.y - by
        if dx * dx + dy * dy < bp_limit2:
            return True
    n = len(players)
    if n == 2:  # HFO 1v1: the one pair without the loops
        a, b = players
        dx = b.x - a.x
        dy = b.y - a.y
        return dx * dx + dy * dy < pp_limit2
    for i in range(n - 1):
        a = players[i]
        for j in range(i + 1, n):
            b = players[j]
            dx = b.x - a.x
            dy = b.y - a.y
            if dx * dx + dy * dy < pp_limit2:
                return True
    return False


#: :func:`_any_overlap_python`, by hfo2d._accel's kernel when it is in use
_any_overlap = _any_overlap_python if _accel.ACCEL is None else _accel.ACCEL.any_overlap


# The referee's names lived here before hfo2d.referee and hfo2d.protocol held them; importing them from this module
# still works (read lazily: hfo2d.referee imports this module).
_MOVED_TO_REFEREE = ("HFOReferee", "crosses_right_goal_line", "in_hfo_area")
_MOVED_STATUSES = {
    "HFO_IN_GAME": "IN_GAME",
    "HFO_GOAL": "GOAL",
    "HFO_CAPTURED_BY_DEFENSE": "CAPTURED_BY_DEFENSE",
    "HFO_OUT_OF_BOUNDS": "OUT_OF_BOUNDS",
    "HFO_OUT_OF_TIME": "OUT_OF_TIME",
    "HFO_TURNOVER_TIME": "TURNOVER_TIME",
}


def __getattr__(name: str) -> object:
    if name in _MOVED_TO_REFEREE:
        from hfo2d import referee

        return getattr(referee, name)
    if name in _MOVED_STATUSES:
        from hfo2d import protocol

        return getattr(protocol, _MOVED_STATUSES[name])
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
