"""Acting strategies of :class:`~sb3_hfo.skill_ddpg.policies.HFOPolicy`: how a trained policy turns its actor's
output into the action it plays. They change no network, so they can be switched on a trained model.

Each strategy is a small frozen dataclass, and a policy takes any combination of them as one argument,
``acting``: a tuple of strategies or its text form, the strategies' tokens joined by commas (the form the
command lines take, ``evaluate --acting critic,kick_mask,mirror:0.1``):

* :class:`CriticChoice` (``critic``): the critic picks the discrete action at the actor's parameters, as P-DQN does;
  without it the actor's largest preference does.
* :class:`KickMask` (``kick_mask``): KICK is never the greedy choice while the ball is out of reach.
* :class:`MirrorChoice` (``mirror`` or ``mirror:M``): play the better, by the critic, of the greedy action in the
  state and in its mirror image; with a margin ``M > 0`` the side played is kept through an episode, in
  ``predict``'s ``state``, and switched only when the other is better by more than ``M``.

The empty tuple (text ``""`` or ``"actor"``) is the paper's policy: the actor's greedy action as it is.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class CriticChoice:
    """The critic picks the discrete action, trying each one at the actor's parameters."""

    token = "critic"

    def __str__(self) -> str:
        return self.token


@dataclass(frozen=True)
class KickMask:
    """KICK is left out of the greedy choice while the observation says the ball is out of reach."""

    token = "kick_mask"

    def __str__(self) -> str:
        return self.token


@dataclass(frozen=True)
class MirrorChoice:
    """Play the better, by the critic, of the greedy action in the state and in its mirror image.

    :param margin: ``0`` decides afresh every step; ``> 0`` keeps the side played through an episode and switches
        only when the other side's value exceeds it by more than ``margin`` (``inf``: never switches).
    """

    margin: float = 0.0
    token = "mirror"

    def __post_init__(self) -> None:
        margin = self.margin
        if isinstance(margin, bool) or not isinstance(margin, (int, float)) or not margin >= 0.0:
            # ``not >= 0`` also rejects NaN
            raise ValueError(f"MirrorChoice margin must be a number >= 0 (or inf), got {margin!r}")
        object.__setattr__(self, "margin", float(margin))

    def __str__(self) -> str:
        return self.token if self.margin == 0.0 else f"{self.token}:{self.margin!r}"


ActingStrategy = CriticChoice | KickMask | MirrorChoice
#: The type each strategy's token names, in the order :func:`format_acting` writes them.
STRATEGIES: tuple[type, ...] = (CriticChoice, KickMask, MirrorChoice)
#: What ``HFOPolicy(acting=...)`` accepts: strategies, their text form, or ``None`` (none).
ActingSpec = str | Sequence[ActingStrategy] | None


def _parse_token(token: str) -> ActingStrategy:
    name, _, argument = token.partition(":")
    if name == MirrorChoice.token:
        if not argument:
            return MirrorChoice()
        try:
            margin = float(argument)
        except ValueError:
            raise ValueError(
                f"acting token {token!r}: the mirror margin must be a number >= 0 (or inf)"
            ) from None
        try:
            return MirrorChoice(margin)
        except ValueError as error:
            raise ValueError(f"acting token {token!r}: {error}") from None
    for strategy in (CriticChoice, KickMask):
        if name == strategy.token:
            if argument:
                raise ValueError(f"acting token {token!r}: {strategy.token} takes no argument")
            return strategy()
    known = ", ".join(["critic", "kick_mask", "mirror", "mirror:M", "actor"])
    raise ValueError(f"unknown acting token {token!r} (known: {known})")


def parse_acting(spec: ActingSpec) -> tuple[ActingStrategy, ...]:
    """The strategies of ``spec`` in :data:`STRATEGIES` order.

    :param spec: ``None``, a tuple or list of strategies, or text such as ``"critic,kick_mask,mirror:0.1"``
        (``""`` or ``"actor"``: none).
    :raises ValueError: for an unknown token or object (the message names it), or a strategy given twice.
    """
    if spec is None:
        return ()
    if isinstance(spec, str):
        tokens = [token.strip() for token in spec.split(",") if token.strip()]
        if tokens == ["actor"]:
            tokens = []
        strategies = [_parse_token(token) for token in tokens]
    else:
        strategies = list(spec)
        for strategy in strategies:
            if not isinstance(strategy, STRATEGIES):
                raise ValueError(
                    f"acting takes CriticChoice, KickMask and MirrorChoice objects, got {strategy!r}"
                )
    kinds = [type(strategy) for strategy in strategies]
    for kind in STRATEGIES:
        if kinds.count(kind) > 1:
            raise ValueError(f"acting names {kind.token} more than once: {spec!r}")  # type: ignore[attr-defined]
    return tuple(sorted(strategies, key=lambda strategy: STRATEGIES.index(type(strategy))))


def format_acting(acting: Sequence[ActingStrategy]) -> str:
    """The text form of ``acting``, which :func:`parse_acting` reads back (``""``: no strategy)."""
    return ",".join(str(strategy) for strategy in parse_acting(acting))


def acting_from_options(
    discrete_choice: str = "actor",
    kick_only_when_kickable: bool = False,
    mirror_choice: bool = False,
    mirror_margin: float = 0.0,
) -> tuple[ActingStrategy, ...]:
    """The strategies equal to the policy's four acting options (``HFOPolicy.acting_options()``)."""
    if discrete_choice not in ("actor", "critic"):
        raise ValueError(f"discrete_choice must be 'actor' or 'critic', got {discrete_choice!r}")
    strategies: list[ActingStrategy] = []
    if discrete_choice == "critic":
        strategies.append(CriticChoice())
    if kick_only_when_kickable:
        strategies.append(KickMask())
    if mirror_choice:
        strategies.append(MirrorChoice(mirror_margin))
    return tuple(strategies)


def acting_options(acting: Sequence[ActingStrategy]) -> dict[str, Any]:
    """The four acting options equal to ``acting`` (the inverse of :func:`acting_from_options`)."""
    strategies = parse_acting(acting)
    mirror = next((s for s in strategies if isinstance(s, MirrorChoice)), None)
    return {
        "discrete_choice": "critic" if any(isinstance(s, CriticChoice) for s in strategies) else "actor",
        "kick_only_when_kickable": any(isinstance(s, KickMask) for s in strategies),
        "mirror_choice": mirror is not None,
        "mirror_margin": 0.0 if mirror is None else mirror.margin,
    }
