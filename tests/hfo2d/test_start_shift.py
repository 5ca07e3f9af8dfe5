"""hfo2d's start_shift: the ball's (and so the agent's) start moved toward the goal, for start-distance curricula."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import hfo2d  # noqa: F401  (registers the ids)
from hfo2d.hfo_env import MAX_START_SHIFT


def _start(seed: int, **kwargs: float) -> dict:
    env = gym.make("HFO/Keeper-v1", **kwargs)
    _, info = env.reset(seed=seed)
    return info


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_shift_moves_the_ball_by_the_shift_and_draws_nothing_more(seed: int) -> None:
    plain, zero, shifted = _start(seed), _start(seed, start_shift=0.0), _start(seed, start_shift=20.0)
    assert zero["ball"] == plain["ball"] and zero["player"] == plain["player"]
    assert shifted["ball"][0] == pytest.approx(plain["ball"][0] + 20.0)
    assert shifted["ball"][1] == plain["ball"][1]
    # the agent starts relative to the ball (HFO's offsets), clamped to the pitch
    if plain["player"][0] > -0.1:  # not clamped at the halfway line
        assert shifted["player"][0] == pytest.approx(min(plain["player"][0] + 20.0, 52.5))
    else:
        assert -0.1 <= shifted["player"][0] < 20.0 - 0.1
    assert shifted["player"][1] == plain["player"][1]


def test_set_start_shift_applies_from_the_next_reset_and_refuses_bad_values() -> None:
    env = gym.make("HFO/Keeper-v1").unwrapped
    _, before = env.reset(seed=5)
    env.set_start_shift(MAX_START_SHIFT)
    _, after = env.reset(seed=5)
    assert after["ball"][0] == pytest.approx(before["ball"][0] + MAX_START_SHIFT)
    assert 52.5 - after["ball"][0] >= 7.0 - 1e-9  # still clear of the goal line
    for bad in (-1.0, MAX_START_SHIFT + 0.5, float("nan"), True, "3"):
        with pytest.raises(ValueError, match="start_shift"):
            env.set_start_shift(bad)  # type: ignore[arg-type]
        with pytest.raises(ValueError, match="start_shift"):
            gym.make("HFO/Keeper-v1", start_shift=bad)
    assert env.start_shift == MAX_START_SHIFT
    assert np.isfinite(after["ball"][0])
