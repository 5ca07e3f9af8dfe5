"""sb3_hfo.demonstrations: a scripted striker's episodes in the replay buffer, and cloning a striker into the actor."""

from __future__ import annotations

import numpy as np
import pytest
from stable_baselines3.common.env_util import make_vec_env

import hfo2d  # noqa: F401  (registers the ids)
from hfo2d.strikers import make_striker
from sb3_hfo import SkillDDPG
from sb3_hfo.demonstrations import DemonstrationPrefillCallback


def test_prefill_stores_the_strikers_episodes_as_sb3_would() -> None:
    env = make_vec_env("HFO/EmptyGoal-v0", n_envs=1, seed=3)
    # learning_starts beyond the budget: after the prefill only the rollout runs, no gradient step.
    model = SkillDDPG("HFOPolicy", env, learning_starts=10_000, seed=0)
    prefill = DemonstrationPrefillCallback(striker="mid_shot", episodes=2)
    model.learn(1, callback=prefill)

    buffer = model.replay_buffer
    stored = prefill.stored
    assert stored == buffer.pos - 1  # the demonstrations, then the one learning step
    observations, actions = buffer.observations[:stored, 0], buffer.actions[:stored, 0]
    # each stored action is the striker's for its observation (mid_shot keeps no state), in the actor's [-1, 1]
    # scale, exactly as SB3 stores its own
    striker = make_striker("mid_shot")
    expected = model.policy.scale_action(np.stack([striker(obs) for obs in observations]))
    np.testing.assert_allclose(actions, expected, atol=1e-6)
    assert actions.min() >= -1.0 and actions.max() <= 1.0
    # two episodes: an episode's last transition is terminal and holds the terminal observation, every other one
    # continues into the next stored observation
    dones = buffer.dones[:stored, 0]
    assert dones.sum() == 2 and dones[-1] == 1.0
    first_end = int(np.flatnonzero(dones)[0])
    continuing = np.flatnonzero(dones == 0.0)
    np.testing.assert_array_equal(buffer.next_observations[continuing, 0], observations[continuing + 1])
    assert not np.allclose(buffer.next_observations[first_end, 0], observations[first_end + 1])
    assert prefill.goals == 2  # mid_shot scores both against the empty goal from these starts
    # the agent's own first transition follows the demonstrations, and the demonstrations count as no timesteps
    assert model.num_timesteps == 1
    assert not np.allclose(buffer.observations[stored, 0], observations[-1])


def test_prefill_refuses_bad_arguments() -> None:
    with pytest.raises(ValueError, match="striker must be one of"):
        DemonstrationPrefillCallback(striker="nobody")
    for episodes in (0, -1, 1.5, True):
        with pytest.raises(ValueError, match="episodes must be an integer"):
            DemonstrationPrefillCallback(episodes=episodes)  # type: ignore[arg-type]
