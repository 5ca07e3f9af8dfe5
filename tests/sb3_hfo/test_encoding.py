"""The critic's action encoding (sb3_hfo.skill_ddpg.encoding): Fourier features of the action's directions, absolute
and relative to landmarks, their chain rule against autograd, the ``critic_action_encoding`` argument in its two
forms, its errors, and save / load."""

from __future__ import annotations

import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
import torch as th
from gymnasium import spaces

from hfo2d.action_layout import HybridActionLayout, hfo_flat_action_space
from sb3_hfo import HFOPolicy, SkillDDPG
from sb3_hfo.common.toy_env import HybridTargetEnv
from sb3_hfo.skill_ddpg.encoding import ActionEncoder, DirectionFeatures, parse_encoding
from sb3_hfo.skill_ddpg.fast_update import critic_action_gradient, critic_forward_for_backward
from sb3_hfo.skill_ddpg.legacy import LEGACY_POLICY_OPTIONS, translate_legacy_options

OBS_SPACE = spaces.Box(-1.0, 1.0, (58,), np.float32)  # HFO's features without a goalie
GOALIE_OBS_SPACE = spaces.Box(-1.0, 1.0, (66,), np.float32)  # with one
ACTION_SPACE = hfo_flat_action_space()  # HFO's flat action, its layout declared


def make_policy(**kwargs: object) -> HFOPolicy:
    th.manual_seed(0)
    return HFOPolicy(OBS_SPACE, ACTION_SPACE, lambda _: 1e-3, **{"domain": "hfo", **kwargs})  # type: ignore[arg-type]


def make_goalie_policy(**kwargs: object) -> HFOPolicy:
    th.manual_seed(0)
    return HFOPolicy(GOALIE_OBS_SPACE, ACTION_SPACE, lambda _: 1e-3, **{"domain": "hfo", **kwargs})  # type: ignore[arg-type]


def batch_obs(n: int = 32, seed: int = 0, dim: int = 58) -> th.Tensor:
    return th.as_tensor(np.random.default_rng(seed).uniform(-1, 1, (n, dim)), dtype=th.float32)


def random_actions(n: int, seed: int = 1) -> th.Tensor:
    return th.empty(n, 8).uniform_(-1, 1, generator=th.Generator().manual_seed(seed))


# ----------------------------------------------------------------------------------------------------------
# Absolute direction features


def test_critic_direction_features_are_off_by_default_and_encode_each_direction() -> None:
    plain = make_policy(net_arch=[16, 8])
    assert plain.critic_action_encoding is None
    assert plain.critic.action_layer.in_features == 16 + 8
    assert plain.critic.action_encoder.n_angles == 0 and plain.critic.action_encoder.out_dim == 8
    untouched = th.rand(3, 8)
    assert plain.critic.encode_action(untouched) is untouched  # no copy without features
    policy = make_policy(net_arch=[16, 8], critic_action_encoding=DirectionFeatures(frequencies=(1, 4)))
    critic = policy.critic
    assert policy.critic_action_encoding == DirectionFeatures(frequencies=(1.0, 4.0), relative_to=())
    encoder = critic.action_encoder
    assert encoder.n_angles == 3 * 2 and encoder.n_relative == 0  # 3 directions, 2 frequencies
    assert encoder.out_dim == 8 + 2 * 3 * 2  # sin and cos of each
    assert critic.action_layer.in_features == 16 + encoder.out_dim
    assert encoder.index.tolist() == [4, 5, 7, 4, 5, 7]  # dash, turn and kick direction at each frequency
    th.testing.assert_close(encoder.scale, th.tensor([1.0, 1.0, 1.0, 4.0, 4.0, 4.0]) * np.pi)
    action = th.zeros(1, 8)
    action[0, 4], action[0, 5], action[0, 7] = 0.5, -0.25, 1.0  # dash 90, turn -45, kick 180 degrees
    seen = critic.encode_action(action)
    th.testing.assert_close(seen, encoder(action))
    th.testing.assert_close(seen[:, :8], action)
    degrees = th.tensor([90.0, -45.0, 180.0, 4 * 90.0, 4 * -45.0, 4 * 180.0])
    th.testing.assert_close(seen[0, 8:14], th.sin(th.deg2rad(degrees)), atol=1e-6, rtol=0)
    th.testing.assert_close(seen[0, 14:], th.cos(th.deg2rad(degrees)), atol=1e-6, rtol=0)
    # The target critic encodes the same way; the encoder's tensors follow from the encoding and are not saved.
    th.testing.assert_close(policy.critic_target.encode_action(action), seen)
    assert not any("action_encoder" in key for key in policy.state_dict())


