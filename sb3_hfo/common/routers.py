"""Skill routers: the hand-coded rule that says which actor head (skill) acts in a given state.

The seed paper ("Method"): "In the skills architecture the actor has 2 parallel output layers [...] The condition of
which skill to use is hard coded by the developer." Its experiments ("Experiments") split the field in half: in the
half away from the goal the skill approaches the ball and dribbles it towards the goal, in the half near the goal
the skill shoots. A router implements such a condition from the observation alone, for a whole batch at once.

A router is a plain (picklable) object with an ``n_skills`` attribute and ``__call__(obs) -> skills``:

* ``obs``: ``np.ndarray`` or ``torch.Tensor`` of shape ``(batch, obs_dim)`` (what the policy sees);
* returns integer skill indices of shape ``(batch,)`` in ``[0, n_skills)``, of the same kind as ``obs``
  (``np.int64`` array for numpy input, ``torch.long`` tensor on ``obs.device`` for tensor input).

Routers must be vectorised (no Python loop over the batch): they run on every training minibatch. The policy
checks their output on every call (:func:`check_skills`: type, shape and range), when acting and in every update.
Routers can be named by string in ``HFOPolicy(skill_router=...)`` so that YAML configs can select them; see
:data:`ROUTERS` and :func:`make_router`. ``"field_half"`` reads its column from the policy's domain adapter
(:class:`~sb3_hfo.common.domain.DomainAdapter`: this module knows no task).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import torch as th

from sb3_hfo.common.domain import DomainAdapter, DomainSpec, resolve_domain

__all__ = [
    "ROUTERS",
    "BallPlayerRouter",
    "FieldHalfRouter",
    "OneHotRouter",
    "SingleSkillRouter",
    "SkillRouter",
    "check_skills",
    "field_half_router",
    "make_router",
    "validate_skills",
]


class SkillRouter:
    """Base class of skill routers (see the module docstring for the calling convention).

    Subclasses set ``n_skills`` and implement :meth:`__call__`. They should be cheap, vectorised and picklable
    (they are stored with the model by ``SkillDDPG.save``).
    """

    #: Number of skills the router chooses among; routers return indices in ``[0, n_skills)``.
    n_skills: int = 1

    def __call__(self, obs: np.ndarray | th.Tensor) -> np.ndarray | th.Tensor:
        """Skill index per row of ``obs`` (shape ``(batch, obs_dim)``); returns shape ``(batch,)`` integers."""
        raise NotImplementedError

    def numpy_route(self, obs: np.ndarray) -> np.ndarray:
        """:meth:`__call__` on a numpy batch ``(batch, obs_dim)``, returned as an ``np.int64`` array ``(batch,)``."""
        skills = self(np.asarray(obs, dtype=np.float32))
        if isinstance(skills, th.Tensor):
            skills = skills.detach().cpu().numpy()
        return np.asarray(skills, dtype=np.int64)

    def __repr__(self) -> str:
        fields = ", ".join(f"{key}={value!r}" for key, value in sorted(vars(self).items()))
        return f"{type(self).__name__}({fields})"

    def __eq__(self, other: object) -> bool:
        return type(self) is type(other) and vars(self) == vars(other)

    def __hash__(self) -> int:
        return hash((type(self).__name__, tuple(sorted(vars(self).items()))))


class SingleSkillRouter(SkillRouter):
    """Every state uses skill 0: the paper's plain (skill-less) agent when ``n_skills == 1``."""

    n_skills = 1

    def __call__(self, obs: np.ndarray | th.Tensor) -> np.ndarray | th.Tensor:
        if isinstance(obs, th.Tensor):
            return th.zeros(obs.shape[0], dtype=th.long, device=obs.device)
        return np.zeros(np.shape(obs)[0], dtype=np.int64)


