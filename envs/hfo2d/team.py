"""HFO's team game in hfo2d: ``offense_agents`` learning strikers against ``defense_agents`` learning defenders and
``defense_npcs`` scripted defenders, as bin/HFO's flags of the same names set them.

:class:`TeamGame` is the game itself (every agent acts each cycle; no RL interface of its own);
:class:`HalfFieldOffenseEnv` (``gym.make("HFO/HalfFieldOffense-v0", ...)``) makes one of its agents a Gymnasium
env, :func:`hfo2d.parallel_env` all of them a PettingZoo ParallelEnv (:mod:`hfo2d.team_parallel`), and
``sb3_hfo.multi_agent`` all the agents of one side an SB3 VecEnv for parameter-shared training.

HFO's rules, with their sources (LARG/HFO b8b2a1d ``bin/HFO``, ``bin/Trainer.py``, ``bin/Teams.py``; rcssserver's
HFO fork ``src/referee.cpp`` ``HFORef``; librcsc ``rcsc/player/*``):

* Team sizes: bin/HFO ``parseArgs`` allows 0-10 offense agents / NPCs and 0-11 defense agents / NPCs, with 1-10
  offense players and 0-11 defense players in all. agent2d's offense (``--offense-npcs``) is not ported: in its
  places hfo2d can put its own scripted strikers (``scripted_strikers``, :mod:`hfo2d.strikers`), which take the
  offense unums after the agents' as HFO's offense NPCs do.
* Uniform numbers (Trainer.py ``getTeams`` and ``run``; Teams.py ``Agent2d``): the offense's players are the first
  ``n`` of ``11, 7, 8, 9, 10, 6, 3, 2, 4, 5``, its agents the first ``offense_agents`` of them, sorted (agent ``i``
  gets the ``i``-th smallest). The defense's players are the first ``m`` of ``1, 2, 3, 4, 5, 6, 7, 8, 11, 9, 10``,
  sorted; its agents take the *largest* ``defense_agents`` of them, or the smallest with ``agent_play_goalie``
  (bin/HFO ``--agent-play-goalie``), and the NPCs the rest. Unum 1 is the goalie (Teams.py launches NPC 1 with
  ``-g``; Trainer.launch_agent's ``play_goalie=agent_ext_num==1``): an NPC goalie is agent2d's goalie
  (:class:`hfo2d.agent2d.goalie.Agent2dGoalie`), every other NPC agent2d's field defender
  (``hfo2d.agent2d.defender.Agent2dDefender``), and a defense agent with unum 1 plays goalie (it may CATCH). So
  without ``agent_play_goalie`` the goalie is an agent only when there are no defense NPCs.
* Server order (who the referee and the physics walk first): Trainer.run connects unums 1..11 of the offense, then
  of the defense, so the offense comes first, each side by increasing unum.
* Start positions (referee.cpp ``HFORef::resetField``): the ball at rest at x ~ U(0, 10.5), y ~ U(-27.2, 27.2);
  HFO's ten offsets shuffled (``std::random_shuffle``), and the ``k``-th offense player (server order) at
  ``ball + 10.5 (U(0, 1) + offset_k)`` per axis, x clamped to [-0.1, 52.5] and y to [-27.2, 27.2]; the goalie at
  (52.5, 0); every other defender at x ~ U(42, 52.5), y ~ U(-27.2, 27.2). The draws are made in that order (the
  ball, the shuffle, then player by player in server order). Body angles are not placed by HFO (they carry over):
  hfo2d draws each agent's from U(-180, 180) every episode (as ``HFOEnv`` does for its agent) and an NPC keeps its
  own (``DefenseNPC.start_body_deg`` for its first episode or after ``reset(seed=...)``).
* Referee: :class:`hfo2d.referee.Referee` with rcssserver's rules over every player (GOAL; OUT_OF_BOUNDS;
  CAPTURED_BY_DEFENSE when any defender is the last player within kickable_area of the ball for 2 cycles, or at
  once when it is the goalie, unum 1; OUT_OF_TIME after ``untouched_time`` untouched cycles or ``frames_per_trial``
  cycles, the latter a truncation), and real HFO's timing as in ``HFO/Keeper-v1``: one wait cycle between episodes
  (NPCs act, agents do not), the agents' first observation 2 cycles after the placement.
* Collisions between all players and the ball: :class:`hfo2d.physics.World`.

Agents' actions (HFO ``src/common.hpp``, ``src/agent.cpp``; librcsc ``PlayerAgent::doDash / doTurn / doKick /
doTackle / doCatch``): an offense agent plays the paper's DASH(power, direction), TURN(direction) and KICK(power,
direction) (the old envs' flat 8-vector, so the same policies fit); a defense agent plays DASH, TURN,
TACKLE(direction) and KICK, and the goalie also CATCH(), in HFO's enum order. Powers lie in [0, 100], directions in
[-180, 180] degrees relative to the body. TACKLE is librcsc's: refused while frozen, the direction normalised and
rounded to 0.001, no foul; CATCH is librcsc's ``setCatch``: refused while frozen, aimed at the ball's direction plus
the catch area's diagonal angle (atan2(catchable_area_w / 2, catchable_area_l) = 22.6 degrees), then rcssserver's
catch rule (:meth:`hfo2d.physics.World.catch`: ban cycles, catchable area, probability).

Observations: HFO's low-level features (:mod:`hfo2d.features`) with one block per teammate (the other players of
the agent's side) and per opponent, ``feature_set`` "paper" (58 + 8 per other player) or "hfo" (HFO master's 58 +
9 per other player + 1); or HFO's high-level features, ``"high_level"`` (10 + 6 per teammate + 3 per opponent + 2,
:func:`hfo2d.features.high_level_feature_list`, where this hfo2d has it). A defense agent sees the field as librcsc shows a right-side player
(``PlayerAgent::parse`` -> ``FullstateSensor::reverse``: positions and velocities negated, body angle + 180), so
its landmarks are those of the goal *it* attacks; HFO's listing test (``pos().x > 0``, in that frame) then hides
every player inside the HFO half from a defense agent, as in real HFO. The frozen flag (feature 8) is +1 while
the agent is frozen by its own tackle (librcsc ``SelfObject::isFrozen``).

Rewards (this project's choice; HFO itself gives none):

* offense (``reward``): ``"shaped"`` (default), Hausknecht & Stone's shaping as DQNHFO computes it, from each
  agent's own features (:class:`hfo2d.reward.ShapedReward`: its own move-to-ball and first-kickable bonus, the
  ball's progress to the goal, +5 on a goal, whoever scored); ``"shaped_gap"`` and ``"shaped_gap_refund"``
  (:mod:`hfo2d.reward`: the ball's progress measured to the gap beside the goalie, lost shots refunded), which
  read the goalie where ``HFO/Keeper-v1`` has it (:meth:`TeamGame._reward_features`); ``"carry"`` and
  ``"carry_shot"`` (:mod:`hfo2d.reward`: the ball's record closeness to the goal while within 2 m of the striker,
  and the shot's record speed; they read the basic features only, so each striker's own); ``"sparse"``: 1 on a goal.
  Role-aware (``"shaped_gap_refund_nearest"`` and ``"carry_shot_nearest"``, this project's): the reward they are
  named after, except that the ball-pull
  terms (move to the ball, first-kickable bonus) are paid only to the learning striker nearest the ball after the
  cycle (world distances; a tie goes to the lower agent index), while the progress and goal terms stay each
  striker's. Why: with every striker paid for its own move to the ball, all of them chase it and the goalie
  captures (benchmarks/README.md, 2v1); with one striker it equals ``"shaped_gap_refund"``. A striker that is not
  the nearest still has its kick bonus marked paid if it became kickable (the bonus is the episode's first touch).
* defense (``defense_reward``): ``"sparse"`` (default): +1 on the last step when the episode ends in
  CAPTURED_BY_DEFENSE, OUT_OF_BOUNDS or OUT_OF_TIME (truncation included), -1 on a GOAL, else 0;
  ``"shaped"``: the same plus the rise of the agent's ball proximity since its last step (DQNHFO's move-to-ball
  term, feature 53; 0 on an episode's first and last step).
"""

