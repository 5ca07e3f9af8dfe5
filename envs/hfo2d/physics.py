"""Soccer physics of HFO's rcssserver, one 100 ms server cycle per :meth:`World.step`.

Sources (numbers and rules, no code): rcssserver 15.2.2 as forked by HFO (``mhauskn/rcssserver``:
``serverparam.cpp``, ``player.cpp``, ``object.cpp``, ``stadium.cpp``) and the client library HFO agents
use, librcsc (``mhauskn/librcsc``: ``action_effector.cpp``), both via hfo_reference §1, §3.2, §4 and §9.

Units and frame are rcssserver's: metres, metres per cycle, degrees; 0 deg faces +x (the attacked goal),
+90 deg faces +y (down on screen), so a positive relative angle means "on the agent's right".

Order of one cycle (rcssserver ``Stadium::step``, hfo_reference §4.1):

1. Commands act as they arrive, i.e. when :meth:`World.dash`, :meth:`World.turn` or :meth:`World.kick`
   is called: a turn changes the body angle at once, a dash adds to the player's acceleration, a kick
   adds to the ball's acceleration.
2. :meth:`World.step` moves every object (``MPObject::_inc``): cap |a| at accel_max, v += a, cap |v| at
   speed_max (only when a != 0); v += polar(U(0, rand*|v|), U(-pi, pi)); goal-post overlap and path
   intersection are resolved by reflecting the velocity about the post normal (elastic); pos += v;
   v *= decay; a = 0.
3. Overlaps (``Stadium::collisions``): ball-player pairs closer than player_size + ball_size, player-player
   pairs closer than 2 * player_size are pushed apart symmetrically about their midpoint until just
   touching (each object moves to the mean of the positions its pairs ask for), for up to 10 passes; every
   object that collided then gets v *= -0.1.
4. Stamina, effort and recovery of every player are updated (``Player::updateStamina``).

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
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import pymunk

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
_RANDOM_BLOCK = 1024  # uniforms drawn from the numpy Generator at a time (one call ~1 us, per-float ~10 ns)
_POST_CATEGORY = 0b1
_OBJECT_CATEGORY = 0b10


@dataclass(frozen=True)
class ServerParams:
    """rcssserver parameters of the default player type, by rcssserver name, with HFO's defaults.

    Values: rcssserver 15.2.2 ``serverparam.cpp`` as HFO builds it (hfo_reference §4, §9). Units: metres,
    m/cycle, m/cycle², degrees, stamina units. Thresholds ``*_thr`` are fractions of ``stamina_max``.
    Tackle, catch and wind parameters are kept for completeness; this simulator does not use them.
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
            ValueError: for an unknown name (the message lists the valid ones), a value that is not a finite
                number, or a non-zero wind (wind is not simulated).
        """
        if not overrides:
            return cls()
        valid = cls.field_names()
        unknown = sorted(str(k) for k in overrides if k not in valid)
        if unknown:
            raise ValueError(f"unknown server parameter(s) {unknown}; valid names: {', '.join(valid)}")
        values: dict[str, float] = {}
        for name, value in overrides.items():
            try:
                number = float(value)
            except (TypeError, ValueError):
                raise ValueError(f"server parameter {name!r} must be a number, got {value!r}") from None
            if not math.isfinite(number):
                raise ValueError(f"server parameter {name!r} must be finite, got {value!r}")
            values[name] = number
        if values.get("wind_force", 0.0) != 0.0 or values.get("wind_rand", 0.0) != 0.0:
            raise ValueError("wind_force and wind_rand must stay 0: HFO runs without wind and so does hfo2d")
        return cls(**values)


@dataclass(slots=True)
class PlayerState:
    """One player. Positions in m, velocities in m/cycle as held between cycles (after decay).

    ``body_deg`` is in [-180, 180). ``ax``, ``ay`` hold the acceleration of a dash issued this cycle.
    The ``collided_*`` flags describe the last :meth:`World.step`.
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
            ``--deterministic``.
        pymunk_contacts: take the separation direction of two overlapping objects from pymunk's
            ``Shape.shapes_collide`` contact normal instead of the centre line computed in floats. Both give
            the same unit vector (tested); the pymunk path syncs two bodies and costs about 13 us per
            overlapping cycle against under 1 us, and an agent pushing the ball overlaps it most cycles,
            so the float path is the default.
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
        self._ball_body, self._ball_shape = self._new_body(params.ball_size)
        self._player_bodies: list[pymunk.Body] = []
        self._player_shapes: list[pymunk.Circle] = []

    # --- set-up ------------------------------------------------------------------------------------
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
    def _dash_dir_rate(self, dir_deg: float) -> float:
        p = self.params
        a = abs(dir_deg)
        if a > 90.0:
            rate = p.back_dash_rate - (p.back_dash_rate - p.side_dash_rate) * (1.0 - (a - 90.0) / 90.0)
        else:
            rate = p.side_dash_rate + (1.0 - p.side_dash_rate) * (1.0 - a / 90.0)
        return min(1.0, max(0.0, rate))

    def _discretize_dash_dir(self, direction_deg: float) -> float:
        p = self.params
        d = min(p.max_dash_angle, max(p.min_dash_angle, float(direction_deg)))
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
        power = min(sp.maxpower, max(sp.minpower, float(power)))
        d = self._discretize_dash_dir(direction_deg)
        self._push_dash(p, power, d, self._dash_dir_rate(d))

    def _push_dash(self, p: PlayerState, power: float, d: float, dir_rate: float) -> None:
        """The stamina and acceleration part of ``Player::dash`` for a clamped power and rounded direction."""
        sp = self.params
        back = power < 0.0
        need = -2.0 * power if back else power
        need = min(need, p.stamina + sp.extra_stamina)
        p.stamina = max(0.0, p.stamina - need)
        power = -0.5 * need if back else need
        edp = abs(p.effort * power * dir_rate * sp.dash_power_rate)
        if back:
            d += 180.0
        ang = (p.body_deg + d) * _DEG
        p.ax += edp * math.cos(ang)
        p.ay += edp * math.sin(ang)

    def turn(self, p: PlayerState, moment_deg: float) -> None:
        """Server turn: body += (1 + U(-player_rand, player_rand)) * clamp(moment) / (1 + inertia*|v|)."""
        sp = self.params
        moment = min(sp.max_moment, max(sp.min_moment, float(moment_deg)))
        factor = 1.0
        if self.noise and sp.player_rand > 0.0:
            factor += sp.player_rand * (2.0 * self._uniform() - 1.0)
        speed = math.hypot(p.vx, p.vy)
        p.body_deg = normalize_deg(p.body_deg + factor * moment / (1.0 + sp.inertia_moment * speed))

    def kick(self, p: PlayerState, power: float, direction_deg: float) -> bool:
        """Server kick; returns False (no effect) unless the ball is within kickable_area (1.085 m).

        The ball's acceleration gets ``polar(eff, body + dir)`` with
        ``eff = power * kick_power_rate * (1 - 0.25 * dir_diff/pi - 0.25 * gap/kickable_margin)`` plus, with
        noise, ``polar(U(0, m), U(-pi, pi))``, ``m = kick_rand * (|power|/maxpower) * (pos_rate + speed_rate)``.
        """
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
        self.turn(p, min(sp.max_moment, max(sp.min_moment, moment)))

    def client_dash(
        self, p: PlayerState, power: float, direction_deg: float = 0.0, limit_speed: bool = True
    ) -> None:
        """HFO DASH as librcsc sends it.

        Power clamped to [-100, 100]; direction rounded to dash_angle_step; power cut to the available
        stamina (stamina + extra_stamina; half of it for a backward dash); with ``limit_speed`` the
        acceleration is shrunk so that |v + a| <= player_speed_max.
        """
        sp = self.params
        power = min(sp.maxpower, max(sp.minpower, float(power)))
        d = self._discretize_dash_dir(direction_deg)
        available = p.stamina + sp.extra_stamina
        # librcsc conserveDashPower: a backward dash costs twice its power
        power = min(power, available) if power >= 0.0 else max(power, -0.5 * available)
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
        if self.ball_distance(p) > sp.kickable_area - CLIENT_KICKABLE_BUFFER:
            return False
        power = min(sp.maxpower, max(0.0, float(power)))
        return self.kick(p, power, normalize_deg(float(direction_deg)))

    # --- one cycle ---------------------------------------------------------------------------------
    def step(self) -> None:
        """Advance one cycle (see the module docstring for the order) and increment ``cycle``."""
        sp = self.params
        noise = self.noise
        for player in self.players:
            player.collided_ball = player.collided_player = False
            self._move(
                player,
                sp.player_size,
                sp.player_decay,
                sp.player_rand if noise else 0.0,
                sp.player_speed_max,
                sp.player_accel_max,
            )
        ball = self.ball
        ball.collided_player = False
        self._move(
            ball,
            sp.ball_size,
            sp.ball_decay,
            sp.ball_rand if noise else 0.0,
            sp.ball_speed_max,
            sp.ball_accel_max,
        )
        self._collisions()
        for player in self.players:
            self._update_stamina(player)
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
        """``MPObject::_inc``: accelerate with caps, noise, goal posts, move, decay."""
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
        bp_limit = sp.ball_size + sp.player_size
        pp_limit = 2.0 * sp.player_size
        bp_limit2 = bp_limit * bp_limit
        pp_limit2 = pp_limit * pp_limit
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

    def _update_stamina(self, p: PlayerState) -> None:
        """``Player::updateStamina`` (hfo_reference §4.5): thresholds on the current stamina, then recover."""
        sp = self.params
        stamina = p.stamina
        smax = sp.stamina_max
        if stamina <= sp.recover_dec_thr * smax and p.recovery > sp.recover_min:
            p.recovery = max(sp.recover_min, p.recovery - sp.recover_dec)
        if stamina <= sp.effort_dec_thr * smax and p.effort > sp.effort_min:
            p.effort = max(sp.effort_min, p.effort - sp.effort_dec)
        if stamina >= sp.effort_inc_thr * smax and p.effort < sp.effort_init:
            p.effort = min(sp.effort_init, p.effort + sp.effort_inc)
        inc = min(sp.stamina_inc_max * p.recovery, smax - stamina)
        if sp.stamina_capacity >= 0.0:
            if p.capacity >= inc:
                p.capacity -= inc
            else:
                inc = p.capacity
                p.capacity = 0.0
        p.stamina = min(smax, stamina + max(0.0, inc))
