"""Scripted strikers for measuring goalies: deterministic functions of the observation, the same in hfo2d and HFO.

Each striker maps hfo2d's paper-era features (58 against an empty goal, 66 against a goalie; real HFO's vector
converted with :func:`hfo2d.features.paper_from_hfo`) to a flat action (the 8-vector of ``HFOEnv``'s ``"flat"``
format). Nothing else is read, so a striker plays identically in hfo2d and in the real HFO. A striker may keep
per-episode state (the cycles it has waited); :meth:`Striker.reset` clears it and must be called at the start of
every episode.

Where the striker is (global frame, rcssserver units; documented in :func:`perceive`):

* body angle: features 5, 6 are (sin, cos) of the global body angle;
* own position: every landmark feature triple (sin, cos, proximity) gives the landmark's body-frame offset
  (:func:`hfo2d.features.landmark_position`: bearing ``atan2(sin, cos)``, distance ``(1 - proximity) / 2 · 62.55``).
  Rotating it by the body angle and subtracting it from the landmark's known position gives the position; the
  estimate is the mean over the landmarks whose proximity is not clipped (distance < 59 m);
* ball: its body-frame offset (51-53) rotated and added; its velocity from the speed (55, over 5 m/cycle) and the
  global heading (56, 57);
* goalie: its offset (58-60), when the goalie block is listed (not all zeros).

Strikers (:data:`STRIKERS` by name):

* ``long_shot``: dribbles toward the goal, shoots from about 20 m at the far post;
* ``mid_shot``: dribbles to about 14 m, shoots at the far post;
* ``close_shot``: dribbles with short kicks to about 8 m, shoots at the far post;
* ``soft_dribble``: dribbles with soft touches (0.6 m/cycle: the ball stays within a few metres, so the goalie
  mostly sees an opponent on the ball), shoots from about 12 m at the far post;
* ``brisk_dribble``: the same with 0.9 m/cycle touches, shooting from about 10 m;
* ``cross_shot``: dribbles out to the side of the box (x 41, |y| 13, the side the ball is on), shoots across at
  the far post;
* ``delayed_shot``: dribbles to about 16 m, stops the ball, waits ``wait_cycles`` cycles on it, then shoots;
* ``goalie_runner``: dribbles straight at the goalie and shoots past it at the far post from about 6 m away;
* ``aimed_shot``: HFO's identical-shot test (benchmarks/keeper_fidelity.py ``shots``): already on the ball, turns
  toward ``(52.5, target_y)`` for ``aim_cycles`` cycles, then kicks at full power at that point, then idles.

"The far post" is the post farther from the goalie (against an empty goal: the post on the other side of the
ball), aimed at ``post_inset`` metres inside it. The kick solver is the one of :mod:`hfo2d.heuristic` (rcssserver's
kick model), so a shot cancels the ball's current velocity and sends it at up to 3 m/cycle along the wanted line.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from hfo2d.features import (
    BALL_ANGLE_COS,
    BALL_ANGLE_SIN,
    BALL_PROXIMITY,
    BALL_SPEED,
    BALL_SPEED_MAX,
    BALL_VEL_ANGLE_COS,
    BALL_VEL_ANGLE_SIN,
    FEATURES_PER_PLAYER,
    FIRST_LANDMARK,
    GOAL_HALF_WIDTH,
    GOALIE_ANGLE_COS,
    GOALIE_ANGLE_SIN,
    GOALIE_PROXIMITY,
    KICKABLE,
    LANDMARKS,
    NUM_BASIC_FEATURES,
    PITCH_HALF_LENGTH,
    SELF_BODY_COS,
    SELF_BODY_SIN,
    hfo_num_features,
    landmark_position,
    paper_from_hfo,
    proximity_distance,
)
from hfo2d.heuristic import BALL_DECAY, BODY_CLEARANCE, MAX_POWER, PLAYER_RUN_SPEED, SHOT_SPEED, _kick_command

DASH, TURN, KICK = 0, 1, 2
# A landmark farther than this is not used for the position estimate: its proximity may be clipped at 62.55 m.
LANDMARK_TRUST_DIST = 59.0
GOAL_CENTRE = (PITCH_HALF_LENGTH, 0.0)
MIN_TURN_ANGLE_DEG = 8.0  # body-direction error tolerated while dashing
SIDE_STEP_OFFSET = 0.8  # m beside the ball to stand on before kicking it back past oneself
SIDE_STEP_RANGE = 4.0  # m; closer than this to the ball, a side step replaces the direct approach
MAX_PREDICTION_CYCLES = 20
STOPPED_BALL_SPEED = 0.05  # m/cycle under which a held ball counts as stopped
GOALIE_UNUM = 1  # HFO's goalie (bin/Teams.py launches the defense's unum 1 with -g)


@dataclass(frozen=True)
class Percept:
    """The global-frame state a striker reads from one observation (see :func:`perceive`)."""

    x: float
    y: float
    body_deg: float
    ball_x: float
    ball_y: float
    ball_vx: float
    ball_vy: float
    kickable: bool
    goalie: tuple[float, float] | None

    def to_body(self, gx: float, gy: float) -> tuple[float, float]:
        """Body-frame offset (x ahead, y to the right) of the global point (gx, gy)."""
        dx, dy = gx - self.x, gy - self.y
        body = math.radians(self.body_deg)
        cos_b, sin_b = math.cos(body), math.sin(body)
        return dx * cos_b + dy * sin_b, -dx * sin_b + dy * cos_b

    def vel_to_body(self, vx: float, vy: float) -> tuple[float, float]:
        """A global vector in the body frame."""
        body = math.radians(self.body_deg)
        cos_b, sin_b = math.cos(body), math.sin(body)
        return vx * cos_b + vy * sin_b, -vx * sin_b + vy * cos_b

    @property
    def ball_goal_dist(self) -> float:
        """Distance (m) from the ball to the goal centre (52.5, 0)."""
        return math.hypot(GOAL_CENTRE[0] - self.ball_x, GOAL_CENTRE[1] - self.ball_y)


def _rotate(x: float, y: float, angle_deg: float) -> tuple[float, float]:
    a = math.radians(angle_deg)
    c, s = math.cos(a), math.sin(a)
    return x * c - y * s, x * s + y * c


def perceive(obs: np.ndarray) -> Percept:
    """Global positions from hfo2d's features (58 or 66); see the module docstring for the method."""
    body_deg = math.degrees(math.atan2(float(obs[SELF_BODY_SIN]), float(obs[SELF_BODY_COS])))
    sum_x = sum_y = 0.0
    used = 0
    for index, (_, (landmark_x, landmark_y)) in enumerate(LANDMARKS):
        first = FIRST_LANDMARK + 3 * index
        if proximity_distance(float(obs[first + 2])) > LANDMARK_TRUST_DIST:
            continue
        off_x, off_y = _rotate(*landmark_position(obs, first, first + 1, first + 2), body_deg)
        sum_x += landmark_x - off_x
        sum_y += landmark_y - off_y
        used += 1
    if used == 0:  # cannot happen inside the HFO half; fall back to the goal centre, clipped or not
        off_x, off_y = _rotate(
            *landmark_position(obs, FIRST_LANDMARK, FIRST_LANDMARK + 1, FIRST_LANDMARK + 2), body_deg
        )
        sum_x, sum_y, used = GOAL_CENTRE[0] - off_x, GOAL_CENTRE[1] - off_y, 1
    x, y = sum_x / used, sum_y / used
    ball_off_x, ball_off_y = _rotate(
        *landmark_position(obs, BALL_ANGLE_SIN, BALL_ANGLE_COS, BALL_PROXIMITY), body_deg
    )
    ball_speed = (float(obs[BALL_SPEED]) + 1.0) * 0.5 * BALL_SPEED_MAX
    heading = math.atan2(float(obs[BALL_VEL_ANGLE_SIN]), float(obs[BALL_VEL_ANGLE_COS]))
    goalie: tuple[float, float] | None = None
    if obs.shape[0] > NUM_BASIC_FEATURES and not (
        obs[GOALIE_ANGLE_SIN] == 0.0 and obs[GOALIE_ANGLE_COS] == 0.0
    ):
        goalie_off_x, goalie_off_y = _rotate(
            *landmark_position(obs, GOALIE_ANGLE_SIN, GOALIE_ANGLE_COS, GOALIE_PROXIMITY), body_deg
        )
        goalie = (x + goalie_off_x, y + goalie_off_y)
    return Percept(
        x=x,
        y=y,
        body_deg=body_deg,
        ball_x=x + ball_off_x,
        ball_y=y + ball_off_y,
        ball_vx=ball_speed * math.cos(heading),
        ball_vy=ball_speed * math.sin(heading),
        kickable=bool(obs[KICKABLE] > 0.0),
        goalie=goalie,
    )


