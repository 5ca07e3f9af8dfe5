"""Actor, critic and policy of SkillDDPG: the seed paper's architecture (its "Method" section, Figure 1).

Paper, line by line, and where it lives here:

* "The state inputs are processed by 3 fully connected layers consisting of 400-300-200 units" -> default
  ``net_arch = dict(pi=[400, 300, 200], qf=[400, 300, 200])``.
* "Each fully connected layer is followed by a LeakyReLU activation with negative slope of 10^-2 except the last
  layers in both networks" -> ``nn.LeakyReLU(0.01)`` after every hidden layer, none after the output layers.
* "The final layer in the actor network is connected to a sigmoid activation giving a vector of 8 values" -> SB3
  stores actions rescaled to [-1, 1] in its replay buffer, so the actor ends in ``tanh`` (its raw output lives in
  the buffer's scale) and SB3 maps it onto the environment's ``Box(0, 1, (8,))`` by ``(a + 1) / 2``.
  ``(tanh(z) + 1) / 2 == sigmoid(2 z)``: the environment receives exactly a sigmoid of (twice) the final linear
  layer's output, i.e. the paper's sigmoid up to a factor 2 absorbed by the last layer's weights.
* "The final layer of the critic is not followed by an activation" -> linear Q output.
* "Weights are initialized with a truncated normal distribution with a standard deviation 10^-2" ->
  ``trunc_normal_(std=1e-2, a=-2e-2, b=2e-2)`` (TensorFlow's ``truncated_normal`` convention: re-draw beyond two
  standard deviations). Biases are not mentioned: they start at 0 (TensorFlow's default bias initialiser).
* "the critic network also takes as input the output of the action layer" and Figure 1: "The state and action are
  concatenated at the second layer of the critic network" -> ``HFOCritic``: state -> 400 (LeakyReLU), concatenate
  the action, -> 300 -> 200 (LeakyReLU each) -> 1.
* "We used the ADAM optimizer for both actor and critic" with learning rates 1e-4 / 1e-3 -> one Adam for the
  critic (``policy.critic_optimizer``) and, "In the skills architecture the actor has 2 parallel output layers,
  each having it's own ADAM optimizer", one Adam per skill (``policy.actor_skill_{k}_optimizer``).

Skills and the shared trunk (our reading, documented because the paper leaves it open): the paper's actor is a
TensorFlow graph in which each skill's optimiser minimises that skill's loss over the variables it depends on,
i.e. the shared trunk *and* its own output layer. So skill ``k``'s Adam owns ``trunk + head k`` and the trunk
receives one Adam step per skill that had samples in the minibatch, each with that skill's own moment estimates.
A skill that no sample chose takes no step at all (its head and its Adam state stay untouched).

Inverting gradients (Hausknecht & Stone 2016, the paper's Figure 2 alternative): with ``inverting_gradients=True``
the actor's output layer is linear (no ``tanh``); the algorithm rescales dQ/da to keep actions inside [-1, 1] and
acting clips actions to [-1, 1]. Figure 2's 1024-512-256-128 network is ``net_arch=[1024, 512, 256, 128]``.

Options beyond the paper, each off by default; each says why in one sentence, and the measurements are in
docs/findings.md (docs/results.md gives the committed models' figures):

* ``mask_unused_parameters``: the critic sees the action with every other discrete action's parameters set to 0
  (the middle of the [-1, 1] scale), from the replay buffer and from the actor alike, as Bester et al. 2019's
  multi-pass Q-network (MP-DQN) zeroes them. Why: only the chosen action's parameters reach the environment, and
  without the mask dQ/da drives the others into ``tanh``'s saturation, from where they pass back no gradient when
  they are finally used.
* ``critic_action_encoding``: the critic also sees Fourier features of the action's directions, absolute and
  relative to landmarks (:mod:`sb3_hfo.skill_ddpg.encoding`, which says why).

How a trained policy acts is one argument too, ``acting``: the critic's choice of the discrete action, the kick
mask and the mirror choice (:mod:`sb3_hfo.skill_ddpg.acting`, which says why). They change no network, so they can
be switched on a trained model; the mirror choice's kept side travels in ``predict``'s recurrent ``state``
(``episode_start`` resets it), as SB3's ``evaluate_policy``, rl-zoo3's ``enjoy`` and ``sb3_hfo.evaluate`` pass it.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterable, Iterator
from typing import Any

import numpy as np
import torch as th
from gymnasium import spaces
from stable_baselines3.common.policies import BasePolicy
from stable_baselines3.common.preprocessing import get_action_dim, get_flattened_obs_dim
from stable_baselines3.common.torch_layers import BaseFeaturesExtractor, FlattenExtractor
from stable_baselines3.common.type_aliases import PyTorchObs, Schedule
from torch import nn
from torch.nn import functional as F

from hfo2d.action_layout import HFO_FLAT_ACTION_LAYOUT, HybridActionLayout, action_layout
from hfo2d.features import KICKABLE
from sb3_hfo.common.mirror import Mirror, make_mirror
from sb3_hfo.common.routers import SkillRouter, check_skills, make_router, validate_skills
from sb3_hfo.skill_ddpg.acting import (
    ActingSpec,
    ActingStrategy,
    CriticChoice,
    KickMask,
    MirrorChoice,
    format_acting,
    parse_acting,
)
from sb3_hfo.skill_ddpg.encoding import ActionEncoder, ActionEncodingSpec, parse_encoding

__all__ = [
    "DEFAULT_NET_ARCH",
    "HFO_ACTION_PARAMETER_SIZES",
    "HFOActor",
    "HFOCritic",
    "HFOPolicy",
    "HiddenActivation",
    "Segment",
    "parse_net_arch",
]

#: ``(skill, start, stop)``: rows ``start:stop`` of a minibatch sorted by skill belong to ``skill``.
Segment = tuple[int, int, int]

#: The seed paper's hidden layers (Method: "3 fully connected layers consisting of 400-300-200 units").
DEFAULT_NET_ARCH: dict[str, list[int]] = {"pi": [400, 300, 200], "qf": [400, 300, 200]}
#: "LeakyReLU activation with negative slope of 10^-2" (seed paper, Method).
LEAKY_RELU_SLOPE = 1e-2
#: "Weights are initialized with a truncated normal distribution with a standard deviation 10^-2".
WEIGHT_INIT_STD = 1e-2
# HFO's flat action as hfo2d declares it (hfo2d.action_layout.HFO_FLAT_ACTION_LAYOUT), by the names other modules
# import: the parameter count of DASH, TURN and KICK, their number, the action's size and KICK's index.
HFO_ACTION_PARAMETER_SIZES = HFO_FLAT_ACTION_LAYOUT.parameter_sizes
HFO_N_DISCRETE_ACTIONS = HFO_FLAT_ACTION_LAYOUT.n_discrete
HFO_FLAT_ACTION_DIM = HFO_FLAT_ACTION_LAYOUT.size
HFO_KICK_ACTION = HFO_FLAT_ACTION_LAYOUT.ball_action
#: Column of HFO's low-level features holding "able to kick" (+1 when the ball is kickable, -1 otherwise); hfo2d
#: owns the layout (HFO's LowLevelFeatureExtractor).
KICKABLE_FEATURE_INDEX = KICKABLE


def parse_net_arch(net_arch: list[int] | dict[str, list[int]] | None) -> tuple[list[int], list[int]]:
    """Split ``net_arch`` into (actor hidden sizes, critic hidden sizes).

    ``None`` -> the paper's 400-300-200 for both; a list -> the same sizes for both; a dict needs the keys
    ``"pi"`` and ``"qf"``. Each list must hold at least one positive int.

    :raises ValueError: anything else (the message names the offending value).
    """
    if net_arch is None:
        return list(DEFAULT_NET_ARCH["pi"]), list(DEFAULT_NET_ARCH["qf"])
    if isinstance(net_arch, dict):
        unknown = set(net_arch) - {"pi", "qf"}
        if unknown or not {"pi", "qf"} <= set(net_arch):
            raise ValueError(f"net_arch dict needs exactly the keys 'pi' and 'qf', got {sorted(net_arch)}")
        actor_arch, critic_arch = net_arch["pi"], net_arch["qf"]
    elif isinstance(net_arch, (list, tuple)):
        actor_arch = critic_arch = net_arch
    else:
        raise ValueError(
            f"net_arch must be a list of layer sizes or dict(pi=[...], qf=[...]), got {net_arch!r}"
        )
    for name, arch in (("pi", actor_arch), ("qf", critic_arch)):
        if (
            not isinstance(arch, (list, tuple))
            or len(arch) == 0
            or not all(isinstance(n, (int, np.integer)) and not isinstance(n, bool) and n > 0 for n in arch)
        ):
            raise ValueError(f"net_arch[{name!r}] must be a non-empty list of positive ints, got {arch!r}")
    return [int(n) for n in actor_arch], [int(n) for n in critic_arch]


def _resolve_layout(
    space_layout: HybridActionLayout | None, mask_unused_parameters: object, action_dim: int
) -> HybridActionLayout | None:
    """The action layout the policy works with: the action space's (:func:`hfo2d.action_layout.action_layout`), or
    one given by ``mask_unused_parameters`` as the parameter count of each discrete action; ``None`` (a plain
    ``Box``, no discrete actions) otherwise.

    :raises ValueError: a bad ``mask_unused_parameters``, sizes that do not fit the action or the space's layout, or
        ``True`` without a layout.
    """
    option = mask_unused_parameters
    if isinstance(option, (bool, np.bool_)) or option is None:
        if option and space_layout is None:
            raise ValueError(
                f"mask_unused_parameters=True needs the action space's hybrid layout (hfo2d's HybridActionBox, as "
                f"the HFO envs have), but the {action_dim}-entry action space declares none; pass the parameter "
                "count of each discrete action instead, e.g. (2, 1, 2)"
            )
        return space_layout
    if isinstance(option, (str, bytes)) or not isinstance(option, (tuple, list)):
        raise ValueError(f"mask_unused_parameters must be a bool or a sequence of ints, got {option!r}")
    sizes = tuple(option)
    if not sizes or any(isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0 for n in sizes):
        raise ValueError(
            f"mask_unused_parameters must list ints >= 0 (one per discrete action), got {option!r}"
        )
    if len(sizes) + sum(sizes) != action_dim:
        raise ValueError(
            f"mask_unused_parameters={option!r} describes {len(sizes)} preferences + {sum(sizes)} parameters = "
            f"{len(sizes) + sum(sizes)} action entries, but the action has {action_dim}"
        )
    if space_layout is not None:
        if space_layout.parameter_sizes != tuple(int(n) for n in sizes):
            raise ValueError(
                f"mask_unused_parameters={option!r} differs from the action space's layout "
                f"{space_layout.parameter_sizes}"
            )
        return space_layout
    return HybridActionLayout.from_sizes(sizes)


def _make_activation(activation_fn: type[nn.Module]) -> nn.Module:
    """Instantiate ``activation_fn``; LeakyReLU gets the paper's negative slope 0.01 explicitly."""
    if activation_fn is nn.LeakyReLU:
        return nn.LeakyReLU(negative_slope=LEAKY_RELU_SLOPE)
    return activation_fn()


