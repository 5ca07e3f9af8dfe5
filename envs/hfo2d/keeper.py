"""Scripted goalie for the 1v1 HFO tasks (``HFO/Keeper-v0``).

The behaviour follows the decision list of HFO's default defense team ("base", a modified agent2d goalie),
as summarised in hfo_reference §5.4 and converted to the global frame with the defended goal at x = +52.5:

1. (catch / clear are not needed: the episode ends as soon as the goalie is within kickable_area = 1.085 m
   of the ball, HFORef's immediate goalie capture rule, hfo_reference §5.1)
2. **intercept** in a chase situation: the ball's next position is within 8 m of the goal line with |y| < 10,
   or the ball is a shot moving at goal that the keeper can reach before it crosses the line, or the keeper's
   intercept point lies inside the penalty area (shrunk by a margin of 1 + 0.1 * distance) and no opponent
   gets there at least 2 cycles sooner;
3. otherwise **position** at x = 49.8 on the line from the predicted ball to a point 7 m behind the goal
   centre, with |y| <= 6.51; at the post (51.5, +-7.01) when the ball is wide at a dangerous angle, and at
   (49.8, +-6.91) when the ball is within 8 m of the goal line with |y| > 9.

Everything is issued as server-side commands (``World.dash`` / ``World.turn``, rcssserver semantics), because
the keeper is part of the simulator, not an agent behind librcsc.

``skill`` in [0, 1] interpolates between an almost static keeper (skill 0: it only turns to face the ball)
and the full behaviour (skill 1): it scales the dash power, the reaction delay (the keeper acts on the ball
state seen ``reaction_delay`` cycles ago), the intercept prediction horizon and the chance of hesitating
(doing nothing) in a cycle. The numbers of that schedule are this project's design choice, not HFO's.
"""

from __future__ import annotations

import math
from collections import deque

import numpy as np

from hfo2d.physics import (
    GOAL_HALF_WIDTH,
    PENALTY_AREA_HALF_WIDTH,
    PENALTY_AREA_X,
    PITCH_HALF_LENGTH,
    PlayerState,
    ServerParams,
    World,
)
from hfo2d.protocol import KEEPER_START_BODY_DEG

# --- agent2d goalie positioning geometry (hfo_reference §5.4), global frame, goal at x = +52.5 ---------------
BASE_MOVE_X = 49.8  # the keeper's normal depth
BASE_MAX_ABS_Y = 6.51  # lateral limit of the normal position
LINE_ANCHOR_X = PITCH_HALF_LENGTH + 7.0  # the positioning line runs from the ball to 7 m behind goal centre
POST_MOVE_X = 51.5  # guarding the near post against a shot from a sharp angle
POST_MOVE_ABS_Y = GOAL_HALF_WIDTH
WIDE_MOVE_ABS_Y = 6.91  # ball wide and close to the goal line
WIDE_BALL_LINE_DIST = 8.0  # "within 8 m of the goal line"
WIDE_BALL_ABS_Y = 9.0
# A ball is "wide at a dangerous angle" when it is beyond the goal width and closer to the goal line than the
# keeper's base depth (the line construction would put the keeper behind the ball). Design choice: the
# reference does not give agent2d's exact test.
DANGER_BALL_X = BASE_MOVE_X

# --- chase situations (hfo_reference §5.4 item 3) -------------------------------------------------------------
CHASE_LINE_DIST = 8.0  # next ball position within 8 m of the goal line ...
CHASE_ABS_Y = 10.0  # ... and |y| < 10
SHOT_POST_MARGIN = 1.0  # a ball crossing the line within goal half width + 1 m counts as a shot at goal
BOX_MARGIN_BASE = 1.0  # penalty area shrunk by 1 + 0.1 * (keeper distance to the intercept point)
BOX_MARGIN_PER_METRE = 0.1
OPPONENT_LEAD_CYCLES = 2  # do not chase a ball an opponent reaches >= 2 cycles sooner ...
OPPONENT_LEAD_METRES = 2.0  # ... or from >= 2 m closer

# --- body control ------------------------------------------------------------------------------------------
MIN_ANGLE_TOLERANCE_DEG = 10.0  # smallest body-direction error that triggers a turn before dashing
OMNI_DASH_DIST = (
    3.0  # closer than this the keeper side-steps (dash direction rounded to 45 deg) instead of turning
)
FACE_BALL_TOLERANCE_DEG = 15.0
# The capture test is "centre distance <= kickable_area"; aim a little inside it because of motion noise.
CAPTURE_SAFETY = 0.15

