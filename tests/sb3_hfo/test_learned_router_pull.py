"""A learned-router HybridPPO policy started from, and pulled toward, a hand-coded router's policy (issue 33 item 4):
the KL over (skill, action) of HybridPPO.reference_kl, hand_routed_copy, and distillation with skill labels."""

from __future__ import annotations

import copy
from typing import Any

import numpy as np
import pytest
import torch as th
from stable_baselines3.common.env_util import make_vec_env

from sb3_hfo.common.routers import FieldHalfRouter
from sb3_hfo.common.toy_env import HybridTargetEnv
from sb3_hfo.hybrid_ppo import HybridPPO
from sb3_hfo.hybrid_ppo.distill import distill
from sb3_hfo.hybrid_ppo.distributions import hybrid_kl

SMALL = {"n_steps": 32, "batch_size": 64, "n_epochs": 2}
#: the toy's region feature splits its states as field_half splits the field (r > 0: skill 0)
REGION_ROUTER = FieldHalfRouter(HybridTargetEnv().region_index)


def _model(router: Any = "learned", skills: int = 2, **kwargs: Any) -> HybridPPO:
    env = make_vec_env(HybridTargetEnv, n_envs=4, seed=0)
    policy_kwargs = {"net_arch": [16], "skills": skills, "router": router}
    return HybridPPO("MlpPolicy", env, seed=0, policy_kwargs=policy_kwargs, **{**SMALL, **kwargs})


def _observations(count: int) -> th.Tensor:
    env = HybridTargetEnv()
    return th.as_tensor(np.stack([env.reset(seed=i)[0] for i in range(count)]))


def _shifted_reference(model: HybridPPO) -> Any:
    """The model's trunk and heads routed by REGION_ROUTER, then moved: other logits, means and log stds."""
    reference = model.policy.hand_routed_copy(REGION_ROUTER)
    with th.no_grad():
        reference.heads[0].linear.bias += th.tensor([1.0, -0.5, 0.0, 0.4, -0.3, 0.2, 0.6, 0.1])
        reference.heads[1].linear.bias += th.tensor([-0.7, 0.8, 0.3, -0.2, 0.5, 0.0, -0.4, 0.3])
        reference.heads[0].log_std -= 0.4
        reference.heads[1].log_std += 0.2
    return reference


def test_the_pull_of_a_learned_router_is_the_monte_carlo_kl_over_skill_and_action() -> None:
    """KL(reference || pi) over (skill, k, u), estimated from the reference's own samples with both policies'
    log-probabilities (evaluate_actions, the path PPO's ratios use), matches reference_kl."""
    model = _model()
    with th.no_grad():
        model.policy.router_net.bias += th.tensor([0.6, -0.6])  # a router that disagrees often
    reference = _shifted_reference(model)
    model.set_reference(reference)
    states = _observations(4)
    with th.no_grad():
        exact = model.reference_kl(states)
        th.manual_seed(0)
        samples = 20_000
        for row in range(len(states)):
            obs = states[row : row + 1].expand(samples, -1)
            actions = reference._predict(obs, deterministic=False)  # [k, parameters]: the reference's action
            skill = (
                reference.routed_skills(obs).unsqueeze(-1).float()
            )  # the reference's skill, with certainty
            log_reference = reference.evaluate_actions(obs, actions)[1]
            log_pi = model.policy.evaluate_actions(obs, th.cat([actions, skill], dim=-1))[1]
            terms = log_reference - log_pi
            error = 4.0 * terms.std().item() / np.sqrt(samples)
            assert terms.mean().item() == pytest.approx(exact[row].item(), abs=error)
    assert (exact > 0).all()


def test_the_pull_of_a_learned_router_splits_into_the_router_term_and_the_routed_heads_kl() -> None:
    model = _model()
    states = _observations(64)
    reference = model.policy.hand_routed_copy(REGION_ROUTER)
    model.set_reference(reference)
    skills = reference.routed_skills(states)
    with th.no_grad():
        log_rho = model.policy.skill_distribution(states, skills)[1]
        router_term = -log_rho.gather(-1, skills.unsqueeze(-1)).squeeze(-1)
        # the same trunk and heads: only the router's cross-entropy to the reference's choice is left
        assert th.allclose(model.reference_kl(states), router_term, atol=1e-6)
        assert (router_term > 0.5).all()  # a fresh router is near uniform over 2 skills: -log(1/2)
        model.set_reference(_shifted_reference(model))
        current = model.policy.skill_distribution(states, skills)[0]
        heads = hybrid_kl(model.reference_policy.action_distribution(states), current)
        assert th.allclose(model.reference_kl(states), router_term + heads, atol=1e-6)


