"""HybridPPO: its distribution, action adapter, policy (skills, learned router), learning, save/load and hooks."""

from __future__ import annotations

import math
from types import SimpleNamespace
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
import torch as th
from gymnasium import spaces
from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.env_util import make_vec_env

from hfo2d.action_layout import HFO_FLAT_ACTION_LAYOUT, hfo_flat_action_space
from hfo2d.features import SELF_X
from sb3_hfo.common.toy_env import HybridTargetEnv
from sb3_hfo.hybrid_ppo import ActionAdapter, HybridDistribution, HybridPPO

# --------------------------------------------------------------------------------------------------------------
# The distribution


def test_log_prob_and_entropy_by_hand() -> None:
    # K = 2 actions, P = 2 parameters: action 0 reads parameter 0, action 1 reads parameter 1.
    mask = th.tensor([[1.0, 0.0], [0.0, 1.0]])
    logits = th.tensor([[0.0, math.log(3.0)]])  # pi = (1/4, 3/4)
    mean = th.tensor([[0.5, -0.2]])
    log_std = th.tensor([math.log(2.0), math.log(0.5)])
    dist = HybridDistribution(logits, mean, log_std, mask)
    # k = 1 with its parameter one standard deviation (0.5) above the mean; parameter 0 is ignored
    log_p = dist.log_prob(th.tensor([1]), th.tensor([[123.0, 0.3]]))
    expected = math.log(0.75) + (-0.5 * 1.0 - math.log(0.5) - 0.5 * math.log(2 * math.pi))
    assert log_p.item() == pytest.approx(expected, abs=1e-6)
    entropy = dist.entropy(th.tensor([0]))
    categorical = -(0.25 * math.log(0.25) + 0.75 * math.log(0.75))
    gaussian_0 = 0.5 + 0.5 * math.log(2 * math.pi) + math.log(2.0)
    assert entropy.item() == pytest.approx(categorical + gaussian_0, abs=1e-6)


def test_log_prob_entropy_and_gradients_match_torch_distributions() -> None:
    """Against torch.distributions (Categorical x Normal over the chosen action's slice), values and gradients."""
    gen = th.Generator().manual_seed(0)
    sizes = HFO_FLAT_ACTION_LAYOUT.parameter_sizes  # (2, 1, 2)
    mask = th.as_tensor(ActionAdapter.from_space(hfo_flat_action_space()).parameter_mask, dtype=th.float32)
    batch, n_parameters = 6, sum(sizes)
    logits = th.randn(batch, 3, generator=gen, requires_grad=True)
    mean = th.randn(batch, n_parameters, generator=gen, requires_grad=True)
    log_std = (0.3 * th.randn(n_parameters, generator=gen)).requires_grad_()
    discrete = th.tensor([0, 1, 2, 2, 1, 0])
    parameters = th.randn(batch, n_parameters, generator=gen)

    ours = HybridDistribution(logits, mean, log_std, mask)
    ours_total = ours.log_prob(discrete, parameters).sum() + ours.entropy(discrete).sum()
    our_grads = th.autograd.grad(ours_total, (logits, mean, log_std))

    categorical = th.distributions.Categorical(logits=logits)
    normal = th.distributions.Normal(mean, log_std.exp().expand_as(mean))
    ends = np.cumsum([0, *sizes])
    chosen = [slice(ends[k], ends[k + 1]) for k in discrete.tolist()]
    ref_log_prob = categorical.log_prob(discrete) + th.stack(
        [normal.log_prob(parameters)[row, part].sum() for row, part in enumerate(chosen)]
    )
    ref_entropy = categorical.entropy() + th.stack(
        [normal.entropy()[row, part].sum() for row, part in enumerate(chosen)]
    )
    th.testing.assert_close(ours.log_prob(discrete, parameters), ref_log_prob)
    th.testing.assert_close(ours.entropy(discrete), ref_entropy)
    ref_grads = th.autograd.grad(ref_log_prob.sum() + ref_entropy.sum(), (logits, mean, log_std))
    for got, want in zip(our_grads, ref_grads, strict=True):
        th.testing.assert_close(got, want)
    # the parameters of actions not played get no gradient: row 1 plays TURN (parameter 2 only)
    assert th.all(our_grads[1][1, [0, 1, 3, 4]] == 0) and our_grads[1][1, 2] != 0