# --- skill schedule (design choice): skill 1 = full keeper, skill 0 = almost static --------------------------
MAX_REACTION_DELAY_CYCLES = 4
MIN_HORIZON_CYCLES = 3
MAX_HORIZON_CYCLES = 40
MAX_HESITATION_PROBABILITY = 0.5


def normalize_angle_deg(angle_deg: float) -> float:
    """Wrap an angle in degrees into [-180, 180)."""
    return (angle_deg + 180.0) % 360.0 - 180.0


def dash_reach_table(params: ServerParams, power: float, cycles: int) -> list[float]:
    """Distance (m) a player starting at rest covers by dashing straight ahead at ``power`` for n cycles.

    Follows rcssserver's ``_inc`` (hfo_reference §4.1/4.2): accel = power * dash_power_rate (effort 1), capped
    at player_accel_max; v += a, capped at player_speed_max; pos += v; v *= player_decay. Noise is ignored.

    Returns:
        list of length ``cycles + 1``; entry n is the distance covered after n cycles (entry 0 is 0).
    """
    accel = min(abs(power) * params.dash_power_rate, params.player_accel_max)
    speed = 0.0
    covered = 0.0
    table = [0.0]
    for _ in range(cycles):
        speed = min(speed + accel, params.player_speed_max)
        covered += speed
        table.append(covered)
        speed *= params.player_decay
    return table


def turn_toward(world: World, player: PlayerState, relative_deg: float) -> None:
    """Issue a server-side turn that rotates ``player`` by about ``relative_deg`` degrees.

    rcssserver divides the moment by (1 + inertia_moment * |v|) (hfo_reference §4.3), so the moment is
    pre-multiplied by that factor and clamped to [min_moment, max_moment].
    """
    params = world.params
    speed = math.hypot(player.vx, player.vy)
    moment = relative_deg * (1.0 + params.inertia_moment * speed)
    world.turn(player, max(params.min_moment, min(params.max_moment, moment)))


def go_to_point(
    world: World,
    player: PlayerState,
    target_x: float,
    target_y: float,
    power: float,
    dist_tolerance: float,
    angle_tolerance_deg: float | None = None,
) -> bool:
    """Turn-then-dash body control toward a target point (global frame, metres).

    Far targets: turn to face the target when the body direction is off by more than ``angle_tolerance_deg``
    (default: the angle under which ``dist_tolerance`` is seen, at least ``MIN_ANGLE_TOLERANCE_DEG``), else
    dash ahead at ``power``.
    Targets closer than ``OMNI_DASH_DIST``: dash toward them with the dash direction rounded to the server's
    dash_angle_step (a side/back step) so the keeper keeps facing the play.

    Returns:
        True if a command was issued, False if the player is already within ``dist_tolerance``.
    """
    dx = target_x - player.x
    dy = target_y - player.y
    dist = math.hypot(dx, dy)
    if dist <= dist_tolerance:
        return False
    relative_deg = normalize_angle_deg(math.degrees(math.atan2(dy, dx)) - player.body_deg)
    if angle_tolerance_deg is None:
        angle_tolerance_deg = max(MIN_ANGLE_TOLERANCE_DEG, math.degrees(math.atan2(dist_tolerance, dist)))
    if abs(relative_deg) <= angle_tolerance_deg:
        world.dash(player, power, 0.0)
    elif dist < OMNI_DASH_DIST:
        step = world.params.dash_angle_step
        world.dash(player, power, step * round(relative_deg / step))
    else:
        turn_toward(world, player, relative_deg)
    return True