class FieldHalfRouter(SkillRouter):
    """The paper's two skills: split the attacked half-field in half along x.

    * skill 0 ("approach and dribble"): the agent is in the half away from the goal,
      ``obs[:, feature_index] > threshold``;
    * skill 1 ("shoot"): the agent is in the half near the goal.

    The domain adapter says which column and threshold (``DomainAdapter.field_half_router``; HFO's:
    :data:`sb3_hfo.hfo.HFO_DOMAIN`, the self-x feature at 0.0, x = 26.25 m).

    :param feature_index: column of ``obs`` holding the agent's normalised x-position feature (positive away from
        the goal).
    :param threshold: feature value at the dividing line.
    """

    n_skills = 2

    def __init__(self, feature_index: int, threshold: float = 0.0) -> None:
        if not isinstance(feature_index, (int, np.integer)) or feature_index < 0:
            raise ValueError(
                f"FieldHalfRouter: feature_index must be a non-negative int, got {feature_index!r}"
            )
        self.feature_index = int(feature_index)
        self.threshold = float(threshold)

    def __call__(self, obs: np.ndarray | th.Tensor) -> np.ndarray | th.Tensor:
        if obs.shape[-1] <= self.feature_index:
            raise ValueError(
                f"FieldHalfRouter reads obs[..., {self.feature_index}] but the observation has only "
                f"{obs.shape[-1]} features (is this the domain the router was made for?)"
            )
        x_feature = obs[..., self.feature_index]
        if isinstance(x_feature, th.Tensor):
            return (x_feature <= self.threshold).long()
        return (np.asarray(x_feature) <= self.threshold).astype(np.int64)


class BallPlayerRouter(SkillRouter):
    """A team's role split as a hand-coded router: an agent that judges itself nearest the ball among its teammates
    plays ``ball_router``'s skills, the others play one more skill, the *support* skill (index
    ``ball_router.n_skills``). Each agent judges from its own observation alone (a decentralised rule, like the
    paper's field half), so two agents may both judge themselves nearest.

    Positions come from bearings and proximities, the way HFO's low-level features give the ball and each
    teammate: a bearing as ``(sin, cos)`` in the agent's frame and a proximity ``1 - distance / distance_scale``,
    so an object's position relative to the agent is ``distance * (cos, sin)`` and a teammate's distance to the
    ball is the distance between the two positions. A tie counts as nearest (both play the ball rather than both
    waiting). A teammate whose bearing is not a unit vector (its block all zero: the observation does not list it,
    e.g. HFO's features of a player outside the half field) counts as farther.

    :param ball_router: the skills of the agent nearest the ball (e.g. :class:`FieldHalfRouter`).
    :param ball_columns: ``(sin, cos, proximity)`` columns of the ball's bearing and proximity.
    :param teammate_columns: one ``(sin, cos, proximity)`` triple per teammate.
    :param distance_scale: the distance at proximity 0 (proximity ``1 - d / distance_scale``).
    :param n_features: the observation's size, checked on every call when given (a team of another size puts
        other players' features in the teammate columns, e.g. HFO's 1v1 the goalie's).
    """

    def __init__(
        self,
        ball_router: SkillRouter,
        ball_columns: tuple[int, int, int],
        teammate_columns: tuple[tuple[int, int, int], ...],
        distance_scale: float,
        n_features: int | None = None,
    ) -> None:
        if not callable(ball_router) or getattr(ball_router, "n_skills", None) is None:
            raise ValueError(f"ball_router must be a SkillRouter (n_skills, __call__), got {ball_router!r}")
        triples = (tuple(ball_columns), *(tuple(triple) for triple in teammate_columns))
        for triple in triples:
            if len(triple) != 3 or any(
                isinstance(c, bool) or not isinstance(c, (int, np.integer)) or c < 0 for c in triple
            ):
                raise ValueError(
                    f"columns must be (sin, cos, proximity) triples of non-negative ints, got {triple!r}"
                )
        if not teammate_columns:
            raise ValueError(
                "BallPlayerRouter needs at least one teammate (with none every agent plays the ball)"
            )
        if not float(distance_scale) > 0.0:
            raise ValueError(f"distance_scale must be > 0, got {distance_scale!r}")
        self.ball_router = ball_router
        self.ball_columns = tuple(int(c) for c in ball_columns)
        self.teammate_columns = tuple(tuple(int(c) for c in triple) for triple in teammate_columns)
        self.distance_scale = float(distance_scale)
        self.n_features = None if n_features is None else int(n_features)
        self.n_skills = int(ball_router.n_skills) + 1

    @property
    def support_skill(self) -> int:
        """The skill index of the agents that are not nearest the ball."""
        return self.n_skills - 1

    def _position(self, obs: Any, columns: tuple[int, ...]) -> tuple[Any, Any]:
        sin, cos, proximity = columns
        distance = (1.0 - obs[:, proximity]) * self.distance_scale
        return distance * obs[:, cos], distance * obs[:, sin]

    def nearest(self, obs: np.ndarray | th.Tensor) -> np.ndarray | th.Tensor:
        """Whether each row's agent judges itself nearest the ball: ``(batch,)`` bool (numpy or torch)."""
        if self.n_features is not None and obs.shape[-1] != self.n_features:
            raise ValueError(
                f"BallPlayerRouter is for observations of {self.n_features} features, got {obs.shape[-1]} (a team "
                "of another size puts other players in the teammate columns)"
            )
        needed = 1 + max(max(triple) for triple in (self.ball_columns, *self.teammate_columns))
        if obs.shape[-1] < needed:
            raise ValueError(
                f"BallPlayerRouter reads columns up to {needed - 1} but the observation has only "
                f"{obs.shape[-1]} features (is this a team of {len(self.teammate_columns) + 1}?)"
            )
        hypot = th.hypot if isinstance(obs, th.Tensor) else np.hypot
        ball_x, ball_y = self._position(obs, self.ball_columns)
        own_distance = hypot(ball_x, ball_y)
        nearest = (
            th.ones_like(own_distance, dtype=th.bool)
            if isinstance(obs, th.Tensor)
            else np.ones(own_distance.shape, dtype=bool)
        )
        for triple in self.teammate_columns:
            mate_x, mate_y = self._position(obs, triple)
            listed = hypot(obs[:, triple[0]], obs[:, triple[1]]) > 0.5  # a unit vector, not an all-zero block
            nearest = nearest & ((own_distance <= hypot(ball_x - mate_x, ball_y - mate_y)) | ~listed)
        return nearest

    def __call__(self, obs: np.ndarray | th.Tensor) -> np.ndarray | th.Tensor:
        nearest = self.nearest(obs)
        ball_skills = self.ball_router(obs)
        if isinstance(obs, th.Tensor):
            return th.where(nearest, ball_skills, th.full_like(ball_skills, self.support_skill))
        return np.where(nearest, ball_skills, self.support_skill).astype(np.int64)


