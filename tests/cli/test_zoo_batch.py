"""``vec_env: batch`` in an rl-zoo3 config: ``python -m sb3_hfo.train`` steps the ``n_envs`` games through hfo2d's
batch (``sb3_hfo.vec_env.make_hfo_vec_env``) instead of rl-zoo3's ``DummyVecEnv``, and trains the same model.

One subprocess trains the HybridPPO E1 config three times at a tiny size (the batch in one process, the batch on
two worker processes, rl-zoo3's ``DummyVecEnv``); the tests compare what the runs left in their folders. The
refusals run in-process: they fail before any env is made.
"""

from __future__ import annotations

import csv
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import torch as th
from stable_baselines3.common.save_util import load_from_zip_file

REPO = Path(__file__).resolve().parents[2]
CONFIG = REPO / "zoo_configs" / "hybrid_ppo_empty_goal.yml"
ENV = "HFO/EmptyGoal-v0"
RUN = Path("hybrid_ppo") / "HFO-EmptyGoal-v0_1"
#: 16 games x 64 steps x 2 rollouts: each game ends at least one 100-cycle episode.
TINY = [
    *("--algo", "hybrid_ppo", "--env", ENV, "--conf-file", str(CONFIG), "--seed", "3", "-n", "2048"),
    *("--num-threads", "1", "--log-interval", "1", "--eval-freq", "64", "--eval-episodes", "1"),
    *("--hyperparams", "n_steps:64", "batch_size:256", "n_epochs:2"),
    "policy_kwargs:dict(net_arch=[16,16],log_std_init=-0.5)",
]
VARIANTS = {
    "batch": [],
    "batch_two_workers": ["num_workers:2"],
    "dummy": ["vec_env:'dummy'"],
}

# Each run's stdout (SB3's log tables) to its own file; the report says "ok" or the traceback per run.
DRIVER = """
import contextlib, json, sys, traceback
from sb3_hfo.cli.train import main
runs, root = json.loads(sys.argv[1]), sys.argv[2]
report = {}
for name, argv in runs.items():
    with open(f"{root}/{name}.out", "w") as out, contextlib.redirect_stdout(out):
        try:
            main([*argv, "-f", f"{root}/{name}"])
            report[name] = "ok"
        except BaseException:
            report[name] = traceback.format_exc()
with open(f"{root}/report.json", "w") as f:
    json.dump(report, f)
"""


@pytest.fixture(scope="module")
def runs(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("zoo_batch")
    argvs = {name: [*TINY, *extra] for name, extra in VARIANTS.items()}
    environment = {**os.environ, "OMP_NUM_THREADS": "1", "PYTHONPATH": os.pathsep.join(sys.path)}
    completed = subprocess.run(
        [sys.executable, "-c", DRIVER, json.dumps(argvs), str(root)],
        cwd=root,
        env=environment,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    report_file = root / "report.json"
    assert report_file.is_file(), completed.stderr[-3000:]
    report = json.loads(report_file.read_text())
    for name, outcome in report.items():
        assert outcome == "ok", f"{name}:\n{outcome}"
    return root


def _weights(root: Path, name: str) -> dict[str, th.Tensor]:
    _, params, _ = load_from_zip_file(root / name / RUN / "HFO-EmptyGoal-v0.zip")
    assert params is not None
    return params["policy"]


def _monitor_rows(files: list[Path]) -> list[tuple[float, int]]:
    """Every episode's (return, length) in the files, sorted (the batch writes them in order of episode end)."""
    rows = []
    for file in files:
        lines = file.read_text().splitlines()[1:]  # after the JSON header line
        rows += [(float(row["r"]), int(row["l"])) for row in csv.DictReader(lines)]
    return sorted(rows, key=lambda row: (round(row[0], 4), row[1]))


def test_the_batch_trains_the_same_model_as_rl_zoo_s_dummy_vec_env(runs: Path) -> None:
    # hfo2d's batch plays game i bit for bit like gym.make(id) seeded with seed + i, so the weights match exactly.
    reference = _weights(runs, "dummy")
    for name in ("batch", "batch_two_workers"):
        weights = _weights(runs, name)
        assert weights.keys() == reference.keys()
        for key, tensor in reference.items():
            assert th.equal(weights[key], tensor), f"{name}: {key} differs from the DummyVecEnv run's"


def test_the_batch_writes_one_monitor_file_with_every_episode(runs: Path) -> None:
    dummy_files = sorted((runs / "dummy" / RUN).glob("*.monitor.csv"))
    assert len(dummy_files) == 16  # rl-zoo3's Monitor: one file per env
    expected = _monitor_rows(dummy_files)
    assert len(expected) >= 16
    for name in ("batch", "batch_two_workers"):
        folder = runs / name / RUN
        assert [path.name for path in folder.glob("*monitor.csv")] == ["monitor.csv"]
        rows = _monitor_rows([folder / "monitor.csv"])
        assert [length for _, length in rows] == [length for _, length in expected]
        # VecMonitor sums the float32 rewards; Monitor rounds its float64 sum to 6 decimals
        np.testing.assert_allclose([r for r, _ in rows], [r for r, _ in expected], atol=1e-5)


@pytest.mark.parametrize("name", list(VARIANTS))
def test_the_log_has_the_goal_rate_and_episode_statistics(runs: Path, name: str) -> None:
    log = (runs / f"{name}.out").read_text()
    for key in ("success_rate", "ep_rew_mean", "ep_len_mean", "episodes"):
        assert f"| {key} " in log or f"|    {key} " in log, f"{name}: no {key} in the log"
    assert "Eval num_timesteps" in log  # rl-zoo3's EvalCallback ran beside the batch


@pytest.mark.parametrize(
    ("extra", "expected"),
    [
        (["--checkpoint-freq", "100"], "--checkpoint-freq / --resume need rl-zoo3's DummyVecEnv"),
        (
            ["--vec-env", "subproc"],
            "--vec-env SubprocVecEnv and vec_env: batch (the config's) exclude each other",
        ),
        (["--hyperparams", "num_workers:0"], "num_workers must be a positive integer, got 0"),
        (["--hyperparams", "vec_env:'subproc'"], "vec_env must be one of dummy, batch, got 'subproc'"),
        (["--hyperparams", "vec_env:'dummy'", "num_workers:2"], "num_workers applies to vec_env: batch only"),
        (
            ["--hyperparams", "env_wrapper:'gymnasium.wrappers.ClipReward'"],
            "env_wrapper wraps each env, and vec_env: batch has no per-game wrappers",
        ),
    ],
)
def test_what_the_batch_cannot_do_is_refused_in_one_line(
    capsys: pytest.CaptureFixture[str], tmp_path: Path, extra: list[str], expected: str
) -> None:
    from sb3_hfo.cli.train import main

    logs = tmp_path / "logs"
    with pytest.raises(SystemExit) as raised:
        main(["--algo", "hybrid_ppo", "--env", ENV, "--conf-file", str(CONFIG), "-f", str(logs), *extra])
    assert raised.value.code == 2
    error = capsys.readouterr().err.strip().splitlines()[-1]
    assert error.startswith("error: ") and expected in error
    assert not logs.exists() or not any(logs.rglob("*"))  # no run folder left behind
