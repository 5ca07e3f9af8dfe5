"""HFO's team games in a real HFO build: a PettingZoo ParallelEnv over ``bin/HFO`` with several agents.

:class:`RealTeamParallelEnv` plays what ``bin/HFO --offense-agents N --defense-agents M --defense-npcs K`` plays:
every learning agent is one of HFO's agent processes (a worker of :mod:`hfo2d.real`, since HFO's binding allows
one ``connectToServer`` per process), the NPCs are agent2d's (the first defender is the goalie). It reuses
:mod:`hfo2d.real`'s machinery: the build lookup, bin/HFO's arguments (:func:`hfo2d.real.bin_hfo_args`), the
launcher and its log, the workers and their wire format, the process groups and their clean-up, the env's side of
a session (``hfo2d.real._SessionEnv``: its options, its start on ``reset`` and on a new seed), the start-up and
end-of-episode timing (three NOOPs after an episode's last cycle, the last observation of an episode lost) and the
recovery from SERVER_DOWN (the episode ends truncated for every agent with ``info["status"] == "SERVER_DOWN"`` and
a warning; the next ``reset`` starts a new session).

Agents are named ``"offense_0"``, ... then ``"defense_0"``, ..., in HFO's order: bin/Trainer.py launches the offense
agents on their sorted uniform numbers (agent2d's offense order: one agent is 11, two are 7 and 11, ...), then the
defense agents (the goalie's unum 1 first with ``agent_play_goalie``, otherwise the last defense numbers).

Spaces (each agent's own, one object per agent):

* observation, ``feature_set``:

  - ``"paper"`` (default): hfo2d's paper-era low-level features, ``58 + 8 * (teammates + opponents)``
    (:func:`hfo2d.features.num_features`), converted from HFO master's vector by
    :func:`hfo2d.features.paper_from_hfo`, ``Box(-1, 1)``;
  - ``"hfo"``: HFO master's low-level vector as HFO sends it, ``58 + 9 * (teammates + opponents) + 1``;
  - ``"high_level"``: HFO's high-level vector (``10 + 6 * teammates + 3 * opponents + 2``,
    :func:`hfo2d.features.high_level_num_features`), bounds from :func:`hfo2d.features.high_level_bounds`;

* action: a flat hybrid action (:class:`hfo2d.action_layout.HybridActionBox`, values in [0, 1]): the offense's is
  hfo2d's (DASH, TURN, KICK; :func:`hfo2d.action_layout.hfo_flat_action_space`), a defender's adds HFO's TACKLE
  (direction) and, for the goalie, CATCH (:func:`defense_action_space`). Powers map to [0, 100], directions to
  [-180, 180] degrees, as in :class:`hfo2d.hfo_env.HFOEnv`; each is sent as HFO's low-level ``act``.

Rewards: an offense agent gets hfo2d's ``reward`` (:mod:`hfo2d.reward`) from its own paper-era features (the
gap rewards, which read the goalie's block, from HFO/Keeper-v1's view of them: :func:`hfo2d.features.
keeper_view_from_hfo`, as hfo2d's TeamGame does; with
``feature_set="high_level"`` only ``"sparse"`` is possible, since the shaped rewards read low-level features); a
defender gets +1 when the episode ends with the ball captured, out of bounds or out of time, -1 on a goal, 0 else.

Episodes end for all agents at once (HFO's referee). PettingZoo's convention: after the last step ``agents`` is
empty until ``reset``. Run the servers in a loopback-only network namespace (``tools/real_hfo/loopback.sh``).
"""

from __future__ import annotations

import os
import re
import socket
import subprocess
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from gymnasium import spaces

