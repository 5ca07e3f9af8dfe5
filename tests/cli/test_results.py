"""The results table (devtools/results_page.py) is generated from the manifest's evaluations and cannot drift."""

from __future__ import annotations

import copy
import importlib.util
import sys
from pathlib import Path
from types import ModuleType

import pytest

from sb3_hfo.models import read_manifest

RESULTS_PAGE_SCRIPT = Path(__file__).resolve().parents[2] / "devtools" / "results_page.py"


def _load_script(path: Path) -> ModuleType:
    """Import a script of the repository's devtools/ by its path (devtools/ is not a package on sys.path)."""
    spec = importlib.util.spec_from_file_location(path.stem, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[path.stem] = module  # dataclasses look their module up in sys.modules
    spec.loader.exec_module(module)
    return module


results = _load_script(RESULTS_PAGE_SCRIPT)
BEGIN_MARKER = results.BEGIN_MARKER
END_MARKER = results.END_MARKER
README_PATH = results.README_PATH
RESULTS_PAGE_PATH = results.RESULTS_PAGE_PATH
TASKS = results.TASKS
readme_block = results.readme_block
results_page = results.results_page
table = results.table
with_readme_block = results.with_readme_block

REGENERATE = "run python devtools/results_page.py to regenerate it from sb3_hfo/pretrained/manifest.json"


def test_the_readme_table_is_what_the_manifest_gives() -> None:
    readme = README_PATH.read_text()
    assert readme.count(BEGIN_MARKER) == 1 and readme.count(END_MARKER) == 1
    assert readme == with_readme_block(readme, readme_block(read_manifest())), REGENERATE


def test_the_results_page_is_what_the_manifest_gives() -> None:
    assert RESULTS_PAGE_PATH.read_text() == results_page(read_manifest()), REGENERATE


def _entry(goals: int, episodes: int = 1000, real: tuple[int, int] | None = None) -> dict:
    from sb3_hfo.evaluation import wilson_interval

    def rate(goals: int, episodes: int) -> dict:
        return {
            "goals": goals,
            "episodes": episodes,
            "scoring_rate": goals / episodes,
            "scoring_rate_ci95": list(wilson_interval(goals, episodes)),
        }

    return {
        "config": "zoo_configs/empty_goal_skill_pdqn_fast.yml",
        "seed": 4,
        "evaluation": rate(goals, episodes),
        "real_hfo": {**rate(*real), "env_id": "HFO/RealKeeper-v0"} if real else None,
    }


def test_each_task_gets_one_row_with_its_evaluation() -> None:
    models = {"e1": _entry(988), "e6": _entry(348, real=(300, 1000)), "extra": _entry(500)}
    lines = table(models).splitlines()
    rows = lines[2:]
    assert len(rows) == len(TASKS) + 1  # every task, then the model no task names
    e1 = next(row for row in rows if row.startswith("| E1 "))
    assert (
        "**98.8 % [97.9, 99.3]**" in e1
        and "`e1` (empty_goal_skill_pdqn_fast, seed 4)" in e1
        and e1.endswith("| not measured |")
    )
    e6 = next(row for row in rows if "`e6`" in row)
    assert "34.8 % [31.9, 37.8]" in e6 and "30.0 % [27.2, 32.9] (against agent2d's goalie)" in e6
    assert sum("no committed model yet" in row for row in rows) == len(TASKS) - 2
    assert rows[-1].startswith("| extra | - | **50.0 %")


def test_a_benchmark_script_s_model_shows_its_script_and_command() -> None:
    """A model without a zoo config ("config": null) is named by its script in the table and its page gives the
    script's exact command."""
    script = "benchmarks/rl_from_clone.py"
    command = f"python {script} --seed 1 --out DIR --steps 2000000"
    entry = {
        **_entry(920, real=(921, 1000)),
        "config": None,
        "script": script,
        "command": command,
        "seed": 1,
        "method": "reinforcement learning from reward, started from the imitation clone e6_imitation",
        "file": "e6.zip",
        "bytes": 1,
        "env_id": "HFO/Keeper-v1",
        "env_kwargs": {},
        "acting": None,
        "source": "the final model",
        "evaluation_machine": "a test",
        "evaluation_command": "python -m sb3_hfo.evaluate e6",
    }
    entry["evaluation"] = {
        **entry["evaluation"],
        "status_counts": {"GOAL": 920, "OUT_OF_BOUNDS": 80},
        "seed": 0,
    }
    entry["real_hfo"]["source"] = "a real-HFO run"
    row = next(row for row in table({"e6": entry}).splitlines() if "`e6`" in row)
    assert (
        "`e6` (rl_from_clone, seed 1; reinforcement learning from reward, started from the imitation" in row
    )
    page = results_page({"e6": entry})
    assert f"* trained with: `{script}` (a benchmark script, no zoo config), seed 1: `{command}`" in page


def test_a_changed_evaluation_changes_the_generated_table() -> None:
    models = read_manifest()
    changed = copy.deepcopy(models)
    name = next(iter(changed))
    changed[name]["evaluation"]["scoring_rate"] = 0.5
    assert table(changed) != table(models)


def test_the_readme_block_needs_both_markers() -> None:
    with pytest.raises(ValueError, match="results markers"):
        with_readme_block("# a readme\n", "table\n")
    text = f"a\n{BEGIN_MARKER}\nold\n{END_MARKER}\nb\n"
    assert with_readme_block(text, "new\n") == f"a\n{BEGIN_MARKER}\nnew\n{END_MARKER}\nb\n"


def test_the_script_checks_the_checkout_from_its_command_line(tmp_path: Path) -> None:
    """``python devtools/results_page.py --check`` from another folder: the checkout's files are up to date."""
    import subprocess

    completed = subprocess.run(
        [sys.executable, str(RESULTS_PAGE_SCRIPT), "--check"], cwd=tmp_path, capture_output=True, text=True
    )
    assert completed.returncode == 0, completed.stderr[-2000:]
