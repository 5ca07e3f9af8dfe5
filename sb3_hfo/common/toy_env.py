"""A one-step hybrid-action toy task with HFO's flat action layout, for tests and benchmarks.

``HybridTargetEnv`` is a contextual bandit: each episode is one step. The observation holds two random context
features, the rest are zeros:

* ``obs[region_index] = r ~ U(-1, 1)``: which discrete action is right. ``r > 0`` (the "far half" of the HFO field
  router, see :class:`~sb3_hfo.common.routers.FieldHalfRouter`): DASH (preference 0), whose power (entry 3) must
  match the target; ``r <= 0``: KICK (preference 2), whose power (entry 6) must match it.
* ``obs[region_index + 1] = u ~ U(-1, 1)``: the target parameter is ``0.5 + 0.4 * u`` (DASH) or ``0.5 - 0.4 * u``
  (KICK), in the action's [0, 1] scale.

Action: ``Box(0, 1, (8,))`` like ``HFO/*-v0`` (``[pref_dash, pref_turn, pref_kick, dash_power, dash_dir, turn_dir,
kick_power, kick_dir]``, hfo2d's ``HFO_FLAT_ACTION_LAYOUT``), decoded by its rule. Reward: ``1 - 2 |p -
target|`` (in [0.2, 1]) for the right discrete action, ``-1`` otherwise. ``info["status"]`` is ``"GOAL"`` when the
discrete action is right and ``|p - target| < 0.1``, ``"OUT_OF_TIME"`` otherwise, and ``info["is_success"]`` is true
at a ``"GOAL"`` (as in HFO: SB3 logs it as ``rollout/success_rate``).
A correct agent needs both halves of a parameterised action: a discrete choice and a continuous parameter.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from sb3_hfo.hfo import DASH, HFO_DOMAIN, HFO_FLAT_ACTION_LAYOUT, KICK, hfo_flat_action_space

__all__ = ["HybridTargetEnv"]

#: DASH's and KICK's power entries (their first parameters) in HFO's flat action.
DASH_POWER_INDEX = HFO_FLAT_ACTION_LAYOUT.parameter_slice(DASH).start
KICK_POWER_INDEX = HFO_FLAT_ACTION_LAYOUT.parameter_slice(KICK).start
#: A parameter within this distance of its target counts as a "GOAL".
GOAL_TOLERANCE = 0.1


class HybridTargetEnv(gym.Env[np.ndarray, np.ndarray]):
    """One-step "pick the right discrete action and set its power" task (see the module docstring).

    :param obs_dim: observation size (default 58 like ``HFO/EmptyGoal-v0``).
    :param region_index: column of the region feature (default the column HFO's field-half router reads,
        :data:`sb3_hfo.hfo.HFO_DOMAIN`); the target feature sits at ``region_index + 1``.
    """

    metadata: dict[str, Any] = {"render_modes": []}

    def __init__(self, obs_dim: int = 58, region_index: int | None = None) -> None:
        if region_index is None:
            assert HFO_DOMAIN.field_half_column is not None
            region_index = HFO_DOMAIN.field_half_column
        if not 0 <= region_index < obs_dim - 1:
            raise ValueError(
                f"region_index must lie in [0, obs_dim - 1) = [0, {obs_dim - 1}), got {region_index}"
            )
        self.obs_dim = obs_dim
        self.region_index = region_index
        self.observation_space = spaces.Box(-1.0, 1.0, (obs_dim,), np.float32)
        self.action_space = hfo_flat_action_space()
        self._obs = np.zeros(obs_dim, dtype=np.float32)

    def _new_context(self) -> np.ndarray:
        self._obs = np.zeros(self.obs_dim, dtype=np.float32)
        self._obs[self.region_index : self.region_index + 2] = self.np_random.uniform(-1.0, 1.0, 2)
        return self._obs.copy()

    def correct_action(self, obs: np.ndarray) -> tuple[int, int, float]:
        """(discrete action, index of its power entry, target power in [0, 1]) for observation ``obs (obs_dim,)``."""
        region, u = float(obs[self.region_index]), float(obs[self.region_index + 1])
        if region > 0:
            return DASH, DASH_POWER_INDEX, 0.5 + 0.4 * u
        return KICK, KICK_POWER_INDEX, 0.5 - 0.4 * u

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict]:
        super().reset(seed=seed)
        return self._new_context(), {}

    def step(self, action: np.ndarray) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        action = np.clip(np.asarray(action, dtype=np.float64).reshape(HFO_FLAT_ACTION_LAYOUT.size), 0.0, 1.0)
        discrete, power_index, target = self.correct_action(self._obs)
        chosen = int(HFO_FLAT_ACTION_LAYOUT.choose(action))
        error = abs(float(action[power_index]) - target)
        if chosen == discrete:
            reward = 1.0 - 2.0 * error
            status = "GOAL" if error < GOAL_TOLERANCE else "OUT_OF_TIME"
        else:
            reward, status = -1.0, "OUT_OF_TIME"
        info = {"status": status, "is_success": status == "GOAL", "chosen": chosen, "error": error}
        return self._obs.copy(), reward, True, False, info