def test_sample_and_mode() -> None:
    th.manual_seed(0)
    logits = th.tensor([[0.0, 5.0, 0.0]]).repeat(4000, 1)
    mean = th.tensor([[0.2, -0.4]]).repeat(4000, 1)
    dist = HybridDistribution(logits, mean, th.tensor([math.log(0.1), math.log(0.3)]), th.ones(3, 2))
    discrete, parameters = dist.sample()
    probs = th.softmax(logits[0], dim=0)
    assert (discrete == 1).float().mean().item() == pytest.approx(probs[1].item(), abs=0.02)
    th.testing.assert_close(parameters.std(dim=0), th.tensor([0.1, 0.3]), atol=0.01, rtol=0)
    mode_k, mode_u = dist.mode()
    assert th.all(mode_k == 1) and th.equal(mode_u, mean)


# --------------------------------------------------------------------------------------------------------------
# The action adapter


def _parameterized_space() -> spaces.Tuple:
    return gym.make("HFO/EmptyGoal-v0", action_format="parameterized").action_space


def _duck_layout_box() -> spaces.Box:
    box = spaces.Box(np.array([0, 0, -5, 10], np.float32), np.array([1, 1, 5, 20], np.float32))
    box.layout = SimpleNamespace(names=("A", "B"), parameter_sizes=(1, 1))  # type: ignore[attr-defined]
    return box


FORMATS: dict[str, tuple[Any, dict[str, Any], tuple[int, ...]]] = {
    "hfo_flat": (hfo_flat_action_space, {}, (2, 1, 2)),
    "duck_layout": (_duck_layout_box, {}, (1, 1)),
    "hfo_parameterized": (_parameterized_space, {}, (2, 1, 2)),
    "tuple_shared": (lambda: spaces.Tuple((spaces.Discrete(3), spaces.Box(-1, 1, (3,)))), {}, (3, 3, 3)),
    "tuple_shared_sizes": (
        lambda: spaces.Tuple((spaces.Discrete(3), spaces.Box(0, 4, (2,)))),
        {"parameter_sizes": (1, 1, 0)},
        (1, 1, 0),
    ),
    "tuple_nested": (
        lambda: spaces.Tuple(
            (spaces.Discrete(2), spaces.Tuple((spaces.Box(0, 1, (1,)), spaces.Box(-3, 3, (2,)))))
        ),
        {},
        (1, 2),
    ),
    "box": (lambda: spaces.Box(-2, 3, (2, 2)), {}, (4,)),
    "discrete": (lambda: spaces.Discrete(4, start=2), {}, (0, 0, 0, 0)),
}


@pytest.mark.parametrize("name", sorted(FORMATS))
def test_adapter_round_trip(name: str) -> None:
    make_space, kwargs, per_action = FORMATS[name]
    space = make_space()
    adapter = ActionAdapter.from_space(space, **kwargs)
    assert tuple(adapter.parameter_mask.sum(axis=1)) == per_action
    rng = np.random.default_rng(0)
    n = 7
    internal = np.concatenate(
        [rng.integers(0, adapter.n_discrete, (n, 1)), rng.uniform(-1, 1, (n, adapter.n_parameters))], axis=1
    ).astype(np.float32)
    env_actions = adapter.to_env(internal)
    assert all(space.contains(action) for action in env_actions)
    np.testing.assert_allclose(adapter.from_env(env_actions), internal, atol=1e-5)


def test_adapter_clips_to_the_env_bounds() -> None:
    space = _parameterized_space()
    adapter = ActionAdapter.from_space(space)
    action = adapter.to_env(np.array([[2, 3.0, -7.0, 0.0, -1.5, 1.5]], np.float32))[0]
    assert action[0] == 2
    np.testing.assert_array_equal(action[1], [100.0, -180.0])  # DASH power 0..100, direction -180..180
    np.testing.assert_array_equal(action[3], [0.0, 180.0])


