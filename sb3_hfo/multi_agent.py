"""Parameter-shared training of a team: one SB3 ``VecEnv`` whose slots are the learning agents of HFO team games.

``make_team_vec_env(2, offense_agents=2, defense_npcs=1, seed=0)`` is a VecEnv of 4 slots: the two strikers of
each of two 2v1 games (:class:`hfo2d.team.TeamGame`). One policy acts for every slot, so all the strikers share its
parameters (the usual "parameter sharing" of cooperative multi-agent RL); each slot is one agent's own experience
(its observation, its reward, its episode), so any SB3 algorithm (``HybridPPO``, ``SkillDDPG``, PPO, ...) trains on
it unchanged. This module is the adapter layer: the algorithms never import hfo2d.

Self-play and adversarial training: ``make_team_vec_env(8, offense_agents=1, defense_agents=1, side="defense",
opponent=striker_model)`` lets the goalie learn while a frozen policy plays the strikers. The ``opponent`` (an SB3
model, played greedily through ``predict``, or a function of a batch of observations) acts for every agent of the
other side of every game in one call per step, so a batch of games costs one forward pass of the frozen network.
"""

from __future__ import annotations

import warnings
from collections import Counter
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import Any, Protocol, runtime_checkable

import gymnasium as gym
import numpy as np
import torch as th
from stable_baselines3.common.vec_env import VecEnv, VecMonitor
from stable_baselines3.common.vec_env.base_vec_env import VecEnvIndices, VecEnvObs, VecEnvStepReturn

from hfo2d.features import FEATURES_PER_PLAYER, NUM_BASIC_FEATURES
from hfo2d.team import TeamGame
from sb3_hfo.evaluation import goal_rate_summary

__all__ = [
    "FrozenOpponent",
    "MatchResult",
    "TeamVecEnv",
    "as_opponent",
    "evaluate_team",
    "evaluate_team_games",
    "make_team_vec_env",
    "play_matches",
    "teammate_block_insertion",
    "widen_policy_inputs",
]


SIDES: tuple[str, ...] = ("offense", "defense")


@runtime_checkable
class _Predictor(Protocol):
    """What SB3's models offer (``predict``); the opponent is played through it."""

    def predict(self, observation: np.ndarray, *args: Any, **kwargs: Any) -> tuple[Any, Any]: ...


class FrozenOpponent:
    """A fixed policy that plays one side of the team games of a :class:`TeamVecEnv` while the other side learns.

    Args:
        policy: an SB3 model (anything with ``predict(observations, deterministic=...)``: its weights are not
            changed here) or a function from a batch of observations ``(n, obs_dim)`` to a batch of ``n`` actions.
        deterministic: play a model greedily (default: the opponent is then a fixed function of its
            observation, so seeded games repeat); False samples, from the model's own generator.
        name: for messages and ``repr`` (default: the model's class or the function's name).
    """

    def __init__(self, policy: Any, deterministic: bool = True, name: str | None = None) -> None:
        if isinstance(policy, FrozenOpponent):
            raise ValueError("policy is already a FrozenOpponent: pass it as it is")
        if isinstance(policy, _Predictor):
            self.observation_space: gym.Space | None = getattr(policy, "observation_space", None)
            self.action_space: gym.Space | None = getattr(policy, "action_space", None)
        elif callable(policy):
            self.observation_space = self.action_space = None
        else:
            raise ValueError(
                f"an opponent must be an SB3 model (with predict) or a function of a batch of observations, got "
                f"{type(policy).__name__}"
            )
        if not isinstance(deterministic, (bool, np.bool_)):
            raise ValueError(f"deterministic must be True or False, got {deterministic!r}")
        self.policy = policy
        self.deterministic = bool(deterministic)
        self.name = name or getattr(policy, "__name__", type(policy).__name__)

    def check_spaces(self, observation_space: gym.Space, action_space: gym.Space, where: str) -> None:
        """ValueError when a model's spaces differ from those of the agents it is to play (``where`` names them)."""
        for kind, own, wanted in (
            ("observation", self.observation_space, observation_space),
            ("action", self.action_space, action_space),
        ):
            if own is None:
                continue
            if getattr(own, "shape", None) != getattr(wanted, "shape", None) or type(own) is not type(wanted):
                raise ValueError(
                    f"the opponent {self.name} was made for the {kind} space {own}, but that of {where} is {wanted} "
                    "(a striker model plays the offense, a goalie model the defense, with the same team sizes)"
                )

    def __call__(self, observations: np.ndarray) -> np.ndarray:
        """The actions of a batch of observations, as an array with one row per observation."""
        if isinstance(self.policy, _Predictor):
            actions, _ = self.policy.predict(observations, deterministic=self.deterministic)
        else:
            actions = self.policy(observations)
        if isinstance(actions, np.ndarray):
            rows = actions.shape[0] if actions.ndim > 0 else 0
        else:
            actions = list(actions)
            rows = len(actions)
        if rows != len(observations):
            raise ValueError(
                f"the opponent {self.name} returned {rows} actions for {len(observations)} observations"
            )
        return actions

    def __repr__(self) -> str:
        return f"FrozenOpponent({self.name}, deterministic={self.deterministic})"