from hfo2d.action_layout import HybridActionBox, HybridActionLayout, hfo_flat_action_space
from hfo2d.features import (
    KICKABLE,
    hfo_num_features,
    high_level_bounds,
    high_level_num_features,
    keeper_view_from_hfo,
    num_features,
    paper_from_hfo,
)
from hfo2d.protocol import (
    CAPTURED_BY_DEFENSE,
    DEFAULT_FRAMES_PER_TRIAL,
    DEFAULT_UNTOUCHED_TIME,
    DIRECTION_MAX,
    DIRECTION_MIN,
    GOAL,
    IN_GAME,
    OUT_OF_BOUNDS,
    OUT_OF_TIME,
    POWER_MAX,
    POWER_MIN,
)
from hfo2d.real import (
    _HANDSHAKE_HEAD,
    _REPLY_HEAD,
    _REQUEST,
    HFO_CATCH,
    HFO_DASH,
    HFO_DEFENSE_TEAM_NAME,
    HFO_HIGH_LEVEL_FEATURE_SET,
    HFO_KICK,
    HFO_LOW_LEVEL_FEATURE_SET,
    HFO_NOOP,
    HFO_SERVER_DOWN,
    HFO_TACKLE,
    HFO_TEAM_NAME,
    HFO_TURN,
    SERVER_DOWN,
    SIDE_LETTERS,
    START_NOOPS,
    START_TIMEOUT_S,
    STATUS_NAMES,
    STEP_TIMEOUT_S,
    WAITING_FOR_AGENT,
    HFOSessionError,
    SessionDown,
    _is_int,
    _Session,
    _SessionEnv,
)
from hfo2d.reward import GOALIE_READING_REWARDS, REWARD_NAMES, make_reward

try:  # PettingZoo is optional: without it the class keeps the same API, duck-typed
    from pettingzoo import ParallelEnv as _ParallelBase
except ImportError:  # pragma: no cover - exercised only where pettingzoo is missing
    _ParallelBase = object  # type: ignore[assignment,misc]

__all__ = [
    "DEFENSE_ACTION_NAMES",
    "FEATURE_SETS",
    "MAX_DEFENSE",
    "MAX_OFFENSE",
    "RealTeamParallelEnv",
    "defense_action_space",
]

FEATURE_SETS: tuple[str, ...] = ("paper", "hfo", "high_level")
#: bin/HFO's team limits (its parseArgs): offense agents + NPCs in [1, 10], defense agents + NPCs in [0, 11].
MAX_OFFENSE, MAX_DEFENSE = 10, 11
#: A defender's discrete actions in HFO's action order (src/common.hpp: DASH, TURN, TACKLE, KICK, ..., CATCH); CATCH
#: for the goalie only. The same layouts as hfo2d's own team game (``hfo2d.team``), so that models move between
#: the two backends.
DEFENSE_ACTION_NAMES: tuple[str, ...] = ("DASH", "TURN", "TACKLE", "KICK", "CATCH")
_HFO_CODES: dict[str, int] = {
    "DASH": HFO_DASH,
    "TURN": HFO_TURN,
    "KICK": HFO_KICK,
    "TACKLE": HFO_TACKLE,
    "CATCH": HFO_CATCH,
}
#: Statuses that count for the defense (its reward is +1 on them, -1 on GOAL).
DEFENSE_WINS: frozenset[str] = frozenset({CAPTURED_BY_DEFENSE, OUT_OF_BOUNDS, OUT_OF_TIME})
#: reset options that hfo2d's own envs use to place players by hand; the real HFO's referee places them.
_PLACEMENT_OPTIONS = ("player", "ball", "keeper", "offense", "defense", "players")
# bin/Trainer.py's line for each agent it waits for, with HFO's play_goalie for it.
_WAITING_LINE = re.compile(re.escape(WAITING_FOR_AGENT) + r" (\S+)-(\d+):.*play_goalie=(True|False)")


def defense_action_space(goalie: bool) -> HybridActionBox:
    """A defender's flat action: the preferences of DASH, TURN, TACKLE, KICK (and CATCH for the goalie), then
    DASH(power, dir), TURN(dir), TACKLE(dir), KICK(power, dir), values in [0, 1] (HFO's low-level defense actions,
    src/common.hpp; CATCH has no parameter)."""
    names = DEFENSE_ACTION_NAMES if goalie else DEFENSE_ACTION_NAMES[:4]
    layout = HybridActionLayout(
        names=names,
        parameter_sizes=(2, 1, 1, 2, 0)[: len(names)],
        direction_indices=tuple(len(names) + k for k in (1, 2, 3, 5)),
        ball_action=3,
    )
    return HybridActionBox(layout)


