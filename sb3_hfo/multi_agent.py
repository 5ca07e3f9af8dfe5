"""Parameter-shared training of a team: one SB3 ``VecEnv`` whose slots are the learning agents of HFO team games.

``make_team_vec_env(2, offense_agents=2, defense_npcs=1, seed=0)`` is a VecEnv of 4 slots: the two strikers of
each of two 2v1 games (:class:`hfo2d.team.TeamGame`). One policy acts for every slot, so all the strikers share its
parameters (the usual "parameter sharing" of cooperative multi-agent RL); each slot is one agent's own experience
(its observation, its reward, its episode), so any SB3 algorithm (``HybridPPO``, ``SkillDDPG``, PPO, ...) trains on
it unchanged. This module is the adapter layer: the algorithms never import hfo2d.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterable, Sequence
from typing import Any

import gymnasium as gym
import numpy as np
from stable_baselines3.common.vec_env import VecEnv, VecMonitor
from stable_baselines3.common.vec_env.base_vec_env import VecEnvIndices, VecEnvObs, VecEnvStepReturn

from hfo2d.team import TeamGame

__all__ = ["TeamVecEnv", "make_team_vec_env"]

SIDES: tuple[str, ...] = ("offense", "defense")


class TeamVecEnv(VecEnv):
    """SB3's ``VecEnv`` over the learning agents of one side of several team games (the adapter owns the games).

    Slot ``k`` is agent ``slots[k] = (game index, agent name)``: the games in order, each game's agents of
    ``side`` in their order ("offense_0", "offense_1", ...). Every agent of every game must be on ``side`` (an agent
    of the other side would get no action) and all slots must share one observation and one action space.

    SB3's conventions, as ``DummyVecEnv`` keeps them: float32 rewards; ``dones = terminated | truncated``; when a
    game's episode ends, all its slots are done at once, the game is reset, their observations are the new
    episode's, and their infos carry ``terminal_observation`` and ``TimeLimit.truncated``; the reset infos go to
    ``reset_infos``. ``seed(s)`` seeds game ``g``'s next reset with ``s`` plus the index of its first slot.
    ``get_attr`` / ``set_attr`` / ``env_method`` reach each slot's game (a :class:`hfo2d.team.TeamGame`); with
    several slots per game, a method called on all slots runs once per slot.
    """

    def __init__(
        self, games: Sequence[TeamGame], side: str = "offense", render_mode: str | None = None
    ) -> None:
        if side not in SIDES:
            raise ValueError(f"unknown side {side!r}; choose one of {SIDES}")
        if len(games) == 0:
            raise ValueError("TeamVecEnv needs at least one game")
        slots: list[tuple[int, str]] = []
        for index, game in enumerate(games):
            if not isinstance(game, TeamGame):
                raise ValueError(f"TeamVecEnv takes hfo2d.team.TeamGame games, got {type(game).__name__}")
            others = [name for name in game.agent_names if not name.startswith(side)]
            if others:
                raise ValueError(
                    f"game {index} has learning agents {others} outside side {side!r}: their actions would be "
                    "missing; make them NPCs, or train them in another VecEnv"
                )
            if not game.agent_names:
                raise ValueError(f"game {index} has no {side} agent")
            slots.extend((index, name) for name in game.agent_names)
        first = games[0].agent(games[0].agent_names[0])
        for index, name in slots:
            agent = games[index].agent(name)
            if agent.observation_space != first.observation_space or agent.action_space != first.action_space:
                raise ValueError(
                    f"every slot must share one observation and one action space: game {index}'s {name} has "
                    f"{agent.observation_space} / {agent.action_space}, the first slot {first.observation_space} / "
                    f"{first.action_space} (parameter sharing needs the same team sizes and formats)"
                )
        self.games = list(games)
        self.side = side
        self.slots = slots
        self._render_mode = render_mode
        self._first_slot = {
            game: slots.index((game, games[game].agent_names[0])) for game in range(len(games))
        }
        self._actions: np.ndarray | None = None
        super().__init__(len(slots), first.observation_space, first.action_space)
        self._observations = np.zeros((self.num_envs, *first.observation_space.shape), dtype=np.float32)

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
        return f"TeamVecEnv({len(self.games)} games, side={self.side!r}, {self.num_envs} slots)"


def make_team_vec_env(
    n_games: int,
    offense_agents: int = 1,
    defense_agents: int = 0,
    defense_npcs: int = 0,
    seed: int | None = None,
    monitor: bool = True,
    side: str | None = None,
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
        side: "offense" or "defense"; None: the side of the learning agents.
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
        side = "offense" if offense_agents > 0 else "defense"
    vec_env: VecEnv = TeamVecEnv(games, side=side, render_mode=render_mode)
    if seed is not None:
        vec_env.seed(seed)
    if monitor:
        vec_env = VecMonitor(vec_env)
    return vec_env
