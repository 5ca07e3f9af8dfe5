"""HFO's low-level state features, paper era (58 features for 1v0, 66 against one goalie).

The layout, encodings and normalisers are those of HFO's ``LowLevelFeatureExtractor`` as it stood before
July 2017, the version Hausknecht & Stone (ICLR 2016) trained on (hfo_reference §2 and §9):

* flags are +1 / -1;
* an angle is the pair (sin θ, cos θ);
* a proximity is ``1 - 2 * clip(d / dmax, 0, 1)``: +1 when co-located, -1 at ``dmax`` or beyond;
* a scalar over [lo, hi] is mapped linearly onto [-1, 1] after clipping;
* a landmark is (sin, cos) of its bearing relative to the body, ``atan2(landmark - self) - body``, followed by its
  proximity with ``dmax = MAX_HFO_DIST``. With rcssserver's frame (+y down) a positive bearing puts the landmark
  on the agent's right, so a ball straight to the right of an agent facing +x reads (sin, cos) = (1, 0).

Normalisers (hfo_reference §2.1, §2.2, §9): ``MAX_HFO_DIST = sqrt(52.5² + 34²) = 62.55`` (the value before
2018-09), out-of-bounds ``dmax`` 52.5 for x and 68 for y (before 2019-03), self speed 0.46, other players' speed
0.75, ball speed 5.0, stamina 8000. The state is "fullstate": exact, with every valid flag +1. Nobody tackles, so
the frozen flag is always -1. The kickable flag follows librcsc's world model: the ball's centre lies within
``kickable_area - 0.055 = 1.03`` m (hfo_reference §2.3).

Per other player (8 features): landmark at its position (3), its body angle (2), its speed over [0, 0.75] (1), its
velocity heading (2). Teammates come first, then opponents, each sorted by distance from self; a player is
listed only while its x > 0 (HFO's test), otherwise its slot is zeros.

HFO master (b8b2a1d), which the real-HFO backend talks to, returns a longer vector (:func:`hfo_num_features`: 59
for 1v0, 68 for 1v1) with other normalisers: :func:`hfo_feature_list` computes it from the state and
:func:`paper_from_hfo` converts it into the paper layout above.

The code is plain ``math`` on Python floats: the env needs tens of thousands of feature vectors per second and a
few dozen tiny numpy operations would cost more than the whole computation. :func:`low_level_feature_list` (and
:data:`paper_feature_list`) run the port of :func:`low_level_feature_list_python` in the optional C extension
(:mod:`hfo2d.accel`) when it is built, with the same floats.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, TypeVar

import numpy as np

from hfo2d import accel as _accel

if TYPE_CHECKING:
    from hfo2d.physics import BallState, PlayerState, World

# ---------------------------------------------------------------------------------------------------------------
# Normalisers (hfo_reference §2.1, §9; HFO feature_extractor of 2015-2016)
# ---------------------------------------------------------------------------------------------------------------
PITCH_HALF_LENGTH = 52.5
PITCH_HALF_WIDTH = 34.0
PITCH_WIDTH = 68.0
GOAL_HALF_WIDTH = 7.01
PENALTY_AREA_X = 36.0  # pitch_half_length - penalty_area_length (16.5)
PENALTY_AREA_HALF_WIDTH = 20.16
MAX_HFO_DIST = math.sqrt(PITCH_HALF_LENGTH**2 + PITCH_HALF_WIDTH**2)  # 62.55 m, paper-era maxHFODist
OUT_OF_BOUNDS_X_DIST_MAX = PITCH_HALF_LENGTH  # 52.5 m, features 46 and 47 before 2019-03
OUT_OF_BOUNDS_Y_DIST_MAX = PITCH_WIDTH  # 68 m, features 48 and 49 before 2019-03
SELF_SPEED_MAX = 0.46  # m/cycle, HFO's observedSelfSpeedMax
PLAYER_SPEED_MAX = 0.75  # m/cycle, HFO's observedPlayerSpeedMax
BALL_SPEED_MAX = 5.0  # m/cycle, HFO's observedBallSpeedMax
STAMINA_MAX = 8000.0  # HFO's observedStaminaMax
KICKABLE_BUFFER = 0.055  # m; librcsc marks the ball kickable within kickable_area - 0.055 (1.03 m)

NUM_BASIC_FEATURES = 58
FEATURES_PER_PLAYER = 8

# HFO master's normalisers (HFO b8b2a1d). maxHFODist is a float32 sqrtf of half length² + full WIDTH²
# (src/feature_extractor.cpp), 85.90838 m; the out-of-bounds normalisers are 1.1 * 52.5 and 1.05 * 68
# (src/lowlevel_feature_extractor.cpp), passed to addDistFeature as floats (hence the float32 roundings).
HFO_MASTER_MAX_DIST = 85.90837860107422  # float32 sqrtf(52.5² + 68²)
HFO_MASTER_OUT_OF_BOUNDS_X_DIST_MAX = 57.75  # float32(1.1 * 52.5)
HFO_MASTER_OUT_OF_BOUNDS_Y_DIST_MAX = 71.4000015258789  # float32(1.05 * 68)

# ---------------------------------------------------------------------------------------------------------------
# Feature indices (hfo_reference §2.2)
# ---------------------------------------------------------------------------------------------------------------
SELF_POS_VALID = 0
SELF_VEL_VALID = 1
SELF_VEL_ANGLE_SIN = 2  # sin(body - own velocity heading)
SELF_VEL_ANGLE_COS = 3
SELF_SPEED = 4
SELF_BODY_SIN = 5  # global body angle
SELF_BODY_COS = 6
SELF_STAMINA = 7
SELF_FROZEN = 8
COLLIDING_WITH_BALL = 9
COLLIDING_WITH_PLAYER = 10
COLLIDING_WITH_POST = 11
KICKABLE = 12
GOAL_CENTER_SIN = 13
GOAL_CENTER_COS = 14
GOAL_CENTER_PROXIMITY = 15
GOAL_POST_TOP_SIN = 16
GOAL_POST_TOP_COS = 17
GOAL_POST_TOP_PROXIMITY = 18
GOAL_POST_BOTTOM_SIN = 19
GOAL_POST_BOTTOM_COS = 20
GOAL_POST_BOTTOM_PROXIMITY = 21
PENALTY_BOX_CENTER_SIN = 22
PENALTY_BOX_CENTER_COS = 23
PENALTY_BOX_CENTER_PROXIMITY = 24
PENALTY_BOX_TOP_SIN = 25
PENALTY_BOX_TOP_COS = 26
PENALTY_BOX_TOP_PROXIMITY = 27
PENALTY_BOX_BOTTOM_SIN = 28
PENALTY_BOX_BOTTOM_COS = 29
PENALTY_BOX_BOTTOM_PROXIMITY = 30
CENTER_FIELD_SIN = 31
CENTER_FIELD_COS = 32
CENTER_FIELD_PROXIMITY = 33
CORNER_TOP_LEFT_SIN = 34
CORNER_TOP_LEFT_COS = 35
CORNER_TOP_LEFT_PROXIMITY = 36
CORNER_TOP_RIGHT_SIN = 37
CORNER_TOP_RIGHT_COS = 38
CORNER_TOP_RIGHT_PROXIMITY = 39
CORNER_BOTTOM_RIGHT_SIN = 40
CORNER_BOTTOM_RIGHT_COS = 41
CORNER_BOTTOM_RIGHT_PROXIMITY = 42
CORNER_BOTTOM_LEFT_SIN = 43
CORNER_BOTTOM_LEFT_COS = 44
CORNER_BOTTOM_LEFT_PROXIMITY = 45
OUT_OF_BOUNDS_LEFT = 46  # proximity of x = 0:    1 - 2 * min(x / 52.5, 1)
OUT_OF_BOUNDS_RIGHT = 47  # proximity of x = 52.5: 1 - 2 * min((52.5 - x) / 52.5, 1)
OUT_OF_BOUNDS_TOP = 48  # proximity of y = -34:   1 - 2 * min((34 + y) / 68, 1)
OUT_OF_BOUNDS_BOTTOM = 49  # proximity of y = +34: 1 - 2 * min((34 - y) / 68, 1)
#: The agent's own x position, as the field-half skill router reads it: the proximity of x = 0 above, positive
#: exactly when x < 26.25 m (the half of the attacked half-field away from the goal).
SELF_X = OUT_OF_BOUNDS_LEFT
BALL_POS_VALID = 50
BALL_ANGLE_SIN = 51
BALL_ANGLE_COS = 52
BALL_PROXIMITY = 53
BALL_VEL_VALID = 54
BALL_SPEED = 55
BALL_VEL_ANGLE_SIN = 56  # global heading of the ball's velocity
BALL_VEL_ANGLE_COS = 57

# Offsets inside an 8-feature player block.
PLAYER_ANGLE_SIN = 0
PLAYER_ANGLE_COS = 1
PLAYER_PROXIMITY = 2
PLAYER_BODY_SIN = 3
PLAYER_BODY_COS = 4
PLAYER_SPEED = 5
PLAYER_VEL_ANGLE_SIN = 6
PLAYER_VEL_ANGLE_COS = 7

# The goalie block of the 66-feature (1v1) vector: the one opponent, right after the basic features.
GOALIE_ANGLE_SIN = NUM_BASIC_FEATURES + PLAYER_ANGLE_SIN  # 58
GOALIE_ANGLE_COS = NUM_BASIC_FEATURES + PLAYER_ANGLE_COS  # 59
GOALIE_PROXIMITY = NUM_BASIC_FEATURES + PLAYER_PROXIMITY  # 60
GOALIE_BODY_SIN = NUM_BASIC_FEATURES + PLAYER_BODY_SIN  # 61
GOALIE_BODY_COS = NUM_BASIC_FEATURES + PLAYER_BODY_COS  # 62
GOALIE_SPEED = NUM_BASIC_FEATURES + PLAYER_SPEED  # 63
GOALIE_VEL_ANGLE_SIN = NUM_BASIC_FEATURES + PLAYER_VEL_ANGLE_SIN  # 64
GOALIE_VEL_ANGLE_COS = NUM_BASIC_FEATURES + PLAYER_VEL_ANGLE_COS  # 65

# Landmarks in feature order: name -> (x, y) in metres (HFO LowLevelFeatureExtractor, paper era).
LANDMARKS: tuple[tuple[str, tuple[float, float]], ...] = (
    ("goal_center", (PITCH_HALF_LENGTH, 0.0)),
    ("goal_post_top", (PITCH_HALF_LENGTH, -GOAL_HALF_WIDTH)),
    ("goal_post_bottom", (PITCH_HALF_LENGTH, GOAL_HALF_WIDTH)),
    ("penalty_box_center", (PENALTY_AREA_X, 0.0)),
    ("penalty_box_top", (PENALTY_AREA_X, -PENALTY_AREA_HALF_WIDTH)),
    ("penalty_box_bottom", (PENALTY_AREA_X, PENALTY_AREA_HALF_WIDTH)),
    ("center_field", (0.0, 0.0)),
    ("corner_top_left", (0.0, -PITCH_HALF_WIDTH)),
    ("corner_top_right", (PITCH_HALF_LENGTH, -PITCH_HALF_WIDTH)),
    ("corner_bottom_right", (PITCH_HALF_LENGTH, PITCH_HALF_WIDTH)),
    ("corner_bottom_left", (0.0, PITCH_HALF_WIDTH)),
)
_LANDMARK_POINTS: tuple[tuple[float, float], ...] = tuple(point for _, point in LANDMARKS)
FIRST_LANDMARK = GOAL_CENTER_SIN  # 13


def _basic_feature_names() -> tuple[str, ...]:
    names = [
        "self_pos_valid",
        "self_vel_valid",
        "self_vel_angle_sin",
        "self_vel_angle_cos",
        "self_speed",
        "self_body_sin",
        "self_body_cos",
        "self_stamina",
        "self_frozen",
        "colliding_with_ball",
        "colliding_with_player",
        "colliding_with_post",
        "kickable",
    ]
    for name, _ in LANDMARKS:
        names += [f"{name}_sin", f"{name}_cos", f"{name}_proximity"]
    names += ["out_of_bounds_left", "out_of_bounds_right", "out_of_bounds_top", "out_of_bounds_bottom"]
    names += ["ball_pos_valid", "ball_angle_sin", "ball_angle_cos", "ball_proximity"]
    names += ["ball_vel_valid", "ball_speed", "ball_vel_angle_sin", "ball_vel_angle_cos"]
    return tuple(names)


BASIC_FEATURE_NAMES: tuple[str, ...] = _basic_feature_names()
PLAYER_FEATURE_NAMES: tuple[str, ...] = (
    "angle_sin",
    "angle_cos",
    "proximity",
    "body_sin",
    "body_cos",
    "speed",
    "vel_angle_sin",
    "vel_angle_cos",
)
GOALIE_FEATURE_NAMES: tuple[str, ...] = tuple(f"goalie_{name}" for name in PLAYER_FEATURE_NAMES)


def num_features(num_teammates: int = 0, num_opponents: int = 0) -> int:
    """Length of the feature vector: ``58 + 8 * (teammates + opponents)`` (paper era, no uniform numbers)."""
    return NUM_BASIC_FEATURES + FEATURES_PER_PLAYER * (num_teammates + num_opponents)


def hfo_num_features(num_teammates: int = 0, num_opponents: int = 0) -> int:
    """Length of HFO master's low-level vector: ``58 + 9 * (teammates + opponents) + 1`` (59 for 1v0, 68 for 1v1).

    HFO master's layout (src/lowlevel_feature_extractor.cpp): the 58 basic features, the 8-feature blocks of the
    teammates then the opponents, then one uniform number / 100 per teammate slot and per opponent slot in the same
    order (-1 for a slot with nobody listed), then the last action's status (+1 succeeded, -1 failed).
    """
    players = num_teammates + num_opponents
    return NUM_BASIC_FEATURES + (FEATURES_PER_PLAYER + 1) * players + 1


def feature_names(num_teammates: int = 0, num_opponents: int = 0) -> tuple[str, ...]:
    """Names of the features in order; with one opponent and no teammate the block is ``goalie_*``."""
    if num_teammates == 0 and num_opponents == 1:
        return BASIC_FEATURE_NAMES + GOALIE_FEATURE_NAMES
    names = list(BASIC_FEATURE_NAMES)
    for kind, count in (("teammate", num_teammates), ("opponent", num_opponents)):
        for slot in range(count):
            names += [f"{kind}{slot}_{name}" for name in PLAYER_FEATURE_NAMES]
    return tuple(names)


_DEG_TO_RAD = math.pi / 180.0


def _append_player_block(
    features: list[float],
    other: PlayerState,
    self_x: float,
    self_y: float,
    body_cos: float,
    body_sin: float,
    max_dist: float = MAX_HFO_DIST,
) -> None:
    """Append the 8 features describing ``other`` as seen from self (position, body angle, velocity)."""
    dx = other.x - self_x
    dy = other.y - self_y
    dist = math.hypot(dx, dy)
    if dist > 0.0:
        heading_cos = dx / dist
        heading_sin = dy / dist
    else:  # rcsc's Vector2D::th() of the zero vector is 0
        heading_cos, heading_sin = 1.0, 0.0
    other_body = other.body_deg * _DEG_TO_RAD
    speed = math.hypot(other.vx, other.vy)
    if speed > 0.0:
        vel_cos = other.vx / speed
        vel_sin = other.vy / speed
    else:
        vel_cos, vel_sin = 1.0, 0.0
    features += (
        heading_sin * body_cos - heading_cos * body_sin,
        heading_cos * body_cos + heading_sin * body_sin,
        1.0 - 2.0 / max_dist * dist if dist < max_dist else -1.0,
        math.sin(other_body),
        math.cos(other_body),
        2.0 * speed / PLAYER_SPEED_MAX - 1.0 if speed < PLAYER_SPEED_MAX else 1.0,
        vel_sin,
        vel_cos,
    )


# low_level_feature_list unrolls the landmark loop for exactly these points, in this order
if _LANDMARK_POINTS != (
    (PITCH_HALF_LENGTH, 0.0),
    (PITCH_HALF_LENGTH, -GOAL_HALF_WIDTH),
    (PITCH_HALF_LENGTH, GOAL_HALF_WIDTH),
    (PENALTY_AREA_X, 0.0),
    (PENALTY_AREA_X, -PENALTY_AREA_HALF_WIDTH),
    (PENALTY_AREA_X, PENALTY_AREA_HALF_WIDTH),
    (0.0, 0.0),
    (0.0, -PITCH_HALF_WIDTH),
    (PITCH_HALF_LENGTH, -PITCH_HALF_WIDTH),
    (PITCH_HALF_LENGTH, PITCH_HALF_WIDTH),
    (0.0, PITCH_HALF_WIDTH),
):
    raise ImportError("LANDMARKS changed: update low_level_feature_list's unrolled landmark block")


def _landmark_features(
    x: float, y: float, body_cos: float, body_sin: float, max_dist: float = MAX_HFO_DIST
) -> list[float]:
    """The (sin bearing, cos bearing, proximity) triples of the landmarks, in LANDMARKS order, one by one."""
    features: list[float] = []
    two_over_max_dist = 2.0 / max_dist
    for landmark_x, landmark_y in _LANDMARK_POINTS:
        dx = landmark_x - x
        dy = landmark_y - y
        dist = math.hypot(dx, dy)
        if dist > 0.0:
            # (sin, cos) of bearing = heading - body, expanded so that no atan2 is needed
            features += (
                (dy * body_cos - dx * body_sin) / dist,
                (dx * body_cos + dy * body_sin) / dist,
                1.0 - two_over_max_dist * dist if dist < max_dist else -1.0,
            )
        else:  # rcsc's Vector2D::th() of the zero vector is 0, so the bearing is -body
            features += (-body_sin, body_cos, 1.0)
    return features


def low_level_feature_list_python(
    player: PlayerState,
    ball: BallState,
    kickable_distance: float,
    teammates: list[PlayerState] | tuple[PlayerState, ...] = (),
    opponents: list[PlayerState] | tuple[PlayerState, ...] = (),
    *,
    max_dist: float = MAX_HFO_DIST,
    out_of_bounds_x_max: float = OUT_OF_BOUNDS_X_DIST_MAX,
    out_of_bounds_y_max: float = OUT_OF_BOUNDS_Y_DIST_MAX,
    opponent_control: bool = False,
) -> list[float]:
    """The features as a list of Python floats (the fast path; see :func:`low_level_features`), in pure Python:
    the reference of the compiled kernel that :func:`low_level_feature_list` runs when hfo2d._accel is built.

    Args:
        player: the observing player.
        ball: the ball.
        kickable_distance: the ball-centre distance (m) under which the kickable flag is +1 (librcsc: 1.03).
        teammates: the other players of the observer's side, one 8-feature slot each.
        opponents: the players of the other side, one 8-feature slot each.
        max_dist: normaliser of the proximities (landmarks, ball, players); the paper era's by default.
        out_of_bounds_x_max: normaliser of features 46 and 47.
        out_of_bounds_y_max: normaliser of features 48 and 49.
        opponent_control: apply librcsc's opponent-control rule (:func:`opponent_controls_ball`): the ball's
            velocity reads 0 while the opponent nearest the ball can kick it and the observer cannot. The real
            HFO's agents see the ball so (measured: benchmarks/team_features_fidelity.py); off by default, which
            keeps hfo2d's registered envs as they were.

    Returns:
        ``num_features(len(teammates), len(opponents))`` floats in [-1, 1].
    """
    x = player.x
    y = player.y
    vx = player.vx
    vy = player.vy
    body = player.body_deg * _DEG_TO_RAD
    body_cos = math.cos(body)
    body_sin = math.sin(body)

    speed = math.hypot(vx, vy)
    if speed > 0.0:
        vel_cos = vx / speed
        vel_sin = vy / speed
    else:  # heading of a zero velocity is 0, so body - heading = body
        vel_cos, vel_sin = 1.0, 0.0
    stamina = player.stamina

    features: list[float] = [
        1.0,  # self position valid (fullstate)
        1.0,  # self velocity valid
        body_sin * vel_cos - body_cos * vel_sin,  # sin(body - velocity heading)
        body_cos * vel_cos + body_sin * vel_sin,
        2.0 * speed / SELF_SPEED_MAX - 1.0 if speed < SELF_SPEED_MAX else 1.0,
        body_sin,
        body_cos,
        (2.0 * stamina / STAMINA_MAX - 1.0 if stamina < STAMINA_MAX else 1.0) if stamina > 0.0 else -1.0,
        -1.0,  # frozen: nobody tackles
        1.0 if player.collided_ball else -1.0,
        1.0 if player.collided_player else -1.0,
        1.0 if player.collided_post else -1.0,
        0.0,  # kickable, filled in with the ball below
    ]
    hypot = math.hypot
    two_over_max_dist = 2.0 / max_dist
    # The landmarks, unrolled (the loop of _landmark_features costs about 10% more): they share three x and seven
    # y coordinates, so each offset and its products with the body's cos and sin are formed once, by the same
    # operations as per landmark (the same floats).
    gx = PITCH_HALF_LENGTH - x  # goal line
    gxc = gx * body_cos
    gxs = gx * body_sin
    px = PENALTY_AREA_X - x  # penalty box line
    pxc = px * body_cos
    pxs = px * body_sin
    cx = 0.0 - x  # halfway line
    cxc = cx * body_cos
    cxs = cx * body_sin
    oy = 0.0 - y
    oyc = oy * body_cos
    oys = oy * body_sin
    ty = -GOAL_HALF_WIDTH - y  # posts
    tyc = ty * body_cos
    tys = ty * body_sin
    by = GOAL_HALF_WIDTH - y
    byc = by * body_cos
    bys = by * body_sin
    tpy = -PENALTY_AREA_HALF_WIDTH - y  # penalty box corners
    tpyc = tpy * body_cos
    tpys = tpy * body_sin
    bpy = PENALTY_AREA_HALF_WIDTH - y
    bpyc = bpy * body_cos
    bpys = bpy * body_sin
    tcy = -PITCH_HALF_WIDTH - y  # touch lines
    tcyc = tcy * body_cos
    tcys = tcy * body_sin
    bcy = PITCH_HALF_WIDTH - y
    bcyc = bcy * body_cos
    bcys = bcy * body_sin
    d0 = hypot(gx, oy)
    d1 = hypot(gx, ty)
    d2 = hypot(gx, by)
    d3 = hypot(px, oy)
    d4 = hypot(px, tpy)
    d5 = hypot(px, bpy)
    d6 = hypot(cx, oy)
    d7 = hypot(cx, tcy)
    d8 = hypot(gx, tcy)
    d9 = hypot(gx, bcy)
    d10 = hypot(cx, bcy)
    if (
        d0 > 0.0
        and d1 > 0.0
        and d2 > 0.0
        and d3 > 0.0
        and d4 > 0.0
        and d5 > 0.0
        and d6 > 0.0
        and d7 > 0.0
        and d8 > 0.0
        and d9 > 0.0
        and d10 > 0.0
    ):
        # (sin, cos) of bearing = heading - body, expanded so that no atan2 is needed
        features += (
            (oyc - gxs) / d0,
            (gxc + oys) / d0,
            1.0 - two_over_max_dist * d0 if d0 < max_dist else -1.0,
            (tyc - gxs) / d1,
            (gxc + tys) / d1,
            1.0 - two_over_max_dist * d1 if d1 < max_dist else -1.0,
            (byc - gxs) / d2,
            (gxc + bys) / d2,
            1.0 - two_over_max_dist * d2 if d2 < max_dist else -1.0,
            (oyc - pxs) / d3,
            (pxc + oys) / d3,
            1.0 - two_over_max_dist * d3 if d3 < max_dist else -1.0,
            (tpyc - pxs) / d4,
            (pxc + tpys) / d4,
            1.0 - two_over_max_dist * d4 if d4 < max_dist else -1.0,
            (bpyc - pxs) / d5,
            (pxc + bpys) / d5,
            1.0 - two_over_max_dist * d5 if d5 < max_dist else -1.0,
            (oyc - cxs) / d6,
            (cxc + oys) / d6,
            1.0 - two_over_max_dist * d6 if d6 < max_dist else -1.0,
            (tcyc - cxs) / d7,
            (cxc + tcys) / d7,
            1.0 - two_over_max_dist * d7 if d7 < max_dist else -1.0,
            (tcyc - gxs) / d8,
            (gxc + tcys) / d8,
            1.0 - two_over_max_dist * d8 if d8 < max_dist else -1.0,
            (bcyc - gxs) / d9,
            (gxc + bcys) / d9,
            1.0 - two_over_max_dist * d9 if d9 < max_dist else -1.0,
            (bcyc - cxs) / d10,
            (cxc + bcys) / d10,
            1.0 - two_over_max_dist * d10 if d10 < max_dist else -1.0,
        )
    else:  # the player stands on a landmark
        features += _landmark_features(x, y, body_cos, body_sin, max_dist)

    # Out-of-bounds proximities: 1 - 2 * clip(d / dmax, 0, 1) of the distances to the four lines.
    left = x
    right = PITCH_HALF_LENGTH - x
    top = PITCH_HALF_WIDTH + y
    bottom = PITCH_HALF_WIDTH - y

    dx = ball.x - x
    dy = ball.y - y
    dist = hypot(dx, dy)
    if dist > 0.0:
        heading_cos = dx / dist
        heading_sin = dy / dist
    else:
        heading_cos, heading_sin = 1.0, 0.0
    features[KICKABLE] = 1.0 if dist <= kickable_distance else -1.0
    ball_vx = ball.vx
    ball_vy = ball.vy
    if (
        opponent_control
        and dist > kickable_distance
        and opponent_controls_ball(player, ball, opponents, dist)
    ):
        ball_vx = ball_vy = 0.0
    ball_speed = hypot(ball_vx, ball_vy)
    if ball_speed > 0.0:
        ball_vel_cos = ball_vx / ball_speed
        ball_vel_sin = ball_vy / ball_speed
    else:
        ball_vel_cos, ball_vel_sin = 1.0, 0.0
    features += (
        # (the out-of-bounds block written out: a loop over the four lines costs about twice as much)
        1.0
        if left <= 0.0
        else (-1.0 if left >= out_of_bounds_x_max else 1.0 - 2.0 * left / out_of_bounds_x_max),
        1.0
        if right <= 0.0
        else (-1.0 if right >= out_of_bounds_x_max else 1.0 - 2.0 * right / out_of_bounds_x_max),
        1.0
        if top <= 0.0
        else (-1.0 if top >= out_of_bounds_y_max else 1.0 - 2.0 * top / out_of_bounds_y_max),
        1.0
        if bottom <= 0.0
        else (-1.0 if bottom >= out_of_bounds_y_max else 1.0 - 2.0 * bottom / out_of_bounds_y_max),
        1.0,  # ball position valid
        heading_sin * body_cos - heading_cos * body_sin,
        heading_cos * body_cos + heading_sin * body_sin,
        1.0 - two_over_max_dist * dist if dist < max_dist else -1.0,
        1.0,  # ball velocity valid
        2.0 * ball_speed / BALL_SPEED_MAX - 1.0 if ball_speed < BALL_SPEED_MAX else 1.0,
        ball_vel_sin,
        ball_vel_cos,
    )

    if not teammates and len(opponents) == 1:
        # 1v1 (the goalie tasks): the one slot without the sorting loop (the same numbers)
        other = opponents[0]
        if other.x > 0.0:  # HFO lists a player only inside the HFO half (x > 0)
            _append_player_block(features, other, x, y, body_cos, body_sin, max_dist)
        else:
            features += _EMPTY_PLAYER_BLOCK
        return features
    for group in (teammates, opponents):
        if not group:
            continue
        if len(group) > 1:
            group = sorted(group, key=lambda other: (other.x - x) ** 2 + (other.y - y) ** 2)
        listed = 0
        for other in group:
            if other.x > 0.0:  # HFO lists a player only inside the HFO half (x > 0)
                _append_player_block(features, other, x, y, body_cos, body_sin, max_dist)
                listed += 1
        features += [0.0] * (FEATURES_PER_PLAYER * (len(group) - listed))
    return features


_EMPTY_PLAYER_BLOCK = (0.0,) * FEATURES_PER_PLAYER  # the slot of a player not listed

_ACCEL_FEATURES = None if _accel.ACCEL is None else _accel.ACCEL.low_level_feature_list
if _accel.ACCEL is not None and _accel.ACCEL.FEATURE_CONSTANTS != {
    "PITCH_HALF_LENGTH": PITCH_HALF_LENGTH,
    "PITCH_HALF_WIDTH": PITCH_HALF_WIDTH,
    "GOAL_HALF_WIDTH": GOAL_HALF_WIDTH,
    "PENALTY_AREA_X": PENALTY_AREA_X,
    "PENALTY_AREA_HALF_WIDTH": PENALTY_AREA_HALF_WIDTH,
    "SELF_SPEED_MAX": SELF_SPEED_MAX,
    "PLAYER_SPEED_MAX": PLAYER_SPEED_MAX,
    "BALL_SPEED_MAX": BALL_SPEED_MAX,
    "STAMINA_MAX": STAMINA_MAX,
    "NUM_BASIC_FEATURES": NUM_BASIC_FEATURES,
    "FEATURES_PER_PLAYER": FEATURES_PER_PLAYER,
    "MAX_HFO_DIST": MAX_HFO_DIST,
    "OUT_OF_BOUNDS_X_DIST_MAX": OUT_OF_BOUNDS_X_DIST_MAX,
    "OUT_OF_BOUNDS_Y_DIST_MAX": OUT_OF_BOUNDS_Y_DIST_MAX,
}:
    raise ImportError("hfo2d._accel's feature constants differ from hfo2d.features': rebuild the extension")


#: ``low_level_feature_list(player, ball, kickable_distance, teammates, opponents)`` with the paper era's
#: normalisers, positional arguments only: the extension's kernel itself when it is in use (no Python frame: the
#: envs call it every step), else :func:`low_level_feature_list_python`
paper_feature_list = low_level_feature_list_python if _ACCEL_FEATURES is None else _ACCEL_FEATURES


def low_level_feature_list(
    player: PlayerState,
    ball: BallState,
    kickable_distance: float,
    teammates: list[PlayerState] | tuple[PlayerState, ...] = (),
    opponents: list[PlayerState] | tuple[PlayerState, ...] = (),
    *,
    max_dist: float = MAX_HFO_DIST,
    out_of_bounds_x_max: float = OUT_OF_BOUNDS_X_DIST_MAX,
    out_of_bounds_y_max: float = OUT_OF_BOUNDS_Y_DIST_MAX,
    opponent_control: bool = False,
) -> list[float]:
    """The features as a list of Python floats: :func:`low_level_feature_list_python` (arguments and result),
    computed by the compiled kernel of hfo2d._accel when it is in use (the same floats; see :mod:`hfo2d.accel`).
    ``opponent_control`` takes the Python path."""
    if _ACCEL_FEATURES is None or opponent_control:
        return low_level_feature_list_python(
            player,
            ball,
            kickable_distance,
            teammates,
            opponents,
            max_dist=max_dist,
            out_of_bounds_x_max=out_of_bounds_x_max,
            out_of_bounds_y_max=out_of_bounds_y_max,
            opponent_control=opponent_control,
        )
    return _ACCEL_FEATURES(
        player,
        ball,
        kickable_distance,
        teammates,
        opponents,
        max_dist,
        out_of_bounds_x_max,
        out_of_bounds_y_max,
    )


#: rcssserver's default kickable area (kickable_margin 0.7 + player_size 0.3 + ball_size 0.085), m.
DEFAULT_KICKABLE_AREA = 1.085


def opponent_controls_ball(
    player: PlayerState,
    ball: BallState,
    opponents: Sequence[PlayerState],
    ball_distance: float | None = None,
) -> bool:
    """librcsc's test for an opponent in control of the ball, after which its world model sets the ball's velocity
    to 0 (librcsc world_model.cpp ``updateJustBeforeDecision``, ``check_player_kickable``; ball_object.cpp
    ``setOpponentControlEffect``), whenever the observer itself cannot kick the ball.

    Only the opponent nearest the ball counts (players in a tackle are skipped): it controls the ball when its
    distance to the ball is below ``kickable_area + margin``, where the margin is ``min(0.25, 0.02 * d_ball) +
    min(0.25, 0.02 * d_opponent)`` with ``d_ball`` and ``d_opponent`` the ball's and the opponent's distances
    from the observer (librcsc's allowance for observation error, applied under fullstate too: up to 0.5 m).
    """
    candidates = [other for other in opponents if other.tackle_cycles <= 0]
    if not candidates:
        return False
    nearest = min(candidates, key=lambda other: (other.x - ball.x) ** 2 + (other.y - ball.y) ** 2)
    if ball_distance is None:
        ball_distance = math.hypot(ball.x - player.x, ball.y - player.y)
    margin = min(0.25, 0.02 * ball_distance) + min(
        0.25, 0.02 * math.hypot(nearest.x - player.x, nearest.y - player.y)
    )
    return math.hypot(nearest.x - ball.x, nearest.y - ball.y) < DEFAULT_KICKABLE_AREA + margin


def hfo_feature_list(
    player: PlayerState,
    ball: BallState,
    kickable_distance: float,
    teammates: list[PlayerState] | tuple[PlayerState, ...] = (),
    opponents: list[PlayerState] | tuple[PlayerState, ...] = (),
    last_action_succeeded: bool = False,
    *,
    opponent_control: bool = False,
) -> list[float]:
    """HFO master's low-level vector (fullstate) of the state: layout of :func:`hfo_num_features`.

    The paper-era computation with master's normalisers (``HFO_MASTER_*``), then one uniform number / 100 per
    listed teammate and opponent, in the order of their blocks (nearest first; -1 for an empty slot), then
    ``last_action_succeeded`` as +1 / -1 (HFO agent.cpp records librcsc's doDash / doTurn / doKick result: a kick
    fails when the ball is not kickable, dash and turn fail only when frozen). The observing player's own uniform
    number is not part of the vector. hfo2d's uniform numbers are all positive, so HFO's ``unum > 0`` listing
    test reduces to the paper era's ``x > 0``. ``opponent_control``: as in :func:`low_level_feature_list`.

    Returns:
        ``hfo_num_features(len(teammates), len(opponents))`` Python floats in [-1, 1].
    """
    features = low_level_feature_list(
        player,
        ball,
        kickable_distance,
        teammates,
        opponents,
        max_dist=HFO_MASTER_MAX_DIST,
        out_of_bounds_x_max=HFO_MASTER_OUT_OF_BOUNDS_X_DIST_MAX,
        out_of_bounds_y_max=HFO_MASTER_OUT_OF_BOUNDS_Y_DIST_MAX,
        opponent_control=opponent_control,
    )
    x = player.x
    y = player.y
    for group in (teammates, opponents):
        if len(group) > 1:  # the same stable sort as the blocks, so the numbers follow the blocks' order
            group = sorted(group, key=lambda other: (other.x - x) ** 2 + (other.y - y) ** 2)
        listed = [other.unum / 100.0 for other in group if other.x > 0.0]
        features += listed
        features += [-1.0] * (len(group) - len(listed))
    features.append(1.0 if last_action_succeeded else -1.0)
    return features


# Proximity indices of the basic features: the 11 landmarks and the ball (all over maxHFODist).
_BASIC_PROXIMITIES: tuple[int, ...] = (
    *(FIRST_LANDMARK + 3 * k + 2 for k in range(len(LANDMARKS))),
    BALL_PROXIMITY,
)


def _renormalised_proximity(value: float, old_max: float, new_max: float) -> float:
    """A proximity ``1 - 2 clip(d / old_max, 0, 1)`` re-expressed as ``1 - 2 clip(d / new_max, 0, 1)``."""
    ratio = (1.0 - value) * 0.5 * old_max / new_max
    if ratio <= 0.0:
        return 1.0
    if ratio >= 1.0:
        return -1.0
    return 1.0 - 2.0 * ratio


def paper_from_hfo(features: Sequence[float], num_teammates: int = 0, num_opponents: int = 0) -> list[float]:
    """HFO master's low-level vector converted into the paper-era layout hfo2d uses.

    HFO master (b8b2a1d) differs from the paper-era extractor in its normalisers and in extra entries (see
    :func:`hfo_num_features` for its layout). This re-normalises every proximity (landmarks, ball, listed players)
    from ``HFO_MASTER_MAX_DIST`` (85.908 m) to ``MAX_HFO_DIST`` (62.55 m) and the out-of-bounds features 46/47 from
    57.75 m to 52.5 m and 48/49 from 71.4 m to 68 m, by ``d = (1 - f) / 2 * old_max``,
    ``f' = 1 - 2 min(d / new_max, 1)``, and drops the uniform numbers and the last-action flag. A player slot
    whose uniform-number entry is negative (nobody listed; HFO fills it with zeros) stays zeros. Everything else
    is copied. The inverse is not possible in general: the paper vector clips distances beyond 62.55 m.

    Args:
        features: HFO master's vector, ``hfo_num_features(num_teammates, num_opponents)`` numbers.
        num_teammates: teammate slots of the vector (HFO's ``num_offense - 1`` for an offense agent).
        num_opponents: opponent slots (HFO's ``num_defense``).

    Returns:
        ``num_features(num_teammates, num_opponents)`` Python floats (58 for 1v0, 66 for 1v1).

    Raises:
        ValueError: for a negative slot count or a vector of the wrong length.
    """
    if num_teammates < 0 or num_opponents < 0:
        raise ValueError(
            f"slot counts must be >= 0, got num_teammates={num_teammates}, num_opponents={num_opponents}"
        )
    expected = hfo_num_features(num_teammates, num_opponents)
    if len(features) != expected:
        raise ValueError(
            f"HFO master's vector for {num_teammates} teammate(s) and {num_opponents} opponent(s) has {expected} "
            f"features, got {len(features)}"
        )
    players = num_teammates + num_opponents
    paper_length = num_features(num_teammates, num_opponents)
    out = [float(value) for value in features[:paper_length]]
    for index in _BASIC_PROXIMITIES:
        out[index] = _renormalised_proximity(out[index], HFO_MASTER_MAX_DIST, MAX_HFO_DIST)
    for index, old_max, new_max in (
        (OUT_OF_BOUNDS_LEFT, HFO_MASTER_OUT_OF_BOUNDS_X_DIST_MAX, OUT_OF_BOUNDS_X_DIST_MAX),
        (OUT_OF_BOUNDS_RIGHT, HFO_MASTER_OUT_OF_BOUNDS_X_DIST_MAX, OUT_OF_BOUNDS_X_DIST_MAX),
        (OUT_OF_BOUNDS_TOP, HFO_MASTER_OUT_OF_BOUNDS_Y_DIST_MAX, OUT_OF_BOUNDS_Y_DIST_MAX),
        (OUT_OF_BOUNDS_BOTTOM, HFO_MASTER_OUT_OF_BOUNDS_Y_DIST_MAX, OUT_OF_BOUNDS_Y_DIST_MAX),
    ):
        out[index] = _renormalised_proximity(out[index], old_max, new_max)
    for slot in range(players):
        if float(features[paper_length + slot]) < 0.0:  # uniform number -1: nobody listed, the block is zeros
            continue
        index = NUM_BASIC_FEATURES + FEATURES_PER_PLAYER * slot + PLAYER_PROXIMITY
        out[index] = _renormalised_proximity(out[index], HFO_MASTER_MAX_DIST, MAX_HFO_DIST)
    return out


#: The goalie's uniform number (rcssserver: the goalie is unum 1; HFO's trainer gives it to the first defender).
GOALIE_UNUM = 1


def keeper_view_from_hfo(
    features: Sequence[float], num_teammates: int = 0, num_opponents: int = 0
) -> list[float]:
    """HFO/Keeper-v1's view of an offense agent's state in a team game, from HFO master's vector.

    The paper-era 58 basic features (:func:`paper_from_hfo`), then the 8-feature block of the opponent whose
    uniform-number entry is the goalie's (``GOALIE_UNUM / 100``), wherever HFO listed it; just the 58 when no
    opponent slot holds the goalie. This is what the rewards that read the goalie at features 58-65
    (:data:`hfo2d.reward.GOALIE_READING_REWARDS`) need, since a team layout puts the teammates' blocks first.

    Raises:
        ValueError: as :func:`paper_from_hfo`.
    """
    paper = paper_from_hfo(features, num_teammates, num_opponents)
    unum_start = (
        len(paper) + num_teammates
    )  # master's uniform numbers follow the 8-feature blocks, teammates first
    for slot in range(num_opponents):
        if round(float(features[unum_start + slot]) * 100.0) == GOALIE_UNUM:
            start = NUM_BASIC_FEATURES + FEATURES_PER_PLAYER * (num_teammates + slot)
            return paper[:NUM_BASIC_FEATURES] + paper[start : start + FEATURES_PER_PLAYER]
    return paper[:NUM_BASIC_FEATURES]


_FloatOrArray = TypeVar("_FloatOrArray", float, np.ndarray)


def proximity_distance(proximity: _FloatOrArray) -> _FloatOrArray:
    """Metres encoded by a landmark's proximity ``1 - 2 d / MAX_HFO_DIST`` (the inverse, for d < MAX_HFO_DIST);
    a float or, elementwise, an array."""
    return (1.0 - proximity) * 0.5 * MAX_HFO_DIST


def landmark_position(
    features: Sequence[float], sin_index: int, cos_index: int, proximity_index: int
) -> tuple[float, float]:
    """Body-frame position (x ahead, y to the right; metres) of a landmark encoded as (sin, cos, proximity).

    Inverts the landmark encoding above (proximity with ``dmax = MAX_HFO_DIST``); exact up to the float32 rounding
    of the observation. Used by the scripted striker (hfo2d.heuristic) and the gap reward (hfo2d.reward).
    """
    bearing = math.atan2(float(features[sin_index]), float(features[cos_index]))
    distance = proximity_distance(float(features[proximity_index]))
    return distance * math.cos(bearing), distance * math.sin(bearing)


def kickable_distance(world: World) -> float:
    """Ball-centre distance (m) under which librcsc calls the ball kickable: kickable_area - 0.055 = 1.03."""
    return world.params.kickable_area - KICKABLE_BUFFER


def low_level_features(world: World, player: PlayerState, out: np.ndarray | None = None) -> np.ndarray:
    """HFO's low-level features of ``player`` in ``world`` (paper era, fullstate).

    Every other player of the world takes one 8-feature slot: teammates (same side) first, then opponents, each
    group sorted by distance from ``player``. In HFO's 1v0 that is 58 features, against a goalie 66.

    Args:
        world: the simulated world.
        player: the observing player, one of ``world.players``.
        out: optional float32 array of the right length to fill in place.

    Returns:
        float32 array of shape ``(num_features(T, O),)`` with values in [-1, 1]; ``out`` when given.
    """
    teammates = [other for other in world.players if other is not player and other.side == player.side]
    opponents = [other for other in world.players if other.side != player.side]
    features = low_level_feature_list(player, world.ball, kickable_distance(world), teammates, opponents)
    if out is None:
        return np.array(features, dtype=np.float32)
    if out.shape != (len(features),):
        raise ValueError(f"out has shape {out.shape}, expected ({len(features)},)")
    out[:] = features
    return out


# ---------------------------------------------------------------------------------------------------------------
# HFO's high-level features (LARG/HFO b8b2a1d src/highlevel_feature_extractor.cpp, src/feature_extractor.cpp)
# ---------------------------------------------------------------------------------------------------------------
HIGH_LEVEL_BASIC_FEATURES = 10  # highlevel_feature_extractor.h num_basic_features
HIGH_LEVEL_PER_TEAMMATE = 6  # features_per_teammate
HIGH_LEVEL_PER_OPPONENT = 3  # features_per_opponent
#: HFO's FeatureExtractor::FEAT_INVALID: a slot with nobody, or a distance with no opponent
HIGH_LEVEL_INVALID = -2.0
#: The x range a position is normalised over, 10 % of the half length beyond the HFO half on either side
#: (tolerance_x): the offense's half is [0, 52.5], the defense's, in its own (mirrored) frame, [-52.5, 0].
HIGH_LEVEL_X_TOLERANCE = 0.1 * PITCH_HALF_LENGTH
HIGH_LEVEL_Y_TOLERANCE = 0.1 * PITCH_HALF_WIDTH
#: The highest uniform number, the bound of the raw unum entries (HFO writes them unnormalised).
MAX_UNUM = 11.0


def high_level_num_features(num_teammates: int = 0, num_opponents: int = 0) -> int:
    """Length of HFO's high-level vector: ``10 + 6 * teammates + 3 * opponents + 2`` (last action, stamina)."""
    return (
        HIGH_LEVEL_BASIC_FEATURES
        + HIGH_LEVEL_PER_TEAMMATE * num_teammates
        + HIGH_LEVEL_PER_OPPONENT * num_opponents
        + 2
    )


def high_level_bounds(num_teammates: int = 0, num_opponents: int = 0) -> tuple[list[float], list[float]]:
    """Per-feature (low, high) of the high-level vector: [-1, 1] for the normalised features, -2 (HFO's
    FEAT_INVALID) as the low of every entry that can be invalid, ``MAX_UNUM`` as the high of the uniform numbers."""
    size = high_level_num_features(num_teammates, num_opponents)
    low = [-1.0] * size
    high = [1.0] * size
    invalid = [9] + list(range(HIGH_LEVEL_BASIC_FEATURES, size - 2))  # closest opponent and every player slot
    for index in invalid:
        low[index] = HIGH_LEVEL_INVALID
    unums = HIGH_LEVEL_BASIC_FEATURES + 3 * num_teammates
    for slot in range(num_teammates):
        high[unums + 3 * slot + 2] = MAX_UNUM
    for slot in range(num_opponents):
        high[unums + 3 * num_teammates + 3 * slot + 2] = MAX_UNUM
    return low, high


def _hl_normalise(value: float, low: float, high: float) -> float:
    """HFO's FeatureExtractor::normalize: clip to [low, high], then map linearly onto [-1, 1]."""
    value = min(max(value, low), high)
    return (value - low) / (high - low) * 2.0 - 1.0


def _open_angle(
    x: float,
    y: float,
    angle_top: float,
    angle_bottom: float,
    max_dist: float,
    opponents: Sequence[PlayerState],
) -> float:
    """The widest angle (rad) of [angle_bottom, angle_top] seen from (x, y) that no opponent closer than
    ``max_dist`` blocks; each blocks its bearing +- atan2(DEFAULT_KICKABLE_AREA / 2, distance) (HFO uses
    ServerParam::defaultKickableArea as a player's width).

    HFO's calcLargestOpenAngle / splitAngles: an interval an opponent touches is split into the parts below and
    above the opponent's span (either may come out empty or negative), without wrapping angles round +-pi.
    """
    intervals = [(angle_bottom, angle_top)]
    for other in opponents:
        dx = other.x - x
        dy = other.y - y
        dist = math.hypot(dx, dy)
        bearing = math.atan2(dy, dx) if dist > 0.0 else 0.0
        half_width = math.atan2(DEFAULT_KICKABLE_AREA * 0.5, dist)
        lower = bearing - half_width
        upper = bearing + half_width
        if dist < max_dist:
            split = []
            for first, second in intervals:
                if upper < first or lower > second:
                    split.append((first, second))
                else:
                    split.append((first, lower))
                    split.append((upper, second))
            intervals = split
    return max([0.0] + [second - first for first, second in intervals])


def _goal_open_angle(x: float, y: float, opponents: Sequence[PlayerState]) -> float:
    """HFO's calcLargestGoalAngle: the widest open angle (rad) toward the goal mouth at x = +52.5 (its posts at
    y = +-7.01, whatever the side: HFO does not mirror it for the defense)."""
    top = math.atan2(GOAL_HALF_WIDTH - y, PITCH_HALF_LENGTH - x)
    bottom = math.atan2(-GOAL_HALF_WIDTH - y, PITCH_HALF_LENGTH - x)
    return _open_angle(x, y, top, bottom, 99999.0, opponents)


def _closest_distance(x: float, y: float, opponents: Sequence[PlayerState]) -> float:
    """HFO's calcClosestOpp: distance (m) from (x, y) to the nearest opponent (float max when there is none)."""
    return min((math.hypot(other.x - x, other.y - y) for other in opponents), default=3.4028234663852886e38)


def norm_deg(angle: float) -> float:
    """An angle folded into [-180, 180] as librcsc's AngleDeg::normalize_angle does (180 stays 180); agent2d's port
    (hfo2d.agent2d.common) uses it too."""
    if angle < -360.0 or angle > 360.0:
        angle = math.fmod(angle, 360.0)
    if angle < -180.0:
        angle += 360.0
    if angle > 180.0:
        angle -= 360.0
    return angle


def mirrored_state(state: PlayerState | BallState) -> PlayerState | BallState:
    """``state`` as a right-side (defense) player's world model sees it: librcsc turns the field round so that its
    own team attacks +x (x, y and the velocity negated, the body angle plus 180 degrees, folded as librcsc's
    FullstateSensor::reverse does: a body of 0 becomes 180)."""
    from dataclasses import replace

    changes: dict[str, float] = {"x": -state.x, "y": -state.y, "vx": -state.vx, "vy": -state.vy}
    if hasattr(state, "body_deg"):
        changes["body_deg"] = norm_deg(state.body_deg + 180.0)
    return replace(state, **changes)  # type: ignore[arg-type,return-value]


def high_level_feature_list(
    player: PlayerState,
    ball: BallState,
    kickable_distance: float,
    teammates: Sequence[PlayerState] = (),
    opponents: Sequence[PlayerState] = (),
    last_action_succeeded: bool = False,
    *,
    playing_offense: bool = True,
) -> list[float]:
    """HFO's high-level feature vector (fullstate) of the state, as LARG/HFO b8b2a1d computes it.

    Layout (``high_level_num_features(T, O)`` entries; positions and angles in the observer's world-model frame,
    which for the defense is the mirrored field, see :func:`mirrored_state`):

    * 0, 1: own x over [-5.25, 57.75] (offense) or [-57.75, 5.25] (defense), own y over [-37.4, 37.4];
    * 2: global body angle over [-pi, pi];
    * 3, 4: ball x and y as above; 5: kickable (+1 / -1);
    * 6, 7: distance to the goal centre ((52.5, 0) for the offense, (-52.5, 0) for the defense) over [0, maxR]
      (maxR = 85.91 m, :data:`HFO_MASTER_MAX_DIST`), and its global direction over [-pi, pi];
    * 8: the widest open angle toward the goal mouth at x = 52.5, over [0, pi];
    * 9: distance to the closest opponent over [0, maxR] (-2 without opponents);
    * per teammate, nearest first (every one with a known position and a positive uniform number, wherever it
      stands): its open angle to the goal (T entries), its distance to its closest opponent (T), the widest open
      pass angle to it, within +-45 degrees of its bearing, from opponents nearer than it (T), then its x, y and
      raw uniform number (3T);
    * per opponent, nearest first: x, y and raw uniform number (3O);
    * the last action's status (+1 / -1) and the stamina over [0, 8000].

    Empty slots are -2 (HFO's FEAT_INVALID). Angles come from ``atan2``, as HFO's ``Vector2D::th()``.

    Args:
        player: the observing player, in the server's (left-side) frame.
        ball: the ball.
        kickable_distance: the ball-centre distance under which the kickable flag is +1 (librcsc: 1.03 m).
        teammates: the observer's teammates (positive uniform numbers).
        opponents: the players of the other side.
        last_action_succeeded: HFO's status of the agent's last action.
        playing_offense: False for a defender: every state is mirrored first, and the x ranges are the defense's.
    """
    if not playing_offense:
        player = mirrored_state(player)  # type: ignore[assignment]
        ball = mirrored_state(ball)  # type: ignore[assignment]
        teammates = [mirrored_state(other) for other in teammates]  # type: ignore[misc]
        opponents = [mirrored_state(other) for other in opponents]  # type: ignore[misc]
    x_low, x_high = (
        (-HIGH_LEVEL_X_TOLERANCE, PITCH_HALF_LENGTH + HIGH_LEVEL_X_TOLERANCE)
        if playing_offense
        else (-PITCH_HALF_LENGTH - HIGH_LEVEL_X_TOLERANCE, HIGH_LEVEL_X_TOLERANCE)
    )
    y_low, y_high = -PITCH_HALF_WIDTH - HIGH_LEVEL_Y_TOLERANCE, PITCH_HALF_WIDTH + HIGH_LEVEL_Y_TOLERANCE
    max_r = HFO_MASTER_MAX_DIST
    x, y = player.x, player.y
    body = math.radians(norm_deg(player.body_deg))  # librcsc's AngleDeg, in [-180, 180]
    goal_x = PITCH_HALF_LENGTH if playing_offense else -PITCH_HALF_LENGTH
    goal_dx, goal_dy = goal_x - x, -y
    features = [
        _hl_normalise(x, x_low, x_high),
        _hl_normalise(y, y_low, y_high),
        _hl_normalise(body, -math.pi, math.pi),
        _hl_normalise(ball.x, x_low, x_high),
        _hl_normalise(ball.y, y_low, y_high),
        1.0 if math.hypot(ball.x - x, ball.y - y) <= kickable_distance else -1.0,
        _hl_normalise(math.hypot(goal_dx, goal_dy), 0.0, max_r),
        _hl_normalise(math.atan2(goal_dy, goal_dx), -math.pi, math.pi),
        _hl_normalise(_goal_open_angle(x, y, opponents), 0.0, math.pi),
        _hl_normalise(_closest_distance(x, y, opponents), 0.0, max_r) if opponents else HIGH_LEVEL_INVALID,
    ]
    listed = sorted(
        (other for other in teammates if other.unum > 0), key=lambda o: (o.x - x) ** 2 + (o.y - y) ** 2
    )
    missing = len(teammates) - len(listed)
    features += [_hl_normalise(_goal_open_angle(o.x, o.y, opponents), 0.0, math.pi) for o in listed]
    features += [HIGH_LEVEL_INVALID] * missing
    if opponents:
        features += [_hl_normalise(_closest_distance(o.x, o.y, opponents), 0.0, max_r) for o in listed]
        features += [HIGH_LEVEL_INVALID] * missing
    else:
        features += [HIGH_LEVEL_INVALID] * len(teammates)
    for other in listed:
        bearing = math.atan2(other.y - y, other.x - x)
        dist = math.hypot(other.x - x, other.y - y)
        pass_angle = _open_angle(x, y, bearing + math.pi / 4, bearing - math.pi / 4, dist, opponents)
        features.append(_hl_normalise(pass_angle, 0.0, math.pi))
    features += [HIGH_LEVEL_INVALID] * missing
    for other in listed:
        features += (
            _hl_normalise(other.x, x_low, x_high),
            _hl_normalise(other.y, y_low, y_high),
            float(other.unum),
        )
    features += [HIGH_LEVEL_INVALID] * (3 * missing)
    listed_opponents = sorted(
        (other for other in opponents if other.unum > 0), key=lambda o: (o.x - x) ** 2 + (o.y - y) ** 2
    )
    for other in listed_opponents:
        features += (
            _hl_normalise(other.x, x_low, x_high),
            _hl_normalise(other.y, y_low, y_high),
            float(other.unum),
        )
    features += [HIGH_LEVEL_INVALID] * (3 * (len(opponents) - len(listed_opponents)))
    features.append(1.0 if last_action_succeeded else -1.0)
    features.append(_hl_normalise(player.stamina, 0.0, STAMINA_MAX))
    return features