# Derivatives written from an activation's output ``y`` (what the forward pass keeps); ATen's own backward kernels,
# one fused kernel each instead of a mask, a multiply and a select.
_leaky_relu_backward = th.ops.aten.leaky_relu_backward.default
_threshold_backward = th.ops.aten.threshold_backward.default
_tanh_backward = th.ops.aten.tanh_backward.default


class HiddenActivation:
    """A hidden-layer activation with its derivative, for the explicit forward / backward passes of the update.

    ``forward(z)`` maps a pre-activation ``(B, n)`` to ``y`` in place (``z`` is a fresh layer output that nothing
    else keeps); ``backward(grad_y, y)`` returns ``dL/dz`` from ``dL/dy`` and the *output* ``y`` (no pre-activation
    needs to be kept). Supported: ``nn.LeakyReLU`` with a positive slope (then ``y`` has the sign of ``z``),
    ``nn.ReLU`` and ``nn.Tanh``. Plain attributes only, so that networks holding one stay picklable.

    :raises ValueError: for any other activation (the message names it).
    """

    def __init__(self, module: nn.Module) -> None:
        self.name = type(module).__name__
        self.slope = 0.0
        if isinstance(module, nn.LeakyReLU) and module.negative_slope > 0:
            self.kind = "leaky_relu"
            self.slope = float(module.negative_slope)
        elif isinstance(module, nn.ReLU):
            self.kind = "relu"
        elif isinstance(module, nn.Tanh):
            self.kind = "tanh"
        else:
            raise ValueError(
                f"activation_fn must be nn.LeakyReLU (slope > 0), nn.ReLU or nn.Tanh, got {self.name}: "
                "SkillDDPG back-propagates explicitly and needs its derivative"
            )

    def forward(self, z: th.Tensor) -> th.Tensor:
        """``y = f(z)``, written into ``z``."""
        if self.kind == "leaky_relu":
            return F.leaky_relu_(z, self.slope)
        return th.relu_(z) if self.kind == "relu" else th.tanh_(z)

    def backward(self, grad: th.Tensor, y: th.Tensor) -> th.Tensor:
        """``dL/dz = dL/dy * f'(z)``, with ``f'`` written from the output ``y``."""
        if self.kind == "leaky_relu":
            return _leaky_relu_backward(grad, y, self.slope, True)
        return _threshold_backward(grad, y, 0.0) if self.kind == "relu" else _tanh_backward(grad, y)