class OneHotRouter(SkillRouter):
    """The skill written into the observation as one-hot columns: ``obs[:, first_column + s]`` is 1 for skill ``s``
    and the other ``n_skills - 1`` columns are 0.

    For a hand-coded rule that is cheaper to run once per env step than on every training minibatch (e.g. a team's
    roles read from HFO's features by per-agent geometry): an observation wrapper appends the rule's one-hot and
    this router reads it back. A row that is not one-hot (an observation without the appended columns, or with
    other features there) is refused, so a policy is never routed by columns that hold something else.

    :param first_column: the column of skill 0's indicator.
    :param n_skills: how many columns (skills), at least 2.
    """

    def __init__(self, first_column: int, n_skills: int) -> None:
        for name, value, low in (("first_column", first_column, 0), ("n_skills", n_skills, 2)):
            if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
                raise ValueError(f"OneHotRouter: {name} must be an int >= {low}, got {value!r}")
        self.first_column = int(first_column)
        self.n_skills = int(n_skills)

    def __call__(self, obs: np.ndarray | th.Tensor) -> np.ndarray | th.Tensor:
        end = self.first_column + self.n_skills
        if obs.shape[-1] < end:
            raise ValueError(
                f"OneHotRouter reads columns {self.first_column}..{end - 1} but the observation has only "
                f"{obs.shape[-1]} features (was the skill's one-hot appended?)"
            )
        columns = obs[:, self.first_column : end]
        if isinstance(columns, th.Tensor):
            one_hot = bool(((columns == 0) | (columns == 1)).all()) and bool((columns.sum(dim=1) == 1).all())
            skills = columns.argmax(dim=1)
        else:
            columns = np.asarray(columns)
            one_hot = bool(((columns == 0) | (columns == 1)).all() and (columns.sum(axis=1) == 1).all())
            skills = columns.argmax(axis=1).astype(np.int64)
        if not one_hot:
            raise ValueError(
                f"OneHotRouter: columns {self.first_column}..{end - 1} are not one-hot in every row (was the "
                "skill's one-hot appended to these observations?)"
            )
        return skills


#: Routers selectable by name (``skill_router="field_half"`` in policy_kwargs / YAML).
ROUTERS: dict[str, type[SkillRouter]] = {
    "single": SingleSkillRouter,
    "field_half": FieldHalfRouter,
}


def field_half_router(domain: DomainAdapter) -> FieldHalfRouter:
    """The paper's field-half router on ``domain``'s column and threshold.

    :raises ValueError: the domain names no field-half column.
    """
    if domain.field_half_column is None:
        raise ValueError(
            f"the 'field_half' skill router needs a domain that names the column to split on; the {domain.name} "
            "domain does not (pass domain='hfo' for the HFO envs, or a SkillRouter object)"
        )
    return FieldHalfRouter(domain.field_half_column, domain.field_half_threshold)