# ---------------------------------------------------------------------------------------------------------------
# Commands: (kind, first, second) as hfo2d.heuristic.heuristic_command returns them, and the flat action
# ---------------------------------------------------------------------------------------------------------------
Command = tuple[int, float, float]


def flat_action(command: Command) -> np.ndarray:
    """The flat action (float32, 8 values in [0, 1]) that ``HFOEnv`` maps back onto ``command``.

    DASH (power, direction), TURN (direction, unused), KICK (power, direction); directions in degrees relative to
    the body, [-180, 180]; powers [0, 100].
    """
    kind, first, second = command
    flat = np.full(8, 0.5, dtype=np.float32)
    flat[0:3] = 0.0
    flat[kind] = 1.0
    if kind == DASH:
        flat[3] = min(max(first, 0.0), MAX_POWER) / MAX_POWER
        flat[4] = (min(max(second, -180.0), 180.0) + 180.0) / 360.0
    elif kind == TURN:
        flat[5] = (min(max(first, -180.0), 180.0) + 180.0) / 360.0
    else:
        flat[6] = min(max(first, 0.0), MAX_POWER) / MAX_POWER
        flat[7] = (min(max(second, -180.0), 180.0) + 180.0) / 360.0
    return flat


def idle() -> Command:
    """A command that changes nothing: a turn by 0 degrees."""
    return TURN, 0.0, 0.0