@dataclass(frozen=True)
class AgentRole:
    """One learning agent of an HFO game: its name here, HFO's team name, its number in the team (from 0) and
    whether it is the goalie."""

    name: str
    team: str
    index: int
    offense: bool
    goalie: bool = False


class _TeamSession(_Session):
    """One running HFO with one worker per learning agent (hfo2d.real's workers, any team and feature set)."""

    def __init__(
        self,
        hfo_dir: Path,
        args: list[str],
        port: int | None,
        log_dir: Path | None,
        rng: np.random.Generator,
        roles: Sequence[AgentRole],
        feature_set: int,
    ) -> None:
        self.roles = tuple(roles)
        self.feature_set = int(feature_set)
        self.workers: list[subprocess.Popen[bytes] | None] = []
        self.socks: list[socket.socket | None] = []
        self.heads: list[tuple[int, int, int, int]] = []  # (state size, teammates, opponents, unum) per agent
        self.states: list[np.ndarray] = []
        self._replies: list[bytearray] = []
        self.play_goalie: list[bool] = []
        super().__init__(hfo_dir, args, port, log_dir, rng)

    def _workers(self) -> list[tuple[subprocess.Popen[bytes] | None, socket.socket | None]]:
        return list(zip(self.workers, self.socks, strict=True))

    def _start(self, args: list[str], port: int | None, rng: np.random.Generator) -> None:
        offset = self._launch(args, port, rng)
        # bin/Trainer.py waits for each agent in turn (offense, then defense), printing a line for each; an
        # agent's connectToServer returns once the game starts, so every worker is started before any handshake.
        for role in self.roles:
            wanted = f"{WAITING_FOR_AGENT} {role.team}-{role.index}:"
            self._wait_for_line(wanted, f"wait for agent {role.name}")
            line = next(line for line in self._log_text(offset).splitlines() if wanted in line)
            match = _WAITING_LINE.search(line)
            goalie = match is not None and match.group(3) == "True"
            self.play_goalie.append(goalie)
            feature_set = str(self.feature_set)
            worker, sock = self._spawn_worker("--worker", (role.team, feature_set, "1" if goalie else "0"))
            self.workers.append(worker)
            self.socks.append(sock)
        self._arm_finalizer()
        for k, role in enumerate(self.roles):
            head = self._receive_from(k, _HANDSHAKE_HEAD.size, START_TIMEOUT_S, f"{role.name}'s connection")
            size, teammates, opponents, unum = _HANDSHAKE_HEAD.unpack(head)
            self.heads.append((size, teammates, opponents, unum))
            reply = bytearray(_REPLY_HEAD.size + 4 * size)
            self._replies.append(reply)
            self.states.append(np.frombuffer(reply, dtype=np.float32, offset=_REPLY_HEAD.size))
            self._receive_into_from(
                k, memoryview(reply)[_REPLY_HEAD.size :], START_TIMEOUT_S, "a first state"
            )

    def _receive_from(self, k: int, size: int, timeout_s: float, what: str) -> bytes:
        buffer = bytearray(size)
        self._receive_into_from(k, memoryview(buffer), timeout_s, what)
        return bytes(buffer)

    def _receive_into_from(self, k: int, view: memoryview, timeout_s: float, what: str) -> None:
        self._receive_into(view, timeout_s, f"{what} ({self.roles[k].name})", self.socks[k], self.workers[k])

    def step_all(self, commands: Sequence[tuple[int, float, float]]) -> list[tuple[int, int, int]]:
        """Every agent's ``act`` + ``step`` in one server cycle: (status, side on ball, unum on ball) per agent;
        the states land in ``self.states``. The requests go out first (each worker blocks in HFO's step until the
        synchronous server has every agent's command), then the replies are read."""
        if any(sock is None for sock in self.socks):
            raise SessionDown("the session is closed")
        try:
            for sock, command in zip(self.socks, commands, strict=True):
                assert sock is not None
                sock.sendall(_REQUEST.pack(*command))
            for k, reply in enumerate(self._replies):
                self._receive_into_from(k, memoryview(reply), STEP_TIMEOUT_S, "a step")
        except OSError as error:
            raise SessionDown(f"connection to an HFO worker failed: {error}") from error
        return [_REPLY_HEAD.unpack_from(reply) for reply in self._replies]

    def close(self) -> None:
        super().close()
        self.socks = [None] * len(self.socks)


