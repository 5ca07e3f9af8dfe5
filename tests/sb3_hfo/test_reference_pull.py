"""HybridPPO started from a reference policy: the hybrid KL, the pull toward the reference and its decaying
coefficient, the critic warm-up, squashed means and distillation."""

from __future__ import annotations

import copy
from typing import Any

import numpy as np
import pytest
import torch as th
from stable_baselines3.common.env_util import make_vec_env

from sb3_hfo.common.schedules import DecayToZero
from sb3_hfo.common.toy_env import HybridTargetEnv
from sb3_hfo.hybrid_ppo import HybridDistribution, HybridPPO
from sb3_hfo.hybrid_ppo.distill import distill
from sb3_hfo.hybrid_ppo.distributions import hybrid_kl

SMALL = {"n_steps": 32, "batch_size": 64, "n_epochs": 2, "policy_kwargs": {"net_arch": [16]}}


def _random_distribution(gen: th.Generator, mask: th.Tensor, batch: int = 5) -> HybridDistribution:
    k, p = mask.shape
    return HybridDistribution(
        th.randn(batch, k, generator=gen),
        th.randn(batch, p, generator=gen),
        th.randn(p, generator=gen) * 0.5,
        mask,
    )


def test_hybrid_kl_matches_torch_distributions_and_is_zero_for_itself() -> None:
    gen = th.Generator().manual_seed(0)
    mask = th.tensor([[1.0, 1.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]])  # action 1 reads no parameter
    reference, current = _random_distribution(gen, mask), _random_distribution(gen, mask)
    kl = hybrid_kl(reference, current)
    categorical = th.distributions.kl_divergence(
        th.distributions.Categorical(logits=reference.log_pi),
        th.distributions.Categorical(logits=current.log_pi),
    )
    gaussians = th.distributions.kl_divergence(
        th.distributions.Normal(reference.mean, reference.log_std.exp()),
        th.distributions.Normal(current.mean, current.log_std.exp()),
    )  # (B, P)
    pi = reference.log_pi.exp()
    expected = categorical + sum(pi[:, k] * (gaussians * mask[k]).sum(dim=-1) for k in range(3))
    assert th.allclose(kl, expected, atol=1e-5)
    assert (kl > 0).all()
    assert th.allclose(hybrid_kl(reference, reference), th.zeros(5), atol=1e-6)
    with pytest.raises(ValueError, match="same shape"):
        hybrid_kl(reference, _random_distribution(gen, mask, batch=4))


def test_decay_to_zero_falls_linearly_then_stays_at_zero() -> None:
    schedule = DecayToZero(2.0, 0.5)  # progress_remaining: 1 at the start, 0 at the end
    assert [schedule(p) for p in (1.0, 0.75, 0.5, 0.25, 0.0)] == [2.0, 1.0, 0.0, 0.0, 0.0]
    assert DecayToZero(1.0, 1.0)(0.3) == pytest.approx(0.3)
    for bad in [(-1.0, 0.5), (1.0, 0.0), (1.0, 1.5), (float("nan"), 0.5)]:
        with pytest.raises(ValueError, match="DecayToZero"):
            DecayToZero(*bad)


def _model(**kwargs: Any) -> HybridPPO:
    env = make_vec_env(HybridTargetEnv, n_envs=4, seed=0)
    return HybridPPO("MlpPolicy", env, seed=0, **{**SMALL, **kwargs})


def _kl_to_reference(model: HybridPPO, obs: th.Tensor) -> float:
    with th.no_grad():
        return model.reference_kl(obs).mean().item()


def test_the_pull_is_zero_for_the_reference_itself_and_moves_the_policy_toward_it() -> None:
    obs = th.as_tensor(np.stack([HybridTargetEnv().reset(seed=i)[0] for i in range(64)]))
    model = _model(reference_coef=50.0, learning_rate=3e-3, n_epochs=8)
    model.set_reference(copy.deepcopy(model.policy))
    assert _kl_to_reference(model, obs) == pytest.approx(0.0, abs=1e-7)
    # a reference far from the policy: its heads' logits and means shifted, its log stds halved
    reference = copy.deepcopy(model.policy)
    with th.no_grad():
        for head in reference.heads:
            head.linear.bias += th.tensor([2.0, -1.0, 0.0, 0.5, -0.5, 0.3, 0.8, 0.0])
            head.log_std -= 0.5
    model.set_reference(reference)
    assert not any(parameter.requires_grad for parameter in reference.parameters())
    before = _kl_to_reference(model, obs)
    unpulled = _model(learning_rate=3e-3, n_epochs=8)  # the same run without the pull
    unpulled.set_reference(copy.deepcopy(reference))
    model.learn(512)
    unpulled.learn(512)
    assert _kl_to_reference(model, obs) < 0.5 * before
    assert _kl_to_reference(model, obs) < 0.5 * _kl_to_reference(unpulled, obs)
    assert model.logger.name_to_value["train/reference_coef"] == 50.0


