"""Acting strategies of :class:`~sb3_hfo.skill_ddpg.policies.HFOPolicy`: how a trained policy turns its actor's
output into the action it plays. They change no network, so they can be switched on a trained model.

Each strategy is a small frozen dataclass, and a policy takes any combination of them as one argument,
``acting``: a tuple of strategies or its text form, the strategies' tokens joined by commas (the form the
command lines take, ``evaluate --acting critic,kick_mask,mirror:0.1``):

* :class:`CriticChoice` (``critic``): the critic picks the discrete action, trying each one as its one-hot
  preference vector (+1 / -1, the form epsilon-greedy exploration with ``exploration_keep_parameters`` stores) at
  the actor's parameters, as P-DQN / MP-DQN choose (Xiong et al. 2018; Bester et al. 2019); without it the actor's
  largest preference does. Why: with ``mask_unused_parameters`` the critic values each discrete action by its own
  parameters, which the actor's preferences do not.
* :class:`KickMask` (``kick_mask``): KICK is never the greedy choice while the observation's "able to kick" feature
  is -1; the critic's choice and SkillDDPG's ``discrete_target="max"`` leave it out of their maximum, and the
  actor's choice falls to its best other preference (invalid-action masking, as in sb3-contrib's MaskablePPO;
  exploration may still try such kicks). Why: rcssserver ignores a kick out of reach, so a deterministic policy
  that picks KICK there repeats it until HFO's time limit.
* :class:`MirrorChoice` (``mirror`` or ``mirror:M``): HFO is symmetric about the pitch's long axis
  (:mod:`hfo2d.symmetry`), so the policy played in the state's mirror image, its action mirrored back, is another
  policy for the real state; acting (``predict``, not SkillDDPG's training rollouts) plays the better, by the
  critic, of the two greedy actions (ties: the unmirrored one). Why: a one-step policy improvement over two
  policies, for agents that score by one route only. With a margin ``M > 0`` the side played is kept through an
  episode, in ``predict``'s ``state``, and switched only when the other is better by more than ``M``, so that the
  choice does not alternate between two routes. HFO's start distribution is not mirror-symmetric, and on the empty
  goal the choice can cost points (docs/findings.md, "The mirror choice").

The empty tuple (text ``""`` or ``"actor"``) is the paper's policy: the actor's greedy action as it is.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass


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

    :param spec: ``None``, a strategy, a tuple or list of strategies, or text such as ``"critic,kick_mask,mirror:0.1"``
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
    elif isinstance(spec, STRATEGIES):
        strategies = [spec]
    elif not isinstance(spec, (tuple, list)):
        raise ValueError(
            f"acting takes CriticChoice, KickMask and MirrorChoice objects (one, or a tuple of them), their text "
            f"form or None, got {spec!r}"
        )
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