class RealTeamParallelEnv(_SessionEnv, _ParallelBase):  # type: ignore[misc,valid-type]
    """HFO's team game in a real HFO build, as a PettingZoo ParallelEnv (see the module docstring).

    Args:
        offense_agents: learning offense agents (bin/HFO ``--offense-agents``), 0 ..  MAX_OFFENSE.
        defense_agents: learning defenders (``--defense-agents``).
        defense_npcs: agent2d defenders (``--defense-npcs``); the first defender is the goalie.
        offense_npcs: agent2d attackers (``--offense-npcs``); hfo2d's own team game has none.
        agent_play_goalie: bin/HFO's ``--agent-play-goalie``: the first defense agent is the goalie (unum 1).
        hfo_dir: the HFO build (folder with ``bin/HFO``); None: ``$HFO_DIR``.
        feature_set: "paper", "hfo" or "high_level" (see the module docstring).
        reward: the offense's reward, one of hfo2d's REWARD_NAMES.
        defense_reward: the defense's: only "sparse" (+1 when the episode ends in the defense's favour, -1 on a
            goal, 0 otherwise), the name hfo2d's team game gives it.
        action_format: only "flat" (the hybrid flat vector; hfo2d's team game also offers "parameterized").
        noise: False runs HFO ``--deterministic``.
        seed: HFO's ``--seed`` (start positions), an int in [0, 2**31 - 1]; None: the seed of the first
            ``reset(seed=...)``, else HFO's own.
        frames_per_trial: HFO's ``--frames-per-trial``.
        untouched_time: HFO's ``--untouched-time``.
        port: the server's UDP port (it also uses the next two); None: a free one.
        log_dir: HFO's game logs (.rcg, .rcl, .hfo) and the launcher's output go there; None: ``--no-logging``.
        fullstate: HFO's ``--fullstate`` (exact features); False: each agent's noisy world model.
        render_mode: only None.
    """

    metadata = {"name": "hfo_real_teams_v0", "render_modes": [], "is_parallelizable": True}
    _session: _TeamSession | None
    _pending: list[tuple[list[float], int, int]] | None

    def __init__(
        self,
        offense_agents: int = 1,
        defense_agents: int = 0,
        defense_npcs: int = 0,
        *,
        offense_npcs: int = 0,
        agent_play_goalie: bool = False,
        hfo_dir: str | os.PathLike[str] | None = None,
        feature_set: str = "paper",
        reward: str = "shaped",
        defense_reward: str = "sparse",
        action_format: str = "flat",
        noise: bool = True,
        seed: int | None = None,
        frames_per_trial: int = DEFAULT_FRAMES_PER_TRIAL,
        untouched_time: int = DEFAULT_UNTOUCHED_TIME,
        port: int | None = None,
        log_dir: str | os.PathLike[str] | None = None,
        fullstate: bool = True,
        render_mode: str | None = None,
    ) -> None:
        counts = {
            "offense_agents": offense_agents,
            "defense_agents": defense_agents,
            "defense_npcs": defense_npcs,
            "offense_npcs": offense_npcs,
        }
        for name, value in counts.items():
            if not _is_int(value) or value < 0:
                raise ValueError(f"{name} must be an integer >= 0, got {value!r}")
        if offense_agents + defense_agents < 1:
            raise ValueError(
                "a game needs at least one learning agent (offense_agents + defense_agents >= 1)"
            )
        if not 1 <= offense_agents + offense_npcs <= MAX_OFFENSE:
            raise ValueError(
                f"the offense must have 1 to {MAX_OFFENSE} players (bin/HFO), got {offense_agents + offense_npcs}"
            )
        if defense_agents + defense_npcs > MAX_DEFENSE:
            raise ValueError(
                f"the defense has at most {MAX_DEFENSE} players (bin/HFO), got {defense_agents + defense_npcs}"
            )
        if agent_play_goalie and defense_agents == 0:
            raise ValueError("agent_play_goalie needs a defense agent (defense_agents >= 1)")
        if feature_set not in FEATURE_SETS:
            raise ValueError(f"unknown feature_set {feature_set!r}; choose one of {FEATURE_SETS}")
        if reward not in REWARD_NAMES:
            raise ValueError(f"unknown reward {reward!r}; choose one of {REWARD_NAMES}")
        if defense_reward != "sparse":
            raise ValueError(
                f"defense_reward {defense_reward!r} is not available in the real HFO; only 'sparse' (+1 when the "
                "defense wins, -1 on a goal)"
            )
        if action_format != "flat":
            raise ValueError(
                f"the real HFO's team game takes flat actions only, got action_format={action_format!r}"
            )
        if feature_set == "high_level" and reward != "sparse" and offense_agents > 0:
            raise ValueError(
                f"reward {reward!r} reads low-level features; with feature_set='high_level' use reward='sparse'"
            )
        if render_mode is not None:
            raise ValueError(f"RealTeamParallelEnv does not render (render_mode={render_mode!r})")
        if not isinstance(agent_play_goalie, (bool, np.bool_)):
            raise ValueError(f"agent_play_goalie must be True or False, got {agent_play_goalie!r}")
        self._set_session_options(
            hfo_dir=hfo_dir,
            noise=noise,
            seed=seed,
            frames_per_trial=frames_per_trial,
            untouched_time=untouched_time,
            port=port,
            log_dir=log_dir,
            fullstate=fullstate,
        )
        self.offense_agents = int(offense_agents)
        self.defense_agents = int(defense_agents)
        self.defense_npcs = int(defense_npcs)
        self.offense_npcs = int(offense_npcs)
        self.agent_play_goalie = bool(agent_play_goalie)
        self.feature_set = feature_set
        self.reward_name = reward
        self.render_mode = render_mode

        num_offense = self.offense_agents + self.offense_npcs
        num_defense = self.defense_agents + self.defense_npcs
        roles = [AgentRole(f"offense_{k}", HFO_TEAM_NAME, k, True) for k in range(self.offense_agents)]
        # the goalie among the defense agents (bin/Trainer.py run: the agents take the first of the sorted defense
        # numbers with --agent-play-goalie, else the last ones, so they include unum 1, the goalie, when there is no
        # defense NPC); the session checks it against the trainer's own line for each agent
        goalie_agent = (
            0 if self.defense_agents and (self.agent_play_goalie or self.defense_npcs == 0) else None
        )
        roles += [
            AgentRole(f"defense_{k}", HFO_DEFENSE_TEAM_NAME, k, False, goalie=k == goalie_agent)
            for k in range(self.defense_agents)
        ]
        self.roles: tuple[AgentRole, ...] = tuple(roles)
        self.possible_agents: list[str] = [role.name for role in roles]
        self.agents: list[str] = []
        # (teammates, opponents) in each agent's vector (HFO's getNumTeammates / getNumOpponents)
        self._slots: dict[str, tuple[int, int]] = {
            role.name: (num_offense - 1, num_defense) if role.offense else (num_defense - 1, num_offense)
            for role in roles
        }
        self.observation_spaces: dict[str, spaces.Box] = {
            name: self._make_observation_space(*slots) for name, slots in self._slots.items()
        }
        self.action_spaces: dict[str, HybridActionBox] = {
            role.name: hfo_flat_action_space() if role.offense else defense_action_space(role.goalie)
            for role in roles
        }
        self._rewards = {role.name: make_reward(reward) for role in roles if role.offense}
        # a gap reward reads the goalie at features 58-65, where a team's layout has the teammates' blocks: such a
        # reward gets HFO/Keeper-v1's view of the state (keeper_view_from_hfo), as hfo2d's TeamGame gives it
        self._reward_needs_goalie_view = reward in GOALIE_READING_REWARDS and not (
            num_offense == 1 and num_defense == 1
        )

        self._raw: dict[str, list[float]] = {}
        self._obs: dict[str, list[float]] = {}
        self._paper: dict[str, list[float]] = {}
        self._on_ball: tuple[str, int] = ("U", -1)

    # --- spaces ---------------------------------------------------------------------------------------------------
    def _make_observation_space(self, teammates: int, opponents: int) -> spaces.Box:
        if self.feature_set == "paper":
            return spaces.Box(-1.0, 1.0, shape=(num_features(teammates, opponents),), dtype=np.float32)
        if self.feature_set == "hfo":
            return spaces.Box(-1.0, 1.0, shape=(hfo_num_features(teammates, opponents),), dtype=np.float32)
        low, high = high_level_bounds(teammates, opponents)
        return spaces.Box(np.asarray(low, np.float32), np.asarray(high, np.float32), dtype=np.float32)

    def observation_space(self, agent: str) -> spaces.Box:
        """The observation space of ``agent`` (the same object on every call)."""
        return self.observation_spaces[agent]

    def action_space(self, agent: str) -> HybridActionBox:
        """The action space of ``agent`` (the same object on every call)."""
        return self.action_spaces[agent]

    # --- the HFO session --------------------------------------------------------------------------------------------
    def hfo_args(self, seed: int | None = None) -> list[str]:
        """bin/HFO's arguments for this game (less ``--port``), with ``seed`` as ``--seed`` when not None."""
        return self._bin_hfo_args(
            seed,
            offense_agents=self.offense_agents,
            offense_npcs=self.offense_npcs,
            defense_agents=self.defense_agents,
            defense_npcs=self.defense_npcs,
            agent_play_goalie=self.agent_play_goalie,
        )

    def _start_session(self) -> None:
        self._close_session()
        feature_code = (
            HFO_HIGH_LEVEL_FEATURE_SET if self.feature_set == "high_level" else HFO_LOW_LEVEL_FEATURE_SET
        )
        session = _TeamSession(
            self.hfo_dir,
            self.hfo_args(self._session_seed),
            self.port,
            self.log_dir,
            self._port_rng,
            self.roles,
            feature_code,
        )
        for role, (size, teammates, opponents, _), goalie in zip(
            self.roles, session.heads, session.play_goalie, strict=True
        ):
            expected_slots = self._slots[role.name]
            expected_size = self._raw_size(*expected_slots)
            if (teammates, opponents) != expected_slots or size != expected_size or goalie != role.goalie:
                session.close()
                raise HFOSessionError(
                    f"HFO gave {role.name} {size} features for {teammates} teammate(s) and {opponents} opponent(s)"
                    f" (goalie {goalie}); expected {expected_size} for {expected_slots} (goalie {role.goalie})"
                )
        self._adopt_session(session)
        # the first observation precedes the placement: play the NOOPs HFO plays between later episodes
        noops = [(HFO_NOOP, 0.0, 0.0)] * len(self.roles)
        for _ in range(START_NOOPS):
            replies = self._hfo_step(noops)
            if replies is None:
                raise HFOSessionError(
                    f"HFO went down while starting ({self._down_reason}):\n{session.log_tail()}"
                )
            self._pending = self._snapshot(replies)

    def _raw_size(self, teammates: int, opponents: int) -> int:
        if self.feature_set == "high_level":
            return high_level_num_features(teammates, opponents)
        return hfo_num_features(teammates, opponents)

    def _snapshot(self, replies: list[tuple[int, int, int]]) -> list[tuple[list[float], int, int]]:
        assert self._session is not None
        return [
            (state.tolist(), side, unum)
            for state, (_, side, unum) in zip(self._session.states, replies, strict=True)
        ]

    def _hfo_step(self, commands: list[tuple[int, float, float]]) -> list[tuple[int, int, int]] | None:
        """One cycle for every agent; None when the session went down (the reason in ``_down_reason``)."""
        assert self._session is not None
        try:
            replies = self._session.step_all(commands)
        except SessionDown as error:
            self._down_reason = str(error)
            return None
        codes = {status for status, _, _ in replies}
        if HFO_SERVER_DOWN in codes or any(not 0 <= code < len(STATUS_NAMES) for code in codes):
            self._down_reason = "HFO reported SERVER_DOWN"
            return None
        if len(codes) > 1:
            self._down_reason = f"the agents disagree on the status of one cycle: {sorted(codes)}"
            return None
        return replies

    # --- PettingZoo API ---------------------------------------------------------------------------------------------
    def reset(
        self, seed: int | None = None, options: Mapping[str, Any] | None = None
    ) -> tuple[dict[str, np.ndarray], dict[str, dict[str, Any]]]:
        """Start the next HFO episode (the session itself on the first call, or when ``seed`` asks for another).

        ``options`` are accepted for PettingZoo's API; HFO's referee places the players, so hfo2d's placement
        options (``player``, ``ball``, ...) raise ValueError.
        """
        if options:
            placed = [key for key in _PLACEMENT_OPTIONS if key in options]
            if placed:
                raise ValueError(
                    f"the real HFO places the players itself; unsupported reset options {placed}"
                )
        if seed is not None and not _is_int(seed):
            raise ValueError(f"seed must be an integer, got {seed!r}")
        self._set_current(self._next_episode(seed))
        self.agents = list(self.possible_agents)
        for name, reward_fn in self._rewards.items():
            reward_fn.reset(self._reward_features(name))
        return self._observations(), {name: self._info(name) for name in self.agents}

    def _finish_episode(self) -> None:
        """NOOPs until HFO ends the episode in progress; its end becomes pending (None if the session went down)."""
        noops = [(HFO_NOOP, 0.0, 0.0)] * len(self.roles)
        for _ in range(self.frames_per_trial + START_NOOPS + 1):
            replies = self._hfo_step(noops)
            if replies is None:
                return
            if replies[0][0] != 0:
                self._pending = self._snapshot(replies)
                return
        self._down_reason = f"HFO did not end an episode within {self.frames_per_trial} NOOP cycles"

    def step(
        self, actions: Mapping[str, Any]
    ) -> tuple[
        dict[str, np.ndarray],
        dict[str, float],
        dict[str, bool],
        dict[str, bool],
        dict[str, dict[str, Any]],
    ]:
        """One server cycle: every live agent's action as HFO's ``act``, then HFO's ``step``.

        ``actions`` must hold an action for every agent in ``agents`` (and no other key).
        """
        if not self.agents:
            raise RuntimeError("call reset() before step(): no agent is live")
        missing = [name for name in self.agents if name not in actions]
        extra = [name for name in actions if name not in self.agents]
        if missing or extra:
            raise ValueError(
                f"actions must be given for exactly {self.agents}; missing {missing}, unknown {extra}"
            )
        decoded = {name: self._decode(name, actions[name]) for name in self.agents}  # validates before acting
        replies = self._hfo_step([decoded[role.name][1] for role in self.roles])
        self._steps += 1
        agents = list(self.agents)
        if replies is None:
            self._session_down()
            self._status = SERVER_DOWN
            self.agents = []
            infos = {name: self._info(name) for name in agents}
            for name in agents:
                infos[name].update(action=decoded[name][0], stale_observation=True)
            return (
                self._observations(agents),
                dict.fromkeys(agents, 0.0),
                dict.fromkeys(agents, False),
                dict.fromkeys(agents, True),
                infos,
            )
        status = STATUS_NAMES[replies[0][0]]
        if status == IN_GAME:
            self._set_current(self._snapshot(replies))
            terminated = truncated = False
        else:
            # HFO's step() has already played three NOOPs into the next episode: keep them for reset()
            self._pending = self._snapshot(replies)
            truncated = status == OUT_OF_TIME and self._steps >= self._frame_limit_steps
            terminated = not truncated
        self._status = status
        rewards: dict[str, float] = {}
        infos = {}
        for role in self.roles:
            name = role.name
            info = self._info(name)
            info["action"] = decoded[name][0]
            info["stale_observation"] = status != IN_GAME
            if role.offense:
                features = self._reward_features(name)
                reward, terms = self._rewards[name](features, status, terminated or truncated)
                info["reward_terms"] = terms
            else:
                reward = 0.0
                if status in DEFENSE_WINS:
                    reward = 1.0
                elif status == GOAL:
                    reward = -1.0
            rewards[name] = float(reward)
            infos[name] = info
        if terminated or truncated:
            self.agents = []
        return (
            self._observations(agents),
            rewards,
            dict.fromkeys(agents, terminated),
            dict.fromkeys(agents, truncated),
            infos,
        )

    def render(self) -> None:
        """The real HFO is not rendered here (HFO's own monitor can watch a session)."""
        raise NotImplementedError("RealTeamParallelEnv does not render; run HFO's monitor against its port")

    def close(self) -> None:
        """Stop the HFO session (server, trainer, NPCs, workers)."""
        self._stop()
        self.agents = []

    def state(self) -> np.ndarray:
        """Not available: HFO gives each agent its own features, not a global state."""
        raise NotImplementedError("the real HFO exposes no global state; use each agent's observation")

    # --- internals ------------------------------------------------------------------------------------------------
    def hfo_vector(self, agent: str) -> np.ndarray:
        """``agent``'s vector as HFO sent it for the current observation (low-level master or high-level)."""
        return np.asarray(self._raw[agent], dtype=np.float32)

    def _decode(self, name: str, action: Any) -> tuple[str, tuple[int, float, float]]:
        """(action name, HFO's act command) of a flat hybrid action; ValueError for a malformed one."""
        space = self.action_spaces[name]
        layout = space.layout
        values = np.asarray(action, dtype=np.float64).reshape(-1) if not isinstance(action, str) else None
        if values is None or values.shape != (layout.size,):
            raise ValueError(
                f"{name}'s action must be a flat vector of shape ({layout.size},), got {action!r}"
            )
        if not np.all((values >= 0.0) & (values <= 1.0)):  # NaN fails too
            raise ValueError(f"{name}'s action must lie in [0, 1], got {values.tolist()}")
        kind, params = layout.decode(values.tolist())
        start = layout.parameter_slice(kind).start
        scaled = [
            DIRECTION_MIN + (DIRECTION_MAX - DIRECTION_MIN) * value
            if start + k in layout.direction_indices
            else POWER_MIN + (POWER_MAX - POWER_MIN) * value
            for k, value in enumerate(params)
        ]
        scaled += [0.0] * (2 - len(scaled))
        action_name = layout.names[kind]
        return action_name, (_HFO_CODES[action_name], float(scaled[0]), float(scaled[1]))

    def _set_current(self, snapshot: list[tuple[list[float], int, int]]) -> None:
        for role, (raw, side, unum) in zip(self.roles, snapshot, strict=True):
            self._raw[role.name] = raw
            if self.feature_set != "high_level":
                self._paper[role.name] = paper_from_hfo(raw, *self._slots[role.name])
            self._on_ball = (SIDE_LETTERS.get(side, "U"), int(unum))

    def _reward_features(self, name: str) -> list[float]:
        """What offense agent ``name``'s reward reads: its paper features, or HFO/Keeper-v1's view of them for a
        reward that reads the goalie's block (empty before the first state)."""
        if name not in self._paper:
            return []
        if not self._reward_needs_goalie_view:
            return self._paper[name]
        return keeper_view_from_hfo(self._raw[name], *self._slots[name])

    def _observations(self, agents: Sequence[str] | None = None) -> dict[str, np.ndarray]:
        names = self.agents if agents is None else agents
        source = self._paper if self.feature_set == "paper" else self._raw
        return {name: np.array(source[name], dtype=np.float32) for name in names}

    def _info(self, name: str) -> dict[str, Any]:
        paper = self._paper.get(name)
        info: dict[str, Any] = {
            "status": self._status,
            "is_success": self._status == GOAL,
            "player_on_ball": self._on_ball,
            "episode": self._episode,
            "session_restarts": self._restarts,
        }
        if self._session is not None:
            info["unum"] = self._session.heads[self.possible_agents.index(name)][3]
        if paper is not None:
            info["kickable"] = paper[KICKABLE] > 0.0
        return info