def turn_to(p: Percept, gx: float, gy: float) -> Command:
    """Turn the body toward the global point (gx, gy) (the flat TURN asks for the actual turn)."""
    bx, by = p.to_body(gx, gy)
    return TURN, math.degrees(math.atan2(by, bx)), 0.0


def move_to(p: Percept, gx: float, gy: float) -> Command:
    """Turn toward (gx, gy) when it is off the body direction, else dash at it at full power."""
    tx, ty = p.to_body(gx, gy)
    dist = math.hypot(tx, ty)
    bearing = math.degrees(math.atan2(ty, tx))
    tolerance = max(MIN_TURN_ANGLE_DEG, math.degrees(math.atan2(0.5, max(dist, 1e-6))))
    if abs(bearing) > tolerance:
        return TURN, bearing, 0.0
    return DASH, MAX_POWER, 0.0


def kick_to(p: Percept, gx: float, gy: float, speed: float) -> Command:
    """Kick the ball so that it leaves along the line to (gx, gy) at ``speed`` m/cycle (or as fast as it can)."""
    ball_x, ball_y = p.to_body(p.ball_x, p.ball_y)
    ball_vx, ball_vy = p.vel_to_body(p.ball_vx, p.ball_vy)
    tx, ty = p.to_body(gx, gy)
    dx, dy = tx - ball_x, ty - ball_y
    norm = max(math.hypot(dx, dy), 1e-6)
    power, direction = _kick_command(ball_x, ball_y, ball_vx, ball_vy, dx / norm, dy / norm, speed)
    return KICK, power, direction


def stop_ball(p: Percept) -> Command:
    """Kick that cancels the ball's velocity (a trap)."""
    ball_x, ball_y = p.to_body(p.ball_x, p.ball_y)
    ball_vx, ball_vy = p.vel_to_body(p.ball_vx, p.ball_vy)
    speed = math.hypot(ball_vx, ball_vy)
    if speed < 1e-9:
        return idle()
    power, direction = _kick_command(
        ball_x, ball_y, ball_vx, ball_vy, -ball_vx / speed, -ball_vy / speed, 0.0
    )
    return KICK, power, direction


def segment_distance(px: float, py: float, ax: float, ay: float, bx: float, by: float) -> float:
    """Distance (m) from the point p to the segment a-b (e.g. a defender from a passing lane)."""
    dx, dy = bx - ax, by - ay
    length_squared = dx * dx + dy * dy
    t = 0.0 if length_squared == 0.0 else ((px - ax) * dx + (py - ay) * dy) / length_squared
    t = min(max(t, 0.0), 1.0)
    return math.hypot(px - ax - t * dx, py - ay - t * dy)


