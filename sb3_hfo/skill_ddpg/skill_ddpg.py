"""SkillDDPG: DDPG with hand-routed skills (seed paper, "Method"), as a Stable-Baselines3 off-policy algorithm.

One update (``train`` does ``gradient_steps`` of them, each on a minibatch of ``batch_size``):

1. Critic: ``y = r + gamma * (1 - done) * Q'(s', mu'_{skill(s')}(s'))`` with the target networks (paper eq. 6),
   ``L = mean((Q(s, a) - y)^2)`` (eq. 5), one Adam step (``policy.critic_optimizer``).
   With ``discrete_target="max"`` (P-DQN, beyond the paper) ``Q'(s', ...)`` is the best of the discrete actions
   at the target actor's parameters, the value of the policy that the critic's choice (acting ``CriticChoice``) acts with.
2. Actor (eq. 7), with the critic just updated: every row's action comes from the head its skill router picks;
   ``g = dQ/da`` at ``a = mu_{skill(s)}(s)`` for the whole minibatch in one critic pass. Skill ``k``'s loss is
   ``-mean over the rows routed to k of Q(s, a)``; its gradient over (trunk + head k) is the back-propagation of
   ``-g / n_k`` through the actor on those rows (computed for all skills in one backward pass, each skill's weight
   gradients summed over its own rows only). All skills' gradients are evaluated at the same parameters (the
   per-layer ``dZ`` of all rows first; the weight products need no parameter), then each skill that had rows
   takes one step of its own Adam (``policy.actor_skill_{k}_optimizer``). A skill without rows takes no step
   (parameters and Adam state unchanged). With one skill this is exactly DDPG's actor update.
   With ``inverting_gradients`` ``g`` is first rescaled per dimension (Hausknecht & Stone 2016, bounds [-1, 1]):
   ``g * (1 - a) / 2`` where ``g > 0`` (the update would increase ``a``) and ``g * (a + 1) / 2`` elsewhere.
   With the policy's ``mask_unused_parameters`` the critic sees every action (replayed, the actor's and the target
   actor's) with the parameters of the discrete actions not chosen set to 0, and ``g`` is zero on them.
   With ``parameter_loss="each_action"`` (P-DQN's parameter loss, beyond the paper; needs that mask) the actor's
   loss is ``-Q(s, mu(s))`` for the preferences only plus ``-sum_k Q(s, e_k, x_k(s))`` for the parameters: each
   discrete action ``k``'s parameters ``x_k`` are trained by the value of ``k`` played with them (``e_k``: its
   one-hot preferences), in every state, whichever action the preferences favour (KICK's not where
   the kick mask leaves it out); one extra critic pass over ``n_discrete * B`` rows.
3. Target networks: ``theta' <- theta' + tau * (theta - theta')`` (one ``torch._foreach_lerp_`` call).

The update above is :meth:`SkillDDPG._autograd_update`, written with autograd in the style of SB3's
``TD3.train``. By default (``fast_update=True``) training runs the same update back-propagated by hand, with
torch's fused Adam kernel called directly (:mod:`sb3_hfo.skill_ddpg.fast_update`, about twice SB3's ``DDPG``
updates per second with one skill); ``tests/test_skill_ddpg.py`` checks that both give the same parameters.

Exploration (``_sample_action``): SB3's random warm-up (``learning_starts``) and ``action_noise`` as usual, then
epsilon-greedy over the discrete actions of a parameterised flat action (the action space's hybrid layout,
:mod:`hfo2d.action_layout`; HFO: DASH / TURN / KICK preferences first; Hausknecht & Stone anneal epsilon 1 -> 0.1): with probability epsilon the whole
action is redrawn uniformly and one of the ``n_discrete_actions`` preferences, chosen uniformly, is set to the
maximum (1 in the buffer scale) so that the environment's argmax picks it. Epsilon anneals linearly from
``exploration_initial_eps`` to ``exploration_final_eps`` over the first ``exploration_fraction`` of the
``learn()`` call (SB3's DQN convention). ``n_discrete_actions=None`` takes the number from the action layout
and 0 (no epsilon-greedy) for a plain ``Box``, e.g. Pendulum. With ``exploration_keep_parameters=True`` an
exploring step only re-picks the discrete action (its preference set to 1, the others to -1) and keeps the policy's
(noisy) continuous parameters, so that a randomly chosen KICK is taken with the kick the actor would make.

Threads: ``learn`` trains with one torch thread, as ``python -m sb3_hfo.train`` does, unless the user has chosen a
count (:func:`training_threads` gives the rule). Logging: besides SB3's ``rollout/*`` and ``time/*`` (the goal rate
is SB3's ``rollout/success_rate``, from HFO's ``info["is_success"]``), ``train/critic_loss``, ``train/actor_loss``
(and per skill), ``train/max_q``, ``train/mean_q``, both learning rates, ``rollout/skill_<k>_fraction`` and
``rollout/epsilon``.
"""

from __future__ import annotations

import io
import math
import os
import pathlib
from collections.abc import Iterable
from typing import Any, ClassVar, TypeVar

