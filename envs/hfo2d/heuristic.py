"""A scripted striker computed from the observation alone (the counterpart of LunarLander's ``heuristic``).

It reads only HFO's low-level features (hfo2d.features): the ball's bearing, distance and velocity, the
kickable flag, the body angle and the goal landmarks. Behaviour, in the body frame (x ahead, y to the right):

* not kickable: go for the ball, aiming where it will be after about (distance / 1 m per cycle) cycles; turn
  when the target is off the body direction by more than a few degrees, else dash at full power. When the
  agent stands between the ball and the goal, it first steps to the side of the ball so the kick does not run
  into its own body;
* kickable and far from goal (> ``SHOOT_DISTANCE``): dribble, i.e. kick the ball toward the goal at
  ``DRIBBLE_SPEED`` m/cycle and chase it;
* kickable and close enough: shoot at full speed at the goal centre (1v0) or, when a goalie is observed (66
  features), at a point inside the post farther from the goalie.

The kick power is solved from rcssserver's kick model (hfo_reference §4.4): the ball's new velocity is
``v + a`` with ``|a| = power * kick_power_rate * (1 - 0.25 * dir_diff / 180 - 0.25 * gap / kickable_margin)``,
capped at ball_accel_max, so the kick cancels the ball's current velocity and sends it where wanted.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from hfo2d.features import (
    BALL_ANGLE_COS,
    BALL_ANGLE_SIN,
    BALL_PROXIMITY,
    BALL_SPEED,
    BALL_SPEED_MAX,
    BALL_VEL_ANGLE_COS,
    BALL_VEL_ANGLE_SIN,
    GOAL_CENTER_COS,
    GOAL_CENTER_PROXIMITY,
    GOAL_CENTER_SIN,
    GOAL_POST_BOTTOM_COS,
    GOAL_POST_BOTTOM_PROXIMITY,
    GOAL_POST_BOTTOM_SIN,
    GOAL_POST_TOP_COS,
    GOAL_POST_TOP_PROXIMITY,
    GOAL_POST_TOP_SIN,
    GOALIE_ANGLE_COS,
    GOALIE_ANGLE_SIN,
    GOALIE_PROXIMITY,
    KICKABLE,
    NUM_BASIC_FEATURES,
    SELF_BODY_COS,
    SELF_BODY_SIN,
    landmark_position,
)

# rcssserver defaults used by the kick solver (rcssserver 15.2.2 serverparam.cpp, via hfo_reference §4).
KICK_POWER_RATE = 0.027
BALL_ACCEL_MAX = 2.7
BALL_SPEED_LIMIT = 3.0
BALL_DECAY = 0.94
KICKABLE_MARGIN = 0.7
PLAYER_SIZE = 0.3
BALL_SIZE = 0.085
MAX_POWER = 100.0
PLAYER_RUN_SPEED = 1.0  # m/cycle covered by a player dashing at full power (hfo_reference §4.2)

SHOOT_DISTANCE = 24.0  # m from ball to goal below which the striker shoots instead of dribbling
DRIBBLE_SPEED = 1.6  # m/cycle given to the ball when dribbling (it rolls ~27 m; the striker catches it)
SHOT_SPEED = BALL_SPEED_LIMIT
MIN_TURN_ANGLE_DEG = 8.0  # body-direction error tolerated while dashing
BODY_CLEARANCE = PLAYER_SIZE + BALL_SIZE + 0.2  # a kicked ball passing closer than this would hit the kicker
SIDE_STEP_OFFSET = 0.8  # m beside the ball to stand on before kicking it back past oneself
SIDE_STEP_RANGE = 4.0  # m; closer than this to the ball the side step replaces the direct approach
POST_AIM_INSET = 2.0  # m inside the post when aiming away from the goalie
MAX_PREDICTION_CYCLES = 20

DASH, TURN, KICK = 0, 1, 2


def _aim_point(obs: np.ndarray) -> tuple[float, float]:
    """Body-frame point to shoot at: goal centre, or inside the post farther from an observed goalie."""
    goal = landmark_position(obs, GOAL_CENTER_SIN, GOAL_CENTER_COS, GOAL_CENTER_PROXIMITY)
    if obs.shape[0] <= NUM_BASIC_FEATURES or (obs[GOALIE_ANGLE_SIN] == 0.0 and obs[GOALIE_ANGLE_COS] == 0.0):
        return goal
    goalie = landmark_position(obs, GOALIE_ANGLE_SIN, GOALIE_ANGLE_COS, GOALIE_PROXIMITY)
    top = landmark_position(obs, GOAL_POST_TOP_SIN, GOAL_POST_TOP_COS, GOAL_POST_TOP_PROXIMITY)
    bottom = landmark_position(obs, GOAL_POST_BOTTOM_SIN, GOAL_POST_BOTTOM_COS, GOAL_POST_BOTTOM_PROXIMITY)
    far_post = max(top, bottom, key=lambda post: math.hypot(post[0] - goalie[0], post[1] - goalie[1]))
    to_centre_x, to_centre_y = goal[0] - far_post[0], goal[1] - far_post[1]
    half_width = math.hypot(to_centre_x, to_centre_y)
    if half_width <= POST_AIM_INSET:
        return goal
    scale = POST_AIM_INSET / half_width
    return far_post[0] + scale * to_centre_x, far_post[1] + scale * to_centre_y


def _kick_command(
    ball_x: float, ball_y: float, ball_vx: float, ball_vy: float, dir_x: float, dir_y: float, speed: float
) -> tuple[float, float]:
    """(power, direction_deg) that gives the ball velocity ``speed * (dir_x, dir_y)`` (body frame, unit dir).

    If that needs more than the strongest kick from this ball position, the kick sends the ball as fast as
    possible along the wanted direction instead.
    """
    dist = math.hypot(ball_x, ball_y)
    dir_diff_deg = abs(math.degrees(math.atan2(ball_y, ball_x)))
    gap = max(0.0, dist - PLAYER_SIZE - BALL_SIZE)
    efficiency = max(1e-3, 1.0 - 0.25 * dir_diff_deg / 180.0 - 0.25 * gap / KICKABLE_MARGIN)
    max_accel = min(MAX_POWER * KICK_POWER_RATE * efficiency, BALL_ACCEL_MAX)
    accel_x = speed * dir_x - ball_vx
    accel_y = speed * dir_y - ball_vy
    if math.hypot(accel_x, accel_y) > max_accel:
        # Largest s with |s * dir - v| = max_accel: s = (dir . v) + sqrt((dir . v)^2 - |v|^2 + max_accel^2).
        along = dir_x * ball_vx + dir_y * ball_vy
        discriminant = along * along - (ball_vx * ball_vx + ball_vy * ball_vy) + max_accel * max_accel
        if discriminant > 0.0:
            reachable = along + math.sqrt(discriminant)
            accel_x = reachable * dir_x - ball_vx
            accel_y = reachable * dir_y - ball_vy
        else:
            accel_x, accel_y = dir_x, dir_y
    accel = math.hypot(accel_x, accel_y)
    power = min(MAX_POWER, accel / (KICK_POWER_RATE * efficiency))
    return power, math.degrees(math.atan2(accel_y, accel_x))


def _move_command(target_x: float, target_y: float) -> tuple[int, float, float]:
    """Turn toward a body-frame target when it is off the body direction, else dash at it at full power."""
    dist = math.hypot(target_x, target_y)
    bearing_deg = math.degrees(math.atan2(target_y, target_x))
    tolerance = max(MIN_TURN_ANGLE_DEG, math.degrees(math.atan2(0.5, max(dist, 1e-6))))
    if abs(bearing_deg) > tolerance:
        return TURN, bearing_deg, 0.0
    return DASH, MAX_POWER, 0.0


def heuristic_command(obs: np.ndarray) -> tuple[int, float, float]:
    """The striker's decision for one observation: (action, first parameter, second parameter).

    Returns:
        (DASH, power [0, 100], direction_deg), (TURN, direction_deg, 0) or (KICK, power [0, 100], direction_deg),
        directions relative to the body in [-180, 180].
    """
    ball_x, ball_y = landmark_position(obs, BALL_ANGLE_SIN, BALL_ANGLE_COS, BALL_PROXIMITY)
    body = math.atan2(float(obs[SELF_BODY_SIN]), float(obs[SELF_BODY_COS]))
    ball_speed = (float(obs[BALL_SPEED]) + 1.0) * 0.5 * BALL_SPEED_MAX
    ball_heading = math.atan2(float(obs[BALL_VEL_ANGLE_SIN]), float(obs[BALL_VEL_ANGLE_COS])) - body
    ball_vx = ball_speed * math.cos(ball_heading)
    ball_vy = ball_speed * math.sin(ball_heading)

    aim_x, aim_y = _aim_point(obs)
    to_goal_x, to_goal_y = aim_x - ball_x, aim_y - ball_y
    goal_dist = math.hypot(to_goal_x, to_goal_y)
    dir_x, dir_y = to_goal_x / max(goal_dist, 1e-6), to_goal_y / max(goal_dist, 1e-6)
    # Where the ball passes the kicker: the kicker is at the origin, the ball moves from b along dir.
    along = ball_x * dir_x + ball_y * dir_y
    lateral = ball_x * dir_y - ball_y * dir_x
    kick_blocked = along < 0.0 and abs(lateral) < BODY_CLEARANCE

    if obs[KICKABLE] > 0.0 and not kick_blocked:
        speed = SHOT_SPEED if goal_dist <= SHOOT_DISTANCE else DRIBBLE_SPEED
        power, direction = _kick_command(ball_x, ball_y, ball_vx, ball_vy, dir_x, dir_y, speed)
        return KICK, power, direction

    ball_dist = math.hypot(ball_x, ball_y)
    if ball_dist < SIDE_STEP_RANGE and along < 0.0 and abs(lateral) < SIDE_STEP_OFFSET:
        # Between the ball and the goal: step to the ball's side (the side the kicker is already on).
        side = 1.0 if lateral >= 0.0 else -1.0
        return _move_command(
            ball_x - side * SIDE_STEP_OFFSET * dir_y, ball_y + side * SIDE_STEP_OFFSET * dir_x
        )

    cycles = min(ball_dist / PLAYER_RUN_SPEED, MAX_PREDICTION_CYCLES)
    travel = (1.0 - BALL_DECAY**cycles) / (1.0 - BALL_DECAY)
    return _move_command(ball_x + ball_vx * travel, ball_y + ball_vy * travel)


def heuristic(env: Any, obs: np.ndarray) -> np.ndarray | tuple[int, np.ndarray, np.ndarray, np.ndarray]:
    """Scripted striker action for ``obs`` (58 or 66 features), in ``env``'s action format.

    Only the observation is used for the decision; ``env`` only says whether the action is ``"flat"`` (the
    default: float32 array of 8 values in [0, 1], [pref_dash, pref_turn, pref_kick, dash_power, dash_dir,
    turn_dir, kick_power, kick_dir]) or ``"parameterized"`` (gym-soccer's tuple).
    """
    action, first, second = heuristic_command(obs)
    action_format = getattr(getattr(env, "unwrapped", env), "action_format", "flat")
    if action_format == "parameterized":
        dash = np.array([first, second] if action == DASH else [0.0, 0.0], dtype=np.float32)
        turn = np.array([first] if action == TURN else [0.0], dtype=np.float32)
        kick = np.array([first, second] if action == KICK else [0.0, 0.0], dtype=np.float32)
        return action, dash, turn, kick
    flat = np.full(8, 0.5, dtype=np.float32)
    flat[0:3] = 0.0
    flat[action] = 1.0
    if action == DASH:
        flat[3] = first / MAX_POWER
        flat[4] = (second + 180.0) / 360.0
    elif action == TURN:
        flat[5] = (first + 180.0) / 360.0
    else:
        flat[6] = first / MAX_POWER
        flat[7] = (second + 180.0) / 360.0
    return flat