@pytest.mark.parametrize("critic_arch", [[16], [16, 8], [16, 8, 4]])
def test_critic_action_gradient_through_direction_features_equals_autograd(critic_arch: list[int]) -> None:
    policy = make_policy(
        net_arch=dict(pi=[8], qf=critic_arch),
        critic_action_encoding=DirectionFeatures(frequencies=(1, 2, 8, 32)),
    )
    critic = policy.critic
    obs = batch_obs(16)
    action = random_actions(16).requires_grad_(True)
    critic(obs, action).sum().backward()
    q, inputs = critic_forward_for_backward(critic, obs, action.detach())
    th.testing.assert_close(q, critic(obs, action).detach())
    th.testing.assert_close(critic_action_gradient(critic, inputs), action.grad, atol=1e-6, rtol=1e-5)
    assert action.grad is not None and action.grad[:, [4, 5, 7]].abs().min() > 0


def test_encoder_action_gradient_is_the_chain_rule_of_its_forward() -> None:
    """``ActionEncoder.action_gradient`` against autograd through the encoder alone, for any upstream gradient."""
    for policy, obs in (
        (make_policy(critic_action_encoding=DirectionFeatures((1, 3, 16))), batch_obs(16)),
        (
            make_goalie_policy(critic_action_encoding=DirectionFeatures((2, 8), ("goalie", "goal_center"))),
            batch_obs(16, dim=66),
        ),
    ):
        encoder = policy.critic.action_encoder
        action = random_actions(16).requires_grad_(True)
        seen = encoder(action, obs)
        assert seen.shape == (16, encoder.out_dim)
        grad_seen = th.empty_like(seen).normal_(generator=th.Generator().manual_seed(2))
        (seen * grad_seen).sum().backward()
        th.testing.assert_close(
            encoder.action_gradient(grad_seen, seen.detach()), action.grad, atol=1e-5, rtol=1e-5
        )


# ----------------------------------------------------------------------------------------------------------
# The kick direction relative to landmarks


def test_critic_sees_the_kick_direction_relative_to_the_goalie_bearing() -> None:
    policy = make_goalie_policy(
        net_arch=[16, 8],
        critic_action_encoding=DirectionFeatures(frequencies=(1, 4), relative_to=("goalie",)),
    )
    critic = policy.critic
    assert policy.critic_action_encoding is not None
    assert policy.critic_action_encoding.relative_to == ("goalie",)
    encoder = critic.action_encoder
    assert encoder.n_relative == 2 and encoder.n_angles == 3 * 2 + 2  # 3 absolute + 1 relative, 2 frequencies
    assert encoder.index.tolist() == [4, 5, 7, 4, 5, 7, 7, 7]
    th.testing.assert_close(encoder.scale[6:], th.tensor([1.0, 4.0]) * np.pi)
    assert critic.action_layer.in_features == 16 + 8 + 2 * (3 + 1) * 2
    obs = th.zeros(2, 66)
    obs[:, 58], obs[:, 59] = (
        np.sin(np.radians(30.0)),
        np.cos(np.radians(30.0)),
    )  # goalie 30 degrees to the right
    action = th.zeros(2, 8)
    action[0, 7], action[1, 7] = 30.0 / 180.0, 40.0 / 180.0  # kick at him, and 10 degrees past him
    seen = critic.encode_action(action, obs)
    n = 8
    # sines: the 6 absolute columns (3 directions x 2 frequencies), then the relative one at each frequency
    relative_sin = seen[:, [n + 6, n + 7]]
    relative_cos = seen[:, [n + 8 + 6, n + 8 + 7]]
    expected = th.deg2rad(th.tensor([[0.0, 0.0], [10.0, 40.0]]))  # (kick - bearing) at frequencies 1 and 4
    th.testing.assert_close(relative_sin, th.sin(expected), atol=1e-6, rtol=0)
    th.testing.assert_close(relative_cos, th.cos(expected), atol=1e-6, rtol=0)
    with pytest.raises(ValueError, match="pass obs"):
        critic.encode_action(action)


