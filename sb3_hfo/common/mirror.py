"""HFO's mirror image (:mod:`hfo2d.symmetry`) as torch operations on batches, for SkillDDPG and HFOPolicy."""

from __future__ import annotations

from typing import NamedTuple

import torch as th

from hfo2d.hfo_env import FLAT_ACTION_SIZE
from hfo2d.symmetry import feature_mirror, flat_action_mirror_signs

__all__ = ["Mirror", "make_mirror"]


class Mirror(NamedTuple):
    """Index and sign tensors of the mirror image: ``observations (B, obs_dim)[:, source] * sign`` and
    ``actions (B, 8) * action_sign`` (actions in SB3's [-1, 1] scale)."""

    source: th.Tensor
    sign: th.Tensor
    action_sign: th.Tensor

    def observations(self, obs: th.Tensor) -> th.Tensor:
        """The mirror image of ``obs (B, obs_dim)``."""
        return obs[:, self.source] * self.sign

    def actions(self, actions: th.Tensor) -> th.Tensor:
        """The mirror image of ``actions (B, 8)`` in [-1, 1]."""
        return actions * self.action_sign

    def to(self, device: th.device) -> Mirror:
        """The same tensors on ``device``."""
        return Mirror(*(tensor.to(device) for tensor in self))


def make_mirror(obs_shape: tuple[int, ...] | None, action_dim: int, option: str) -> Mirror:
    """The :class:`Mirror` of HFO observations of ``obs_shape`` and flat actions of ``action_dim`` entries (CPU).

    :raises ValueError: naming ``option`` when the spaces are not HFO's feature vector and 8-dimensional action.
    """
    if action_dim != FLAT_ACTION_SIZE:
        raise ValueError(
            f"{option} needs HFO's {FLAT_ACTION_SIZE}-dimensional flat action, got action dim {action_dim}"
        )
    if obs_shape is None or len(obs_shape) != 1:
        raise ValueError(f"{option} needs HFO's 1-D feature vector, got observation shape {obs_shape}")
    try:
        source, sign = feature_mirror(obs_shape[0])
    except ValueError as error:
        raise ValueError(f"{option}: {error}") from None
    return Mirror(
        th.tensor(source, dtype=th.long),
        th.tensor(sign, dtype=th.float32),
        th.tensor(flat_action_mirror_signs(), dtype=th.float32),
    )
