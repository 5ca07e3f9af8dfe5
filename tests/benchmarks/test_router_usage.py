"""benchmarks/router_usage.py: the skill each field half gets from a two-skill HybridPPO model."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

from sb3_hfo.hybrid_ppo import HybridPPO
from sb3_hfo.vec_env import make_hfo_vec_env

REPO = Path(__file__).resolve().parents[2]
_SPEC = importlib.util.spec_from_file_location("router_usage", REPO / "benchmarks" / "router_usage.py")
router_usage = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(router_usage)


def _model(**policy_kwargs: object) -> HybridPPO:
    env = make_hfo_vec_env("HFO/EmptyGoal-v0", 2, seed=0, monitor=False)
    return HybridPPO("MlpPolicy", env, seed=0, policy_kwargs={"domain": "hfo", **policy_kwargs})


def test_field_half_router_table_is_diagonal_and_learned_router_counts_every_step() -> None:
    fixed = router_usage.router_usage(_model(skills=2, router="field_half"), "HFO/EmptyGoal-v0", 4, seed=0)
    far, near = (fixed["steps"][half] for half in router_usage.HALVES)
    assert far[1] == 0 and near[0] == 0 and far[0] + near[1] > 0
    assert fixed["episodes"] == 4
    # both tables count the same steps
    assert sum(map(sum, fixed["steps_by_possession"].values())) == sum(map(sum, fixed["steps"].values()))
    learned = router_usage.router_usage(_model(skills=2, router="learned"), "HFO/EmptyGoal-v0", 4, seed=0)
    assert learned["router"] == "learned" and learned["episodes"] == 4
    for half in router_usage.HALVES:
        shares = learned["skill_share"][half]
        assert sum(learned["steps"][half]) == 0 or sum(shares) == pytest.approx(1.0, abs=1e-3)


def test_one_skill_model_is_refused() -> None:
    with pytest.raises(ValueError, match="skills > 1"):
        router_usage.router_usage(_model(), "HFO/EmptyGoal-v0", 2, seed=0)
