"""The hybrid action layout: a parameterised action flattened into one ``Box`` vector, declared in one place.

A parameterised action (Masson et al. 2016; HFO's DASH(power, direction), TURN(direction), KICK(power, direction))
is flattened as ``[one preference per discrete action, then each action's parameters in order]``. The discrete
action played is the one with the largest preference, the first on ties; only its parameters are executed.
:class:`HybridActionLayout` says where everything sits and holds that rule (:meth:`~HybridActionLayout.decode`,
:meth:`~HybridActionLayout.choose`). The env declares its layout by its action space, a :class:`HybridActionBox`;
:func:`action_layout` reads it back, and returns ``None`` for any other space (a plain ``Box``: no discrete
actions, plain DDPG semantics for an agent).

This module needs numpy and gymnasium only (no torch), so that ``hfo2d`` stays importable without it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from gymnasium import spaces

__all__ = [
    "ACTION_NAMES",
    "DASH",
    "HFO_FLAT_ACTION_LAYOUT",
    "KICK",
    "TURN",
    "HybridActionBox",
    "HybridActionLayout",
    "action_layout",
    "hfo_flat_action_space",
]

#: HFO's discrete actions in the flat action's order (gym-soccer's and the paper's DASH, TURN, KICK).
ACTION_NAMES: tuple[str, ...] = ("DASH", "TURN", "KICK")
DASH, TURN, KICK = 0, 1, 2


@dataclass(frozen=True)
class HybridActionLayout:
    """Where the preferences and each discrete action's parameters sit in a flat hybrid action.

    :param names: the discrete actions, in the order of their preferences (entries ``0 .. n - 1``).
    :param parameter_sizes: how many parameters each discrete action has, in the same order; they follow the
        preferences, action after action.
    :param direction_indices: flat indices of the parameters that are directions (the flat scale's ends are
        -180 and +180 degrees); ``()`` when none is.
    :param ball_action: index of the discrete action that needs the ball within reach (HFO's KICK: rcssserver
        ignores a kick otherwise), or ``None``.
    """

    names: tuple[str, ...]
    parameter_sizes: tuple[int, ...]
    direction_indices: tuple[int, ...] = ()
    ball_action: int | None = None

    def __post_init__(self) -> None:
        if len(self.names) == 0 or len(self.names) != len(self.parameter_sizes):
            raise ValueError(
                f"a hybrid action layout needs one parameter size per discrete action, got names {self.names} "
                f"and parameter_sizes {self.parameter_sizes}"
            )
        if any(
            isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0 for n in self.parameter_sizes
        ):
            raise ValueError(f"parameter_sizes must be ints >= 0, got {self.parameter_sizes}")
        parameters = range(self.n_discrete, self.size)
        if any(index not in parameters for index in self.direction_indices):
            raise ValueError(
                f"direction_indices must be parameter indices in [{self.n_discrete}, {self.size}), got "
                f"{self.direction_indices}"
            )
        if self.ball_action is not None and not 0 <= self.ball_action < self.n_discrete:
            raise ValueError(f"ball_action must be a discrete action index or None, got {self.ball_action}")

    @classmethod
    def from_sizes(cls, parameter_sizes: Sequence[int]) -> HybridActionLayout:
        """A layout with anonymous discrete actions (``"action_0"``, ...), no directions and no ball action."""
        sizes = tuple(int(n) for n in parameter_sizes)
        return cls(names=tuple(f"action_{k}" for k in range(len(sizes))), parameter_sizes=sizes)

    @property
    def n_discrete(self) -> int:
        """Number of discrete actions (= preferences at the front of the flat action)."""
        return len(self.names)

    @property
    def size(self) -> int:
        """Entries of the flat action: the preferences and every parameter."""
        return self.n_discrete + sum(self.parameter_sizes)

    def parameter_slice(self, action: int) -> slice:
        """Where discrete action ``action``'s parameters sit in the flat action."""
        start = self.n_discrete + sum(self.parameter_sizes[:action])
        return slice(start, start + self.parameter_sizes[action])

    def action_direction(self, action: int) -> int | None:
        """Flat index of discrete action ``action``'s first direction parameter, or ``None``."""
        own = range(self.size)[self.parameter_slice(action)]
        return next((index for index in self.direction_indices if index in own), None)

    def parameter_masks(self, with_preferences: bool = True) -> np.ndarray:
        """``(n_discrete, size)`` float32: row ``k`` is 1 on discrete action ``k``'s parameters (and, with
        ``with_preferences``, on every preference), 0 elsewhere: what the env executes when ``k`` is played."""
        masks = np.zeros((self.n_discrete, self.size), dtype=np.float32)
        for action in range(self.n_discrete):
            masks[action, self.parameter_slice(action)] = 1.0
        if with_preferences:
            masks[:, : self.n_discrete] = 1.0
        return masks

    def choose(self, flat: np.ndarray) -> np.ndarray:
        """The discrete action played for each flat action ``(..., size)``: the largest preference, the first on
        ties (numpy's and torch's ``argmax``, the same rule as :meth:`decode`)."""
        return np.asarray(flat)[..., : self.n_discrete].argmax(axis=-1)

    def decode(self, flat: Sequence[float]) -> tuple[int, Sequence[float]]:
        """``(discrete action, its parameters)`` of one flat action: the largest preference, the first on ties."""
        best = 0
        for action in range(1, self.n_discrete):
            if flat[action] > flat[best]:
                best = action
        return best, flat[self.parameter_slice(best)]


#: HFO's flat action (hfo2d's ``action_format="flat"``, the paper's): [pref_dash, pref_turn, pref_kick,
#: dash_power, dash_dir, turn_dir, kick_power, kick_dir], each in [0, 1] (powers 0..100, directions -180..180).
HFO_FLAT_ACTION_LAYOUT = HybridActionLayout(
    names=ACTION_NAMES, parameter_sizes=(2, 1, 2), direction_indices=(4, 5, 7), ball_action=KICK
)


class HybridActionBox(spaces.Box):
    """A ``Box`` whose vector is a flat hybrid action laid out by :attr:`layout` (equal to the plain ``Box`` of the
    same bounds, so models saved with either load with either)."""

    def __init__(
        self,
        layout: HybridActionLayout,
        low: float = 0.0,
        high: float = 1.0,
        dtype: Any = np.float32,
        seed: int | np.random.Generator | None = None,
    ) -> None:
        super().__init__(low, high, shape=(layout.size,), dtype=dtype, seed=seed)
        self.layout = layout

    def __repr__(self) -> str:
        return f"HybridActionBox({self.layout.names}, {super().__repr__()})"


def action_layout(space: spaces.Space) -> HybridActionLayout | None:
    """The hybrid action layout ``space`` declares (a :class:`HybridActionBox`), or ``None``."""
    return space.layout if isinstance(space, HybridActionBox) else None


def hfo_flat_action_space() -> HybridActionBox:
    """HFO's flat action space: ``Box(0, 1, (8,))`` laid out by :data:`HFO_FLAT_ACTION_LAYOUT`."""
    return HybridActionBox(HFO_FLAT_ACTION_LAYOUT)