def kick_blocked(p: Percept, gx: float, gy: float) -> bool:
    """True when a kick toward (gx, gy) would send the ball through the kicker's own body."""
    ball_x, ball_y = p.to_body(p.ball_x, p.ball_y)
    tx, ty = p.to_body(gx, gy)
    dx, dy = tx - ball_x, ty - ball_y
    norm = max(math.hypot(dx, dy), 1e-6)
    dir_x, dir_y = dx / norm, dy / norm
    along = ball_x * dir_x + ball_y * dir_y
    lateral = ball_x * dir_y - ball_y * dir_x
    return along < 0.0 and abs(lateral) < BODY_CLEARANCE


def chase_ball(p: Percept, gx: float, gy: float) -> Command:
    """Run to where the ball will be, stepping to its side first when standing between it and (gx, gy)."""
    ball_x, ball_y = p.to_body(p.ball_x, p.ball_y)
    tx, ty = p.to_body(gx, gy)
    dx, dy = tx - ball_x, ty - ball_y
    norm = max(math.hypot(dx, dy), 1e-6)
    dir_x, dir_y = dx / norm, dy / norm
    along = ball_x * dir_x + ball_y * dir_y
    lateral = ball_x * dir_y - ball_y * dir_x
    ball_dist = math.hypot(ball_x, ball_y)
    body = p.body_deg
    if ball_dist < SIDE_STEP_RANGE and along < 0.0 and abs(lateral) < SIDE_STEP_OFFSET:
        side = 1.0 if lateral >= 0.0 else -1.0
        gx_step, gy_step = _rotate(
            ball_x - side * SIDE_STEP_OFFSET * dir_y, ball_y + side * SIDE_STEP_OFFSET * dir_x, body
        )
        return move_to(p, p.x + gx_step, p.y + gy_step)
    cycles = min(ball_dist / PLAYER_RUN_SPEED, MAX_PREDICTION_CYCLES)
    travel = (1.0 - BALL_DECAY**cycles) / (1.0 - BALL_DECAY)
    return move_to(p, p.ball_x + p.ball_vx * travel, p.ball_y + p.ball_vy * travel)


def far_post(p: Percept, inset: float) -> tuple[float, float]:
    """``inset`` metres inside the post farther from the goalie (no goalie: the post across from the ball)."""
    reference_y = p.goalie[1] if p.goalie is not None else p.ball_y
    side = -1.0 if reference_y >= 0.0 else 1.0
    return PITCH_HALF_LENGTH, side * (GOAL_HALF_WIDTH - inset)


# ---------------------------------------------------------------------------------------------------------------
# Strikers
# ---------------------------------------------------------------------------------------------------------------
class Striker:
    """Base class: ``striker(obs)`` is the flat action for one observation; ``command(obs)`` the raw command.

    Subclasses implement :meth:`decide` on a :class:`Percept`; per-episode state lives on the instance and
    :meth:`reset` (call it at every episode start) clears it.
    """

    name = "striker"

    def reset(self) -> None:
        """Start of an episode: forget the per-episode state."""

    def decide(self, p: Percept) -> Command:
        raise NotImplementedError

    def command(self, obs: np.ndarray) -> Command:
        """(kind, first, second) for ``obs``: DASH (power, dir), TURN (dir, 0), KICK (power, dir)."""
        return self.decide(perceive(np.asarray(obs)))

    def __call__(self, obs: np.ndarray) -> np.ndarray:
        return flat_action(self.command(obs))


class DribbleShooter(Striker):
    """Dribble the ball toward ``waypoint(p)`` at ``dribble_speed``; shoot at the far post once ``ready(p)``.

    The default waypoint is the goal centre and the default shot trigger is the ball within ``shot_distance``
    metres of it.
    """

    def __init__(
        self,
        name: str,
        shot_distance: float,
        dribble_speed: float = 1.6,
        post_inset: float = 0.8,
        shot_speed: float = SHOT_SPEED,
    ) -> None:
        self.name = name
        self.shot_distance = float(shot_distance)
        self.dribble_speed = float(dribble_speed)
        self.post_inset = float(post_inset)
        self.shot_speed = float(shot_speed)

    def waypoint(self, p: Percept) -> tuple[float, float]:
        return GOAL_CENTRE

    def ready(self, p: Percept) -> bool:
        return p.ball_goal_dist <= self.shot_distance

    def aim(self, p: Percept) -> tuple[float, float]:
        return far_post(p, self.post_inset)

    def on_ball(self, p: Percept) -> Command:
        """The kick when the ball is kickable: a shot when ready, else a dribble kick."""
        if self.ready(p):
            return kick_to(p, *self.aim(p), self.shot_speed)
        return kick_to(p, *self.waypoint(p), self.dribble_speed)

    def decide(self, p: Percept) -> Command:
        target = self.aim(p) if self.ready(p) else self.waypoint(p)
        if p.kickable and not kick_blocked(p, *target):
            return self.on_ball(p)
        return chase_ball(p, *target)


