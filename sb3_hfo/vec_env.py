"""hfo2d's batch (:mod:`hfo2d.vector`) as a Stable-Baselines3 ``VecEnv``.

``make_hfo_vec_env("HFO/Keeper-v1", 16, seed=0)`` is the fast counterpart of SB3's
``make_vec_env("HFO/Keeper-v1", 16, seed=0)``: the same games (game i seeded with seed + i, bit for bit the same
observations, rewards, dones and infos as a ``DummyVecEnv`` of ``gym.make(id)`` seeded alike), stepped by one batch
in this process (``num_workers=1``) or split into shards stepped in parallel (``num_workers=2`` on two cores: this
process and one worker process), without SB3's per-env wrappers and info copies.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterable, Sequence
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode
from stable_baselines3.common.vec_env import VecEnv, VecMonitor
from stable_baselines3.common.vec_env.base_vec_env import VecEnvIndices, VecEnvObs, VecEnvStepReturn

from hfo2d import ENV_IDS
from hfo2d.vector import HFOVectorEnv, ShardedHFOVectorEnv

__all__ = ["HFOVecEnv", "make_hfo_vec_env"]


class HFOVecEnv(VecEnv):
    """SB3's ``VecEnv`` interface over one hfo2d batch: ``HFOVecEnv(batch)``.

    Args:
        batch: an :class:`hfo2d.vector.HFOVectorEnv` (all games in this process, e.g.
            ``gym.make_vec("HFO/Keeper-v1", 16, vectorization_mode="vector_entry_point")``) or an
            :class:`hfo2d.vector.ShardedHFOVectorEnv` (one batch per worker process), with auto-reset mode
            ``SAME_STEP`` (their default). The adapter owns it: ``close()`` closes it.

    Most code wants :func:`make_hfo_vec_env`, which makes the batch, seeds it and wraps it in ``VecMonitor``.

    SB3's conventions, as its ``DummyVecEnv`` keeps them:

    * ``step`` returns float32 rewards and ``dones = terminated | truncated``; a game whose episode ended is
      reset at once (its returned observation is the new episode's) and its info is the last step's info with
      ``terminal_observation`` (the last observation) and ``TimeLimit.truncated`` (truncated, not terminated; on
      every step's info); the new episode's reset info goes to ``reset_infos``.
    * ``seed(s)`` makes the next ``reset()`` seed game i with ``s + i``; ``set_options`` (one dict for all games or
      one per game: HFOEnv's hand placements) applies to the next ``reset()``.
    * ``env_method`` / ``get_attr`` / ``set_attr`` reach the games (unwrapped ``hfo2d.HFOEnv`` s; with workers the
      values travel through pipes, so they must pickle), e.g. ``env_method("set_keeper_skill", 0.5)``.
    * ``get_images`` / ``render`` work when the games were made with ``render_mode="rgb_array"``.
    * ``env_is_wrapped`` is False for every wrapper: the games are not wrapped.
    """

    def __init__(self, batch: HFOVectorEnv | ShardedHFOVectorEnv) -> None:
        if not isinstance(batch, (HFOVectorEnv, ShardedHFOVectorEnv)):
            raise ValueError(
                f"HFOVecEnv wraps an hfo2d.vector.HFOVectorEnv or ShardedHFOVectorEnv, got {type(batch).__name__}"
            )
        if batch.autoreset_mode is not AutoresetMode.SAME_STEP:
            raise ValueError(
                f"HFOVecEnv needs a batch with autoreset_mode SAME_STEP (SB3's convention), got {batch.autoreset_mode}"
            )
        self.batch = batch
        self._actions: Any = None
        super().__init__(batch.num_envs, batch.single_observation_space, batch.single_action_space)
        #: The games' registered EnvSpec (None for a batch made from bare kwargs): SB3's VecMonitor writes its id
        #: into the monitor.csv header, as it does for a DummyVecEnv of gym.make(id).
        self.spec = gym.spec(batch.env_id) if batch.env_id else None

    # --- stepping ------------------------------------------------------------------------------------------------
    def reset(self) -> VecEnvObs:
        per_game = self._options if any(self._options) else None
        infos = self.batch.reset_games(seed=list(self._seeds), per_game_options=per_game)
        self.reset_infos = infos
        self._reset_seeds()
        self._reset_options()
        return self.batch._observations.copy()

    def step_async(self, actions: np.ndarray) -> None:
        self._actions = actions

    def step_wait(self) -> VecEnvStepReturn:
        infos = self.batch.step_games(self._actions)
        terminations = self.batch._terminations
        truncations = self.batch._truncations
        dones = terminations | truncations
        reset_infos = self.reset_infos
        for index in np.flatnonzero(dones):
            reset_info = infos[index]
            final_info = reset_info.pop("final_info")
            final_info["terminal_observation"] = reset_info.pop("final_obs")
            infos[index] = final_info
            reset_infos[index] = reset_info
        for info, terminated, truncated in zip(
            infos, terminations.tolist(), truncations.tolist(), strict=True
        ):
            info["TimeLimit.truncated"] = truncated and not terminated
        return (
            self.batch._observations.copy(),
            self.batch._rewards.astype(np.float32),  # DummyVecEnv's reward dtype
            dones,
            infos,
        )

    def close(self) -> None:
        self.batch.close()

    # --- the games ---------------------------------------------------------------------------------------------
    def get_images(self) -> Sequence[np.ndarray | None]:
        if self.render_mode != "rgb_array":
            warnings.warn(
                f"the games' render_mode is {self.render_mode!r}; get_images needs 'rgb_array' "
                "(make_hfo_vec_env(..., render_mode='rgb_array'))",
                stacklevel=2,
            )
            return [None] * self.num_envs
        return list(self.batch.render())

    def get_attr(self, attr_name: str, indices: VecEnvIndices = None) -> list[Any]:
        return self.batch.get_attr_games(attr_name, _sb3_indices(indices))

    def set_attr(self, attr_name: str, value: Any, indices: VecEnvIndices = None) -> None:
        chosen = _sb3_indices(indices)
        # SB3 sets one value on every chosen env (a list value is one value, not one per env)
        self.batch.set_attr_games(
            attr_name, [value] * (self.num_envs if chosen is None else len(chosen)), chosen
        )

    def env_method(
        self, method_name: str, *method_args: Any, indices: VecEnvIndices = None, **method_kwargs: Any
    ) -> list[Any]:
        return self.batch.call_games(method_name, method_args, method_kwargs, _sb3_indices(indices))

    def env_is_wrapped(self, wrapper_class: type[gym.Wrapper], indices: VecEnvIndices = None) -> list[bool]:
        chosen = _sb3_indices(indices)
        return [False] * (self.num_envs if chosen is None else len(chosen))

    def __repr__(self) -> str:
        return f"HFOVecEnv({self.batch!r})"


def _sb3_indices(indices: VecEnvIndices) -> list[int] | None:
    if indices is None:
        return None
    if isinstance(indices, (int, np.integer)):
        return [int(indices)]
    assert isinstance(indices, Iterable)
    return list(indices)


def make_hfo_vec_env(
    env_id: str,
    n_envs: int,
    seed: int | None = None,
    num_workers: int = 1,
    monitor: bool = True,
    **env_kwargs: Any,
) -> VecEnv:
    """``n_envs`` games of the hfo2d id ``env_id`` as an SB3 ``VecEnv`` (an :class:`HFOVecEnv`), like SB3's
    ``make_vec_env(env_id, n_envs, seed)`` but batched.

    Args:
        env_id: ``"HFO/EmptyGoal-v0"``, ``"HFO/StaticKeeper-v0"``, ``"HFO/Keeper-v0"`` or ``"HFO/Keeper-v1"``.
        n_envs: the number of games.
        seed: game i's first episode is seeded with ``seed + i`` (None: unseeded).
        num_workers: 1 steps every game in this process; more splits them into that many shards stepped in
            parallel, one by this process and one by each of ``num_workers - 1`` worker processes
            (:class:`hfo2d.vector.ShardedHFOVectorEnv`; one shard per core pays off; a worker costs a process
            start, ~1 s, and ~40 MiB).
        monitor: wrap in SB3's ``VecMonitor`` (episode returns and lengths in ``info["episode"]`` and the
            logger's ``rollout/ep_rew_mean``), as ``make_vec_env`` wraps each env in ``Monitor``.
        **env_kwargs: :class:`hfo2d.HFOEnv`'s arguments beyond the id's own, with ``gym.make``'s rules (e.g.
            ``keeper_skill=0.5``, ``reward="sparse"``; ``goalie="hfo2d"`` on Keeper-v1 is a ValueError).
    """
    if env_id not in ENV_IDS:
        raise ValueError(f"make_hfo_vec_env takes an hfo2d id, one of {tuple(ENV_IDS)}; got {env_id!r}")
    if num_workers == 1:
        batch: HFOVectorEnv | ShardedHFOVectorEnv = gym.make_vec(
            env_id, n_envs, vectorization_mode="vector_entry_point", **env_kwargs
        )
    else:
        batch = ShardedHFOVectorEnv(env_id, n_envs, num_workers, **env_kwargs)
    vec_env: VecEnv = HFOVecEnv(batch)
    if seed is not None:
        vec_env.seed(seed)
    if monitor:
        vec_env = VecMonitor(vec_env)
    return vec_env
