"""Distillation: fit a HybridPPO policy's actor to a teacher's actions, supervised (e.g. to start PPO from a clone).

For labelled states ``(s, k*, u*)`` (the teacher's discrete action and its parameters on the adapter's normalised
scale, :mod:`sb3_hfo.hybrid_ppo.layout`), the loss of one minibatch is

    cross-entropy(pi(.|s), k*) + parameter_weight * sum_j M[k*, j] (mu_j(s) - u*_j)^2

averaged over the rows: the teacher's choice becomes the categorical's most likely action, and the chosen action's
parameter means move to the teacher's (the parameters the env would not read carry no label). The log standard
deviations and the critic are left alone: Adam runs over the features extractor, the actor trunk and the heads'
linear layers only. Deterministic for a given ``seed`` (the minibatch order).

A policy with a learned router also takes skill labels ``s*`` (e.g. the skill a hand-coded router picks in that
state): the terms above then score head ``s*``, the loss adds the router's cross-entropy ``-log rho(s*|s)`` (weight
``router_weight``), and Adam also runs over the router's layer. A policy with a hand-coded router takes no skill labels (its router
picks the head).
"""

from __future__ import annotations

import numpy as np
import torch as th

from sb3_hfo.hybrid_ppo.distributions import HybridDistribution
from sb3_hfo.hybrid_ppo.policies import HybridActorCriticPolicy

__all__ = ["distill", "distillation_loss", "routed_distillation_loss"]


def distillation_loss(
    policy: HybridActorCriticPolicy,
    observations: th.Tensor,
    discrete: th.Tensor,
    parameters: th.Tensor,
    parameter_weight: float = 1.0,
) -> tuple[th.Tensor, th.Tensor, th.Tensor, th.Tensor]:
    """``(loss, cross-entropy, parameter squared error, agreement)`` of one labelled batch (module docstring), each a
    scalar; ``agreement`` (no gradient) is the fraction of rows whose most likely discrete action is the label."""
    distribution = policy.action_distribution(observations)
    return _head_terms(distribution, discrete, parameters, parameter_weight)


def _head_terms(
    distribution: HybridDistribution, discrete: th.Tensor, parameters: th.Tensor, parameter_weight: float
) -> tuple[th.Tensor, th.Tensor, th.Tensor, th.Tensor]:
    cross_entropy = -distribution.log_pi.gather(-1, discrete.unsqueeze(-1)).squeeze(-1).mean()
    chosen = distribution.parameter_mask[discrete]
    squared_error = (chosen * (distribution.mean - parameters) ** 2).sum(dim=-1).mean()
    agreement = (distribution.log_pi.detach().argmax(dim=-1) == discrete).float().mean()
    return cross_entropy + parameter_weight * squared_error, cross_entropy, squared_error, agreement


def routed_distillation_loss(
    policy: HybridActorCriticPolicy,
    observations: th.Tensor,
    skills: th.Tensor,
    discrete: th.Tensor,
    parameters: th.Tensor,
    parameter_weight: float = 1.0,
    router_weight: float = 1.0,
) -> tuple[th.Tensor, th.Tensor, th.Tensor, th.Tensor, th.Tensor, th.Tensor]:
    """A learned-router policy's batch (module docstring): :func:`distillation_loss`'s four scalars for head
    ``skills`` with ``router_weight`` times the router's cross-entropy added to the loss, then that cross-entropy and the fraction of rows
    whose greedy skill is the label (``router_agreement``, no gradient)."""
    distribution, log_rho = policy.skill_distribution(observations, skills)
    if log_rho is None:
        raise ValueError(
            "skill labels need a policy with router='learned' (a hand-coded router picks the head)"
        )
    loss, cross_entropy, squared_error, agreement = _head_terms(
        distribution, discrete, parameters, parameter_weight
    )
    router_cross_entropy = -log_rho.gather(-1, skills.unsqueeze(-1)).squeeze(-1).mean()
    router_agreement = (log_rho.detach().argmax(dim=-1) == skills).float().mean()
    return (
        loss + router_weight * router_cross_entropy,
        cross_entropy,
        squared_error,
        agreement,
        router_cross_entropy,
        router_agreement,
    )