class CrossShooter(DribbleShooter):
    """Dribble out to the side of the box on the ball's side, then shoot across to the far post."""

    def __init__(self, name: str = "cross_shot", side_x: float = 41.0, side_y: float = 13.0) -> None:
        super().__init__(name, shot_distance=0.0, dribble_speed=1.4, post_inset=0.7)
        self.side_x = float(side_x)
        self.side_y = float(side_y)

    def _side(self, p: Percept) -> float:
        return 1.0 if p.ball_y >= 0.0 else -1.0

    def waypoint(self, p: Percept) -> tuple[float, float]:
        return self.side_x, self._side(p) * self.side_y

    def ready(self, p: Percept) -> bool:
        wx, wy = self.waypoint(p)
        return p.ball_x >= self.side_x or math.hypot(wx - p.ball_x, wy - p.ball_y) <= 3.0

    def on_ball(self, p: Percept) -> Command:
        if self.ready(p):
            return kick_to(p, *self.aim(p), self.shot_speed)
        # slow down near the waypoint: a ball at speed v rolls v / (1 - 0.94) m
        wx, wy = self.waypoint(p)
        speed = min(
            self.dribble_speed, max(0.6, (1.0 - BALL_DECAY) * math.hypot(wx - p.ball_x, wy - p.ball_y))
        )
        return kick_to(p, wx, wy, speed)

    def aim(self, p: Percept) -> tuple[float, float]:
        return PITCH_HALF_LENGTH, -self._side(p) * (GOAL_HALF_WIDTH - self.post_inset)


class DelayedShooter(DribbleShooter):
    """Dribble to ``shot_distance``, stop the ball, wait ``wait_cycles`` cycles on it, then shoot at the far post."""

    def __init__(self, name: str = "delayed_shot", shot_distance: float = 16.0, wait_cycles: int = 8) -> None:
        super().__init__(name, shot_distance=shot_distance, dribble_speed=1.3, post_inset=0.8)
        self.wait_cycles = int(wait_cycles)
        self.waited = 0

    def reset(self) -> None:
        self.waited = 0

    def on_ball(self, p: Percept) -> Command:
        if not self.ready(p):
            return kick_to(p, *self.waypoint(p), self.dribble_speed)
        if self.waited < self.wait_cycles:
            self.waited += 1
            if math.hypot(p.ball_vx, p.ball_vy) > STOPPED_BALL_SPEED:
                return stop_ball(p)
            return turn_to(p, *self.aim(p))
        return kick_to(p, *self.aim(p), self.shot_speed)


class GoalieRunner(DribbleShooter):
    """Dribble straight at the goalie; shoot past it at the far post once the ball is within ``shot_range``."""

    def __init__(self, name: str = "goalie_runner", shot_range: float = 6.0) -> None:
        super().__init__(name, shot_distance=9.0, dribble_speed=1.2, post_inset=1.0)
        self.shot_range = float(shot_range)

    def waypoint(self, p: Percept) -> tuple[float, float]:
        return p.goalie if p.goalie is not None else GOAL_CENTRE

    def ready(self, p: Percept) -> bool:
        if p.goalie is None:
            return p.ball_goal_dist <= self.shot_distance
        return math.hypot(p.goalie[0] - p.ball_x, p.goalie[1] - p.ball_y) <= self.shot_range


