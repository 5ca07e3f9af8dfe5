"""HybridPPO: PPO (Schulman et al. 2017) over parameterised (discrete + continuous) actions, as an SB3 algorithm.

The update is SB3's PPO (clipped surrogate, optional value clipping, entropy bonus, GAE from SB3's
``RolloutBuffer``, early stop on ``target_kl``) with the hybrid log-probability and entropy of
:mod:`sb3_hfo.hybrid_ppo.distributions`; ``train`` reads top to bottom like SB3's ``PPO.train``. What differs from
SB3's ``PPO``:

* the action space may be hybrid (:mod:`sb3_hfo.hybrid_ppo.layout`): the rollout buffer stores the internal
  vector ``[k, parameters (unclipped), skill (learned router only)]``, and ``collect_rollouts`` hands the env
  its own format (clipped to its bounds) through the policy's adapter;
* one optimizer per skill head plus one for the shared parts (:mod:`sb3_hfo.hybrid_ppo.policies`);
* ``rollout/action_<name>_fraction`` (and ``rollout/skill_<s>_fraction`` with skills) log how often each discrete
  action (skill) was sampled in the last rollout;
* two options for starting from a good policy (e.g. one distilled from an imitation clone), both off by default:

  - a pull toward a frozen *reference* policy (:meth:`HybridPPO.set_reference`): the loss adds
    ``reference_coef(progress_remaining) * mean KL(reference(.|s) || pi(.|s))`` over each minibatch's states
    (:func:`~sb3_hfo.hybrid_ppo.distributions.hybrid_kl`), the cross-entropy to the teacher of "kickstarting"
    (Schmitt et al. 2018, "Kickstarting deep reinforcement learning") with a coefficient that may decay to 0
    (:class:`~sb3_hfo.common.schedules.DecayToZero`). The reference is not saved with the model. A policy with a
    learned router may be pulled toward a hand-coded-router reference of as many skills: the KL is then over the
    joint action (skill, discrete action, parameters), :meth:`HybridPPO.reference_kl`;
  - a critic warm-up: for the first ``critic_warmup_steps`` env steps the update trains the value function only
    (no policy, entropy or pull term; the actor's weights get no gradient and do not move), so that the first
    policy updates use advantages from a critic fitted to the starting policy rather than a random one.
"""

from __future__ import annotations

from typing import Any, ClassVar, TypeVar

import numpy as np
import torch as th
from gymnasium import spaces
from stable_baselines3.common.buffers import RolloutBuffer
from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.on_policy_algorithm import OnPolicyAlgorithm
from stable_baselines3.common.policies import BasePolicy
from stable_baselines3.common.type_aliases import GymEnv, Schedule
from stable_baselines3.common.utils import FloatSchedule, explained_variance, obs_as_tensor
from stable_baselines3.common.vec_env import VecEnv

from sb3_hfo.common.domain import LEGACY_DOMAIN
from sb3_hfo.hybrid_ppo.distributions import hybrid_kl
from sb3_hfo.hybrid_ppo.policies import HybridActorCriticPolicy

__all__ = ["HybridPPO"]

SelfHybridPPO = TypeVar("SelfHybridPPO", bound="HybridPPO")