from __future__ import annotations

import math
import struct
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces
from gymnasium.utils import seeding

from hfo2d import accel as _accel
from hfo2d import features as features_module
from hfo2d.action_layout import (
    HFO_FLAT_ACTION_LAYOUT,
    HybridActionBox,
    HybridActionLayout,
)
from hfo2d.features import (
    BALL_PROXIMITY,
    KICKABLE,
    KICKABLE_BUFFER,
    SELF_FROZEN,
    hfo_feature_list,
    hfo_num_features,
    num_features,
    paper_feature_list,
)
from hfo2d.hfo_env import _as_float_list, check_render_mode  # the single-agent env's checks, shared
from hfo2d.npc import DefenseNPC
from hfo2d.physics import BallState, PlayerState, ServerParams, World, normalize_deg
from hfo2d.protocol import (
    AGENT2D_FIRST_OBSERVATION_DELAY,
    BALL_X_RANGE,
    BALL_Y_RANGE,
    CAPTURED_BY_DEFENSE,
    DEFAULT_FRAMES_PER_TRIAL,
    DEFAULT_UNTOUCHED_TIME,
    DEFENSE_SIDE,
    DIRECTION_MAX,
    DIRECTION_MIN,
    GOAL,
    IN_GAME,
    KEEPER_START,
    KEEPER_UNUM,
    OFFENSE_OFFSETS,
    OFFENSE_SIDE,
    OFFENSE_SPREAD,
    OFFENSE_X_RANGE,
    OFFENSE_Y_RANGE,
    OUT_OF_BOUNDS,
    OUT_OF_TIME,
    POWER_MAX,
    POWER_MIN,
)
from hfo2d.referee import Referee
from hfo2d.reward import GOALIE_READING_REWARDS as SINGLE_AGENT_GOALIE_READING_REWARDS
from hfo2d.reward import make_reward
from hfo2d.strikers import STRIKERS, Striker, make_striker

__all__ = [
    "DEFENSE_ACTION_NAMES",
    "DEFENSE_ORDER",
    "DEFENDER_FLAT_ACTION_LAYOUT",
    "GOALIE_FLAT_ACTION_LAYOUT",
    "MAX_DEFENSE_PLAYERS",
    "MAX_OFFENSE_PLAYERS",
    "OFFENSE_ORDER",
    "TEAM_ACTION_FORMATS",
    "TEAM_DEFENSE_REWARDS",
    "TEAM_FEATURE_SETS",
    "TEAM_OFFENSE_REWARDS",
    "BALL_PULL_TERMS",
    "NEAREST_PULL_REWARDS",
    "HalfFieldOffenseEnv",
    "TeamGame",
    "TeamRoster",
    "team_roster",
]

# --- team sizes and uniform numbers -----------------------------------------------------------------------------
#: bin/HFO parseArgs (b8b2a1d lines 214-238): offense players (agents + NPCs) 1-10, defense players 0-11.
MAX_OFFENSE_PLAYERS = 10
MAX_DEFENSE_PLAYERS = 11
#: bin/Teams.py Agent2d ``offenseOrder`` (line 65): the offense's unums in the order the trainer fills them.
OFFENSE_ORDER: tuple[int, ...] = (11, 7, 8, 9, 10, 6, 3, 2, 4, 5)
#: bin/Trainer.py getTeams (line 117): ``[1] + defenseOrder`` (Teams.py line 66), the goalie first.
DEFENSE_ORDER: tuple[int, ...] = (1, 2, 3, 4, 5, 6, 7, 8, 11, 9, 10)

# --- start positions (referee.cpp HFORef::resetField, bin/HFO defaults) -------------------------------------------
PITCH_LENGTH = 105.0
#: Field defenders (not the goalie) start at x ~ U(0.4, 0.5) * pitch_length, y ~ U(-0.4, 0.4) * pitch_width.
DEFENDER_X_RANGE = (0.4 * PITCH_LENGTH, 0.5 * PITCH_LENGTH)
DEFENDER_Y_RANGE = BALL_Y_RANGE  # -0.4 * 68, 0.4 * 68 (= 27.2, written out as in hfo2d.protocol)

# --- actions (HFO src/common.hpp action enum order: DASH, TURN, TACKLE, KICK, ..., CATCH) --------------------------
DEFENSE_ACTION_NAMES: tuple[str, ...] = ("DASH", "TURN", "TACKLE", "KICK", "CATCH")
#: A field defender's flat action: [pref DASH, TURN, TACKLE, KICK, dash power, dash dir, turn dir, tackle dir,
#: kick power, kick dir], each in [0, 1] (powers 0..100, directions -180..180).
DEFENDER_FLAT_ACTION_LAYOUT = HybridActionLayout(
    names=DEFENSE_ACTION_NAMES[:4],
    parameter_sizes=(2, 1, 1, 2),
    direction_indices=(5, 6, 7, 9),
    ball_action=3,
)
#: The goalie's: the same with CATCH (no parameter) last: 5 preferences, then the same parameters.
GOALIE_FLAT_ACTION_LAYOUT = HybridActionLayout(
    names=DEFENSE_ACTION_NAMES,
    parameter_sizes=(2, 1, 1, 2, 0),
    direction_indices=(6, 7, 8, 10),
    ball_action=3,
)
#: Bounds of each action's parameters (low, high per parameter), by action name.
_PARAMETER_BOUNDS: dict[str, tuple[tuple[float, float], ...]] = {
    "DASH": ((POWER_MIN, POWER_MAX), (DIRECTION_MIN, DIRECTION_MAX)),
    "TURN": ((DIRECTION_MIN, DIRECTION_MAX),),
    "TACKLE": ((DIRECTION_MIN, DIRECTION_MAX),),
    "KICK": ((POWER_MIN, POWER_MAX), (DIRECTION_MIN, DIRECTION_MAX)),
    "CATCH": (),
}
# librcsc ActionEffector::setCatch: the catch is aimed this far beside the ball, along the catch area's diagonal
# (AngleDeg::atan2_deg(catchAreaWidth() * 0.5, catchAreaLength()); computed from the params in TeamGame)

TEAM_ACTION_FORMATS: tuple[str, ...] = ("flat", "parameterized")
#: "high_level" is HFO's high-level feature set, offered when hfo2d.features has it (high_level_feature_list).
TEAM_FEATURE_SETS: tuple[str, ...] = ("paper", "hfo", "high_level")
#: Team rewards that pay the ball-pull terms (BALL_PULL_TERMS) only to the striker nearest the ball: name -> the
#: per-striker reward whose other terms they keep (see the module docstring, "role-aware").
NEAREST_PULL_REWARDS: dict[str, str] = {
    "shaped_gap_refund_nearest": "shaped_gap_refund",
    "carry_shot_nearest": "carry_shot",
}
TEAM_OFFENSE_REWARDS: tuple[str, ...] = (
    "shaped",
    "shaped_gap",
    "shaped_gap_refund",
    "carry",
    "carry_shot",
    "sparse",
    *NEAREST_PULL_REWARDS,
)
#: Offense rewards that read the goalie's block (hfo2d.reward.GOALIE_READING_REWARDS, and the role-aware ones built
#: on them): the team game gives them HFO/Keeper-v1's view of the state.
GOALIE_READING_REWARDS: tuple[str, ...] = (
    *SINGLE_AGENT_GOALIE_READING_REWARDS,
    *(name for name, base in NEAREST_PULL_REWARDS.items() if base in SINGLE_AGENT_GOALIE_READING_REWARDS),
)
#: The shaped reward's terms that pull a striker to the ball (hfo2d.reward.REWARD_TERM_NAMES); a role-aware team
#: reward pays them to the striker nearest the ball alone.
BALL_PULL_TERMS: tuple[str, ...] = ("move_to_ball", "kick_bonus")
TEAM_DEFENSE_REWARDS: tuple[str, ...] = ("sparse", "shaped")
#: The statuses that end an episode in the defense's favour (its sparse reward +1).
DEFENSE_WINS: tuple[str, ...] = (CAPTURED_BY_DEFENSE, OUT_OF_BOUNDS, OUT_OF_TIME)

