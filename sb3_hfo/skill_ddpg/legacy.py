"""The policy options that ``acting`` and ``critic_action_encoding`` replaced, translated for models and configs
that still carry them.

Before these two arguments, :class:`~sb3_hfo.skill_ddpg.policies.HFOPolicy` took six single options. A model saved
then holds them in its ``policy_kwargs``: :meth:`SkillDDPG.load <sb3_hfo.skill_ddpg.skill_ddpg.SkillDDPG>` translates
them silently, so that it acts and trains as it was saved. Given to ``SkillDDPG(policy_kwargs=...)`` they are
translated too, with a ``DeprecationWarning`` that names the replacement.
"""

from __future__ import annotations

import warnings
from typing import Any

from sb3_hfo.skill_ddpg.acting import CriticChoice, KickMask, MirrorChoice, format_acting, parse_acting
from sb3_hfo.skill_ddpg.encoding import DirectionFeatures, parse_encoding

#: The acting options and the strategy each one stood for.
LEGACY_ACTING_OPTIONS = ("discrete_choice", "kick_only_when_kickable", "mirror_choice", "mirror_margin")
#: The critic's action-encoding options, now the fields of :class:`DirectionFeatures`.
LEGACY_ENCODING_OPTIONS = ("critic_direction_frequencies", "critic_kick_relative_to")
LEGACY_POLICY_OPTIONS = LEGACY_ACTING_OPTIONS + LEGACY_ENCODING_OPTIONS


def _legacy_acting(acting: Any, options: dict[str, Any]) -> str:
    """``acting`` with each legacy option overriding its part (as the options did when they sat beside it)."""
    strategies = {type(s): s for s in parse_acting(acting)}
    choice = options.get("discrete_choice")
    if choice is not None:
        if choice not in ("actor", "critic"):
            raise ValueError(f"discrete_choice must be 'actor' or 'critic', got {choice!r}")
        strategies.pop(CriticChoice, None)
        if choice == "critic":
            strategies[CriticChoice] = CriticChoice()
    kick = options.get("kick_only_when_kickable")
    if kick is not None:
        if not isinstance(kick, bool):
            raise ValueError(f"kick_only_when_kickable must be a bool, got {kick!r}")
        strategies.pop(KickMask, None)
        if kick:
            strategies[KickMask] = KickMask()
    mirror, margin = options.get("mirror_choice"), options.get("mirror_margin")
    if mirror is not None and not isinstance(mirror, bool):
        raise ValueError(f"mirror_choice must be a bool, got {mirror!r}")
    if mirror is False:
        strategies.pop(MirrorChoice, None)
    elif mirror or (margin is not None and MirrorChoice in strategies):
        kept = strategies.get(MirrorChoice, MirrorChoice())
        strategies[MirrorChoice] = MirrorChoice(kept.margin if margin is None else margin)
    return format_acting(tuple(strategies.values()))


def _legacy_encoding(encoding: Any, options: dict[str, Any]) -> dict[str, list[Any]] | None:
    frequencies = options.get("critic_direction_frequencies") or ()
    landmarks = options.get("critic_kick_relative_to") or ()
    if not frequencies and not landmarks:
        parsed = parse_encoding(encoding)
        return None if parsed is None else parsed.as_dict()
    if encoding is not None:
        raise ValueError(
            "critic_action_encoding cannot be combined with critic_direction_frequencies / critic_kick_relative_to"
        )
    if not frequencies:
        raise ValueError(
            "critic_kick_relative_to needs critic_direction_frequencies (it uses the same frequencies)"
        )
    return DirectionFeatures(tuple(frequencies), tuple(landmarks)).as_dict()


def translate_legacy_options(policy_kwargs: dict[str, Any], warn: bool) -> dict[str, Any]:
    """``policy_kwargs`` with the legacy options folded into ``acting`` and ``critic_action_encoding``.

    :param warn: emit a ``DeprecationWarning`` naming the options found (a user's arguments; not a saved model's).
    :return: a new dict; ``policy_kwargs`` itself when it holds none of them.
    :raises ValueError: a bad value of a legacy option (the message names it).
    """
    found = [name for name in LEGACY_POLICY_OPTIONS if name in policy_kwargs]
    if not found:
        return policy_kwargs
    if warn:
        warnings.warn(
            f"policy_kwargs {found} are deprecated: use acting= (e.g. 'critic,kick_mask,mirror:0.1', "
            "sb3_hfo.skill_ddpg.acting) and critic_action_encoding=DirectionFeatures(frequencies, relative_to)",
            DeprecationWarning,
            stacklevel=3,
        )
    options = {name: policy_kwargs[name] for name in found}
    kept = {key: value for key, value in policy_kwargs.items() if key not in LEGACY_POLICY_OPTIONS}
    if any(name in options for name in LEGACY_ACTING_OPTIONS):
        kept["acting"] = _legacy_acting(kept.get("acting"), options)
    if any(name in options for name in LEGACY_ENCODING_OPTIONS):
        kept["critic_action_encoding"] = _legacy_encoding(kept.get("critic_action_encoding"), options)
    return kept
