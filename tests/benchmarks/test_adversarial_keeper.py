"""benchmarks/adversarial_keeper.py end to end at tiny settings, and its opponent pool (figures: full runs only)."""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
from pathlib import Path
from types import ModuleType

import numpy as np
from gymnasium import spaces

from sb3_hfo.hybrid_ppo import HybridPPO
from sb3_hfo.multi_agent import make_team_vec_env

REPO = Path(__file__).resolve().parents[2]


def _script() -> ModuleType:
    spec = importlib.util.spec_from_file_location(
        "adversarial_keeper", REPO / "benchmarks" / "adversarial_keeper.py"
    )
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class _Constant:
    observation_space = spaces.Box(-1.0, 1.0, (3,), np.float32)
    action_space = spaces.Box(0.0, 1.0, (2,), np.float32)

    def __init__(self, value: float) -> None:
        self.value = value

    def predict(self, observations: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
        return np.full((len(observations), 2), self.value, dtype=np.float32), None


def test_the_pool_gives_half_the_games_to_the_current_striker() -> None:
    script = _script()
    assert script.pool_assignment(5, 1) == [0] * 5
    assert script.pool_assignment(6, 3) == [2, 2, 2, 0, 1, 0]
    pool = script.OpponentPool([_Constant(0.25), _Constant(0.75)], [1, 0, 1])
    actions, _ = pool.predict(np.zeros((3, 3), dtype=np.float32))
    np.testing.assert_array_equal(actions[:, 0], [0.75, 0.25, 0.75])


def test_the_smoke_run_trains_both_sides_and_reports(tmp_path: Path) -> None:
    start = HybridPPO(
        "MlpPolicy", make_team_vec_env(1, offense_agents=1, defense_npcs=1, seed=0), n_steps=8, seed=0
    )
    start.save(tmp_path / "start.zip")
    out = tmp_path / "run"
    command = [
        sys.executable,
        str(REPO / "benchmarks" / "adversarial_keeper.py"),
        "--smoke",
        "--out",
        str(out),
        "--striker",
        str(tmp_path / "start.zip"),
    ]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    goalie = HybridPPO.load(out / "round1" / "goalie.zip", device="cpu")
    assert (
        goalie.action_space.shape == (11,) and goalie.num_timesteps >= 64
    )  # DASH, TURN, TACKLE, KICK, CATCH
    striker = HybridPPO.load(out / "round1" / "striker.zip", device="cpu")
    assert striker.num_timesteps >= 64
    assert not all(
        (a == b).all() for a, b in zip(start.policy.parameters(), striker.policy.parameters(), strict=True)
    )
    rounds = [json.loads(line) for line in (out / "rounds.jsonl").read_text().splitlines()]
    assert [row["round"] for row in rounds] == [1]
    report = json.loads((out / "report.json").read_text())
    matches = [row["match"] for row in report["rows"]]
    assert "e6_imitation vs learned goalie" in matches and "scripted long_shot vs agent2d goalie" in matches
    for row in report["rows"]:
        assert sum(row["statuses"].values()) == row["episodes"] == 2
        assert row["goal_rate_ci95"][0] <= row["goal_rate"] <= row["goal_rate_ci95"][1]
