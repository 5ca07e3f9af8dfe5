"""Gymnasium environment for RoboCup Half Field Offense (1v0 and 1v1 against a goalie) on the hfo2d simulator.

The env plays the agent against a list of defense NPCs (:mod:`hfo2d.npc`; today at most the goalie), judged by one
:class:`hfo2d.referee.Referee`; HFO's protocol (statuses, action bounds, episode rules, start state) lives in
:mod:`hfo2d.protocol`, whose names this module re-exports.
"""

from __future__ import annotations

import math
import struct
from collections.abc import Mapping, Sequence
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from hfo2d.action_layout import ACTION_NAMES, DASH, HFO_FLAT_ACTION_LAYOUT, KICK, TURN, hfo_flat_action_space
from hfo2d.features import (
    KICKABLE_BUFFER,
    hfo_feature_list,
    hfo_num_features,
    high_level_bounds,
    high_level_feature_list,
    num_features,
    paper_feature_list,
)
from hfo2d.npc import DefenseNPC, StillGoalie
from hfo2d.physics import PlayerState, ServerParams, World
from hfo2d.protocol import (
    AGENT2D_FIRST_BODY_DEGS,
    AGENT2D_FIRST_OBSERVATION_DELAY,
    AGENT_SIDE,
    AGENT_UNUM,
    BALL_X_RANGE,
    BALL_Y_RANGE,
    CAPTURED_BY_DEFENSE,
    DEFAULT_FRAMES_PER_TRIAL,
    DEFAULT_UNTOUCHED_TIME,
    DIRECTION_MAX,
    DIRECTION_MIN,
    GOAL,
    GOAL_LINE_X,
    GOAL_MOUTH_HALF_WIDTH,
    IN_GAME,
    KEEPER_SIDE,
    KEEPER_START,
    KEEPER_START_BODY_DEG,
    KEEPER_UNUM,
    OFFENSE_OFFSETS,
    OFFENSE_SPREAD,
    OFFENSE_X_RANGE,
    OFFENSE_Y_RANGE,
    OUT_OF_BOUNDS,
    OUT_OF_TIME,
    PITCH_MARGIN,
    PLACEMENT_MAX_X,
    PLACEMENT_MAX_Y,
    POWER_MAX,
    POWER_MIN,
    TURNOVER_TIME,
)
from hfo2d.referee import Referee
from hfo2d.reward import REWARD_NAMES, make_reward

# The protocol's names this module has always offered (hfo2d.protocol holds them now)
__all__ = [
    "ACTION_FORMATS",
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
    "DIRECTION_MAX",
    "DIRECTION_MIN",
    "FEATURE_SETS",
    "FLAT_ACTION_DIRECTIONS",
    "FLAT_ACTION_SIZE",
    "GOAL",
    "GOALIES",
    "GOAL_LINE_X",
    "GOAL_MOUTH_HALF_WIDTH",
    "HFOEnv",
    "IN_GAME",
    "KEEPER_SIDE",
    "KEEPER_START",
    "KEEPER_START_BODY_DEG",
    "KEEPER_UNUM",
    "KICK",
    "OFFENSE_OFFSETS",
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
    "RESET_OPTION_LENGTHS",
    "TASKS",
    "TURN",
    "TURNOVER_TIME",
    "check_render_mode",
]

# ---------------------------------------------------------------------------------------------------------------
# Tasks, action formats, goalies (HFO's protocol itself: hfo2d.protocol, whose names this module re-exports)
# ---------------------------------------------------------------------------------------------------------------
TASKS: tuple[str, ...] = ("empty_goal", "static_keeper", "keeper")
ACTION_FORMATS: tuple[str, ...] = ("flat", "parameterized")
#: Observation layouts: the paper era's (58 / 66, the default), HFO master's (59 / 68) or HFO's high-level set
#: (12 / 15, :func:`hfo2d.features.high_level_feature_list`).
FEATURE_SETS: tuple[str, ...] = ("paper", "hfo", "high_level")
# [pref_dash, pref_turn, pref_kick, dash_power, dash_dir, turn_dir, kick_power, kick_dir]: the flat action's size
# and its three directions (dash_dir, turn_dir, kick_dir), from its layout (hfo2d.action_layout).
FLAT_ACTION_SIZE = HFO_FLAT_ACTION_LAYOUT.size
FLAT_ACTION_DIRECTIONS: tuple[int, ...] = HFO_FLAT_ACTION_LAYOUT.direction_indices
#: The goalies of task "keeper": hfo2d's own design (HFO/Keeper-v0) and HFO's agent2d goalie (HFO/Keeper-v1).
GOALIES: tuple[str, ...] = ("hfo2d", "agent2d")
# The referee's rules that go with each goalie's id: Keeper-v1 is judged as real HFO judges (rcssserver's HFORef,
# with real HFO's cycles between episodes and before the first observation), the v0 ids as they were measured.
_GOALIE_RULES: dict[str, str] = {"agent2d": "rcssserver", "hfo2d": "hfo2d_v0"}

RESET_OPTION_LENGTHS: dict[str, tuple[int, ...]] = {
    "player": (3, 5),  # (x, y, body_deg[, vx, vy])
    "ball": (2, 4),  # (x, y[, vx, vy])
    "keeper": (3,),  # (x, y, body_deg)
}


