"""HFO's mirror symmetry (hfo2d.symmetry) against the simulator itself, with noise off."""

from __future__ import annotations

from collections.abc import Callable

import gymnasium as gym
import numpy as np
import pytest

import hfo2d
from hfo2d.features import GOAL_POST_BOTTOM_PROXIMITY, GOAL_POST_TOP_PROXIMITY, SELF_BODY_SIN
from hfo2d.symmetry import (
    feature_mirror,
    mirror_features,
    mirror_flat_action,
    start_offset_is_drawn,
    start_y_is_clamped,
)

STARTS = [
    {"player": (20.0, 8.0, 30.0), "ball": (25.0, 12.0), "keeper": (49.0, 2.0, 170.0)},
    {"player": (35.0, -15.0, -60.0), "ball": (36.0, -14.0), "keeper": (50.0, -3.0, 180.0)},
]


def mirrored_start(start: dict[str, tuple[float, ...]]) -> dict[str, tuple[float, ...]]:
    """The placement options of the mirror image: y and angles change sign."""
    return {name: (x, -y, *(-angle for angle in rest)) for name, (x, y, *rest) in start.items()}


def play_mirrored(
    env_id: str, start: dict[str, tuple[float, ...]], pick: Callable[[gym.Env, np.ndarray, int], np.ndarray]
) -> tuple[int, str, float]:
    """Play ``start`` and its mirror image side by side, the mirror with mirrored actions; assert every step's
    features, reward and end agree; return (steps, final status, largest feature difference)."""
    if env_id == "HFO/EmptyGoal-v0":
        start = {name: place for name, place in start.items() if name != "keeper"}
    env, mirror_env = gym.make(env_id, noise=False), gym.make(env_id, noise=False)
    obs, _ = env.reset(seed=3, options=start)
    mirror_obs, _ = mirror_env.reset(seed=3, options=mirrored_start(start))
    largest = float(np.abs(mirror_features(obs) - mirror_obs).max())
    steps, done, status = 0, False, ""
    while not done:
        action = pick(env, obs, steps)
        obs, reward, terminated, truncated, info = env.step(action)
        mirror_obs, mirror_reward, *ends, mirror_info = mirror_env.step(
            mirror_flat_action(action).astype(np.float32)
        )
        steps += 1
        largest = max(largest, float(np.abs(mirror_features(obs) - mirror_obs).max()))
        assert ends == [terminated, truncated] and mirror_info["status"] == info["status"], steps
        assert mirror_reward == pytest.approx(reward, abs=1e-5), steps
        done, status = terminated or truncated, info["status"]
    return steps, status, largest


@pytest.mark.parametrize("env_id", list(hfo2d.ENV_IDS))
@pytest.mark.parametrize("start", STARTS)
def test_a_mirrored_episode_of_the_scripted_striker_is_the_mirror_image(
    env_id: str, start: dict[str, tuple[float, ...]]
) -> None:
    steps, status, largest = play_mirrored(
        env_id, start, lambda env, obs, _: hfo2d.heuristic(env.unwrapped, obs)
    )
    assert status in ("GOAL", "CAPTURED_BY_DEFENSE") and steps > 5
    assert largest < 1e-4


@pytest.mark.parametrize("env_id", ["HFO/Keeper-v0", "HFO/EmptyGoal-v0"])
def test_random_actions_stay_mirror_images(env_id: str) -> None:
    rng = np.random.default_rng(0)
    actions = rng.random((400, 8)).astype(np.float32)  # dashes, turns and kicks in every direction
    steps, _, largest = play_mirrored(env_id, STARTS[0], lambda env, obs, step: actions[step])
    assert steps > 20 and largest < 1e-4


def test_feature_mirror_is_an_involution_that_swaps_top_and_bottom() -> None:
    features = np.random.default_rng(1).uniform(-1.0, 1.0, size=(5, 74)).astype(np.float32)  # 2 other players
    once = mirror_features(features)
    assert once.dtype == np.float32 and once.shape == features.shape
    np.testing.assert_array_equal(mirror_features(once), features)
    np.testing.assert_array_equal(once[:, GOAL_POST_TOP_PROXIMITY], features[:, GOAL_POST_BOTTOM_PROXIMITY])
    np.testing.assert_array_equal(once[:, SELF_BODY_SIN], -features[:, SELF_BODY_SIN])
    source, sign = feature_mirror(66)
    assert sorted(source) == list(range(66)) and set(sign) == {-1.0, 1.0}


def test_mirror_flat_action_reflects_the_three_directions_only() -> None:
    action = np.array([0.9, 0.1, 0.2, 0.7, 0.25, 1.0, 0.4, 0.0], dtype=np.float32)
    np.testing.assert_allclose(mirror_flat_action(action), [0.9, 0.1, 0.2, 0.7, 0.75, 0.0, 0.4, 1.0])
    assert mirror_flat_action([0.5] * 8).tolist() == [0.5] * 8


@pytest.mark.parametrize("n_features", [57, 59, 65, True])
def test_feature_mirror_rejects_a_length_that_is_not_hfos(n_features: int) -> None:
    with pytest.raises(ValueError, match="58 \\+ 8 \\* players"):
        feature_mirror(n_features)


def test_mirror_flat_action_rejects_other_shapes() -> None:
    with pytest.raises(ValueError, match="8 entries"):
        mirror_flat_action([0.5] * 7)


def test_hfos_start_distribution_is_not_its_own_mirror_image() -> None:
    # The agent's y offset from the ball is 10.5 * (U(0, 1) + o), o in {-2, -1, 1, 2}: offsets in (-10.5, 0) are
    # drawn, their mirror images in (0, 10.5) never (away from the side lines, where y is clamped).
    env = gym.make("HFO/EmptyGoal-v0")
    offsets = []
    for seed in range(600):
        _, info = env.reset(seed=seed)
        if not start_y_is_clamped(info["player"][1]):
            offsets.append(info["player"][1] - info["ball"][1])
    offsets_array = np.array(offsets)
    assert len(offsets) > 400
    assert np.sum((offsets_array > -10.5) & (offsets_array < 0.0)) > 60
    assert np.sum((offsets_array > 0.0) & (offsets_array < 10.5)) == 0
    assert np.sum(offsets_array > 21.0) > 60 and np.sum(offsets_array < -21.0) == 0
    assert all(start_offset_is_drawn(offset) for offset in offsets)
    mirrors_drawn = np.mean([start_offset_is_drawn(-offset) for offset in offsets])
    assert 0.4 < mirrors_drawn < 0.6  # o = -1 or 2: half the draws, less the clamped ones
    assert not start_offset_is_drawn(5.0) and start_offset_is_drawn(-5.0) and not start_offset_is_drawn(-25.0)
