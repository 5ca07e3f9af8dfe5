"""The agent's reading of a flat hybrid action: where the preferences and each discrete action's parameters sit.

An env declares the layout of its flat ``Box`` action by a ``layout`` attribute on the action space holding
``names`` and ``parameter_sizes`` (and optionally ``direction_indices`` and ``ball_action``); hfo2d's
``HybridActionBox`` is one such space. :func:`space_layout` reads that attribute by duck typing into an
:class:`ActionLayout`, so that no algorithm or policy imports an env package. The flat vector is ``[one preference
per discrete action, then each action's parameters in order]``; the env plays the largest preference (the first on
ties) with that action's parameters (Masson et al. 2016's parameterised actions, as HFO's flat action lays them out).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from gymnasium import spaces

__all__ = ["ActionLayout", "space_layout"]


@dataclass(frozen=True)
class ActionLayout:
    """Where everything sits in a flat hybrid action (see the module docstring).

    :param names: the discrete actions, in the order of their preferences.
    :param parameter_sizes: how many parameters each discrete action has, in the same order.
    :param direction_indices: flat indices of the parameters that are directions (the scale's ends are -180 and +180
        degrees; the critic's direction features encode them); ``()`` when none is.
    :param ball_action: the discrete action that takes effect only with the ball within reach (HFO's KICK), or None.
    :raises ValueError: sizes, directions or a ball action that do not fit together.
    """

    names: tuple[str, ...]
    parameter_sizes: tuple[int, ...]
    direction_indices: tuple[int, ...] = ()
    ball_action: int | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "names", tuple(str(name) for name in self.names))
        sizes = tuple(self.parameter_sizes)
        if not sizes or len(sizes) != len(self.names):
            raise ValueError(
                f"an action layout needs one parameter size per discrete action, got names {self.names} and "
                f"parameter_sizes {sizes}"
            )
        if any(isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0 for n in sizes):
            raise ValueError(f"parameter_sizes must be ints >= 0, got {sizes}")
        object.__setattr__(self, "parameter_sizes", tuple(int(n) for n in sizes))
        object.__setattr__(self, "direction_indices", tuple(int(i) for i in self.direction_indices))
        if any(index not in range(self.n_discrete, self.size) for index in self.direction_indices):
            raise ValueError(
                f"direction_indices must be parameter indices in [{self.n_discrete}, {self.size}), got "
                f"{self.direction_indices}"
            )
        if self.ball_action is not None and not 0 <= self.ball_action < self.n_discrete:
            raise ValueError(f"ball_action must be a discrete action index or None, got {self.ball_action}")

    @classmethod
    def from_sizes(cls, parameter_sizes: Sequence[int]) -> ActionLayout:
        """A layout with anonymous discrete actions (``"action_0"``, ...), no directions and no ball action."""
        sizes = tuple(parameter_sizes)
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


def space_layout(space: spaces.Space) -> ActionLayout | None:
    """The layout a ``Box`` action space declares by its ``layout`` attribute, as an :class:`ActionLayout`; ``None``
    for a space without one (a plain ``Box``: no discrete actions).

    :raises ValueError: a ``layout`` without ``names`` and ``parameter_sizes``, or one that does not describe the
        space's flat vector.
    """
    declared = getattr(space, "layout", None)
    if declared is None or not isinstance(space, spaces.Box):
        return None
    try:
        layout = ActionLayout(
            names=tuple(declared.names),
            parameter_sizes=tuple(declared.parameter_sizes),
            direction_indices=tuple(getattr(declared, "direction_indices", ()) or ()),
            ball_action=getattr(declared, "ball_action", None),
        )
    except (AttributeError, TypeError) as error:
        raise ValueError(
            f"the action space's layout {declared!r} needs 'names' and 'parameter_sizes' ({error})"
        ) from None
    if space.shape != (layout.size,):
        raise ValueError(
            f"the action space's layout {declared!r} describes {layout.size} entries, but the space has shape "
            f"{space.shape}"
        )
    return layout