def _linear_params(modules: Iterable[nn.Module]) -> list[tuple[nn.Parameter, nn.Parameter]]:
    """``(weight (out, in), bias (out,))`` of every ``nn.Linear`` in ``modules``, in order.

    The Parameter objects stay the same through ``load_state_dict`` and ``.to(device)`` (both write into them), so
    the networks keep these lists instead of walking their submodules on every call.
    """
    return [(m.weight, m.bias) for m in modules if isinstance(m, nn.Linear)]


def _init_linear(layer: nn.Linear, std: float) -> None:
    """Paper initialisation: weights ~ truncated normal (std ``std``, cut at 2 std), biases 0."""
    nn.init.trunc_normal_(layer.weight, mean=0.0, std=std, a=-2.0 * std, b=2.0 * std)
    nn.init.zeros_(layer.bias)


class HFOActor(nn.Module):
    """Deterministic actor: shared trunk + ``n_skills`` parallel output layers ("skills").

    ``obs (B, obs_dim)`` -> trunk (Linear + activation per entry of ``net_arch``) -> ``(B, hidden[-1])`` -> head of
    each row's skill, ``Linear(hidden[-1], action_dim)`` -> ``tanh`` (or identity with ``squash=False``) ->
    ``(B, action_dim)`` in the replay buffer's action scale [-1, 1].

    :param obs_dim: number of (flattened) observation features.
    :param action_dim: number of action dimensions (8 for HFO's flat action).
    :param net_arch: hidden layer sizes of the trunk, e.g. ``[400, 300, 200]``.
    :param n_skills: number of output heads.
    :param activation_fn: activation class after each hidden layer.
    :param squash: ``tanh`` on the output (True) or a linear output (False, inverting gradients).
    :param weight_init_std: standard deviation of the truncated-normal weight initialisation.
    """

    def __init__(
        self,
        obs_dim: int,
        action_dim: int,
        net_arch: list[int],
        n_skills: int = 1,
        activation_fn: type[nn.Module] = nn.LeakyReLU,
        squash: bool = True,
        weight_init_std: float = WEIGHT_INIT_STD,
    ) -> None:
        super().__init__()
        layers: list[nn.Module] = []
        in_features = obs_dim
        for width in net_arch:
            layers += [nn.Linear(in_features, width), _make_activation(activation_fn)]
            in_features = width
        self.trunk = nn.Sequential(*layers)
        self.heads = nn.ModuleList([nn.Linear(in_features, action_dim) for _ in range(n_skills)])
        self.squash = squash
        self.n_skills = n_skills
        self.action_dim = action_dim
        self.activation = HiddenActivation(layers[1])
        self.trunk_layers = _linear_params(self.trunk)
        self.head_layers = _linear_params(self.heads)
        for module in self.modules():
            if isinstance(module, nn.Linear):
                _init_linear(module, weight_init_std)

    def all_skills(self, obs: th.Tensor) -> th.Tensor:
        """Every head's action for every row: ``(B, obs_dim)`` -> ``(B, n_skills, action_dim)``."""
        features = self.features(obs)
        out = th.stack([F.linear(features, weight, bias) for weight, bias in self.head_layers], dim=1)
        return th.tanh(out) if self.squash else out

    def features(self, obs: th.Tensor) -> th.Tensor:
        """The shared trunk: ``(B, obs_dim)`` -> ``(B, hidden[-1])``."""
        hidden = obs
        for weight, bias in self.trunk_layers:
            hidden = self.activation.forward(F.linear(hidden, weight, bias))
        return hidden

    def forward(self, obs: th.Tensor, skills: th.Tensor | None = None) -> th.Tensor:
        """Action of each row's skill.

        :param obs: ``(B, obs_dim)`` float tensor.
        :param skills: ``(B,)`` long tensor of head indices; ``None`` means head 0 (only valid with one skill).
        :return: ``(B, action_dim)``; in [-1, 1] when ``squash`` is set.
        """
        out = self.head_outputs(obs, skills)
        return th.tanh(out) if self.squash else out

    def head_outputs(self, obs: th.Tensor, skills: th.Tensor | None = None) -> th.Tensor:
        """:meth:`forward` before the ``tanh``: each row's skill head's output ``(B, action_dim)``."""
        features = self.features(obs)
        if skills is None or self.n_skills == 1:
            weight, bias = self.head_layers[0]
            out = F.linear(features, weight, bias)
        elif skills.shape[0] == 1:
            # Acting in one environment: only the routed head (one scalar read instead of every head and a select).
            weight, bias = self.head_layers[int(skills)]
            out = F.linear(features, weight, bias)
        elif self.n_skills == 2:
            # One select instead of stacking both heads and gathering (~10 us less per call).
            (weight_0, bias_0), (weight_1, bias_1) = self.head_layers
            out = th.where(
                skills.view(-1, 1).bool(),
                F.linear(features, weight_1, bias_1),
                F.linear(features, weight_0, bias_0),
            )
        else:
            per_skill = th.stack([F.linear(features, w, b) for w, b in self.head_layers], dim=1)
            index = skills.view(-1, 1, 1).expand(-1, 1, self.action_dim)
            out = per_skill.gather(1, index).squeeze(1)
        return out