def as_opponent(policy: Any, deterministic: bool = True) -> FrozenOpponent:
    """``policy`` as a :class:`FrozenOpponent` (returned as it is when it already is one)."""
    if isinstance(policy, FrozenOpponent):
        return policy
    return FrozenOpponent(policy, deterministic=deterministic)


class TeamVecEnv(VecEnv):
    """SB3's ``VecEnv`` over the learning agents of one side of several team games (the adapter owns the games).

    Slot ``k`` is agent ``slots[k] = (game index, agent name)``: the games in order, each game's agents of
    ``side`` in their order ("offense_0", "offense_1", ...). All slots must share one observation and one action
    space. Without an ``opponent`` every agent of every game must be on ``side`` (an agent of the other side would
    get no action); with one (:class:`FrozenOpponent`, or anything :func:`as_opponent` takes), the opponent plays
    all the other side's agents (``opponent_slots``: (game index, agent name), games in order) with one call per
    step on their stacked observations. Games may mix: some against the opponent, others against NPCs (e.g. a
    striker learning against a frozen learned goalie in half its games and agent2d's goalie in the rest), as long
    as one game has agents for the opponent and all of them share spaces. The opponent's rewards and infos are
    dropped (each slot's info carries its game's status). :meth:`set_opponent` swaps the opponent between
    ``learn`` calls.

    SB3's conventions, as ``DummyVecEnv`` keeps them: float32 rewards; ``dones = terminated | truncated``; when a
    game's episode ends, all its slots are done at once, the game is reset, their observations are the new
    episode's, and their infos carry ``terminal_observation`` and ``TimeLimit.truncated``; the reset infos go to
    ``reset_infos``. ``seed(s)`` seeds game ``g``'s next reset with ``s`` plus the index of its first slot.
    ``get_attr`` / ``set_attr`` / ``env_method`` reach each slot's game (a :class:`hfo2d.team.TeamGame`); with
    several slots per game, a method called on all slots runs once per slot.
    """

    def __init__(
        self,
        games: Sequence[TeamGame],
        side: str = "offense",
        render_mode: str | None = None,
        opponent: Any = None,
    ) -> None:
        if side not in SIDES:
            raise ValueError(f"unknown side {side!r}; choose one of {SIDES}")
        if len(games) == 0:
            raise ValueError("TeamVecEnv needs at least one game")
        frozen = None if opponent is None else as_opponent(opponent)
        slots: list[tuple[int, str]] = []
        opponent_slots: list[tuple[int, str]] = []
        for index, game in enumerate(games):
            if not isinstance(game, TeamGame):
                raise ValueError(f"TeamVecEnv takes hfo2d.team.TeamGame games, got {type(game).__name__}")
            own = [name for name in game.agent_names if name.startswith(side)]
            others = [name for name in game.agent_names if not name.startswith(side)]
            if others and frozen is None:
                raise ValueError(
                    f"game {index} has learning agents {others} outside side {side!r}: their actions would be "
                    "missing; make them NPCs, give an opponent to play them, or train them in another VecEnv"
                )
            if not own:
                raise ValueError(f"game {index} has no {side} agent")
            slots.extend((index, name) for name in own)
            opponent_slots.extend((index, name) for name in others)
        if frozen is not None and not opponent_slots:
            raise ValueError(
                f"no game has an agent outside side {side!r} for the opponent {frozen.name} to play: add agents of "
                "the other side (e.g. offense_agents=1, defense_agents=1)"
            )
        first = games[0].agent(slots[0][1])
        for group, what in ((slots, "slot"), (opponent_slots, "opponent agent")):
            if not group:
                continue
            reference = games[group[0][0]].agent(group[0][1])
            for index, name in group:
                agent = games[index].agent(name)
                if (
                    agent.observation_space != reference.observation_space
                    or agent.action_space != reference.action_space
                ):
                    raise ValueError(
                        f"every {what} must share one observation and one action space: game {index}'s {name} "
                        f"has {agent.observation_space} / {agent.action_space}, the first "
                        f"{reference.observation_space} / {reference.action_space} (parameter sharing needs the "
                        "same team sizes and formats)"
                    )
        self.games = list(games)
        self.side = side
        self.slots = slots
        self.opponent_slots = opponent_slots
        self._render_mode = render_mode
        self._first_slot = {
            game: min(k for k, (g, _) in enumerate(slots) if g == game) for game in range(len(games))
        }
        self._actions: np.ndarray | None = None
        super().__init__(len(slots), first.observation_space, first.action_space)
        self._observations = np.zeros((self.num_envs, *first.observation_space.shape), dtype=np.float32)
        self.opponent: FrozenOpponent | None = None
        self._opponent_observations = np.zeros((0, 0), dtype=np.float32)
        if opponent_slots:
            other = games[opponent_slots[0][0]].agent(opponent_slots[0][1])
            self.opponent_observation_space = other.observation_space
            self.opponent_action_space = other.action_space
            self._opponent_observations = np.zeros(
                (len(opponent_slots), *other.observation_space.shape), dtype=np.float32
            )
            self.set_opponent(frozen)

    def set_opponent(self, opponent: Any) -> None:
        """Play the other side with ``opponent`` from the next step on (anything :func:`as_opponent` takes);
        ValueError, changing nothing, when its spaces do not fit those agents or this VecEnv has none."""
        if not self.opponent_slots:
            raise ValueError("this TeamVecEnv has no agents of the other side for an opponent to play")
        frozen = as_opponent(opponent)
        frozen.check_spaces(
            self.opponent_observation_space,
            self.opponent_action_space,
            f"the {'defense' if self.side == 'offense' else 'offense'} agents",
        )
        self.opponent = frozen

    # --- stepping ------------------------------------------------------------------------------------------------
    def reset(self) -> VecEnvObs:
        reset_infos: list[dict[str, Any]] = [{} for _ in range(self.num_envs)]
        for game_index, game in enumerate(self.games):
            seed = self._seeds[self._first_slot[game_index]]
            observations, infos = game.reset(seed=seed)
            self._store(game_index, observations, infos, reset_infos)
        self.reset_infos = reset_infos
        self._reset_seeds()
        self._reset_options()
        return self._observations.copy()

    def _store(
        self,
        game_index: int,
        observations: dict[str, np.ndarray],
        infos: dict[str, dict[str, Any]],
        into: list[dict[str, Any]],
    ) -> None:
        for slot, (index, name) in enumerate(self.slots):
            if index == game_index:
                self._observations[slot] = observations[name]
                into[slot] = infos[name]
        for row, (index, name) in enumerate(self.opponent_slots):
            if index == game_index:
                self._opponent_observations[row] = observations[name]

    def step_async(self, actions: np.ndarray) -> None:
        self._actions = actions

    def step_wait(self) -> VecEnvStepReturn:
        actions = self._actions
        if actions is None:
            raise RuntimeError("step_async() must come before step_wait()")
        self._actions = None
        rewards = np.zeros(self.num_envs, dtype=np.float32)
        dones = np.zeros(self.num_envs, dtype=bool)
        infos: list[dict[str, Any]] = [{} for _ in range(self.num_envs)]
        per_game: list[dict[str, Any]] = [{} for _ in self.games]
        for slot, (index, name) in enumerate(self.slots):
            per_game[index][name] = actions[slot]
        if self.opponent is not None:
            # one call for the whole batch: a frozen network costs one forward pass per step, not one per game
            opponent_actions = self.opponent(self._opponent_observations.copy())
            for row, (index, name) in enumerate(self.opponent_slots):
                per_game[index][name] = opponent_actions[row]
        for game_index, game in enumerate(self.games):
            observations, game_rewards, terminated, truncated, game_infos = game.step(per_game[game_index])
            for slot, (index, name) in enumerate(self.slots):
                if index != game_index:
                    continue
                rewards[slot] = game_rewards[name]
                dones[slot] = terminated or truncated
                info = game_infos[name]
                info["TimeLimit.truncated"] = truncated and not terminated
                infos[slot] = info
                self._observations[slot] = observations[name]
            for row, (index, name) in enumerate(self.opponent_slots):
                if index == game_index:
                    self._opponent_observations[row] = observations[name]
            if terminated or truncated:
                for slot, (index, _) in enumerate(self.slots):
                    if index == game_index:
                        infos[slot]["terminal_observation"] = self._observations[slot].copy()
                observations, reset_infos = game.reset()
                self._store(game_index, observations, reset_infos, self.reset_infos)
        return self._observations.copy(), rewards, dones, infos

    def close(self) -> None:
        for game in self.games:
            game.close()

    # --- the games ---------------------------------------------------------------------------------------------
    def _chosen(self, indices: VecEnvIndices) -> list[int]:
        if indices is None:
            return list(range(self.num_envs))
        if isinstance(indices, (int, np.integer)):
            return [int(indices)]
        assert isinstance(indices, Iterable)
        return list(indices)

    def get_images(self) -> Sequence[np.ndarray | None]:
        if self.render_mode != "rgb_array":
            warnings.warn(
                f"render_mode is {self.render_mode!r}; get_images needs 'rgb_array' "
                "(make_team_vec_env(..., render_mode='rgb_array'))",
                stacklevel=2,
            )
            return [None] * self.num_envs
        return [self.games[index].render("rgb_array") for index, _ in self.slots]

    def get_attr(self, attr_name: str, indices: VecEnvIndices = None) -> list[Any]:
        if attr_name == "render_mode":  # the games draw in the mode they are asked for: the VecEnv's
            return [self._render_mode] * len(self._chosen(indices))
        return [getattr(self.games[self.slots[slot][0]], attr_name) for slot in self._chosen(indices)]

    def set_attr(self, attr_name: str, value: Any, indices: VecEnvIndices = None) -> None:
        for slot in self._chosen(indices):
            setattr(self.games[self.slots[slot][0]], attr_name, value)

    def env_method(
        self, method_name: str, *method_args: Any, indices: VecEnvIndices = None, **method_kwargs: Any
    ) -> list[Any]:
        return [
            getattr(self.games[self.slots[slot][0]], method_name)(*method_args, **method_kwargs)
            for slot in self._chosen(indices)
        ]

    def env_is_wrapped(self, wrapper_class: type[gym.Wrapper], indices: VecEnvIndices = None) -> list[bool]:
        return [False] * len(self._chosen(indices))

    def __repr__(self) -> str:
        against = f", against {self.opponent!r}" if self.opponent is not None else ""
        return f"TeamVecEnv({len(self.games)} games, side={self.side!r}, {self.num_envs} slots{against})"


