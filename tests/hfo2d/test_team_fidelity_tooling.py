"""benchmarks/team_fidelity.py without a real HFO: its smoke mode in hfo2d, and the report that joins backends."""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import pytest


def test_smoke_mode_plays_both_configurations_in_hfo2d(
    tmp_path: Path, benchmark_script: Callable[[str], ModuleType]
) -> None:
    script = benchmark_script("team_fidelity")
    out = tmp_path / "sim.json"
    result = script.main(
        ["play", "--backends", "hfo2d", "--smoke", "--strikers", "soft_dribble", "--out", str(out)]
    )
    assert json.loads(out.read_text())["cells"] == json.loads(json.dumps(result["cells"]))
    cells = result["cells"]
    assert [(c["config"], c["offense_agents"], c["backend"]) for c in cells] == [
        ("1v2", 1, "hfo2d"),
        ("2v2", 2, "hfo2d"),
    ]
    for cell in cells:
        assert cell["episodes"] == script.SMOKE_EPISODES == len(cell["statuses"])
        assert set(cell["statuses"]) <= set(script.STATUSES)
        assert cell["summary"]["n"] == cell["episodes"] and cell["defense_npcs"] == 2
        assert sum(cell["summary"]["statuses"].values()) == cell["episodes"]
    # the same seed plays the same episodes
    again = script.main(["play", "--backends", "hfo2d", "--smoke", "--strikers", "soft_dribble"])
    assert [c["statuses"] for c in again["cells"]] == [c["statuses"] for c in cells]


def _cell(backend: str, statuses: list[str], script: ModuleType) -> dict:
    return {
        "config": "2v2",
        "striker": "soft_dribble",
        "backend": backend,
        "episodes": len(statuses),
        "server_down": 0,
        "summary": script.rate_summary(statuses),
        "mean_steps": 50.0,
        "wall_s": 1.0,
        "load_1min": [1.0, 1.0],
    }


def test_report_joins_the_backends_and_takes_real_minus_hfo2d(
    tmp_path: Path, benchmark_script: Callable[[str], ModuleType]
) -> None:
    script = benchmark_script("team_fidelity")
    real = tmp_path / "real.json"
    sim = tmp_path / "sim.json"
    real.write_text(json.dumps({"cells": [_cell("real", ["GOAL"] * 3 + ["CAPTURED_BY_DEFENSE"], script)]}))
    sim.write_text(json.dumps({"cells": [_cell("hfo2d", ["GOAL"] + ["OUT_OF_BOUNDS"] * 3, script)]}))
    out = tmp_path / "joined.json"
    result = script.main(["report", str(real), str(sim), "--out", str(out)])
    (row,) = result["rows"]
    assert row["diff"] == pytest.approx(0.75 - 0.25)
    assert row["se"] == pytest.approx(math.sqrt(0.75 * 0.25 / 4 + 0.25 * 0.75 / 4))
    assert row["real"]["summary"]["statuses"] == {"GOAL": 3, "CAPTURED_BY_DEFENSE": 1}
    assert json.loads(out.read_text())["rows"][0]["config"] == "2v2"


def test_it_refuses_no_episodes(benchmark_script: Callable[[str], ModuleType]) -> None:
    script = benchmark_script("team_fidelity")
    with pytest.raises(SystemExit, match="episodes"):
        script.main(["play", "--backends", "hfo2d", "--episodes", "0"])