def test_flat_layout_sends_a_one_hot_preference_the_env_plays() -> None:
    adapter = ActionAdapter.from_space(hfo_flat_action_space())
    env = gym.make("HFO/EmptyGoal-v0")
    env.reset(seed=0)
    for k, name in enumerate(HFO_FLAT_ACTION_LAYOUT.names):
        flat = adapter.to_env(np.array([[k, 0.5, 0.0, 0.0, 0.5, 0.0]], np.float32))[0]
        np.testing.assert_array_equal(flat[:3], np.eye(3)[k])
        assert env.step(flat)[4]["action"] == name


@pytest.mark.parametrize(
    ("space", "kwargs", "message"),
    [
        (spaces.MultiDiscrete([2, 3]), {}, "MultiDiscrete"),
        (
            spaces.Tuple((spaces.Discrete(3), spaces.Box(0, 1, (2,)))),
            {"parameter_sizes": (1, 0, 0)},
            "summing to 2",
        ),
        (
            spaces.Tuple((spaces.Discrete(3), spaces.Box(0, 1, (2,)), spaces.Box(0, 1, (2,)))),
            {},
            "one Box per",
        ),
        (spaces.Box(-np.inf, np.inf, (2,)), {}, "infinite bounds"),
        (spaces.Box(0, 1, (2,)), {"parameter_sizes": (2,)}, "only for Tuple"),
        (spaces.Dict({"a": spaces.Discrete(2)}), {}, "Dict"),
    ],
)
def test_adapter_errors_name_the_space(space: spaces.Space, kwargs: dict[str, Any], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        ActionAdapter.from_space(space, **kwargs)


class _ActionSpaceEnv(gym.Env):
    """A one-step env with any action space (for construction errors)."""

    def __init__(self, action_space: spaces.Space) -> None:
        self.observation_space = spaces.Box(-1, 1, (3,), np.float32)
        self.action_space = action_space

    def reset(self, *, seed: int | None = None, options: dict | None = None) -> tuple[np.ndarray, dict]:
        super().reset(seed=seed)
        return np.zeros(3, np.float32), {}

    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict]:
        return np.zeros(3, np.float32), 0.0, True, False, {}


def test_algorithm_errors() -> None:
    with pytest.raises(ValueError, match="MultiDiscrete"):
        HybridPPO("MlpPolicy", _ActionSpaceEnv(spaces.MultiDiscrete([2, 2])))
    env = HybridTargetEnv()
    with pytest.raises(ValueError, match="needs skills > 1"):
        HybridPPO("MlpPolicy", env, policy_kwargs={"router": "learned"})
    with pytest.raises(ValueError, match="skills must be an integer"):
        HybridPPO("MlpPolicy", env, policy_kwargs={"skills": 0})
    with pytest.raises(ValueError, match="Unknown skill_router"):
        HybridPPO("MlpPolicy", env, policy_kwargs={"skills": 2, "router": "nowhere"})
    with pytest.raises(ValueError, match="gSDE"):
        HybridPPO("MlpPolicy", env, policy_kwargs={"use_sde": True})


# --------------------------------------------------------------------------------------------------------------
# Learning, acting, save/load

TOY_HYPERPARAMS: dict[str, Any] = dict(n_steps=32, batch_size=128, n_epochs=5, learning_rate=3e-3)


def _greedy_success(model: HybridPPO, episodes: int = 300) -> float:
    env = HybridTargetEnv()
    obs, _ = env.reset(seed=123)
    successes = 0
    for _ in range(episodes):
        action, _ = model.predict(obs, deterministic=True)
        successes += env.step(action)[4]["is_success"]
        obs, _ = env.reset()
    return successes / episodes