def make_router(
    skill_router: SkillRouter | str | None, n_skills: int, domain: DomainSpec = None
) -> SkillRouter:
    """Resolve ``skill_router`` (an object, a name from :data:`ROUTERS` or ``None``) and check it against ``n_skills``.

    ``None`` picks the paper's defaults: ``"single"`` for one skill, ``"field_half"`` for two; more skills need an
    explicit router. ``"field_half"`` takes its column from ``domain`` (:mod:`sb3_hfo.common.domain`).

    :raises ValueError: unknown name, ``n_skills < 1``, a router without ``__call__``, a router whose
        ``n_skills`` differs from ``n_skills``, or ``"field_half"`` with a domain that names no column for it.
    """
    if isinstance(n_skills, bool) or not isinstance(n_skills, (int, np.integer)) or n_skills < 1:
        raise ValueError(f"n_skills must be an integer >= 1, got {n_skills!r}")
    if skill_router is None:
        if n_skills == 1:
            skill_router = "single"
        elif n_skills == 2:
            skill_router = "field_half"
        else:
            raise ValueError(
                f"n_skills={n_skills} needs an explicit skill_router (the defaults cover 1 skill: 'single' and "
                "2 skills: 'field_half')"
            )
    if isinstance(skill_router, str):
        if skill_router not in ROUTERS:
            raise ValueError(f"Unknown skill_router {skill_router!r}; known routers: {sorted(ROUTERS)}")
        router: Any = (
            field_half_router(resolve_domain(domain))
            if ROUTERS[skill_router] is FieldHalfRouter
            else ROUTERS[skill_router]()
        )
    else:
        router = skill_router
    if not callable(router):
        raise ValueError(f"skill_router must be callable (obs -> skill indices), got {type(router).__name__}")
    router_skills = getattr(router, "n_skills", None)
    if router_skills is None:
        raise ValueError(
            f"skill_router {router!r} has no 'n_skills' attribute (subclass sb3_hfo.SkillRouter)"
        )
    if int(router_skills) != int(n_skills):
        raise ValueError(
            f"skill_router {router!r} routes to {router_skills} skill(s) but the policy has n_skills={n_skills}"
        )
    return router


def check_skills(skills: Any, batch_size: int, n_skills: int, router: object) -> None:
    """Check a router's output: a numpy array or torch tensor of integers, shape ``(batch_size,)``, in
    ``[0, n_skills)``. Cheap enough for every call (one reduction for the range): the policy checks every routing,
    when acting and in every update, so that a bad index is never routed to a wrong head.

    :raises ValueError: wrong type, shape, non-integer values or values outside ``[0, n_skills)``; the message
        names the router and what it returned.
    """
    if isinstance(skills, th.Tensor):
        dtype = skills.dtype
        integer = not (dtype.is_floating_point or dtype.is_complex or dtype == th.bool)
    elif isinstance(skills, np.ndarray):
        dtype = skills.dtype
        integer = np.issubdtype(dtype, np.integer)
    else:
        raise ValueError(
            f"skill_router {router!r} must return an array/tensor of skill indices, got {type(skills).__name__}"
        )
    if tuple(skills.shape) != (batch_size,):
        raise ValueError(
            f"skill_router {router!r} returned shape {tuple(skills.shape)} for a batch of {batch_size} "
            f"observations; expected ({batch_size},)"
        )
    if not integer:
        raise ValueError(f"skill_router {router!r} must return integer skill indices, got dtype {dtype}")
    if batch_size > 0:
        if batch_size == 1:  # acting in one env: one read
            low = high = int(skills.item())
        elif isinstance(skills, th.Tensor):
            extremes = th.aminmax(skills)
            low, high = int(extremes.min), int(extremes.max)
        else:
            low, high = int(skills.min()), int(skills.max())
        if low < 0 or high >= n_skills:
            raise ValueError(
                f"skill_router {router!r} returned skill indices in [{low}, {high}]; they must lie in "
                f"[0, {n_skills}) because n_skills={n_skills}"
            )


def validate_skills(
    skills: Any, batch_size: int, n_skills: int, router: object, device: th.device | str | None = None
) -> th.Tensor:
    """:func:`check_skills`, then the skills as a ``torch.long`` tensor of shape ``(batch_size,)`` (on ``device``
    when given, else where they are; numpy input goes to the CPU).

    :raises ValueError: as :func:`check_skills`.
    """
    check_skills(skills, batch_size, n_skills, router)
    tensor = skills if isinstance(skills, th.Tensor) else th.from_numpy(np.ascontiguousarray(skills))
    if device is not None:
        tensor = tensor.to(device)
    return tensor if tensor.dtype == th.long else tensor.long()
