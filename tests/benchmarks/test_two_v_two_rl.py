"""benchmarks/two_v_two_rl.py end to end at tiny settings: PPO from a routed start, then its evaluation."""

from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

from hfo2d.team import TeamGame

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "benchmarks" / "two_v_two_rl.py"


def run(*arguments: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, str(SCRIPT), *arguments], capture_output=True, text=True, cwd=REPO, timeout=180
    )


def test_the_script_trains_an_arm_from_its_start_and_evaluates_start_and_final(tmp_path: Path) -> None:
    trained = run("train", "--arm", "2v2", "--out", str(tmp_path), "--smoke")
    assert trained.returncode == 0, trained.stderr[-2000:]
    folder = tmp_path / "arm_2v2"
    assert {"start.zip", "final.zip", "run.json", "curve.jsonl"} <= {path.name for path in folder.iterdir()}
    rows = [json.loads(line) for line in (folder / "curve.jsonl").read_text().splitlines()]
    assert rows[-1]["final"] and rows[-1]["steps"] >= 512
    evaluated = run("evaluate", "--out", str(tmp_path), "--episodes", "2", "--games", "2")
    assert evaluated.returncode == 0, evaluated.stderr[-2000:]
    for which in ("start", "final"):
        result = json.loads((tmp_path / f"eval_hfo2d_2v2_{which}.json").read_text())
        assert result["episodes"] == 2 and sum(result["status"].values()) == 2
    assert "skipping 1v2 start" in evaluated.stdout  # the arm that was not trained is named, not invented


def test_a_start_of_another_arm_or_a_second_run_in_one_folder_is_refused(tmp_path: Path) -> None:
    assert run("train", "--arm", "2v2", "--out", str(tmp_path), "--smoke").returncode == 0
    again = run("train", "--arm", "2v2", "--out", str(tmp_path), "--smoke")
    assert again.returncode != 0 and "already holds a run" in again.stderr
    wrong = run(
        "train", "--arm", "1v2", "--start", str(tmp_path / "arm_2v2" / "final.zip"), "--out", str(tmp_path)
    )
    assert wrong.returncode != 0 and "is it this arm's routed clone" in wrong.stderr
    missing = run("train", "--arm", "1v2", "--out", str(tmp_path / "other"))
    assert missing.returncode == 2 and "--start is required" in missing.stderr


def game_observations(script: ModuleType, steps: int) -> list[np.ndarray]:
    """Both strikers' HFO-master vectors over ``steps`` cycles of the scripted own_pass pair in 2v2."""
    game = TeamGame(2, 0, 2, seed=4, feature_set="hfo")
    observations, _ = game.reset(seed=4)
    rule = script.ScriptedPredictor("own_pass", 1)
    batches = []
    for _ in range(steps):
        batch = np.stack([observations[name] for name in game.agent_names])
        batches.append(batch)
        observations, _, terminated, truncated, _ = game.step(
            dict(zip(game.agent_names, rule.predict(batch)[0], strict=True))
        )
        if terminated or truncated:
            observations, _ = game.reset()
    return batches


def test_a_mixed_team_without_models_is_the_rule_and_the_play_model_reads_the_vector_without_its_mate(
    benchmark_script: Callable[[str], ModuleType],
) -> None:
    script = benchmark_script("two_v_two_rl")
    read_team_view = sys.modules["two_v_two_scripted"].read_team_view  # the sibling the script imported
    team = script.MixedTeam(None, [])
    rule = script.ScriptedPredictor("own_pass", 1)
    assert len(team.alone_columns) == 77  # HFO master's 1v2 vector: 58 + 9 * 2 + 1
    for batch in game_observations(script, 40):
        np.testing.assert_array_equal(team.predict(batch)[0], rule.predict(batch)[0])
        for observation in batch:
            with_mate = read_team_view(observation, 1, 2)
            alone = read_team_view(observation[team.alone_columns], 0, 2)
            assert alone.percept == with_mate.percept and alone.field_defenders == with_mate.field_defenders
            assert alone.teammates == ()
    with pytest.raises(ValueError, match="not both"):
        script.MixedTeam(object(), ["play"], play_model=object())