def test_learns_the_hybrid_toy_task() -> None:
    # random acting: the right discrete action (1/3) with its power within 0.1 (about 0.2) ~ 7 %
    model = HybridPPO("MlpPolicy", make_vec_env(HybridTargetEnv, n_envs=8, seed=0), seed=0, **TOY_HYPERPARAMS)
    before = _greedy_success(model)
    model.learn(4_000)
    after = _greedy_success(model)
    assert before < 0.15 and after > 0.4, (before, after)


def test_learns_plain_discrete_and_box_spaces() -> None:
    """Discrete (K actions, no parameters) and Box (one action, a Gaussian): both learn a one-step target."""

    class OneStep(gym.Env):
        def __init__(self, discrete: bool) -> None:
            self.observation_space = spaces.Box(-1, 1, (1,), np.float32)
            self.action_space = spaces.Discrete(3) if discrete else spaces.Box(-2, 2, (1,), np.float32)
            self.discrete = discrete

        def reset(self, *, seed: int | None = None, options: dict | None = None) -> tuple[np.ndarray, dict]:
            super().reset(seed=seed)
            self.x = float(self.np_random.uniform(-1, 1))
            return np.array([self.x], np.float32), {}

        def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict]:
            target = 0 if self.x < 0 else 2
            reward = float(action == target) if self.discrete else -abs(float(action[0]) - self.x)
            return np.array([self.x], np.float32), reward, True, False, {}

    xs = np.linspace(-0.9, 0.9, 10, dtype=np.float32)[:, None]
    for discrete, steps in ((True, 3_000), (False, 6_000)):
        env = make_vec_env(lambda d=discrete: OneStep(d), n_envs=8, seed=0)
        model = HybridPPO("MlpPolicy", env, seed=0, **TOY_HYPERPARAMS)
        error_before = np.abs(model.predict(xs, deterministic=True)[0] - xs).mean()
        model.learn(steps)
        actions, _ = model.predict(xs, deterministic=True)
        if discrete:
            np.testing.assert_array_equal(actions, np.where(xs[:, 0] < 0, 0, 2))
        else:  # a Gaussian action of Box(-2, 2): its mean follows x
            assert actions.shape == (10, 1) and np.abs(actions - xs).mean() < 0.5 * error_before


def test_predict_is_argmax_and_mean() -> None:
    model = HybridPPO("MlpPolicy", HybridTargetEnv(), seed=0)
    obs = np.random.default_rng(0).uniform(-1, 1, (5, 58)).astype(np.float32)
    with th.no_grad():
        latent = model.policy.actor_trunk(th.as_tensor(obs))
        logits, mean = model.policy.heads[0](latent)
    actions, _ = model.predict(obs, deterministic=True)
    expected = model.policy.adapter.to_env(
        np.concatenate([logits.argmax(1, keepdim=True).numpy(), mean.numpy()], 1)
    )
    np.testing.assert_array_equal(actions, expected)
    single, _ = model.predict(obs[0], deterministic=True)
    np.testing.assert_array_equal(single, expected[0])


class _Recorder(gym.Wrapper):
    """Records the actions the env receives."""

    def __init__(self, env: gym.Env) -> None:
        super().__init__(env)
        self.received: list[Any] = []

    def step(self, action: Any) -> Any:
        self.received.append(action)
        return self.env.step(action)


def test_buffer_keeps_unclipped_parameters_and_the_env_gets_its_format() -> None:
    recorder = _Recorder(gym.make("HFO/EmptyGoal-v0", action_format="parameterized"))
    model = HybridPPO(
        "MlpPolicy", recorder, n_steps=64, batch_size=64, seed=0, policy_kwargs={"log_std_init": 1.0}
    )
    model.learn(64)
    buffer_actions = model.rollout_buffer.actions.reshape(-1, 6)
    assert np.abs(buffer_actions[:, 1:]).max() > 1.0  # sampled beyond the bounds, kept so for the update
    np.testing.assert_allclose(
        [a[0] for a in recorder.received], buffer_actions[: len(recorder.received), 0].astype(int)
    )
    assert all(recorder.action_space.contains(action) for action in recorder.received)


