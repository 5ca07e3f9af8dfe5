"""The hybrid action adapter: one internal action vector, many env action formats.

HybridPPO's policy and rollout buffer see every action as one float vector ``[k, u_0, ..., u_{P-1}]``: ``k`` the
discrete action (an integer stored as a float), ``u_j`` every continuous parameter of every discrete action on a
normalised scale where ``-1`` is the parameter's env lower bound and ``+1`` its upper bound. The parameters are
sampled unbounded (a Gaussian) and kept so in the buffer; :meth:`ActionAdapter.to_env` clips them to ``[-1, 1]``
(the env's bounds, as SB3 clips a Box action) and maps them linearly onto ``[low, high]``.

Which parameters belong to which discrete action is a ``(K, P)`` boolean matrix, :attr:`ActionAdapter.parameter_mask`:
row ``k`` marks what the env reads when ``k`` is played; HybridPPO's log-probability and entropy count only those.
:meth:`ActionAdapter.from_space` reads it from the env's action space (duck typing only, no env package imported):

* a ``Box`` with a ``layout`` attribute holding ``names`` and ``parameter_sizes`` (hfo2d's layout contract,
  ``hfo2d.action_layout``): the flat vector is ``K`` preferences, then each action's parameters in order; the env
  plays the largest preference, so the adapter sends a one-hot preference (the chosen one at its upper bound, the
  others at their lower bounds);
* ``Tuple(Discrete(K), Box(P))`` (gym-platform / gym-hybrid style): ``P`` = all parameters, the env reads the chosen
  action's part. Which part is the env's business, so by default every action is assumed to read all ``P``
  parameters (each row of the mask is all ones: the log-probability then counts all of them);
  ``parameter_sizes=(n_0, ..., n_{K-1})`` (summing to ``P``) says that action ``k`` reads the ``n_k`` entries after
  those of actions ``0 .. k-1``;
* ``Tuple(Discrete(K), Box_0, ..., Box_{K-1})``, one ``Box`` per action (gym-soccer; hfo2d's
  ``action_format="parameterized"``), and ``Tuple(Discrete(K), Tuple(Box_0, ..., Box_{K-1}))`` (gym-platform);
* a plain ``Box`` (``K = 1``: a pure Gaussian policy) and a plain ``Discrete`` (``P = 0``: a pure categorical).

This module needs numpy and gymnasium only.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from gymnasium import spaces

__all__ = ["ActionAdapter"]

#: Formats :meth:`ActionAdapter.to_env` writes, one per supported kind of action space.
FORMATS = ("layout_box", "box", "discrete", "tuple_shared", "tuple_per_action", "tuple_nested")


def _finite_box(space: spaces.Space, where: str) -> spaces.Box:
    if not isinstance(space, spaces.Box) or not np.issubdtype(space.dtype, np.floating):
        raise ValueError(f"HybridPPO: {where} must be a float Box, got {space!r}")
    if not (np.all(np.isfinite(space.low)) and np.all(np.isfinite(space.high))):
        raise ValueError(
            f"HybridPPO: {where} {space!r} has infinite bounds; the parameters are scaled onto [low, high]"
        )
    return space


def _mask_from_sizes(sizes: Sequence[int], n_parameters: int) -> np.ndarray:
    mask = np.zeros((len(sizes), n_parameters), dtype=bool)
    start = 0
    for action, size in enumerate(sizes):
        mask[action, start : start + size] = True
        start += size
    return mask


def _check_sizes(
    parameter_sizes: Sequence[int], n_discrete: int, n_parameters: int, space: Any
) -> tuple[int, ...]:
    sizes = tuple(parameter_sizes)
    if (
        len(sizes) != n_discrete
        or any(isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0 for n in sizes)
        or sum(sizes) != n_parameters
    ):
        raise ValueError(
            f"HybridPPO: parameter_sizes {sizes} must be {n_discrete} ints >= 0 summing to {n_parameters} "
            f"for the action space {space!r}"
        )
    return tuple(int(n) for n in sizes)


class ActionAdapter:
    """Maps HybridPPO's internal action vectors ``(n, 1 + P)`` to an env's actions and back (module docstring).

    Build it with :meth:`from_space`. Attributes: ``kind`` (one of :data:`FORMATS`), ``names`` (the ``K`` discrete
    actions), ``parameter_mask`` (``(K, P)`` bool), ``low`` / ``high`` (``(P,)`` env bounds of each parameter).
    """

    def __init__(
        self,
        space: spaces.Space,
        kind: str,
        names: Sequence[str],
        parameter_mask: np.ndarray,
        low: np.ndarray,
        high: np.ndarray,
    ) -> None:
        self.space = space
        self.kind = kind
        self.names = tuple(str(name) for name in names)
        self.parameter_mask = np.asarray(parameter_mask, dtype=bool)
        self.low = np.asarray(low, dtype=np.float64).reshape(-1)
        self.high = np.asarray(high, dtype=np.float64).reshape(-1)

    # ---- construction -------------------------------------------------------------------------------------------
    @classmethod
    def from_space(cls, space: spaces.Space, parameter_sizes: Sequence[int] | None = None) -> ActionAdapter:
        """The adapter for ``space``; ``parameter_sizes`` only for ``Tuple(Discrete(K), Box(P))`` (see module doc).

        :raises ValueError: an unsupported space (named in the message), or ``parameter_sizes`` that do not fit.
        """
        layout = getattr(space, "layout", None)
        if isinstance(space, spaces.Box) and layout is not None:
            return cls._from_layout_box(space, layout, parameter_sizes)
        if isinstance(space, spaces.Box):
            cls._no_sizes(parameter_sizes, space)
            box = _finite_box(space, "a Box action space")
            size = int(np.prod(box.shape))
            return cls(space, "box", ("action",), np.ones((1, size), bool), box.low, box.high)
        if isinstance(space, spaces.Discrete):
            cls._no_sizes(parameter_sizes, space)
            names = tuple(f"action_{k}" for k in range(int(space.n)))
            return cls(space, "discrete", names, np.zeros((int(space.n), 0), bool), np.zeros(0), np.zeros(0))
        if (
            isinstance(space, spaces.Tuple)
            and len(space.spaces) >= 2
            and isinstance(space.spaces[0], spaces.Discrete)
        ):
            return cls._from_tuple(space, parameter_sizes)
        raise ValueError(
            f"HybridPPO does not support the action space {space!r}: use a Box (with or without a hybrid 'layout'), "
            "a Discrete, Tuple(Discrete(K), Box(P)), Tuple(Discrete(K), Box_0, ..., Box_K-1) or "
            "Tuple(Discrete(K), Tuple(Box_0, ..., Box_K-1))"
        )

    @staticmethod
    def _no_sizes(parameter_sizes: Sequence[int] | None, space: spaces.Space) -> None:
        if parameter_sizes is not None:
            raise ValueError(
                f"HybridPPO: parameter_sizes is only for Tuple(Discrete(K), Box(P)) action spaces, not {space!r}"
            )

    @classmethod
    def _from_layout_box(
        cls, space: spaces.Box, layout: Any, parameter_sizes: Sequence[int] | None
    ) -> ActionAdapter:
        box = _finite_box(space, "a hybrid layout Box")
        try:
            names = tuple(layout.names)
            sizes = tuple(int(n) for n in layout.parameter_sizes)
        except (AttributeError, TypeError) as error:
            raise ValueError(
                f"HybridPPO: the action space's layout {layout!r} needs 'names' and 'parameter_sizes' ({error})"
            ) from None
        n_discrete = len(names)
        if len(box.shape) != 1 or box.shape[0] != n_discrete + sum(sizes) or len(sizes) != n_discrete:
            raise ValueError(
                f"HybridPPO: layout {layout!r} (names {names}, parameter_sizes {sizes}) does not describe the "
                f"flat action space {space!r} (expected shape ({n_discrete + sum(sizes)},))"
            )
        if parameter_sizes is not None and tuple(parameter_sizes) != sizes:
            raise ValueError(
                f"HybridPPO: parameter_sizes {tuple(parameter_sizes)} differ from the env's layout {sizes}"
            )
        n_parameters = sum(sizes)
        return cls(
            space,
            "layout_box",
            names,
            _mask_from_sizes(sizes, n_parameters),
            box.low[n_discrete:],
            box.high[n_discrete:],
        )

    @classmethod
    def _from_tuple(cls, space: spaces.Tuple, parameter_sizes: Sequence[int] | None) -> ActionAdapter:
        discrete, rest = space.spaces[0], space.spaces[1:]
        n_discrete = int(discrete.n)
        names = tuple(f"action_{k}" for k in range(n_discrete))
        if int(discrete.start) != 0:
            raise ValueError(f"HybridPPO: the discrete part of {space!r} must start at 0")
        if len(rest) == 1 and isinstance(rest[0], spaces.Box):
            box = _finite_box(rest[0], f"the parameter Box of {space!r}")
            if len(box.shape) != 1:
                raise ValueError(f"HybridPPO: the parameter Box of {space!r} must be 1-D")
            n_parameters = box.shape[0]
            if parameter_sizes is None:  # every action may read every parameter (module docstring)
                mask = np.ones((n_discrete, n_parameters), dtype=bool)
            else:
                mask = _mask_from_sizes(
                    _check_sizes(parameter_sizes, n_discrete, n_parameters, space), n_parameters
                )
            return cls(space, "tuple_shared", names, mask, box.low, box.high)
        kind = "tuple_per_action"
        if len(rest) == 1 and isinstance(rest[0], spaces.Tuple):
            rest, kind = rest[0].spaces, "tuple_nested"
        if len(rest) != n_discrete:
            raise ValueError(
                f"HybridPPO does not support the action space {space!r}: after Discrete({n_discrete}) it needs one "
                f"Box of parameters, or one Box per discrete action ({n_discrete}), got {len(rest)} spaces"
            )
        boxes = [_finite_box(box, f"parameter space {i} of {space!r}") for i, box in enumerate(rest)]
        if any(len(box.shape) != 1 for box in boxes):
            raise ValueError(f"HybridPPO: every parameter Box of {space!r} must be 1-D")
        sizes = tuple(int(box.shape[0]) for box in boxes)
        if parameter_sizes is not None and tuple(parameter_sizes) != sizes:
            raise ValueError(
                f"HybridPPO: parameter_sizes {tuple(parameter_sizes)} differ from the space's {sizes}"
            )
        low = np.concatenate([box.low for box in boxes]) if boxes else np.zeros(0)
        high = np.concatenate([box.high for box in boxes]) if boxes else np.zeros(0)
        return cls(space, kind, names, _mask_from_sizes(sizes, sum(sizes)), low, high)

    # ---- sizes --------------------------------------------------------------------------------------------------
    @property
    def n_discrete(self) -> int:
        """``K``, the number of discrete actions."""
        return self.parameter_mask.shape[0]

    @property
    def n_parameters(self) -> int:
        """``P``, the number of continuous parameters of all discrete actions together."""
        return self.parameter_mask.shape[1]

    @property
    def internal_size(self) -> int:
        """Length of an internal action vector: ``1 + P``."""
        return 1 + self.n_parameters

    # ---- conversions --------------------------------------------------------------------------------------------
    def scale(self, normalised: np.ndarray) -> np.ndarray:
        """Parameters ``(..., P)`` on the normalised scale, clipped to ``[-1, 1]``, in the env's ``[low, high]``."""
        clipped = np.clip(normalised, -1.0, 1.0)
        return self.low + (clipped + 1.0) * 0.5 * (self.high - self.low)

    def unscale(self, parameters: np.ndarray) -> np.ndarray:
        """Env parameters ``(..., P)`` on the normalised ``[-1, 1]`` scale (inverse of :meth:`scale` in bounds)."""
        span = np.where(self.high > self.low, self.high - self.low, 1.0)
        return 2.0 * (np.asarray(parameters, dtype=np.float64) - self.low) / span - 1.0

    def to_env(self, internal: np.ndarray) -> Any:
        """A batch of internal vectors ``(n, 1 + P)`` as a batch of env actions: an array ``(n, ...)`` for a Box
        or Discrete space, a list of ``n`` tuples for a Tuple space (what SB3's VecEnvs step with)."""
        internal = np.asarray(internal)
        if internal.ndim != 2 or internal.shape[1] != self.internal_size:
            raise ValueError(
                f"internal actions must have shape (n, {self.internal_size}), got {internal.shape}"
            )
        discrete = internal[:, 0].astype(np.int64)
        parameters = self.scale(internal[:, 1:])
        if self.kind == "discrete":
            return (discrete + int(self.space.start)).astype(self.space.dtype)
        if self.kind == "box":
            return parameters.reshape((-1, *self.space.shape)).astype(self.space.dtype)
        if self.kind == "layout_box":
            n_discrete = self.n_discrete
            preferences = np.where(
                np.arange(n_discrete) == discrete[:, None],
                self.space.high[:n_discrete],
                self.space.low[:n_discrete],
            )
            return np.concatenate([preferences, parameters], axis=1).astype(self.space.dtype)
        if self.kind == "tuple_shared":
            box = self.space.spaces[1]
            return [(int(k), p.astype(box.dtype)) for k, p in zip(discrete, parameters, strict=True)]
        boxes = self.space.spaces[1:] if self.kind == "tuple_per_action" else self.space.spaces[1].spaces
        ends = np.cumsum([0, *self.parameter_mask.sum(axis=1)])
        actions = []
        for k, row in zip(discrete, parameters, strict=True):
            parts = tuple(row[ends[i] : ends[i + 1]].astype(box.dtype) for i, box in enumerate(boxes))
            actions.append((int(k), *parts) if self.kind == "tuple_per_action" else (int(k), parts))
        return actions

    def from_env(self, actions: Any) -> np.ndarray:
        """A batch of env actions (as :meth:`to_env` returns them) as internal vectors ``(n, 1 + P)`` float32; the
        discrete action of a layout Box is its largest preference (the first on ties), as the env plays it."""
        if self.kind == "discrete":
            discrete = np.asarray(actions, dtype=np.int64).reshape(-1) - int(self.space.start)
            return discrete[:, None].astype(np.float32)
        if self.kind == "box":
            flat = np.asarray(actions, dtype=np.float64).reshape(-1, self.n_parameters)
            return np.concatenate([np.zeros((len(flat), 1)), self.unscale(flat)], axis=1).astype(np.float32)
        if self.kind == "layout_box":
            flat = np.asarray(actions, dtype=np.float64).reshape(-1, self.n_discrete + self.n_parameters)
            discrete = flat[:, : self.n_discrete].argmax(axis=1)
            parameters = self.unscale(flat[:, self.n_discrete :])
        else:
            discrete = np.array([int(action[0]) for action in actions], dtype=np.int64)
            if self.kind == "tuple_shared":
                raw = np.array([np.asarray(action[1]) for action in actions], dtype=np.float64)
            elif self.kind == "tuple_per_action":
                raw = np.array([np.concatenate([np.asarray(p) for p in action[1:]]) for action in actions])
            else:
                raw = np.array([np.concatenate([np.asarray(p) for p in action[1]]) for action in actions])
            parameters = self.unscale(raw.reshape(len(discrete), self.n_parameters))
        return np.concatenate([discrete[:, None], parameters], axis=1).astype(np.float32)

    def __repr__(self) -> str:
        sizes = tuple(int(n) for n in self.parameter_mask.sum(axis=1))
        return f"ActionAdapter({self.kind}, names={self.names}, parameters per action={sizes})"