def distill(
    policy: HybridActorCriticPolicy,
    observations: np.ndarray,
    discrete: np.ndarray,
    parameters: np.ndarray,
    epochs: int = 10,
    batch_size: int = 256,
    learning_rate: float = 1e-3,
    parameter_weight: float = 1.0,
    seed: int = 0,
    skills: np.ndarray | None = None,
    router_weight: float = 1.0,
) -> list[dict[str, float]]:
    """Fit ``policy``'s actor to the labels ``(discrete (N,), parameters (N, P))`` at ``observations (N, ...)``;
    a learned-router policy also to the skill labels ``skills (N,)`` (required for it, refused otherwise).

    :return: one row per epoch: its mean ``loss``, ``cross_entropy``, ``squared_error`` and the fraction of rows
        whose greedy discrete action is the label's (``agreement``), all over that epoch's minibatches; with skill
        labels also ``router_cross_entropy`` and ``router_agreement``.
    :raises ValueError: labels whose sizes do not fit the observations or the policy's actions, a discrete or skill
        label out of range, skill labels missing for a learned router or given for a hand-coded one.
    """
    n_rows = len(observations)
    adapter = policy.adapter
    discrete = np.asarray(discrete).reshape(-1)
    parameters = np.asarray(parameters, dtype=np.float32).reshape(n_rows, -1) if n_rows else np.zeros((0, 0))
    if n_rows == 0 or len(discrete) != n_rows or parameters.shape != (n_rows, adapter.n_parameters):
        raise ValueError(
            f"distill needs N > 0 observations, N discrete labels and (N, {adapter.n_parameters}) parameters; got "
            f"{n_rows}, {len(discrete)} and {parameters.shape}"
        )
    if discrete.min() < 0 or discrete.max() >= adapter.n_discrete:
        raise ValueError(
            f"discrete labels must lie in [0, {adapter.n_discrete}), got {discrete.min()}..{discrete.max()}"
        )
    if policy.learned_router != (skills is not None):
        raise ValueError(
            "distill needs skill labels for a policy with router='learned' and takes none for a hand-coded router"
            f" (router={policy.router!r}, skills given: {skills is not None})"
        )
    if skills is not None:
        skills = np.asarray(skills).reshape(-1)
        if len(skills) != n_rows or skills.min() < 0 or skills.max() >= policy.n_skills:
            raise ValueError(
                f"skill labels must be N = {n_rows} integers in [0, {policy.n_skills}), got {len(skills)} in "
                f"{skills.min()}..{skills.max()}"
            )
    if epochs < 1 or batch_size < 1:
        raise ValueError(f"epochs and batch_size must be >= 1, got {epochs} and {batch_size}")
    device = policy.device
    obs_t = th.as_tensor(np.asarray(observations, dtype=np.float32), device=device)
    discrete_t = th.as_tensor(discrete.astype(np.int64), device=device)
    parameters_t = th.as_tensor(parameters, device=device)
    trained = [
        *policy.features_extractor.parameters(),
        *policy.actor_trunk.parameters(),
        *(head.linear.weight for head in policy.heads),
        *(head.linear.bias for head in policy.heads),
        *(policy.router_net.parameters() if policy.router_net is not None else []),
    ]
    skills_t = None if skills is None else th.as_tensor(skills.astype(np.int64), device=device)
    names = ["loss", "cross_entropy", "squared_error", "agreement"]
    if skills_t is not None:
        names += ["router_cross_entropy", "router_agreement"]
    optimizer = th.optim.Adam(trained, lr=learning_rate)
    generator = th.Generator().manual_seed(seed)
    policy.set_training_mode(True)
    history = []
    for _ in range(epochs):
        order = th.randperm(n_rows, generator=generator).to(device)
        sums = np.zeros(len(names))
        for start in range(0, n_rows, batch_size):
            rows = order[start : start + batch_size]
            if skills_t is None:
                terms = distillation_loss(
                    policy, obs_t[rows], discrete_t[rows], parameters_t[rows], parameter_weight
                )
            else:
                terms = routed_distillation_loss(
                    policy,
                    obs_t[rows],
                    skills_t[rows],
                    discrete_t[rows],
                    parameters_t[rows],
                    parameter_weight,
                    router_weight,
                )
            optimizer.zero_grad(set_to_none=True)
            terms[0].backward()
            optimizer.step()
            sums += len(rows) * np.array([term.item() for term in terms])
        means = sums / n_rows
        history.append(dict(zip(names, means.tolist(), strict=True)))
    policy.set_training_mode(False)
    return history