class ScriptedKeeper:
    """agent2d-style goalie defending the goal at x = +52.5 (hfo_reference §5.4).

    Args:
        params: server parameters (for the dash model and the capture radius).
        rng: generator for the hesitation draws of a weakened keeper (skill < 1); unused at skill 1.
        skill: in [0, 1]. 1 = full behaviour; 0 = only turns to face the ball.

    Per-skill quantities (design choice):
        dash_power = maxpower * skill; reaction_delay = round(4 * (1 - skill)) cycles;
        horizon = round(3 + 37 * skill) cycles of ball prediction; hesitation = 0.5 * (1 - skill) per cycle.
    """

    #: its client state is forgotten between episodes (:class:`hfo2d.npc.DefenseNPC`)
    carries_over = False

    def __init__(self, params: ServerParams, rng: np.random.Generator, skill: float = 1.0) -> None:
        self.params = params
        self.rng = rng
        self.set_skill(skill)
        # What the keeper decided in the last call ("idle", "face", "position", "intercept"); for tests/debugging.
        self.last_mode = "idle"

    def set_skill(self, skill: float) -> None:
        """Play with quality ``skill`` in [0, 1] from now on; the remembered ball states are forgotten."""
        if not 0.0 <= skill <= 1.0 or not math.isfinite(skill):
            raise ValueError(f"keeper skill must be in [0, 1], got {skill}")
        params = self.params
        self.skill = float(skill)
        self.dash_power = params.maxpower * self.skill
        self.reaction_delay = round(MAX_REACTION_DELAY_CYCLES * (1.0 - self.skill))
        self.horizon = round(MIN_HORIZON_CYCLES + (MAX_HORIZON_CYCLES - MIN_HORIZON_CYCLES) * self.skill)
        self.hesitation = MAX_HESITATION_PROBABILITY * (1.0 - self.skill)
        self.capture_radius = params.kickable_area - CAPTURE_SAFETY
        self._own_reach = dash_reach_table(params, self.dash_power, self.horizon)
        self._opponent_reach = dash_reach_table(params, params.maxpower, self.horizon)
        # Distance a player drifts in n cycles per m/cycle of current velocity: (1 - decay^n) / (1 - decay).
        cycles = range(self.horizon + 1)
        self._drift = [(1.0 - params.player_decay**n) / (1.0 - params.player_decay) for n in cycles]
        self._player_decay_pow = [params.player_decay**n for n in cycles]
        # Ball travel in n cycles per m/cycle of velocity, and its speed factor after n cycles.
        self._ball_series = [(1.0 - params.ball_decay**n) / (1.0 - params.ball_decay) for n in cycles]
        self._ball_decay_pow = [params.ball_decay**n for n in cycles]
        self._ball_memory: deque[tuple[float, float, float, float]] = deque(maxlen=self.reaction_delay + 1)

    def reset(self) -> None:
        """Forget the remembered ball states (call at the start of every episode)."""
        self._ball_memory.clear()
        self.last_mode = "idle"

    def restart(self) -> None:
        """As a new keeper: nothing outlives an episode but the skill, so :meth:`reset`."""
        self.reset()

    def start_body_deg(self, rng: np.random.Generator) -> float:
        """Facing the field (no draw)."""
        return KEEPER_START_BODY_DEG

    def decide(self, world: World, keeper: PlayerState) -> None:
        """Nothing: this keeper looks at the world when its command is sent (:meth:`apply`), after the striker's
        command of the cycle, as ``HFO/Keeper-v0`` was measured."""
        return None

    def act(self, world: World, keeper: PlayerState) -> None:
        """Issue at most one server-side command (dash or turn) for ``keeper`` for the coming cycle."""
        self.apply(world, keeper)

    # ---------------------------------------------------------------------------------------------------------
    def apply(self, world: World, keeper: PlayerState, decision: None = None) -> None:
        """Decide on the world as it is and issue at most one server-side command (dash or turn) for ``keeper``."""
        ball = world.ball
        if self.reaction_delay > 0:
            self._ball_memory.append((ball.x, ball.y, ball.vx, ball.vy))
            bx, by, bvx, bvy = self._ball_memory[0]
        else:
            bx, by, bvx, bvy = ball.x, ball.y, ball.vx, ball.vy
        if self.hesitation > 0.0 and self.rng.random() < self.hesitation:
            self.last_mode = "idle"
            return
        if self.dash_power <= 0.0:
            self._face(world, keeper, bx, by)
            return

        intercept = self._intercept_point(keeper, bx, by, bvx, bvy)
        if intercept is not None and self._is_chase_situation(world, keeper, intercept, bx, by, bvx, bvy):
            _, _, _, aim_x, aim_y = intercept
            self.last_mode = "intercept"
            go_to_point(world, keeper, aim_x, aim_y, self.dash_power, 0.0)
            return

        target_x, target_y = self._position_target(world, bx, by, bvx, bvy)
        ball_dist = math.hypot(bx - keeper.x, by - keeper.y)
        tolerance = min(1.0, max(0.3, 0.05 * ball_dist))
        self.last_mode = "position"
        if not go_to_point(world, keeper, target_x, target_y, self.dash_power, tolerance):
            self._face(world, keeper, bx, by)

    # ---------------------------------------------------------------------------------------------------------
    def _face(self, world: World, keeper: PlayerState, bx: float, by: float) -> None:
        self.last_mode = "face"
        relative_deg = normalize_angle_deg(
            math.degrees(math.atan2(by - keeper.y, bx - keeper.x)) - keeper.body_deg
        )
        if abs(relative_deg) > FACE_BALL_TOLERANCE_DEG:
            turn_toward(world, keeper, relative_deg)

    def _intercept_point(
        self, keeper: PlayerState, bx: float, by: float, bvx: float, bvy: float
    ) -> tuple[float, float, int, float, float] | None:
        """First predicted ball position the keeper can reach within its horizon, or None.

        Returns:
            (x, y, cycles, aim_x, aim_y): the ball position, the cycles until then, and the point to dash
            toward, which is the ball position minus the keeper's own drift over those cycles.
        """
        found = self._first_reach(
            bx,
            by,
            bvx,
            bvy,
            keeper.x,
            keeper.y,
            keeper.vx,
            keeper.vy,
            self._own_reach,
            self.capture_radius,
            keeper.body_deg,
        )
        if found is None:
            return None
        cycles, dx, dy = found
        series = self._ball_series[cycles]
        # Dash direction: from the keeper to the ball position minus the keeper's drift, i.e. keeper + (dx, dy).
        return bx + bvx * series, by + bvy * series, cycles, keeper.x + dx, keeper.y + dy

    def _first_reach(
        self,
        bx: float,
        by: float,
        bvx: float,
        bvy: float,
        px: float,
        py: float,
        pvx: float,
        pvy: float,
        reach: list[float],
        radius: float,
        body_deg: float | None,
    ) -> tuple[int, float, float] | None:
        """Fewest cycles t <= horizon after which a player can have the predicted ball within ``radius``.

        Ball after t cycles: b + v * (1 - ball_decay^t) / (1 - ball_decay) (no noise, no posts). Player: its
        drift p + v_p * (1 - player_decay^t) / (1 - player_decay) plus a straight dash from rest (``reach``;
        motion is linear, so the two add up), after one cycle to turn (only when ``body_deg`` is given) when the
        point is off the body direction by more than the angle under which ``radius`` is seen.

        Cycles that cannot work are skipped: the shortfall ``gap - reach[t]`` shrinks per cycle by at most
        player_speed_max + the ball's speed + the player's drift speed, all non-increasing in t.

        Returns:
            (t, dx, dy) with (dx, dy) the ball position at t minus the player's drift position at t, or None.
        """
        series = self._ball_series
        decay_pow = self._ball_decay_pow
        drift = self._drift
        drift_pow = self._player_decay_pow
        speed_max = self.params.player_speed_max
        ball_speed = math.hypot(bvx, bvy)
        player_speed = math.hypot(pvx, pvy)
        horizon = self.horizon
        cycles = 0
        while cycles <= horizon:
            dx = bx + bvx * series[cycles] - px - pvx * drift[cycles]
            dy = by + bvy * series[cycles] - py - pvy * drift[cycles]
            dist = math.hypot(dx, dy)
            if dist <= radius:
                return cycles, dx, dy
            shortfall = dist - radius - reach[cycles]
            if shortfall <= 0.0:
                if body_deg is None:
                    return cycles, dx, dy
                relative_deg = normalize_angle_deg(math.degrees(math.atan2(dy, dx)) - body_deg)
                if abs(relative_deg) <= max(MIN_ANGLE_TOLERANCE_DEG, math.degrees(math.asin(radius / dist))):
                    return cycles, dx, dy
                if reach[cycles - 1] >= dist - radius:  # one cycle spent turning
                    return cycles, dx, dy
                cycles += 1
                continue
            closing = speed_max + ball_speed * decay_pow[cycles] + player_speed * drift_pow[cycles]
            cycles += max(1, math.ceil(shortfall / closing))
        return None

    def _opponent_reach_cycles(self, world: World, bx: float, by: float, bvx: float, bvy: float) -> int:
        """Fewest cycles any offense player needs to get the (predicted) ball within kickable_area.

        Optimistic for the opponent: a straight full-power dash from rest with no turn and no drift. Returns
        ``horizon + 1`` if nobody gets there within the horizon.
        """
        best = self.horizon + 1
        for player in world.players:
            if player.side != "l":
                continue
            found = self._first_reach(
                bx,
                by,
                bvx,
                bvy,
                player.x,
                player.y,
                0.0,
                0.0,
                self._opponent_reach,
                self.params.kickable_area,
                None,
            )
            if found is not None and found[0] < best:
                best = found[0]
        return best

    def _is_chase_situation(
        self,
        world: World,
        keeper: PlayerState,
        intercept: tuple[float, float, int, float, float],
        bx: float,
        by: float,
        bvx: float,
        bvy: float,
    ) -> bool:
        ix, iy, my_cycles, _, _ = intercept
        # (a) the ball's next position is close to the goal mouth
        next_x = bx + bvx
        if next_x > PITCH_HALF_LENGTH - CHASE_LINE_DIST and abs(by + bvy) < CHASE_ABS_Y:
            return True
        # (b) a shot moving at goal that the keeper reaches before the line
        decay = self.params.ball_decay
        if bvx > 0.0 and ix <= PITCH_HALF_LENGTH and bx + bvx / (1.0 - decay) >= PITCH_HALF_LENGTH:
            y_at_line = by + bvy * (PITCH_HALF_LENGTH - bx) / bvx
            if abs(y_at_line) <= GOAL_HALF_WIDTH + SHOT_POST_MARGIN:
                return True
        # (c) the intercept point is safely inside the penalty area and no opponent is clearly first
        my_dist = math.hypot(ix - keeper.x, iy - keeper.y)
        margin = BOX_MARGIN_BASE + BOX_MARGIN_PER_METRE * my_dist
        if not (
            PENALTY_AREA_X + margin <= ix <= PITCH_HALF_LENGTH and abs(iy) <= PENALTY_AREA_HALF_WIDTH - margin
        ):
            return False
        opponent_cycles = self._opponent_reach_cycles(world, bx, by, bvx, bvy)
        if opponent_cycles + OPPONENT_LEAD_CYCLES <= my_cycles:
            return False
        opponent_dist = min(
            (math.hypot(ix - p.x, iy - p.y) for p in world.players if p.side == "l"), default=math.inf
        )
        return opponent_dist + OPPONENT_LEAD_METRES > my_dist

    def _position_target(
        self, world: World, bx: float, by: float, bvx: float, bvy: float
    ) -> tuple[float, float]:
        """Positioning point (global frame): agent2d's base move with the post and wide-ball exceptions."""
        # Predict the ball where the first opponent would get it; a ball at an opponent's feet stays put.
        if bvx * bvx + bvy * bvy > 0.01:
            cycles = self._opponent_reach_cycles(world, bx, by, bvx, bvy)
            shrink = (1.0 - self.params.ball_decay**cycles) / (1.0 - self.params.ball_decay)
            bx += bvx * shrink
            by += bvy * shrink
        side = 1.0 if by >= 0.0 else -1.0
        if abs(by) > GOAL_HALF_WIDTH and bx > DANGER_BALL_X:
            return POST_MOVE_X, side * POST_MOVE_ABS_Y
        if bx > PITCH_HALF_LENGTH - WIDE_BALL_LINE_DIST and abs(by) > WIDE_BALL_ABS_Y:
            return BASE_MOVE_X, side * WIDE_MOVE_ABS_Y
        # Point at x = BASE_MOVE_X on the segment from the ball to (LINE_ANCHOR_X, 0).
        depth = LINE_ANCHOR_X - bx
        if depth <= LINE_ANCHOR_X - BASE_MOVE_X:
            # Ball level with or behind the base line inside the goal width: stand level with it.
            return BASE_MOVE_X, max(-BASE_MAX_ABS_Y, min(BASE_MAX_ABS_Y, by))
        target_y = by * (LINE_ANCHOR_X - BASE_MOVE_X) / depth
        return BASE_MOVE_X, max(-BASE_MAX_ABS_Y, min(BASE_MAX_ABS_Y, target_y))
