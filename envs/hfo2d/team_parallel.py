"""HFO's team game (:class:`hfo2d.team.TeamGame`) as a PettingZoo ``ParallelEnv``: :func:`hfo2d.parallel_env`.

This module imports PettingZoo (the ``[teams]`` extra: ``pip install -e ".[teams]"``); ``hfo2d`` imports it only
when :func:`hfo2d.parallel_env` is called, so hfo2d works without PettingZoo.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from gymnasium import spaces

from hfo2d.team import TeamGame

try:
    from pettingzoo import ParallelEnv
except ModuleNotFoundError as error:  # pragma: no cover - the test extra installs it
    if error.name != "pettingzoo":
        raise
    raise ImportError(
        'hfo2d.parallel_env needs PettingZoo, from the [teams] extra: pip install -e ".[teams]" (in the sb3-hfo '
        "folder), or pip install 'pettingzoo>=1.24'"
    ) from None

__all__ = ["HFOTeamParallelEnv"]


class HFOTeamParallelEnv(ParallelEnv):
    """Every learning agent of one HFO team game, PettingZoo's parallel API.

    Agents ``"offense_0"``, ..., then ``"defense_0"``, ... (bin/HFO's numbering: ``offense_i`` has the ``i``-th
    smallest unum of the offense's agents); spaces, rules and rewards: :class:`hfo2d.team.TeamGame` and
    :class:`hfo2d.team.HalfFieldOffenseEnv`. Every agent acts every cycle and the episode ends for all at once, so
    after a terminal step ``agents`` is empty until the next ``reset``. ``reset(seed=s)`` repeats an episode
    exactly; ``options`` are accepted (PettingZoo passes them) and not read: the team game has no hand placements
    yet. ``infos`` hold each agent's ``status``, ``is_success``, ``unum``, ``player``, ``ball`` and, after a step,
    ``action``, ``action_success`` and ``reward_terms``.

    Args:
        offense_agents, defense_agents, defense_npcs: bin/HFO's team sizes (``offense_agents + defense_agents``
            learning agents, at least one).
        render_mode: None, "human" or "rgb_array".
        **game_kwargs: :class:`hfo2d.team.TeamGame`'s other arguments (``scripted_strikers``, ``agent_play_goalie``,
            ``action_format``, ``feature_set``, ``reward``, ``defense_reward``, ``noise``, ``server_params``,
            ``frames_per_trial``, ``untouched_time``).
    """

    metadata = {
        "name": "hfo2d_half_field_offense_v0",
        "render_modes": ["human", "rgb_array"],
        "render_fps": 10,
    }

    def __init__(
        self,
        offense_agents: int = 1,
        defense_agents: int = 0,
        defense_npcs: int = 0,
        *,
        render_mode: str | None = None,
        **game_kwargs: Any,
    ) -> None:
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(
                f"unknown render_mode {render_mode!r}; choose None or one of {self.metadata['render_modes']}"
            )
        self.game = TeamGame(offense_agents, defense_agents, defense_npcs, **game_kwargs)
        if not self.game.agent_names:
            raise ValueError("a ParallelEnv needs a learning agent: offense_agents + defense_agents >= 1")
        self.render_mode = render_mode
        self.possible_agents: list[str] = list(self.game.agent_names)
        self.agents: list[str] = []
        self.observation_spaces: dict[str, spaces.Space] = {
            name: self.game.agent(name).observation_space for name in self.possible_agents
        }
        self.action_spaces: dict[str, spaces.Space] = {
            name: self.game.agent(name).action_space for name in self.possible_agents
        }

    def observation_space(self, agent: str) -> spaces.Space:
        return self.observation_spaces[agent]

    def action_space(self, agent: str) -> spaces.Space:
        return self.action_spaces[agent]

    def reset(
        self, seed: int | None = None, options: Mapping[str, Any] | None = None
    ) -> tuple[dict[str, np.ndarray], dict[str, dict[str, Any]]]:
        observations, infos = self.game.reset(seed=seed)
        self.agents = list(self.possible_agents)
        if self.render_mode == "human":
            self.render()
        return observations, infos

    def step(
        self, actions: Mapping[str, Any]
    ) -> tuple[
        dict[str, np.ndarray],
        dict[str, float],
        dict[str, bool],
        dict[str, bool],
        dict[str, dict[str, Any]],
    ]:
        if not self.agents:
            raise RuntimeError("the episode has ended (no agents left): call reset() before step()")
        observations, rewards, terminated, truncated, infos = self.game.step(actions)
        terminations = dict.fromkeys(self.agents, terminated)
        truncations = dict.fromkeys(self.agents, truncated)
        if terminated or truncated:
            self.agents = []
        if self.render_mode == "human":
            self.render()
        return observations, rewards, terminations, truncations, infos

    def render(self) -> np.ndarray | None:
        if self.render_mode is None:
            return None
        return self.game.render(self.render_mode)

    def close(self) -> None:
        self.game.close()

    def state(self) -> np.ndarray:
        """The global state, offense frame: the ball (x, y, vx, vy), then every player in server order (x, y,
        vx, vy, body angle in degrees), float32 (for centralised critics)."""
        world = self.game.world
        ball = world.ball
        values = [ball.x, ball.y, ball.vx, ball.vy]
        for player in world.players:
            values += [player.x, player.y, player.vx, player.vy, player.body_deg]
        return np.asarray(values, dtype=np.float32)
