"""The interface of hfo2d's scripted players (HFO's NPCs), and the still goalie.

An env holds a list of ``(player, npc)`` pairs and plays every NPC the same way, whatever it is:

1. at an episode's start, :meth:`DefenseNPC.start_body_deg` gives the body angle it is placed with (unless the
   server carries the last episode's over), then :meth:`DefenseNPC.reset`;
2. every cycle, :meth:`DefenseNPC.decide` on the state after the last step, before any command of the cycle
   arrives (the NPC keeps its decision); then the agents' commands; then :meth:`DefenseNPC.apply` sends the NPC's;
3. :meth:`DefenseNPC.act` (decide, then apply) in the cycles where no agent plays (real HFO's wait cycles).

Four NPCs implement it today: HFO's own goalie (:class:`hfo2d.agent2d.goalie.Agent2dGoalie`, ``HFO/Keeper-v1``),
agent2d's field defenders (:class:`hfo2d.agent2d.defender.Agent2dDefender`, the team game's defense NPCs after the
goalie), hfo2d's first goalie (:class:`hfo2d.keeper.ScriptedKeeper`, ``HFO/Keeper-v0``) and :class:`StillGoalie`
(``HFO/StaticKeeper-v0``). agent2d's offense, when it is ported, is to follow the same interface.
"""

from __future__ import annotations

from typing import Any, Protocol, runtime_checkable

import numpy as np

from hfo2d.physics import PlayerState, ServerParams, World
from hfo2d.protocol import KEEPER_START_BODY_DEG

__all__ = ["DefenseNPC", "StillGoalie"]


@runtime_checkable
class DefenseNPC(Protocol):
    """A scripted player of the defense, as an env plays it (see the module docstring).

    Attributes:
        params: the server parameters of the world it plays in; its predictions use them.
        rng: the generator of its random draws (an env hands it its own, again after ``reset(seed=...)``).
        skill: its quality in [0, 1] (1: the full behaviour); :meth:`set_skill` changes it.
        carries_over: whether its client state outlives an episode as in real HFO (agent2d's does: the trainer
            re-places only the server's objects). An env restarts such an NPC (:meth:`restart`) only when it is
            reseeded.
    """

    params: ServerParams
    rng: np.random.Generator
    skill: float
    carries_over: bool

    def reset(self) -> None:
        """A new episode starts (the field has been placed)."""

    def restart(self) -> None:
        """Forget everything, as a freshly made NPC (with the same params, generator and skill)."""

    def set_skill(self, skill: float) -> None:
        """Play with quality ``skill`` in [0, 1] from now on (an env calls it between episodes)."""

    def start_body_deg(self, rng: np.random.Generator) -> float:
        """The body angle (degrees) it starts an episode with when the server carries none over."""

    def decide(self, world: World, player: PlayerState) -> Any:
        """Decide the coming cycle on the state after the last step; the NPC keeps the decision for :meth:`apply`
        (and returns it)."""

    def apply(self, world: World, player: PlayerState) -> None:
        """Send the command :meth:`decide` kept this cycle to the world."""

    def act(self, world: World, player: PlayerState) -> None:
        """:meth:`decide`, then :meth:`apply`."""


class StillGoalie:
    """A goalie that never moves (``HFO/StaticKeeper-v0``): it stands on the goal line facing the field."""

    carries_over = False

    def __init__(self, params: ServerParams, rng: np.random.Generator, skill: float = 1.0) -> None:
        self.params = params
        self.rng = rng
        self.skill = float(skill)

    def reset(self) -> None:
        """Nothing to forget."""

    def restart(self) -> None:
        """Nothing to forget."""

    def set_skill(self, skill: float) -> None:
        """Recorded only: a still goalie plays the same at any skill."""
        self.skill = float(skill)

    def start_body_deg(self, rng: np.random.Generator) -> float:
        """Facing the field (no draw)."""
        return KEEPER_START_BODY_DEG

    def decide(self, world: World, player: PlayerState) -> None:
        """No decision."""
        return None

    def apply(self, world: World, player: PlayerState, decision: None = None) -> None:
        """No command."""

    def act(self, world: World, player: PlayerState) -> None:
        """No command."""
