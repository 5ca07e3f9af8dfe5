"""MonteCarloReplayBuffer returns and SkillDDPG's mixed Monte Carlo / TD critic target (``mc_mixing``)."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
import torch as th
from gymnasium import spaces

from sb3_hfo import SkillDDPG
from sb3_hfo.common.buffers import MonteCarloReplayBuffer, MonteCarloReplayBufferSamples

OBS_SPACE = spaces.Box(-1.0, 1.0, (2,), dtype=np.float32)
ACTION_SPACE = spaces.Box(-1.0, 1.0, (1,), dtype=np.float32)


def make_buffer(size: int, n_envs: int = 1, gamma: float = 0.5) -> MonteCarloReplayBuffer:
    return MonteCarloReplayBuffer(size, OBS_SPACE, ACTION_SPACE, device="cpu", n_envs=n_envs, gamma=gamma)


def add_steps(buffer: MonteCarloReplayBuffer, rewards: list[list[float]], dones: list[list[bool]]) -> None:
    """One ``add`` per row; each row has one entry per environment."""
    n_envs = buffer.n_envs
    for reward_row, done_row in zip(rewards, dones, strict=True):
        buffer.add(
            np.zeros((n_envs, 2), dtype=np.float32),
            np.zeros((n_envs, 2), dtype=np.float32),
            np.zeros((n_envs, 1), dtype=np.float32),
            np.array(reward_row, dtype=np.float32),
            np.array(done_row),
            [{} for _ in range(n_envs)],
        )


def test_returns_are_written_when_the_episode_ends() -> None:
    buffer = make_buffer(10)
    add_steps(buffer, [[1.0], [2.0], [3.0], [4.0]], [[False], [False], [True], [False]])
    # G_2 = 3, G_1 = 2 + 0.5 * 3, G_0 = 1 + 0.5 * 3.5; the step after the end belongs to an open episode.
    assert buffer.mc_returns[:3, 0] == pytest.approx([2.75, 3.5, 3.0])
    assert buffer.mc_valid[:4, 0].tolist() == [1.0, 1.0, 1.0, 0.0]


def test_returns_survive_wrap_around_and_overwritten_slots_are_invalidated() -> None:
    buffer = make_buffer(4, gamma=1.0)
    add_steps(buffer, [[1.0]] * 6, [[False]] * 5 + [[True]])
    # The last 4 of 6 steps are stored (positions 2, 3, 0, 1): their returns are 4, 3, 2, 1.
    assert buffer.mc_returns[[2, 3, 0, 1], 0] == pytest.approx([4.0, 3.0, 2.0, 1.0])
    assert buffer.mc_valid[:, 0].tolist() == [1.0, 1.0, 1.0, 1.0]
    add_steps(buffer, [[5.0]], [[False]])
    assert buffer.mc_valid[2, 0] == 0.0 and buffer.mc_valid[3, 0] == 1.0


def test_each_environment_keeps_its_own_episode() -> None:
    buffer = make_buffer(10, n_envs=2, gamma=0.5)
    add_steps(
        buffer,
        [[1.0, 10.0], [1.0, 20.0], [1.0, 30.0]],
        [[False, True], [True, False], [False, True]],
    )
    assert buffer.mc_returns[:2, 0] == pytest.approx([1.5, 1.0])
    assert buffer.mc_returns[:3, 1] == pytest.approx([10.0, 35.0, 30.0])
    assert buffer.mc_valid[2, 0] == 0.0 and buffer.mc_valid[2, 1] == 1.0


def test_long_episodes_with_tiny_discounts_do_not_underflow() -> None:
    buffer = make_buffer(2000, gamma=0.01)
    add_steps(buffer, [[1.0]] * 1500, [[False]] * 1499 + [[True]])
    assert np.isfinite(buffer.mc_returns[:1500, 0]).all()
    assert buffer.mc_returns[0, 0] == pytest.approx(1.0 / (1.0 - 0.01))


def test_samples_carry_returns_and_validity() -> None:
    buffer = make_buffer(10)
    add_steps(buffer, [[1.0], [2.0], [3.0]], [[False], [True], [False]])
    batch = buffer._get_samples(np.array([0, 1, 2]))
    assert isinstance(batch, MonteCarloReplayBufferSamples)
    assert batch.mc_returns.shape == (3, 1) and batch.mc_valid.flatten().tolist() == [1.0, 1.0, 0.0]
    assert batch.mc_returns[:2, 0].tolist() == pytest.approx([2.0, 2.0])


def test_bad_buffer_arguments_raise() -> None:
    with pytest.raises(ValueError, match="optimize_memory_usage"):
        MonteCarloReplayBuffer(10, OBS_SPACE, ACTION_SPACE, optimize_memory_usage=True)
    with pytest.raises(ValueError, match="gamma"):
        make_buffer(10, gamma=1.5)


# ---------------------------------------------------------------------------------------------------------------
# SkillDDPG with mc_mixing


def pendulum_model(**kwargs: object) -> SkillDDPG:
    return SkillDDPG(
        "HFOPolicy",
        gym.make("Pendulum-v1"),
        learning_starts=20,
        policy_kwargs={"net_arch": [16, 16], "n_skills": 1},
        device="cpu",
        seed=0,
        **kwargs,  # type: ignore[arg-type]
    )


def test_mc_mixing_selects_the_buffer_and_mixes_the_target() -> None:
    model = pendulum_model(mc_mixing=0.25, gamma=0.9)
    assert isinstance(model.replay_buffer, MonteCarloReplayBuffer) and model.replay_buffer.gamma == 0.9
    model.learn(250)  # Pendulum truncates at 200 steps: at least one episode's returns are known.
    assert model.replay_buffer.mc_valid[:200, 0].all()
    batch = model.replay_buffer._get_samples(np.array([0, 1, 210, 211]))
    assert batch.mc_valid.flatten().tolist() == [1.0, 1.0, 0.0, 0.0]
    mixed = model._critic_target(batch)
    model.mc_mixing = 0.0
    td = model._critic_target(batch)
    expected = td + 0.25 * batch.mc_valid * (batch.mc_returns - td)
    assert th.allclose(mixed, expected) and not th.allclose(mixed[:2], td[:2])
    assert th.equal(mixed[2:], td[2:])


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"mc_mixing": 1.5}, "mc_mixing must lie in"),
        ({"mc_mixing": 0.2, "n_steps": 3}, "cannot be combined with n_steps"),
        ({"mc_mixing": 0.2, "replay_buffer_class": th.nn.Module}, "needs a MonteCarloReplayBuffer"),
    ],
)
def test_bad_mc_mixing_arguments_raise(kwargs: dict[str, object], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        pendulum_model(**kwargs)


def test_mc_mixing_model_round_trips_through_save_and_load(tmp_path: object) -> None:
    model = pendulum_model(mc_mixing=0.2)
    model.learn(30)
    path = f"{tmp_path}/model.zip"
    model.save(path)
    loaded = SkillDDPG.load(path, env=gym.make("Pendulum-v1"), device="cpu")
    assert loaded.mc_mixing == 0.2 and isinstance(loaded.replay_buffer, MonteCarloReplayBuffer)


def test_load_replay_buffer_refuses_a_plain_buffer_into_an_mc_mixing_model(tmp_path: object) -> None:
    plain = pendulum_model(buffer_size=500)
    plain.learn(25)
    path = f"{tmp_path}/plain.pkl"
    plain.save_replay_buffer(path)
    model = pendulum_model(mc_mixing=0.2, buffer_size=500)
    own = model.replay_buffer
    with pytest.raises(
        ValueError, match=r"mc_mixing=0.2 needs a MonteCarloReplayBuffer .*got a ReplayBuffer"
    ):
        model.load_replay_buffer(path)
    assert model.replay_buffer is own  # kept: the next update still finds mc_valid
    model.learn(25)
    # The other way round is fine: a MonteCarloReplayBuffer is a ReplayBuffer.
    model.save_replay_buffer(f"{tmp_path}/mc.pkl")
    plain.load_replay_buffer(f"{tmp_path}/mc.pkl")
    assert isinstance(plain.replay_buffer, MonteCarloReplayBuffer)


def test_load_replay_buffer_refuses_returns_of_another_gamma_and_other_shapes(tmp_path: object) -> None:
    source = pendulum_model(mc_mixing=0.2, gamma=0.9, buffer_size=500)
    path = f"{tmp_path}/mc.pkl"
    source.save_replay_buffer(path)
    model = pendulum_model(mc_mixing=0.2, gamma=0.99, buffer_size=500)
    with pytest.raises(ValueError, match=r"discounted with gamma=0.9, the model's is 0.99"):
        model.load_replay_buffer(path)
    other = SkillDDPG(
        "HFOPolicy",
        "HFO/EmptyGoal-v0",
        buffer_size=100,
        policy_kwargs={"net_arch": [8]},
        mc_mixing=0.2,
        gamma=0.9,
    )
    with pytest.raises(ValueError, match=r"observations of shape \(3,\), the model's have shape \(58,\)"):
        other.load_replay_buffer(path)
