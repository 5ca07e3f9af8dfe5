"""benchmarks/rl_from_clone.py end to end at tiny settings (its figures come from full runs, not from here)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from sb3_hfo.hybrid_ppo import HybridPPO

REPO = Path(__file__).resolve().parents[2]


def test_rl_from_clone_smoke_distils_the_clone_then_trains_with_the_pull(tmp_path: Path) -> None:
    out = tmp_path / "run"
    command = [sys.executable, str(REPO / "benchmarks" / "rl_from_clone.py"), "--smoke", "--out", str(out)]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    distilled = json.loads((out / "distill.json").read_text())
    assert [round_["states"] > 0 for round_ in distilled["rounds"]] == [
        True,
        True,
    ]  # e6's games, then a DAgger round
    assert distilled["rounds"][1]["states"] > distilled["rounds"][0]["states"]
    assert sum(distilled["greedy_eval"]["status"].values()) == distilled["greedy_eval"]["episodes"] == 4
    rows = [json.loads(line) for line in (out / "curve.jsonl").read_text().splitlines()]
    assert [row["final"] for row in rows] == [False, False, True]
    assert [row["steps"] for row in rows] == [1024, 2048, 2048]
    record = json.loads((out / "run.json").read_text())
    assert record["method"] == "reinforcement learning from reward, started from the imitation clone"
    assert record["reward"] == "shaped_gap_refund" and record["teacher"] == "e6_imitation"
    final = HybridPPO.load(out / "final.zip", device="cpu")
    assert final.policy.squash_mean and final.policy.n_skills == 2
    assert final.reference_policy is None  # the reference is not saved
    assert final.reference_coef(1.0) == 1.0 and final.reference_coef(0.0) == 0.0
    # the smoke run's warm-up covers its first rollout only: the distilled actor then moved
    distilled_policy = HybridPPO.load(out / "distilled.zip", device="cpu").policy
    assert not all(
        (a == b).all()
        for a, b in zip(distilled_policy.heads.parameters(), final.policy.heads.parameters(), strict=True)
    )
    again = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert again.returncode == 2 and "already holds a run" in again.stderr
