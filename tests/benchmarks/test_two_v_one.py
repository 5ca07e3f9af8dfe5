"""benchmarks/two_v_one.py end to end at tiny settings (its figures come from full runs, not from here)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import torch as th

from sb3_hfo.hybrid_ppo import HybridPPO

REPO = Path(__file__).resolve().parents[2]


def test_two_v_one_smoke_trains_both_arms_on_one_budget_and_evaluates_them(tmp_path: Path) -> None:
    out = tmp_path / "run"
    command = [sys.executable, str(REPO / "benchmarks" / "two_v_one.py"), "smoke", "--out", str(out)]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    runs = {arm: json.loads((out / f"arm_{arm}" / "run.json").read_text()) for arm in ("1v1", "2v1")}
    assert [runs[arm]["slots"] for arm in runs] == [4, 4] and [runs[arm]["games"] for arm in runs] == [4, 2]
    assert {runs[arm]["reward"] for arm in runs} == {"shaped_gap_refund"}
    for arm, strikers in (("1v1", 1), ("2v1", 2)):
        rows = [json.loads(line) for line in (out / f"arm_{arm}" / "curve.jsonl").read_text().splitlines()]
        # the same agent-step budget; the 2v1 arm plays half the game cycles
        assert [row["steps"] for row in rows] == [1024, 2048, 2048] and rows[-1]["final"]
        assert rows[-1]["eval"]["cycles"] == 2048 // strikers
        assert rows[-1]["eval"]["agents"] == [f"offense_{k}" for k in range(strikers)]
    # both arms start from one policy: the 2v1 start is the 1v1 start with zero weights on the teammate's block
    one = HybridPPO.load(out / "arm_1v1" / "start.zip", device="cpu").policy.state_dict()
    two = HybridPPO.load(out / "arm_2v1" / "start.zip", device="cpu").policy.state_dict()
    for key in one:
        if key.endswith("trunk.0.weight"):
            assert th.count_nonzero(two[key][:, 58:66]) == 0
            assert th.equal(th.cat([two[key][:, :58], two[key][:, 66:]], dim=1), one[key])
        else:
            assert th.equal(one[key], two[key]), key
    names = ["final_1v1", "final_2v1", "start_1v1", "zero_shot_2v1"]
    evaluation = {name: json.loads((out / f"eval_hfo2d_{name}.json").read_text()) for name in names}
    for result in evaluation.values():
        assert result["episodes"] == 4 == sum(result["status"].values())
    again = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert again.returncode != 0 and "already holds a run" in again.stderr
