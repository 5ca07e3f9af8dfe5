"""HFO's left-right symmetry: the mirror image (y -> -y) of a feature vector and of a flat action.

Half Field Offense's dynamics are symmetric about the pitch's long axis (y = 0): the field, the goal, the keeper's
decision rules (they use |y| and the ball's side) and the server's noise (uniform in direction) all look the same
in a mirror. Its start distribution is not: the ball's y is drawn symmetrically, but the agent's y offset from the
ball is 10.5 m * (U(0, 1) + o) with o in {-2, -1, 1, 2} (HFO's resetField, hfo_reference §5.3), i.e. in [-21, 0)
or [10.5, 31.5) m before clamping to the pitch, and the mirror image of an offset drawn with o = -1 or o = 2 (half
the draws) is one HFO never draws. A policy's mirror twin (the policy played in the mirrored state, its action
mirrored back) therefore meets, at the start, states its training never saw. Mirroring the world maps

* every angle θ to −θ (global angles and bearings relative to the body alike), so the sine of each (sin, cos)
  pair changes sign and the cosine stays;
* the top landmarks onto the bottom ones: goal posts, penalty-box corners, field corners, and the top / bottom
  out-of-bounds proximities swap places;
* flags, proximities, speeds and stamina onto themselves;
* a flat action's three directions (dash, turn and kick, degrees relative to the body) d onto −d, i.e. the
  [0, 1] parameter u onto 1 − u; preferences and powers stay.

So a transition (s, a, r, s') of the environment has a mirror image (m(s), m(a), r, m(s')) with the same reward
and episode end (HFO's rewards depend on distances only), which an off-policy learner can train on as well.
``tests/test_symmetry.py`` checks this against the simulator with noise off: a mirrored start played with
mirrored actions gives the mirrored features, the same rewards and the same end, against the scripted keeper too.

Features follow :mod:`hfo2d.features` (58 basic features, then 8 per other player; hfo_reference §2.2).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from hfo2d.action_layout import HFO_FLAT_ACTION_LAYOUT
from hfo2d.features import (
    BALL_ANGLE_SIN,
    BALL_VEL_ANGLE_SIN,
    CENTER_FIELD_SIN,
    CORNER_BOTTOM_LEFT_SIN,
    CORNER_BOTTOM_RIGHT_SIN,
    CORNER_TOP_LEFT_SIN,
    CORNER_TOP_RIGHT_SIN,
    FEATURES_PER_PLAYER,
    GOAL_CENTER_SIN,
    GOAL_POST_BOTTOM_SIN,
    GOAL_POST_TOP_SIN,
    NUM_BASIC_FEATURES,
    OUT_OF_BOUNDS_BOTTOM,
    OUT_OF_BOUNDS_TOP,
    PENALTY_BOX_BOTTOM_SIN,
    PENALTY_BOX_CENTER_SIN,
    PENALTY_BOX_TOP_SIN,
    PLAYER_ANGLE_SIN,
    PLAYER_BODY_SIN,
    PLAYER_VEL_ANGLE_SIN,
    SELF_BODY_SIN,
    SELF_VEL_ANGLE_SIN,
)
from hfo2d.protocol import (
    OFFENSE_OFFSETS,
    OFFENSE_SPREAD,
    OFFENSE_Y_RANGE,
)

__all__ = [
    "feature_mirror",
    "flat_action_mirror_signs",
    "mirror_features",
    "mirror_flat_action",
    "start_offset_is_drawn",
    "start_y_is_clamped",
]

# Landmarks are (sin, cos, proximity) triples starting at their sine: pairs of triples that swap in a mirror.
_SWAPPED_LANDMARKS = (
    (GOAL_POST_TOP_SIN, GOAL_POST_BOTTOM_SIN),
    (PENALTY_BOX_TOP_SIN, PENALTY_BOX_BOTTOM_SIN),
    (CORNER_TOP_LEFT_SIN, CORNER_BOTTOM_LEFT_SIN),
    (CORNER_TOP_RIGHT_SIN, CORNER_BOTTOM_RIGHT_SIN),
)
# Sines of angles whose landmark (or meaning) stays in place; the swapped landmarks' sines are added below.
_BASIC_SINES = (
    SELF_VEL_ANGLE_SIN,
    SELF_BODY_SIN,
    GOAL_CENTER_SIN,
    PENALTY_BOX_CENTER_SIN,
    CENTER_FIELD_SIN,
    BALL_ANGLE_SIN,
    BALL_VEL_ANGLE_SIN,
)
_PLAYER_SINES = (PLAYER_ANGLE_SIN, PLAYER_BODY_SIN, PLAYER_VEL_ANGLE_SIN)


def feature_mirror(n_features: int) -> tuple[list[int], list[float]]:
    """``(source, sign)`` such that ``mirrored[i] = sign[i] * features[source[i]]`` for ``n_features`` features.

    ``n_features`` must be 58 + 8 * (number of other players); ValueError otherwise.
    """
    extra = n_features - NUM_BASIC_FEATURES
    if isinstance(n_features, bool) or extra < 0 or extra % FEATURES_PER_PLAYER:
        raise ValueError(
            f"an HFO feature vector has {NUM_BASIC_FEATURES} + {FEATURES_PER_PLAYER} * players entries, "
            f"got {n_features}"
        )
    source = list(range(n_features))
    sign = [1.0] * n_features
    for top, bottom in _SWAPPED_LANDMARKS:
        for offset in range(3):
            source[top + offset], source[bottom + offset] = bottom + offset, top + offset
        sign[top] = sign[bottom] = -1.0
    source[OUT_OF_BOUNDS_TOP], source[OUT_OF_BOUNDS_BOTTOM] = OUT_OF_BOUNDS_BOTTOM, OUT_OF_BOUNDS_TOP
    for index in _BASIC_SINES:
        sign[index] = -1.0
    for block in range(NUM_BASIC_FEATURES, n_features, FEATURES_PER_PLAYER):
        for offset in _PLAYER_SINES:
            sign[block + offset] = -1.0
    return source, sign


def mirror_features(features: Sequence[float] | np.ndarray) -> np.ndarray:
    """The mirror image of one feature vector ``(n,)`` or a batch ``(..., n)`` (same dtype as a numpy input)."""
    array = np.asarray(features)
    source, sign = feature_mirror(array.shape[-1])
    return array[..., source] * np.asarray(sign, dtype=array.dtype if array.dtype.kind == "f" else np.float64)


def flat_action_mirror_signs() -> list[float]:
    """Per-entry signs that mirror a flat action in a scale centred on 0 (SB3's replay-buffer scale [-1, 1]): the
    directions of :data:`~hfo2d.action_layout.HFO_FLAT_ACTION_LAYOUT` negated."""
    layout = HFO_FLAT_ACTION_LAYOUT
    return [-1.0 if index in layout.direction_indices else 1.0 for index in range(layout.size)]


def mirror_flat_action(action: Sequence[float] | np.ndarray) -> np.ndarray:
    """The mirror image of a flat action in the env's scale [0, 1] (``(8,)`` or ``(..., 8)``): u -> 1 - u for
    the three directions, everything else unchanged."""
    array = np.array(action)  # a copy
    if array.dtype.kind != "f":
        array = array.astype(np.float64)
    layout = HFO_FLAT_ACTION_LAYOUT
    if array.shape[-1:] != (layout.size,):
        raise ValueError(f"a flat HFO action has {layout.size} entries, got shape {array.shape}")
    directions = list(layout.direction_indices)
    array[..., directions] = 1.0 - array[..., directions]
    return array


def start_offset_is_drawn(offset_y: float) -> bool:
    """Whether HFO's start draws an agent-minus-ball y offset of ``offset_y`` m (before clamping to the pitch):
    ``OFFENSE_SPREAD * (U(0, 1) + o)`` for one of the offsets ``o`` of ``OFFENSE_OFFSETS``. The mirror image of a
    start is drawn when ``start_offset_is_drawn(-offset_y)``; for half of HFO's starts it is not (module doc)."""
    units = offset_y / OFFENSE_SPREAD
    return any(o <= units < o + 1.0 for o in {o_y for _, o_y in OFFENSE_OFFSETS})


def start_y_is_clamped(agent_y: float) -> bool:
    """Whether an agent's start y lies on the clamp limit of HFO's start (its offset then says nothing)."""
    return abs(agent_y) >= OFFENSE_Y_RANGE[1] - 1e-6