@pytest.mark.parametrize("critic_arch", [[16], [16, 8, 4]])
def test_critic_action_gradient_through_relative_kick_features_equals_autograd(
    critic_arch: list[int],
) -> None:
    policy = make_goalie_policy(
        net_arch=dict(pi=[8], qf=critic_arch),
        critic_action_encoding=DirectionFeatures(
            frequencies=(1, 8, 32), relative_to=("goalie", "goal_post_top", "goal_post_bottom")
        ),
    )
    critic = policy.critic
    assert critic.action_encoder.n_relative == 3 * 3
    obs = batch_obs(16, dim=66)
    action = random_actions(16).requires_grad_(True)
    critic(obs, action).sum().backward()
    q, inputs = critic_forward_for_backward(critic, obs, action.detach())
    th.testing.assert_close(q, critic(obs, action).detach())
    th.testing.assert_close(critic_action_gradient(critic, inputs), action.grad, atol=1e-5, rtol=1e-5)


# ----------------------------------------------------------------------------------------------------------
# The argument's two forms and their errors


def test_the_dict_form_and_direction_features_are_equivalent() -> None:
    features = DirectionFeatures(frequencies=(1, 4), relative_to=("goalie",))
    as_dict = {"frequencies": [1, 4], "relative_to": ["goalie"]}
    assert parse_encoding(as_dict) == features
    assert parse_encoding({"frequencies": [2]}) == DirectionFeatures((2.0,))  # relative_to is optional
    assert parse_encoding(features) is features and parse_encoding(None) is None
    assert features.as_dict() == {"frequencies": [1.0, 4.0], "relative_to": ["goalie"]}
    assert parse_encoding(features.as_dict()) == features
    from_object = make_goalie_policy(net_arch=[16, 8], critic_action_encoding=features)
    from_dict = make_goalie_policy(net_arch=[16, 8], critic_action_encoding=as_dict)
    assert from_dict.critic_action_encoding == from_object.critic_action_encoding == features
    assert from_dict.critic.action_encoder.out_dim == from_object.critic.action_encoder.out_dim
    # The same seed builds the same networks, which see the same action the same way.
    for key, value in from_object.state_dict().items():
        assert th.equal(from_dict.state_dict()[key], value), key
    obs, action = batch_obs(8, dim=66), random_actions(8)
    with th.no_grad():
        th.testing.assert_close(
            from_dict.critic(obs, action), from_object.critic(obs, action), atol=0, rtol=0
        )
    # The policy saves the dict form.
    assert from_object._get_constructor_parameters()["critic_action_encoding"] == features.as_dict()
    assert make_policy()._get_constructor_parameters()["critic_action_encoding"] is None