import numpy as np
import torch as th
from gymnasium import spaces
from stable_baselines3.common.buffers import ReplayBuffer
from stable_baselines3.common.noise import ActionNoise
from stable_baselines3.common.off_policy_algorithm import OffPolicyAlgorithm
from stable_baselines3.common.policies import BasePolicy
from stable_baselines3.common.type_aliases import GymEnv, MaybeCallback, ReplayBufferSamples, Schedule
from stable_baselines3.common.utils import (
    ConstantSchedule,
    FloatSchedule,
    LinearSchedule,
    polyak_update,
    update_learning_rate,
)
from torch.nn import functional as F

from hfo2d.action_layout import action_layout, hfo_flat_action_space
from sb3_hfo.common.buffers import MonteCarloReplayBuffer, MonteCarloReplayBufferSamples
from sb3_hfo.skill_ddpg.acting import format_acting
from sb3_hfo.skill_ddpg.fast_update import FastUpdate
from sb3_hfo.skill_ddpg.legacy import translate_legacy_options
from sb3_hfo.skill_ddpg.policies import HFOPolicy

__all__ = [
    "DISCRETE_TARGETS",
    "PARAMETER_LOSSES",
    "TORCH_THREAD_VARIABLES",
    "TRAINING_THREADS",
    "SkillDDPG",
    "training_threads",
]

#: Values of ``SkillDDPG(discrete_target=...)``.
DISCRETE_TARGETS = ("actor", "max")
#: Values of ``SkillDDPG(parameter_loss=...)``.
PARAMETER_LOSSES = ("chosen", "each_action")

SelfSkillDDPG = TypeVar("SelfSkillDDPG", bound="SkillDDPG")

#: Options removed because no recommended config used them and no measurement supported them, with the value that
#: meant "off": models saved before carry it, and load drops it. Any other value is refused.
REMOVED_OPTIONS: dict[str, object] = {"mirror_fraction": 0.0}
#: The same for ``policy_kwargs`` (``n_critics=2``, TD3's clipped double Q, learned more slowly on E1).
REMOVED_POLICY_OPTIONS: dict[str, object] = {"n_critics": 1}

# Layout of the running sums of training statistics (one row of a tensor, summed over updates).
_STAT_CRITIC_LOSS, _STAT_ACTOR_LOSS, _STAT_MAX_Q, _STAT_MEAN_Q = 0, 1, 2, 3
_N_GLOBAL_STATS = 4
#: torch threads ``SkillDDPG.learn`` trains with unless the user has chosen a count: what ``python -m
#: sb3_hfo.train`` passes to rl-zoo3 (``--num-threads 1``, :func:`sb3_hfo.cli.zoo.default_algo_argv`).
TRAINING_THREADS = 1
#: Environment variables from which torch takes its thread count at start-up; one that is set is the user's choice.
TORCH_THREAD_VARIABLES = ("OMP_NUM_THREADS", "MKL_NUM_THREADS")
# torch's thread count when sb3_hfo was imported: a different count at learn() was set by the user.
_THREADS_AT_IMPORT = th.get_num_threads()


def training_threads() -> int | None:
    """The torch thread count ``SkillDDPG.learn`` switches to, or ``None`` to leave torch's count as it is.

    ``None`` when the user has chosen a count: ``OMP_NUM_THREADS`` or ``MKL_NUM_THREADS`` is set, or
    ``torch.get_num_threads()`` differs from its value when this module was imported (``torch.set_num_threads`` was
    called since; a count set before ``sb3_hfo`` was imported looks like torch's own). Else :data:`TRAINING_THREADS`.
    """
    if any(os.environ.get(variable) for variable in TORCH_THREAD_VARIABLES):
        return None
    if th.get_num_threads() != _THREADS_AT_IMPORT:
        return None
    return TRAINING_THREADS


def _is_real(value: object) -> bool:
    """A real number (Python or numpy; not a bool, which would pass as 0 / 1 by mistake)."""
    if isinstance(value, (bool, np.bool_)):
        return False
    return isinstance(value, (int, float, np.integer, np.floating))


def _check_unit_interval(name: str, value: object) -> None:
    """``ValueError`` naming ``name`` unless ``value`` is a number in [0, 1] (NaN is not)."""
    if not (_is_real(value) and 0.0 <= value <= 1.0):  # type: ignore[operator]
        raise ValueError(f"{name} must lie in [0, 1], got {value!r}")


