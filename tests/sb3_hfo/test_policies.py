"""HFOPolicy / HFOActor / HFOCritic and the skill routers: architecture, initialisation, scales, routing, errors."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
import torch as th
from gymnasium import spaces
from torch import nn

from hfo2d.action_layout import hfo_flat_action_space
from sb3_hfo import (
    ROUTERS,
    FieldHalfRouter,
    HFOPolicy,
    SingleSkillRouter,
    SkillDDPG,
    SkillRouter,
    make_router,
)
from sb3_hfo.common.routers import field_half_router, validate_skills
from sb3_hfo.common.toy_env import HybridTargetEnv
from sb3_hfo.hfo import HFO_DOMAIN
from sb3_hfo.skill_ddpg.acting import CriticChoice, KickMask, MirrorChoice
from sb3_hfo.skill_ddpg.encoding import DirectionFeatures

OBS_SPACE = spaces.Box(-1.0, 1.0, (58,), np.float32)
ACTION_SPACE = hfo_flat_action_space()  # HFO's flat action, its layout declared


def make_policy(**kwargs: object) -> HFOPolicy:
    th.manual_seed(0)
    return HFOPolicy(OBS_SPACE, ACTION_SPACE, lambda _: 1e-3, **{"domain": "hfo", **kwargs})  # type: ignore[arg-type]


def linear_sizes(module: nn.Module) -> list[tuple[int, int]]:
    return [(m.in_features, m.out_features) for m in module.modules() if isinstance(m, nn.Linear)]


def batch_obs(n: int = 32, seed: int = 0) -> th.Tensor:
    return th.as_tensor(np.random.default_rng(seed).uniform(-1, 1, (n, 58)), dtype=th.float32)


# ----------------------------------------------------------------------------------------------------------
# Architecture (seed paper, Method / Figure 1)


def test_actor_layers_are_400_300_200_then_8_with_leaky_relu_and_tanh() -> None:
    policy = make_policy()
    actor = policy.actor
    assert linear_sizes(actor.trunk) == [(58, 400), (400, 300), (300, 200)]
    assert [linear_sizes(head) for head in actor.heads] == [[(200, 8)]]
    activations = [m for m in actor.trunk if not isinstance(m, nn.Linear)]
    assert len(activations) == 3
    assert all(isinstance(m, nn.LeakyReLU) and m.negative_slope == 0.01 for m in activations)
    # Each Linear of the trunk is followed by its activation; the output layer by tanh only.
    assert [type(m) for m in actor.trunk] == [nn.Linear, nn.LeakyReLU] * 3
    assert actor.squash
    with th.no_grad():
        out = actor(batch_obs())
    assert out.shape == (32, 8)
    assert float(out.abs().max()) < 1.0


def test_critic_injects_the_action_at_its_second_layer() -> None:
    policy = make_policy()
    critic = policy.critic
    assert linear_sizes(critic.obs_net) == [(58, 400)]
    assert linear_sizes(critic.joint_net) == [(408, 300), (300, 200), (200, 1)]
    assert [type(m) for m in critic.joint_net] == [
        nn.Linear,
        nn.LeakyReLU,
        nn.Linear,
        nn.LeakyReLU,
        nn.Linear,
    ]
    leaky = [m for m in critic.modules() if isinstance(m, nn.LeakyReLU)]
    assert len(leaky) == 3 and all(m.negative_slope == 0.01 for m in leaky)
    assert isinstance(critic.joint_net[-1], nn.Linear)  # no activation after Q

    seen: dict[str, th.Tensor] = {}
    handles = [
        critic.obs_net[0].register_forward_hook(lambda m, inp, out: seen.__setitem__("first", inp[0])),
        critic.action_layer.register_forward_hook(lambda m, inp, out: seen.__setitem__("second", inp[0])),
    ]
    obs, action = batch_obs(), th.rand(32, 8) * 2 - 1
    with th.no_grad():
        q = critic(obs, action)
    for handle in handles:
        handle.remove()
    assert q.shape == (32, 1)
    assert seen["first"].shape == (32, 58) and th.equal(seen["first"], obs)  # state only at layer one
    assert seen["second"].shape == (32, 408)
    assert th.equal(seen["second"][:, 400:], action)  # the action enters at layer two
    assert float(seen["second"][:, :400].min()) >= -0.01 * float(seen["second"][:, :400].abs().max())


def test_net_arch_list_dict_and_hausknecht_stone_sizes() -> None:
    policy = make_policy(net_arch=dict(pi=[64, 32], qf=[48, 24, 12]))
    assert linear_sizes(policy.actor) == [(58, 64), (64, 32), (32, 8)]
    assert linear_sizes(policy.critic) == [(58, 48), (56, 24), (24, 12), (12, 1)]
    hs = make_policy(net_arch=[1024, 512, 256, 128], inverting_gradients=True)
    assert linear_sizes(hs.actor.trunk) == [(58, 1024), (1024, 512), (512, 256), (256, 128)]
    assert linear_sizes(hs.critic.joint_net)[0] == (1032, 512)
    for bad in ([], [0, 4], dict(pi=[4]), "400-300", [4.5]):
        with pytest.raises(ValueError, match="net_arch"):
            make_policy(net_arch=bad)


def test_weights_truncated_normal_std_1e_2_and_zero_biases() -> None:
    policy = make_policy()
    weights = th.cat(
        [m.weight.detach().flatten() for m in policy.critic.modules() if isinstance(m, nn.Linear)]
    )
    assert float(weights.abs().max()) <= 0.02  # truncated at two standard deviations
    # Std of N(0, 0.01) truncated at +-2 sigma is 0.0088.
    assert 0.0083 < float(weights.std()) < 0.0093
    assert all(
        float(m.bias.detach().abs().max()) == 0.0 for m in policy.modules() if isinstance(m, nn.Linear)
    )
    # Targets start as exact copies.
    for online, target in zip(policy.actor.parameters(), policy.actor_target.parameters(), strict=True):
        assert th.equal(online, target) and not target.requires_grad


def test_env_action_is_sigmoid_of_twice_the_last_linear_layer() -> None:
    policy = make_policy(net_arch=[64, 64])
    for (
        layer
    ) in policy.actor.modules():  # larger outputs than the paper's init, so the sigmoid is not just 0.5
        if isinstance(layer, nn.Linear):
            nn.init.normal_(layer.weight, std=1.0)
    obs = batch_obs(8)
    with th.no_grad():
        z = policy.actor.heads[0](policy.actor.trunk(obs))
    env_action, _ = policy.predict(obs.numpy(), deterministic=True)
    np.testing.assert_allclose(env_action, th.sigmoid(2 * z).numpy(), atol=1e-6)
    assert env_action.min() < 0.05 and env_action.max() > 0.95


def test_critic_sees_one_scale_from_buffer_and_actor() -> None:
    """Actions stored by acting (buffer) and actions produced by the actor in an update are the same numbers."""
    env = HybridTargetEnv()
    model = SkillDDPG(
        "HFOPolicy",
        env,
        learning_starts=0,
        gradient_steps=0,  # act with the policy, never update: the actor stays fixed
        exploration_initial_eps=0.0,
        exploration_final_eps=0.0,
        seed=0,
        policy_kwargs=dict(net_arch=[32, 32]),
    )
    for layer in model.policy.actor.modules():
        if isinstance(layer, nn.Linear):
            nn.init.normal_(layer.weight, std=1.0)
    model.learn(200)
    buffer = model.replay_buffer
    assert buffer is not None
    stored_obs = th.as_tensor(buffer.observations[: buffer.pos, 0])
    stored_actions = th.as_tensor(buffer.actions[: buffer.pos, 0])
    with th.no_grad():
        actor_actions = model.policy.actor(stored_obs)
    # Identical up to float32 rounding of SB3's unscale (to [0, 1]) / rescale (back to [-1, 1]) round trip.
    th.testing.assert_close(stored_actions, actor_actions, atol=1e-5, rtol=0)
    for actions in (stored_actions, actor_actions):
        assert float(actions.min()) >= -1.0 and float(actions.max()) <= 1.0
        assert float(actions.min()) < -0.9 and float(actions.max()) > 0.9  # both reach the ends of [-1, 1]
    # Random warm-up actions (uniform in the env's Box [0, 1]) are stored in the same [-1, 1] scale.
    warm = SkillDDPG("HFOPolicy", env, learning_starts=300, seed=0, policy_kwargs=dict(net_arch=[8]))
    warm.learn(300)
    assert warm.replay_buffer is not None
    random_actions = warm.replay_buffer.actions[:300, 0]
    assert random_actions.min() < -0.95 and random_actions.max() > 0.95
    assert random_actions.min() >= -1.0 and random_actions.max() <= 1.0


def test_inverting_gradients_actor_is_linear_and_acting_clips() -> None:
    policy = make_policy(net_arch=[16], inverting_gradients=True)
    assert not policy.actor.squash
    with th.no_grad():
        policy.actor.heads[0].weight.fill_(0.0)
        policy.actor.heads[0].bias.copy_(th.tensor([3.0, -3.0, 0.5, 0, 0, 0, 0, 0]))
    obs = batch_obs(4)
    with th.no_grad():
        raw = policy.actor(obs)
    assert float(raw.max()) == pytest.approx(3.0) and float(raw.min()) == pytest.approx(-3.0)
    env_action, _ = policy.predict(obs.numpy(), deterministic=True)
    np.testing.assert_allclose(env_action[0, :3], [1.0, 0.0, 0.75], atol=1e-6)


# ----------------------------------------------------------------------------------------------------------
# Skills


def test_each_row_uses_its_own_skill_head() -> None:
    policy = make_policy(net_arch=[16, 16], n_skills=2)
    for layer in policy.actor.modules():
        if isinstance(layer, nn.Linear):
            nn.init.normal_(layer.weight, std=0.5)
    obs = batch_obs(64)
    skills = policy.route(obs)
    assert skills is not None
    expected_skills = (obs[:, 46] <= 0).long()
    assert th.equal(skills, expected_skills) and 0 < int(skills.sum()) < 64
    with th.no_grad():
        chosen = policy.actor(obs, skills)
        every = policy.actor.all_skills(obs)
    th.testing.assert_close(chosen, every[th.arange(64), skills])
    assert not th.allclose(every[:, 0], every[:, 1])
    # The policy's greedy action uses the routed head too.
    th.testing.assert_close(policy._predict(obs), chosen)


def test_optimizers_one_per_skill_over_trunk_and_own_head() -> None:
    policy = make_policy(net_arch=[16, 8], n_skills=3, skill_router=FieldHalfRouter3())
    trunk = {id(p) for p in policy.actor.trunk.parameters()}
    for k, optimizer in enumerate(policy.actor_optimizers):
        assert optimizer is getattr(policy, f"actor_skill_{k}_optimizer")
        owned = {id(p) for group in optimizer.param_groups for p in group["params"]}
        assert owned == trunk | {id(p) for p in policy.actor.heads[k].parameters()}
        assert isinstance(optimizer, th.optim.Adam) and optimizer.defaults["fused"]
    critic_owned = {id(p) for group in policy.critic_optimizer.param_groups for p in group["params"]}
    assert critic_owned == {id(p) for p in policy.critic.parameters()}


class FieldHalfRouter3(SkillRouter):
    """Three bands of the x feature (for tests)."""

    n_skills = 3

    def __call__(self, obs: np.ndarray | th.Tensor) -> np.ndarray | th.Tensor:
        x = obs[..., 46]
        if isinstance(x, th.Tensor):
            return (x < 0.3).long() + (x < -0.3).long()
        return (x < 0.3).astype(np.int64) + (x < -0.3).astype(np.int64)


# ----------------------------------------------------------------------------------------------------------
# Routers


def test_field_half_router_splits_at_x_feature_zero() -> None:
    router = field_half_router(HFO_DOMAIN)
    obs = np.zeros((4, 58), np.float32)
    obs[:, 46] = [0.9, 1e-6, 0.0, -0.5]  # obs[46] > 0  <=>  agent x < 26.25 m  <=>  skill 0
    np.testing.assert_array_equal(router(obs), [0, 0, 1, 1])
    assert router(obs).dtype == np.int64
    as_tensor = router(th.as_tensor(obs))
    assert isinstance(as_tensor, th.Tensor) and as_tensor.dtype == th.long
    assert as_tensor.tolist() == [0, 0, 1, 1]
    np.testing.assert_array_equal(router.numpy_route(obs), [0, 0, 1, 1])
    np.testing.assert_array_equal(SingleSkillRouter()(obs), [0, 0, 0, 0])
    with pytest.raises(ValueError, match="only 10 features"):
        router(np.zeros((2, 10), np.float32))


def test_field_half_router_matches_hfo_observation() -> None:
    import hfo2d  # noqa: F401

    env = gym.make("HFO/EmptyGoal-v0")
    router = field_half_router(HFO_DOMAIN)
    for x, skill in ((10.0, 0), (26.0, 0), (27.0, 1), (45.0, 1)):
        obs, _ = env.reset(seed=0, options={"player": (x, 0.0, 0.0), "ball": (x + 2.0, 0.0)})
        assert int(router.numpy_route(obs[None])[0]) == skill, x
    env.close()


def test_router_names_and_consistency_errors() -> None:
    assert set(ROUTERS) == {"single", "field_half"}
    assert make_router("field_half", 2, "hfo") == FieldHalfRouter(HFO_DOMAIN.field_half_column, 0.0)
    assert isinstance(make_router(None, 1), SingleSkillRouter)
    assert isinstance(make_router(None, 2, HFO_DOMAIN), FieldHalfRouter)
    # the field-half rule is the domain's: without one, the router is refused by name
    with pytest.raises(ValueError, match="'field_half' skill router needs a domain.*generic domain"):
        make_router(None, 2)
    with pytest.raises(ValueError, match=r"Unknown skill_router 'halves'.*\['field_half', 'single'\]"):
        make_router("halves", 2)
    with pytest.raises(ValueError, match="routes to 2 skill.*n_skills=1"):
        make_router("field_half", 1, "hfo")
    with pytest.raises(ValueError, match="routes to 1 skill.*n_skills=2"):
        make_router("single", 2)
    with pytest.raises(ValueError, match="n_skills=3 needs an explicit skill_router"):
        make_router(None, 3)
    for bad in (0, -1, 1.5, True):
        with pytest.raises(ValueError, match="n_skills must be an integer >= 1"):
            make_router(None, bad)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="callable"):
        make_router(object(), 1)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="n_skills"):
        make_router(lambda obs: obs[:, 0], 2)  # type: ignore[arg-type]
    # The same checks surface from the policy.
    with pytest.raises(ValueError, match="Unknown skill_router"):
        make_policy(n_skills=2, skill_router="nope")


class BadRouter(SkillRouter):
    n_skills = 2

    def __init__(self, mode: str) -> None:
        self.mode = mode

    def __call__(self, obs: np.ndarray | th.Tensor) -> np.ndarray | th.Tensor:
        n = obs.shape[0]
        if self.mode == "range":
            return th.full((n,), 2, dtype=th.long)
        if self.mode == "negative":
            return th.full((n,), -1, dtype=th.long)
        if self.mode == "shape":
            return th.zeros((n, 1), dtype=th.long)
        return th.zeros(n)  # float


@pytest.mark.parametrize(
    ("mode", "message"),
    [
        ("range", r"skill indices in \[2, 2\].*\[0, 2\)"),
        ("negative", r"skill indices in \[-1, -1\]"),
        ("shape", r"returned shape \(5, 1\).*expected \(5,\)"),
        ("float", "integer skill indices"),
    ],
)
def test_router_output_is_validated_at_first_call(mode: str, message: str) -> None:
    policy = make_policy(net_arch=[8], n_skills=2, skill_router=BadRouter(mode))
    with pytest.raises(ValueError, match=message):
        policy.predict(np.zeros((5, 58), np.float32))
    with pytest.raises(ValueError, match=message):
        policy.numpy_route(np.zeros((5, 58), np.float32))
    with pytest.raises(ValueError, match="must return an array"):
        validate_skills([0, 1], 2, 2, "router")


class SwitchableRouter(SkillRouter):
    """Routes by ``obs[:, 46]`` (FieldHalfRouter's rule) until ``index`` is set, then returns ``index`` everywhere."""

    n_skills = 2

    def __init__(self) -> None:
        self.index: int | None = None

    def __call__(self, obs: np.ndarray | th.Tensor) -> np.ndarray | th.Tensor:
        if self.index is None:
            return field_half_router(HFO_DOMAIN)(obs)
        if isinstance(obs, th.Tensor):
            return th.full((obs.shape[0],), self.index, dtype=th.long)
        return np.full(obs.shape[0], self.index, dtype=np.int64)


@pytest.mark.parametrize("index", [-1, 2])
@pytest.mark.parametrize("batch", [1, 4])
def test_router_output_is_validated_on_every_call(index: int, batch: int) -> None:
    router = SwitchableRouter()
    policy = make_policy(net_arch=[8], n_skills=2, skill_router=router)
    obs = np.zeros((batch, 58), np.float32)
    policy.predict(obs, deterministic=True)  # a valid first call
    assert policy.numpy_route(obs).tolist() == [1] * batch
    router.index = index
    message = rf"skill indices in \[{index}, {index}\].*\[0, 2\)"
    with pytest.raises(ValueError, match=message):
        policy.predict(obs, deterministic=True)  # not routed to the last head
    with pytest.raises(ValueError, match=message):
        policy.route(th.as_tensor(obs))
    with pytest.raises(ValueError, match=message):
        policy.numpy_route(obs)


def test_router_objects_compare_and_pickle() -> None:
    import pickle

    router = FieldHalfRouter(feature_index=3, threshold=0.25)
    clone = pickle.loads(pickle.dumps(router))
    assert clone == router and clone != field_half_router(HFO_DOMAIN) and hash(clone) == hash(router)
    assert "feature_index=3" in repr(router)


# ----------------------------------------------------------------------------------------------------------
# Bad spaces


def test_policy_rejects_unsupported_spaces() -> None:
    with pytest.raises(ValueError, match="Box action space"):
        HFOPolicy(OBS_SPACE, spaces.Discrete(3), lambda _: 1e-3)
    with pytest.raises(ValueError, match="bounded Box"):
        HFOPolicy(OBS_SPACE, spaces.Box(-np.inf, np.inf, (2,)), lambda _: 1e-3)
    with pytest.raises(ValueError, match="Box observation space"):
        HFOPolicy(spaces.Discrete(4), ACTION_SPACE, lambda _: 1e-3)
    with pytest.raises(ValueError, match="weight_init_std"):
        make_policy(weight_init_std=0.0)


def test_parameter_mask_keeps_the_preferences_and_the_chosen_actions_parameters() -> None:
    policy = make_policy(mask_unused_parameters=True)
    assert policy.action_parameter_sizes == (2, 1, 2)
    actions = th.tensor(
        [
            [0.9, 0.1, 0.2, 0.5, -0.5, 0.7, -0.8, 0.9],  # DASH: dash power and direction kept
            [0.1, 0.9, 0.2, 0.5, -0.5, 0.7, -0.8, 0.9],  # TURN: turn direction kept
            [0.1, 0.2, 0.9, 0.5, -0.5, 0.7, -0.8, 0.9],  # KICK: kick power and direction kept
            [0.3, 0.3, 0.3, 0.5, -0.5, 0.7, -0.8, 0.9],  # a tie: the first maximum (DASH), as hfo2d decides
        ]
    )
    expected = th.tensor(
        [
            [0.9, 0.1, 0.2, 0.5, -0.5, 0.0, 0.0, 0.0],
            [0.1, 0.9, 0.2, 0.0, 0.0, 0.7, 0.0, 0.0],
            [0.1, 0.2, 0.9, 0.0, 0.0, 0.0, -0.8, 0.9],
            [0.3, 0.3, 0.3, 0.5, -0.5, 0.0, 0.0, 0.0],
        ]
    )
    assert th.equal(policy.critic_action(actions), expected)
    custom = HFOPolicy(OBS_SPACE, spaces.Box(0.0, 1.0, (5,)), lambda _: 1e-3, mask_unused_parameters=[0, 3])
    assert th.equal(
        custom.critic_action(th.tensor([[0.5, -0.5, 0.1, 0.2, 0.3], [-0.5, 0.5, 0.1, 0.2, 0.3]])),
        th.tensor([[0.5, -0.5, 0.0, 0.0, 0.0], [-0.5, 0.5, 0.1, 0.2, 0.3]]),
    )
    unmasked = make_policy()
    assert unmasked.parameter_mask(actions) is None and unmasked.critic_action(actions) is actions
    # Not saved in the state dict: models saved without the option load unchanged.
    assert "parameter_masks" not in policy.state_dict()


def test_mask_unused_parameters_errors_name_the_problem() -> None:
    with pytest.raises(
        ValueError, match="needs the action space's hybrid layout.*5-entry action space declares none"
    ):
        HFOPolicy(OBS_SPACE, spaces.Box(0.0, 1.0, (5,)), lambda _: 1e-3, mask_unused_parameters=True)
    with pytest.raises(ValueError, match=r"3 preferences \+ 4 parameters = 7 action entries.*has 8"):
        make_policy(mask_unused_parameters=(2, 1, 1))
    with pytest.raises(ValueError, match="ints >= 0"):
        make_policy(mask_unused_parameters=(2, -1, 4))
    with pytest.raises(ValueError, match="a bool or a sequence of ints"):
        make_policy(mask_unused_parameters="kick")


@pytest.mark.parametrize("mask", [False, True])
def test_critic_choice_plays_the_best_one_hot_action_at_the_actors_parameters(mask: bool) -> None:
    # Large initial weights: a critic far from linear, so that rows differ in their best action.
    policy = make_policy(
        mask_unused_parameters=mask, acting=(CriticChoice(),), net_arch=[32, 16], weight_init_std=1.0
    )
    obs = batch_obs(64)
    with th.no_grad():
        actor_actions = policy.actor(obs)
        chosen = policy._predict(obs)
        q_each = []
        for j in range(3):  # the same choice worked out candidate by candidate
            candidate = actor_actions.clone()
            candidate[:, :3] = -1.0
            candidate[:, j] = 1.0
            q_each.append(policy.critic(obs, policy.critic_action(candidate)).squeeze(1))
    best = th.stack(q_each, dim=1).argmax(dim=1)
    assert len(set(best.tolist())) > 1  # the batch exercises more than one choice
    assert th.equal(chosen[:, :3], 2.0 * nn.functional.one_hot(best, 3).float() - 1.0)
    assert th.equal(chosen[:, 3:], actor_actions[:, 3:])  # the parameters stay the actor's
    policy.acting = ()  # switchable on a built policy: the actor picks again
    with th.no_grad():
        assert th.equal(policy._predict(obs), actor_actions)


def test_critic_choice_errors_and_round_trip(tmp_path) -> None:
    with pytest.raises(ValueError, match="unknown acting token 'router'"):
        make_policy(acting="router")
    with pytest.raises(
        ValueError, match="CriticChoice needs the discrete actions: an action space with a hybrid layout"
    ):
        HFOPolicy(OBS_SPACE, spaces.Box(0.0, 1.0, (5,)), lambda _: 1e-3, acting=(CriticChoice(),))
    policy = HFOPolicy(
        OBS_SPACE,
        spaces.Box(0.0, 1.0, (5,)),
        lambda _: 1e-3,
        mask_unused_parameters=(0, 3),
        acting=(CriticChoice(),),
    )
    assert policy.n_discrete_actions == 2
    env = HybridTargetEnv()
    model = SkillDDPG(
        "HFOPolicy",
        env,
        policy_kwargs=dict(net_arch=[16], mask_unused_parameters=True, acting="critic"),
        n_discrete_actions=3,
        seed=0,
    )
    obs = np.random.default_rng(0).uniform(-1, 1, (5, *env.observation_space.shape)).astype(np.float32)
    model.save(tmp_path / "m.zip")
    loaded = SkillDDPG.load(tmp_path / "m.zip")
    assert loaded.policy.acting == (CriticChoice(),)
    assert np.array_equal(
        loaded.predict(obs, deterministic=True)[0], model.predict(obs, deterministic=True)[0]
    )


def test_kickable_feature_index_is_hfo2ds() -> None:
    from hfo2d import features

    assert HFO_DOMAIN.kickable_column == features.KICKABLE


@pytest.mark.parametrize("choice", ["actor", "critic"])
def test_kick_mask_never_kicks_at_a_ball_out_of_reach(choice: str) -> None:
    policy = make_policy(
        mask_unused_parameters=True,
        acting=(CriticChoice(),) if choice == "critic" else (),
        net_arch=[32, 16],
        weight_init_std=1.0,
    )
    obs = batch_obs(256)
    obs[:, HFO_DOMAIN.kickable_column] = th.where(obs[:, HFO_DOMAIN.kickable_column] > 0, 1.0, -1.0)
    out_of_reach = obs[:, HFO_DOMAIN.kickable_column] < 0
    with th.no_grad():
        free = policy._predict(obs)
        policy.acting = (*policy.acting, KickMask())
        masked = policy._predict(obs)
    free_kicks = free[:, :3].argmax(dim=1) == 2
    assert (free_kicks & out_of_reach).any()  # the batch exercises the rule
    assert not (masked[:, :3].argmax(dim=1) == 2)[out_of_reach].any()
    # Where the ball is kickable, or the free choice was not KICK, nothing changes.
    unchanged = ~out_of_reach | ~free_kicks
    assert th.equal(masked[unchanged], free[unchanged])
    # Elsewhere: the one-hot of the better of DASH and TURN (by preference or by Q), parameters kept.
    changed = ~unchanged
    assert th.equal(masked[changed][:, 3:], free[changed][:, 3:])
    if choice == "actor":
        best = free[changed][:, :2].argmax(dim=1)
    else:
        with th.no_grad():
            _, q_values = policy.discrete_values(obs[changed], free[changed])
        best = q_values[:, :2].argmax(dim=1)
    assert th.equal(masked[changed][:, :3], 2.0 * nn.functional.one_hot(best, 3).float() - 1.0)


def test_kick_mask_errors_and_round_trip(tmp_path) -> None:
    with pytest.raises(ValueError, match="KickMask needs an action layout with a ball action"):
        HFOPolicy(OBS_SPACE, spaces.Box(0.0, 1.0, (5,)), lambda _: 1e-3, acting=(KickMask(),), domain="hfo")
    with pytest.raises(
        ValueError, match="KickMask needs a domain with the observation column.*generic domain"
    ):
        HFOPolicy(OBS_SPACE, ACTION_SPACE, lambda _: 1e-3, acting=(KickMask(),))
    with pytest.raises(ValueError, match="acting takes CriticChoice, KickMask and MirrorChoice objects"):
        make_policy(acting=["kick_mask"])  # the token, not the strategy
    model = SkillDDPG(
        "HFOPolicy",
        HybridTargetEnv(),
        policy_kwargs=dict(net_arch=[16], acting="kick_mask,critic", domain="hfo"),
        seed=0,
    )
    model.save(tmp_path / "m.zip")
    assert SkillDDPG.load(tmp_path / "m.zip").policy.acting == (CriticChoice(), KickMask())


GOALIE_OBS_SPACE = spaces.Box(-1.0, 1.0, (66,), np.float32)


def make_goalie_policy(**kwargs: object) -> HFOPolicy:
    th.manual_seed(0)
    return HFOPolicy(GOALIE_OBS_SPACE, ACTION_SPACE, lambda _: 1e-3, **{"domain": "hfo", **kwargs})  # type: ignore[arg-type]


# ----------------------------------------------------------------------------------------------------------
# The better of the state and its mirror image (beyond the paper)


@pytest.mark.parametrize("choice", ["actor", "critic"])
def test_mirror_choice_plays_the_better_of_the_state_and_its_mirror_image(choice: str) -> None:
    from hfo2d.symmetry import mirror_features

    policy = make_goalie_policy(
        net_arch=[32, 16],
        n_skills=2,
        mask_unused_parameters=True,
        acting=(CriticChoice(), KickMask()) if choice == "critic" else (KickMask(),),
    )
    obs = th.as_tensor(np.random.default_rng(3).uniform(-1, 1, (64, 66)), dtype=th.float32)
    mirrored_obs = th.as_tensor(mirror_features(obs.numpy()))
    with th.no_grad():
        plain = policy._predict(obs)
        in_mirror = policy._predict(mirrored_obs)
        plain_q = policy.critic(obs, policy.critic_action(plain))
        mirror_q = policy.critic(mirrored_obs, policy.critic_action(in_mirror))
        policy.acting = (*policy.acting, MirrorChoice())
        chosen = policy._predict(obs)
    signs = th.tensor([1, 1, 1, 1, -1, -1, 1, -1], dtype=th.float32)
    expected = th.where(mirror_q > plain_q, in_mirror * signs, plain)
    assert 5 < int((mirror_q > plain_q).sum()) < 59  # both kinds of rows are tested
    th.testing.assert_close(chosen, expected)


def test_mirror_choice_keeps_a_state_that_is_its_own_mirror_image() -> None:
    policy = make_policy(net_arch=[16], acting=(CriticChoice(), MirrorChoice()))
    obs = th.zeros(4, 58)  # every sine 0: symmetric
    obs[:, 14] = 1.0
    with th.no_grad():
        chosen = policy._predict(obs)
        policy.acting = (CriticChoice(),)
        th.testing.assert_close(chosen, policy._predict(obs))


def test_mirror_choice_errors_and_round_trip(tmp_path) -> None:
    with pytest.raises(ValueError, match=r"acting MirrorChoice needs the hfo domain's flat action"):
        HFOPolicy(
            OBS_SPACE, spaces.Box(0.0, 1.0, (5,)), lambda _: 1e-3, acting=(MirrorChoice(),), domain="hfo"
        )
    with pytest.raises(ValueError, match="acting MirrorChoice needs a domain that knows its mirror image"):
        HFOPolicy(OBS_SPACE, ACTION_SPACE, lambda _: 1e-3, acting=(MirrorChoice(),))
    with pytest.raises(
        ValueError, match=r"acting MirrorChoice: an HFO feature vector has 58 \+ 8 \* players entries"
    ):
        HFOPolicy(
            spaces.Box(-1.0, 1.0, (60,)), ACTION_SPACE, lambda _: 1e-3, acting=(MirrorChoice(),), domain="hfo"
        )
    with pytest.raises(ValueError, match="acting names mirror more than once"):
        make_policy(acting=(MirrorChoice(), MirrorChoice(0.5)))
    model = SkillDDPG("HFOPolicy", HybridTargetEnv(), policy_kwargs=dict(net_arch=[16], domain="hfo"), seed=0)
    model.policy.acting = (MirrorChoice(),)  # acting strategies switched on a built model are saved with it
    model.policy.acting = (CriticChoice(), KickMask(), *model.policy.acting)
    model.save(tmp_path / "m.zip")
    loaded = SkillDDPG.load(tmp_path / "m.zip")
    assert loaded.policy.acting == (CriticChoice(), KickMask(), MirrorChoice(0.0))
    obs = batch_obs(8).numpy()
    np.testing.assert_array_equal(model.predict(obs)[0], loaded.predict(obs)[0])


def mirror_margin_setup() -> tuple[HFOPolicy, np.ndarray, th.Tensor, th.Tensor, th.Tensor]:
    """A goalie-layout policy with the mirror choice, 64 random states, the plain and the mirrored greedy actions (in
    [-1, 1], the mirrored one mapped back) and the gain of the mirrored side, mirror Q - plain Q, per row."""
    from hfo2d.symmetry import mirror_features

    policy = make_goalie_policy(net_arch=[32, 16], mask_unused_parameters=True, acting=(CriticChoice(),))
    obs = np.random.default_rng(5).uniform(-1, 1, (64, 66)).astype(np.float32)
    mirrored_obs = th.as_tensor(mirror_features(obs))
    with th.no_grad():
        plain = policy._predict(th.as_tensor(obs))
        in_mirror = policy._predict(mirrored_obs)
        gain = policy.critic(mirrored_obs, policy.critic_action(in_mirror)) - policy.critic(
            th.as_tensor(obs), policy.critic_action(plain)
        )
    policy.acting = (*policy.acting, MirrorChoice())
    signs = th.tensor([1, 1, 1, 1, -1, -1, 1, -1], dtype=th.float32)
    return policy, obs, plain, in_mirror * signs, gain.squeeze(1)


def test_mirror_margin_keeps_the_side_unless_the_other_is_better_by_the_margin() -> None:
    policy, obs, plain, mirrored, gain = mirror_margin_setup()
    margin = float(gain.abs().median())
    policy.acting = (CriticChoice(), MirrorChoice(margin))

    def played(sides: th.Tensor) -> np.ndarray:
        return policy.unscale_action(th.where(sides.unsqueeze(1), mirrored, plain).numpy())

    # No state, or a new episode: the better side, as without a margin; the sides come back as the state.
    actions, (sides,) = policy.predict(obs)
    np.testing.assert_array_equal(sides, (gain > 0).numpy().astype(np.float32))
    np.testing.assert_allclose(actions, played(gain > 0), atol=1e-6)
    _, (restarted,) = policy.predict(obs, state=(np.ones(64),), episode_start=np.ones(64, dtype=bool))
    np.testing.assert_array_equal(restarted, sides)
    # Kept mirrored: back to plain only where plain is better by more than the margin; kept plain: the reverse.
    for kept, switch in ((1.0, -gain > margin), (0.0, gain > margin)):
        state = (np.full(64, kept, dtype=np.float32),)
        actions, (sides,) = policy.predict(obs, state=state, episode_start=np.zeros(64, dtype=bool))
        expected = th.full((64,), bool(kept)) ^ switch
        assert 5 < int(switch.sum()) < 59  # rows that switch and rows that stay
        np.testing.assert_array_equal(sides, expected.numpy().astype(np.float32))
        np.testing.assert_allclose(actions, played(expected), atol=1e-6)
    # inf: the side of the episode's first step is kept whatever the values; a one-row state for one observation.
    policy.acting = (CriticChoice(), MirrorChoice(float("inf")))
    action, (side,) = policy.predict(obs[0], state=(np.ones(1),), episode_start=np.zeros(1, dtype=bool))
    assert action.shape == (8,) and side.tolist() == [1.0]
    np.testing.assert_allclose(action, played(th.ones(64, dtype=th.bool))[0], atol=1e-6)


def test_mirror_margin_zero_decides_every_step_and_passes_the_state_through() -> None:
    policy, obs, plain, mirrored, gain = mirror_margin_setup()
    state = (np.ones(64, dtype=np.float32),)
    actions, returned = policy.predict(obs, state=state, episode_start=np.zeros(64, dtype=bool))
    assert returned is state  # SB3's contract when the policy keeps no state
    expected = th.where((gain > 0).unsqueeze(1), mirrored, plain).numpy()
    np.testing.assert_allclose(actions, policy.unscale_action(expected), atol=1e-6)


def test_mirror_margin_errors_and_round_trip(tmp_path) -> None:
    for bad in (-0.1, float("nan")):
        with pytest.raises(ValueError, match="MirrorChoice margin must be"):
            make_policy(acting=f"mirror:{bad}")
    for bad in ("0.1", True):
        with pytest.raises(ValueError, match="MirrorChoice margin must be"):
            MirrorChoice(bad)  # type: ignore[arg-type]
    policy, obs, _, _, _ = mirror_margin_setup()
    policy.acting = (CriticChoice(), MirrorChoice(0.5))
    with pytest.raises(ValueError, match="state has 3 sides but the observation batch has 64 rows"):
        policy.predict(obs, state=(np.zeros(3),))
    with pytest.raises(ValueError, match="episode_start has 2 entries but state has 64 sides"):
        policy.predict(obs, state=(np.zeros(64),), episode_start=np.zeros(2, dtype=bool))
    with pytest.raises(
        ValueError, match=r"state must be the \(sides,\) tuple returned by the previous predict"
    ):
        policy.predict(obs, state=np.zeros(64))  # type: ignore[arg-type]
    model = SkillDDPG(
        "HFOPolicy",
        HybridTargetEnv(),
        policy_kwargs=dict(net_arch=[16], acting="mirror", domain="hfo"),
        seed=0,
    )
    model.policy.acting = (MirrorChoice(0.25),)
    model.save(tmp_path / "m.zip")
    assert SkillDDPG.load(tmp_path / "m.zip").policy.acting == (MirrorChoice(0.25),)


def test_a_plain_box_without_a_layout_gets_plain_ddpg_semantics() -> None:
    """An 8-entry ``Box`` that declares no hybrid layout is not taken for HFO's flat action: no discrete actions,
    the actor's output played as it is, and the options that need the layout refused."""
    plain = spaces.Box(0.0, 1.0, (8,), np.float32)
    policy = HFOPolicy(OBS_SPACE, plain, lambda _: 1e-3)
    assert policy.action_layout is None and policy.n_discrete_actions == 0
    obs = th.rand(4, 58) * 2 - 1
    th.testing.assert_close(policy._predict(obs), policy.actor(obs))
    for option in (
        {"mask_unused_parameters": True},
        {"acting": (CriticChoice(),)},
        {"acting": (KickMask(),)},
        {"critic_action_encoding": DirectionFeatures(frequencies=(1,))},
    ):
        with pytest.raises(ValueError):
            HFOPolicy(OBS_SPACE, plain, lambda _: 1e-3, **option)
    assert SkillDDPG("HFOPolicy", "Pendulum-v1", seed=0)._n_discrete == 0
