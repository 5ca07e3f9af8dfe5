"""Demonstrations from a scripted striker in the replay buffer before training (an option beyond the paper).

:class:`DemonstrationPrefillCallback` plays ``episodes`` episodes of one of :mod:`hfo2d.strikers`' scripted
strikers in the training envs when training starts and stores their transitions in the model's replay buffer, as
SB3's own rollout collection would store the agent's (scaled actions, terminal observations, time-limit flags).
The agent's own experience then replaces them first-in first-out. The strikers read only the observation, so the
demonstrations are what the same env would have produced under that policy.
"""

from __future__ import annotations

import numpy as np
from stable_baselines3.common.callbacks import BaseCallback

from hfo2d.strikers import STRIKERS, make_striker


class DemonstrationPrefillCallback(BaseCallback):
    """Fill the replay buffer with ``episodes`` episodes of the scripted striker ``striker`` before training.

    Args:
        striker: a name of :data:`hfo2d.strikers.STRIKERS`.
        episodes: episodes to store (at least 1), counted over all training envs.
        verbose: 1 prints the demonstrations' goal rate.

    Needs envs with HFOEnv's ``"flat"`` action format and observations in the paper's layout (the strikers' input).
    """

    def __init__(self, striker: str = "soft_dribble", episodes: int = 200, verbose: int = 0) -> None:
        super().__init__(verbose)
        if striker not in STRIKERS:
            raise ValueError(f"striker must be one of {tuple(STRIKERS)}, got {striker!r}")
        if isinstance(episodes, bool) or not isinstance(episodes, int) or episodes < 1:
            raise ValueError(f"episodes must be an integer >= 1, got {episodes!r}")
        self.striker = striker
        self.episodes = episodes
        self.goals = 0
        self.stored = 0

    def _on_training_start(self) -> None:
        env = self.training_env
        model = self.model
        strikers = [make_striker(self.striker) for _ in range(env.num_envs)]
        obs = env.reset()
        finished = 0
        while finished < self.episodes:
            actions = np.stack([striker(o) for striker, o in zip(strikers, obs, strict=True)])
            new_obs, rewards, dones, infos = env.step(actions)
            next_obs = new_obs.copy()
            for i, done in enumerate(dones):
                if done:
                    next_obs[i] = infos[i]["terminal_observation"]
                    strikers[i].reset()
                    finished += 1
                    self.goals += bool(infos[i].get("is_success", False))
            model.replay_buffer.add(obs, next_obs, model.policy.scale_action(actions), rewards, dones, infos)
            self.stored += env.num_envs
            obs = new_obs
        # training starts from fresh episodes, as after SB3's own _setup_learn
        model._last_obs = env.reset()
        model._last_episode_starts = np.ones((env.num_envs,), dtype=bool)
        if self.verbose:
            print(
                f"demonstrations: {finished} episodes of {self.striker} ({self.stored} transitions), "
                f"{self.goals / finished:.1%} goals"
            )
        self.logger.record("demonstrations/goal_rate", self.goals / finished)

    def _on_step(self) -> bool:
        return True
