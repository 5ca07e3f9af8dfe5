"""A replay buffer that also keeps each transition's Monte Carlo return, for mixed Monte Carlo / TD targets.

Hausknecht & Stone ("On-Policy vs. Off-Policy Updates for Deep Reinforcement Learning", 2016) trained DDPG on
HFO with the critic target ``y = beta * G + (1 - beta) * (r + gamma * Q'(s', mu'(s')))``, where ``G`` is the
discounted return the behaviour policy actually collected from ``s`` to the end of its episode; with
``beta = 0.2`` every run learned to score, while pure off-policy targets failed in some. ``SkillDDPG(mc_mixing=beta)``
uses this buffer to get ``G``.

``G`` is known only once the episode has ended, so transitions of an episode still in progress are sampled with
``mc_valid = 0`` and the algorithm uses the plain TD target for those rows. An episode cut by a time limit ends its
returns there (HFO ends an episode at its frame limit too, with no value after it).
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np
import torch as th
from gymnasium import spaces
from stable_baselines3.common.buffers import ReplayBuffer
from stable_baselines3.common.vec_env import VecNormalize

__all__ = ["MonteCarloReplayBuffer", "MonteCarloReplayBufferSamples"]


class MonteCarloReplayBufferSamples(NamedTuple):
    """SB3's ``ReplayBufferSamples`` fields plus the Monte Carlo return of each row.

    All tensors have batch size ``B`` first; ``mc_returns`` and ``mc_valid`` are ``(B, 1)``; ``mc_valid`` is 1 where
    the row's episode has ended (its return is known) and 0 otherwise.
    """

    observations: th.Tensor
    actions: th.Tensor
    next_observations: th.Tensor
    dones: th.Tensor
    rewards: th.Tensor
    discounts: th.Tensor | None
    mc_returns: th.Tensor
    mc_valid: th.Tensor


class MonteCarloReplayBuffer(ReplayBuffer):
    """SB3 ``ReplayBuffer`` that writes the discounted return ``G_t = r_t + gamma * G_{t+1}`` of every step of an
    episode into ``mc_returns`` when the episode ends.

    :param buffer_size: capacity in transitions per environment.
    :param observation_space: the environment's observation space.
    :param action_space: the environment's action space.
    :param device: torch device of the sampled tensors.
    :param n_envs: number of parallel environments.
    :param optimize_memory_usage: not supported (must be False).
    :param handle_timeout_termination: as in SB3: a time-limit end does not count as ``done`` for the TD target.
    :param gamma: the discount used for the returns (the algorithm's ``gamma``).
    """

    def __init__(
        self,
        buffer_size: int,
        observation_space: spaces.Space,
        action_space: spaces.Space,
        device: th.device | str = "auto",
        n_envs: int = 1,
        optimize_memory_usage: bool = False,
        handle_timeout_termination: bool = True,
        gamma: float = 0.99,
    ) -> None:
        if optimize_memory_usage:
            raise ValueError("MonteCarloReplayBuffer does not support optimize_memory_usage=True")
        if not 0.0 <= gamma <= 1.0:
            raise ValueError(f"gamma must lie in [0, 1], got {gamma}")
        super().__init__(
            buffer_size,
            observation_space,
            action_space,
            device=device,
            n_envs=n_envs,
            optimize_memory_usage=False,
            handle_timeout_termination=handle_timeout_termination,
        )
        self.gamma = gamma
        self.mc_returns = np.zeros((self.buffer_size, self.n_envs), dtype=np.float32)
        self.mc_valid = np.zeros((self.buffer_size, self.n_envs), dtype=np.float32)
        # Steps of each environment's current episode stored so far (capped at the buffer size on wrap-around).
        self.episode_lengths = np.zeros(self.n_envs, dtype=np.int64)

    def add(
        self,
        obs: np.ndarray,
        next_obs: np.ndarray,
        action: np.ndarray,
        reward: np.ndarray,
        done: np.ndarray,
        infos: list[dict[str, Any]],
    ) -> None:
        position = self.pos
        # The slot is being overwritten: its old return no longer applies.
        self.mc_valid[position] = 0.0
        super().add(obs, next_obs, action, reward, done, infos)
        self.episode_lengths = np.minimum(self.episode_lengths + 1, self.buffer_size)
        for env_index in np.flatnonzero(np.asarray(done).reshape(-1)):
            self._write_returns(position, int(env_index))

    def _write_returns(self, last_position: int, env_index: int) -> None:
        """Fill ``mc_returns`` for the episode of ``env_index`` that ended at ``last_position``."""
        length = int(self.episode_lengths[env_index])
        positions = (last_position - np.arange(length - 1, -1, -1)) % self.buffer_size  # oldest first
        rewards = self.rewards[positions, env_index].astype(np.float64)
        # A plain backward loop: once per episode (<= 500 steps in HFO), and no gamma^t that could underflow.
        returns = np.empty_like(rewards)
        running = 0.0
        for step in range(length - 1, -1, -1):
            running = rewards[step] + self.gamma * running
            returns[step] = running
        self.mc_returns[positions, env_index] = returns
        self.mc_valid[positions, env_index] = 1.0
        self.episode_lengths[env_index] = 0

    def _get_samples(  # type: ignore[override]
        self, batch_inds: np.ndarray, env: VecNormalize | None = None
    ) -> MonteCarloReplayBufferSamples:
        if env is not None and env.norm_reward:
            raise ValueError(
                "MonteCarloReplayBuffer stores returns of the raw rewards; VecNormalize(norm_reward=True) would mix "
                "two reward scales in one target. Use norm_reward=False with mc_mixing."
            )
        env_indices = np.random.randint(0, high=self.n_envs, size=(len(batch_inds),))
        data = (
            self._normalize_obs(self.observations[batch_inds, env_indices, :], env),
            self.actions[batch_inds, env_indices, :],
            self._normalize_obs(self.next_observations[batch_inds, env_indices, :], env),
            # SB3's convention: a time-limit end is not a terminal state for the TD target.
            (self.dones[batch_inds, env_indices] * (1 - self.timeouts[batch_inds, env_indices])).reshape(
                -1, 1
            ),
            self.rewards[batch_inds, env_indices].reshape(-1, 1),
        )
        returns = (
            self.mc_returns[batch_inds, env_indices].reshape(-1, 1),
            self.mc_valid[batch_inds, env_indices].reshape(-1, 1),
        )
        observations, actions, next_observations, dones, rewards = map(self.to_torch, data)
        mc_returns, mc_valid = map(self.to_torch, returns)
        return MonteCarloReplayBufferSamples(
            observations, actions, next_observations, dones, rewards, None, mc_returns, mc_valid
        )
