"""HFO's domain adapter: the facts of Half Field Offense the algorithms are given, read from hfo2d in one place.

The algorithms and policies import no hfo2d (:mod:`sb3_hfo.common.domain` says why and what an adapter holds).
:data:`HFO_DOMAIN` is what ``domain="hfo"`` names: HFO's "able to kick" feature, the paper's field-half rule on the
agent's x-position feature, HFO's mirror image (:mod:`hfo2d.symmetry`) and the landmark bearings the critic's
direction features can be relative to. The constants below name HFO's flat action for the modules that work on HFO
only (demonstrations, the toy env).
"""

from __future__ import annotations

from hfo2d.action_layout import DASH, HFO_FLAT_ACTION_LAYOUT, KICK, hfo_flat_action_space
from hfo2d.features import (
    BALL_ANGLE_COS,
    BALL_ANGLE_SIN,
    BALL_PROXIMITY,
    FEATURES_PER_PLAYER,
    GOAL_CENTER_COS,
    GOAL_CENTER_SIN,
    GOAL_POST_BOTTOM_COS,
    GOAL_POST_BOTTOM_SIN,
    GOAL_POST_TOP_COS,
    GOAL_POST_TOP_SIN,
    GOALIE_ANGLE_COS,
    GOALIE_ANGLE_SIN,
    KICKABLE,
    MAX_HFO_DIST,
    NUM_BASIC_FEATURES,
    PLAYER_ANGLE_COS,
    PLAYER_ANGLE_SIN,
    PLAYER_PROXIMITY,
    SELF_X,
    num_features,
)
from hfo2d.symmetry import feature_mirror, flat_action_mirror_signs
from sb3_hfo.common.domain import DomainAdapter
from sb3_hfo.common.routers import BallPlayerRouter, field_half_router

__all__ = [
    "DASH",
    "HFO_ACTION_PARAMETER_SIZES",
    "HFO_DOMAIN",
    "HFO_FLAT_ACTION_DIM",
    "HFO_FLAT_ACTION_LAYOUT",
    "HFO_KICK_ACTION",
    "HFO_N_DISCRETE_ACTIONS",
    "KICK",
    "KICK_REFERENCE_BEARINGS",
    "hfo_ball_player_router",
    "hfo_flat_action_space",
]

# HFO's flat action as hfo2d declares it: the parameter count of DASH, TURN and KICK, their number, the action's
# size and KICK's index.
HFO_ACTION_PARAMETER_SIZES = HFO_FLAT_ACTION_LAYOUT.parameter_sizes
HFO_N_DISCRETE_ACTIONS = HFO_FLAT_ACTION_LAYOUT.n_discrete
HFO_FLAT_ACTION_DIM = HFO_FLAT_ACTION_LAYOUT.size
HFO_KICK_ACTION = HFO_FLAT_ACTION_LAYOUT.ball_action

#: Landmarks the kick direction can be encoded relative to: name -> (sin, cos) columns of the landmark's bearing in
#: HFO's low-level features (the goalie's exists only on goalie tasks).
KICK_REFERENCE_BEARINGS: dict[str, tuple[int, int]] = {
    "goalie": (GOALIE_ANGLE_SIN, GOALIE_ANGLE_COS),
    "goal_center": (GOAL_CENTER_SIN, GOAL_CENTER_COS),
    "goal_post_top": (GOAL_POST_TOP_SIN, GOAL_POST_TOP_COS),
    "goal_post_bottom": (GOAL_POST_BOTTOM_SIN, GOAL_POST_BOTTOM_COS),
}

#: HFO's adapter (``domain="hfo"``).
#:
#: * kickable: HFO's LowLevelFeatureExtractor's "able to kick" feature, +1 / -1;
#: * field half: the self-x feature ``1 - 2 * min(x / 52.5, 1)`` (the paper-era out-of-bounds normaliser) is
#:   positive exactly when ``x < 26.25`` m, the half of the attacked half-field away from the goal (skill 0,
#:   "approach and dribble"); the seed paper's Experiments split the field there;
#: * the mirror: y -> -y (hfo2d.symmetry), on the feature vector and on the flat action's [-1, 1] scale.
HFO_DOMAIN = DomainAdapter(
    name="hfo",
    kickable_column=KICKABLE,
    field_half_column=SELF_X,
    field_half_threshold=0.0,
    bearings=tuple(
        (name, sin_column, cos_column) for name, (sin_column, cos_column) in KICK_REFERENCE_BEARINGS.items()
    ),
    observation_mirror=feature_mirror,
    action_mirror_signs=tuple(flat_action_mirror_signs()),
    mirror_parameter_sizes=HFO_FLAT_ACTION_LAYOUT.parameter_sizes,
    flat_action_space=hfo_flat_action_space(),
)


def hfo_ball_player_router(teammates: int, opponents: int = 1) -> BallPlayerRouter:
    """The role split of ``teammates + 1`` strikers on HFO's paper-era features (hfo2d's layout: 58 basic features,
    then one 8-feature block per teammate, then the opponents'): a striker that judges itself nearest the ball plays
    the paper's two field-half skills (0: approach and dribble, 1: shoot), the others skill 2 (support). The ball's
    landmark is features 51-53 and each teammate's the first three of its block (bearing sin, cos, proximity);
    proximities are ``1 - 2 d / MAX_HFO_DIST`` (hfo2d.features), so the distance scale is ``MAX_HFO_DIST / 2``.
    The router checks the observation's size, ``58 + 8 * (teammates + opponents)``.

    :raises ValueError: ``teammates`` < 1 or ``opponents`` < 0.
    """
    if isinstance(teammates, bool) or not isinstance(teammates, int) or teammates < 1:
        raise ValueError(f"teammates must be an integer >= 1 (the router splits a team), got {teammates!r}")
    if isinstance(opponents, bool) or not isinstance(opponents, int) or opponents < 0:
        raise ValueError(f"opponents must be an integer >= 0, got {opponents!r}")
    blocks = [NUM_BASIC_FEATURES + FEATURES_PER_PLAYER * index for index in range(teammates)]
    return BallPlayerRouter(
        field_half_router(HFO_DOMAIN),
        (BALL_ANGLE_SIN, BALL_ANGLE_COS, BALL_PROXIMITY),
        tuple((b + PLAYER_ANGLE_SIN, b + PLAYER_ANGLE_COS, b + PLAYER_PROXIMITY) for b in blocks),
        MAX_HFO_DIST / 2.0,
        n_features=num_features(teammates, opponents),
    )
