"""SkillDDPG's fast update: the same maths as :meth:`SkillDDPG._autograd_update
<sb3_hfo.skill_ddpg.skill_ddpg.SkillDDPG._autograd_update>`, back-propagated by hand.

The readable update, written with autograd, is the algorithm's definition and lives in the algorithm module. This
module computes the same update without autograd, for speed; ``SkillDDPG(fast_update=True)`` (the default) uses it
where it applies (:meth:`FastUpdate.applies_to`: the policy's own actor and critic classes, whose backward passes
are written here), and ``tests/test_skill_ddpg.py`` checks both against each other over the option combinations.

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
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import torch as th
from stable_baselines3.common.type_aliases import ReplayBufferSamples
from torch.nn import functional as F

from sb3_hfo.common.buffers import MonteCarloReplayBufferSamples
from sb3_hfo.skill_ddpg.policies import HFOActor, HFOCritic, HFOPolicy, Segment

if TYPE_CHECKING:
    from sb3_hfo.skill_ddpg.skill_ddpg import SkillDDPG

# ATen's tanh backward kernel: dL/dz from dL/dy and y = tanh(z), one fused kernel.
_tanh_backward = th.ops.aten.tanh_backward.default

__all__ = [
    "FastUpdate",
    "actor_forward_for_backward",
    "actor_output_gradients",
    "adam_step",
    "critic_action_gradient",
    "critic_forward_for_backward",
    "critic_output_gradients",
]

# Bound on SkillDDPG's cache of minibatch layouts (one per split of the batch between skills).
_MAX_CACHED_LAYOUTS = 4096
# (segments, row_weight, skill_weight, mean_weight): see FastUpdate._skill_layout.
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


def actor_forward_for_backward(
    actor: HFOActor, obs: th.Tensor, segments: list[Segment]
) -> tuple[th.Tensor, list[th.Tensor], th.Tensor]:
    """the network's ``forward`` on rows grouped by skill, keeping what the backward pass (:func:`actor_output_gradients`)
    needs.

    :param obs: ``(B, obs_dim)``, rows sorted by skill.
    :param segments: ``(skill, start, stop)`` for each skill with rows: rows ``start:stop`` use head ``skill``.
    :return: ``(action (B, action_dim), layer_inputs, head_outputs)``: the input of every trunk layer and of
        the heads (``obs``, then each hidden activation ``(B, hidden[i])``), and the heads' outputs before
        ``tanh`` ``(B, action_dim)``.
    """
    inputs = [obs]
    for weight, bias in actor.trunk_layers:
        inputs.append(actor.activation.forward(F.linear(inputs[-1], weight, bias)))
    features = inputs[-1]
    if len(segments) == 1:
        weight, bias = actor.head_layers[segments[0][0]]
        out = F.linear(features, weight, bias)
    else:
        out = th.cat(
            [
                F.linear(features[start:stop], actor.head_layers[k][0], actor.head_layers[k][1])
                for k, start, stop in segments
            ]
        )
    return (th.tanh(out) if actor.squash else out), inputs, out


def actor_output_gradients(
    actor: HFOActor,
    inputs: list[th.Tensor],
    action: th.Tensor,
    grad_action: th.Tensor,
    segments: list[Segment],
    grad_outputs: th.Tensor | None = None,
) -> list[th.Tensor]:
    """Explicit backward pass of ``grad_action`` for all rows: every layer's pre-activation gradient ``dZ``.

    Rows never mix in an MLP, so one backward pass gives every layer's ``dZ`` for all rows at the current
    parameters; skill ``k``'s weight gradients are then ``dZ[rows_k].T @ input[rows_k]`` over its
    rows alone (the gradient of skill ``k``'s loss alone, for the FLOPs of one backward pass), needing no
    parameter.

    :param inputs: the layer inputs returned by :func:`actor_forward_for_backward` (same ``segments``).
    :param action: ``(B, action_dim)``, the actions it returned.
    :param grad_action: ``(B, action_dim)``, dLoss/daction (each row already weighted by its skill's loss).
    :param segments: as for :func:`critic_forward_for_backward`.
    :param grad_outputs: optional ``(B, action_dim)`` extra gradient with respect to the heads' outputs before
        ``tanh`` (a loss term on them, e.g. SkillDDPG's ``preactivation_penalty``).
    :return: ``dZ`` of every trunk layer, input side first, then of the heads' outputs ``(B, action_dim)``.
    """
    grad_out = _tanh_backward(grad_action, action) if actor.squash else grad_action
    if grad_outputs is not None:
        grad_out = grad_out + grad_outputs
    trunk_layers = actor.trunk_layers
    backward = actor.activation.backward
    if len(segments) == 1:
        grad_hidden = grad_out.mm(actor.head_layers[segments[0][0]][0])
    else:
        sizes = [stop - start for _, start, stop in segments]
        grad_hidden = th.empty_like(inputs[-1])
        for (k, _, _), grad_part, hidden_part in zip(
            segments, grad_out.split(sizes), grad_hidden.split(sizes), strict=True
        ):
            th.mm(grad_part, actor.head_layers[k][0], out=hidden_part)
    grad_zs = [grad_out]  # collected from the output down, reversed at the end
    for index in range(len(trunk_layers) - 1, -1, -1):
        grad_z = backward(grad_hidden, inputs[index + 1])
        grad_zs.append(grad_z)
        if index > 0:
            grad_hidden = grad_z.mm(trunk_layers[index][0])
    return grad_zs[::-1]


def critic_forward_for_backward(
    critic: HFOCritic, obs: th.Tensor, action: th.Tensor
) -> tuple[th.Tensor, list[th.Tensor]]:
    """the network's ``forward`` (same numbers) keeping every layer's input for :func:`critic_output_gradients` /
    :func:`critic_action_gradient`.

    :return: ``(Q (B, 1), layer_inputs)``: ``obs``, ``[obs features, encoded action]
        (B, qf[0] + action_encoder.out_dim)``, then each later hidden activation ``(B, qf[i])``.
    """
    layers = critic.layers
    weight, bias = layers[0]
    features = critic.activation.forward(F.linear(obs, weight, bias))
    inputs = [obs, th.cat((features, critic.encode_action(action, obs)), dim=1)]
    for weight, bias in layers[1:-1]:
        inputs.append(critic.activation.forward(F.linear(inputs[-1], weight, bias)))
    weight, bias = layers[-1]
    return F.linear(inputs[-1], weight, bias), inputs


def critic_output_gradients(critic: HFOCritic, inputs: list[th.Tensor], grad_q: th.Tensor) -> list[th.Tensor]:
    """Explicit backward pass of ``grad_q = dLoss/dQ (B, 1)``: every layer's pre-activation gradient ``dZ``,
    input side first (the last one is ``grad_q``). Layer ``i``'s weight gradient is ``dZ_i.T @ inputs[i]``,
    its bias gradient the row sum of ``dZ_i``.

    :param inputs: the layer inputs returned by :func:`critic_forward_for_backward`.
    """
    layers = critic.layers
    n_features = critic.n_features
    backward = critic.activation.backward
    grad_z = grad_q
    grad_zs = [grad_z]  # collected from the output down, reversed at the end
    for index in range(len(layers) - 1, 0, -1):
        weight = layers[index][0]
        if index == 1:  # only the features' gradient; the action's is not needed here
            grad_z = backward(grad_z.mm(weight[:, :n_features]), inputs[1][:, :n_features])
        else:
            grad_z = backward(grad_z.mm(weight), inputs[index])
        grad_zs.append(grad_z)
    return grad_zs[::-1]


def critic_action_gradient(critic: HFOCritic, inputs: list[th.Tensor]) -> th.Tensor:
    """dQ/da ``(B, action_dim)`` of every row's own ``Q`` (i.e. of ``Q.sum()``), without any weight gradient.

    :param inputs: the layer inputs returned by :func:`critic_forward_for_backward`.
    """
    layers = critic.layers
    n_features = critic.n_features
    # d(sum Q)/d(last layer's input) is the output layer's weight row, for every row of the batch.
    grad_input = layers[-1][0].expand(inputs[0].shape[0], -1)
    if len(layers) > 2:  # otherwise (qf = [n]) the action enters the output layer
        for index in range(len(layers) - 2, 0, -1):
            grad_z = critic.activation.backward(grad_input, inputs[index + 1])
            weight = layers[index][0]
            # At the action layer only the action's columns: a (B, action_dim) product, not (B, qf[0] + ...).
            grad_input = grad_z.mm(weight if index > 1 else weight[:, n_features:])
    else:
        grad_input = grad_input[:, n_features:]
    return critic.action_encoder.action_gradient(grad_input, inputs[1][:, n_features:])


class FastUpdate:
    """The hand-derived update of a :class:`~sb3_hfo.skill_ddpg.skill_ddpg.SkillDDPG` model, with the parameter
    lists, gradient buffers and minibatch layouts it reuses from one update to the next.

    Build it after the model's policy (``SkillDDPG._setup_model`` does); the model's hyperparameters and
    statistics are read and written through ``model`` on every update.
    """

    def __init__(self, model: SkillDDPG) -> None:
        self.model = model
        policy = model.policy
        actor, critic = policy.actor, policy.critic
        # Fixed parameter lists: module.to(device) and load_state_dict keep the same Parameter objects.
        self._critic_params = list(critic.parameters())
        self._online_params = [*actor.parameters(), *self._critic_params]
        self._target_params = [*policy.actor_target.parameters(), *policy.critic_target.parameters()]
        self._skill_params = [policy.skill_parameters(k) for k in range(policy.n_skills)]
        self._skill_optimizers = policy.actor_optimizers
        self._layouts: dict[tuple[Any, ...], _Layout] = {}
        # Every skill's gradients are written into the same tensors in turn (all skills' shapes are the same).
        self._actor_grads = _GradientBuffers(self._skill_params[0], policy.n_skills)
        self._critic_grads = _GradientBuffers(self._critic_params, 1)

    @staticmethod
    def applies_to(policy: HFOPolicy) -> bool:
        """Whether the hand-written backward passes are the policy's networks' (not a subclass that may compute
        something else)."""
        return type(policy.actor) is HFOActor and type(policy.critic) is HFOCritic

    @th.no_grad()
    def update(self, batch: ReplayBufferSamples) -> None:
        """One critic, actor and target update on ``batch`` (observations ``(B, obs_dim)``, actions ``(B, A)``
        in [-1, 1], rewards / dones ``(B, 1)``), back-propagated explicitly (no autograd graph)."""
        model = self.model
        policy = model.policy
        actor, critic = model.actor, model.critic
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
        current_q, critic_inputs = critic_forward_for_backward(
            critic, obs, policy.critic_action(batch.actions)
        )
        error = current_q - target_q
        grad_q = error * (2.0 / batch_size)
        critic_grad_zs = critic_output_gradients(critic, critic_inputs, grad_q)
        critic_grads = self._critic_grads
        critic_grads.weight_gradients(
            [(g.t(), x) for g, x in zip(critic_grad_zs, critic_inputs, strict=True)]
        )
        critic_grads.bias_gradients(self._batch_ones(batch_size, obs), critic_grad_zs)
        model._stat_views[0].addmm_(error.t(), grad_q, alpha=0.5)  # the loss: error . grad_q / 2
        adam_step(policy.critic_optimizer, self._critic_params, critic_grads.grads[0])

        # 2. Actor (eq. 7) against the updated critic; skill k's loss is -mean over its n_k rows of Q(s, mu(s)).
        if skills is None:
            counts: tuple[int, ...] = (batch_size,)
        else:
            # Rows sorted by skill, so that each skill's rows are one slice.
            obs = obs.index_select(0, th.argsort(skills, stable=True))
            counts = tuple(th.bincount(skills, minlength=policy.n_skills).tolist())
        segments, row_weight, skill_weight, mean_weight, indicator = self._skill_layout(counts, obs)
        actor_actions, actor_inputs, actor_outputs = actor_forward_for_backward(actor, obs, segments)
        parameter_mask = policy.parameter_mask(actor_actions)
        if parameter_mask is None:
            actor_q, q_inputs = critic_forward_for_backward(critic, obs, actor_actions)
            dq_da = critic_action_gradient(critic, q_inputs)
        else:  # Q sees a * mask, so dQ/da = mask * dQ/d(a * mask): no gradient for parameters the env ignores
            actor_q, q_inputs = critic_forward_for_backward(critic, obs, actor_actions * parameter_mask)
            dq_da = critic_action_gradient(critic, q_inputs) * parameter_mask
            if model.parameter_loss == "each_action":
                dq_da = self._each_action_gradient(obs, actor_actions, dq_da)
        if policy.inverting_gradients:
            dq_da = model._invert_gradients(dq_da, actor_actions)
        # d(lambda * mean_k ||z||^2)/dz = 2 lambda z / n_k = -2 lambda z * row_weight.
        grad_outputs = (
            actor_outputs * (row_weight * (-2.0 * model.preactivation_penalty))
            if model.preactivation_penalty > 0
            else None
        )
        grad_zs = actor_output_gradients(
            actor, actor_inputs, actor_actions, dq_da * row_weight, segments, grad_outputs=grad_outputs
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
            model._skill_updates[k] += 1

        # 3. Targets.
        th._foreach_lerp_(self._target_params, self._online_params, model.tau)

        # Statistics, summed in place into views of self._stat_sums (no synchronisation; the critic loss above).
        # Means are products with the (B, 1) column of 1 / B, and skill k's loss -mean_k Q is row k of
        # skill_weight @ Q: one kernel each, where .mean() would also convert its divisor every time.
        _, actor_loss, max_q, mean_q, skill_losses = model._stat_views
        actor_loss.addmm_(actor_q.t(), mean_weight, alpha=-1.0)
        max_q.add_(current_q.max())
        mean_q.addmm_(current_q.t(), mean_weight)
        skill_losses.addmm_(skill_weight, actor_q)
        model._stat_updates += 1

    def _each_action_gradient(self, obs: th.Tensor, actor_actions: th.Tensor, dq_da: th.Tensor) -> th.Tensor:
        """``parameter_loss="each_action"``: ``dq_da (B, A)``'s preference columns (the actor's own action) with
        every discrete action ``k``'s parameter columns replaced by ``dQ(s, e_k, x_k)/dx_k``, the gradient of ``k``
        played with the actor's parameters (preferences ``e_k``: +1 for ``k``, -1 for the others; the other
        actions' parameters at 0). Zero for KICK's parameters where :meth:`HFOPolicy.kick_unavailable`."""
        model = self.model
        policy = model.policy
        rows, own_masks = policy.discrete_action_rows, policy.own_parameter_masks
        assert rows is not None and own_masks is not None
        n_discrete, batch_size = rows.shape[0], obs.shape[0]
        own_masks = own_masks.unsqueeze(1)
        # (n, B, A): block k is the actor's action played as discrete action k, as the critic sees it; the n * B
        # rows go through one critic pass.
        candidates = th.addcmul(rows.unsqueeze(1), actor_actions.unsqueeze(0), own_masks)
        _, q_inputs = critic_forward_for_backward(
            model.critic, obs.repeat(n_discrete, 1), candidates.view(n_discrete * batch_size, -1)
        )
        grads = critic_action_gradient(model.critic, q_inputs).view(n_discrete, batch_size, -1) * own_masks
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
        model = self.model
        policy = model.policy
        next_obs = batch.next_observations
        if next_skills is None:
            next_skills = policy.route(next_obs)
        next_actions = model.actor_target.forward(next_obs, next_skills)
        if policy.inverting_gradients:
            next_actions = next_actions.clamp(-1.0, 1.0)
        if model.discrete_target == "max":
            _, next_values = policy.discrete_values(next_obs, next_actions, model.critic_target)
            next_q = next_values.max(dim=1, keepdim=True).values
        else:
            next_q, _ = critic_forward_for_backward(
                model.critic_target, next_obs, policy.critic_action(next_actions)
            )
        if batch.discounts is None:
            # (1 - done) is 0 or 1, so this is r + gamma * (1 - done) * Q' with the same rounding, in one kernel.
            target_q = th.addcmul(batch.rewards, 1 - batch.dones, next_q, value=model.gamma)
        else:
            target_q = batch.rewards + (1 - batch.dones) * batch.discounts * next_q
        if model.mc_mixing > 0:
            mixed: MonteCarloReplayBufferSamples = batch  # type: ignore[assignment]
            target_q += model.mc_mixing * mixed.mc_valid * (mixed.mc_returns - target_q)
        return target_q
