"""benchmarks/paper_budget.py: the training curve read back from SB3's own stdout tables."""

from __future__ import annotations

import importlib.util
from pathlib import Path
from types import ModuleType

import pytest
from stable_baselines3.common.logger import HumanOutputFormat, Logger

REPO = Path(__file__).resolve().parents[2]


def _script() -> ModuleType:
    spec = importlib.util.spec_from_file_location("paper_budget", REPO / "benchmarks" / "paper_budget.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _write_log(path: Path, rows: list[tuple[int, float, float | None]]) -> None:
    """SB3's stdout tables as SkillDDPG's runs print them: (episodes, rollout rate, eval rate or None) per dump."""
    with path.open("w") as file:
        logger = Logger(folder=None, output_formats=[HumanOutputFormat(file)])
        for episodes, rate, eval_rate in rows:
            logger.record("rollout/ep_len_mean", 120.0)
            logger.record("rollout/episodes", episodes)
            logger.record("rollout/success_rate", rate)
            if eval_rate is not None:  # the periodic greedy evaluation's own success_rate: not the curve
                logger.record("eval/success_rate", eval_rate)
            logger.record("time/episodes", episodes)
            logger.record("time/total_timesteps", 100 * episodes)
            logger.dump(100 * episodes)


def test_the_curve_pairs_each_rollout_rate_with_its_episodes_and_ignores_evaluations(tmp_path: Path) -> None:
    module = _script()
    log = tmp_path / "train.log"
    # a run stopped after 12 episodes and resumed from its checkpoint at 8: 12 is logged twice, the later row wins
    _write_log(log, [(4, 0.0, None), (8, 0.25, 1.0), (12, 0.5, None), (12, 0.75, None), (16, 1.0, 0.0)])
    assert module.read_curve(log) == {4: 0.0, 8: 0.25, 12: 0.75, 16: 1.0}
    table = module.table({"run": module.read_curve(log)}, every=8)
    assert table.splitlines()[2:] == ["| 0-8 | 12 % |", "| 8-16 | 88 % |"]


def test_a_log_without_tables_is_named(tmp_path: Path) -> None:
    log = tmp_path / "empty.log"
    log.write_text("Using cpu device\n")
    with pytest.raises(SystemExit, match="holds no SB3 table"):
        _script().read_curve(log)
