"""sb3_hfo.demonstrations: a scripted striker's episodes in the replay buffer, and cloning a striker into the actor."""

from __future__ import annotations

import numpy as np
import pytest
import torch as th
from stable_baselines3.common.env_util import make_vec_env

import hfo2d  # noqa: F401  (registers the ids)
from hfo2d.strikers import make_striker
from sb3_hfo import SkillDDPG
from sb3_hfo.demonstrations import (
    DemonstrationPrefillCallback,
    StrikerCloningCallback,
    _play_round,
    clone_striker,
)
from sb3_hfo.skill_ddpg.acting import CriticChoice


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


def _cloning_model(env_id: str = "HFO/EmptyGoal-v0", seed: int = 0, **policy_kwargs: object) -> SkillDDPG:
    env = make_vec_env(env_id, n_envs=2, seed=0)
    kwargs = dict(
        net_arch=[64, 64],
        n_skills=2,
        skill_router="field_half",
        domain="hfo",
        inverting_gradients=False,
        weight_init_std=0.08,
    )
    kwargs.update(policy_kwargs)
    return SkillDDPG("HFOPolicy", env, learning_starts=10_000, seed=seed, policy_kwargs=kwargs)


#: A fit that learns the striker's choices from 4 episodes in a few seconds.
FIT = dict(rounds=1, episodes_per_round=4, epochs=40, batch_size=32, learning_rate=3e-3, seed=1)


def _actor_state(model: SkillDDPG) -> dict[str, th.Tensor]:
    return {k: v.clone() for k, v in model.policy.actor.state_dict().items()}


def test_round_labels_are_the_strikers_actions_in_the_visited_states() -> None:
    model = _cloning_model()
    env = model.get_env()
    env.seed(5)
    observations, labels, goals = _play_round(model, env, "mid_shot", 3, expert_acts=True, progress=None)
    striker = make_striker("mid_shot")  # keeps no state between cycles
    expected = model.policy.scale_action(np.stack([striker(obs) for obs in observations]))
    np.testing.assert_allclose(labels, expected, atol=1e-6)
    assert observations.shape == (labels.shape[0], env.observation_space.shape[0])
    assert goals == 3  # mid_shot scores on the empty goal from these starts


def test_cloning_teaches_the_actor_the_strikers_choices_and_repeats_with_its_seed() -> None:
    model = _cloning_model()
    env = model.get_env()
    env.seed(FIT["seed"])
    observations, labels, _ = _play_round(model, env, "mid_shot", 4, expert_acts=True, progress=None)

    def recall() -> list[float]:  # per discrete action: how often the actor picks it where the striker does
        picked = model.predict(observations, deterministic=True)[0][:, :3].argmax(1)
        wanted = labels[:, :3].argmax(1)
        return [float(np.mean(picked[wanted == k] == k)) for k in range(3)]

    untrained = recall()
    history = clone_striker(model, "mid_shot", **FIT)
    assert [entry.round for entry in history] == [0, 1]
    assert history[0].goal_rate == 1.0  # round 0 is the striker's own play
    assert history[0].loss > 0 and np.isnan(history[1].loss)
    assert history[1].transitions > history[0].transitions
    # on the striker's round-0 states the fitted actor picks the striker's DASH / TURN / KICK far more often
    # (round 0 replays these states: same seed, the striker acting)
    # (mostly DASH: always dashing would score 0 on TURN and KICK)
    fitted = recall()
    assert min(fitted[0], fitted[2]) >= 0.9 and np.mean(fitted) >= 0.75 > np.mean(untrained), (
        untrained,
        fitted,
    )
    # the target actor follows the fitted actor
    for online, target in zip(
        model.policy.actor.parameters(), model.policy.actor_target.parameters(), strict=True
    ):
        th.testing.assert_close(online, target)
    # the same seed gives the same actor
    again = _cloning_model()
    clone_striker(again, "mid_shot", **FIT)
    for key, value in _actor_state(model).items():
        th.testing.assert_close(value, again.policy.actor.state_dict()[key])
    # without a seed, the model's own seed (an rl-zoo3 run's --seed) decides
    unseeded = {key: value for key, value in FIT.items() if key != "seed"}
    by_model_seed, by_argument = _cloning_model(seed=FIT["seed"]), _cloning_model(seed=FIT["seed"])
    clone_striker(by_model_seed, "mid_shot", **unseeded)
    clone_striker(by_argument, "mid_shot", **FIT)
    for key, value in _actor_state(by_model_seed).items():
        th.testing.assert_close(value, by_argument.policy.actor.state_dict()[key])


def test_cloning_refuses_bad_arguments_and_leaves_the_actor_alone() -> None:
    model = _cloning_model()
    before = _actor_state(model)
    bad = [
        (dict(striker="nobody"), "striker must be one of"),
        (dict(rounds=0), "rounds must be an integer"),
        (dict(episodes_per_round=1.5), "episodes_per_round must be an integer"),
        (dict(epochs=True), "epochs must be an integer"),
        (dict(learning_rate=float("nan")), "learning_rate must be a finite number"),
        (dict(kick_weight=0), "kick_weight must be a finite number"),
        (dict(seed=-1), "seed must be an integer"),
    ]
    for kwargs, message in bad:
        with pytest.raises(ValueError, match=message):
            clone_striker(model, **kwargs)  # type: ignore[arg-type]
    model.policy.acting = (*model.policy.acting, CriticChoice())
    with pytest.raises(ValueError, match="acting without 'critic'.*got acting 'critic'"):
        clone_striker(model)
    for key, value in before.items():
        th.testing.assert_close(value, model.policy.actor.state_dict()[key])
    with pytest.raises(ValueError, match="unknown clone_striker arguments"):
        StrikerCloningCallback(episodes=3)
    with pytest.raises(ValueError, match="train_after must be True or False"):
        StrikerCloningCallback(train_after="no")  # type: ignore[arg-type]


def test_cloning_callback_stops_training_after_cloning_unless_asked() -> None:
    model = _cloning_model()
    before = _actor_state(model)
    callback = StrikerCloningCallback(striker="mid_shot", rounds=1, episodes_per_round=2, epochs=2)
    model.learn(1_000, callback=callback)
    assert len(callback.history) == 2
    assert model.num_timesteps == model.get_env().num_envs  # stopped at the first step
    changed = [not th.equal(value, model.policy.actor.state_dict()[key]) for key, value in before.items()]
    assert any(changed)
    going_on = _cloning_model()
    going_on.learn(
        30,
        callback=StrikerCloningCallback(
            train_after=True, striker="mid_shot", rounds=1, episodes_per_round=2, epochs=1
        ),
    )
    assert going_on.num_timesteps >= 30