@pytest.mark.parametrize(
    ("spec", "named"),
    [
        ({"frequencies": [1], "relativ_to": ["goalie"]}, "relativ_to"),
        ({"frequency": [1]}, "frequency"),
        ({"relative_to": ["goalie"]}, "needs the key 'frequencies'"),
        ([1, 4], "got list"),
        ("1,4", "got str"),
        ((1, 4), "got tuple"),
        (4, "got int"),
    ],
)
def test_parse_encoding_rejects_unknown_keys_and_types_naming_them(spec: object, named: str) -> None:
    with pytest.raises(ValueError, match=named):
        parse_encoding(spec)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=named):  # and so does the policy
        make_policy(critic_action_encoding=spec)


def test_direction_features_errors_name_the_problem() -> None:
    for bad in ([0], [-1.0], [float("nan")], [float("inf")], "1, 2", [True], 4, (), []):
        with pytest.raises(ValueError, match="DirectionFeatures frequencies must be"):
            DirectionFeatures(frequencies=bad)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="DirectionFeatures frequencies must be"):  # the dict form too
        make_policy(critic_action_encoding={"frequencies": [0]})
    # the landmarks are the domain's: names are checked against it when the policy is built
    with pytest.raises(
        ValueError, match=r"unknown landmark\(s\) \['keeper'\]; the policy's domain knows \('goalie'"
    ):
        make_goalie_policy(critic_action_encoding={"frequencies": [1], "relative_to": ["goalie", "keeper"]})
    with pytest.raises(
        ValueError, match=r"unknown landmark\(s\) \['goalie'\]; the policy's domain knows \(\)"
    ):
        make_goalie_policy(
            critic_action_encoding={"frequencies": [1], "relative_to": ["goalie"]}, domain=None
        )
    with pytest.raises(ValueError, match="relative_to must name landmarks by non-empty strings"):
        DirectionFeatures(frequencies=(1,), relative_to=("",))
    with pytest.raises(
        ValueError, match="DirectionFeatures relative_to must be a sequence of landmark names"
    ):
        DirectionFeatures(frequencies=(1,), relative_to="goalie")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="names a landmark twice"):
        DirectionFeatures(frequencies=(1,), relative_to=("goalie", "goalie"))
    with pytest.raises(AttributeError):
        DirectionFeatures(frequencies=(1,)).frequencies = (2.0,)  # type: ignore[misc]


def test_encoding_errors_name_what_the_spaces_lack() -> None:
    with pytest.raises(
        ValueError, match="critic_action_encoding needs an action layout with direction parameters"
    ):
        HFOPolicy(
            OBS_SPACE,
            spaces.Box(0.0, 1.0, (5,)),
            lambda _: 1e-3,
            critic_action_encoding=DirectionFeatures(frequencies=(1,)),
        )
    with pytest.raises(
        ValueError,
        match="critic_action_encoding relative_to 'goalie' needs observation column .*goalie tasks",
    ):
        make_policy(critic_action_encoding=DirectionFeatures(frequencies=(1,), relative_to=("goalie",)))  # 58
    # The goal's landmarks are in every task's features.
    assert (
        make_policy(
            critic_action_encoding=DirectionFeatures((1,), ("goal_center",))
        ).critic.action_encoder.n_relative
        == 1
    )
    no_kick = HybridActionLayout(names=("DASH", "TURN"), parameter_sizes=(2, 1), direction_indices=(3, 4))
    assert ActionEncoder(5, DirectionFeatures((1, 2)), no_kick, 66).index.tolist() == [3, 4, 3, 4]
    with pytest.raises(ValueError, match="relative_to needs an action layout with a kick direction"):
        ActionEncoder(5, DirectionFeatures((1,), ("goalie",)), no_kick, 66)


# ----------------------------------------------------------------------------------------------------------
# Save / load


