"""SkillDDPG: DDPG with hand-routed skills (seed paper, "Method"), as a Stable-Baselines3 off-policy algorithm.

One update (``train`` does ``gradient_steps`` of them, each on a minibatch of ``batch_size``):

1. Critic: ``y = r + gamma * (1 - done) * Q'(s', mu'_{skill(s')}(s'))`` with the target networks (paper eq. 6),
   ``L = mean((Q(s, a) - y)^2)`` (eq. 5), one Adam step (``policy.critic_optimizer``).
   With ``discrete_target="max"`` (P-DQN, beyond the paper) ``Q'(s', ...)`` is the best of the discrete actions
   at the target actor's parameters, the value of the policy that ``discrete_choice="critic"`` acts with.
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
   ``kick_only_when_kickable`` leaves it out); one extra critic pass over ``n_discrete * B`` rows.
3. Target networks: ``theta' <- theta' + tau * (theta - theta')`` (one ``torch._foreach_lerp_`` call).

Speed (same maths as SB3's DDPG, measured in benchmarks/update_throughput.py on a quiet 2-core VM: 2.1-2.2x
SB3's ``DDPG`` updates per second with 1 skill, 1.8x with 2, at 1 and 2 threads; see benchmarks/README.md): the update is back-propagated by hand under ``torch.no_grad()`` instead of
through autograd (``HFOActor.forward_for_backward`` / ``output_gradients``,
``HFOCritic.forward_for_backward`` / ``output_gradients`` / ``action_gradient``: ``F.linear`` forward passes that
keep each layer's input, then ``dZ @ W`` input gradients with activation derivatives from the kept outputs,
``dZ.T @ input`` weight gradients and row sums of ``dZ`` as bias gradients). That removes the graph building, the
autograd engine and ``nn.Module.__call__`` from the hot path, and computes only what is needed: no input gradient
for the first layer, no critic weight gradient in the actor step, and at the critic's action layer only the
``(B, action_dim)`` action gradient. Skills: one router call for the states and next states, rows sorted by
skill, one backward pass gives every layer's ``dZ`` for all rows, and each skill's weight gradients are the
products over its own rows (the FLOPs of one backward pass), formed right before that skill's Adam step (they need
no parameter) in buffers reused by every skill and update. All bias gradients of a network come from one product
``indicator @ [dZ_1 | ... | dZ_n]``. Adam is torch's fused kernel called directly (``adam_step``, state lists
gathered once, step counters advanced by one ``add_``), the targets move in one ``torch._foreach_lerp_``,
statistics are summed in place by small products (no per-update ``.item()`` or ``.mean()``) and
``set_training_mode`` writes the flags without ``nn.Module.train``'s recursion. What remains is mostly matrix
products (~1.9 M multiply-adds per sample and update at 400-300-200), the Adam steps (one per optimiser: with 2
skills two of them over the trunk, each streaming its own moments) and the target update.

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
from collections.abc import Iterable, Sequence
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
    update_learning_rate,
)

from hfo2d.action_layout import action_layout, hfo_flat_action_space
from sb3_hfo.common.buffers import MonteCarloReplayBuffer, MonteCarloReplayBufferSamples
from sb3_hfo.skill_ddpg.policies import HFOPolicy, Segment

__all__ = [
    "DISCRETE_TARGETS",
    "PARAMETER_LOSSES",
    "TORCH_THREAD_VARIABLES",
    "TRAINING_THREADS",
    "SkillDDPG",
    "adam_step",
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
# Bound on SkillDDPG's cache of minibatch layouts (one per split of the batch between skills).
_MAX_CACHED_LAYOUTS = 4096
# (segments, row_weight, skill_weight, mean_weight): see SkillDDPG._skill_layout.
_Layout = tuple[list[Segment], th.Tensor | float, th.Tensor, th.Tensor, th.Tensor]

# torch's fused Adam kernel (an ATen op, present since torch 2.0); used directly by adam_step.
_HAS_FUSED_ADAM = hasattr(th, "_fused_adam_")


class _FusedAdamState:
    """What :func:`adam_step`'s direct path needs of one optimiser's state for one parameter list, gathered once.

    The step counters of the parameters are rebound to views of one 1-D tensor (same values, dtype and device), so
    that one ``add_`` advances them all: ``torch._foreach_add_`` over 0-dim CPU tensors falls back to one ``add_``
    per tensor (~18 us for 8 of them). ``Adam.step``, ``state_dict`` and saving see ordinary 0-dim step tensors.
    Valid while ``optimizer.state`` is the same object (``load_state_dict`` replaces it) and holds these tensors.
    """

    __slots__ = ("exp_avg_sqs", "exp_avgs", "ones", "params", "state", "step_views", "steps")

    def __init__(self, optimizer: th.optim.Optimizer, params: list[th.Tensor]) -> None:
        states = optimizer.state
        param_states = [states[param] for param in params]
        self.state = states
        self.params = params
        self.steps = th.stack([state["step"] for state in param_states])
        self.step_views = list(self.steps.unbind())
        # Adding a tensor of ones: ``add_(1)`` would convert the wrapped Python scalar on every call.
        self.ones = th.ones_like(self.steps)
        for state, view in zip(param_states, self.step_views, strict=True):
            state["step"] = view
        self.exp_avgs = [state["exp_avg"] for state in param_states]
        self.exp_avg_sqs = [state["exp_avg_sq"] for state in param_states]

    def valid_for(self, optimizer: th.optim.Optimizer, params: list[th.Tensor]) -> bool:
        return self.state is optimizer.state and self.params is params


class _GradientBuffers:
    """Gradient tensors reused from one update to the next for parameters laid out ``[W_1, b_1, ..., W_n, b_n]``.

    One set of weight-gradient tensors, and the bias gradients of up to ``n_rows`` gradients (one per skill with
    rows) as rows of one ``(n_rows, sum of bias sizes)`` tensor, so that all of them come from one product
    ``indicator @ [dZ_1 | ... | dZ_n]`` (row ``j`` of ``indicator`` selects gradient ``j``'s minibatch rows)
    instead of one ``sum`` per layer and skill. ``grads[j]`` is the parameter-ordered list handed to the
    optimiser for gradient ``j``: the shared weight tensors and row ``j``'s bias views.
    """

    def __init__(self, params: list[th.Tensor], n_rows: int) -> None:
        self.weights = [th.empty_like(weight) for weight in params[0::2]]
        sizes = [bias.numel() for bias in params[1::2]]
        self.biases = params[1].new_empty(n_rows, sum(sizes))
        self.first_rows = [self.biases[:n] for n in range(1, n_rows + 1)]
        self.grads: list[list[th.Tensor]] = []
        for row in self.biases:
            views = row.split(sizes)
            self.grads.append([tensor for pair in zip(self.weights, views, strict=True) for tensor in pair])

    def bias_gradients(self, indicator: th.Tensor, grad_zs: list[th.Tensor]) -> None:
        """Row ``j`` of the bias gradients: the sums of every ``dZ`` over the rows that ``indicator[j]`` selects."""
        th.mm(indicator, th.cat(grad_zs, dim=1), out=self.first_rows[indicator.shape[0] - 1])

    def weight_gradients(self, parts: Sequence[tuple[th.Tensor, th.Tensor]]) -> None:
        """``dZ.T @ input`` of every layer, for ``parts`` = ``(dZ.T, input)`` of each layer (rows of one gradient)."""
        for (grad_z_t, layer_input), out in zip(parts, self.weights, strict=True):
            th.mm(grad_z_t, layer_input, out=out)


def adam_step(optimizer: th.optim.Optimizer, params: list[th.Tensor], grads: Sequence[th.Tensor]) -> None:
    """One step of ``optimizer`` on ``params`` with gradients ``grads`` (same order as the optimizer's params).

    For a fused ``torch.optim.Adam`` with one parameter group, no hooks and plain settings, whose state exists (after
    its first step), this calls the fused kernel directly: exactly what ``Adam.step`` would run, without its ~0.15 ms
    of Python bookkeeping per call. The optimizer's state tensors are updated in place, so ``state_dict`` / save /
    load are unaffected. The state lists are gathered once per (optimizer state, ``params`` list object): pass the
    same list object on every call. Any other case goes through ``optimizer.step()``.
    """
    groups = optimizer.param_groups
    group = groups[0]
    fast = (
        _HAS_FUSED_ADAM
        and type(optimizer) is th.optim.Adam
        and len(groups) == 1
        and group.get("fused")
        and not (group["amsgrad"] or group["maximize"] or group.get("decoupled_weight_decay"))
        and not (optimizer._optimizer_step_pre_hooks or optimizer._optimizer_step_post_hooks)
    )
    if fast:
        cached: _FusedAdamState | None = optimizer.__dict__.get("_sb3_hfo_fused_adam")
        if cached is None or not cached.valid_for(optimizer, params):
            states = optimizer.state
            cached = None
            if all(param in states for param in params):
                cached = _FusedAdamState(optimizer, params)
                optimizer.__dict__["_sb3_hfo_fused_adam"] = cached
        if cached is not None:
            beta1, beta2 = group["betas"]
            cached.steps.add_(cached.ones)
            th._fused_adam_(
                params,
                grads if isinstance(grads, list) else list(grads),
                cached.exp_avgs,
                cached.exp_avg_sqs,
                [],
                cached.step_views,
                amsgrad=False,
                lr=group["lr"],
                beta1=beta1,
                beta2=beta2,
                weight_decay=group["weight_decay"],
                eps=group["eps"],
                maximize=False,
            )
            return
    for param, grad in zip(params, grads, strict=True):
        param.grad = grad
    optimizer.step()
    for param in params:
        param.grad = None


#: torch threads ``SkillDDPG.learn`` trains with unless the user has chosen a count: what ``python -m
#: sb3_hfo.train`` passes to rl-zoo3 (``--num-threads 1``, :func:`sb3_hfo.zoo.default_algo_argv`).
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
        is the target of the policy ``discrete_choice="critic"`` acts with; it needs a known discrete layout.
    :param parameter_loss: which continuous parameters the actor trains in a state: ``"chosen"`` (the paper, DDPG
        with the policy's ``mask_unused_parameters``) those of the discrete action its own preferences pick;
        ``"each_action"`` (P-DQN's loss, beyond the paper) every discrete action's, each by the critic's value of
        that action played with them. With the policy's ``discrete_choice="critic"`` the preferences never pick
        what is played, so under ``"chosen"`` the parameters played were ones the actor had not trained in that state
        in 31-51 % of the greedy steps of three committed agents (research/RESULTS.md, session 12). Needs
        ``mask_unused_parameters``.
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
            policy_kwargs=policy_kwargs,
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
        self._critic_params = list(self.critic.parameters())
        self._online_params = [*self.actor.parameters(), *self._critic_params]
        self._target_params = [*self.actor_target.parameters(), *self.critic_target.parameters()]
        self._skill_params = [self.policy.skill_parameters(k) for k in range(self.policy.n_skills)]
        self._skill_optimizers = self.policy.actor_optimizers
        self._layouts: dict[tuple[Any, ...], _Layout] = {}
        # Every skill's gradients are written into the same tensors in turn (all skills' shapes are the same).
        self._actor_grads = _GradientBuffers(self._skill_params[0], self.policy.n_skills)
        self._critic_grads = _GradientBuffers(self._critic_params, 1)

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

    @th.no_grad()
    def _update(self, batch: ReplayBufferSamples) -> None:
        """One critic, actor and target update on ``batch`` (observations ``(B, obs_dim)``, actions ``(B, A)``
        in [-1, 1], rewards / dones ``(B, 1)``), back-propagated explicitly (no autograd graph)."""
        policy = self.policy
        actor, critic = self.actor, self.critic
        obs = batch.observations
        batch_size = obs.shape[0]

        # Skills of the states and of the next states, from one router call.
        skills = next_skills = None
        if policy.n_skills > 1:
            both = policy.route(th.cat((obs, batch.next_observations)))
            assert both is not None
            skills, next_skills = both[:batch_size], both[batch_size:]

        # 1. Critic (eq. 5, 6): L = mean((Q - y)^2), dL/dQ = 2 (Q - y) / B.
        target_q = self._critic_target(batch, next_skills)
        current_q, critic_inputs = critic.forward_for_backward(obs, policy.critic_action(batch.actions))
        error = current_q - target_q
        grad_q = error * (2.0 / batch_size)
        critic_grad_zs = critic.output_gradients(critic_inputs, grad_q)
        critic_grads = self._critic_grads
        critic_grads.weight_gradients(
            [(g.t(), x) for g, x in zip(critic_grad_zs, critic_inputs, strict=True)]
        )
        critic_grads.bias_gradients(self._batch_ones(batch_size, obs), critic_grad_zs)
        self._stat_views[0].addmm_(error.t(), grad_q, alpha=0.5)  # the loss: error . grad_q / 2
        adam_step(policy.critic_optimizer, self._critic_params, critic_grads.grads[0])

        # 2. Actor (eq. 7) against the updated critic; skill k's loss is -mean over its n_k rows of Q(s, mu(s)).
        if skills is None:
            counts: tuple[int, ...] = (batch_size,)
        else:
            # Rows sorted by skill, so that each skill's rows are one slice.
            obs = obs.index_select(0, th.argsort(skills, stable=True))
            counts = tuple(th.bincount(skills, minlength=policy.n_skills).tolist())
        segments, row_weight, skill_weight, mean_weight, indicator = self._skill_layout(counts, obs)
        actor_actions, actor_inputs, actor_outputs = actor.forward_for_backward(obs, segments)
        parameter_mask = policy.parameter_mask(actor_actions)
        if parameter_mask is None:
            actor_q, q_inputs = critic.forward_for_backward(obs, actor_actions)
            dq_da = critic.action_gradient(q_inputs)
        else:  # Q sees a * mask, so dQ/da = mask * dQ/d(a * mask): no gradient for parameters the env ignores
            actor_q, q_inputs = critic.forward_for_backward(obs, actor_actions * parameter_mask)
            dq_da = critic.action_gradient(q_inputs) * parameter_mask
            if self.parameter_loss == "each_action":
                dq_da = self._each_action_gradient(obs, actor_actions, dq_da)
        if policy.inverting_gradients:
            dq_da = self._invert_gradients(dq_da, actor_actions)
        # d(lambda * mean_k ||z||^2)/dz = 2 lambda z / n_k = -2 lambda z * row_weight.
        grad_outputs = (
            actor_outputs * (row_weight * (-2.0 * self.preactivation_penalty))
            if self.preactivation_penalty > 0
            else None
        )
        grad_zs = actor.output_gradients(
            actor_inputs, actor_actions, dq_da * row_weight, segments, grad_outputs=grad_outputs
        )
        # All skills' dZ were taken at the same parameters and their weight gradients need no parameter: all bias
        # gradients come from one product, then each skill with rows takes its weight gradients and its Adam step
        # in turn, in the same buffers (hot in cache for the step).
        buffers = self._actor_grads
        buffers.bias_gradients(indicator, grad_zs)
        if len(segments) == 1:
            parts = [[(g.t(), x) for g, x in zip(grad_zs, actor_inputs, strict=True)]]
        else:
            sizes = [stop - start for _, start, stop in segments]
            per_layer = [
                zip(g.t().split(sizes, dim=1), x.split(sizes), strict=True)
                for g, x in zip(grad_zs, actor_inputs, strict=True)
            ]
            parts = list(zip(*per_layer, strict=True))
        for row, ((k, _, _), skill_parts) in enumerate(zip(segments, parts, strict=True)):
            buffers.weight_gradients(skill_parts)
            adam_step(self._skill_optimizers[k], self._skill_params[k], buffers.grads[row])
            self._skill_updates[k] += 1

        # 3. Targets.
        th._foreach_lerp_(self._target_params, self._online_params, self.tau)

        # Statistics, summed in place into views of self._stat_sums (no synchronisation; the critic loss above).
        # Means are products with the (B, 1) column of 1 / B, and skill k's loss -mean_k Q is row k of
        # skill_weight @ Q: one kernel each, where .mean() would also convert its divisor every time.
        _, actor_loss, max_q, mean_q, skill_losses = self._stat_views
        actor_loss.addmm_(actor_q.t(), mean_weight, alpha=-1.0)
        max_q.add_(current_q.max())
        mean_q.addmm_(current_q.t(), mean_weight)
        skill_losses.addmm_(skill_weight, actor_q)
        self._stat_updates += 1

    def _each_action_gradient(self, obs: th.Tensor, actor_actions: th.Tensor, dq_da: th.Tensor) -> th.Tensor:
        """``parameter_loss="each_action"``: ``dq_da (B, A)``'s preference columns (the actor's own action) with
        every discrete action ``k``'s parameter columns replaced by ``dQ(s, e_k, x_k)/dx_k``, the gradient of ``k``
        played with the actor's parameters (preferences ``e_k``: +1 for ``k``, -1 for the others; the other
        actions' parameters at 0). Zero for KICK's parameters where :meth:`HFOPolicy.kick_unavailable`."""
        policy = self.policy
        rows, own_masks = policy.discrete_action_rows, policy.own_parameter_masks
        assert rows is not None and own_masks is not None
        n_discrete, batch_size = rows.shape[0], obs.shape[0]
        own_masks = own_masks.unsqueeze(1)
        # (n, B, A): block k is the actor's action played as discrete action k, as the critic sees it; the n * B
        # rows go through one critic pass.
        candidates = th.addcmul(rows.unsqueeze(1), actor_actions.unsqueeze(0), own_masks)
        _, q_inputs = self.critic.forward_for_backward(
            obs.repeat(n_discrete, 1), candidates.view(n_discrete * batch_size, -1)
        )
        grads = self.critic.action_gradient(q_inputs).view(n_discrete, batch_size, -1) * own_masks
        no_kick = policy.kick_unavailable(obs)
        if no_kick is not None:
            grads[policy.action_layout.ball_action].masked_fill_(no_kick.unsqueeze(1), 0.0)  # type: ignore[union-attr]
        result = grads.sum(dim=0)
        result[:, :n_discrete] = dq_da[:, :n_discrete]
        return result

    def _skill_layout(self, counts: tuple[int, ...], like: th.Tensor) -> _Layout:
        """Segments and loss weights of a minibatch sorted by skill with ``counts[k]`` rows of skill ``k``.

        :return: ``(segments, row_weight, skill_weight (n_skills, B), mean_weight (B, 1), indicator)``: ``row_weight`` is
            ``-1 / n_k`` on skill ``k``'s rows (the derivative of ``-mean_k Q`` by each row's ``Q``; a ``(B, 1)``
            tensor, or the float ``-1 / B`` with one skill), ``skill_weight[k]`` is ``row_weight`` restricted to
            skill ``k``'s rows (zero elsewhere), so that ``skill_weight @ Q`` gives every skill's loss, and
            ``mean_weight`` is ``1 / B`` on every row; ``indicator (n_segments, B)`` is 1 on segment ``j``'s rows
            in row ``j`` (0 elsewhere). Cached by ``counts``: a batch of 32 split between 2 skills
            has 33 layouts, and building one takes ~10 small tensor operations.
        """
        key = (counts, like.dtype, like.device)
        layout = self._layouts.get(key)
        if layout is None:
            segments: list[Segment] = []
            batch_size = sum(counts)
            skill_weight = th.zeros(len(counts), batch_size, dtype=like.dtype, device=like.device)
            start = 0
            for k, n_rows in enumerate(counts):
                if n_rows > 0:
                    segments.append((k, start, start + n_rows))
                    skill_weight[k, start : start + n_rows] = -1.0 / n_rows
                    start += n_rows
            row_weight = -1.0 / batch_size if len(counts) == 1 else skill_weight.sum(0).unsqueeze(1)
            mean_weight = th.full((batch_size, 1), 1.0 / batch_size, dtype=like.dtype, device=like.device)
            indicator = (skill_weight[[k for k, _, _ in segments]] != 0).to(like.dtype)
            if len(self._layouts) >= _MAX_CACHED_LAYOUTS:
                self._layouts.clear()
            layout = self._layouts[key] = (segments, row_weight, skill_weight, mean_weight, indicator)
        return layout

    def _batch_ones(self, batch_size: int, like: th.Tensor) -> th.Tensor:
        """``(1, batch_size)`` ones: the indicator of a gradient over all rows (cached)."""
        return self._skill_layout((batch_size,), like)[4]

    def _critic_target(self, batch: ReplayBufferSamples, next_skills: th.Tensor | None = None) -> th.Tensor:
        """``y (B, 1) = r + gamma^n * (1 - done) * Q'(s', mu'(s'))`` (eq. 6; ``max_k Q'(s', e_k, x'(s'))`` with
        ``discrete_target="max"``; ``gamma^n`` from ``batch.discounts``
        with n-step returns), mixed
        with the episode's return ``G`` as ``y + beta * (G - y)`` on rows whose return is known when
        ``mc_mixing = beta > 0``. ``next_skills``: the routed skills of the next states
        (``None``: routed here). Call under ``torch.no_grad()``."""
        policy = self.policy
        next_obs = batch.next_observations
        if next_skills is None:
            next_skills = policy.route(next_obs)
        next_actions = self.actor_target.forward(next_obs, next_skills)
        if policy.inverting_gradients:
            next_actions = next_actions.clamp(-1.0, 1.0)
        if self.discrete_target == "max":
            _, next_values = policy.discrete_values(next_obs, next_actions, self.critic_target)
            next_q = next_values.max(dim=1, keepdim=True).values
        else:
            next_q, _ = self.critic_target.forward_for_backward(next_obs, policy.critic_action(next_actions))
        if batch.discounts is None:
            # (1 - done) is 0 or 1, so this is r + gamma * (1 - done) * Q' with the same rounding, in one kernel.
            target_q = th.addcmul(batch.rewards, 1 - batch.dones, next_q, value=self.gamma)
        else:
            target_q = batch.rewards + (1 - batch.dones) * batch.discounts * next_q
        if self.mc_mixing > 0:
            mixed: MonteCarloReplayBufferSamples = batch  # type: ignore[assignment]
            target_q += self.mc_mixing * mixed.mc_valid * (mixed.mc_returns - target_q)
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
        # The mirror choice is for evaluation: rollouts act with the plain greedy action (x31: no gain from it).
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
        """SB3's ``save``, with the acting options switched on the policy after construction
        (:attr:`HFOPolicy.ACTING_OPTIONS`, e.g. ``model.policy.mirror_choice = True``) written into
        ``policy_kwargs``, which is what ``load`` rebuilds the policy from."""
        self.policy_kwargs = {**self.policy_kwargs, **self.policy.acting_options()}
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
            "_critic_params",
            "_skill_optimizers",
            "_stat_sums",
            "_stat_views",
            "_layouts",
            "_actor_grads",
            "_critic_grads",
            "_loading",
        ]

    def _get_torch_save_params(self) -> tuple[list[str], list[str]]:
        # Every optimiser is saved: the critic's and one per skill (named attributes of the policy).
        skill_optimizers = [f"policy.actor_skill_{k}_optimizer" for k in range(self.policy.n_skills)]
        return ["policy", "policy.critic_optimizer", *skill_optimizers], []