def one_hot_preferences(n_discrete: int, like: th.Tensor) -> th.Tensor:
    """``(n, n)`` in ``like``'s dtype and device: row ``k`` is discrete action ``k``'s preferences, +1 for ``k`` and
    -1 for the others (the form epsilon-greedy exploration stores and the critic's choice tries)."""
    return 2.0 * th.eye(n_discrete, dtype=like.dtype, device=like.device) - 1.0


class HFOCritic(nn.Module):
    """Q(s, a) with the action entering at the second layer (seed paper, Figure 1).

    ``obs (B, obs_dim)`` -> ``obs_net``: Linear(obs_dim, qf[0]) + activation -> concatenate ``action (B, action_dim)``
    -> ``joint_net``: Linear(qf[0] + action_dim, qf[1]) + activation -> ... -> Linear(qf[-1], 1) -> ``(B, 1)``.
    With ``qf = [400]`` the action enters the (linear) output layer.

    :param obs_dim: number of (flattened) observation features.
    :param action_dim: number of action dimensions.
    :param net_arch: hidden layer sizes, e.g. ``[400, 300, 200]``.
    :param activation_fn: activation class after each hidden layer.
    :param weight_init_std: standard deviation of the truncated-normal weight initialisation.
    :param action_encoder: how the critic sees the action (:class:`~sb3_hfo.skill_ddpg.encoding.ActionEncoder`);
        default: as it is.
    """

    def __init__(
        self,
        obs_dim: int,
        action_dim: int,
        net_arch: list[int],
        activation_fn: type[nn.Module] = nn.LeakyReLU,
        weight_init_std: float = WEIGHT_INIT_STD,
        action_encoder: ActionEncoder | None = None,
    ) -> None:
        super().__init__()
        self.action_dim = action_dim
        self.action_encoder = ActionEncoder(action_dim) if action_encoder is None else action_encoder
        self.obs_net = nn.Sequential(nn.Linear(obs_dim, net_arch[0]), _make_activation(activation_fn))
        layers: list[nn.Module] = []
        in_features = net_arch[0] + self.action_encoder.out_dim
        for width in net_arch[1:]:
            layers += [nn.Linear(in_features, width), _make_activation(activation_fn)]
            in_features = width
        layers.append(nn.Linear(in_features, 1))
        self.joint_net = nn.Sequential(*layers)
        self.activation = HiddenActivation(self.obs_net[1])
        self.n_features = net_arch[0]
        self.layers = _linear_params([*self.obs_net, *self.joint_net])
        for module in self.modules():
            if isinstance(module, nn.Linear):
                _init_linear(module, weight_init_std)

    @property
    def action_layer(self) -> nn.Linear:
        """The layer that receives ``[obs features, action]`` (the critic's second layer)."""
        first = self.joint_net[0]
        assert isinstance(first, nn.Linear)
        return first

    def encode_action(self, action: th.Tensor, obs: th.Tensor | None = None) -> th.Tensor:
        """``action (B, action_dim)`` -> what the critic's second layer sees (:class:`ActionEncoder`); ``obs``
        gives the landmarks' bearings when the encoding is relative to them."""
        return self.action_encoder.forward(action, obs)  # not (...): no module hooks on the hot path

    def forward(self, obs: th.Tensor, action: th.Tensor) -> th.Tensor:
        """``obs (B, obs_dim)``, ``action (B, action_dim)`` in the buffer scale -> ``Q (B, 1)``."""
        return self.joint_net(th.cat((self.obs_net(obs), self.encode_action(action, obs)), dim=1))