def _check_int(name: str, value: object, minimum: int, meaning: str) -> None:
    """``ValueError`` naming ``name`` unless ``value`` is an integer >= ``minimum``."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum} {meaning}, got {value!r}")


class SkillDDPG(OffPolicyAlgorithm):
    """DDPG with skills (seed paper) for Box-action environments, HFO's flat hybrid action in particular.

    :param policy: ``"HFOPolicy"`` / ``"MlpPolicy"`` (the same class) or an :class:`HFOPolicy` subclass.
    :param env: environment or its registered id (``"HFO/EmptyGoal-v0"``).
    :param learning_rate_actor: Adam learning rate of every skill (paper: 1e-4); a float or an SB3 schedule of
        ``progress_remaining`` (1 -> 0).
    :param learning_rate_critic: Adam learning rate of the critic (paper: 1e-3, "decaying through out the training
        process": pass a schedule, e.g. ``lambda p: 1e-3 * p``).
    :param buffer_size: replay buffer capacity (transitions).
    :param learning_starts: environment steps of uniformly random actions before the first update.
    :param batch_size: minibatch size (paper: 32).
    :param tau: target-network tracking rate (paper: 1e-4).
    :param gamma: discount factor (not given by the paper; 0.99).
    :param train_freq: update every ``train_freq`` steps (paper: every frame).
    :param gradient_steps: updates per ``train_freq`` (paper: 1).
    :param action_noise: optional SB3 action noise, added in the buffer scale [-1, 1].
    :param exploration_initial_eps: epsilon-greedy probability at the start of ``learn``.
    :param exploration_final_eps: epsilon after annealing.
    :param exploration_fraction: fraction of ``total_timesteps`` over which epsilon anneals linearly (0: the final
        value from the start).
    :param exploration_keep_parameters: epsilon-greedy re-picks only the discrete action and keeps the policy's
        continuous parameters (``False``: the whole action is redrawn uniformly, as Hausknecht & Stone did).
    :param n_discrete_actions: number of leading action entries that are discrete-action preferences; ``None``:
        the policy's action layout's (HFO: 3), 0 without a layout. 0 disables epsilon-greedy.
    :param replay_buffer_class: SB3 replay buffer class (default ``ReplayBuffer``).
    :param replay_buffer_kwargs: its keyword arguments.
    :param optimize_memory_usage: SB3's memory-efficient replay buffer variant.
    :param n_steps: n-step returns (SB3's ``NStepReplayBuffer``) when > 1.
    :param mc_mixing: ``beta`` of the mixed critic target ``beta * G + (1 - beta) * y_TD`` (Hausknecht & Stone 2016,
        "On-Policy vs. Off-Policy Updates"; they used 0.2 on HFO), where ``G`` is the episode's actual discounted
        return from the sampled state (:class:`~sb3_hfo.common.buffers.MonteCarloReplayBuffer`, selected
        automatically). 0 (default) is the paper's pure TD target. Not combinable with ``n_steps > 1``.
    :param preactivation_penalty: ``lambda`` of an extra actor loss ``lambda * mean over rows of ||z||^2`` on the
        output layer's pre-``tanh`` values ``z`` (per skill, over its own rows). The critic's gradient can push
        ``z`` without bound towards an action bound, where ``tanh`` saturates and passes back no gradient
        (Hausknecht & Stone 2016's motivation for inverting gradients); the penalty holds ``z`` where ``tanh``
        still responds. 0: the paper.
    :param discrete_target: the next action in the critic's TD target: ``"actor"`` (the paper, DDPG) values the
        target actor's action as it is, ``Q'(s', mu'(s'))``; ``"max"`` (P-DQN's target, beyond the paper) the best
        discrete action at the target actor's parameters, ``max_k Q'(s', e_k, x'(s'))`` with ``e_k`` discrete
        action ``k``'s one-hot preferences. ``"max"``
        is the target of the policy the critic's choice (acting ``CriticChoice``) acts with; it needs a known discrete layout.
    :param parameter_loss: which continuous parameters the actor trains in a state: ``"chosen"`` (the paper, DDPG
        with the policy's ``mask_unused_parameters``) those of the discrete action its own preferences pick;
        ``"each_action"`` (P-DQN's loss, beyond the paper) every discrete action's, each by the critic's value of
        that action played with them. Why: with the critic's choice (acting ``CriticChoice``) the preferences do not
        pick what is played, so under ``"chosen"`` the parameters played are often ones the actor never trained in
        that state. Needs ``mask_unused_parameters``.
    :param fast_update: train with the hand-derived update (:mod:`sb3_hfo.skill_ddpg.fast_update`, the same
        maths as :meth:`_autograd_update`, about twice as fast) where it applies; ``False``: the autograd update.
    :param stats_window_size: episodes averaged in ``rollout/*`` statistics, the goal rate among them: SB3's
        ``rollout/success_rate`` from the env's ``info["is_success"]`` (HFO's GOAL status), the one name the
        training goal rate is logged under.
    :param tensorboard_log: TensorBoard log folder (``None``: no TensorBoard).
    :param policy_kwargs: :class:`HFOPolicy` arguments (``net_arch``, ``n_skills``, ``skill_router``,
        ``inverting_gradients``, ...).
    :param verbose: 0 silent, 1 info, 2 debug.
    :param seed: seed of every random generator (Python, numpy, torch, action space, env).
    :param device: torch device (``"auto"``: CUDA when available).
    :param _init_setup_model: build networks and buffer now (``False`` is used by ``load``).
    """

    policy_aliases: ClassVar[dict[str, type[BasePolicy]]] = {"HFOPolicy": HFOPolicy, "MlpPolicy": HFOPolicy}
    policy: HFOPolicy

    def __init__(
        self,
        policy: str | type[HFOPolicy],
        env: GymEnv | str,
        learning_rate_actor: float | Schedule = 1e-4,
        learning_rate_critic: float | Schedule = 1e-3,
        buffer_size: int = 1_000_000,
        learning_starts: int = 100,
        batch_size: int = 32,
        tau: float = 1e-4,
        gamma: float = 0.99,
        train_freq: int | tuple[int, str] = 1,
        gradient_steps: int = 1,
        action_noise: ActionNoise | None = None,
        exploration_initial_eps: float = 1.0,
        exploration_final_eps: float = 0.1,
        exploration_fraction: float = 0.1,
        exploration_keep_parameters: bool = False,
        n_discrete_actions: int | None = None,
        replay_buffer_class: type[ReplayBuffer] | None = None,
        replay_buffer_kwargs: dict[str, Any] | None = None,
        optimize_memory_usage: bool = False,
        n_steps: int = 1,
        mc_mixing: float = 0.0,
        preactivation_penalty: float = 0.0,
        discrete_target: str = "actor",
        parameter_loss: str = "chosen",
        fast_update: bool = True,
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
            learning_rate_actor,
            buffer_size,
            learning_starts,
            batch_size,
            tau,
            gamma,
            train_freq,
            gradient_steps,
            action_noise=action_noise,
            replay_buffer_class=replay_buffer_class,
            replay_buffer_kwargs=replay_buffer_kwargs,
            optimize_memory_usage=optimize_memory_usage,
            n_steps=n_steps,
            policy_kwargs=None
            if policy_kwargs is None
            else translate_legacy_options(policy_kwargs, warn=True),
            stats_window_size=stats_window_size,
            tensorboard_log=tensorboard_log,
            verbose=verbose,
            device=device,
            seed=seed,
            sde_support=False,
            supported_action_spaces=(spaces.Box,),
            support_multi_env=True,
        )
        self.learning_rate_actor = learning_rate_actor
        self.learning_rate_critic = learning_rate_critic
        self.exploration_initial_eps = exploration_initial_eps
        self.exploration_final_eps = exploration_final_eps
        self.exploration_fraction = exploration_fraction
        self.exploration_keep_parameters = exploration_keep_parameters
        self.n_discrete_actions = n_discrete_actions
        self.exploration_rate = exploration_initial_eps
        self.mc_mixing = mc_mixing
        self.preactivation_penalty = preactivation_penalty
        self.discrete_target = discrete_target
        self.parameter_loss = parameter_loss
        # SB3's load builds the model with _init_setup_model=False, then sets the saved attributes.
        self._loading = not _init_setup_model
        self.fast_update = fast_update
        if _init_setup_model:
            self._setup_model()

    # ------------------------------------------------------------------------------------------------------
    # Set-up

    def _check_arguments(self) -> None:
        """Reject bad or inconsistent arguments (NaN included) with a ``ValueError`` naming the argument."""
        for name in ("exploration_initial_eps", "exploration_final_eps", "exploration_fraction"):
            _check_unit_interval(name, getattr(self, name))
        _check_unit_interval("tau", self.tau)
        _check_unit_interval("gamma", self.gamma)
        _check_int("batch_size", self.batch_size, 1, "(transitions per minibatch)")
        _check_int("buffer_size", self.buffer_size, 1, "(transitions the replay buffer holds)")
        _check_int(
            "learning_starts", self.learning_starts, 0, "(random-action steps before the first update)"
        )
        for name in ("learning_rate_actor", "learning_rate_critic"):
            value = getattr(self, name)
            if not callable(value) and not (_is_real(value) and 0 <= value < math.inf):
                raise ValueError(
                    f"{name} must be a finite float >= 0 or a schedule (callable), got {value!r}"
                )
        if not (_is_real(self.preactivation_penalty) and 0 <= self.preactivation_penalty < math.inf):
            raise ValueError(
                f"preactivation_penalty must be a finite number >= 0, got {self.preactivation_penalty!r}"
            )
        _check_unit_interval("mc_mixing", self.mc_mixing)
        if self.discrete_target not in DISCRETE_TARGETS:
            raise ValueError(
                f"discrete_target must be one of {DISCRETE_TARGETS}, got {self.discrete_target!r}"
            )
        if self.parameter_loss not in PARAMETER_LOSSES:
            raise ValueError(f"parameter_loss must be one of {PARAMETER_LOSSES}, got {self.parameter_loss!r}")

    def _select_replay_buffer(self) -> None:
        """``mc_mixing > 0`` needs the episode returns that only :class:`MonteCarloReplayBuffer` keeps."""
        if self.mc_mixing > 0:
            if self.n_steps > 1:
                raise ValueError(
                    "mc_mixing > 0 cannot be combined with n_steps > 1: choose one kind of return"
                )
            if self.replay_buffer_class is None:
                self.replay_buffer_class = MonteCarloReplayBuffer
                self.replay_buffer_kwargs = {"gamma": self.gamma, **self.replay_buffer_kwargs}
            elif not issubclass(self.replay_buffer_class, MonteCarloReplayBuffer):
                raise ValueError(
                    f"mc_mixing > 0 needs a MonteCarloReplayBuffer, got replay_buffer_class="
                    f"{self.replay_buffer_class.__name__}"
                )

    def _resolve_n_discrete_actions(self) -> int:
        action_dim = int(np.prod(self.action_space.shape))
        if self.n_discrete_actions is None:
            return self.policy.n_discrete_actions
        n_discrete = self.n_discrete_actions
        if isinstance(n_discrete, bool) or not isinstance(n_discrete, (int, np.integer)):
            raise ValueError(f"n_discrete_actions must be None or an int, got {n_discrete!r}")
        if not 0 <= n_discrete <= action_dim:
            raise ValueError(
                f"n_discrete_actions must lie in [0, action dim = {action_dim}], got {n_discrete}"
            )
        return int(n_discrete)

    def _setup_lr_schedule(self) -> None:
        # ``self.learning_rate`` is the actor's rate (what BaseAlgorithm received); the critic has its own.
        self.lr_schedule = FloatSchedule(self.learning_rate_actor)
        self.lr_schedule_critic = FloatSchedule(self.learning_rate_critic)

    def _drop_removed_options(self) -> None:
        """Drop the :data:`REMOVED_OPTIONS` (and :data:`REMOVED_POLICY_OPTIONS`) a saved model carries at their "off"
        value; ``ValueError`` naming the option for any other value (the model would not train as it was saved)."""
        policy_kwargs = dict(self.policy_kwargs)
        for saved, removed in ((self.__dict__, REMOVED_OPTIONS), (policy_kwargs, REMOVED_POLICY_OPTIONS)):
            for name, off in removed.items():
                value = saved.pop(name, off)
                if value != off:
                    raise ValueError(f"{name}={value!r}: the option was removed (only {name}={off!r} loads)")
        self.policy_kwargs = policy_kwargs

    def _adopt_hfo_layout_of_a_legacy_model(self) -> None:
        """A model saved before the action layout contract (hfo2d.action_layout) holds HFO's flat action space as a
        plain ``Box(0, 1, (8,))``: on load it gets its layout back, so that it acts and trains as it was saved."""
        if self._loading and action_layout(self.action_space) is None:
            hfo_space = hfo_flat_action_space()
            if isinstance(self.action_space, spaces.Box) and self.action_space == hfo_space:
                self.action_space = hfo_space

    def _setup_model(self) -> None:
        self._adopt_hfo_layout_of_a_legacy_model()
        self._drop_removed_options()
        # a saved model's single acting / encoding options (a user's were translated, with a warning, in __init__)
        self.policy_kwargs = translate_legacy_options(self.policy_kwargs, warn=False)
        self._check_arguments()
        self._select_replay_buffer()
        super()._setup_model()
        if not isinstance(self.policy, HFOPolicy):
            raise ValueError(f"SkillDDPG needs an HFOPolicy (or subclass), got {type(self.policy).__name__}")
        update_learning_rate(self.policy.critic_optimizer, self.lr_schedule_critic(1.0))
        self._n_discrete = self._resolve_n_discrete_actions()
        if self.discrete_target == "max" and self.policy.n_discrete_actions == 0:
            raise ValueError(
                "discrete_target='max' needs the discrete actions: an action space with a hybrid layout (the HFO "
                "envs'), or the policy's mask_unused_parameters given as per-action parameter counts"
            )
        if self.parameter_loss == "each_action" and self.policy.parameter_masks is None:
            raise ValueError(
                "parameter_loss='each_action' needs the policy's mask_unused_parameters: each discrete action's "
                "parameters are valued with the others' set to 0"
            )
        if self.exploration_fraction > 0:
            self.exploration_schedule: Schedule = LinearSchedule(
                self.exploration_initial_eps, self.exploration_final_eps, self.exploration_fraction
            )
        else:
            self.exploration_schedule = ConstantSchedule(self.exploration_final_eps)
        self._create_aliases()
        self._reset_stats()

    def _create_aliases(self) -> None:
        self.actor = self.policy.actor
        self.actor_target = self.policy.actor_target
        self.critic = self.policy.critic
        self.critic_target = self.policy.critic_target
        # Fixed parameter lists: module.to(device) and load_state_dict keep the same Parameter objects.
        self._online_params = [*self.actor.parameters(), *self.critic.parameters()]
        self._target_params = [*self.actor_target.parameters(), *self.critic_target.parameters()]
        self._skill_params = [self.policy.skill_parameters(k) for k in range(self.policy.n_skills)]
        self._skill_optimizers = self.policy.actor_optimizers
        self._fast_update = (
            FastUpdate(self) if self.fast_update and FastUpdate.applies_to(self.policy) else None
        )

    def _reset_stats(self) -> None:
        """Clear the training and rollout statistics gathered since the last log dump."""
        n_skills = self.policy.n_skills
        self._stat_sums = th.zeros(_N_GLOBAL_STATS + n_skills, device=self.device)
        # (1, 1) views of each global statistic and the (n_skills, 1) view of the skills' losses, for addmm_.
        column = self._stat_sums.view(-1, 1)
        self._stat_views = (
            column[_STAT_CRITIC_LOSS : _STAT_CRITIC_LOSS + 1],
            column[_STAT_ACTOR_LOSS : _STAT_ACTOR_LOSS + 1],
            column[_STAT_MAX_Q : _STAT_MAX_Q + 1],
            column[_STAT_MEAN_Q : _STAT_MEAN_Q + 1],
            column[_N_GLOBAL_STATS:],
        )
        self._stat_updates = 0
        self._skill_updates = [0] * n_skills
        self._skill_steps = np.zeros(n_skills, dtype=np.int64)

    # ------------------------------------------------------------------------------------------------------
    # Training

    def train(self, gradient_steps: int, batch_size: int = 32) -> None:
        """Do ``gradient_steps`` updates on minibatches of ``batch_size`` sampled from the replay buffer."""
        self.policy.set_training_mode(True)
        lr_actor = self.lr_schedule(self._current_progress_remaining)
        lr_critic = self.lr_schedule_critic(self._current_progress_remaining)
        for optimizer in self.policy.actor_optimizers:
            update_learning_rate(optimizer, lr_actor)
        update_learning_rate(self.policy.critic_optimizer, lr_critic)
        self.logger.record("train/learning_rate_actor", lr_actor)
        self.logger.record("train/learning_rate_critic", lr_critic)
        assert self.replay_buffer is not None
        for _ in range(gradient_steps):
            self._n_updates += 1
            batch = self.replay_buffer.sample(batch_size, env=self._vec_normalize_env)
            self._update(batch)
        self.logger.record("train/n_updates", self._n_updates, exclude="tensorboard")

    def _update(self, batch: ReplayBufferSamples) -> None:
        """One update on ``batch``: the fast update where it applies, else :meth:`_autograd_update` (same maths)."""
        if self._fast_update is not None:
            self._fast_update.update(batch)
        else:
            self._autograd_update(batch)

    def _autograd_update(self, batch: ReplayBufferSamples) -> None:
        """One critic, actor and target update, written with autograd: what SkillDDPG computes (module docstring).

        ``batch``: observations ``(B, obs_dim)``, actions ``(B, A)`` in [-1, 1], rewards / dones ``(B, 1)``.
        """
        policy, actor, critic = self.policy, self.actor, self.critic
        obs = batch.observations

        # 1. Critic (eq. 5, 6): regress Q(s, a) on the TD target.
        with th.no_grad():
            target_q = self._critic_target(batch)
        current_q = critic(obs, policy.critic_action(batch.actions))
        critic_loss = F.mse_loss(current_q, target_q)
        policy.critic_optimizer.zero_grad()
        critic_loss.backward()
        policy.critic_optimizer.step()

        # 2. Actor (eq. 7), against the updated critic: skill k's loss is -mean over its rows of the value
        # (plus the pre-activation penalty), its gradient taken over trunk + head k; all skills' gradients at
        # the same parameters, then each skill's Adam steps.
        skills = policy.route(obs)
        if skills is None:
            skills = th.zeros(obs.shape[0], dtype=th.long, device=obs.device)
        preactivations = actor.head_outputs(obs, skills)
        actions = th.tanh(preactivations) if actor.squash else preactivations
        value, actor_q = self._actor_value(obs, actions)
        row_loss = self.preactivation_penalty * preactivations.square().sum(dim=1, keepdim=True) - value
        gradients = {}
        for k in range(policy.n_skills):
            rows = skills == k
            if rows.any():
                gradients[k] = th.autograd.grad(
                    row_loss[rows].mean(), self._skill_params[k], retain_graph=True
                )
        for k, skill_gradients in gradients.items():
            for param, gradient in zip(self._skill_params[k], skill_gradients, strict=True):
                param.grad = gradient
            self._skill_optimizers[k].step()
            self._skill_optimizers[k].zero_grad()
            self._skill_updates[k] += 1

        # 3. Target networks.
        with th.no_grad():
            polyak_update(self._online_params, self._target_params, self.tau)
            critic_loss_sum, actor_loss, max_q, mean_q, skill_losses = self._stat_views
            critic_loss_sum += critic_loss
            actor_loss -= actor_q.mean()
            max_q += current_q.max()
            mean_q += current_q.mean()
            for k in gradients:
                skill_losses[k] -= actor_q[skills == k].mean()
            self._stat_updates += 1

    def _actor_value(self, obs: th.Tensor, actions: th.Tensor) -> tuple[th.Tensor, th.Tensor]:
        """What the actor ascends, per row ``(B, 1)``, and the critic's value of ``actions`` (detached).

        ``parameter_loss="chosen"``: ``Q(s, mu(s))``. ``"each_action"``: ``Q`` of the actor's preferences with
        its parameters held, plus ``Q(s, e_k, x_k(s))`` for every discrete action ``k`` (KICK's left out where the
        ball is out of reach with the acting ``KickMask``). With inverting gradients, a surrogate whose
        gradient is the rescaled ``dQ/da`` pushed through the actor.
        """
        policy, critic = self.policy, self.critic
        actor_q = critic(obs, policy.critic_action(actions))
        value = actor_q
        if self.parameter_loss == "each_action":
            n_discrete = policy.n_discrete_actions
            held = th.cat((actions[:, :n_discrete], actions[:, n_discrete:].detach()), dim=1)
            value = critic(obs, policy.critic_action(held))
            no_kick = policy.kick_unavailable(obs)
            rows, own_masks = policy.discrete_action_rows, policy.own_parameter_masks
            assert rows is not None and own_masks is not None
            for k in range(n_discrete):
                value_k = critic(obs, rows[k] + actions * own_masks[k])
                if no_kick is not None and k == policy.action_layout.ball_action:  # type: ignore[union-attr]
                    value_k = value_k.masked_fill(no_kick.unsqueeze(1), 0.0)
                value = value + value_k
        if policy.inverting_gradients:
            (dq_da,) = th.autograd.grad(value.sum(), actions, retain_graph=True)
            inverted = self._invert_gradients(dq_da, actions.detach())
            value = (inverted * actions).sum(dim=1, keepdim=True)
        return value, actor_q.detach()

    def _critic_target(self, batch: ReplayBufferSamples) -> th.Tensor:
        """``y (B, 1) = r + gamma^n (1 - done) Q'(s', mu'(s'))`` (eq. 6; ``Q'`` of the best discrete action at the
        target actor's parameters with ``discrete_target="max"``), mixed as ``y + beta (G - y)`` with the
        episode's return ``G`` where it is known, when ``mc_mixing = beta > 0``."""
        policy = self.policy
        next_obs = batch.next_observations
        next_actions = self.actor_target(next_obs, policy.route(next_obs))
        if policy.inverting_gradients:
            next_actions = next_actions.clamp(-1.0, 1.0)
        if self.discrete_target == "max":
            _, next_values = policy.discrete_values(next_obs, next_actions, self.critic_target)
            next_q = next_values.max(dim=1, keepdim=True).values
        else:
            next_q = self.critic_target(next_obs, policy.critic_action(next_actions))
        discounts = self.gamma if batch.discounts is None else batch.discounts
        target_q = batch.rewards + (1 - batch.dones) * discounts * next_q
        if self.mc_mixing > 0:
            mixed: MonteCarloReplayBufferSamples = batch  # type: ignore[assignment]
            target_q = target_q + self.mc_mixing * mixed.mc_valid * (mixed.mc_returns - target_q)
        return target_q

    @staticmethod
    def _invert_gradients(dq_da: th.Tensor, actions: th.Tensor) -> th.Tensor:
        """Hausknecht & Stone's inverting gradients for parameters bounded in [p_min, p_max] = [-1, 1].

        ``dq_da, actions``: ``(B, A)``. Where the gradient asks to increase ``a`` (``dq_da > 0``) it is scaled by
        ``(p_max - a) / (p_max - p_min)``, otherwise by ``(a - p_min) / (p_max - p_min)``; outside the bounds the
        factor turns negative and pushes the action back.
        """
        scale = th.where(dq_da > 0, (1.0 - actions) * 0.5, (actions + 1.0) * 0.5)
        return dq_da * scale

    # ------------------------------------------------------------------------------------------------------
    # Acting

    def _sample_action(
        self, learning_starts: int, action_noise: ActionNoise | None = None, n_envs: int = 1
    ) -> tuple[np.ndarray, np.ndarray]:
        """SB3's warm-up / policy action with optional noise, then epsilon-greedy over the discrete actions.

        :return: (action for ``env.step`` in the env's bounds, action in [-1, 1] for the buffer), each ``(n_envs, A)``.
        """
        if self.policy.n_skills > 1 and self._last_obs is not None:
            # Counted for the rollout statistics only: routed in numpy (~5 us) rather than through a tensor (~30 us).
            obs = np.asarray(self._last_obs, dtype=np.float32).reshape(n_envs, -1)
            skills = self.policy.numpy_route(obs)
            self._skill_steps += np.bincount(skills, minlength=self.policy.n_skills)
        else:
            self._skill_steps[0] += n_envs
        # The mirror choice is for evaluation: rollouts act with the plain greedy action (playing it while training measured no gain).
        with self.policy.mirror_choice_suspended():
            action, buffer_action = super()._sample_action(learning_starts, action_noise, n_envs)
        if self._n_discrete == 0 or self.num_timesteps < learning_starts or self.exploration_rate <= 0.0:
            return action, buffer_action
        explore = np.random.random_sample(n_envs) < self.exploration_rate
        if not explore.any():
            return action, buffer_action
        n_explore = int(explore.sum())
        buffer_action = np.array(buffer_action, dtype=np.float32, copy=True)
        if self.exploration_keep_parameters:
            random_actions = buffer_action[explore]
            random_actions.reshape(n_explore, -1)[:, : self._n_discrete] = -1.0
        else:
            random_actions = np.random.uniform(-1.0, 1.0, size=(n_explore, *buffer_action.shape[1:]))
        flat = random_actions.reshape(n_explore, -1)
        flat[np.arange(n_explore), np.random.randint(self._n_discrete, size=n_explore)] = 1.0
        buffer_action[explore] = random_actions
        return self.policy.unscale_action(buffer_action), buffer_action

    def _on_step(self) -> None:
        self.exploration_rate = self.exploration_schedule(self._current_progress_remaining)

    # ------------------------------------------------------------------------------------------------------
    # Logging

    def dump_logs(self) -> None:
        """Record the statistics gathered since the last dump (training means, rollout fractions), then dump."""
        self._record_stats()
        super().dump_logs()

    def _record_stats(self) -> None:
        n_skills = self.policy.n_skills
        if self._stat_updates > 0:
            sums = self._stat_sums.cpu().tolist()
            n = self._stat_updates
            self.logger.record("train/critic_loss", sums[_STAT_CRITIC_LOSS] / n)
            self.logger.record("train/actor_loss", sums[_STAT_ACTOR_LOSS] / n)
            self.logger.record("train/max_q", sums[_STAT_MAX_Q] / n)
            self.logger.record("train/mean_q", sums[_STAT_MEAN_Q] / n)
            for k in range(n_skills):
                if self._skill_updates[k] > 0:
                    self.logger.record(
                        f"train/actor_loss_skill_{k}", sums[_N_GLOBAL_STATS + k] / self._skill_updates[k]
                    )
        total_steps = int(self._skill_steps.sum())
        if total_steps > 0:
            for k in range(n_skills):
                self.logger.record(f"rollout/skill_{k}_fraction", float(self._skill_steps[k]) / total_steps)
        self.logger.record("rollout/epsilon", self.exploration_rate if self._n_discrete > 0 else 0.0)
        self._reset_stats()

    # ------------------------------------------------------------------------------------------------------
    # SB3 plumbing

    def save(
        self,
        path: str | pathlib.Path | io.BufferedIOBase,
        exclude: Iterable[str] | None = None,
        include: Iterable[str] | None = None,
    ) -> None:
        """SB3's ``save``, with the policy's current acting strategies (``model.policy.acting``, which may have
        been switched after construction) written into ``policy_kwargs`` as their text form, which is what
        ``load`` rebuilds the policy from."""
        self.policy_kwargs = {**self.policy_kwargs, "acting": format_acting(self.policy.acting)}
        super().save(path, exclude=exclude, include=include)

    def load_replay_buffer(
        self, path: str | pathlib.Path | io.BufferedIOBase, truncate_last_traj: bool = True
    ) -> None:
        """SB3's ``load_replay_buffer``, refusing a buffer this model cannot train from, with a ``ValueError``
        (the model keeps its previous buffer): one that is not an instance of the model's ``replay_buffer_class``
        (with ``mc_mixing > 0``: a :class:`~sb3_hfo.common.buffers.MonteCarloReplayBuffer`, whose episode returns
        the target mixes in), a Monte Carlo buffer whose returns were discounted by another ``gamma``, or one whose
        observation or action shape, or number of environments, differs from the model's."""
        previous = self.replay_buffer
        super().load_replay_buffer(path, truncate_last_traj)
        problem = self._replay_buffer_problem(self.replay_buffer)
        if problem is not None:
            self.replay_buffer = previous
            raise ValueError(f"load_replay_buffer({path!r}): {problem}")

    def _replay_buffer_problem(self, buffer: Any) -> str | None:
        """Why ``buffer`` cannot be this model's replay buffer, or ``None``."""
        name = type(buffer).__name__
        if self.mc_mixing > 0 and not isinstance(buffer, MonteCarloReplayBuffer):
            return (
                f"mc_mixing={self.mc_mixing} needs a MonteCarloReplayBuffer (the episode returns its targets mix "
                f"in), got a {name}"
            )
        expected = self.replay_buffer_class
        if expected is not None and not isinstance(buffer, expected):
            return f"the model's replay_buffer_class is {expected.__name__}, got a {name}"
        if self.mc_mixing > 0 and not math.isclose(buffer.gamma, self.gamma):
            return (
                f"the buffer's returns were discounted with gamma={buffer.gamma}, the model's is {self.gamma}"
            )
        obs_shape, model_obs_shape = tuple(buffer.obs_shape), tuple(self.observation_space.shape)
        if obs_shape != model_obs_shape:
            return f"the buffer holds observations of shape {obs_shape}, the model's have shape {model_obs_shape}"
        action_dim = int(np.prod(self.action_space.shape))
        if buffer.action_dim != action_dim:
            return f"the buffer holds {buffer.action_dim}-entry actions, the model's have {action_dim}"
        if buffer.n_envs != self.n_envs:
            return f"the buffer was filled by {buffer.n_envs} env(s), the model has n_envs={self.n_envs}"
        return None

    def learn(
        self: SelfSkillDDPG,
        total_timesteps: int,
        callback: MaybeCallback = None,
        log_interval: int = 4,
        tb_log_name: str = "SkillDDPG",
        reset_num_timesteps: bool = True,
        progress_bar: bool = False,
    ) -> SelfSkillDDPG:
        """SB3's ``learn``, with torch's thread count chosen as ``python -m sb3_hfo.train`` chooses it.

        Unless the user has chosen a thread count, ``learn`` runs with :data:`TRAINING_THREADS` (1) torch threads,
        what the CLI sets (``--num-threads 1``), and restores the previous count when it returns. SkillDDPG's
        networks are small: torch's default of one thread per core only makes the threads contend with each
        other and with the environment (``benchmarks/python_vs_cli.py``). The user has chosen when
        ``OMP_NUM_THREADS`` or ``MKL_NUM_THREADS`` is set (torch takes its count from them), or when
        ``torch.get_num_threads()`` differs from its value when ``sb3_hfo`` was imported (``torch.set_num_threads``
        was called since): then the count is left as it is. See :func:`training_threads`.
        """
        threads = training_threads()
        previous = th.get_num_threads()
        if threads is not None and threads != previous:
            th.set_num_threads(threads)
        try:
            return super().learn(
                total_timesteps=total_timesteps,
                callback=callback,
                log_interval=log_interval,
                tb_log_name=tb_log_name,
                reset_num_timesteps=reset_num_timesteps,
                progress_bar=progress_bar,
            )
        finally:
            # Restored unless something (a callback) chose another count during learn.
            if threads is not None and th.get_num_threads() == threads:
                th.set_num_threads(previous)

    def _excluded_save_params(self) -> list[str]:
        return [
            *super()._excluded_save_params(),
            "actor",
            "critic",
            "actor_target",
            "critic_target",
            "_online_params",
            "_target_params",
            "_skill_params",
            "_skill_optimizers",
            "_stat_sums",
            "_stat_views",
            "_fast_update",
            "_loading",
        ]

    def _get_torch_save_params(self) -> tuple[list[str], list[str]]:
        # Every optimiser is saved: the critic's and one per skill (named attributes of the policy).
        skill_optimizers = [f"policy.actor_skill_{k}_optimizer" for k in range(self.policy.n_skills)]
        return ["policy", "policy.critic_optimizer", *skill_optimizers], []
