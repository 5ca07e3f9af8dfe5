"""HFO's mirror image (:mod:`hfo2d.symmetry`) as torch operations on batches, for SkillDDPG and HFOPolicy."""

from __future__ import annotations

from typing import NamedTuple

import torch as th

from hfo2d.action_layout import HFO_FLAT_ACTION_LAYOUT, HybridActionLayout
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


def make_mirror(obs_shape: tuple[int, ...] | None, layout: HybridActionLayout | None, option: str) -> Mirror:
    """The :class:`Mirror` of HFO observations of ``obs_shape`` and flat actions laid out by ``layout`` (CPU).

    :raises ValueError: naming ``option`` when the spaces are not HFO's feature vector and flat action.
    """
    if layout != HFO_FLAT_ACTION_LAYOUT:
        raise ValueError(
            f"{option} needs HFO's flat action (hfo2d's HFO_FLAT_ACTION_LAYOUT), got layout {layout}"
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