def test_save_load_round_trip(tmp_path: Any) -> None:
    env = gym.make("HFO/EmptyGoal-v0", action_format="parameterized")
    model = HybridPPO("MlpPolicy", env, n_steps=32, batch_size=32, seed=0, policy_kwargs={"net_arch": [16]})
    model.learn(64)
    model.save(tmp_path / "model.zip")
    loaded = HybridPPO.load(tmp_path / "model.zip", device="cpu")
    obs = np.stack([env.observation_space.sample() for _ in range(8)])
    for got, want in zip(
        loaded.predict(obs, deterministic=True)[0], model.predict(obs, deterministic=True)[0], strict=True
    ):
        assert got[0] == want[0] and all(np.array_equal(a, b) for a, b in zip(got[1:], want[1:], strict=True))
    for name in model.policy.optimizer_names:
        saved = getattr(model.policy, name).state_dict()["state"]
        restored = getattr(loaded.policy, name).state_dict()["state"]
        assert saved.keys() == restored.keys() and all(
            th.equal(saved[i]["exp_avg"], restored[i]["exp_avg"]) for i in saved
        )
    loaded.set_env(env)
    loaded.learn(64)  # trains on after loading


def test_logs_action_fractions_to_tensorboard(tmp_path: Any) -> None:
    from tensorboard.backend.event_processing.event_accumulator import EventAccumulator

    seen: dict[str, float] = {}

    class Grab(BaseCallback):
        def _on_step(self) -> bool:
            return True

        def _on_rollout_end(self) -> None:
            seen.update(self.logger.name_to_value)

    env = make_vec_env(HybridTargetEnv, n_envs=2, seed=0)
    model = HybridPPO("MlpPolicy", env, n_steps=50, batch_size=50, tensorboard_log=str(tmp_path))
    model.learn(200, callback=Grab(), progress_bar=True)  # train/ logs are written at the next iteration
    fractions = [seen[f"rollout/action_{name}_fraction"] for name in HFO_FLAT_ACTION_LAYOUT.names]
    assert sum(fractions) == pytest.approx(1.0) and all(0.1 < f < 0.6 for f in fractions)
    (run,) = tmp_path.iterdir()
    events = EventAccumulator(str(run))
    events.Reload()
    tags = set(events.Tags()["scalars"])
    assert {f"rollout/action_{name}_fraction" for name in HFO_FLAT_ACTION_LAYOUT.names} <= tags
    assert {"train/approx_kl", "train/entropy_loss", "train/std"} <= tags


# --------------------------------------------------------------------------------------------------------------
# Skills


class _FarHalfToy(HybridTargetEnv):
    """The toy task with the agent always in the far half (HFO's self-x feature > 0): the field-half router
    always picks skill 0."""

    def _new_context(self) -> np.ndarray:
        obs = super()._new_context()
        self._obs[SELF_X] = obs[SELF_X] = abs(obs[SELF_X]) + 0.01
        return obs


def test_field_half_skills_route_to_their_head() -> None:
    model = HybridPPO(
        "MlpPolicy",
        HybridTargetEnv(),
        seed=0,
        policy_kwargs={"skills": 2, "router": "field_half", "domain": "hfo"},
    )
    policy = model.policy
    obs = np.zeros((4, 58), np.float32)
    obs[:, SELF_X] = [0.5, -0.5, 0.2, -0.9]  # far, near, far, near
    before, _ = model.predict(obs, deterministic=True)
    with th.no_grad():
        policy.heads[1].linear.bias.add_(th.linspace(-3, 3, policy.heads[1].linear.bias.numel()))
    after, _ = model.predict(obs, deterministic=True)
    np.testing.assert_array_equal(after[[0, 2]], before[[0, 2]])  # skill 0's rows: head 1 plays no part
    assert not np.array_equal(after[[1, 3]], before[[1, 3]])


def _toy_model(**policy_kwargs: Any) -> HybridPPO:
    """HybridPPO on two far-half toy games (``field_half`` routes every state to skill 0), tiny rollouts."""
    return HybridPPO(
        "MlpPolicy",
        make_vec_env(_FarHalfToy, n_envs=2, seed=0),
        n_steps=32,
        batch_size=32,
        n_epochs=2,
        seed=0,
        policy_kwargs=policy_kwargs,
    )


