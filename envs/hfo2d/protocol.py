"""HFO's protocol as hfo2d plays it: statuses, actions and their bounds, episode rules, start state, sides.

The one place these numbers live. :mod:`hfo2d.hfo_env`, :mod:`hfo2d.referee`, :mod:`hfo2d.real` and
:mod:`hfo2d.symmetry` read them here (``hfo2d.hfo_env`` re-exports the names it always had). This module needs only
the pitch geometry of :mod:`hfo2d.physics` and the action layout of :mod:`hfo2d.action_layout`, so importing it
builds no env.

Sources (facts and numbers, no code): HFO (``mhauskn/HFO``: ``bin/HFO``, ``src/hfo.hpp``), its rcssserver fork
(``referee.cpp`` ``HFORef``, ``serverparam.cpp``), gym-soccer and DQNHFO, as summarised in hfo_reference §1, §3.3,
§5.
"""

from __future__ import annotations

from hfo2d.action_layout import ACTION_NAMES, DASH, KICK, TURN
from hfo2d.physics import PITCH_HALF_LENGTH, PITCH_HALF_WIDTH

__all__ = [
    "ACTION_NAMES",
    "AGENT2D_FIRST_BODY_DEGS",
    "AGENT2D_FIRST_OBSERVATION_DELAY",
    "AGENT_SIDE",
    "AGENT_UNUM",
    "BALL_X_RANGE",
    "BALL_Y_RANGE",
    "CAPTURED_BY_DEFENSE",
    "DASH",
    "DEFAULT_FRAMES_PER_TRIAL",
    "DEFAULT_UNTOUCHED_TIME",
    "DEFENSE_SIDE",
    "DIRECTION_MAX",
    "DIRECTION_MIN",
    "GOAL",
    "GOAL_LINE_X",
    "GOAL_MOUTH_HALF_WIDTH",
    "IN_GAME",
    "KEEPER_SIDE",
    "KEEPER_START",
    "KEEPER_START_BODY_DEG",
    "KEEPER_UNUM",
    "KICK",
    "OFFENSE_OFFSETS",
    "OFFENSE_SIDE",
    "OFFENSE_SPREAD",
    "OFFENSE_X_RANGE",
    "OFFENSE_Y_RANGE",
    "OUT_OF_BOUNDS",
    "OUT_OF_TIME",
    "PITCH_MARGIN",
    "PLACEMENT_MAX_X",
    "PLACEMENT_MAX_Y",
    "POWER_MAX",
    "POWER_MIN",
    "STATUSES",
    "TURN",
    "TURNOVER_TIME",
]

# --- statuses: HFO's hfo::Status names (src/common.hpp), also the messages of rcssserver's HFORef -----------------
IN_GAME = "IN_GAME"
GOAL = "GOAL"
CAPTURED_BY_DEFENSE = "CAPTURED_BY_DEFENSE"
OUT_OF_BOUNDS = "OUT_OF_BOUNDS"
OUT_OF_TIME = "OUT_OF_TIME"
#: The statuses of an hfo2d episode, in HFO's code order (SERVER_DOWN, HFO's sixth, is real HFO's only).
STATUSES: tuple[str, ...] = (IN_GAME, GOAL, CAPTURED_BY_DEFENSE, OUT_OF_BOUNDS, OUT_OF_TIME)

# --- actions (DASH, TURN, KICK and their names: hfo2d.action_layout) and their bounds --------------------------
POWER_MIN, POWER_MAX = 0.0, 100.0  # gym-soccer / paper dash and kick power range (hfo_reference §3.3)
DIRECTION_MIN, DIRECTION_MAX = -180.0, 180.0  # degrees relative to the body

# --- episode rules ---------------------------------------------------------------------------------------------
DEFAULT_FRAMES_PER_TRIAL = 500  # gym-soccer and DQNHFO (hfo_reference §5.2)
DEFAULT_UNTOUCHED_TIME = 100  # HFO default (bin/HFO --untouched-time)
TURNOVER_TIME = 2  # cycles a defender must hold the ball before CAPTURED_BY_DEFENSE (referee.cpp HFORef)
GOAL_LINE_X = 52.585  # pitch_half_length + ball_size: the ball's centre must cross it (rcssserver referee)
GOAL_MOUTH_HALF_WIDTH = 7.07  # goal_width / 2 + goal post radius (hfo_reference §1)

# --- sides and uniform numbers -----------------------------------------------------------------------------------
OFFENSE_SIDE, DEFENSE_SIDE = "l", "r"  # HFO's offense plays on the left and attacks x = +52.5
AGENT_SIDE, AGENT_UNUM = OFFENSE_SIDE, 11  # HFO's first offense agent
KEEPER_SIDE, KEEPER_UNUM = DEFENSE_SIDE, 1  # HFO's first defender is the goalie, unum 1

# --- starting state (HFO resetField with bin/HFO defaults, hfo_reference §5.3) -------------------------------------
# (written out: 0.8 * 34 is 27.200000000000003 in floating point)
BALL_X_RANGE = (0.0, 10.5)  # m: bin/HFO ball_x_min / max 0 / 0.2 of 52.5
BALL_Y_RANGE = (-27.2, 27.2)  # m: ball_y_min / max -0.8 / 0.8 of 34
OFFENSE_SPREAD = 10.5  # m per unit of offset: 0.2 * 52.5
OFFENSE_OFFSETS: tuple[tuple[float, float], ...] = (
    (-1.0, -1.0),
    (-1.0, 1.0),
    (1.0, 1.0),
    (1.0, -1.0),
    (0.0, 2.0),
    (0.0, -2.0),
    (-2.0, -2.0),
    (-2.0, 2.0),
    (2.0, 2.0),
    (2.0, -2.0),
)
OFFENSE_X_RANGE = (-0.1, PITCH_HALF_LENGTH)
OFFENSE_Y_RANGE = BALL_Y_RANGE
KEEPER_START = (PITCH_HALF_LENGTH, 0.0)
KEEPER_START_BODY_DEG = -180.0  # facing the field
# rcssserver's initial body angle is 0 (facing the goalie's own goal); agent2d's before-kick-off scan turns it by
# 180 degrees every few cycles, so real HFO's first episode starts facing either way (agent2d goalie spec §2.5).
AGENT2D_FIRST_BODY_DEGS = (0.0, -180.0)
# Cycles between the trainer's placement and the agent's first observation in real HFO (hfo2d.real, measured).
AGENT2D_FIRST_OBSERVATION_DELAY = 2

#: Hand placements (reset options) must lie on the pitch or within this margin of it (m): rcssserver
#: serverparam.cpp PITCH_MARGIN 5.0 (stadium.cpp, placePlayersInField, keeps players within it).
PITCH_MARGIN = 5.0
PLACEMENT_MAX_X = PITCH_HALF_LENGTH + PITCH_MARGIN
PLACEMENT_MAX_Y = PITCH_HALF_WIDTH + PITCH_MARGIN

if (ACTION_NAMES[DASH], ACTION_NAMES[TURN], ACTION_NAMES[KICK]) != ("DASH", "TURN", "KICK"):
    raise ImportError("hfo2d.action_layout's DASH / TURN / KICK no longer name HFO's actions")
