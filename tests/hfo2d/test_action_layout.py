"""hfo2d.action_layout: the hybrid action layout the env and the policy share, and its decoding rule."""

from __future__ import annotations

import pickle
import subprocess
import sys

import numpy as np
import pytest
from gymnasium import spaces

from hfo2d.action_layout import (
    DASH,
    HFO_FLAT_ACTION_LAYOUT,
    KICK,
    TURN,
    HybridActionLayout,
    action_layout,
    hfo_flat_action_space,
)
from hfo2d.hfo_env import HFOEnv


def test_hfo_flat_layout_names_sizes_directions_and_kick() -> None:
    layout = HFO_FLAT_ACTION_LAYOUT
    assert layout.names == ("DASH", "TURN", "KICK") and layout.n_discrete == 3 and layout.size == 8
    assert [layout.parameter_slice(k) for k in (DASH, TURN, KICK)] == [slice(3, 5), slice(5, 6), slice(6, 8)]
    assert layout.direction_indices == (4, 5, 7) and layout.action_direction(KICK) == 7
    assert layout.ball_action == KICK
    masks = layout.parameter_masks()
    assert masks.tolist()[TURN] == [1, 1, 1, 0, 0, 1, 0, 0]
    assert layout.parameter_masks(with_preferences=False).tolist()[KICK] == [0, 0, 0, 0, 0, 0, 1, 1]


@pytest.mark.parametrize(
    ("preferences", "expected"),
    [((0.5, 0.5, 0.5), DASH), ((0.2, 0.7, 0.7), TURN), ((0.2, 0.1, 0.7), KICK), ((0.6, 0.1, 0.6), DASH)],
)
def test_decode_and_choose_take_the_first_largest_preference(preferences: tuple, expected: int) -> None:
    flat = [*preferences, 0.1, 0.2, 0.3, 0.4, 0.5]
    kind, parameters = HFO_FLAT_ACTION_LAYOUT.decode(flat)
    assert kind == expected and list(parameters) == flat[HFO_FLAT_ACTION_LAYOUT.parameter_slice(expected)]
    assert int(HFO_FLAT_ACTION_LAYOUT.choose(np.array(flat))) == expected


def test_the_env_plays_what_the_layout_decodes() -> None:
    env = HFOEnv()
    rng = np.random.default_rng(0)
    for _ in range(200):
        flat = rng.choice([0.0, 0.5, 1.0], size=8).astype(np.float32)  # ties are common
        kind, power, direction = env._parse_flat_action(flat)
        expected, parameters = HFO_FLAT_ACTION_LAYOUT.decode(flat.tolist())
        assert kind == expected
        # the parameters the env plays are the chosen action's, on rcssserver's scales (power 0-100, -180-180 deg)
        if kind == TURN:
            assert (power, direction) == (0.0, -180.0 + 360.0 * parameters[0])
        else:
            assert (power, direction) == (100.0 * parameters[0], -180.0 + 360.0 * parameters[1])


def test_the_hfo_envs_declare_the_layout_by_their_action_space() -> None:
    space = HFOEnv().action_space
    assert action_layout(space) == HFO_FLAT_ACTION_LAYOUT
    assert space == spaces.Box(0.0, 1.0, (8,), np.float32)  # equal to the plain Box older models saved
    assert action_layout(pickle.loads(pickle.dumps(space))) == HFO_FLAT_ACTION_LAYOUT
    assert action_layout(spaces.Box(0.0, 1.0, (8,), np.float32)) is None
    assert action_layout(HFOEnv(action_format="parameterized").action_space) is None
    assert action_layout(hfo_flat_action_space()) == HFO_FLAT_ACTION_LAYOUT


def test_bad_layouts_are_refused() -> None:
    with pytest.raises(ValueError, match="one parameter size per discrete action"):
        HybridActionLayout(names=("A", "B"), parameter_sizes=(1,))
    with pytest.raises(ValueError, match="direction_indices"):
        HybridActionLayout(names=("A",), parameter_sizes=(1,), direction_indices=(0,))
    with pytest.raises(ValueError, match="ball_action"):
        HybridActionLayout(names=("A",), parameter_sizes=(1,), ball_action=1)
    assert HybridActionLayout.from_sizes((2, 0)).size == 4


def test_hfo2d_imports_without_torch() -> None:
    code = "import sys; sys.modules['torch'] = None; import hfo2d, hfo2d.action_layout, hfo2d.symmetry"
    completed = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert completed.returncode == 0, completed.stderr[-2000:]
