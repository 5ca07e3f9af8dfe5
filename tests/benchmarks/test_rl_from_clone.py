"""benchmarks/rl_from_clone.py end to end at tiny settings (its figures come from full runs, not from here)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import torch as th

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


def test_rl_from_clone_smoke_with_a_learned_router_fits_it_to_field_half_then_trains(tmp_path: Path) -> None:
    out = tmp_path / "learned"
    command = [
        sys.executable,
        str(REPO / "benchmarks" / "rl_from_clone.py"),
        "--smoke",
        "--out",
        str(out),
        "--router",
        "learned",
        "--distill-eval-episodes",
        "0",
    ]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    rounds = json.loads((out / "distill.json").read_text())["rounds"]
    assert all(0.0 <= round_["last_epoch"]["router_agreement"] <= 1.0 for round_ in rounds)
    assert all(round_["last_epoch"]["router_cross_entropy"] > 0.0 for round_ in rounds)
    assert json.loads((out / "run.json").read_text())["options"]["router"] == "learned"
    rows = [json.loads(line) for line in (out / "curve.jsonl").read_text().splitlines()]
    assert [row["steps"] for row in rows] == [1024, 2048, 2048]
    distilled = HybridPPO.load(out / "distilled.zip", device="cpu").policy
    final = HybridPPO.load(out / "final.zip", device="cpu").policy
    assert final.learned_router and final.n_skills == 2 and final.squash_mean
    # PPO (with the pull, after the warm-up's first rollout) moved the router as well as the heads
    assert not th.equal(distilled.router_net.weight, final.router_net.weight)


def test_rl_from_clone_smoke_with_a_log_std_schedule_a_decaying_learning_rate_and_the_sparse_reward(
    tmp_path: Path,
) -> None:
    out = tmp_path / "scheduled"
    script = str(REPO / "benchmarks" / "rl_from_clone.py")
    options = ["--smoke", "--distill-eval-episodes", "0", "--log-std", "-3", "--log-std-final", "-4"]
    command = [
        sys.executable,
        script,
        *options,
        "--lr-schedule",
        "linear",
        "--reward",
        "sparse",
        "--out",
        str(out),
    ]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    options_recorded = json.loads((out / "run.json").read_text())["options"]
    assert options_recorded["log_std_final"] == -4.0 and options_recorded["lr_schedule"] == "linear"
    assert json.loads((out / "run.json").read_text())["reward"] == "sparse"
    final = HybridPPO.load(out / "final.zip", device="cpu")
    # two rollouts of 1,024 steps out of 2,048: the second collected at half the schedule, -3.5, and kept
    for head in final.policy.heads:
        assert th.allclose(head.log_std, th.full_like(head.log_std, -3.5))
    assert final.lr_schedule(1.0) == 1e-4 and final.lr_schedule(0.25) == 0.25e-4
    for bad, message in [
        (["--log-std-final", "nan"], "--log-std-final must be a finite number"),
        (["--lr-schedule", "linear", "--hp", '{"learning_rate": "x"}'], "needs a numeric learning_rate"),
    ]:
        refused = [sys.executable, script, "--smoke", *bad, "--out", str(tmp_path / "refused")]
        completed = subprocess.run(refused, capture_output=True, text=True, timeout=300, cwd=tmp_path)
        assert completed.returncode == 2 and message in completed.stderr
        assert not (tmp_path / "refused").exists()  # refused before anything was written