def make_team_vec_env(
    n_games: int,
    offense_agents: int = 1,
    defense_agents: int = 0,
    defense_npcs: int = 0,
    seed: int | None = None,
    monitor: bool = True,
    side: str | None = None,
    opponent: Any = None,
    **game_kwargs: Any,
) -> VecEnv:
    """``n_games`` HFO team games of bin/HFO's team sizes, their learning agents as one SB3 VecEnv
    (:class:`TeamVecEnv`), for parameter-shared training.

    Args:
        n_games: the number of games (the VecEnv has ``n_games`` times the side's agents slots).
        offense_agents, defense_agents, defense_npcs: bin/HFO's team sizes; the learning agents must all be on one
            side (e.g. 2 strikers against agent2d's goalie, or 1 goalie agent against ``scripted_strikers``).
        seed: game ``g``'s first episode is seeded with ``seed`` plus its first slot's index (None: unseeded).
        monitor: wrap in SB3's ``VecMonitor`` (per-slot episode returns and lengths).
        side: "offense" or "defense"; None: the side of the learning agents (with an ``opponent``: the side it
            does not play, which must then be named).
        opponent: a frozen policy for the other side's agents (:class:`FrozenOpponent`: an SB3 model played
            greedily, or a function of a batch of observations); None: every agent learns on ``side``.
        **game_kwargs: :class:`hfo2d.team.TeamGame`'s other arguments (``reward``, ``feature_set``, ...;
            ``render_mode`` goes to the VecEnv).
    """
    if isinstance(n_games, bool) or not isinstance(n_games, (int, np.integer)) or n_games < 1:
        raise ValueError(f"n_games must be a positive integer, got {n_games!r}")
    render_mode = game_kwargs.pop("render_mode", None)
    games = [
        TeamGame(offense_agents, defense_agents, defense_npcs, **game_kwargs) for _ in range(int(n_games))
    ]
    if side is None:
        if opponent is not None:
            raise ValueError(
                "with an opponent, name the learning side: side='offense' (the opponent plays the defense agents) "
                "or side='defense'"
            )
        side = "offense" if offense_agents > 0 else "defense"
    vec_env: VecEnv = TeamVecEnv(games, side=side, render_mode=render_mode, opponent=opponent)
    if seed is not None:
        vec_env.seed(seed)
    if monitor:
        vec_env = VecMonitor(vec_env)
    return vec_env


