"""HybridPPO's action distribution: a categorical over the discrete actions, a diagonal Gaussian over the parameters.

For one state, with ``pi`` the categorical over the ``K`` discrete actions, ``N(mu_j, sigma_j)`` one Gaussian per
continuous parameter ``j`` (on the normalised scale of :mod:`sb3_hfo.hybrid_ppo.layout`, where ``[-1, 1]`` spans
the env's bounds) and ``M`` the ``(K, P)`` mask of which parameters each discrete action reads:

* sampling draws ``k ~ pi`` and every parameter ``u_j ~ N(mu_j, sigma_j)`` (the env ignores the others);
* ``log p(k, u) = log pi(k) + sum_j M[k, j] log N(u_j; mu_j, sigma_j)``: only the chosen action's parameters count,
  because only they change what the env does (the others carry no gradient signal and no ratio);
* ``H(k) = H(pi) + sum_j M[k, j] (1/2 + 1/2 log(2 pi) + log sigma_j)``: the categorical's entropy plus the entropy of
  the parameters of the discrete action ``k`` of the action being scored (in training: the buffer's action).
  Averaged over a batch whose ``k`` were drawn from ``pi`` it estimates the joint entropy
  ``H(pi) + sum_k pi(k) H(params_k)`` without bias.
* the mode: ``argmax pi`` and ``u = mu``.

Log-densities are in the normalised unit; in the env's units each parameter adds the constant
``-log((high - low) / 2)``, which cancels in PPO's probability ratios and shifts the entropy by a constant.

The optional first-level choice (a learned skill router) is a second categorical ``rho`` over skills, whose
``log rho(s)`` and ``H(rho)`` are added by the policy (:class:`~sb3_hfo.hybrid_ppo.policies.HybridActorCriticPolicy`).
Written with plain tensor operations (no ``torch.distributions`` objects): the rollout samples one batch per step.
"""

from __future__ import annotations

import math

import torch as th

__all__ = ["HybridDistribution", "categorical_entropy", "hybrid_kl"]

#: ``1/2 log(2 pi)``, the constant of a Gaussian log-density.
HALF_LOG_TWO_PI = 0.5 * math.log(2.0 * math.pi)


def categorical_entropy(log_probs: th.Tensor) -> th.Tensor:
    """Entropy ``-sum p log p`` over the last axis of normalised log-probabilities (0 log 0 = 0)."""
    probs = log_probs.exp()
    return -(probs * log_probs).sum(dim=-1)


class HybridDistribution:
    """A batch of hybrid distributions (see the module docstring).

    :param logits: ``(B, K)`` unnormalised log-probabilities of the discrete actions.
    :param mean: ``(B, P)`` Gaussian means of all parameters.
    :param log_std: ``(B, P)`` or ``(P,)`` Gaussian log standard deviations.
    :param parameter_mask: ``(K, P)`` float or bool, 1 where discrete action ``k`` reads parameter ``j``.
    """

    def __init__(
        self, logits: th.Tensor, mean: th.Tensor, log_std: th.Tensor, parameter_mask: th.Tensor
    ) -> None:
        self.log_pi = th.log_softmax(logits, dim=-1)
        self.mean = mean
        self.log_std = log_std.expand_as(mean)
        self.parameter_mask = parameter_mask.to(mean.dtype)

    def sample(self) -> tuple[th.Tensor, th.Tensor]:
        """``(k (B,) long, u (B, P))``: a discrete action from ``pi`` and every parameter from its Gaussian."""
        discrete = th.multinomial(self.log_pi.exp(), 1).squeeze(-1)
        parameters = self.mean + self.log_std.exp() * th.randn_like(self.mean)
        return discrete, parameters

    def mode(self) -> tuple[th.Tensor, th.Tensor]:
        """``(argmax pi, mu)``: the greedy action (the first discrete action on ties)."""
        return self.log_pi.argmax(dim=-1), self.mean

    def log_prob(self, discrete: th.Tensor, parameters: th.Tensor) -> th.Tensor:
        """``(B,)`` ``log pi(k) + sum of the chosen k's parameters' Gaussian log-densities``."""
        log_pi_k = self.log_pi.gather(-1, discrete.unsqueeze(-1)).squeeze(-1)
        z = (parameters - self.mean) * th.exp(-self.log_std)
        per_parameter = -0.5 * z * z - self.log_std - HALF_LOG_TWO_PI
        return log_pi_k + (self.parameter_mask[discrete] * per_parameter).sum(dim=-1)

    def entropy(self, discrete: th.Tensor) -> th.Tensor:
        """``(B,)`` ``H(pi) + entropy of discrete action k's parameters`` (k per row)."""
        per_parameter = 0.5 + HALF_LOG_TWO_PI + self.log_std
        return categorical_entropy(self.log_pi) + (self.parameter_mask[discrete] * per_parameter).sum(dim=-1)


def hybrid_kl(reference: HybridDistribution, current: HybridDistribution) -> th.Tensor:
    """``(B,)`` ``KL(reference || current)`` of two hybrid distributions over the same actions, row by row.

    With ``r`` and ``q`` the two categoricals and ``M`` the parameter mask: ``sum_k r(k) (log r(k) - log q(k))``
    plus ``sum_k r(k) sum_j M[k, j] KL(N_r,j || N_q,j)``, the Gaussians' KL
    ``log(sigma_q / sigma_r) + (sigma_r^2 + (mu_r - mu_q)^2) / (2 sigma_q^2) - 1/2``. Exact (the joint density
    factorises into the choice and the chosen action's parameters); 0 for identical distributions and > 0 otherwise.
    Gradients flow into both arguments; pass a detached ``reference`` to pull ``current`` toward it.
    """
    if reference.log_pi.shape != current.log_pi.shape or reference.mean.shape != current.mean.shape:
        raise ValueError(
            f"hybrid_kl needs distributions of the same shape, got logits {tuple(reference.log_pi.shape)} / "
            f"{tuple(current.log_pi.shape)} and means {tuple(reference.mean.shape)} / {tuple(current.mean.shape)}"
        )
    pi_reference = reference.log_pi.exp()
    categorical = (pi_reference * (reference.log_pi - current.log_pi)).sum(dim=-1)
    variance_ratio = th.exp(2.0 * (reference.log_std - current.log_std))
    mean_term = (reference.mean - current.mean) ** 2 * th.exp(-2.0 * current.log_std)
    per_parameter = current.log_std - reference.log_std + 0.5 * (variance_ratio + mean_term) - 0.5  # (B, P)
    # weight of parameter j: the reference's probability of playing an action that reads it
    read_probability = pi_reference @ reference.parameter_mask  # (B, P)
    return categorical + (read_probability * per_parameter).sum(dim=-1)
