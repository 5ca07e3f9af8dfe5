"""A task's mirror image (its :class:`~sb3_hfo.common.domain.DomainAdapter`'s) as torch operations on batches, for
SkillDDPG and HFOPolicy."""

from __future__ import annotations

from typing import NamedTuple

import torch as th

from sb3_hfo.common.action_layout import ActionLayout
from sb3_hfo.common.domain import DomainAdapter

__all__ = ["Mirror", "make_mirror"]


class Mirror(NamedTuple):
    """Index and sign tensors of the mirror image: ``observations (B, obs_dim)[:, source] * sign`` and
    ``actions (B, action_dim) * action_sign`` (actions in SB3's [-1, 1] scale)."""

    source: th.Tensor
    sign: th.Tensor
    action_sign: th.Tensor

    def observations(self, obs: th.Tensor) -> th.Tensor:
        """The mirror image of ``obs (B, obs_dim)``."""
        return obs[:, self.source] * self.sign

    def actions(self, actions: th.Tensor) -> th.Tensor:
        """The mirror image of ``actions (B, action_dim)`` in [-1, 1]."""
        return actions * self.action_sign

    def to(self, device: th.device) -> Mirror:
        """The same tensors on ``device``."""
        return Mirror(*(tensor.to(device) for tensor in self))


def make_mirror(
    obs_shape: tuple[int, ...] | None, layout: ActionLayout | None, option: str, domain: DomainAdapter
) -> Mirror:
    """The :class:`Mirror` of ``domain`` for observations of ``obs_shape`` and flat actions laid out by ``layout``
    (CPU).

    :raises ValueError: naming ``option`` when the domain knows no mirror, or the spaces are not the ones its mirror
        is for.
    """
    if domain.observation_mirror is None or domain.action_mirror_signs is None:
        raise ValueError(
            f"{option} needs a domain that knows its mirror image; the {domain.name} domain does not"
        )
    if layout is None or layout.parameter_sizes != domain.mirror_parameter_sizes:
        raise ValueError(
            f"{option} needs the {domain.name} domain's flat action (parameter sizes "
            f"{domain.mirror_parameter_sizes}), got layout {layout}"
        )
    if obs_shape is None or len(obs_shape) != 1:
        raise ValueError(f"{option} needs a 1-D feature vector, got observation shape {obs_shape}")
    try:
        source, sign = domain.observation_mirror(obs_shape[0])
    except ValueError as error:
        raise ValueError(f"{option}: {error}") from None
    return Mirror(
        th.tensor(source, dtype=th.long),
        th.tensor(sign, dtype=th.float32),
        th.tensor(domain.action_mirror_signs, dtype=th.float32),
    )