def test_a_model_saved_with_direction_features_loads_with_an_equal_encoding(tmp_path: Path) -> None:
    features = DirectionFeatures(frequencies=(1, 16))
    model = SkillDDPG(
        "HFOPolicy",
        HybridTargetEnv(),
        policy_kwargs=dict(net_arch=[16], critic_action_encoding=features),
        seed=0,
    )
    obs = batch_obs(4)
    action = th.rand(4, 8) * 2 - 1
    model.save(tmp_path / "m.zip")
    loaded = SkillDDPG.load(tmp_path / "m.zip")
    assert isinstance(loaded.policy.critic_action_encoding, DirectionFeatures)
    assert loaded.policy.critic_action_encoding == features
    assert loaded.policy.critic.action_encoder.out_dim == model.policy.critic.action_encoder.out_dim
    with th.no_grad():
        th.testing.assert_close(loaded.policy.critic(obs, action), model.policy.critic(obs, action))


def test_relative_kick_features_round_trip_in_the_dict_form_and_train(tmp_path: Path) -> None:
    model = SkillDDPG(
        "HFOPolicy",
        gym.make("HFO/StaticKeeper-v0"),
        policy_kwargs=dict(
            net_arch=[16],
            critic_action_encoding={"frequencies": [1, 16], "relative_to": ["goalie"]},
            domain="hfo",
        ),
        seed=0,
    )
    obs = batch_obs(4, seed=2, dim=66)
    action = th.rand(4, 8) * 2 - 1
    model.save(tmp_path / "m.zip")
    loaded = SkillDDPG.load(tmp_path / "m.zip")
    assert loaded.policy.critic_action_encoding == DirectionFeatures(
        frequencies=(1, 16), relative_to=("goalie",)
    )
    with th.no_grad():
        th.testing.assert_close(loaded.policy.critic(obs, action), model.policy.critic(obs, action))
    model.learn(300)  # the update path (explicit backward, target critic) runs with the relative features


def test_the_legacy_encoding_options_become_direction_features() -> None:
    """``critic_direction_frequencies`` / ``critic_kick_relative_to`` (the options the encoding replaced): folded
    into ``critic_action_encoding``, with a warning when given, and refused when they cannot be."""

    def folded(**kwargs: object) -> object:
        return translate_legacy_options(dict(net_arch=[8], **kwargs), warn=False)

    assert folded(critic_direction_frequencies=[1, 4], critic_kick_relative_to=["goalie"]) == {
        "net_arch": [8],
        "critic_action_encoding": {"frequencies": [1.0, 4.0], "relative_to": ["goalie"]},
    }
    assert folded(critic_direction_frequencies=[], critic_kick_relative_to=[]) == {
        "net_arch": [8],
        "critic_action_encoding": None,
    }
    with pytest.raises(ValueError, match="critic_kick_relative_to needs critic_direction_frequencies"):
        folded(critic_kick_relative_to=["goalie"])
    with pytest.raises(ValueError, match="cannot be combined"):
        folded(critic_direction_frequencies=[1], critic_action_encoding={"frequencies": [2]})
    env = gym.make("HFO/StaticKeeper-v0")
    with pytest.warns(DeprecationWarning, match="critic_direction_frequencies"):
        old = SkillDDPG(
            "HFOPolicy",
            env,
            seed=0,
            policy_kwargs=dict(
                net_arch=[16],
                critic_direction_frequencies=[1, 16],
                critic_kick_relative_to=["goalie"],
                domain="hfo",
            ),
        )
    assert old.policy.critic_action_encoding == DirectionFeatures((1, 16), ("goalie",))
    assert not set(old.policy_kwargs) & set(LEGACY_POLICY_OPTIONS)
    with warnings.catch_warnings():
        warnings.simplefilter("error", DeprecationWarning)
        new = SkillDDPG(
            "HFOPolicy",
            env,
            seed=0,
            policy_kwargs=dict(
                net_arch=[16], critic_action_encoding=DirectionFeatures((1, 16), ("goalie",)), domain="hfo"
            ),
        )
    obs, action = batch_obs(8, dim=66), random_actions(8)
    with th.no_grad():
        th.testing.assert_close(
            old.policy.critic(obs, action), new.policy.critic(obs, action), atol=0, rtol=0
        )
