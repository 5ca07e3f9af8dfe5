"""HybridPPO's actor-critic policy, with the seed paper's skills as an option.

Networks (``net_arch=dict(pi=[...], vf=[...])``, SB3's convention; a list is used for both):

* a features extractor (SB3's; ``FlattenExtractor`` by default), shared by actor and critic;
* the actor trunk (an MLP), shared by all skills;
* one *head* per skill: a linear layer to the ``K`` discrete logits and the ``P`` parameter means, and its own
  state-independent log standard deviations (SB3's PPO keeps one ``log_std`` vector the same way); with
  ``state_dependent_std=True`` a second linear layer from the actor trunk adds a state-dependent part to them
  (zero at the start, so a new policy acts as the state-independent one);
* the critic: an MLP and a linear value output;
* with ``router="learned"``: a linear layer from the actor trunk to one logit per skill.

Skills (seed paper, "Method": "the actor has 2 parallel output layers [...] The condition of which skill to use is
hard coded"): ``skills=1`` is a plain hybrid policy. With ``skills > 1`` a router picks the head of each state:
a hand-coded router (an object with ``n_skills`` and ``__call__(obs) -> skills``, or a name resolved by
:func:`sb3_hfo.common.routers.make_router`, e.g. ``"field_half"``), or ``"learned"``: a categorical ``rho`` over the
skills learned by PPO as a first-level choice (the paper's future work): the skill ``s ~ rho`` is part of the
action (stored in the buffer after the parameters), ``log p = log rho(s) + log p_s(k, u)`` and the entropy adds
``H(rho)``.

Optimizers: one Adam per skill (``skill_{s}_optimizer``) over that skill's head only, and ``optimizer`` over the
shared parts (features extractor, trunk, critic, learned router). Adam works per parameter, so with one skill this
is exactly one Adam over everything; with several, a skill that had no rows in a minibatch takes no step (its
moment estimates would otherwise move its weights with zero gradient), as in SkillDDPG.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import torch as th
from gymnasium import spaces
from stable_baselines3.common.policies import BasePolicy
from stable_baselines3.common.torch_layers import BaseFeaturesExtractor, FlattenExtractor
from stable_baselines3.common.type_aliases import PyTorchObs, Schedule
from torch import nn

from sb3_hfo.hybrid_ppo.distributions import HybridDistribution, categorical_entropy
from sb3_hfo.hybrid_ppo.layout import ActionAdapter

__all__ = ["HybridActorCriticPolicy", "LearnedRouterView", "SkillHead"]

LEARNED_ROUTER = "learned"
# Bounds of a state-dependent log standard deviation (normalised scale, where 0 is half a parameter's range): below
# exp(-5) (0.3 % of the half range) a Gaussian no longer explores and its log-probabilities grow steep; above exp(1)
# most samples fall outside the bounds and are clipped.
LOG_STD_MIN, LOG_STD_MAX = -5.0, 1.0


def mlp(input_size: int, sizes: Sequence[int], activation_fn: type[nn.Module]) -> tuple[nn.Sequential, int]:
    """An MLP ``input_size -> sizes...`` with ``activation_fn`` after each layer; returns it and its output size."""
    layers: list[nn.Module] = []
    for size in sizes:
        layers += [nn.Linear(input_size, size), activation_fn()]
        input_size = size
    return nn.Sequential(*layers), input_size


class SkillHead(nn.Module):
    """One skill's output layer: ``K`` discrete logits, ``P`` parameter means and its ``P`` log standard deviations.
    With ``squash_mean`` the means are ``tanh`` of the linear output (inside the env's bounds, ``[-1, 1]``).

    With ``state_dependent_std`` the log standard deviations are ``log_std + std_linear(latent)``, clipped to
    ``[LOG_STD_MIN, LOG_STD_MAX]``: ``log_std`` stays the state-independent part (what ``log_std_init`` sets and what
    a noise schedule or a reset writes), and ``std_linear`` starts at zero. Why: one deviation per parameter for all
    states must serve both a dribble's soft touches and a shot's hard kick with the same kick-power spread
    (research/e6_from_reward.md Part D).
    """

    def __init__(
        self,
        latent_size: int,
        n_discrete: int,
        n_parameters: int,
        log_std_init: float,
        squash_mean: bool = False,
        state_dependent_std: bool = False,
    ) -> None:
        super().__init__()
        self.n_discrete = n_discrete
        self.squash_mean = squash_mean
        self.linear = nn.Linear(latent_size, n_discrete + n_parameters)
        self.log_std = nn.Parameter(th.full((n_parameters,), float(log_std_init)))
        self.std_linear = nn.Linear(latent_size, n_parameters) if state_dependent_std else None
        if self.std_linear is not None:
            nn.init.zeros_(self.std_linear.weight)
            nn.init.zeros_(self.std_linear.bias)

    def log_std_of(self, latent: th.Tensor) -> th.Tensor:
        """``(B, P)`` (state-dependent) or ``(P,)`` log standard deviations for a batch of trunk outputs."""
        if self.std_linear is None:
            return self.log_std
        return th.clamp(self.log_std + self.std_linear(latent), LOG_STD_MIN, LOG_STD_MAX)

    def forward(self, latent: th.Tensor) -> tuple[th.Tensor, th.Tensor]:
        out = self.linear(latent)
        mean = out[:, self.n_discrete :]
        return out[:, : self.n_discrete], th.tanh(mean) if self.squash_mean else mean


class LearnedRouterView:
    """The learned router seen as a hand-coded one (``n_skills``, ``__call__(obs) -> skills``): its greedy skill.
    For tools that ask a policy which skill acts (``sb3_hfo.evaluate``'s skill counts)."""

    def __init__(self, policy: HybridActorCriticPolicy) -> None:
        self.n_skills = policy.n_skills
        self._policy = policy

    def __call__(self, obs: np.ndarray | th.Tensor) -> np.ndarray | th.Tensor:
        tensor = th.as_tensor(np.asarray(obs) if not isinstance(obs, th.Tensor) else obs, dtype=th.float32)
        with th.no_grad():
            _, router_logits, _ = self._policy.actor_outputs(tensor.to(self._policy.device))
            skills = router_logits.argmax(dim=-1)
        return skills if isinstance(obs, th.Tensor) else skills.cpu().numpy()


class HybridActorCriticPolicy(BasePolicy):
    """Actor-critic policy over any action space :class:`~sb3_hfo.hybrid_ppo.layout.ActionAdapter` supports.

    :param net_arch: ``dict(pi=[...], vf=[...])`` or one list for both (default ``[64, 64]`` each, SB3's PPO).
    :param activation_fn: hidden activation (default ``Tanh``, SB3's PPO).
    :param log_std_init: initial log standard deviation of every parameter (normalised scale: 0 is a standard
        deviation of half the parameter's range).
    :param ortho_init: SB3's orthogonal initialisation (gains sqrt(2) hidden, 0.01 heads, 1 value).
    :param skills: number of actor heads.
    :param router: with ``skills > 1``: ``"learned"``, a router object or a name for
        :func:`sb3_hfo.common.routers.make_router` (``None``: its default for the number of skills; ``"field_half"``
        reads its column from ``domain``).
    :param domain: what the policy knows of the task beyond its spaces (:mod:`sb3_hfo.common.domain`): a
        ``DomainAdapter``, a domain's name (``"hfo"``) or ``None`` (default): nothing.
    :param parameter_sizes: for ``Tuple(Discrete(K), Box(P))`` action spaces, which parameters each action reads.
    :param squash_mean: the parameter means are ``tanh`` of the heads' outputs, so inside the env's bounds (as a
        DDPG actor's squashed output, e.g. SkillDDPG's: such an actor's layers can be copied into this policy and act
        the same); the samples are still Gaussian around them, clipped to the bounds by the adapter.
    :param state_dependent_std: each head's parameter log standard deviations get a state-dependent part, a linear
        layer from the actor trunk that starts at zero (:class:`SkillHead`).
    :param use_sde: accepted for SB3's call signature; must be False.
    """

    def __init__(
        self,
        observation_space: spaces.Space,
        action_space: spaces.Space,
        lr_schedule: Schedule,
        net_arch: dict[str, list[int]] | list[int] | None = None,
        activation_fn: type[nn.Module] = nn.Tanh,
        log_std_init: float = 0.0,
        ortho_init: bool = True,
        skills: int = 1,
        router: Any = None,
        parameter_sizes: Sequence[int] | None = None,
        domain: Any = None,
        squash_mean: bool = False,
        state_dependent_std: bool = False,
        use_sde: bool = False,
        features_extractor_class: type[BaseFeaturesExtractor] = FlattenExtractor,
        features_extractor_kwargs: dict[str, Any] | None = None,
        normalize_images: bool = True,
        optimizer_class: type[th.optim.Optimizer] = th.optim.Adam,
        optimizer_kwargs: dict[str, Any] | None = None,
    ) -> None:
        if use_sde:
            raise ValueError("HybridPPO does not support gSDE (use_sde=True)")
        if optimizer_kwargs is None:
            # SB3's PPO default eps for Adam; torch's fused kernel: one step of a 64-64 network's Adam took 0.7 ms
            # instead of 2.8 ms (for-loop) on the project's 2-core CPU, same update rule
            optimizer_kwargs = {"eps": 1e-5, "fused": True} if optimizer_class == th.optim.Adam else {}
        super().__init__(
            observation_space,
            action_space,
            features_extractor_class,
            features_extractor_kwargs,
            normalize_images=normalize_images,
            optimizer_class=optimizer_class,
            optimizer_kwargs=optimizer_kwargs,
        )
        self.adapter = ActionAdapter.from_space(action_space, parameter_sizes)
        self.parameter_sizes = None if parameter_sizes is None else tuple(int(n) for n in parameter_sizes)
        if isinstance(skills, bool) or not isinstance(skills, (int, np.integer)) or skills < 1:
            raise ValueError(f"skills must be an integer >= 1, got {skills!r}")
        self.n_skills = int(skills)
        self.router = router
        self.domain = domain
        self.learned_router = router == LEARNED_ROUTER
        if self.n_skills == 1 and router not in (None, "single"):
            raise ValueError(f"router={router!r} needs skills > 1 (one skill needs no router)")
        if self.n_skills > 1 and not self.learned_router:
            from sb3_hfo.common.routers import make_router  # resolves names; "field_half" by the domain

            self.skill_router: Any = make_router(router, self.n_skills, domain)
        elif self.learned_router:
            self.skill_router = LearnedRouterView(self)
        else:
            self.skill_router = None
        if net_arch is None:
            net_arch = {"pi": [64, 64], "vf": [64, 64]}
        elif isinstance(net_arch, (list, tuple)):
            net_arch = {"pi": list(net_arch), "vf": list(net_arch)}
        if not isinstance(net_arch, dict) or set(net_arch) != {"pi", "vf"}:
            raise ValueError(f"net_arch must be a list or dict(pi=[...], vf=[...]), got {net_arch!r}")
        self.net_arch = net_arch
        self.activation_fn = activation_fn
        self.log_std_init = float(log_std_init)
        self.ortho_init = ortho_init
        self.squash_mean = bool(squash_mean)
        self.state_dependent_std = bool(state_dependent_std)

        self.features_extractor = self.make_features_extractor()
        features = self.features_extractor.features_dim
        self.actor_trunk, latent_pi = mlp(features, net_arch["pi"], activation_fn)
        self.critic_trunk, latent_vf = mlp(features, net_arch["vf"], activation_fn)
        self.value_net = nn.Linear(latent_vf, 1)
        self.heads = nn.ModuleList(
            SkillHead(
                latent_pi,
                self.adapter.n_discrete,
                self.adapter.n_parameters,
                log_std_init,
                self.squash_mean,
                self.state_dependent_std,
            )
            for _ in range(self.n_skills)
        )
        self.router_net = nn.Linear(latent_pi, self.n_skills) if self.learned_router else None
        self.register_buffer("parameter_mask", th.as_tensor(self.adapter.parameter_mask, dtype=th.float32))
        if ortho_init:
            for module, gain in [
                (self.actor_trunk, np.sqrt(2)),
                (self.critic_trunk, np.sqrt(2)),
                (self.value_net, 1.0),
                *[(head.linear, 0.01) for head in self.heads],
                *([(self.router_net, 0.01)] if self.router_net is not None else []),
            ]:
                module.apply(lambda m, g=gain: self.init_weights(m, gain=g))
        self._build_optimizers(lr_schedule)

    def _build_optimizers(self, lr_schedule: Schedule) -> None:
        head_ids = {id(p) for head in self.heads for p in head.parameters()}
        shared = [p for p in self.parameters() if id(p) not in head_ids]
        self.optimizer = self.optimizer_class(shared, lr=lr_schedule(1), **self.optimizer_kwargs)
        for skill, head in enumerate(self.heads):
            optimizer = self.optimizer_class(head.parameters(), lr=lr_schedule(1), **self.optimizer_kwargs)
            setattr(self, f"skill_{skill}_optimizer", optimizer)

    @property
    def optimizers(self) -> list[th.optim.Optimizer]:
        """The shared optimizer, then one per skill."""
        return [self.optimizer, *self.skill_optimizers]

    @property
    def skill_optimizers(self) -> list[th.optim.Optimizer]:
        return [getattr(self, f"skill_{skill}_optimizer") for skill in range(self.n_skills)]

    @property
    def optimizer_names(self) -> list[str]:
        """Attribute names of :attr:`optimizers` (what save/load stores)."""
        return ["optimizer", *(f"skill_{skill}_optimizer" for skill in range(self.n_skills))]

    @property
    def action_vector_size(self) -> int:
        """Length of a buffer action: ``[k, P parameters]`` plus the skill with a learned router."""
        return self.adapter.internal_size + (1 if self.learned_router else 0)

    def _get_constructor_parameters(self) -> dict[str, Any]:
        data = super()._get_constructor_parameters()
        data.update(
            net_arch=self.net_arch,
            activation_fn=self.activation_fn,
            log_std_init=self.log_std_init,
            ortho_init=self.ortho_init,
            skills=self.n_skills,
            router=self.router,
            parameter_sizes=self.parameter_sizes,
            domain=self.domain,
            squash_mean=self.squash_mean,
            state_dependent_std=self.state_dependent_std,
            lr_schedule=self._dummy_schedule,
            features_extractor_class=self.features_extractor_class,
            features_extractor_kwargs=self.features_extractor_kwargs,
            optimizer_class=self.optimizer_class,
            optimizer_kwargs=self.optimizer_kwargs,
        )
        return data

    # ---- the networks -------------------------------------------------------------------------------------------
    def actor_outputs(self, obs: PyTorchObs) -> tuple[th.Tensor, th.Tensor | None, th.Tensor]:
        """``(latent (B, L), router logits (B, S) or None, features (B, F))`` for a batch of observations."""
        features = self.extract_features(obs, self.features_extractor)
        latent = self.actor_trunk(features)
        router_logits = self.router_net(latent) if self.router_net is not None else None
        return latent, router_logits, features

    def _fixed_skills(self, obs: PyTorchObs, batch: int) -> th.Tensor:
        if self.n_skills == 1:
            return th.zeros(batch, dtype=th.long, device=self.device)
        from sb3_hfo.common.routers import validate_skills

        return validate_skills(self.skill_router(obs), batch, self.n_skills, self.skill_router, self.device)

    def _distribution(self, latent: th.Tensor, skills: th.Tensor) -> HybridDistribution:
        """The hybrid distribution of each row's own skill head."""
        if self.n_skills == 1:
            logits, mean = self.heads[0](latent)
            log_std = self.heads[0].log_std_of(latent)
        else:
            outputs = [head(latent) for head in self.heads]
            rows = th.arange(latent.shape[0], device=latent.device)
            logits = th.stack([o[0] for o in outputs], dim=1)[rows, skills]
            mean = th.stack([o[1] for o in outputs], dim=1)[rows, skills]
            if self.state_dependent_std:
                log_std = th.stack([head.log_std_of(latent) for head in self.heads], dim=1)[rows, skills]
            else:
                log_std = th.stack([head.log_std for head in self.heads])[skills]
        return HybridDistribution(logits, mean, log_std, self.parameter_mask)

    def forward(self, obs: PyTorchObs, deterministic: bool = False) -> tuple[th.Tensor, th.Tensor, th.Tensor]:
        """``(buffer actions (B, action_vector_size), values (B, 1), log-probabilities (B,))`` for a rollout step."""
        latent, router_logits, features = self.actor_outputs(obs)
        values = self.value_net(self.critic_trunk(features))
        actions, log_prob = self._act(obs, latent, router_logits, deterministic)
        return actions, values, log_prob

    def _act(
        self, obs: PyTorchObs, latent: th.Tensor, router_logits: th.Tensor | None, deterministic: bool
    ) -> tuple[th.Tensor, th.Tensor]:
        batch = latent.shape[0]
        if router_logits is not None:
            log_rho = th.log_softmax(router_logits, dim=-1)
            skills = log_rho.argmax(-1) if deterministic else th.multinomial(log_rho.exp(), 1).squeeze(-1)
            router_log_prob = log_rho.gather(-1, skills.unsqueeze(-1)).squeeze(-1)
        else:
            skills = self._fixed_skills(obs, batch)
            router_log_prob = th.zeros(batch, device=latent.device)
        distribution = self._distribution(latent, skills)
        discrete, parameters = distribution.mode() if deterministic else distribution.sample()
        log_prob = distribution.log_prob(discrete, parameters) + router_log_prob
        columns = [discrete.unsqueeze(-1).to(parameters.dtype), parameters]
        if router_logits is not None:
            columns.append(skills.unsqueeze(-1).to(parameters.dtype))
        return th.cat(columns, dim=-1), log_prob

    def skills_of(self, obs: PyTorchObs, actions: th.Tensor) -> th.Tensor:
        """The skill of each buffer action ``(B,)`` long: its stored column with a learned router, else the router's."""
        if self.learned_router:
            return actions[:, -1].long()
        return self._fixed_skills(obs, actions.shape[0])

    def evaluate_actions(self, obs: PyTorchObs, actions: th.Tensor) -> tuple[th.Tensor, th.Tensor, th.Tensor]:
        """``(values (B, 1), log-probabilities (B,), entropies (B,))`` of buffer actions under the current policy."""
        latent, router_logits, features = self.actor_outputs(obs)
        values = self.value_net(self.critic_trunk(features))
        skills = self.skills_of(obs, actions)
        distribution = self._distribution(latent, skills)
        discrete = actions[:, 0].long()
        parameters = actions[:, 1 : self.adapter.internal_size]
        log_prob = distribution.log_prob(discrete, parameters)
        entropy = distribution.entropy(discrete)
        if router_logits is not None:
            log_rho = th.log_softmax(router_logits, dim=-1)
            log_prob = log_prob + log_rho.gather(-1, skills.unsqueeze(-1)).squeeze(-1)
            entropy = entropy + categorical_entropy(log_rho)
        return values, log_prob, entropy

    def action_distribution(self, obs: PyTorchObs) -> HybridDistribution:
        """The hybrid distribution of each row's routed skill head (for a pull toward a reference policy, or
        distillation). A hand-coded router only: with a learned router the skill is part of the action, and this
        distribution would leave it out.

        :raises ValueError: with ``router="learned"``.
        """
        if self.learned_router:
            raise ValueError(
                "action_distribution needs a hand-coded router (or one skill); with router='learned' the skill "
                "choice is part of the action"
            )
        latent, _, _ = self.actor_outputs(obs)
        return self._distribution(latent, self._fixed_skills(obs, latent.shape[0]))

    def routed_skills(self, obs: PyTorchObs) -> th.Tensor:
        """``(B,)`` long: the skill a hand-coded router picks for each state (zeros with one skill).

        :raises ValueError: with ``router="learned"`` (its skill is drawn, not given by the state).
        """
        if self.learned_router:
            raise ValueError("routed_skills needs a hand-coded router; router='learned' draws the skill")
        return self._fixed_skills(obs, obs.shape[0])

    def skill_distribution(
        self, obs: PyTorchObs, skills: th.Tensor
    ) -> tuple[HybridDistribution, th.Tensor | None]:
        """The hybrid distribution of the head ``skills[i]`` in state ``i`` (whatever this policy's router would
        pick), and with a learned router its ``(B, S)`` log-probabilities ``log rho(.|s)`` (else ``None``).

        For fitting or pulling a learned-router policy toward a hand-coded router's choice (distillation, the pull
        of :meth:`sb3_hfo.hybrid_ppo.HybridPPO.reference_kl`).

        :raises ValueError: ``skills`` of another batch size or out of ``[0, n_skills)``.
        """
        latent, router_logits, _ = self.actor_outputs(obs)
        skills = th.as_tensor(skills, device=latent.device).long().reshape(-1)
        if skills.shape[0] != latent.shape[0] or (
            skills.numel() and not 0 <= int(skills.min()) <= int(skills.max()) < self.n_skills
        ):
            raise ValueError(
                f"skill_distribution needs one skill in [0, {self.n_skills}) per state; got {tuple(skills.shape)} "
                f"for {latent.shape[0]} states"
            )
        log_rho = th.log_softmax(router_logits, dim=-1) if router_logits is not None else None
        return self._distribution(latent, skills), log_rho

    def hand_routed_copy(self, router: Any) -> HybridActorCriticPolicy:
        """A copy of this policy whose skills a hand-coded ``router`` picks (as the ``router`` argument; e.g.
        ``"field_half"``): the same features extractor, trunk, heads and critic; a learned router's layer is
        dropped. E.g. the reference a learned-router policy is pulled toward (:meth:`HybridPPO.set_reference`).

        :raises ValueError: ``router="learned"``, or with one skill.
        """
        if router == LEARNED_ROUTER or self.n_skills == 1:
            raise ValueError(
                f"hand_routed_copy needs a hand-coded router and skills > 1; got router={router!r} with "
                f"{self.n_skills} skill(s)"
            )
        copy = type(self)(**{**self._get_constructor_parameters(), "router": router})
        state = {key: value for key, value in self.state_dict().items() if not key.startswith("router_net.")}
        copy.load_state_dict(state)  # strict: every other tensor has its counterpart
        return copy.to(self.device)

    def predict_values(self, obs: PyTorchObs) -> th.Tensor:
        """``(B, 1)`` state values."""
        return self.value_net(self.critic_trunk(self.extract_features(obs, self.features_extractor)))

    def step_optimizers(self, skills: th.Tensor) -> None:
        """One step of the shared optimizer and of each skill's optimizer whose head had rows in ``skills``."""
        self.optimizer.step()
        used = th.bincount(skills, minlength=self.n_skills).tolist() if self.n_skills > 1 else [1]
        for optimizer, count in zip(self.skill_optimizers, used, strict=True):
            if count:
                optimizer.step()

    # ---- acting -------------------------------------------------------------------------------------------------
    def _predict(self, observation: PyTorchObs, deterministic: bool = False) -> th.Tensor:
        latent, router_logits, _ = self.actor_outputs(observation)
        return self._act(observation, latent, router_logits, deterministic)[0]

    def predict(
        self,
        observation: np.ndarray | dict[str, np.ndarray],
        state: tuple[np.ndarray, ...] | None = None,
        episode_start: np.ndarray | None = None,
        deterministic: bool = False,
    ) -> tuple[Any, tuple[np.ndarray, ...] | None]:
        """Env actions for ``observation`` (one or a batch): ``deterministic`` plays the most likely discrete action
        (and skill, with a learned router) with its parameters' means."""
        self.set_training_mode(False)
        obs_tensor, vectorized = self.obs_to_tensor(observation)
        with th.no_grad():
            internal = self._predict(obs_tensor, deterministic=deterministic)
        actions = self.adapter.to_env(internal[:, : self.adapter.internal_size].cpu().numpy())
        return (actions if vectorized else actions[0]), state