class HFOEnv(gym.Env):
    """RoboCup Half Field Offense: one striker against an empty goal or a goalie, at rcssserver's cycle rate.

    One offense agent (left side, unum 11) attacks the right goal (x = +52.5) of the HFO half, x in [0, 52.5],
    |y| <= 34. Units are rcssserver's: metres, m/cycle, degrees, +x toward the goal, +y down the screen, a positive
    relative angle to the agent's right. One step is one 100 ms server cycle. Physics: :class:`hfo2d.physics.World`.

    Tasks (``task``): ``"empty_goal"`` (1v0, ``HFO/EmptyGoal-v0``), ``"static_keeper"`` (a goalie on the goal line
    that never moves, ``HFO/StaticKeeper-v0``), ``"keeper"`` (a scripted goalie whose quality is set by
    ``keeper_skill`` in [0, 1]: with ``goalie="agent2d"`` HFO's own goalie, :mod:`hfo2d.agent2d`,
    ``HFO/Keeper-v1``; with ``goalie="hfo2d"`` this project's earlier design, :mod:`hfo2d.keeper`,
    ``HFO/Keeper-v0``).

    Observation:
        ``Box(-1, 1, (58,), float32)`` for ``empty_goal``, ``(66,)`` with a goalie: HFO's paper-era low-level
        features, fullstate (see :mod:`hfo2d.features` for encodings and normalisers).
        With ``feature_set="hfo"``: ``(59,)`` / ``(68,)``, HFO master's layout of the same state
        (:func:`hfo2d.features.hfo_feature_list`): proximities over 85.908 m, out-of-bounds over 57.75 / 71.4 m,
        the goalie's uniform number / 100 (0.01; -1 while it is not listed) at 66, and last at 58 / 67 the last
        action's status (+1, or -1 for a KICK out of reach; -1 after reset). With ``feature_set="high_level"``:
        ``(12,)`` / ``(15,)``, HFO's high-level features (:func:`hfo2d.features.high_level_feature_list`; -2 marks
        an invalid entry, the goalie's uniform number is 1). Rewards and ``info`` are computed from the paper
        features either way; :func:`hfo2d.features.paper_from_hfo` converts HFO master's.

        ======= =========================================================================
        index   feature
        ======= =========================================================================
        0, 1    self position / velocity valid (always +1)
        2, 3    sin, cos of (body angle - own velocity heading)
        4       own speed over [0, 0.46] m/cycle
        5, 6    sin, cos of the global body angle
        7       stamina over [0, 8000]
        8       frozen (always -1: nobody tackles)
        9-11    colliding with ball / player / goal post (+1 / -1)
        12      kickable (ball centre within 1.03 m, librcsc's test)
        13-15   goal centre (52.5, 0): sin, cos of its bearing, proximity 1 - 2 d / 62.55
        16-18   top goal post (52.5, -7.01)
        19-21   bottom goal post (52.5, 7.01)
        22-24   penalty box centre (36, 0)
        25-27   penalty box top corner (36, -20.16)
        28-30   penalty box bottom corner (36, 20.16)
        31-33   centre field (0, 0)
        34-36   corner top-left (0, -34)
        37-39   corner top-right (52.5, -34)
        40-42   corner bottom-right (52.5, 34)
        43-45   corner bottom-left (0, 34)
        46      left line proximity  1 - 2 min(x / 52.5, 1) (> 0 in the half away from goal)
        47      right line proximity 1 - 2 min((52.5 - x) / 52.5, 1)
        48      top line proximity   1 - 2 min((34 + y) / 68, 1)
        49      bottom line proximity 1 - 2 min((34 - y) / 68, 1)
        50      ball position valid (+1)
        51-53   ball: sin, cos of its bearing, proximity over 62.55 m
        54      ball velocity valid (+1)
        55      ball speed over [0, 5] m/cycle
        56, 57  sin, cos of the ball's velocity heading
        58-60   goalie: sin, cos of its bearing, proximity (goalie tasks; zeros while its x <= 0)
        61, 62  goalie: sin, cos of its body angle
        63      goalie: speed over [0, 0.75] m/cycle
        64, 65  goalie: sin, cos of its velocity heading
        ======= =========================================================================

    Action (``action_format``):
        ``"flat"`` (default): ``Box(0, 1, (8,), float32)`` = [pref_dash, pref_turn, pref_kick, dash_power, dash_dir,
        turn_dir, kick_power, kick_dir]. The largest preference picks the action (ties: the first); its parameters
        map linearly onto power [0, 100] and direction [-180, 180] degrees relative to the body.
        ``"parameterized"``: gym-soccer's ``Tuple(Discrete(3) {0 DASH, 1 TURN, 2 KICK}, Box([0, -180], [100, 180])
        dash power and direction, Box([-180], [180]) turn, Box([0, -180], [100, 180]) kick power and direction)``.
        The commands are processed as HFO's agent (librcsc) does before the server sees them: TURN asks for the
        actual turn, the dash direction is rounded to 45 degrees, KICK fails when the ball is beyond 1.03 m.
        Invalid actions (wrong shape, NaN / inf, outside the space) raise ValueError and leave the state unchanged.

    Reward (``reward``):
        ``"shaped"`` (default): Hausknecht & Stone's, computed as DQNHFO does from the features (see
        :mod:`hfo2d.reward`): Δ ball proximity + 1 on the first kickable step + 3 × ball-to-goal progress + 5 on a
        goal, deltas zero on the first and last step of an episode. ``"shaped_gap"`` (not HFO's): the same with the
        ball's progress measured toward the middle of the wider goalie-post gap (the goal centre without a goalie).
        ``"shaped_gap_refund"`` (not HFO's): ``"shaped_gap"`` whose last step, when an episode ends without a goal,
        takes back the progress paid since the ball was last kickable by the agent (a lost shot pays nothing).
        ``"carry"`` (not HFO's): the shaped reward whose ball-to-goal term pays only new records of the ball's
        closeness to the goal set with the ball within 2 m of the agent, less 0.002 a cycle (``cycle_cost``).
        ``"carry_shot"`` (not HFO's): ``"carry"`` plus a record of the ball's speed after a kick within 12 m of
        the goal centre whose path crosses the goal mouth (``shot``).
        ``"sparse"``: 1 for a goal, else 0.
        ``info["reward_terms"]`` holds each term.

    Episode end (HFO's referee, checked after each cycle in this order):
        1. GOAL: the ball's centre crossed x = 52.585 during the cycle with interpolated |y| <= 7.07.
        2. OUT_OF_BOUNDS: the ball's position at the start of the cycle lay outside x in [0, 52.5], |y| <= 34.
        3. CAPTURED_BY_DEFENSE: the goalie is within 1.085 m of the ball (it becomes the player on ball), or a
           defender held the ball for 2 cycles.
        4. OUT_OF_TIME: more than ``untouched_time`` (100) cycles without any player within 1.085 m of the ball.
        These set ``terminated``. After ``frames_per_trial`` (500) steps the episode is ``truncated`` with status
        OUT_OF_TIME. No TimeLimit wrapper is registered. Once an episode has ended, ``step`` raises
        RuntimeError ("call reset()") and changes nothing.

    Starting state (HFO's resetField, bin/HFO defaults; all draws from ``self.np_random``):
        the ball at rest at x ~ U(0, 10.5), y ~ U(-27.2, 27.2); the agent at ``ball + 10.5 · (U(0, 1) + o)`` per
        axis with ``o`` one of HFO's ten offsets, x clamped to [-0.1, 52.5] and y to [-27.2, 27.2], at rest, body
        angle ~ U(-180, 180); the goalie at (52.5, 0) facing the field. Stamina, effort and recovery are restored.
        ``reset(options=...)`` may place things by hand: ``{"player": (x, y, body_deg[, vx, vy]),
        "ball": (x, y[, vx, vy]), "keeper": (x, y, body_deg)}``, on the pitch or within rcssserver's 5 m margin
        of it (|x| <= 57.5, |y| <= 39), with no two of the placed bodies (and the goalie's start) overlapping.

    Info (every step): ``status``; ``is_success`` (status is GOAL); ``player`` (x, y, vx, vy, body_deg); ``ball`` (x, y, vx, vy); ``keeper``
    (x, y, vx, vy, body_deg) with a goalie; ``reward_terms``; ``action`` ("DASH" / "TURN" / "KICK");
    ``action_success`` (False for a KICK out of reach); ``kickable`` (1.03 m rule); ``kick_power`` (power of the
    executed kick, else 0). ``reset`` returns the same keys except the action ones.

    Args:
        task: one of TASKS.
        render_mode: None, "human" (pygame window, drawn every step) or "rgb_array".
        action_format: "flat" or "parameterized".
        feature_set: "paper" (default, the table above), "hfo" (HFO master's 59 / 68 features) or "high_level"
            (HFO's high-level features, 12 / 15).
        reward: "shaped", "shaped_gap", "shaped_gap_refund", "carry", "carry_shot" or "sparse".
        noise: False turns off player, ball and kick noise (HFO's --deterministic); a bool.
        server_params: rcssserver parameter overrides by name, e.g. ``{"player_rand": 0.0}`` (a mapping; each
            value range-checked, :data:`hfo2d.physics.SERVER_PARAM_RANGES`).
        keeper_skill: goalie quality for task "keeper", in [0, 1] (default 1: the full goalie); an error for the
            other tasks, which have no scripted goalie.
        goalie: the goalie of task "keeper": "agent2d" (HFO's, ``HFO/Keeper-v1``) or "hfo2d" (``HFO/Keeper-v0``).
            With "agent2d" the goalie's body angle, catch ban and catch time carry over from one episode to the
            next as in real HFO (one wait cycle is played after each episode), except after ``reset(seed=...)``,
            which starts the goalie afresh so that a seed repeats; its first body angle faces its own goal or the
            field (drawn). As in real HFO, the goalie plays two cycles after the placement before the agent's first
            observation, and rcssserver's HFO referee judges the episode (:class:`hfo2d.referee.Referee`, rules
            "rcssserver": the untouched limit is checked before the cycle's count; the trial ends on cycle
            ``frames_per_trial + 1``, counted from the placement, i.e. after ``frames_per_trial - 1`` agent steps,
            as a truncation). The other ids are judged as described above (rules "hfo2d_v0").
        frames_per_trial: steps after which an episode is truncated.
        untouched_time: cycles without a player near the ball after which the episode ends.
        start_shift: metres, in [0, MAX_START_SHIFT], added to the ball's start x (toward the goal; the agent's
            start follows the ball's by HFO's offsets). 0 (default) is HFO's start distribution; more starts the
            play closer to the goal: a start-distance curriculum for training (``set_start_shift``), not HFO.

    Version History:
        * v1 (``HFO/Keeper-v1`` only): the goalie is HFO's own (agent2d's, with librcsc's intercept table, body
          actions, catch and tackle), the catch is part of the physics (rcssserver's catchable area, ban cycles),
          and the goalie's body angle and bans carry over between episodes. Checked against a real HFO build
          (see ``benchmarks/keeper_fidelity.py``). ``HFO/EmptyGoal-v0`` and ``HFO/StaticKeeper-v0`` are unchanged.
        * v0: initial version; ``HFO/Keeper-v0`` keeps this project's own goalie design unchanged, so that figures
          measured on it stay reproducible.
    """

    metadata = {"render_modes": ["human", "rgb_array"], "render_fps": 10}

    def __init__(
        self,
        task: str = "empty_goal",
        render_mode: str | None = None,
        action_format: str = "flat",
        reward: str = "shaped",
        noise: bool = True,
        server_params: Mapping[str, float] | None = None,
        keeper_skill: float | None = None,
        goalie: str = "hfo2d",
        frames_per_trial: int = DEFAULT_FRAMES_PER_TRIAL,
        untouched_time: int = DEFAULT_UNTOUCHED_TIME,
        feature_set: str = "paper",
        start_shift: float = 0.0,
    ) -> None:
        if task not in TASKS:
            raise ValueError(f"unknown task {task!r}; choose one of {TASKS}")
        if action_format not in ACTION_FORMATS:
            raise ValueError(f"unknown action_format {action_format!r}; choose one of {ACTION_FORMATS}")
        if feature_set not in FEATURE_SETS:
            raise ValueError(f"unknown feature_set {feature_set!r}; choose one of {FEATURE_SETS}")
        if reward not in REWARD_NAMES:
            raise ValueError(f"unknown reward {reward!r}; choose one of {REWARD_NAMES}")
        check_render_mode(render_mode, self.metadata["render_modes"])
        if keeper_skill is not None:
            _check_keeper_skill(keeper_skill)
            if task != "keeper":
                raise ValueError(
                    f"keeper_skill is for task 'keeper' (HFO/Keeper-v0, HFO/Keeper-v1) only; task {task!r} has no "
                    "scripted goalie"
                )
        if not isinstance(noise, (bool, np.bool_)):
            raise ValueError(f"noise must be True or False, got {noise!r}")
        if goalie not in GOALIES:
            raise ValueError(f"unknown goalie {goalie!r}; choose one of {GOALIES}")
        if goalie != "hfo2d" and task != "keeper":
            raise ValueError(f"goalie={goalie!r} needs task 'keeper'; task {task!r} has no scripted goalie")
        for name, value in (("frames_per_trial", frames_per_trial), ("untouched_time", untouched_time)):
            if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
                raise ValueError(f"{name} must be a positive integer, got {value!r}")

        self.task = task
        self.render_mode = render_mode
        self.action_format = action_format
        self.feature_set = feature_set
        self._hfo_layout = feature_set != "paper"  # the observation is a vector of HFO's own layouts
        self.reward_name = reward
        self.noise = bool(noise)
        self.keeper_skill = 1.0 if keeper_skill is None else float(keeper_skill)
        _check_start_shift(start_shift)
        self.start_shift = float(start_shift)
        self.goalie = goalie
        self.params: ServerParams = ServerParams.with_overrides(server_params)
        self.has_keeper = task != "empty_goal"
        self._kickable_distance = self.params.kickable_area - KICKABLE_BUFFER

        n_opponents = 1 if self.has_keeper else 0
        if feature_set == "high_level":
            low, high = high_level_bounds(0, n_opponents)
            n_features = len(low)
            self.observation_space = spaces.Box(
                np.array(low, dtype=np.float32), np.array(high, dtype=np.float32), dtype=np.float32
            )
        else:
            n_features = (
                hfo_num_features(0, n_opponents) if self._hfo_layout else num_features(0, n_opponents)
            )
            self.observation_space = spaces.Box(-1.0, 1.0, shape=(n_features,), dtype=np.float32)
        # step()'s packer of the observation (see _observation)
        self._observation_packer = struct.Struct(f"={n_features}f")
        if action_format == "flat":
            self.action_space: spaces.Space = hfo_flat_action_space()
        else:
            self.action_space = spaces.Tuple(
                (
                    spaces.Discrete(3),
                    spaces.Box(
                        np.array([POWER_MIN, DIRECTION_MIN], dtype=np.float32),
                        np.array([POWER_MAX, DIRECTION_MAX], dtype=np.float32),
                        dtype=np.float32,
                    ),
                    spaces.Box(
                        np.array([DIRECTION_MIN], dtype=np.float32),
                        np.array([DIRECTION_MAX], dtype=np.float32),
                        dtype=np.float32,
                    ),
                    spaces.Box(
                        np.array([POWER_MIN, DIRECTION_MIN], dtype=np.float32),
                        np.array([POWER_MAX, DIRECTION_MAX], dtype=np.float32),
                        dtype=np.float32,
                    ),
                )
            )

        self._reward_fn = make_reward(reward)
        # The world and its players live as long as the env; reset() re-places them and hands them the env's
        # (possibly reseeded) generator, so references to env.world / env.agent stay valid across episodes.
        rng = self.np_random
        self.world: World = World(self.params, rng, noise=self.noise)
        self.agent: PlayerState = self.world.add_player(AGENT_SIDE, AGENT_UNUM)
        self.keeper: PlayerState | None = None
        #: The defense's scripted players (HFO's NPCs), each with the player it moves, the goalie first.
        self.defense_npcs: list[tuple[PlayerState, DefenseNPC]] = []
        if self.has_keeper:
            self.keeper = self.world.add_player(KEEPER_SIDE, KEEPER_UNUM, goalie=True)
            self.defense_npcs.append((self.keeper, self._make_goalie(rng)))
        rules = _GOALIE_RULES[goalie] if task == "keeper" else "hfo2d_v0"
        #: HFO's referee, judging every player of the world.
        self.referee = Referee(
            self.params, int(untouched_time), trial_time=int(frames_per_trial), rules=rules
        )
        # Real HFO's timing (rules "rcssserver"): the server runs on between episodes, so one cycle is played after
        # each episode and the NPCs' client state carries over; the agent first observes a few cycles after the
        # placement. hfo2d's v0 ids start each episode afresh and observe at once.
        self._server_runs_on = rules == "rcssserver"
        self._first_observation_delay = AGENT2D_FIRST_OBSERVATION_DELAY if self._server_runs_on else 0
        self._opponents: tuple[PlayerState, ...] = (self.keeper,) if self.keeper is not None else ()
        self._rng_in_use = rng
        self._renderer: Any = None
        self._needs_reset = True
        self._episode_started = False
        self._episode_over = False  # the episode has terminated or been truncated: step() needs a reset()
        # for the render overlay: episodes started and ended, goals, (number, status) of the last ended episode
        self._episode_number = 0
        self._episodes_ended = 0
        self._goals = 0
        self._last_end: tuple[int, str] | None = None
        self._steps = 0
        self._status = IN_GAME

    # ------------------------------------------------------------------------------------------------------------
    # Gymnasium API
    # ------------------------------------------------------------------------------------------------------------
    def reset(
        self, *, seed: int | None = None, options: Mapping[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        """Start an episode (HFO resetField; see the class docstring). Returns (observation, info)."""
        placements = self._parse_reset_options(options)
        super().reset(seed=seed)
        rng = self.np_random
        world = self.world
        agent = self.agent
        defense = self.defense_npcs
        if rng is not self._rng_in_use:  # reseeded: every random draw must come from the new generator
            world.rng = rng
            for _, npc in defense:
                npc.rng = rng
            self._rng_in_use = rng
        # the server's state (bodies, bans) and the NPCs' carry over from the last episode, as in real HFO
        carry_over = self._server_runs_on and seed is None and self._episode_started
        if carry_over:
            self._wait_frame()
        elif seed is not None and self._episode_started:
            # reset(seed=...) repeats: the NPCs start as in a fresh env, without real HFO's carry-over
            for _, npc in defense:
                if npc.carries_over:
                    npc.restart()
            self._clear_server_state()

        ball_x = rng.uniform(*BALL_X_RANGE) + self.start_shift
        ball_y = rng.uniform(*BALL_Y_RANGE)
        offset_x, offset_y = OFFENSE_OFFSETS[int(rng.integers(len(OFFENSE_OFFSETS)))]
        agent_x = min(
            max(ball_x + OFFENSE_SPREAD * (rng.uniform() + offset_x), OFFENSE_X_RANGE[0]), OFFENSE_X_RANGE[1]
        )
        agent_y = min(
            max(ball_y + OFFENSE_SPREAD * (rng.uniform() + offset_y), OFFENSE_Y_RANGE[0]), OFFENSE_Y_RANGE[1]
        )
        agent_body = rng.uniform(-180.0, 180.0)

        ball = placements.get("ball", (ball_x, ball_y, 0.0, 0.0))
        world.place_ball(*ball)
        player = placements.get("player", (agent_x, agent_y, agent_body, 0.0, 0.0))
        world.place_player(agent, *player)
        for npc_player, npc in defense:  # (the goalie alone, today)
            # real HFO never resets a body angle (HFORef::resetField): it carries over, or the NPC's own start
            body = npc_player.body_deg if carry_over else npc.start_body_deg(rng)
            world.place_player(npc_player, *placements.get("keeper", (*KEEPER_START, body)))
        world.recover_players()
        # collisions of the last episode's final cycle are not part of the new one
        for placed in world.players:
            placed.collided_ball = placed.collided_player = placed.collided_post = False
        world.ball.collided_post = False
        for _, npc in defense:  # (keeper_skill is the goalie's: the only NPC today)
            if npc.skill != self.keeper_skill:  # set_keeper_skill() was called
                npc.set_skill(self.keeper_skill)
            npc.reset()
        self._steps = 0
        self._status = IN_GAME
        self._needs_reset = False
        self._episode_started = True
        referee = self.referee
        referee.reset(world)
        # Real HFO's agent gets its first observation two cycles after the trainer places the players (measured
        # with hfo2d.real); the NPCs play those cycles, the agent sends nothing.
        for _ in range(self._first_observation_delay):
            for player, npc in defense:
                npc.act(world, player)
            world.step()
            referee.analyse(world)
        self._episode_over = False
        self._episode_number += 1
        features = self._features()
        self._reward_fn.reset(features)
        info = self._info(features)
        info["reward_terms"] = dict.fromkeys(self._reward_fn.term_names, 0.0)
        if self.render_mode == "human":
            self.render()
        # HFO's agent starts with its last action status false (agent.cpp)
        observation = self._hfo_features(False) if self._hfo_layout else features
        return _observation(observation), info

    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        """Advance one server cycle: agent command, goalie command, physics, referee, features, reward."""
        if self._needs_reset:
            raise RuntimeError("call reset() before step()")
        if self._episode_over:
            raise RuntimeError(f"the episode has ended ({self._status}): call reset() before step()")
        world = self.world
        agent = self.agent
        # (_parse_action's dispatch, one call fewer on the hot path)
        if self.action_format == "flat":
            kind, power, direction = self._parse_flat_action(action)
        else:
            kind, power, direction = self._parse_parameterized_action(action)
        defense = self.defense_npcs
        # the NPCs decide on the state after the last step, before this cycle's commands arrive (a turn of the
        # agent changes its body angle at once in World)
        for player, npc in defense:
            npc.decide(world, player)

        success = True
        kick_power = 0.0
        if kind == DASH:
            world.client_dash(agent, power, direction)
        elif kind == TURN:
            world.client_turn(agent, direction)
        else:
            success = bool(world.client_kick(agent, power, direction))
            if success:
                kick_power = min(max(power, POWER_MIN), POWER_MAX)
        for player, npc in defense:
            npc.apply(world, player)  # what it decided above

        world.step()
        self._steps += 1

        referee = self.referee
        status = referee.analyse(world)
        truncated = referee.truncated
        terminated = status != IN_GAME and not truncated
        self._status = status
        if terminated or truncated:
            self._episode_over = True
            self._episodes_ended += 1
            self._goals += status == GOAL
            self._last_end = (self._episode_number, status)

        # (self._features(), one call fewer)
        features = paper_feature_list(agent, world.ball, self._kickable_distance, (), self._opponents)
        reward, terms = self._reward_fn(features, status, terminated)
        info = self._info(features)
        info["reward_terms"] = terms
        info["action"] = ACTION_NAMES[kind]
        info["action_success"] = success
        info["kick_power"] = kick_power
        if self.render_mode == "human":
            self.render()
        observation = self._hfo_features(success) if self._hfo_layout else features
        # _observation(observation), with the packer of this env's feature count
        observation_array = np.frombuffer(self._observation_packer.pack(*observation), np.float32).copy()
        return observation_array, reward, terminated, truncated, info

    def _wait_frame(self) -> None:
        """Real HFO plays one more cycle after an episode ends and before the next reset; the NPCs act in it
        (their body angles and bans carry over), the agent's command is not sent to an episode that has ended."""
        for player, npc in self.defense_npcs:
            npc.act(self.world, player)
        self.world.step()

    def _clear_server_state(self) -> None:
        """The goalie's server-side timers as in a fresh server (catch ban, tackle freeze)."""
        for player in self.world.players:
            for timer in ("catch_ban", "tackle_cycles"):
                if hasattr(player, timer):
                    setattr(player, timer, 0)

    def _make_goalie(self, rng: np.random.Generator) -> DefenseNPC:
        """The goalie NPC of this env's task and ``goalie``."""
        if self.task != "keeper":
            return StillGoalie(self.params, rng, skill=self.keeper_skill)
        if self.goalie == "agent2d":
            from hfo2d.agent2d.goalie import Agent2dGoalie  # only HFO/Keeper-v1 needs it

            return Agent2dGoalie(self.params, rng, skill=self.keeper_skill)
        from hfo2d.keeper import ScriptedKeeper  # only HFO/Keeper-v0 needs it

        return ScriptedKeeper(self.params, rng, skill=self.keeper_skill)

    @property
    def _keeper_policy(self) -> DefenseNPC | None:
        """The goalie NPC (None without a goalie); the name older tests and tools read."""
        return self.defense_npcs[0][1] if self.defense_npcs else None

    def set_keeper_skill(self, skill: float) -> None:
        """Change the scripted goalie's quality (task "keeper" only), in [0, 1]; effective from the next reset.

        For training curricula (``sb3_hfo.callbacks.KeeperSkillCurriculumCallback`` calls it through the VecEnv's
        ``env_method``); an episode in progress keeps the keeper it started with.
        """
        if self.task != "keeper":
            raise ValueError(
                f"set_keeper_skill needs task 'keeper' (HFO/Keeper-v0), this env's task is {self.task!r}"
            )
        _check_keeper_skill(skill)
        self.keeper_skill = float(skill)

    def set_start_shift(self, metres: float) -> None:
        """Move the ball's start range ``metres`` toward the goal (see ``start_shift``); from the next reset.

        For start-distance curricula (``sb3_hfo.callbacks.GoalRateStartShiftCallback`` calls it through the VecEnv's
        ``env_method``); an episode in progress keeps its start.
        """
        _check_start_shift(metres)
        self.start_shift = float(metres)

    def render(self) -> np.ndarray | None:
        """Draw the current state: a pygame window ("human") or an RGB array (H, W, 3) uint8 ("rgb_array").

        An overlay shows the episode number, the cycle within it, the goals so far and, once it has ended, its
        status (:class:`hfo2d.rendering.Overlay`).
        """
        if self.render_mode is None:
            gym.logger.warn(
                "You are calling render method without specifying any render mode. "
                'You can specify the render_mode at initialization, e.g. gym.make("HFO/EmptyGoal-v0", '
                'render_mode="rgb_array")'
            )
            return None
        if self._needs_reset:
            raise RuntimeError("call reset() before render()")
        if self._renderer is None:
            from hfo2d.rendering import HFORenderer  # pygame is imported only when rendering

            self._renderer = HFORenderer(self.render_mode, self.params)
        return self._renderer.render(self.world, self._overlay())

    def _overlay(self) -> Any:
        """The renderer's overlay: episode, cycle in it, goals so far, the end status."""
        from hfo2d.rendering import Overlay

        last = self._last_end
        over = self._episode_over
        return Overlay(
            episode=self._episode_number,
            cycle=self._steps,
            goals=self._goals,
            ended=self._episodes_ended,
            status=self._status if over else None,
            previous=last if last is not None and not over else None,
        )

    def close(self) -> None:
        """Close the render window, if any."""
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None

    def __getstate__(self) -> dict[str, Any]:
        """The env's state for pickle (resumable training checkpoints it mid-episode): everything but the
        observation packer (a ``struct.Struct``, which does not pickle; rebuilt from the observation space) and the
        render window (a new one opens at the next ``render()``)."""
        state = dict(self.__dict__)
        del state["_observation_packer"]
        state["_renderer"] = None
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)
        self._observation_packer = struct.Struct(f"={self.observation_space.shape[0]}f")

    # ------------------------------------------------------------------------------------------------------------
    # Internals
    # ------------------------------------------------------------------------------------------------------------
    @property
    def frames_per_trial(self) -> int:
        """Steps after which an episode is truncated (the referee's trial time)."""
        return self.referee.trial_time

    @frames_per_trial.setter
    def frames_per_trial(self, value: int) -> None:
        self.referee.trial_time = int(value)

    @property
    def untouched_time(self) -> int:
        """Cycles without a player near the ball after which the episode ends (the referee's)."""
        return self.referee.untouched_time

    @untouched_time.setter
    def untouched_time(self, value: int) -> None:
        self.referee.untouched_time = int(value)

    @property
    def status(self) -> str:
        """HFO status of the last step ("IN_GAME" after reset)."""
        return self._status

    @property
    def steps(self) -> int:
        """Steps taken in the current episode."""
        return self._steps

    def _hfo_features(self, last_action_succeeded: bool) -> list[float]:
        """HFO master's vector of the current state (feature_set \"hfo\"), or HFO's high-level one."""
        if self.feature_set == "high_level":
            return high_level_feature_list(
                self.agent,
                self.world.ball,
                self._kickable_distance,
                (),
                self._opponents,
                last_action_succeeded,
            )
        return hfo_feature_list(
            self.agent, self.world.ball, self._kickable_distance, (), self._opponents, last_action_succeeded
        )

    def _features(self) -> list[float]:
        return paper_feature_list(self.agent, self.world.ball, self._kickable_distance, (), self._opponents)

    def _info(self, features: Sequence[float]) -> dict[str, Any]:
        agent = self.agent
        ball = self.world.ball
        info: dict[str, Any] = {
            "status": self._status,
            # SB3's EvalCallback and evaluate_policy read this key to report a success rate.
            "is_success": self._status == GOAL,
            "player": (agent.x, agent.y, agent.vx, agent.vy, agent.body_deg),
            "ball": (ball.x, ball.y, ball.vx, ball.vy),
            "kickable": features[12] > 0.0,
        }
        keeper = self.keeper
        if keeper is not None:
            info["keeper"] = (keeper.x, keeper.y, keeper.vx, keeper.vy, keeper.body_deg)
        return info

    # --- input validation -----------------------------------------------------------------------------------------
    def _parse_action(self, action: Any) -> tuple[int, float, float]:
        """(action kind, power, direction) of a valid action; ValueError naming the problem otherwise."""
        if self.action_format == "flat":
            return self._parse_flat_action(action)
        return self._parse_parameterized_action(action)

    def _parse_flat_action(self, action: Any) -> tuple[int, float, float]:
        if type(action) is np.ndarray and action.shape == _FLAT_ACTION_SHAPE and action.dtype.kind == "f":
            values = action.tolist()
        else:
            values = _as_float_list(action, "flat action")
            if len(values) != FLAT_ACTION_SIZE:
                raise ValueError(f"flat action must have shape ({FLAT_ACTION_SIZE},), got {np.shape(action)}")
        dash_pref, turn_pref, kick_pref, dash_power, dash_dir, turn_dir, kick_power, kick_dir = values
        # every element in [0, 1] (a comparison with NaN is false), tested element by element: cheaper here than
        # min / max / sum over the list; the loop only names the bad element
        if not (
            0.0 <= dash_pref <= 1.0
            and 0.0 <= turn_pref <= 1.0
            and 0.0 <= kick_pref <= 1.0
            and 0.0 <= dash_power <= 1.0
            and 0.0 <= dash_dir <= 1.0
            and 0.0 <= turn_dir <= 1.0
            and 0.0 <= kick_power <= 1.0
            and 0.0 <= kick_dir <= 1.0
        ):
            for index, value in enumerate(values):
                if not 0.0 <= value <= 1.0:  # also rejects NaN
                    what = "not finite" if not math.isfinite(value) else "outside [0, 1]"
                    raise ValueError(f"flat action element {index} is {what}: {value!r}")
        # HFO_FLAT_ACTION_LAYOUT.decode written out for its layout (checked at import, below the class): the
        # largest preference, the first on ties; a step spends less on this than on the layout's generic loop
        if turn_pref > dash_pref:
            if kick_pref > turn_pref:
                return KICK, POWER_MAX * kick_power, DIRECTION_MIN + 360.0 * kick_dir
            return TURN, 0.0, DIRECTION_MIN + 360.0 * turn_dir
        if kick_pref > dash_pref:
            return KICK, POWER_MAX * kick_power, DIRECTION_MIN + 360.0 * kick_dir
        return DASH, POWER_MAX * dash_power, DIRECTION_MIN + 360.0 * dash_dir

    def _parse_parameterized_action(self, action: Any) -> tuple[int, float, float]:
        if not isinstance(action, (tuple, list)) or len(action) != 4:
            raise ValueError(
                "parameterized action must be a tuple (kind, (dash_power, dash_dir), (turn_dir,), "
                f"(kick_power, kick_dir)), got {action!r}"
            )
        kind_raw = action[0]
        if isinstance(kind_raw, np.ndarray) and kind_raw.shape == () and kind_raw.dtype.kind in "iu":
            kind_raw = kind_raw.item()
        if (
            isinstance(kind_raw, bool)
            or not isinstance(kind_raw, (int, np.integer))
            or not 0 <= kind_raw <= 2
        ):
            raise ValueError(
                f"parameterized action kind must be 0 (DASH), 1 (TURN) or 2 (KICK), got {kind_raw!r}"
            )
        kind = int(kind_raw)
        parsed: list[list[float]] = []
        for name, raw, lows, highs in (
            ("dash parameters", action[1], (POWER_MIN, DIRECTION_MIN), (POWER_MAX, DIRECTION_MAX)),
            ("turn parameters", action[2], (DIRECTION_MIN,), (DIRECTION_MAX,)),
            ("kick parameters", action[3], (POWER_MIN, DIRECTION_MIN), (POWER_MAX, DIRECTION_MAX)),
        ):
            values = _as_float_list(raw, name)
            if len(values) != len(lows):
                raise ValueError(f"{name} must have shape ({len(lows)},), got {np.shape(raw)}")
            for value, low, high in zip(values, lows, highs, strict=True):
                if not low <= value <= high:
                    what = "not finite" if not math.isfinite(value) else f"outside [{low:g}, {high:g}]"
                    raise ValueError(f"{name} value {value!r} is {what}")
            parsed.append(values)
        if kind == DASH:
            return DASH, parsed[0][0], parsed[0][1]
        if kind == TURN:
            return TURN, 0.0, parsed[1][0]
        return KICK, parsed[2][0], parsed[2][1]

    def _parse_reset_options(self, options: Mapping[str, Any] | None) -> dict[str, tuple[float, ...]]:
        """Validated hand placements from reset's ``options``, padded with zero velocities."""
        if options is None:
            return {}
        if not isinstance(options, Mapping):
            raise ValueError(f"reset options must be a dict, got {type(options).__name__}")
        placements: dict[str, tuple[float, ...]] = {}
        for key, raw in options.items():
            if key not in RESET_OPTION_LENGTHS:
                raise ValueError(
                    f"unknown reset option {key!r}; known options are {tuple(RESET_OPTION_LENGTHS)}"
                )
            if key == "keeper" and not self.has_keeper:
                raise ValueError(f"reset option 'keeper' given but task {self.task!r} has no keeper")
            lengths = RESET_OPTION_LENGTHS[key]
            values = _as_float_list(raw, f"reset option {key!r}")
            if len(values) not in lengths:
                raise ValueError(
                    f"reset option {key!r} needs {' or '.join(str(n) for n in lengths)} numbers, got {len(values)}"
                )
            if not all(math.isfinite(value) for value in values):
                raise ValueError(f"reset option {key!r} has a non-finite value: {tuple(values)}")
            # a placement without velocity starts at rest
            placements[key] = tuple(values) + (0.0,) * (max(lengths) - len(values))
        _check_placements(placements, self.params, self.has_keeper)
        return placements


# HFOEnv._parse_flat_action decodes the flat action unrolled for exactly this layout
_FLAT_ACTION_SHAPE = (FLAT_ACTION_SIZE,)
if (
    HFO_FLAT_ACTION_LAYOUT.names[DASH],
    HFO_FLAT_ACTION_LAYOUT.names[TURN],
    HFO_FLAT_ACTION_LAYOUT.names[KICK],
) != ("DASH", "TURN", "KICK") or [
    HFO_FLAT_ACTION_LAYOUT.parameter_slice(kind) for kind in (DASH, TURN, KICK)
] != [slice(3, 5), slice(5, 6), slice(6, 8)]:
    raise ImportError("HFO_FLAT_ACTION_LAYOUT changed: update HFOEnv._parse_flat_action's unrolled decode")

_NOT_REAL = (bool, np.bool_, complex, np.complexfloating)  # numbers an action or a placement must not hold


def check_render_mode(render_mode: str | None, render_modes: Sequence[str]) -> None:
    """ValueError unless ``render_mode`` is None or one of the env's ``render_modes`` (its metadata's)."""
    if render_mode is not None and render_mode not in render_modes:
        raise ValueError(f"unknown render_mode {render_mode!r}; choose None or one of {render_modes}")


def _observation(features: list[float]) -> np.ndarray:
    """The features as a new float32 array, each float rounded to float32 as ``np.array(features, np.float32)``
    does (struct's "f" is C's double-to-float conversion, like numpy's cast; the features lie in [-1, 1], so it
    never overflows). Packing them with a precompiled :class:`struct.Struct` costs about half of np.array's
    element-by-element conversion."""
    packer = _FLOAT32_PACKERS.get(len(features))
    if packer is None:
        packer = _FLOAT32_PACKERS[len(features)] = struct.Struct(f"={len(features)}f")
    return np.frombuffer(packer.pack(*features), np.float32).copy()


_FLOAT32_PACKERS: dict[int, struct.Struct] = {}


#: m; the largest ``start_shift``: the ball then starts 7-17.5 m from the goal line, clear of the goalie's area
MAX_START_SHIFT = 35.0


def _check_start_shift(metres: Any) -> None:
    if isinstance(metres, bool) or not isinstance(metres, (int, float, np.number)):
        raise ValueError(f"start_shift must be a number of metres in [0, {MAX_START_SHIFT}], got {metres!r}")
    if not 0.0 <= float(metres) <= MAX_START_SHIFT:  # also rejects NaN
        raise ValueError(f"start_shift must lie in [0, {MAX_START_SHIFT}] m, got {metres!r}")


def _check_keeper_skill(skill: Any) -> None:
    if isinstance(skill, bool) or not isinstance(skill, (int, float, np.number)):
        raise ValueError(f"keeper_skill must be a number in [0, 1], got {skill!r}")
    if not 0.0 <= float(skill) <= 1.0:  # also rejects NaN
        raise ValueError(f"keeper_skill must lie in [0, 1], got {skill!r}")


def _check_placements(
    placements: Mapping[str, tuple[float, ...]], params: ServerParams, has_keeper: bool
) -> None:
    """ValueError unless every hand placement lies on the pitch (or within PITCH_MARGIN of it) and no two
    bodies whose start is known (placed, or the goalie's fixed start) overlap."""
    for key, values in placements.items():
        x, y = values[0], values[1]
        if abs(x) > PLACEMENT_MAX_X or abs(y) > PLACEMENT_MAX_Y:
            raise ValueError(
                f"reset option {key!r} at ({x:g}, {y:g}) is off the pitch: x must lie in "
                f"[{-PLACEMENT_MAX_X:g}, {PLACEMENT_MAX_X:g}] and y in [{-PLACEMENT_MAX_Y:g}, {PLACEMENT_MAX_Y:g}] m "
                f"(the pitch and rcssserver's {PITCH_MARGIN:g} m margin)"
            )
    bodies = {key: values[:2] for key, values in placements.items()}
    if has_keeper and "keeper" not in bodies:
        bodies["keeper start"] = KEEPER_START
    radius = {"player": params.player_size, "ball": params.ball_size}
    names = list(bodies)
    for index, first in enumerate(names):
        for second in names[index + 1 :]:
            reach = radius.get(first, params.player_size) + radius.get(second, params.player_size)
            distance = math.dist(bodies[first], bodies[second])
            if distance < reach:
                raise ValueError(
                    f"reset options put {first!r} and {second!r} {distance:.3g} m apart, overlapping: their "
                    f"centres must be at least {reach:.3g} m apart"
                )


def _as_float_list(raw: Any, what: str) -> list[float]:
    """``raw`` as a flat list of Python floats (1-D real numbers only); ValueError naming ``what`` otherwise."""
    # np.asarray would turn booleans into 0 / 1 and drop imaginary parts (with a warning) without a word
    if isinstance(raw, np.ndarray):
        not_real = raw.dtype.kind in "bc"
    else:
        not_real = isinstance(raw, (list, tuple)) and any(isinstance(value, _NOT_REAL) for value in raw)
    if not_real:
        raise ValueError(f"{what} must be real numbers, not booleans or complex numbers, got {raw!r}")
    try:
        array = np.asarray(raw, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise ValueError(f"{what} must be numbers, got {raw!r}") from error
    if array.ndim != 1:
        raise ValueError(f"{what} must be 1-D, got shape {array.shape}")
    return array.tolist()