def test_set_reference_rejects_another_action_layout_and_is_not_saved(tmp_path: Any) -> None:
    model = _model(reference_coef=DecayToZero(1.0, 0.5))
    other = HybridPPO("MlpPolicy", make_vec_env(lambda: _DiscreteToy(), n_envs=1), **SMALL)
    with pytest.raises(ValueError, match="differ"):
        model.set_reference(other.policy)
    with pytest.raises(ValueError, match="HybridActorCriticPolicy"):
        model.set_reference(object())  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="no reference policy"):
        model.reference_kl(th.zeros(1, 58))
    model.set_reference(copy.deepcopy(model.policy))
    model.save(tmp_path / "pulled.zip")
    loaded = HybridPPO.load(tmp_path / "pulled.zip")
    assert loaded.reference_policy is None
    assert loaded.reference_coef(1.0) == 1.0 and loaded.reference_coef(0.4) == 0.0


class _DiscreteToy(HybridTargetEnv):
    """HybridTargetEnv's observations with a plain Discrete action space (another action layout)."""

    def __init__(self) -> None:
        super().__init__()
        from gymnasium import spaces

        self.action_space = spaces.Discrete(3)

    def step(self, action: Any) -> Any:
        return self._obs.copy(), 0.0, True, False, {}


def test_the_critic_warm_up_leaves_the_actor_alone_then_lets_it_learn() -> None:
    model = _model(critic_warmup_steps=256)
    actor_before = copy.deepcopy(model.policy.heads.state_dict())
    trunk_before = copy.deepcopy(model.policy.actor_trunk.state_dict())
    value_before = model.policy.value_net.weight.detach().clone()
    model.learn(256)  # 2 rollouts of 4 x 32 steps: both inside the warm-up
    assert model.logger.name_to_value["train/critic_only"] == 1.0
    for key, value in model.policy.heads.state_dict().items():
        assert th.equal(value, actor_before[key]), key
    for key, value in model.policy.actor_trunk.state_dict().items():
        assert th.equal(value, trunk_before[key]), key
    assert not th.equal(model.policy.value_net.weight, value_before)
    model.learn(128, reset_num_timesteps=False)  # past the warm-up
    assert model.logger.name_to_value["train/critic_only"] == 0.0
    assert not th.equal(model.policy.heads[0].linear.weight, actor_before["0.linear.weight"])


def test_options_reject_bad_values() -> None:
    with pytest.raises(ValueError, match="reference_coef"):
        _model(reference_coef=-1.0)
    with pytest.raises(ValueError, match="critic_warmup_steps"):
        _model(critic_warmup_steps=-5)


def test_squashed_means_stay_inside_the_bounds_and_round_trip(tmp_path: Any) -> None:
    model = _model(policy_kwargs={"net_arch": [16], "squash_mean": True})
    with th.no_grad():
        model.policy.heads[0].linear.bias[3:] = 50.0  # far outside [-1, 1] before the tanh
    obs = th.zeros(3, 58)
    assert th.allclose(model.policy.action_distribution(obs).mean, th.ones(3, 5))
    model.save(tmp_path / "squashed.zip")
    loaded = HybridPPO.load(tmp_path / "squashed.zip")
    assert loaded.policy.squash_mean
    assert th.equal(loaded.policy.action_distribution(obs).mean, model.policy.action_distribution(obs).mean)


def test_distillation_teaches_a_teachers_choice_and_parameters() -> None:
    """The toy's correct action (DASH when the region feature is > 0, else KICK, with the target power) as labels."""
    env = HybridTargetEnv()
    model = _model()
    adapter = model.policy.adapter
    observations = np.stack([env.reset(seed=i)[0] for i in range(512)])
    region = observations[:, env.region_index]
    discrete = np.where(region > 0, 0, 2)
    parameters = np.zeros((512, adapter.n_parameters), dtype=np.float32)
    parameters[:, 0] = np.where(region > 0, 0.3, 0.0)  # DASH's power
    parameters[:, 3] = np.where(region > 0, 0.0, -0.6)  # KICK's power
    history = distill(
        model.policy, observations, discrete, parameters, epochs=30, batch_size=64, learning_rate=3e-3
    )
    assert history[-1]["loss"] < 0.2 * history[0]["loss"]
    assert history[-1]["agreement"] > 0.95
    with th.no_grad():
        greedy = model.policy.action_distribution(th.as_tensor(observations)).mode()
    assert (greedy[0].numpy() == discrete).mean() > 0.95
    with pytest.raises(ValueError, match="discrete labels"):
        distill(model.policy, observations, np.full(512, 7), parameters)
    with pytest.raises(ValueError, match="distill needs"):
        distill(model.policy, observations, discrete[:10], parameters)


def test_action_distribution_needs_a_hand_coded_router() -> None:
    model = _model(policy_kwargs={"net_arch": [16], "skills": 2, "router": "learned"})
    with pytest.raises(ValueError, match="hand-coded router"):
        model.policy.action_distribution(th.zeros(2, 58))
    with pytest.raises(ValueError, match="hand-coded router"):
        model.set_reference(copy.deepcopy(model.policy))