class HFOPolicy(BasePolicy):
    """SkillDDPG's policy: actor (with skills), critic, their target copies and their optimisers.

    :param observation_space: a ``Box`` (flattened; HFO: 58 or 66 features in [-1, 1]).
    :param action_space: a bounded ``Box`` (HFO flat action: ``Box(0, 1, (8,))``).
    :param lr_schedule: learning-rate schedule used to create the optimisers (SkillDDPG resets the actor's and the
        critic's learning rates from its own two schedules before every update).
    :param net_arch: hidden sizes, ``[400, 300, 200]`` or ``dict(pi=[...], qf=[...])``; default the paper's.
    :param activation_fn: hidden activation (default LeakyReLU with slope 0.01); ``nn.LeakyReLU``, ``nn.ReLU`` or
        ``nn.Tanh``, whose derivatives the explicit backward pass of SkillDDPG knows (:class:`HiddenActivation`).
    :param n_skills: number of actor output layers (1 = the paper's plain agent).
    :param skill_router: a :class:`~sb3_hfo.common.routers.SkillRouter`, a router name (``"single"``,
        ``"field_half"``) or ``None`` (``"single"`` for 1 skill, ``"field_half"`` for 2).
    :param inverting_gradients: linear actor output + Hausknecht & Stone's inverting gradients (see module doc).
    :param mask_unused_parameters: the critic sees only the chosen discrete action's parameters (see module doc).
        ``False`` (default, the paper), ``True`` (by the action space's hybrid layout,
        :func:`hfo2d.action_layout.action_layout`: the HFO envs declare theirs) or, for a plain ``Box``, the number
        of parameters of each discrete action in order, e.g. ``(2, 1, 2)``: the action is then ``[one preference
        per discrete action, their parameters in the same order]``.
    :param acting: the acting strategies (:mod:`sb3_hfo.skill_ddpg.acting`): a tuple of
        :class:`~sb3_hfo.skill_ddpg.acting.CriticChoice`, :class:`~sb3_hfo.skill_ddpg.acting.KickMask` and
        :class:`~sb3_hfo.skill_ddpg.acting.MirrorChoice` objects or their text form (``"critic,kick_mask,mirror:0.1"``);
        ``None`` (default, the paper): none. The critic's choice needs an action layout (the action space's or
        ``mask_unused_parameters`` given as sizes); the kick mask and the mirror choice need HFO's low-level features
        and flat action. A mirror margin > 0 keeps its side in ``predict``'s ``state`` (see :meth:`predict`).
    :param critic_action_encoding: how the critic sees the action (:mod:`sb3_hfo.skill_ddpg.encoding`): a
        :class:`~sb3_hfo.skill_ddpg.encoding.DirectionFeatures`, its dict form (``{"frequencies": [1, 2, 4],
        "relative_to": ["goalie"]}``) or ``None`` (default, the paper): the action as it is. Needs a layout with
        direction parameters (HFO's).
    :param weight_init_std: truncated-normal standard deviation for all weights (paper: 1e-2).
    :param optimizer_class: optimiser class for the critic and each skill (default Adam).
    :param optimizer_kwargs: extra optimiser arguments; with Adam and neither ``fused`` nor ``foreach`` given,
        ``fused=True`` is used (same maths, one kernel per step instead of ~10 per parameter).
    :param features_extractor_class: kept for SB3 compatibility; only ``FlattenExtractor`` is supported.
    :param features_extractor_kwargs: kept for SB3 compatibility.
    :param normalize_images: kept for SB3 compatibility (observations are feature vectors).
    """

    actor: HFOActor
    actor_target: HFOActor
    critic: HFOCritic
    critic_target: HFOCritic
    critic_optimizer: th.optim.Optimizer

    def __init__(
        self,
        observation_space: spaces.Space,
        action_space: spaces.Space,
        lr_schedule: Schedule,
        net_arch: list[int] | dict[str, list[int]] | None = None,
        activation_fn: type[nn.Module] = nn.LeakyReLU,
        n_skills: int = 1,
        skill_router: SkillRouter | str | None = None,
        inverting_gradients: bool = False,
        mask_unused_parameters: bool | tuple[int, ...] | list[int] = False,
        acting: ActingSpec = None,
        critic_action_encoding: ActionEncodingSpec = None,
        weight_init_std: float = WEIGHT_INIT_STD,
        optimizer_class: type[th.optim.Optimizer] = th.optim.Adam,
        optimizer_kwargs: dict[str, Any] | None = None,
        features_extractor_class: type[BaseFeaturesExtractor] = FlattenExtractor,
        features_extractor_kwargs: dict[str, Any] | None = None,
        normalize_images: bool = True,
    ) -> None:
        if not isinstance(action_space, spaces.Box):
            raise ValueError(
                f"HFOPolicy needs a Box action space (HFO: action_format='flat'), got {type(action_space).__name__}"
            )
        if not (np.all(np.isfinite(action_space.low)) and np.all(np.isfinite(action_space.high))):
            raise ValueError("HFOPolicy needs a bounded Box action space (finite low and high)")
        if not isinstance(observation_space, spaces.Box):
            raise ValueError(
                f"HFOPolicy needs a Box observation space, got {type(observation_space).__name__}"
            )
        if features_extractor_class is not FlattenExtractor:
            raise ValueError("HFOPolicy only supports FlattenExtractor (feature-vector observations)")
        if weight_init_std <= 0:
            raise ValueError(f"weight_init_std must be > 0, got {weight_init_std}")
        super().__init__(
            observation_space,
            action_space,
            features_extractor_class,
            features_extractor_kwargs,
            optimizer_class=optimizer_class,
            optimizer_kwargs=optimizer_kwargs,
            squash_output=True,
            normalize_images=normalize_images,
        )
        self.net_arch = net_arch
        self.actor_arch, self.critic_arch = parse_net_arch(net_arch)
        self.activation_fn = activation_fn
        self.skill_router = make_router(skill_router, n_skills)
        self.n_skills = int(n_skills)
        self.inverting_gradients = bool(inverting_gradients)
        self.weight_init_std = float(weight_init_std)
        self.obs_dim = get_flattened_obs_dim(observation_space)
        self.action_dim = get_action_dim(action_space)
        self.mask_unused_parameters = mask_unused_parameters
        #: The hybrid action layout (hfo2d.action_layout), or None: a plain Box, acted on as DDPG does.
        self.action_layout = _resolve_layout(
            action_layout(action_space), mask_unused_parameters, self.action_dim
        )
        #: Each discrete action's parameter count when the critic masks unused parameters, else None.
        self.action_parameter_sizes = (
            self.action_layout.parameter_sizes
            if self.action_layout is not None and mask_unused_parameters is not False
            else None
        )
        self._mirror: Mirror | None = None
        self._mirror_suspended = 0  # > 0 inside mirror_choice_suspended()
        self.acting = acting  # validated by the property setter
        # The kept sides, set by predict for _predict while a call with a mirror margin > 0 runs.
        self._side_box: list[np.ndarray | None] | None = None
        self.critic_action_encoding = parse_encoding(critic_action_encoding)
        self._make_action_encoder()  # refuses an encoding the layout or the observation cannot give, before building
        self._build(lr_schedule)

    def _optimizer_kwargs(self) -> dict[str, Any]:
        kwargs = dict(self.optimizer_kwargs)
        if self.optimizer_class is th.optim.Adam and "fused" not in kwargs and "foreach" not in kwargs:
            kwargs["fused"] = True
        return kwargs

    def _build(self, lr_schedule: Schedule) -> None:
        actor_kwargs = dict(
            obs_dim=self.obs_dim,
            action_dim=self.action_dim,
            net_arch=self.actor_arch,
            n_skills=self.n_skills,
            activation_fn=self.activation_fn,
            squash=not self.inverting_gradients,
            weight_init_std=self.weight_init_std,
        )
        critic_kwargs = dict(
            obs_dim=self.obs_dim,
            action_dim=self.action_dim,
            net_arch=self.critic_arch,
            activation_fn=self.activation_fn,
            weight_init_std=self.weight_init_std,
        )
        self.actor = HFOActor(**actor_kwargs)  # type: ignore[arg-type]
        self.actor_target = HFOActor(**actor_kwargs)  # type: ignore[arg-type]
        self.actor_target.load_state_dict(self.actor.state_dict())
        self.critic = HFOCritic(**critic_kwargs, action_encoder=self._make_action_encoder())  # type: ignore[arg-type]
        self.critic_target = HFOCritic(**critic_kwargs, action_encoder=self._make_action_encoder())  # type: ignore[arg-type]
        self.critic_target.load_state_dict(self.critic.state_dict())
        for target in (self.actor_target, self.critic_target):
            target.requires_grad_(False)
            target.train(False)
        self._build_parameter_masks()

        lr = lr_schedule(1)
        kwargs = self._optimizer_kwargs()
        self.critic_optimizer = self.optimizer_class(self.critic.parameters(), lr=lr, **kwargs)  # type: ignore[call-arg]
        trunk = list(self.actor.trunk.parameters())
        for k, head in enumerate(self.actor.heads):
            optimizer = self.optimizer_class(trunk + list(head.parameters()), lr=lr, **kwargs)  # type: ignore[call-arg]
            # One named attribute per skill so that SkillDDPG.save / load can address each state dict.
            setattr(self, f"actor_skill_{k}_optimizer", optimizer)

    def _make_action_encoder(self) -> ActionEncoder:
        return ActionEncoder(self.action_dim, self.critic_action_encoding, self.action_layout, self.obs_dim)

    def _build_parameter_masks(self) -> None:
        """``parameter_masks (n_discrete, action_dim)``: row ``j`` is 1 on every preference and on discrete action
        ``j``'s parameters, 0 elsewhere. ``own_parameter_masks``: the same without the preferences (1 only on
        ``j``'s parameters), and ``discrete_action_rows``: row ``j`` is ``j``'s one-hot preferences (+1 / -1) with
        every parameter 0, so that ``rows[j] + a * own_masks[j]`` is action ``a`` played as ``j`` as the critic sees
        it (SkillDDPG's ``parameter_loss="each_action"``). Not saved: they follow from ``mask_unused_parameters``."""
        masks = own_masks = rows = None
        if self.action_parameter_sizes is not None:
            layout = self.action_layout
            assert layout is not None
            n_discrete = layout.n_discrete
            own_masks = th.from_numpy(layout.parameter_masks(with_preferences=False))
            masks = th.from_numpy(layout.parameter_masks())
            rows = th.zeros(n_discrete, self.action_dim)
            rows[:, :n_discrete] = one_hot_preferences(n_discrete, rows)
        self.parameter_masks: th.Tensor | None
        self.own_parameter_masks: th.Tensor | None
        self.discrete_action_rows: th.Tensor | None
        self.register_buffer("parameter_masks", masks, persistent=False)
        self.register_buffer("own_parameter_masks", own_masks, persistent=False)
        self.register_buffer("discrete_action_rows", rows, persistent=False)

    def parameter_mask(self, actions: th.Tensor) -> th.Tensor | None:
        """``(B, action_dim)`` mask of what the environment executes for ``actions (B, action_dim)``: the
        preferences and the parameters of their argmax (the first maximum on ties, the layout's rule:
        :meth:`hfo2d.action_layout.HybridActionLayout.choose`); ``None`` when
        ``mask_unused_parameters`` is off."""
        masks = self.parameter_masks
        if masks is None:
            return None
        return masks.index_select(0, actions[:, : masks.shape[0]].argmax(dim=1))

    @property
    def acting(self) -> tuple[ActingStrategy, ...]:
        """The acting strategies (:mod:`sb3_hfo.skill_ddpg.acting`) in use; set it with strategies or their text
        form, e.g. ``policy.acting = "critic,kick_mask,mirror:0.1"`` (may be changed at any time)."""
        return self._acting

    @acting.setter
    def acting(self, spec: ActingSpec) -> None:
        strategies = parse_acting(spec)
        critic_picks = any(isinstance(s, CriticChoice) for s in strategies)
        kick_mask = any(isinstance(s, KickMask) for s in strategies)
        mirror_choice = next((s for s in strategies if isinstance(s, MirrorChoice)), None)
        if critic_picks and self.n_discrete_actions == 0:
            raise ValueError(
                "acting CriticChoice needs the discrete actions: an action space with a hybrid layout (the HFO "
                "envs'), or mask_unused_parameters given as per-action parameter counts"
            )
        layout = self.action_layout
        if kick_mask and (
            layout is None or layout.ball_action is None or self.obs_dim <= KICKABLE_FEATURE_INDEX
        ):
            raise ValueError(
                "acting KickMask needs an action layout with a kick (HFO's flat action) and HFO's low-level "
                f"features (at least {KICKABLE_FEATURE_INDEX + 1}), got layout {layout} and {self.obs_dim} features"
            )
        # validated before anything is set, so that a refused value changes nothing
        mirror = (
            None if mirror_choice is None else make_mirror((self.obs_dim,), layout, "acting MirrorChoice")
        )
        self._acting = strategies
        self._critic_picks = critic_picks
        self._kick_mask = kick_mask
        self._mirror = mirror
        self._mirror_margin = 0.0 if mirror_choice is None else mirror_choice.margin

    @contextlib.contextmanager
    def mirror_choice_suspended(self) -> Iterator[None]:
        """Act without the mirror choice inside the ``with`` block (SkillDDPG's training rollouts); ``acting`` may
        still be changed inside it, and what it is on leaving the block is what the policy acts with."""
        self._mirror_suspended += 1
        try:
            yield
        finally:
            self._mirror_suspended -= 1

    @property
    def mirror_active(self) -> bool:
        """Whether acting now plays the mirror choice: ``MirrorChoice`` is in :attr:`acting` and not suspended."""
        return self._mirror is not None and not self._mirror_suspended

    def kick_unavailable(self, obs: th.Tensor) -> th.Tensor | None:
        """``(B,)`` bool, True where KICK is left out (ball out of reach); ``None`` without the kick mask."""
        if not self._kick_mask:
            return None
        return obs[:, KICKABLE_FEATURE_INDEX] < 0

    @property
    def n_discrete_actions(self) -> int:
        """Number of discrete actions (leading preferences) of the action layout; 0 without a layout."""
        return 0 if self.action_layout is None else self.action_layout.n_discrete

    def discrete_values(
        self, obs: th.Tensor, actions: th.Tensor, critic: HFOCritic | None = None
    ) -> tuple[th.Tensor, th.Tensor]:
        """Each discrete action at the actor's parameters, and its value.

        :param obs: ``(B, obs_dim)``.
        :param actions: ``(B, action_dim)`` in [-1, 1].
        :param critic: the critic to ask (default: ``self.critic``; SkillDDPG's target passes the target critic).
        :return: ``candidates (B, n, action_dim)``, ``actions`` with the preferences replaced by discrete action
            ``k``'s one-hot vector (+1 / -1) in row ``k``, and their values ``(B, n)`` (``-inf`` for KICK where
            :meth:`kick_unavailable`).
        """
        n_discrete = self.n_discrete_actions
        batch = actions.shape[0]
        candidates = actions.unsqueeze(1).repeat(1, n_discrete, 1)
        candidates[:, :, :n_discrete] = one_hot_preferences(n_discrete, actions)
        repeated_obs = obs.repeat_interleave(n_discrete, dim=0)
        seen = self.critic_action(candidates.view(batch * n_discrete, -1))
        q_values = (critic or self.critic).forward(repeated_obs, seen).view(batch, n_discrete)
        no_kick = self.kick_unavailable(obs)
        if no_kick is not None:
            q_values[:, self.action_layout.ball_action].masked_fill_(no_kick, -th.inf)  # type: ignore[union-attr]
        return candidates, q_values

    def critic_choice(self, obs: th.Tensor, actions: th.Tensor) -> th.Tensor:
        """``actions (B, action_dim)`` in [-1, 1] with their preferences replaced by the one-hot vector (+1 / -1)
        of the discrete action the critic values most at the actor's parameters (ties: the first)."""
        candidates, q_values = self.discrete_values(obs, actions)
        best = q_values.argmax(dim=1)
        return candidates[th.arange(actions.shape[0], device=actions.device), best]

    def critic_action(self, actions: th.Tensor) -> th.Tensor:
        """``actions (B, action_dim)`` as the critic sees them: unused parameters set to 0 with
        ``mask_unused_parameters``, unchanged otherwise."""
        mask = self.parameter_mask(actions)
        return actions if mask is None else actions * mask

    @property
    def actor_optimizers(self) -> list[th.optim.Optimizer]:
        """Skill ``k``'s optimiser (over trunk + head ``k``) at index ``k``."""
        return [getattr(self, f"actor_skill_{k}_optimizer") for k in range(self.n_skills)]

    def skill_parameters(self, skill: int) -> list[nn.Parameter]:
        """Parameters skill ``skill`` trains: the shared trunk followed by its own output layer."""
        return list(self.actor.trunk.parameters()) + list(self.actor.heads[skill].parameters())

    def route(self, obs: th.Tensor) -> th.Tensor | None:
        """Skill index per row of ``obs (B, obs_dim)`` as a long tensor ``(B,)`` on ``obs``'s device; ``None`` when
        ``n_skills == 1``.

        The router's output is checked on every call (:func:`~sb3_hfo.common.routers.check_skills`: type, shape,
        range), so that an index outside ``[0, n_skills)`` raises instead of being routed to some head.
        """
        if self.n_skills == 1:
            return None
        return validate_skills(
            self.skill_router(obs), obs.shape[0], self.n_skills, self.skill_router, obs.device
        )

    def numpy_route(self, obs: np.ndarray) -> np.ndarray:
        """:meth:`route` for a numpy batch ``(B, obs_dim)``: ``np.int64`` skill indices ``(B,)``, checked the same
        way (all zeros when ``n_skills == 1``)."""
        obs = np.asarray(obs, dtype=np.float32)
        if self.n_skills == 1:
            return np.zeros(obs.shape[0], dtype=np.int64)
        skills = self.skill_router(obs)
        if isinstance(skills, th.Tensor):
            skills = skills.detach().cpu().numpy()
        check_skills(skills, obs.shape[0], self.n_skills, self.skill_router)
        return skills.astype(np.int64, copy=False)

    def _get_constructor_parameters(self) -> dict[str, Any]:
        data = super()._get_constructor_parameters()
        data.update(
            dict(
                net_arch=self.net_arch,
                activation_fn=self.activation_fn,
                n_skills=self.n_skills,
                skill_router=self.skill_router,
                inverting_gradients=self.inverting_gradients,
                mask_unused_parameters=self.mask_unused_parameters,
                acting=format_acting(self.acting),
                critic_action_encoding=None
                if self.critic_action_encoding is None
                else self.critic_action_encoding.as_dict(),
                weight_init_std=self.weight_init_std,
                lr_schedule=self._dummy_schedule,
                optimizer_class=self.optimizer_class,
                optimizer_kwargs=self.optimizer_kwargs,
                features_extractor_class=self.features_extractor_class,
                features_extractor_kwargs=self.features_extractor_kwargs,
            )
        )
        return data

    @property
    def device(self) -> th.device:
        """Where the policy lives: its actor's first weight (SB3's default walks all submodules on every call, and
        ``predict`` asks on every environment step)."""
        return self.actor.trunk_layers[0][0].device

    def _flatten_obs(self, observation: PyTorchObs) -> th.Tensor:
        assert isinstance(observation, th.Tensor)
        obs = observation.float()
        return obs.flatten(1) if obs.dim() > 2 else obs

    def forward(self, observation: PyTorchObs, deterministic: bool = False) -> th.Tensor:
        return self._predict(observation, deterministic=deterministic)

    def predict(
        self,
        observation: np.ndarray | dict[str, np.ndarray],
        state: tuple[np.ndarray, ...] | None = None,
        episode_start: np.ndarray | None = None,
        deterministic: bool = False,
    ) -> tuple[np.ndarray, tuple[np.ndarray, ...] | None]:
        """SB3's ``predict``; with the acting ``MirrorChoice(margin > 0)``, ``state`` is ``(sides,)``, one
        float per row (1.0: mirrored side kept, 0.0: plain, NaN: none yet), and the sides after this step are
        returned in its place. ``state=None`` and rows with ``episode_start`` true start afresh."""
        if not self.mirror_active or self._mirror_margin == 0.0:
            return super().predict(observation, state, episode_start, deterministic)
        # SB3's predict hands state to the caller only, not to _predict: the sides go through a one-item box that
        # _predict reads and overwrites.
        self._side_box = [self._sides_from_state(state, episode_start)]
        try:
            actions, _ = super().predict(observation, None, None, deterministic)
            sides = self._side_box[0]
        finally:
            self._side_box = None
        return actions, (sides,)

    @staticmethod
    def _sides_from_state(
        state: tuple[np.ndarray, ...] | None, episode_start: np.ndarray | None
    ) -> np.ndarray | None:
        """The kept sides of ``state`` (see :meth:`predict`) with new episodes' rows set to NaN; None: all new."""
        if state is None:
            return None
        if not isinstance(state, tuple) or len(state) != 1:
            raise ValueError(
                "with a mirror margin > 0, state must be the (sides,) tuple returned by the previous predict, got "
                f"{type(state).__name__} of length {len(state) if isinstance(state, tuple) else '-'}"
            )
        sides = np.array(state[0], dtype=np.float32).reshape(-1)
        if episode_start is not None:
            starts = np.asarray(episode_start, dtype=bool).reshape(-1)
            if starts.shape != sides.shape:
                raise ValueError(
                    f"episode_start has {starts.size} entries but state has {sides.size} sides (one per env)"
                )
            sides[starts] = np.nan
        return sides

    def _predict(self, observation: PyTorchObs, deterministic: bool = False) -> th.Tensor:
        """Greedy action in [-1, 1] for ``observation (B, obs_dim)`` (DDPG's actor is deterministic)."""
        obs = self._flatten_obs(observation)
        if not self.mirror_active:
            return self._greedy_action(obs)
        mirror, batch = self._mirror, obs.shape[0]
        assert mirror is not None
        if mirror.sign.device != obs.device:  # the tensors are not module buffers: .to(device) leaves them
            mirror = self._mirror = mirror.to(obs.device)
        both = th.cat((obs, mirror.observations(obs)))
        actions = self._greedy_action(both)
        values = self.critic.forward(both, self.critic_action(actions)).squeeze(1)
        plain_value, mirror_value = values[:batch], values[batch:]
        mirrored = mirror_value > plain_value
        side_box = self._side_box
        if side_box is not None:  # called from predict with a margin: keep each row's side unless outdone
            kept = side_box[0]
            if kept is not None:
                if kept.shape != (batch,):
                    raise ValueError(
                        f"state has {kept.size} sides but the observation batch has {batch} rows"
                    )
                kept_mirrored = th.as_tensor(kept == 1.0, device=obs.device)
                gain = th.where(kept_mirrored, plain_value - mirror_value, mirror_value - plain_value)
                new_episode = th.as_tensor(np.isnan(kept), device=obs.device)
                mirrored = th.where(new_episode, mirrored, kept_mirrored ^ (gain > self._mirror_margin))
            side_box[0] = mirrored.cpu().numpy().astype(np.float32)
        return th.where(mirrored.unsqueeze(1), mirror.actions(actions[batch:]), actions[:batch])

    def _greedy_action(self, obs: th.Tensor) -> th.Tensor:
        """The greedy action in [-1, 1] for ``obs (B, obs_dim)`` by the acting strategies, without the mirror
        choice."""
        action = self.actor.forward(obs, self.route(obs))  # not actor(...): no hooks to run, ~10 us per step
        if self.inverting_gradients:
            action = action.clamp(-1.0, 1.0)
        if self._critic_picks:
            return self.critic_choice(obs, action)
        no_kick = self.kick_unavailable(obs)
        if no_kick is not None:
            layout = self.action_layout
            assert layout is not None and layout.ball_action is not None
            n_discrete, kick = layout.n_discrete, layout.ball_action
            preferences = action[:, :n_discrete]
            replace = no_kick & (preferences.argmax(dim=1) == kick)
            if replace.any():
                best = preferences.index_fill(1, th.tensor([kick], device=action.device), -th.inf).argmax(
                    dim=1
                )
                one_hot = 2.0 * nn.functional.one_hot(best, n_discrete).to(action.dtype) - 1.0
                action = action.clone()
                action[:, :n_discrete] = th.where(replace.unsqueeze(1), one_hot, preferences)
        return action

    def set_training_mode(self, mode: bool) -> None:
        """Set the ``training`` flag of the policy, the actor and the critics (and all their submodules).

        SB3 switches it twice per environment step (acting, then training); ``nn.Module.train``'s recursion costs
        ~0.1 ms per call here, so the flags are written straight into a cached flat list of the modules. No layer
        of these networks behaves differently in either mode; the flags are kept right for code that reads them.
        """
        actor, critic = self.actor, self.critic
        cached = self.__dict__.get("_mode_modules")
        if cached is None or cached[0] is not actor or cached[1] is not critic:
            cached = (actor, critic, [*actor.modules(), *critic.modules()])
            self.__dict__["_mode_modules"] = cached
        for module in cached[2]:
            module.__dict__["training"] = mode
        self.__dict__["training"] = mode