class AimedShot(Striker):
    """HFO's identical-shot test: on the ball, turn toward (52.5, ``target_y``) ``aim_cycles`` times, then kick
    at full power at that point, then idle.

    The turns are recomputed each cycle (the first one faces the target; the rest are ~0). The kick goes along
    the line from the ball to the target. If the ball is not kickable when the kick is due, it keeps waiting.
    """

    def __init__(self, target_y: float = 0.0, aim_cycles: int = 6, name: str | None = None) -> None:
        self.target_y = float(target_y)
        self.aim_cycles = int(aim_cycles)
        self.name = name or f"aimed_shot_{target_y:+g}"
        self.cycle = 0
        self.kicked = False

    def reset(self) -> None:
        self.cycle = 0
        self.kicked = False

    def decide(self, p: Percept) -> Command:
        target = (PITCH_HALF_LENGTH, self.target_y)
        self.cycle += 1
        if self.kicked:
            return idle()
        if self.cycle <= self.aim_cycles:
            return turn_to(p, p.x + (target[0] - p.ball_x), p.y + (target[1] - p.ball_y))
        if not p.kickable:
            return idle()
        self.kicked = True
        return kick_to(p, *target, SHOT_SPEED)


#: Striker factories by name (each call builds a fresh striker with its own episode state).
STRIKERS: dict[str, Callable[[], Striker]] = {
    "long_shot": lambda: DribbleShooter("long_shot", shot_distance=20.0, dribble_speed=1.6, post_inset=1.0),
    "mid_shot": lambda: DribbleShooter("mid_shot", shot_distance=14.0, dribble_speed=1.5, post_inset=0.8),
    "close_shot": lambda: DribbleShooter("close_shot", shot_distance=8.0, dribble_speed=1.1, post_inset=0.8),
    "soft_dribble": lambda: DribbleShooter(
        "soft_dribble", shot_distance=12.0, dribble_speed=0.6, post_inset=1.0
    ),
    "brisk_dribble": lambda: DribbleShooter(
        "brisk_dribble", shot_distance=10.0, dribble_speed=0.9, post_inset=1.0
    ),
    "cross_shot": CrossShooter,
    "delayed_shot": DelayedShooter,
    "goalie_runner": GoalieRunner,
}


def make_striker(name: str, **kwargs: float) -> Striker:
    """A fresh striker: one of :data:`STRIKERS`, or ``"aimed_shot"`` with ``target_y`` / ``aim_cycles``."""
    if name == "aimed_shot":
        return AimedShot(**kwargs)  # type: ignore[arg-type]
    if name not in STRIKERS:
        raise ValueError(f"unknown striker {name!r}; choose one of {(*STRIKERS, 'aimed_shot')}")
    if kwargs:
        raise ValueError(f"striker {name!r} takes no options, got {kwargs}")
    return STRIKERS[name]()


def goalie_view_from_hfo(features: Sequence[float], num_teammates: int, num_opponents: int) -> np.ndarray:
    """What a striker reads in a team game: HFO master's vector cut down to the 1v1 layout (basic + goalie block).

    The strikers know one opponent, the goalie (features 58-65). In a team game the paper-era blocks are sorted
    by distance and carry no uniform numbers, so the goalie is found through HFO master's uniform-number entries
    (``unum / 100`` per slot, :func:`hfo2d.features.hfo_feature_list`): the opponent slot numbered 1. The vector
    is converted with :func:`hfo2d.features.paper_from_hfo`, then its 58 basic features and the goalie's block
    are kept (zeros when the goalie is not listed, which a striker reads as "no goalie"). Both hfo2d's team game
    and the real HFO give this vector with ``feature_set="hfo"``, so a striker plays the same in both; it is
    what ``hfo2d.team.TeamGame`` gives its own scripted strikers, up to float32 rounding.

    Args:
        features: HFO master's vector of an offense player, ``hfo_num_features(num_teammates, num_opponents)``.
        num_teammates, num_opponents: its slot counts.

    Returns:
        66 float32 features (58 + the goalie's 8).

    Raises:
        ValueError: a vector of the wrong length or negative slot counts (from ``paper_from_hfo``).
    """
    paper = paper_from_hfo(features, num_teammates, num_opponents)
    players = num_teammates + num_opponents
    unums = hfo_num_features(num_teammates, num_opponents) - 1 - players  # first uniform-number entry
    view = np.zeros(NUM_BASIC_FEATURES + FEATURES_PER_PLAYER, dtype=np.float32)
    view[:NUM_BASIC_FEATURES] = paper[:NUM_BASIC_FEATURES]
    for slot in range(num_teammates, players):
        if round(float(features[unums + slot]) * 100.0) == GOALIE_UNUM:
            first = NUM_BASIC_FEATURES + FEATURES_PER_PLAYER * slot
            view[NUM_BASIC_FEATURES:] = paper[first : first + FEATURES_PER_PLAYER]
            break
    return view