# --- a 1v1 policy as a team's striker ----------------------------------------------------------------------------
def teammate_block_insertion(teammates_before: int, teammates_after: int) -> tuple[int, int]:
    """Where HFO's paper-era features of a striker with ``teammates_after`` teammates differ from those with
    ``teammates_before``: ``(position, count)`` of the teammate blocks to insert (:mod:`hfo2d.features`: the 58
    basic features, one 8-feature block per teammate, then one per opponent, so the new teammates' blocks go in
    after the old ones, before the opponents'). With the same opponents, removing those columns from the larger
    observation gives the smaller one exactly."""
    for name, value in (("teammates_before", teammates_before), ("teammates_after", teammates_after)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 0:
            raise ValueError(f"{name} must be an integer >= 0, got {value!r}")
    if teammates_after < teammates_before:
        raise ValueError(
            f"teammates_after ({teammates_after}) < teammates_before ({teammates_before}): widening only adds inputs"
        )
    position = NUM_BASIC_FEATURES + FEATURES_PER_PLAYER * int(teammates_before)
    return position, FEATURES_PER_PLAYER * int(teammates_after - teammates_before)


def widen_policy_inputs(source: Any, target: Any, position: int) -> None:
    """Copy ``source``'s weights into ``target``, an actor-critic policy of the same networks whose observation has
    ``count = target's size - source's`` more features, inserted at ``position``: the first linear layer of the
    actor trunk and of the critic trunk get zero weights on the new inputs, so ``target`` acts and values every
    observation exactly as ``source`` acts and values it with those columns removed (a 1v1 striker, before it has
    learned to read its teammate). Both are :class:`sb3_hfo.hybrid_ppo.policies.HybridActorCriticPolicy`
    (``actor_trunk`` and ``critic_trunk`` start with their first ``nn.Linear``); the optimizers' state is not
    copied (their moments belong to the old shapes).

    :raises ValueError: flat observations of other sizes than that, a position outside them, or networks that differ
        elsewhere (nothing is copied then).
    """
    before = int(np.prod(source.observation_space.shape))
    after = int(np.prod(target.observation_space.shape))
    if len(source.observation_space.shape) != 1 or len(target.observation_space.shape) != 1:
        raise ValueError("widen_policy_inputs needs flat (1-D) observations")
    count = after - before
    if count < 0:
        raise ValueError(f"the target's observation ({after}) is smaller than the source's ({before})")
    if (
        isinstance(position, bool)
        or not isinstance(position, (int, np.integer))
        or not 0 <= position <= before
    ):
        raise ValueError(
            f"position must be an integer in [0, {before}] (the source's inputs), got {position!r}"
        )
    first_layers = {f"{trunk}.0.weight" for trunk in ("actor_trunk", "critic_trunk")}
    source_state, target_state = source.state_dict(), target.state_dict()
    if source_state.keys() != target_state.keys():
        raise ValueError(
            "the policies' networks differ: "
            f"only in the source {sorted(source_state.keys() - target_state.keys())}, "
            f"only in the target {sorted(target_state.keys() - source_state.keys())}"
        )
    widened = {}
    for key, value in source_state.items():
        expected = target_state[key].shape
        if key in first_layers:
            if value.shape[1] != before:
                raise ValueError(f"{key} reads {value.shape[1]} inputs, not the source's {before} features")
            zeros = th.zeros(value.shape[0], count, dtype=value.dtype)
            value = th.cat([value[:, :position], zeros, value[:, position:]], dim=1)
        if value.shape != expected:
            raise ValueError(
                f"{key} is {tuple(value.shape)} in the widened source, {tuple(expected)} in the target"
            )
        widened[key] = value
    target.load_state_dict(widened)


# --- evaluation of a parameter-shared team --------------------------------------------------------------------------
def _team_summary(
    statuses: Counter[str], holders: Counter[int], cycles: int, episodes: int, names: list[str]
) -> dict[str, Any]:
    """The result of :func:`evaluate_team` / :func:`evaluate_team_games`: goal rate with its Wilson interval, end
    statuses, mean cycles per episode and how many agents held the ball in an episode."""
    return {
        **goal_rate_summary(statuses, episodes),
        "mean_cycles": cycles / episodes,
        "ball_holders": {str(k): holders[k] for k in sorted(holders)},
        "agents": names,
    }


def evaluate_team(
    model: Any,
    env: Any,
    episodes: int,
    seed: int,
    deterministic: bool = True,
    on_episode: Callable[[int, str], None] | None = None,
) -> dict[str, Any]:
    """Play ``episodes`` episodes of a PettingZoo parallel team env (``hfo2d.parallel_env(...)``, either backend)
    with one policy acting for every agent (all agents' observations in one ``model.predict`` call).

    The first reset takes ``seed``, the later ones continue the env's stream (hfo2d: the same episodes again for the
    same seed; the real HFO: its server's own randomness). The episode's end is HFO's, the same for all agents.
    ``on_episode(episodes played, end status)`` is called after each episode (e.g. to log a long real-HFO run).

    :return: ``episodes``, ``goals``, ``rate`` and its 95 % Wilson interval ``ci95`` (:func:`sb3_hfo.evaluation.
        wilson_interval`), ``status`` (end statuses and counts), ``mean_cycles`` (agent steps per episode),
        ``ball_holders`` (how many episodes had 0, 1, 2, ... agents that had the ball kickable at some step:
        more than one means the ball went from one agent to another) and ``agents``.
    :raises ValueError: ``episodes`` below 1.
    """
    if isinstance(episodes, bool) or not isinstance(episodes, (int, np.integer)) or episodes < 1:
        raise ValueError(f"episodes must be a positive integer, got {episodes!r}")
    statuses: Counter[str] = Counter()
    holders: Counter[int] = Counter()
    cycles = 0
    observations, infos = env.reset(seed=seed)
    names = list(env.possible_agents)
    for _ in range(int(episodes)):
        had_ball = {name for name in names if infos.get(name, {}).get("kickable")}
        status = "IN_GAME"
        while env.agents:
            batch = np.stack([observations[name] for name in names])
            actions, _ = model.predict(batch, deterministic=deterministic)
            observations, _, _, _, infos = env.step(dict(zip(names, actions, strict=True)))
            cycles += 1
            had_ball.update(name for name in names if infos[name].get("kickable"))
            status = str(infos[names[0]]["status"])
        statuses[status] += 1
        holders[len(had_ball)] += 1
        if on_episode is not None:
            on_episode(sum(statuses.values()), status)
        observations, infos = env.reset()
    return _team_summary(statuses, holders, cycles, int(episodes), names)


def evaluate_team_games(
    model: Any,
    games: Sequence[TeamGame],
    episodes: int,
    seed: int,
    deterministic: bool = True,
) -> dict[str, Any]:
    """:func:`evaluate_team` on several hfo2d games at once (one ``model.predict`` call for every agent of every
    game per cycle: many times faster than one game at a time on a busy CPU), with the same result keys.

    Game ``g``'s first episode is seeded with ``seed + g``, its later ones continue its stream. Episodes are handed
    out as games become free, and every episode started is played to its end and counted, so short episodes are not
    favoured; a game stops once ``episodes`` have been started. ``games`` are reset here.

    :raises ValueError: ``episodes`` below 1, no games, or games whose agents differ.
    """
    if isinstance(episodes, bool) or not isinstance(episodes, (int, np.integer)) or episodes < 1:
        raise ValueError(f"episodes must be a positive integer, got {episodes!r}")
    if len(games) == 0:
        raise ValueError("evaluate_team_games needs at least one game")
    names = list(games[0].agent_names)
    if any(list(game.agent_names) != names for game in games):
        raise ValueError("every game must have the same agents")
    statuses: Counter[str] = Counter()
    holders: Counter[int] = Counter()
    cycles = 0
    observations: list[dict[str, np.ndarray]] = []
    had_ball: list[set[str]] = []
    active = [index < episodes for index in range(len(games))]
    for index, game in enumerate(games):
        game_observations, infos = game.reset(seed=seed + index)
        observations.append(game_observations)
        had_ball.append({name for name in names if infos[name].get("kickable")})
    started = sum(active)
    while any(active):
        playing = [index for index, on in enumerate(active) if on]
        batch = np.stack([observations[index][name] for index in playing for name in names])
        actions, _ = model.predict(batch, deterministic=deterministic)
        for position, index in enumerate(playing):
            chosen = actions[position * len(names) : (position + 1) * len(names)]
            game_observations, _, terminated, truncated, infos = games[index].step(
                dict(zip(names, chosen, strict=True))
            )
            cycles += 1
            had_ball[index].update(name for name in names if infos[name].get("kickable"))
            observations[index] = game_observations
            if terminated or truncated:
                statuses[str(infos[names[0]]["status"])] += 1
                holders[len(had_ball[index])] += 1
                if started < episodes:
                    started += 1
                    observations[index], infos = games[index].reset()
                    had_ball[index] = {name for name in names if infos[name].get("kickable")}
                else:
                    active[index] = False
    return _team_summary(statuses, holders, cycles, int(episodes), names)


@dataclass(frozen=True)
class MatchResult:
    """The end status of every episode of :func:`play_matches`, game by game (game 0's episodes first)."""

    statuses: tuple[str, ...]

    @property
    def episodes(self) -> int:
        return len(self.statuses)

    @property
    def goals(self) -> int:
        return sum(status == "GOAL" for status in self.statuses)

    @property
    def goal_rate(self) -> float:
        """The offense's score: goals per episode (lower is better for the defense)."""
        return self.goals / self.episodes if self.statuses else 0.0

    def counts(self) -> dict[str, int]:
        """How many episodes ended in each status."""
        return dict(sorted(Counter(self.statuses).items()))


def play_matches(
    n_games: int,
    episodes: int,
    *,
    offense: Any = None,
    defense: Any = None,
    seed: int = 0,
    **game_kwargs: Any,
) -> MatchResult:
    """Play ``episodes`` episodes of HFO team games, ``n_games`` at a time, with fixed policies on both sides.

    The games are :class:`hfo2d.team.TeamGame` of ``game_kwargs`` (``offense_agents``, ``defense_agents``,
    ``defense_npcs``, ``scripted_strikers``, ``striker``, ...). ``offense`` plays every offense agent and ``defense``
    every defense agent (each anything :func:`as_opponent` takes: an SB3 model is played greedily), one batched
    call per side and step; NPCs and scripted strikers play themselves. A side with agents needs a policy and a
    side without none (ValueError). Game ``g`` plays episodes ``g``, ``g + n_games``, ... of the ``episodes``
    (``episodes // n_games`` or one more: fixed in advance, so short episodes are not favoured), its first reset
    seeded with ``seed + g`` and the later ones carrying over as in real HFO; the same call repeats exactly when
    the policies are deterministic.
    """
    for name, value, low in (("n_games", n_games, 1), ("episodes", episodes, 1)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
            raise ValueError(f"{name} must be a positive integer, got {value!r}")
    n_games = min(int(n_games), int(episodes))
    games = [TeamGame(**game_kwargs) for _ in range(n_games)]
    policies: dict[str, FrozenOpponent] = {}
    for side, policy in (("offense", offense), ("defense", defense)):
        names = [name for name in games[0].agent_names if name.startswith(side)]
        if names and policy is None:
            raise ValueError(f"the games have {side} agents {names}: give a policy for them ({side}=...)")
        if policy is not None and not names:
            raise ValueError(f"{side}= was given, but the games have no {side} agent for it to play")
        if policy is not None:
            frozen = as_opponent(policy)
            agent = games[0].agent(names[0])
            frozen.check_spaces(agent.observation_space, agent.action_space, f"the {side} agents")
            policies[side] = frozen
    quota = [episodes // n_games + (game < episodes % n_games) for game in range(n_games)]
    statuses: list[list[str]] = [[] for _ in range(n_games)]
    observations = [game.reset(seed=seed + index)[0] for index, game in enumerate(games)]
    active = list(range(n_games))
    while active:
        actions: list[dict[str, Any]] = [{} for _ in range(n_games)]
        for side, frozen in policies.items():
            batch = [
                (index, name) for index in active for name in observations[index] if name.startswith(side)
            ]
            chosen = frozen(np.stack([observations[index][name] for index, name in batch]))
            for row, (index, name) in enumerate(batch):
                actions[index][name] = chosen[row]
        still_active = []
        for index in active:
            game = games[index]
            observations[index], _, terminated, truncated, _ = game.step(actions[index])
            if terminated or truncated:
                statuses[index].append(game.status)
                if len(statuses[index]) == quota[index]:
                    continue
                observations[index] = game.reset()[0]
            still_active.append(index)
        active = still_active
    for game in games:
        game.close()
    return MatchResult(tuple(status for per_game in statuses for status in per_game))
