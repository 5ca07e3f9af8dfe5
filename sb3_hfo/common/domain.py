"""Domain adapters: what an algorithm may know of the task beyond its spaces, handed to it as one object.

The algorithms and their policies (:mod:`sb3_hfo.skill_ddpg`, :mod:`sb3_hfo.hybrid_ppo`) import no environment
package. What they read from the env's spaces (the action layout: the discrete actions, their parameters, which
parameters are directions, which action needs the ball, :mod:`sb3_hfo.common.action_layout`) they take from there;
what the spaces cannot say comes from a :class:`DomainAdapter` given as the policy argument ``domain``:

* ``kickable_column``: the observation column that is +1 while the ball action can take effect and -1 while it
  cannot (the kick mask of :class:`~sb3_hfo.skill_ddpg.acting.KickMask` reads it);
* ``field_half_column`` / ``field_half_threshold``: the rule of the paper's ``"field_half"`` skill router
  (:func:`sb3_hfo.common.routers.make_router` builds it);
* ``observation_mirror`` / ``action_mirror_signs``: the task's mirror image, for
  :class:`~sb3_hfo.skill_ddpg.acting.MirrorChoice`;
* ``bearings``: landmark bearings in the observation, as (sin, cos) columns, that the critic's direction features
  may encode the ball action's direction relative to.

Every fact is optional; ``domain=None`` is :data:`GENERIC_DOMAIN`, which knows none of them (options that need one
are refused with a message that says so). A domain can be named by a string (e.g. ``"hfo"`` in a YAML config),
resolved through :data:`DOMAINS` to ``"module:attribute"``, imported only when used. HFO's adapter is
:data:`sb3_hfo.hfo.HFO_DOMAIN`.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from gymnasium import spaces

__all__ = ["DOMAINS", "GENERIC_DOMAIN", "LEGACY_DOMAIN", "DomainAdapter", "DomainSpec", "resolve_domain"]


@dataclass(frozen=True)
class DomainAdapter:
    """The facts of one task that its spaces do not carry (module docstring). ``None`` / empty: not known.

    :param name: the domain's name, for messages.
    :param kickable_column: observation column holding +1 (ball action possible) or -1 (not).
    :param field_half_column: observation column the field-half router splits on: skill 0 where it is above
        ``field_half_threshold``, skill 1 elsewhere.
    :param field_half_threshold: the dividing value of that column.
    :param bearings: ``(name, sin column, cos column)`` of each landmark whose bearing the observation holds.
    :param observation_mirror: ``n_features -> (source, sign)`` such that the mirrored observation is
        ``obs[source] * sign`` (raises ValueError for a size the domain does not know).
    :param action_mirror_signs: per-entry signs that mirror a flat action on the [-1, 1] scale.
    :param mirror_parameter_sizes: the ``parameter_sizes`` of the flat action layout ``action_mirror_signs`` is for.
    :param flat_action_space: the domain's flat action space with its layout, given back on load to a model saved
        with the same space as a plain ``Box`` (before spaces declared layouts).
    """

    name: str = "generic"
    kickable_column: int | None = None
    field_half_column: int | None = None
    field_half_threshold: float = 0.0
    bearings: tuple[tuple[str, int, int], ...] = ()
    observation_mirror: Callable[[int], tuple[Sequence[int], Sequence[float]]] | None = None
    action_mirror_signs: tuple[float, ...] | None = None
    mirror_parameter_sizes: tuple[int, ...] | None = None
    flat_action_space: spaces.Box | None = None

    def __post_init__(self) -> None:
        for field_name in ("kickable_column", "field_half_column"):
            value = getattr(self, field_name)
            if value is not None and (
                isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 0
            ):
                raise ValueError(
                    f"DomainAdapter {field_name} must be a column index >= 0 or None, got {value!r}"
                )
        object.__setattr__(self, "bearings", tuple((str(n), int(s), int(c)) for n, s, c in self.bearings))
        if (self.observation_mirror is None) != (self.action_mirror_signs is None):
            raise ValueError(
                "DomainAdapter needs both observation_mirror and action_mirror_signs, or neither"
            )

    @property
    def bearing_columns(self) -> dict[str, tuple[int, int]]:
        """Landmark name -> (sin column, cos column) of its bearing."""
        return {name: (sin_column, cos_column) for name, sin_column, cos_column in self.bearings}

    @property
    def has_mirror(self) -> bool:
        """Whether the domain knows its mirror image."""
        return self.observation_mirror is not None

    def __repr__(self) -> str:
        return f"DomainAdapter({self.name!r})"


#: The domain that knows nothing beyond the spaces: what ``domain=None`` means.
GENERIC_DOMAIN = DomainAdapter()

#: Domains by name: ``"module:attribute"`` of a :class:`DomainAdapter`, imported when the name is first resolved.
DOMAINS: dict[str, str] = {"hfo": "sb3_hfo.hfo:HFO_DOMAIN"}

#: The domain of a model saved before the algorithms took a ``domain`` (a new model saves its own, None included):
#: until then every domain fact they used (the field-half column, the kick mask's column, the mirror, the landmarks)
#: was hfo2d's, so such a model loads with HFO's adapter and acts as it was saved.
LEGACY_DOMAIN = "hfo"

#: What a policy's ``domain`` argument accepts: an adapter, the name of one in :data:`DOMAINS`, or None (generic).
DomainSpec = DomainAdapter | str | None


def resolve_domain(spec: DomainSpec) -> DomainAdapter:
    """``spec`` as a :class:`DomainAdapter` (``None``: :data:`GENERIC_DOMAIN`).

    :raises ValueError: an unknown name, or an object that is no DomainAdapter.
    """
    if spec is None:
        return GENERIC_DOMAIN
    if isinstance(spec, DomainAdapter):
        return spec
    if isinstance(spec, str):
        if spec not in DOMAINS:
            raise ValueError(
                f"unknown domain {spec!r}; known domains: {sorted(DOMAINS)} (or a DomainAdapter)"
            )
        module_name, _, attribute = DOMAINS[spec].partition(":")
        adapter = getattr(importlib.import_module(module_name), attribute)
        if not isinstance(adapter, DomainAdapter):
            raise ValueError(f"domain {spec!r} ({DOMAINS[spec]}) is no DomainAdapter: {adapter!r}")
        return adapter
    raise ValueError(f"domain must be a DomainAdapter, a domain name {sorted(DOMAINS)} or None, got {spec!r}")
