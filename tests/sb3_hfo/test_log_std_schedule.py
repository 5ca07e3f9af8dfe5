"""LogStdSchedule: HybridPPO's parameter log std set on a linear schedule (policy and pull reference), not learned."""

from __future__ import annotations

import copy

import pytest
import torch as th
from stable_baselines3 import PPO
from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.env_util import make_vec_env

from sb3_hfo.common.toy_env import HybridTargetEnv
from sb3_hfo.hybrid_ppo import HybridPPO
from sb3_hfo.hybrid_ppo.noise import LogStdSchedule

SMALL = {"n_steps": 32, "batch_size": 64, "n_epochs": 2, "learning_rate": 1e-2}


class _RecordLogStd(BaseCallback):
    """Every head's log std (policy, reference) as each rollout collects: runs after the schedule in a list."""

    def __init__(self) -> None:
        super().__init__()
        self.seen: list[tuple[float, list[list[float]], list[list[float]]]] = []

    def _on_rollout_start(self) -> None:
        self.seen.append(
            (
                self.model.num_timesteps,
                [head.log_std.tolist() for head in self.model.policy.heads],
                [head.log_std.tolist() for head in self.model.reference_policy.heads],
            )
        )

    def _on_step(self) -> bool:
        return True


def _model(skills: int) -> HybridPPO:
    env = make_vec_env(HybridTargetEnv, n_envs=2, seed=0)
    policy_kwargs = {"net_arch": [16], "log_std_init": -1.0}
    if skills > 1:
        policy_kwargs.update(skills=skills, router="field_half", domain="hfo")
    model = HybridPPO("MlpPolicy", env, seed=0, policy_kwargs=policy_kwargs, reference_coef=1.0, **SMALL)
    model.set_reference(copy.deepcopy(model.policy))
    return model


@pytest.mark.parametrize("skills", [1, 2])
def test_the_log_std_follows_the_schedule_in_policy_and_reference_and_is_not_learned(skills: int) -> None:
    model = _model(skills)
    record = _RecordLogStd()
    schedule = LogStdSchedule(-1.0, -3.0)
    total = 4 * 64  # four rollouts of 2 envs x 32 steps
    model.learn(total, callback=[schedule, record])
    assert [steps for steps, _, _ in record.seen] == [0, 64, 128, 192]
    for steps, policy_values, reference_values in record.seen:
        expected = -1.0 - 2.0 * steps / total
        assert policy_values == reference_values
        assert len(policy_values) == skills
        for head_values in policy_values:
            assert head_values == pytest.approx([expected] * len(head_values))
    # the updates after the last rollout did not move it (no gradient), though the means did learn
    assert all(not head.log_std.requires_grad for head in model.policy.heads)
    for head in model.policy.heads:
        assert head.log_std.tolist() == pytest.approx([-1.0 - 2.0 * 192 / total] * head.log_std.numel())


def test_without_the_schedule_ppo_learns_the_log_std() -> None:  # what the schedule switches off
    model = _model(1)
    model.learn(4 * 64)
    assert model.policy.heads[0].log_std.requires_grad
    assert not th.allclose(model.policy.heads[0].log_std, th.full_like(model.policy.heads[0].log_std, -1.0))


def test_value_is_linear_in_the_elapsed_share_and_clamped() -> None:
    schedule = LogStdSchedule(-3.5, -5.0)
    assert [schedule.value(p) for p in (1.0, 0.5, 0.0)] == [-3.5, -4.25, -5.0]
    assert schedule.value(1.5) == -3.5 and schedule.value(-0.5) == -5.0
    assert LogStdSchedule(-2.0, -2.0).value(0.3) == -2.0


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), "x", None, True])
def test_bounds_that_are_not_finite_numbers_are_refused(bad: object) -> None:
    with pytest.raises(ValueError, match="LogStdSchedule: end must be a finite number"):
        LogStdSchedule(-3.5, bad)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="LogStdSchedule: start must be a finite number"):
        LogStdSchedule(bad, -3.5)  # type: ignore[arg-type]


def test_a_policy_without_skill_heads_is_refused() -> None:
    model = PPO("MlpPolicy", make_vec_env("Pendulum-v1", n_envs=1, seed=0), n_steps=8, batch_size=8)
    with pytest.raises(ValueError, match="LogStdSchedule needs a HybridPPO policy"):
        model.learn(8, callback=LogStdSchedule(-1.0, -2.0))