def test_the_pull_teaches_a_learned_router_the_references_routing() -> None:
    states = _observations(256)
    skills = REGION_ROUTER(states)
    model = _model(reference_coef=50.0, learning_rate=3e-3, n_epochs=8)
    unpulled = _model(learning_rate=3e-3, n_epochs=8)
    model.set_reference(_shifted_reference(model))
    unpulled.set_reference(_shifted_reference(unpulled))

    def kl_and_agreement(m: HybridPPO) -> tuple[float, float]:
        with th.no_grad():
            log_rho = m.policy.skill_distribution(states, skills)[1]
            return m.reference_kl(states).mean().item(), (log_rho.argmax(-1) == skills).float().mean().item()

    before, _ = kl_and_agreement(model)
    model.learn(512)
    unpulled.learn(512)
    after, agreement = kl_and_agreement(model)
    assert after < 0.5 * before
    assert after < 0.5 * kl_and_agreement(unpulled)[0]
    assert agreement > 0.9


def test_a_hand_coded_router_is_pulled_exactly_as_before() -> None:
    """field_half-style students: the pull is the routed heads' hybrid KL, bit for bit."""
    model = _model(router=REGION_ROUTER)
    model.set_reference(_shifted_reference(model))
    states = _observations(32)
    with th.no_grad():
        expected = hybrid_kl(
            model.reference_policy.action_distribution(states), model.policy.action_distribution(states)
        )
        assert th.equal(model.reference_kl(states), expected)


def test_set_reference_and_hand_routed_copy_reject_what_cannot_be_compared() -> None:
    model = _model()
    single = _model(router=None, skills=1)
    with pytest.raises(ValueError, match="skill by skill"):
        model.set_reference(single.policy)
    with pytest.raises(ValueError, match="hand-coded router"):
        model.set_reference(copy.deepcopy(model.policy))
    with pytest.raises(ValueError, match="hand_routed_copy"):
        model.policy.hand_routed_copy("learned")
    with pytest.raises(ValueError, match="hand_routed_copy"):
        single.policy.hand_routed_copy(REGION_ROUTER)
    with pytest.raises(ValueError, match="routed_skills"):
        model.policy.routed_skills(_observations(2))
    with pytest.raises(ValueError, match="one skill in"):
        model.policy.skill_distribution(_observations(2), th.tensor([0, 2]))
    copied = model.policy.hand_routed_copy(REGION_ROUTER)
    assert copied.router_net is None and not copied.learned_router
    states = _observations(16)
    with th.no_grad():
        skills = REGION_ROUTER(states)
        mine = model.policy.skill_distribution(states, skills)[0]
        theirs = copied.action_distribution(states)
    assert th.equal(mine.log_pi, theirs.log_pi) and th.equal(mine.mean, theirs.mean)


def test_distillation_fits_a_learned_router_to_skill_labels() -> None:
    env = HybridTargetEnv()
    model = _model()
    adapter = model.policy.adapter
    observations = _observations(512).numpy()
    region = observations[:, env.region_index]
    skills = np.where(region > 0, 0, 1)
    discrete = np.where(region > 0, 0, 2)
    parameters = np.zeros((512, adapter.n_parameters), dtype=np.float32)
    parameters[:, 0] = np.where(region > 0, 0.3, 0.0)
    parameters[:, 3] = np.where(region > 0, 0.0, -0.6)
    history = distill(
        model.policy,
        observations,
        discrete,
        parameters,
        epochs=30,
        batch_size=64,
        learning_rate=3e-3,
        skills=skills,
        router_weight=3.0,
    )
    assert history[-1]["router_cross_entropy"] < 0.3 * history[0]["router_cross_entropy"]
    assert history[-1]["router_agreement"] > 0.95 and history[-1]["agreement"] > 0.95
    with th.no_grad():  # greedy play: the router's skill, then its head's action
        greedy = model.policy._predict(th.as_tensor(observations), deterministic=True)
    assert (greedy[:, -1].numpy() == skills).mean() > 0.95
    assert (greedy[:, 0].numpy() == discrete).mean() > 0.95
    with pytest.raises(ValueError, match="needs skill labels"):
        distill(model.policy, observations, discrete, parameters)
    with pytest.raises(ValueError, match="skill labels must be"):
        distill(model.policy, observations, discrete, parameters, skills=np.full(512, 2))
    hand_coded = _model(router=REGION_ROUTER)
    with pytest.raises(ValueError, match="needs skill labels"):
        distill(hand_coded.policy, observations, discrete, parameters, skills=skills)