class HybridPPO(OnPolicyAlgorithm):
    """PPO with a hybrid action distribution. Hyperparameters and defaults are SB3's ``PPO``'s
    (``n_steps`` per env, ``batch_size``, ``n_epochs``, ``clip_range``, ``clip_range_vf``, ``normalize_advantage``,
    ``ent_coef``, ``vf_coef``, ``max_grad_norm``, ``target_kl``); ``policy_kwargs`` go to
    :class:`~sb3_hfo.hybrid_ppo.policies.HybridActorCriticPolicy` (e.g. ``skills=2, router="field_half"``).
    """

    policy_aliases: ClassVar[dict[str, type[BasePolicy]]] = {
        "MlpPolicy": HybridActorCriticPolicy,
        "HybridPolicy": HybridActorCriticPolicy,
    }
    policy: HybridActorCriticPolicy

    def __init__(
        self,
        policy: str | type[HybridActorCriticPolicy],
        env: GymEnv | str,
        learning_rate: float | Schedule = 3e-4,
        n_steps: int = 2048,
        batch_size: int = 64,
        n_epochs: int = 10,
        gamma: float = 0.99,
        gae_lambda: float = 0.95,
        clip_range: float | Schedule = 0.2,
        clip_range_vf: float | Schedule | None = None,
        normalize_advantage: bool = True,
        ent_coef: float = 0.0,
        vf_coef: float = 0.5,
        max_grad_norm: float = 0.5,
        target_kl: float | None = None,
        reference_coef: float | Schedule = 0.0,
        critic_warmup_steps: int = 0,
        stats_window_size: int = 100,
        tensorboard_log: str | None = None,
        policy_kwargs: dict[str, Any] | None = None,
        verbose: int = 0,
        seed: int | None = None,
        device: th.device | str = "auto",
        _init_setup_model: bool = True,
    ) -> None:
        super().__init__(
            policy,
            env,
            learning_rate=learning_rate,
            n_steps=n_steps,
            gamma=gamma,
            gae_lambda=gae_lambda,
            ent_coef=ent_coef,
            vf_coef=vf_coef,
            max_grad_norm=max_grad_norm,
            use_sde=False,
            sde_sample_freq=-1,
            stats_window_size=stats_window_size,
            tensorboard_log=tensorboard_log,
            policy_kwargs=policy_kwargs,
            verbose=verbose,
            seed=seed,
            device=device,
            _init_setup_model=False,
            supported_action_spaces=None,  # the adapter checks the space and names it in a ValueError
        )
        if batch_size < 2 and normalize_advantage:
            raise ValueError(
                "batch_size must be > 1 with normalize_advantage (advantages are normalised per batch)"
            )
        if n_steps < 1 or n_epochs < 1 or batch_size < 1:
            raise ValueError(
                f"n_steps, batch_size and n_epochs must be >= 1, got {n_steps}, {batch_size}, {n_epochs}"
            )
        self.batch_size = batch_size
        self.n_epochs = n_epochs
        self.clip_range = clip_range
        self.clip_range_vf = clip_range_vf
        self.normalize_advantage = normalize_advantage
        self.target_kl = target_kl
        if not callable(reference_coef) and not float(reference_coef) >= 0.0:
            raise ValueError(f"reference_coef must be >= 0 (or a schedule), got {reference_coef!r}")
        if (
            isinstance(critic_warmup_steps, bool)
            or not isinstance(critic_warmup_steps, (int, np.integer))
            or (critic_warmup_steps < 0)
        ):
            raise ValueError(f"critic_warmup_steps must be an integer >= 0, got {critic_warmup_steps!r}")
        self.reference_coef = reference_coef
        self.critic_warmup_steps = int(critic_warmup_steps)
        if _init_setup_model:
            # the domain is saved explicitly, so that a model without it is known to predate it (LEGACY_DOMAIN)
            self.policy_kwargs = {"domain": None, **self.policy_kwargs}
            self._setup_model()

    def _setup_model(self) -> None:
        if "domain" not in self.policy_kwargs:  # loading a model saved before the option
            self.policy_kwargs = {**self.policy_kwargs, "domain": LEGACY_DOMAIN}
        self._setup_lr_schedule()
        self.set_random_seed(self.seed)
        self.policy = self.policy_class(  # type: ignore[assignment]
            self.observation_space, self.action_space, self.lr_schedule, **self.policy_kwargs
        )
        self.policy = self.policy.to(self.device)
        # The buffer stores the internal action vector (unclipped parameters), not the env's format.
        buffer_actions = spaces.Box(-np.inf, np.inf, (self.policy.action_vector_size,), np.float32)
        self.rollout_buffer = RolloutBuffer(
            self.n_steps,
            self.observation_space,  # type: ignore[arg-type]
            buffer_actions,
            device=self.device,
            gamma=self.gamma,
            gae_lambda=self.gae_lambda,
            n_envs=self.n_envs,
        )
        self.clip_range = FloatSchedule(self.clip_range)
        # models saved before the options load without them: no pull, no warm-up
        self.reference_coef = FloatSchedule(getattr(self, "reference_coef", 0.0))
        self.critic_warmup_steps = getattr(self, "critic_warmup_steps", 0)
        self.reference_policy: HybridActorCriticPolicy | None = None
        if self.clip_range_vf is not None:
            if isinstance(self.clip_range_vf, (float, int)) and self.clip_range_vf <= 0:
                raise ValueError("clip_range_vf must be positive (or None to disable value clipping)")
            self.clip_range_vf = FloatSchedule(self.clip_range_vf)

    def _get_torch_save_params(self) -> tuple[list[str], list[str]]:
        return ["policy", *(f"policy.{name}" for name in self.policy.optimizer_names)], []

    def _excluded_save_params(self) -> list[str]:
        return [*super()._excluded_save_params(), "reference_policy"]

    def set_reference(self, reference: HybridActorCriticPolicy | None) -> None:
        """Pull the policy toward ``reference`` with weight ``reference_coef`` (``None``: no pull).

        The reference is frozen here (no gradient, evaluation mode) and moved to the model's device; it must
        have the same action adapter layout (discrete actions and parameters) and a hand-coded router; when this
        policy's router is learned, the reference must have as many skills (its skill ``s`` is compared with this
        policy's skill ``s``, :meth:`reference_kl`).

        :raises ValueError: a reference of another action layout, one with a learned router, or another number of
            skills than a learned-router policy's.
        """
        if reference is None:
            self.reference_policy = None
            return
        if not isinstance(reference, HybridActorCriticPolicy):
            raise ValueError(
                f"the reference must be a HybridActorCriticPolicy, got {type(reference).__name__}"
            )
        mine, theirs = self.policy.adapter, reference.adapter
        if theirs.names != mine.names or not np.array_equal(theirs.parameter_mask, mine.parameter_mask):
            raise ValueError(f"the reference's actions {theirs!r} differ from the policy's {mine!r}")
        if reference.learned_router:
            raise ValueError("the reference must route skills by a hand-coded router, not router='learned'")
        if self.policy.learned_router and reference.n_skills != self.policy.n_skills:
            raise ValueError(
                f"a learned-router policy ({self.policy.n_skills} skills) is pulled skill by skill; the reference "
                f"has {reference.n_skills}"
            )
        reference = reference.to(self.device)
        reference.set_training_mode(False)
        for parameter in reference.parameters():
            parameter.requires_grad_(False)
        self.reference_policy = reference

    def reference_kl(self, obs: th.Tensor) -> th.Tensor:
        """``(B,)`` ``KL(reference(.|s) || pi(.|s))`` of the current policy for a batch of observations.

        With a hand-coded router (or one skill) both policies act by their routed head: the hybrid KL of the two
        heads' distributions (:func:`~sb3_hfo.hybrid_ppo.distributions.hybrid_kl`).

        With a learned router this policy's action is the triple ``(skill s, k, u)`` with
        ``pi(s, k, u) = rho(s) pi_s(k, u)``. The reference is read as a policy over the same triples that plays its
        router's skill ``f(obs)`` with probability 1, so the KL over the triples is exact and finite (the chain rule
        of the KL, the reference's skill being a point mass):

            KL = -log rho(f(obs)) + KL(reference_f(k, u) || pi_f(k, u))

        the router's cross-entropy to the reference's choice plus the hybrid KL of the head the reference routes to.
        It is 0 exactly when the router picks ``f(obs)`` with certainty and that head plays as the reference's.
        Why not the KL to the policy's marginal over ``(k, u)`` (the mixture ``sum_s rho(s) pi_s``): a mixture of
        Gaussians has no closed-form KL, and the joint KL bounds it from above (chain rule again), so pulling the
        joint KL to 0 pulls the marginal one too. The price: a router that leaves ``f(obs)`` is pulled back even
        where the other head would play the same; the pull's coefficient may decay to 0, after which the router is
        free (what the learned-router comparison of benchmarks/rl_from_clone.py wants).

        :raises ValueError: when no reference is set (:meth:`set_reference`).
        """
        if self.reference_policy is None:
            raise ValueError("no reference policy: call set_reference first")
        if not self.policy.learned_router:
            with th.no_grad():
                reference = self.reference_policy.action_distribution(obs)
            return hybrid_kl(reference, self.policy.action_distribution(obs))
        with th.no_grad():
            reference_skills = self.reference_policy.routed_skills(obs)
            reference = self.reference_policy.action_distribution(obs)
        current, log_rho = self.policy.skill_distribution(obs, reference_skills)
        assert log_rho is not None  # a learned router's log-probabilities
        router_cross_entropy = -log_rho.gather(-1, reference_skills.unsqueeze(-1)).squeeze(-1)
        return router_cross_entropy + hybrid_kl(reference, current)

    def collect_rollouts(
        self, env: VecEnv, callback: BaseCallback, rollout_buffer: RolloutBuffer, n_rollout_steps: int
    ) -> bool:
        """Fill ``rollout_buffer`` with ``n_rollout_steps`` steps of every env (SB3's ``collect_rollouts``, with
        the env's action format from the adapter and the discrete-action counts logged)."""
        assert self._last_obs is not None
        self.policy.set_training_mode(False)
        rollout_buffer.reset()
        adapter = self.policy.adapter
        discrete_counts = np.zeros(adapter.n_discrete, dtype=np.int64)
        skill_counts = np.zeros(self.policy.n_skills, dtype=np.int64)
        callback.on_rollout_start()
        for _ in range(n_rollout_steps):
            with th.no_grad():
                obs_tensor = obs_as_tensor(self._last_obs, self.device)  # type: ignore[arg-type]
                actions_t, values, log_probs = self.policy(obs_tensor)
                if self.policy.n_skills > 1:
                    skill_counts += np.bincount(
                        self.policy.skills_of(obs_tensor, actions_t).cpu().numpy(),
                        minlength=self.policy.n_skills,
                    )
            actions = actions_t.cpu().numpy()
            discrete_counts += np.bincount(actions[:, 0].astype(np.int64), minlength=adapter.n_discrete)
            new_obs, rewards, dones, infos = env.step(adapter.to_env(actions[:, : adapter.internal_size]))
            self.num_timesteps += env.num_envs
            callback.update_locals(locals())
            if not callback.on_step():
                return False
            self._update_info_buffer(infos, dones)
            # A time-limit truncation is not a terminal state: bootstrap with the value of the last observation.
            for index, done in enumerate(dones):
                terminal_obs = infos[index].get("terminal_observation")
                if done and terminal_obs is not None and infos[index].get("TimeLimit.truncated", False):
                    with th.no_grad():
                        terminal_value = self.policy.predict_values(
                            self.policy.obs_to_tensor(terminal_obs)[0]
                        )[0]
                    rewards[index] += self.gamma * terminal_value.item()
            rollout_buffer.add(self._last_obs, actions, rewards, self._last_episode_starts, values, log_probs)  # type: ignore[arg-type]
            self._last_obs = new_obs  # type: ignore[assignment]
            self._last_episode_starts = dones
        with th.no_grad():
            last_values = self.policy.predict_values(obs_as_tensor(new_obs, self.device))  # type: ignore[arg-type]
        rollout_buffer.compute_returns_and_advantage(last_values=last_values, dones=dones)
        total = max(int(discrete_counts.sum()), 1)
        for name, count in zip(adapter.names, discrete_counts, strict=True):
            self.logger.record(f"rollout/action_{name}_fraction", count / total)
        if self.policy.n_skills > 1:
            for skill, count in enumerate(skill_counts):
                self.logger.record(f"rollout/skill_{skill}_fraction", count / total)
        callback.update_locals(locals())
        callback.on_rollout_end()
        return True

    def train(self) -> None:
        """PPO's update over the rollout buffer: ``n_epochs`` passes of minibatches of ``batch_size``."""
        self.policy.set_training_mode(True)
        self._update_learning_rate(self.policy.optimizers)
        clip_range = self.clip_range(self._current_progress_remaining)  # type: ignore[operator]
        clip_range_vf = (
            None if self.clip_range_vf is None else self.clip_range_vf(self._current_progress_remaining)
        )  # type: ignore[operator]
        entropy_losses, pg_losses, value_losses, clip_fractions, approx_kls = [], [], [], [], []
        reference_kls: list[float] = []
        reference_coef = float(self.reference_coef(self._current_progress_remaining))
        pulled = self.reference_policy is not None and reference_coef > 0.0
        # the critic warm-up: value loss only (the steps counted include the rollout just collected)
        critic_only = self.num_timesteps <= self.critic_warmup_steps
        continue_training = True
        for _epoch in range(self.n_epochs):
            for batch in self.rollout_buffer.get(self.batch_size):
                values, log_prob, entropy = self.policy.evaluate_actions(batch.observations, batch.actions)
                values = values.flatten()
                advantages = batch.advantages
                if self.normalize_advantage and len(advantages) > 1:
                    advantages = (advantages - advantages.mean()) / (advantages.std() + 1e-8)
                # Clipped surrogate objective
                ratio = th.exp(log_prob - batch.old_log_prob)
                surrogate = th.min(
                    advantages * ratio, advantages * th.clamp(ratio, 1 - clip_range, 1 + clip_range)
                )
                policy_loss = -surrogate.mean()
                # Value loss, optionally clipped around the rollout's values
                if clip_range_vf is not None:
                    values = batch.old_values + th.clamp(
                        values - batch.old_values, -clip_range_vf, clip_range_vf
                    )
                value_loss = th.nn.functional.mse_loss(batch.returns, values)
                entropy_loss = -entropy.mean()
                if critic_only:
                    loss = self.vf_coef * value_loss
                else:
                    loss = policy_loss + self.ent_coef * entropy_loss + self.vf_coef * value_loss
                    if pulled:
                        reference_kl = self.reference_kl(batch.observations).mean()
                        loss = loss + reference_coef * reference_kl
                        reference_kls.append(reference_kl.item())
                with th.no_grad():
                    log_ratio = log_prob - batch.old_log_prob
                    approx_kl = th.mean(th.exp(log_ratio) - 1 - log_ratio).item()  # Schulman's k3 estimator
                pg_losses.append(policy_loss.item())
                value_losses.append(value_loss.item())
                entropy_losses.append(entropy_loss.item())
                clip_fractions.append(th.mean((th.abs(ratio - 1) > clip_range).float()).item())
                approx_kls.append(approx_kl)
                if self.target_kl is not None and approx_kl > 1.5 * self.target_kl:
                    continue_training = False
                    if self.verbose >= 1:
                        print(f"Early stopping at epoch {_epoch} due to reaching max kl: {approx_kl:.2f}")
                    break
                for optimizer in self.policy.optimizers:
                    optimizer.zero_grad(set_to_none=True)
                loss.backward()
                th.nn.utils.clip_grad_norm_(self.policy.parameters(), self.max_grad_norm)
                self.policy.step_optimizers(self.policy.skills_of(batch.observations, batch.actions))
            self._n_updates += 1
            if not continue_training:
                break
        if getattr(self.policy, "state_dependent_std", False):
            # the deviations differ by state: their mean over the last minibatch's states, not the offset alone
            with th.no_grad():
                latent = self.policy.actor_outputs(batch.observations)[0]
                log_std = th.cat([head.log_std_of(latent).flatten() for head in self.policy.heads])
        else:
            log_std = th.cat([head.log_std for head in self.policy.heads])
        self.logger.record("train/entropy_loss", np.mean(entropy_losses))
        self.logger.record("train/policy_gradient_loss", np.mean(pg_losses))
        self.logger.record("train/value_loss", np.mean(value_losses))
        self.logger.record("train/approx_kl", np.mean(approx_kls))
        self.logger.record("train/clip_fraction", np.mean(clip_fractions))
        self.logger.record("train/loss", loss.item())
        self.logger.record(
            "train/explained_variance",
            explained_variance(self.rollout_buffer.values.flatten(), self.rollout_buffer.returns.flatten()),
        )
        if log_std.numel():
            self.logger.record("train/std", th.exp(log_std).mean().item())
        self.logger.record("train/n_updates", self._n_updates, exclude="tensorboard")
        self.logger.record("train/clip_range", clip_range)
        self.logger.record(
            "train/reference_coef", reference_coef if self.reference_policy is not None else 0.0
        )
        self.logger.record("train/critic_only", float(critic_only))
        if reference_kls:
            self.logger.record("train/reference_kl", np.mean(reference_kls))
        if clip_range_vf is not None:
            self.logger.record("train/clip_range_vf", clip_range_vf)

    def learn(
        self: SelfHybridPPO,
        total_timesteps: int,
        callback: Any = None,
        log_interval: int = 1,
        tb_log_name: str = "HybridPPO",
        reset_num_timesteps: bool = True,
        progress_bar: bool = False,
    ) -> SelfHybridPPO:
        return super().learn(
            total_timesteps=total_timesteps,
            callback=callback,
            log_interval=log_interval,
            tb_log_name=tb_log_name,
            reset_num_timesteps=reset_num_timesteps,
            progress_bar=progress_bar,
        )