#: Where the field defenders' port lives; imported only when a team has one.
DEFENDER_MODULE = "hfo2d.agent2d.defender"


@dataclass(frozen=True)
class TeamRoster:
    """Who plays: the uniform numbers of the offense agents, the defense agents and the defense NPCs, each in the
    order the agents are numbered ("offense_0" has ``offense_agents[0]``); the goalie is the defense's unum 1."""

    offense_agents: tuple[int, ...]
    defense_agents: tuple[int, ...]
    defense_npcs: tuple[int, ...]
    offense_npcs: tuple[int, ...] = ()

    @property
    def offense(self) -> tuple[int, ...]:
        """Every offense player's unum, increasing (the server's order)."""
        return tuple(sorted(self.offense_agents + self.offense_npcs))

    @property
    def defense(self) -> tuple[int, ...]:
        """Every defender's unum, increasing (the server's order)."""
        return tuple(sorted(self.defense_agents + self.defense_npcs))

    @property
    def goalie_is_agent(self) -> bool:
        """Whether a defense agent plays goalie (unum 1)."""
        return KEEPER_UNUM in self.defense_agents


def _check_count(name: str, value: Any, low: int, high: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise ValueError(f"{name} must be an integer, got {value!r}")
    if not low <= value <= high:
        raise ValueError(f"{name} must lie in [{low}, {high}] (bin/HFO's limit), got {value}")
    return int(value)


def team_roster(
    offense_agents: int = 1,
    defense_agents: int = 0,
    defense_npcs: int = 0,
    agent_play_goalie: bool = False,
    offense_npcs: int = 0,
) -> TeamRoster:
    """The uniform numbers bin/HFO gives these team sizes (see the module docstring); ValueError for sizes bin/HFO
    rejects."""
    offense = _check_count("offense_agents", offense_agents, 0, MAX_OFFENSE_PLAYERS)
    offense_scripted = _check_count("offense_npcs", offense_npcs, 0, MAX_OFFENSE_PLAYERS)
    agents = _check_count("defense_agents", defense_agents, 0, MAX_DEFENSE_PLAYERS)
    npcs = _check_count("defense_npcs", defense_npcs, 0, MAX_DEFENSE_PLAYERS)
    if not 1 <= offense + offense_scripted <= MAX_OFFENSE_PLAYERS:
        raise ValueError(
            f"the offense needs 1 to {MAX_OFFENSE_PLAYERS} players (bin/HFO: offense agents + offense NPCs; hfo2d's "
            f"NPCs are its scripted_strikers), got {offense + offense_scripted}"
        )
    if agents + npcs > MAX_DEFENSE_PLAYERS:
        raise ValueError(
            f"defense_agents + defense_npcs must be at most {MAX_DEFENSE_PLAYERS} (bin/HFO), got {agents + npcs}"
        )
    if not isinstance(agent_play_goalie, (bool, np.bool_)):
        raise ValueError(f"agent_play_goalie must be True or False, got {agent_play_goalie!r}")
    if agent_play_goalie and agents == 0:
        raise ValueError(
            "agent_play_goalie needs a defense agent (bin/HFO: 'You must add a --defense-agent')"
        )
    # Trainer.run (lines 385-390): offense_unums = offenseOrder[1 : numOffense + 1], agents
    # sorted(offenseOrder[1 : agents + 1])
    offense_agent_unums = tuple(sorted(OFFENSE_ORDER[:offense]))
    offense_npc_unums = tuple(sorted(OFFENSE_ORDER[offense : offense + offense_scripted]))
    # defense_unums = sorted(defenseOrder[:numDefense]); agents take its tail, or its head with --agent-play-goalie
    defense = sorted(DEFENSE_ORDER[: agents + npcs])
    if agents == 0:
        defense_agent_unums: tuple[int, ...] = ()
    elif agent_play_goalie:
        defense_agent_unums = tuple(defense[:agents])
    else:
        defense_agent_unums = tuple(defense[-agents:])
    npc_unums = tuple(unum for unum in defense if unum not in defense_agent_unums)
    return TeamRoster(offense_agent_unums, defense_agent_unums, npc_unums, offense_npc_unums)


@dataclass
class _Agent:
    """One learning agent of a :class:`TeamGame`."""

    name: str
    player: PlayerState
    offense: bool
    layout: HybridActionLayout
    observation_space: spaces.Box
    action_space: spaces.Space
    reward: Any  # an hfo2d.reward reward function (offense) or None (defense)
    last_action_succeeded: bool = False
    previous_ball_proximity: float | None = None
    # per-step constants, looked up once here (a frozen layout hashes all its fields on every dict lookup):
    # the flat action's length and its decoding (_FLAT_DECODING[layout])
    flat_size: int = 0
    flat_decoding: tuple[tuple[int, tuple[tuple[float, float], ...]], ...] = ()


class TeamGame:
    """One HFO game of several agents and NPCs (see the module docstring for HFO's rules and the sources).

    Args:
        offense_agents: learning strikers, 1-10 (bin/HFO ``--offense-agents``).
        defense_agents: learning defenders, 0-11 (``--defense-agents``).
        defense_npcs: agent2d's defenders, 0-11 (``--defense-npcs``); with ``defense_agents`` at most 11.
        scripted_strikers: hfo2d's own scripted strikers (:mod:`hfo2d.strikers`) on the offense, in the places
            bin/HFO gives offense NPCs (the offense's unums after the agents'); each decides on its paper features
            with the goalie's block alone. They are not agent2d's offense, bin/HFO's ``--offense-npcs``, which is
            not ported: ``offense_npcs`` > 0 is a ValueError here (``backend="real"`` plays agent2d's).
        striker: which scripted striker (a name of :data:`hfo2d.strikers.STRIKERS`; default ``"soft_dribble"``).
        offense_npcs: agent2d's offense NPCs: only 0 (see ``scripted_strikers``).
        agent_play_goalie: a defense agent plays goalie (``--agent-play-goalie``).
        action_format: ``"flat"`` (a :class:`~hfo2d.action_layout.HybridActionBox`: the preferences, then every
            action's parameters, all in [0, 1]) or ``"parameterized"`` (``Tuple(Discrete(n), Box(params of each
            action that has any))`` in HFO's units).
        feature_set: ``"paper"``, ``"hfo"`` or ``"high_level"`` (see :mod:`hfo2d.features`).
        reward: the offense's, one of :data:`TEAM_OFFENSE_REWARDS`.
        defense_reward: the defense's, one of :data:`TEAM_DEFENSE_REWARDS`.
        noise: False turns off player, ball and kick noise (HFO's ``--deterministic``).
        server_params: rcssserver parameter overrides (:meth:`hfo2d.physics.ServerParams.with_overrides`).
        frames_per_trial: HFO's ``--frames-per-trial`` (default 500, gym-soccer's and the project's other envs').
        untouched_time: HFO's ``--untouched-time`` (default 100).
        seed: seeds the game's generator (as a first ``reset(seed=...)`` would; None: from the OS).
    """

    def __init__(
        self,
        offense_agents: int = 1,
        defense_agents: int = 0,
        defense_npcs: int = 0,
        *,
        scripted_strikers: int = 0,
        striker: str = "soft_dribble",
        offense_npcs: int = 0,
        agent_play_goalie: bool = False,
        action_format: str = "flat",
        feature_set: str = "paper",
        reward: str = "shaped",
        defense_reward: str = "sparse",
        noise: bool = True,
        server_params: Mapping[str, float] | None = None,
        frames_per_trial: int = DEFAULT_FRAMES_PER_TRIAL,
        untouched_time: int = DEFAULT_UNTOUCHED_TIME,
        seed: int | None = None,
    ) -> None:
        if (
            not (isinstance(offense_npcs, (int, np.integer)) and not isinstance(offense_npcs, bool))
            or offense_npcs
        ):
            raise ValueError(
                f"offense_npcs={offense_npcs!r}: agent2d's offense (bin/HFO --offense-npcs) is not ported to hfo2d "
                "(backend 'real' plays it); hfo2d's own scripted strikers take those places with scripted_strikers=N"
            )
        # the scripted strikers stand where bin/HFO puts offense NPCs
        roster = team_roster(
            offense_agents, defense_agents, defense_npcs, agent_play_goalie, scripted_strikers
        )
        if striker not in STRIKERS:
            raise ValueError(f"unknown striker {striker!r}; choose one of {tuple(STRIKERS)}")
        for name, value, choices in (
            ("action_format", action_format, TEAM_ACTION_FORMATS),
            ("feature_set", feature_set, TEAM_FEATURE_SETS),
            ("reward", reward, TEAM_OFFENSE_REWARDS),
            ("defense_reward", defense_reward, TEAM_DEFENSE_REWARDS),
        ):
            if value not in choices:
                raise ValueError(f"unknown {name} {value!r}; choose one of {choices}")
        if feature_set == "high_level" and not hasattr(features_module, "high_level_feature_list"):
            raise ValueError(
                "feature_set='high_level' needs hfo2d.features.high_level_feature_list (HFO's high-level features), "
                "which this hfo2d does not have yet: use 'paper' or 'hfo'"
            )
        if not isinstance(noise, (bool, np.bool_)):
            raise ValueError(f"noise must be True or False, got {noise!r}")
        for name, value in (("frames_per_trial", frames_per_trial), ("untouched_time", untouched_time)):
            if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
                raise ValueError(f"{name} must be a positive integer, got {value!r}")
        params = ServerParams.with_overrides(server_params)
        npc_classes = _npc_classes(roster)  # before anything is built: a missing port changes nothing

        self.roster = roster
        self.action_format = action_format
        self.feature_set = feature_set
        self.reward_name = reward
        self.defense_reward_name = defense_reward
        self.noise = bool(noise)
        self.params = params
        self._hfo_layout = feature_set == "hfo"
        self._high_level = feature_set == "high_level"
        self._kickable_distance = params.kickable_area - KICKABLE_BUFFER
        # librcsc ActionEffector::setCatch's diagonal angle of the catch area
        self._catch_diagonal_deg = math.degrees(
            math.atan2(params.catchable_area_w * 0.5, params.catchable_area_l)
        )
        self.np_random, _ = seeding.np_random(seed)
        rng = self.np_random
        self.world = World(params, rng, noise=self.noise)
        # players in the server's order: the offense, then the defense, each by increasing unum (Trainer.run)
        self.offense_players: list[PlayerState] = []
        players_by_unum: dict[int, PlayerState] = {}
        for unum in roster.offense:
            self.offense_players.append(self.world.add_player(OFFENSE_SIDE, unum))
        self.defense_players: list[PlayerState] = []
        for unum in roster.defense:
            player = self.world.add_player(DEFENSE_SIDE, unum, goalie=unum == KEEPER_UNUM)
            self.defense_players.append(player)
            players_by_unum[unum] = player
        #: The defense's scripted players with the player each moves, in server order (the goalie first).
        self.defense_npcs: list[tuple[PlayerState, DefenseNPC]] = [
            (players_by_unum[unum], npc_classes[unum](unum, params, rng)) for unum in roster.defense_npcs
        ]
        offense_by_unum = {player.unum: player for player in self.offense_players}
        self.striker_name = striker
        #: The offense's scripted players (hfo2d's scripted strikers, not agent2d's offense) with their players.
        self.scripted_strikers: list[tuple[PlayerState, Striker]] = [
            (offense_by_unum[unum], make_striker(striker)) for unum in roster.offense_npcs
        ]
        self._goalie = next((player for player in self.defense_players if player.goalie), None)
        # a gap reward reads the goalie at features 58-65; a team's layout puts other players there (the nearest
        # teammate first), so such a reward gets the 1v1 view (_reward_features) unless the layout already is it
        self._reward_needs_goalie_view = reward in GOALIE_READING_REWARDS and not (
            len(self.offense_players) == 1 and len(self.defense_players) == 1 and self._goalie is not None
        )
        self.agents: list[_Agent] = []
        n_offense, n_defense = len(self.offense_players), len(self.defense_players)
        for index, unum in enumerate(roster.offense_agents):
            self.agents.append(
                self._make_agent(f"offense_{index}", offense_by_unum[unum], True, n_offense - 1, n_defense)
            )
        for index, unum in enumerate(roster.defense_agents):
            self.agents.append(
                self._make_agent(f"defense_{index}", players_by_unum[unum], False, n_defense - 1, n_offense)
            )
        self.agent_names: tuple[str, ...] = tuple(agent.name for agent in self.agents)
        self._agents_by_name = {agent.name: agent for agent in self.agents}
        self.referee = Referee(
            params, int(untouched_time), trial_time=int(frames_per_trial), rules="rcssserver"
        )
        self._rng_in_use = rng
        self._episode_started = False
        self._episode_over = False
        self._needs_reset = True
        self.status = IN_GAME
        self.steps = 0
        # the render overlay's counters
        self.episode_number = 0
        self.episodes_ended = 0
        self.goals = 0
        self.last_end: tuple[int, str] | None = None
        self._mirror_cache: Any = None
        self._renderer: Any = None
        self._renderer_mode: str | None = None

    # ------------------------------------------------------------------------------------------------------------
    def _make_agent(
        self, name: str, player: PlayerState, offense: bool, n_teammates: int, n_opponents: int
    ) -> _Agent:
        if offense:
            layout = HFO_FLAT_ACTION_LAYOUT
        else:
            layout = GOALIE_FLAT_ACTION_LAYOUT if player.goalie else DEFENDER_FLAT_ACTION_LAYOUT
        if self._high_level:
            low, high = features_module.high_level_bounds(n_teammates, n_opponents)
            observation_space = spaces.Box(
                np.array(low, dtype=np.float32), np.array(high, dtype=np.float32), dtype=np.float32
            )
        else:
            size = (
                hfo_num_features(n_teammates, n_opponents)
                if self._hfo_layout
                else num_features(n_teammates, n_opponents)
            )
            observation_space = spaces.Box(-1.0, 1.0, shape=(size,), dtype=np.float32)
        action_space = (
            HybridActionBox(layout) if self.action_format == "flat" else _parameterized_space(layout)
        )
        reward = (
            make_reward(NEAREST_PULL_REWARDS.get(self.reward_name, self.reward_name)) if offense else None
        )
        return _Agent(
            name,
            player,
            offense,
            layout,
            observation_space,
            action_space,
            reward,
            flat_size=layout.size,
            flat_decoding=_FLAT_DECODING[layout],
        )

    def agent(self, name: str) -> _Agent:
        """The agent called ``name`` ("offense_0", ...); ValueError for an unknown name."""
        try:
            return self._agents_by_name[name]
        except KeyError:
            raise ValueError(f"unknown agent {name!r}; this game's agents are {self.agent_names}") from None

    @property
    def episode_over(self) -> bool:
        """The episode has ended: :meth:`step` needs a :meth:`reset`."""
        return self._episode_over

    # ------------------------------------------------------------------------------------------------------------
    def reset(self, seed: int | None = None) -> tuple[dict[str, np.ndarray], dict[str, dict[str, Any]]]:
        """Start an episode (HFORef::resetField); returns (observations, infos) by agent name.

        ``seed`` reseeds the game's generator and starts the NPCs afresh (no carry-over from the last episode),
        so that ``reset(seed=s)`` repeats; without it the server's state and the NPCs' carry over as in real HFO.
        """
        if seed is not None:
            self.np_random, _ = seeding.np_random(seed)
        rng = self.np_random
        world = self.world
        if rng is not self._rng_in_use:
            world.rng = rng
            for _, npc in self.defense_npcs:
                npc.rng = rng
            self._rng_in_use = rng
        carry_over = seed is None and self._episode_started
        if carry_over:
            self._wait_frame()
        elif seed is not None and self._episode_started:
            for _, npc in self.defense_npcs:
                if npc.carries_over:
                    npc.restart()
            for player in world.players:
                player.catch_ban = 0
                player.tackle_cycles = 0

        # referee.cpp HFORef::resetField (mhauskn/rcssserver, lines 3226-3316): the ball (3236-3245), the offsets
        # shuffled (3249), the offense around the ball and clamped (3286-3294), the goalie at (52.5, 0) and the
        # other defenders drawn (3299-3305), then recoveryPlayers (3309)
        ball_x = rng.uniform(*BALL_X_RANGE)
        ball_y = rng.uniform(*BALL_Y_RANGE)
        offsets = [OFFENSE_OFFSETS[int(k)] for k in rng.permutation(len(OFFENSE_OFFSETS))]
        world.place_ball(ball_x, ball_y)
        positions: list[tuple[float, float]] = []
        for index, _player in enumerate(self.offense_players):
            offset_x, offset_y = offsets[index]
            x = min(
                max(ball_x + OFFENSE_SPREAD * (rng.uniform() + offset_x), OFFENSE_X_RANGE[0]),
                OFFENSE_X_RANGE[1],
            )
            y = min(
                max(ball_y + OFFENSE_SPREAD * (rng.uniform() + offset_y), OFFENSE_Y_RANGE[0]),
                OFFENSE_Y_RANGE[1],
            )
            positions.append((x, y))
        for player in self.defense_players:
            if player.goalie:
                positions.append(KEEPER_START)
            else:
                positions.append((rng.uniform(*DEFENDER_X_RANGE), rng.uniform(*DEFENDER_Y_RANGE)))
        npc_of = {id(player): npc for player, npc in self.defense_npcs}
        for player, (x, y) in zip(self.offense_players + self.defense_players, positions, strict=True):
            npc = npc_of.get(id(player))
            if npc is None:
                body = rng.uniform(-180.0, 180.0)
            else:
                body = player.body_deg if carry_over else npc.start_body_deg(rng)
            world.place_player(player, x, y, body)
        world.recover_players()
        for player in world.players:
            player.collided_ball = player.collided_player = player.collided_post = False
        world.ball.collided_post = False
        for _, npc in self.defense_npcs:
            npc.reset()
        for _, scripted in self.scripted_strikers:
            scripted.reset()
        self.steps = 0
        self.status = IN_GAME
        self._needs_reset = False
        self._episode_started = True
        self.referee.reset(world)
        # real HFO: the agents' first observation comes two cycles after the placement; the NPCs play them
        for _ in range(AGENT2D_FIRST_OBSERVATION_DELAY):
            for player, npc in self.defense_npcs:
                npc.act(world, player)
            world.step()
            self.referee.analyse(world)
        self._episode_over = False
        self.episode_number += 1
        observations: dict[str, np.ndarray] = {}
        infos: dict[str, dict[str, Any]] = {}
        for agent in self.agents:
            agent.last_action_succeeded = False  # HFO's agent starts with its last action status false
            paper = self._paper_features(agent)
            if agent.reward is not None:
                agent.reward.reset(self._reward_features(agent, paper))
            agent.previous_ball_proximity = paper[BALL_PROXIMITY]
            observations[agent.name] = self._observation(agent, paper)
            infos[agent.name] = self._info(agent, paper)
        return observations, infos

    def step(
        self, actions: Mapping[str, Any]
    ) -> tuple[dict[str, np.ndarray], dict[str, float], bool, bool, dict[str, dict[str, Any]]]:
        """One server cycle with every agent's action: (observations, rewards, terminated, truncated, infos), the
        dicts by agent name; the episode ends for all agents at once.

        ``actions`` needs one valid action per agent; anything missing, unknown or invalid is a ValueError that
        changes nothing.
        """
        if self._needs_reset:
            raise RuntimeError("call reset() before step()")
        if self._episode_over:
            raise RuntimeError(f"the episode has ended ({self.status}): call reset() before step()")
        if not isinstance(actions, Mapping):
            raise ValueError(f"actions must be a dict of agent name -> action, got {type(actions).__name__}")
        if actions.keys() != self._agents_by_name.keys():
            missing = [name for name in self.agent_names if name not in actions]
            unknown = [name for name in actions if name not in self._agents_by_name]
            raise ValueError(
                f"actions need exactly this game's agents {self.agent_names}; missing {missing}, unknown {unknown}"
            )
        commands = [(agent, self._parse_action(agent, actions[agent.name])) for agent in self.agents]

        world = self.world
        for player, npc in self.defense_npcs:
            npc.decide(world, player)
        striker_commands = [
            (player, scripted.command(self._striker_observation(player)))
            for player, scripted in self.scripted_strikers
        ]
        for agent, (kind, parameters) in commands:
            agent.last_action_succeeded = self._execute(agent.player, kind, parameters)
        for player, (kind, first, second) in striker_commands:
            self._execute(player, kind, (first, second))
        for player, npc in self.defense_npcs:
            npc.apply(world, player)
        world.step()
        self.steps += 1
        status = self.referee.analyse(world)
        truncated = self.referee.truncated
        terminated = status != IN_GAME and not truncated
        self.status = status
        if terminated or truncated:
            self._episode_over = True
            self.episodes_ended += 1
            self.goals += status == GOAL
            self.last_end = (self.episode_number, status)

        observations: dict[str, np.ndarray] = {}
        rewards: dict[str, float] = {}
        infos: dict[str, dict[str, Any]] = {}
        puller = self._ball_puller()
        for agent, (kind, _) in commands:
            paper = self._paper_features(agent)
            info = self._info(agent, paper)
            if agent.offense:
                reward, terms = agent.reward(self._reward_features(agent, paper), status, terminated)
                if puller is not None and agent is not puller:
                    terms = {**terms, **dict.fromkeys(BALL_PULL_TERMS, 0.0)}
                    reward = sum(terms.values())
            else:
                reward, terms = self._defense_reward(agent, paper, status)
            info["reward_terms"] = terms
            info["action"] = agent.layout.names[kind]
            info["action_success"] = agent.last_action_succeeded
            observations[agent.name] = self._observation(agent, paper)
            rewards[agent.name] = float(reward)
            infos[agent.name] = info
        return observations, rewards, terminated, truncated, infos

    # ------------------------------------------------------------------------------------------------------------
    def _wait_frame(self) -> None:
        """Real HFO plays one cycle after an episode ends (HFORef waits a frame); the NPCs act in it."""
        for player, npc in self.defense_npcs:
            npc.act(self.world, player)
        self.world.step()

    def _execute(self, player: PlayerState, kind_name_index: int, parameters: Sequence[float]) -> bool:
        """Send one agent command as librcsc's PlayerAgent would; returns HFO's last action status."""
        world = self.world
        name = _ACTION_OF_INDEX[player.side == DEFENSE_SIDE][kind_name_index]
        frozen = player.tackle_cycles > 0  # librcsc refuses every body command while frozen
        if name == "DASH":
            world.client_dash(player, parameters[0], parameters[1])
            return not frozen
        if name == "TURN":
            world.client_turn(player, parameters[0])
            return not frozen
        if name == "KICK":
            return bool(world.client_kick(player, parameters[0], parameters[1])) and not frozen
        if frozen:
            return False
        if name == "TACKLE":
            # librcsc ActionEffector::setTackle (version >= 12): normalised, rounded to 0.001; HFO sends no foul
            direction = round(normalize_deg(float(parameters[0])) * 1000.0) * 0.001
            world.tackle(player, direction, foul=False)
            return True
        # CATCH (the goalie's only): librcsc ActionEffector::setCatch (action_effector.cpp lines 1031-1064) aims at
        # the ball plus the diagonal angle
        ball = world.ball
        ball_angle = math.degrees(math.atan2(ball.y - player.y, ball.x - player.x))
        world.catch(player, normalize_deg(ball_angle - player.body_deg + self._catch_diagonal_deg))
        return True

    def _striker_observation(self, player: PlayerState) -> np.ndarray:
        """What a scripted striker reads (hfo2d.strikers): the paper features with the goalie's block only."""
        opponents = (self._goalie,) if self._goalie is not None else ()
        features = paper_feature_list(player, self.world.ball, self._kickable_distance, (), opponents)
        return np.asarray(features, dtype=np.float32)

    def _paper_features(self, agent: _Agent) -> list[float]:
        """The agent's paper-era features (its own frame), frozen flag set; rewards read them."""
        player, ball, teammates, opponents = self._view(agent)
        features = paper_feature_list(player, ball, self._kickable_distance, teammates, opponents)
        if agent.player.tackle_cycles > 0:
            features[SELF_FROZEN] = 1.0
        return features

    def _ball_puller(self) -> _Agent | None:
        """Under a role-aware reward (:data:`NEAREST_PULL_REWARDS`), the learning striker nearest the ball (a tie
        goes to the lower index), the only one paid the ball-pull terms; None under any other reward."""
        if self.reward_name not in NEAREST_PULL_REWARDS:
            return None
        ball = self.world.ball
        strikers = [agent for agent in self.agents if agent.offense]
        if not strikers:
            return None
        return min(
            strikers,
            key=lambda agent: math.hypot(agent.player.x - ball.x, agent.player.y - ball.y),
        )

    def _reward_features(self, agent: _Agent, paper: list[float]) -> list[float]:
        """What an offense agent's reward reads: its paper features, or for a gap reward in a team other than
        1 v the goalie, HFO/Keeper-v1's view of the same state: the 58 basic features, then the goalie's block
        alone (none without a goalie; the reward then aims at the goal centre)."""
        if not self._reward_needs_goalie_view:
            return paper
        opponents = (self._goalie,) if self._goalie is not None else ()
        return paper_feature_list(agent.player, self.world.ball, self._kickable_distance, (), opponents)

    def _view(self, agent: _Agent) -> tuple[PlayerState, BallState, list[PlayerState], list[PlayerState]]:
        """The agent, the ball, its teammates and its opponents as its client sees them (mirrored for the
        defense: librcsc FullstateSensor::reverse)."""
        player = agent.player
        if agent.offense:
            teammates = [other for other in self.offense_players if other is not player]
            return player, self.world.ball, teammates, self.defense_players
        world = self.world
        # the mirrored field, made once per cycle for every defense agent (and both feature sets)
        cache = self._mirror_cache
        if cache is None or cache[0] != (self.episode_number, world.cycle):
            ball = world.ball
            cache = (
                (self.episode_number, world.cycle),
                BallState(x=-ball.x, y=-ball.y, vx=-ball.vx, vy=-ball.vy),
                {id(other): _mirrored_player(other) for other in world.players},
            )
            self._mirror_cache = cache
        _, mirrored_ball, mirrored = cache
        teammates = [mirrored[id(other)] for other in self.defense_players if other is not player]
        opponents = [mirrored[id(other)] for other in self.offense_players]
        return mirrored[id(player)], mirrored_ball, teammates, opponents

    def _observation(self, agent: _Agent, paper: list[float]) -> np.ndarray:
        if self._high_level:
            # the server's frame: high_level_feature_list mirrors the field itself for a defender
            player = agent.player
            own = self.offense_players if agent.offense else self.defense_players
            others = self.defense_players if agent.offense else self.offense_players
            features = features_module.high_level_feature_list(
                player,
                self.world.ball,
                self._kickable_distance,
                [other for other in own if other is not player],
                others,
                agent.last_action_succeeded,
                playing_offense=agent.offense,
            )
        elif self._hfo_layout:
            player, ball, teammates, opponents = self._view(agent)
            features = hfo_feature_list(
                player, ball, self._kickable_distance, teammates, opponents, agent.last_action_succeeded
            )
            if agent.player.tackle_cycles > 0:
                features[SELF_FROZEN] = 1.0
        else:
            features = paper
        # native float32s (struct "=f" rounds to nearest), in a fresh writable array of its own
        return np.frombuffer(bytearray(_float32_packer(len(features))(*features)), np.float32)

    def _defense_reward(
        self, agent: _Agent, paper: list[float], status: str
    ) -> tuple[float, dict[str, float]]:
        """The defense's reward (module docstring): +1 / -1 at the end, plus move-to-ball with "shaped"."""
        outcome = 0.0
        if status == GOAL:
            outcome = -1.0
        elif status in DEFENSE_WINS:
            outcome = 1.0
        move_to_ball = 0.0
        proximity = paper[BALL_PROXIMITY]
        if (
            self.defense_reward_name == "shaped"
            and status == IN_GAME
            and agent.previous_ball_proximity is not None
        ):
            move_to_ball = proximity - agent.previous_ball_proximity
        agent.previous_ball_proximity = proximity
        return outcome + move_to_ball, {"move_to_ball": move_to_ball, "outcome": outcome}

    def _info(self, agent: _Agent, paper: Sequence[float]) -> dict[str, Any]:
        player = agent.player
        ball = self.world.ball
        status = self.status
        over = status != IN_GAME
        return {
            "status": status,
            "is_success": status == GOAL if agent.offense else over and status in DEFENSE_WINS,
            "unum": player.unum,
            "side": "offense" if agent.offense else "defense",
            "goalie": player.goalie,
            "player": (player.x, player.y, player.vx, player.vy, player.body_deg),
            "ball": (ball.x, ball.y, ball.vx, ball.vy),
            "kickable": paper[KICKABLE] > 0.0,
        }

    # --- rendering --------------------------------------------------------------------------------------------
    def render(self, render_mode: str) -> np.ndarray | None:
        """Draw every player and the ball (:mod:`hfo2d.rendering`): a pygame window ("human", returns None) or an
        RGB array (H, W, 3) uint8 ("rgb_array"), with the episode overlay."""
        if self._needs_reset:
            raise RuntimeError("call reset() before render()")
        from hfo2d.rendering import HFORenderer, Overlay  # pygame is imported only when rendering

        if self._renderer is None or self._renderer_mode != render_mode:
            self.close()
            self._renderer = HFORenderer(render_mode, self.params)
            self._renderer_mode = render_mode
        last = self.last_end
        over = self._episode_over
        overlay = Overlay(
            episode=self.episode_number,
            cycle=self.steps,
            goals=self.goals,
            ended=self.episodes_ended,
            status=self.status if over else None,
            previous=last if last is not None and not over else None,
        )
        return self._renderer.render(self.world, overlay)

    def close(self) -> None:
        """Close the render window, if any."""
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None

    def __getstate__(self) -> dict[str, Any]:
        state = dict(self.__dict__)
        state["_renderer"] = None  # a window does not pickle; the next render() opens a new one
        return state

    # --- actions ----------------------------------------------------------------------------------------------
    def _parse_action(self, agent: _Agent, action: Any) -> tuple[int, list[float]]:
        """(index of the action in the agent's layout, its parameters in HFO's units); ValueError if invalid."""
        layout = agent.layout
        if self.action_format == "flat":
            size = agent.flat_size
            if _ACCEL_DECODE_FLAT is not None:
                # the usual case (a float vector of the right length in [0, 1]) by hfo2d._accel's kernel, the
                # same numbers; anything else (None) takes the checks below
                decoded = _ACCEL_DECODE_FLAT(action, size, agent.flat_decoding)
                if decoded is not None:
                    return decoded
            if type(action) is np.ndarray and action.dtype.kind == "f" and action.shape == (size,):
                values = action.tolist()  # the usual case, without _as_float_list's checks
            else:
                values = _as_float_list(action, f"{agent.name}'s flat action")
            if len(values) != size:
                raise ValueError(
                    f"{agent.name}'s flat action must have shape ({size},) ({', '.join(layout.names)}), "
                    f"got {np.shape(action)}"
                )
            for index, value in enumerate(values):
                if not 0.0 <= value <= 1.0:  # (also a NaN)
                    what = "not finite" if not math.isfinite(value) else "outside [0, 1]"
                    raise ValueError(f"{agent.name}'s flat action element {index} is {what}: {value!r}")
            # HybridActionLayout.decode (the largest preference, the first on ties), its slices computed once
            decoding = agent.flat_decoding
            kind = 0
            for index in range(1, len(decoding)):
                if values[index] > values[kind]:
                    kind = index
            start, bounds = decoding[kind]
            return kind, [low + (high - low) * values[start + k] for k, (low, high) in enumerate(bounds)]
        n = layout.n_discrete
        with_parameters = [k for k in range(n) if layout.parameter_sizes[k] > 0]
        if not isinstance(action, (tuple, list)) or len(action) != 1 + len(with_parameters):
            raise ValueError(
                f"{agent.name}'s parameterized action must be a tuple (action index, then the parameters of "
                f"{', '.join(layout.names[k] for k in with_parameters)}), got {action!r}"
            )
        kind_raw = action[0]
        if isinstance(kind_raw, np.ndarray) and kind_raw.shape == () and kind_raw.dtype.kind in "iu":
            kind_raw = kind_raw.item()
        if isinstance(kind_raw, bool) or not isinstance(kind_raw, (int, np.integer)) or not 0 <= kind_raw < n:
            raise ValueError(
                f"{agent.name}'s action index must be an integer in [0, {n}) ({', '.join(layout.names)}), "
                f"got {kind_raw!r}"
            )
        kind = int(kind_raw)
        chosen: list[float] = []
        for position, k in enumerate(with_parameters, start=1):
            name = layout.names[k]
            bounds = _PARAMETER_BOUNDS[name]
            values = _as_float_list(action[position], f"{agent.name}'s {name} parameters")
            if len(values) != len(bounds):
                raise ValueError(
                    f"{agent.name}'s {name} parameters must have shape ({len(bounds)},), got {np.shape(action[position])}"
                )
            for value, (low, high) in zip(values, bounds, strict=True):
                if not low <= value <= high:
                    what = "not finite" if not math.isfinite(value) else f"outside [{low:g}, {high:g}]"
                    raise ValueError(f"{agent.name}'s {name} parameter {value!r} is {what}")
            if k == kind:
                chosen = values
        return kind, chosen


# hfo2d._accel's decoder of the usual flat action, or None for the pure-Python code (hfo2d.accel)
_ACCEL_DECODE_FLAT = None if _accel.ACCEL is None else _accel.ACCEL.decode_flat

# index in a layout -> action name, for the offense's layout (False) and the defense's (True; both defense layouts
# list DASH, TURN, TACKLE, KICK first, the goalie's CATCH last)
_ACTION_OF_INDEX: dict[bool, tuple[str, ...]] = {
    False: HFO_FLAT_ACTION_LAYOUT.names,
    True: GOALIE_FLAT_ACTION_LAYOUT.names,
}
if DEFENDER_FLAT_ACTION_LAYOUT.names != GOALIE_FLAT_ACTION_LAYOUT.names[:4]:
    raise ImportError("the field defender's actions must be the goalie's without CATCH")


#: Per flat layout, per action: where its parameters start and their bounds (the decode of _parse_action).
_FLAT_DECODING: dict[HybridActionLayout, tuple[tuple[int, tuple[tuple[float, float], ...]], ...]] = {
    layout: tuple(
        (layout.parameter_slice(kind).start, _PARAMETER_BOUNDS[name])
        for kind, name in enumerate(layout.names)
    )
    for layout in (HFO_FLAT_ACTION_LAYOUT, DEFENDER_FLAT_ACTION_LAYOUT, GOALIE_FLAT_ACTION_LAYOUT)
}


_FLOAT32_PACKERS: dict[int, Any] = {}


def _float32_packer(count: int) -> Any:
    """``struct.Struct(f"={count}f").pack``, compiled once per length (struct.pack parses its format each call)."""
    pack = _FLOAT32_PACKERS.get(count)
    if pack is None:
        pack = _FLOAT32_PACKERS[count] = struct.Struct(f"={count}f").pack
    return pack


def _mirrored_player(player: PlayerState) -> PlayerState:
    """``player`` as a right-side client sees it (librcsc FullstateSensor::reverse)."""
    return PlayerState(
        side=player.side,
        unum=player.unum,
        goalie=player.goalie,
        x=-player.x,
        y=-player.y,
        vx=-player.vx,
        vy=-player.vy,
        body_deg=_reversed_body_deg(player.body_deg),
        stamina=player.stamina,
        effort=player.effort,
        recovery=player.recovery,
        capacity=player.capacity,
        collided_ball=player.collided_ball,
        collided_player=player.collided_player,
        collided_post=player.collided_post,
        catch_ban=player.catch_ban,
        tackle_cycles=player.tackle_cycles,
    )


def _reversed_body_deg(body_deg: float) -> float:
    """A body angle in [-180, 180) turned round as librcsc's FullstateSensor::reverse does (AngleDeg folds into
    [-180, 180] by +-360 only beyond the ends, so a body of 0 becomes +180, not -180)."""
    turned = body_deg + 180.0
    if turned > 180.0:
        turned -= 360.0
    elif turned < -180.0:
        turned += 360.0
    return turned


def _parameterized_space(layout: HybridActionLayout) -> spaces.Tuple:
    """``Tuple(Discrete(n), Box(parameters) of each action that has any)``, in HFO's units."""
    boxes: list[spaces.Space] = [spaces.Discrete(layout.n_discrete)]
    for name, size in zip(layout.names, layout.parameter_sizes, strict=True):
        if size == 0:
            continue
        bounds = _PARAMETER_BOUNDS[name]
        boxes.append(
            spaces.Box(
                np.array([low for low, _ in bounds], dtype=np.float32),
                np.array([high for _, high in bounds], dtype=np.float32),
                dtype=np.float32,
            )
        )
    return spaces.Tuple(boxes)


def _npc_classes(roster: TeamRoster) -> dict[int, Any]:
    """A maker ``(unum, params, rng) -> DefenseNPC`` per NPC unum: agent2d's goalie for unum 1, agent2d's field
    defender for the others (ValueError while that port is missing)."""
    makers: dict[int, Any] = {}
    for unum in roster.defense_npcs:
        if unum == KEEPER_UNUM:
            from hfo2d.agent2d.goalie import Agent2dGoalie

            makers[unum] = lambda _unum, params, rng: Agent2dGoalie(params, rng)
        else:
            makers[unum] = _defender_maker()
    return makers


def _defender_maker() -> Any:
    try:
        from hfo2d.agent2d.defender import Agent2dDefender  # the field defenders' port (issue 34 item 2)
    except ModuleNotFoundError as error:
        if error.name != DEFENDER_MODULE:
            raise
        raise ValueError(
            f"defense NPCs other than the goalie are agent2d's field defenders, whose port ({DEFENDER_MODULE}."
            "Agent2dDefender) is not in this hfo2d yet: use defense_npcs <= 1 (the goalie), or defense_agents "
            "for the other defenders"
        ) from None
    return lambda unum, params, rng: Agent2dDefender(params, rng, unum=unum)


class HalfFieldOffenseEnv(gym.Env):
    """HFO's Half Field Offense with bin/HFO's team sizes, one learning agent (``HFO/HalfFieldOffense-v0``).

    ## Description

    The game of :class:`TeamGame` (its module docstring gives HFO's rules and their sources): ``offense_agents``
    strikers attack the right goal (x = +52.5) of the HFO half (x in [0, 52.5], |y| <= 34) against
    ``defense_npcs`` agent2d defenders (the first is HFO's goalie, :mod:`hfo2d.agent2d`) and ``defense_agents``
    learning defenders, one 100 ms rcssserver cycle per step. This env is one learning agent: the striker when
    ``offense_agents=1`` (``defense_agents=0``), or the defender when ``defense_agents=1`` (``offense_agents=0``;
    the offense is then ``scripted_strikers`` of :mod:`hfo2d.strikers`). Several learning agents:
    :func:`hfo2d.parallel_env` (PettingZoo) or ``sb3_hfo.multi_agent`` (one SB3 VecEnv of all the agents).

    ## Action Space

    A striker: ``Box(0, 1, (8,))``, HFO's flat action of the other hfo2d envs (``action_format="flat"``):
    [pref DASH, TURN, KICK, dash power, dash direction, turn direction, kick power, kick direction]; the largest
    preference picks the action, its parameters map onto power [0, 100] and direction [-180, 180] degrees relative
    to the body. A field defender: ``Box(0, 1, (10,))`` with DASH, TURN, TACKLE(direction), KICK; the goalie:
    ``Box(0, 1, (11,))`` with CATCH() as well (:data:`DEFENDER_FLAT_ACTION_LAYOUT`,
    :data:`GOALIE_FLAT_ACTION_LAYOUT`). ``action_format="parameterized"``: ``Tuple(Discrete(n), Box(parameters)
    of each action that has any)`` in HFO's units. Commands pass through librcsc's client rules (TURN asks for the
    actual turn, KICK needs the ball within 1.03 m, no command while frozen by one's own tackle).

    ## Observation Space

    HFO's low-level features, fullstate, in [-1, 1] (:mod:`hfo2d.features`): 58 basic features plus one 8-feature
    block per teammate and per opponent, nearest first (``feature_set="paper"``), or HFO master's layout, 58 + 9
    per other player + 1 (``feature_set="hfo"``), or HFO's high-level features (``feature_set="high_level"``,
    where hfo2d has them). 2 strikers against 2 defenders: 82 (paper) / 86 (hfo). A defender sees the field in its
    own frame, as librcsc shows a right-side player (so HFO lists no other player in its low-level blocks while
    everyone is in the HFO half).

    ## Rewards

    A striker (``reward``): ``"shaped"`` (default), Hausknecht & Stone's shaping from its own features (move to
    the ball, +1 the first time kickable, 3 x the ball's progress to the goal, +5 on a goal), ``"shaped_gap"`` /
    ``"shaped_gap_refund"`` (the progress measured to the gap beside the goalie, lost shots refunded:
    :mod:`hfo2d.reward`), ``"carry"`` / ``"carry_shot"`` (the carry and shot records of :mod:`hfo2d.reward`),
    ``"shaped_gap_refund_nearest"`` / ``"carry_shot_nearest"`` (the same, with the move-to-ball and kick terms
    paid only to the striker nearest the ball), or ``"sparse"`` (1 on a goal). A defender (``defense_reward``): ``"sparse"`` (default) +1 when the episode ends in
    CAPTURED_BY_DEFENSE, OUT_OF_BOUNDS or OUT_OF_TIME, -1 on a GOAL; ``"shaped"`` adds its move-to-ball term.

    ## Starting State

    HFO's (rcssserver ``HFORef::resetField``, bin/HFO defaults): the ball at x ~ U(0, 10.5), y ~ U(-27.2, 27.2);
    each striker at the ball plus 10.5 m times (U(0, 1) + one of HFO's ten shuffled offsets) per axis, clamped;
    the goalie at (52.5, 0), other defenders at x ~ U(42, 52.5), y ~ U(-27.2, 27.2). The agents' body angles are
    drawn from U(-180, 180); everyone's stamina is full. The NPCs play two cycles before the first observation.

    ## Episode End

    rcssserver's HFO referee (:class:`hfo2d.referee.Referee`, rules "rcssserver"): GOAL; OUT_OF_BOUNDS (the
    ball left the HFO half); CAPTURED_BY_DEFENSE (the goalie near the ball, or another defender holding it for 2
    cycles); OUT_OF_TIME after ``untouched_time`` cycles without anyone near the ball (terminated) or
    ``frames_per_trial`` cycles (truncated). ``info["status"]`` names it.

    ## Arguments

    ``gym.make("HFO/HalfFieldOffense-v0", offense_agents=1, defense_agents=0, defense_npcs=1, ...)``, with
    bin/HFO's flags as keywords: ``offense_agents``, ``defense_agents``, ``defense_npcs``,
    ``agent_play_goalie`` (``--agent-play-goalie``), ``frames_per_trial`` (default 500), ``untouched_time``
    (100), ``noise`` (False: ``--deterministic``); and hfo2d's ``render_mode`` (None, "human", "rgb_array"),
    ``action_format``, ``feature_set``, ``reward``, ``defense_reward``, ``server_params``; ``scripted_strikers`` (hfo2d's scripted strikers where
    bin/HFO puts offense NPCs; agent2d's offense, ``offense_npcs``, is not ported) and ``striker`` (which one).
    Exactly one of ``offense_agents`` and ``defense_agents`` is 1, the other 0. ``reset(seed=s)`` repeats an
    episode exactly; without a seed the NPCs' state carries over from the last episode as in real HFO.
    ``reset`` takes no options (no hand placements yet).

    ## Version History

    * v0: initial version (HFO's team sizes; agent2d's goalie as the first defense NPC). Later additions that
      change no existing setting: the rewards ``"carry"``, ``"carry_shot"`` and ``"carry_shot_nearest"``.
    """

    metadata = {"render_modes": ["human", "rgb_array"], "render_fps": 10}

    def __init__(
        self,
        offense_agents: int = 1,
        defense_agents: int = 0,
        defense_npcs: int = 0,
        *,
        render_mode: str | None = None,
        **game_kwargs: Any,
    ) -> None:
        check_render_mode(render_mode, self.metadata["render_modes"])
        learning = (offense_agents, defense_agents)
        if learning not in ((1, 0), (0, 1)):
            raise ValueError(
                "HFO/HalfFieldOffense-v0 is one learning agent: offense_agents=1, defense_agents=0 (a striker) or "
                f"offense_agents=0, defense_agents=1 (a defender), got offense_agents={offense_agents!r}, "
                f"defense_agents={defense_agents!r}; several learning agents: hfo2d.parallel_env(...)"
            )
        self.game = TeamGame(offense_agents, defense_agents, defense_npcs, **game_kwargs)
        self.render_mode = render_mode
        self.agent_name = self.game.agent_names[0]
        learner = self.game.agent(self.agent_name)
        self.observation_space = learner.observation_space
        self.action_space = learner.action_space
        self._np_random = self.game.np_random

    def reset(
        self, *, seed: int | None = None, options: Mapping[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        """Start an episode (see Starting State); returns (observation, info)."""
        if options:
            raise ValueError(f"HFO/HalfFieldOffense-v0's reset takes no options yet, got {dict(options)!r}")
        observations, infos = self.game.reset(seed=seed)
        self._np_random = self.game.np_random
        if self.render_mode == "human":
            self.render()
        return observations[self.agent_name], infos[self.agent_name]

    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        """One cycle: (observation, reward, terminated, truncated, info)."""
        observations, rewards, terminated, truncated, infos = self.game.step({self.agent_name: action})
        if self.render_mode == "human":
            self.render()
        name = self.agent_name
        return observations[name], rewards[name], terminated, truncated, infos[name]

    def render(self) -> np.ndarray | None:
        """Every player and the ball: a window ("human") or an RGB array ("rgb_array")."""
        if self.render_mode is None:
            gym.logger.warn(
                "You are calling render method without specifying any render mode, e.g. gym.make("
                '"HFO/HalfFieldOffense-v0", render_mode="rgb_array")'
            )
            return None
        return self.game.render(self.render_mode)

    def close(self) -> None:
        """Close the render window, if any."""
        self.game.close()
