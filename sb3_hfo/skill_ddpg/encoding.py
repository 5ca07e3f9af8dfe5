"""How the critic of :class:`~sb3_hfo.skill_ddpg.policies.HFOPolicy` sees the action: one encoder object.

The policy takes the encoding as one argument, ``critic_action_encoding``: ``None`` (the paper: the critic sees the
action as it is) or a :class:`DirectionFeatures` (also as a dict of its fields, the form a YAML config gives). The
policy turns it into an :class:`ActionEncoder`, the critic's module that computes the encoding and, for the fast
update (:mod:`sb3_hfo.skill_ddpg.fast_update`), its chain rule.

Why: on the [-1, 1] action scale a 5-degree change of the kick direction moves the critic's input by 0.028, too
little for it to tell a shot past a keeper from one at him; Fourier features of the directions (Tancik et al. 2020)
let the network fit such sharp functions, and "kick minus keeper bearing" is otherwise a difference of two inputs
the network has to form itself. The measurements are in docs/findings.md ("Fourier features of the directions").
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import torch as th
from torch import nn

from hfo2d.action_layout import HybridActionLayout
from hfo2d.features import (
    GOAL_CENTER_COS,
    GOAL_CENTER_SIN,
    GOAL_POST_BOTTOM_COS,
    GOAL_POST_BOTTOM_SIN,
    GOAL_POST_TOP_COS,
    GOAL_POST_TOP_SIN,
    GOALIE_ANGLE_COS,
    GOALIE_ANGLE_SIN,
)

__all__ = [
    "KICK_REFERENCE_BEARINGS",
    "ActionEncoder",
    "ActionEncodingSpec",
    "DirectionFeatures",
    "parse_encoding",
]

#: Landmarks the kick direction can be encoded relative to: name -> (sin, cos) columns of the landmark's bearing in
#: HFO's low-level features (hfo2d owns the layout).
KICK_REFERENCE_BEARINGS: dict[str, tuple[int, int]] = {
    "goalie": (GOALIE_ANGLE_SIN, GOALIE_ANGLE_COS),
    "goal_center": (GOAL_CENTER_SIN, GOAL_CENTER_COS),
    "goal_post_top": (GOAL_POST_TOP_SIN, GOAL_POST_TOP_COS),
    "goal_post_bottom": (GOAL_POST_BOTTOM_SIN, GOAL_POST_BOTTOM_COS),
}


def _positive_frequencies(frequencies: object) -> tuple[float, ...]:
    if isinstance(frequencies, (str, bytes)) or not isinstance(frequencies, Iterable):
        raise ValueError(f"DirectionFeatures frequencies must be a sequence of numbers, got {frequencies!r}")
    values = tuple(frequencies)
    if not values or not all(
        isinstance(k, (int, float, np.integer, np.floating))
        and not isinstance(k, bool)
        and np.isfinite(k)
        and k > 0
        for k in values
    ):
        raise ValueError(
            f"DirectionFeatures frequencies must be one or more finite numbers > 0, got {frequencies!r}"
        )
    return tuple(float(k) for k in values)


def _landmarks(names: object) -> tuple[str, ...]:
    if isinstance(names, (str, bytes)) or not isinstance(names, Iterable):
        raise ValueError(f"DirectionFeatures relative_to must be a sequence of landmark names, got {names!r}")
    values = tuple(names)
    unknown = [name for name in values if name not in KICK_REFERENCE_BEARINGS]
    if unknown:
        raise ValueError(
            f"DirectionFeatures relative_to: unknown landmark(s) {unknown}; choose from {tuple(KICK_REFERENCE_BEARINGS)}"
        )
    if len(set(values)) != len(values):
        raise ValueError(f"DirectionFeatures relative_to names a landmark twice: {values}")
    return values


@dataclass(frozen=True)
class DirectionFeatures:
    """The critic also sees ``sin(k * theta)`` and ``cos(k * theta)`` of each direction parameter of the action
    (``theta`` in radians) at every frequency ``k``, and of the kick direction relative to each landmark's bearing.

    The actor is unchanged; dQ/da goes through the features by the chain rule.

    :param frequencies: the frequencies ``k`` (> 0), e.g. ``(1, 2, 4, 8, 16, 32)``.
    :param relative_to: landmarks (:data:`KICK_REFERENCE_BEARINGS`: ``"goalie"``, ``"goal_center"``,
        ``"goal_post_top"``, ``"goal_post_bottom"``) whose bearing, read from the observation's (sin, cos) pair, the
        kick direction is also encoded relative to (both angles are relative to the body); ``()``: none.
    """

    frequencies: tuple[float, ...]
    relative_to: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "frequencies", _positive_frequencies(self.frequencies))
        object.__setattr__(self, "relative_to", _landmarks(self.relative_to))

    def as_dict(self) -> dict[str, list[Any]]:
        """The fields as plain lists: what :func:`parse_encoding` reads back and what a model saves."""
        return {"frequencies": list(self.frequencies), "relative_to": list(self.relative_to)}


#: What ``HFOPolicy(critic_action_encoding=...)`` accepts: the encoding, its dict form, or ``None`` (none).
ActionEncodingSpec = DirectionFeatures | Mapping[str, Any] | None


def parse_encoding(spec: ActionEncodingSpec) -> DirectionFeatures | None:
    """``spec`` as a :class:`DirectionFeatures` (or ``None``).

    :raises ValueError: an unknown key or type, or a bad field (the message names it).
    """
    if spec is None or isinstance(spec, DirectionFeatures):
        return spec
    if isinstance(spec, Mapping):
        unknown = set(spec) - {"frequencies", "relative_to"}
        if unknown or "frequencies" not in spec:
            raise ValueError(
                "critic_action_encoding as a dict needs the key 'frequencies' (and optionally 'relative_to'), got "
                f"keys {sorted(spec)}"
            )
        return DirectionFeatures(**spec)
    raise ValueError(
        f"critic_action_encoding must be a DirectionFeatures, its dict form or None, got {type(spec).__name__}"
    )


class ActionEncoder(nn.Module):
    """The critic's view of the action: ``action (B, action_dim)`` -> ``(B, action_dim + 2 * n_features)``, the
    action followed by the sines, then the cosines, of its encoded angles (the action itself, no copy, when there
    are none).

    Angle column ``c``: first the absolute directions, ``direction_indices[c % n]`` at frequency ``c // n``; then
    the kick direction relative to each landmark, landmark ``c % m`` at frequency ``c // m``.

    :param action_dim: the action's size.
    :param encoding: what to encode (``None``: nothing).
    :param layout: the action layout, which names the direction parameters and the kick.
    :param obs_dim: the observation's size (the landmarks' bearings must lie inside it).
    :raises ValueError: an encoding the layout or the observation cannot give (the message says which).
    """

    def __init__(
        self,
        action_dim: int,
        encoding: DirectionFeatures | None = None,
        layout: HybridActionLayout | None = None,
        obs_dim: int = 0,
    ) -> None:
        super().__init__()
        self.action_dim = action_dim
        self.encoding = encoding
        directions: tuple[int, ...] = ()
        references: list[tuple[int, int, int]] = []
        frequencies: tuple[float, ...] = ()
        if encoding is not None:
            frequencies = encoding.frequencies
            if layout is None or not layout.direction_indices:
                raise ValueError(
                    "critic_action_encoding needs an action layout with direction parameters (HFO's flat action), "
                    f"got layout {layout}"
                )
            directions = tuple(layout.direction_indices)
            kick_direction = (
                None if layout.ball_action is None else layout.action_direction(layout.ball_action)
            )
            if encoding.relative_to and kick_direction is None:
                raise ValueError(
                    f"critic_action_encoding relative_to needs an action layout with a kick direction, got {layout}"
                )
            for name in encoding.relative_to:
                sin_column, cos_column = KICK_REFERENCE_BEARINGS[name]
                if max(sin_column, cos_column) >= obs_dim:
                    raise ValueError(
                        f"critic_action_encoding relative_to {name!r} needs observation column "
                        f"{max(sin_column, cos_column)}, but the observation has {obs_dim} features (the goalie's "
                        "bearing exists only on goalie tasks)"
                    )
                assert kick_direction is not None
                references.append((kick_direction, sin_column, cos_column))
        self.n_relative = len(references) * len(frequencies)
        #: Number of encoded angles (each gives a sine and a cosine).
        self.n_angles = len(directions) * len(frequencies) + self.n_relative
        self.index: th.Tensor
        self.scale: th.Tensor
        self.bearing_sin_column: th.Tensor
        self.bearing_cos_column: th.Tensor
        self.bearing_frequency: th.Tensor
        buffers = (
            (
                "index",
                list(directions) * len(frequencies) + [r[0] for r in references] * len(frequencies),
                th.long,
            ),
            (
                "scale",
                [np.pi * k for k in frequencies for _ in directions]
                + [np.pi * k for k in frequencies for _ in references],
                th.float32,
            ),
            ("bearing_sin_column", [r[1] for r in references] * len(frequencies), th.long),
            ("bearing_cos_column", [r[2] for r in references] * len(frequencies), th.long),
            ("bearing_frequency", [k for k in frequencies for _ in references], th.float32),
        )
        for name, values, dtype in buffers:
            # not persistent: they follow from the encoding, which the policy saves
            self.register_buffer(name, th.tensor(values, dtype=dtype), persistent=False)

    @property
    def out_dim(self) -> int:
        """The size of what the critic sees: ``action_dim + 2 * n_angles``."""
        return self.action_dim + 2 * self.n_angles

    def forward(self, action: th.Tensor, obs: th.Tensor | None = None) -> th.Tensor:
        """``action (B, action_dim)`` -> ``(B, out_dim)``; ``obs (B, obs_dim)`` gives the landmarks' bearings
        (needed when the encoding has ``relative_to``)."""
        if self.n_angles == 0:
            return action
        angles = action.index_select(1, self.index) * self.scale.to(action.dtype)
        if self.n_relative:
            if obs is None:
                raise ValueError(
                    "this critic encodes directions relative to bearings in the observation: pass obs"
                )
            bearings = th.atan2(
                obs.index_select(1, self.bearing_sin_column), obs.index_select(1, self.bearing_cos_column)
            )
            n_absolute = self.n_angles - self.n_relative
            angles = th.cat(
                (
                    angles[:, :n_absolute],
                    angles[:, n_absolute:] - bearings * self.bearing_frequency.to(action.dtype),
                ),
                dim=1,
            )
        return th.cat((action, th.sin(angles), th.cos(angles)), dim=1)

    def action_gradient(self, grad_seen: th.Tensor, seen: th.Tensor) -> th.Tensor:
        """The chain rule through :meth:`forward`: ``grad_seen``, d/d(its output) ``(B, out_dim)``, and that output
        ``seen`` -> d/d(action) ``(B, action_dim)`` (the bearings come from the observation, not the action)."""
        if self.n_angles == 0:
            return grad_seen
        dim, n = self.action_dim, self.n_angles
        sines, cosines = seen[:, dim : dim + n], seen[:, dim + n :]
        grad_angles = (grad_seen[:, dim : dim + n] * cosines - grad_seen[:, dim + n :] * sines) * self.scale
        return grad_seen[:, :dim].index_add(1, self.index, grad_angles)

    def extra_repr(self) -> str:
        return f"action_dim={self.action_dim}, encoding={self.encoding}"