def test_each_skill_optimizer_updates_only_its_head() -> None:
    model = _toy_model(skills=2, router="field_half", domain="hfo")
    policy = model.policy
    assert {id(p) for g in policy.skill_1_optimizer.param_groups for p in g["params"]} == {
        id(p) for p in policy.heads[1].parameters()
    }
    shared = {id(p) for g in policy.optimizer.param_groups for p in g["params"]}
    assert not shared & {id(p) for head in policy.heads for p in head.parameters()}
    snapshot = {name: p.detach().clone() for name, p in policy.named_parameters()}
    model.learn(64)
    changed = {name for name, p in policy.named_parameters() if not th.equal(p, snapshot[name])}
    assert {"heads.0.linear.weight", "heads.0.log_std", "actor_trunk.0.weight", "value_net.weight"} <= changed
    assert not any(name.startswith("heads.1.") for name in changed)
    assert policy.skill_1_optimizer.state_dict()["state"] == {}  # never stepped


def test_learned_router_learns_to_avoid_a_useless_skill() -> None:
    """Skill 1's head is frozen at wide noise: the router should learn to send (almost) everything to skill 0."""
    env = make_vec_env(HybridTargetEnv, n_envs=8, seed=0)
    model = HybridPPO(
        "MlpPolicy", env, seed=0, **TOY_HYPERPARAMS, policy_kwargs={"skills": 2, "router": "learned"}
    )
    policy = model.policy
    with th.no_grad():
        policy.heads[1].log_std.fill_(2.0)
    policy.heads[1].requires_grad_(False)
    assert policy.action_vector_size == 1 + 5 + 1

    def skill_0_probability() -> float:
        obs = th.as_tensor(np.stack([env.observation_space.sample() for _ in range(200)]))
        with th.no_grad():
            _, router_logits, _ = policy.actor_outputs(obs)
        return th.softmax(router_logits, -1)[:, 0].mean().item()

    assert skill_0_probability() == pytest.approx(0.5, abs=0.05)
    model.learn(6_000)
    assert skill_0_probability() > 0.9
    assert _greedy_success(model) > 0.4
    skills = policy.skill_router(np.zeros((3, 58), np.float32))  # the greedy routing, as a router object
    assert skills.shape == (3,) and skills.dtype == np.int64


# --------------------------------------------------------------------------------------------------------------
# The project's hooks: rl-zoo3 name, load_model, evaluate


def test_rl_zoo_name_and_load_model(tmp_path: Any) -> None:
    from sb3_hfo.cli.zoo import algo_classes
    from sb3_hfo.evaluation import evaluate
    from sb3_hfo.models import load_model
    from sb3_hfo.skill_ddpg import SkillDDPG

    assert algo_classes()["hybrid_ppo"] is HybridPPO
    model = HybridPPO("MlpPolicy", "HFO/EmptyGoal-v0", n_steps=32, batch_size=32, seed=0)
    model.save(tmp_path / "m.zip")
    loaded = load_model(tmp_path / "m.zip", SkillDDPG, device="cpu", buffer_size=1)
    assert type(loaded) is HybridPPO
    result = evaluate(str(tmp_path / "m.zip"), env_id="HFO/EmptyGoal-v0", episodes=2, seed=0)
    assert result.episodes == 2


def test_hybrid_ppo_modules_do_not_import_hfo2d() -> None:
    """Issue 33, item 6: the algorithm reads the env's layout by duck typing; no module of it imports hfo2d."""
    import ast
    from pathlib import Path

    import sb3_hfo.hybrid_ppo

    for path in Path(sb3_hfo.hybrid_ppo.__file__).parent.glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom):
                names = [node.module or ""]
            else:
                continue
            assert not any(name.split(".")[0] == "hfo2d" for name in names), (path.name, names)


# --------------------------------------------------------------------------------------------------------------
# State-dependent parameter deviations


def _random_batch(model: HybridPPO, rows: int = 12) -> tuple[th.Tensor, th.Tensor]:
    generator = np.random.default_rng(0)
    obs = th.as_tensor(np.stack([model.observation_space.sample() for _ in range(rows)]), dtype=th.float32)
    internal = generator.uniform(-1.0, 1.0, (rows, model.policy.action_vector_size))
    internal[:, 0] = generator.integers(0, model.policy.adapter.n_discrete, rows)
    return obs, th.as_tensor(internal, dtype=th.float32)


@pytest.mark.parametrize("skills", [1, 2])
def test_state_dependent_std_starts_as_the_fixed_one_and_then_varies_by_state(skills: int) -> None:
    kwargs: dict[str, Any] = {"skills": 2, "router": "field_half", "domain": "hfo"} if skills == 2 else {}
    fixed = _toy_model(net_arch=[16], **kwargs)
    varying = _toy_model(net_arch=[16], state_dependent_std=True, **kwargs)
    missing, unexpected = varying.policy.load_state_dict(fixed.policy.state_dict(), strict=False)
    assert not unexpected and missing and all(".std_linear." in key for key in missing)
    obs, actions = _random_batch(fixed)
    with th.no_grad():
        _, fixed_log_prob, fixed_entropy = fixed.policy.evaluate_actions(obs, actions)
        _, log_prob, entropy = varying.policy.evaluate_actions(obs, actions)
    assert th.allclose(log_prob, fixed_log_prob) and th.allclose(entropy, fixed_entropy)

    # a non-zero layer: each state gets its own deviations, and the log-probability is torch's Normal's with them
    with th.no_grad():
        for head in varying.policy.heads:
            head.std_linear.weight.normal_(0.0, 1.0)
        distribution = varying.policy.action_distribution(obs)
        _, log_prob, _ = varying.policy.evaluate_actions(obs, actions)
    std = distribution.log_std.exp()
    assert std.shape == distribution.mean.shape and not th.allclose(std[0], std[1])
    assert float(distribution.log_std.min()) >= -5.0 and float(distribution.log_std.max()) <= 1.0
    parameters = actions[:, 1 : varying.policy.adapter.internal_size]
    discrete = actions[:, 0].long()
    gaussian = th.distributions.Normal(distribution.mean, std).log_prob(parameters)
    expected = (gaussian * varying.policy.parameter_mask[discrete]).sum(-1)
    expected = expected + distribution.log_pi.gather(-1, discrete.unsqueeze(-1)).squeeze(-1)
    assert th.allclose(log_prob, expected, atol=1e-5)


def test_state_dependent_std_trains_and_round_trips(tmp_path: Any) -> None:
    model = _toy_model(net_arch=[16], state_dependent_std=True)
    before = model.policy.heads[0].std_linear.weight.detach().clone()
    model.learn(64)
    assert not th.equal(model.policy.heads[0].std_linear.weight, before)  # PPO's gradient reaches it
    model.save(tmp_path / "model.zip")
    loaded = HybridPPO.load(tmp_path / "model.zip", device="cpu")
    assert loaded.policy.state_dependent_std
    obs, _ = _random_batch(model)
    with th.no_grad():
        want = model.policy.action_distribution(obs).log_std
        got = loaded.policy.action_distribution(obs).log_std
    assert th.equal(got, want)


def test_state_dependent_std_logs_the_deviations_of_the_states_not_the_offset() -> None:
    from stable_baselines3.common.logger import configure

    model = _toy_model(net_arch=[16], state_dependent_std=True)
    with th.no_grad():
        model.policy.heads[0].std_linear.weight.normal_(0.0, 2.0)
    logger = configure(None, [""])
    recorded: dict[str, float] = {}
    record = logger.record

    def keep(key: str, value: Any, exclude: Any = None) -> None:
        recorded[key] = value
        record(key, value, exclude)

    logger.record = keep  # type: ignore[method-assign]
    model.set_logger(logger)
    model.learn(64)
    offset_only = float(model.policy.heads[0].log_std.exp().mean())
    assert recorded["train/std"] != pytest.approx(offset_only, rel=0.05)
