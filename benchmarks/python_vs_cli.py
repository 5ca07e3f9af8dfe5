"""Training steps per second from Python (the README's "Use" snippet) and from the CLI, in the same run.

Usage::

    python benchmarks/python_vs_cli.py --steps 3000 --rounds 1 --out /tmp/python_vs_cli.json

Contestants, each a fresh Python process (torch's thread count is per process), run one after the other in each
of ``--rounds`` rounds so that load from other processes affects them alike:

* ``python``: the README's "Use" snippet: ``gym.make("HFO/EmptyGoal-v0")``, ``SkillDDPG("HFOPolicy", env,
  policy_kwargs=dict(n_skills=2, skill_router="field_half"), tensorboard_log=..., verbose=1)``,
  ``learn(--steps, progress_bar=True)``, ``save``; only ``seed=0`` and the step count are added;
* ``cli``: the same model through ``python -m sb3_hfo.train --env HFO/EmptyGoal-v0 --conf-file <yaml>
  --tensorboard-log ... -P --seed 0 -f ...``, the YAML holding the same ``policy_kwargs`` and ``n_timesteps``;
* ``python_torch_default_threads`` (unless ``--no-default-threads``): the snippet with ``OMP_NUM_THREADS`` set to
  torch's own default thread count, which ``learn`` takes as the user's choice and keeps: how the Python API ran
  before it chose the CLI's thread count.

Each process times its ``learn`` call from the first to the last environment step with a callback (the same one
in all: ``LearnTimer``, listed under the YAML's ``callback:`` for the CLI), so that start-up, env creation and
saving are excluded and only training is compared. The report gives steps/s, the torch thread count seen during
``learn``, the ratio python / cli, and the 1-minute load average before and after (the measuring machine may be
shared).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from stable_baselines3.common.callbacks import BaseCallback

REPO = Path(__file__).resolve().parents[1]
ENV_ID = "HFO/EmptyGoal-v0"
#: The line a child process prints its measurement on (JSON after the marker).
MARKER = "PYTHON_VS_CLI_RESULT "


class LearnTimer(BaseCallback):
    """Print ``learn``'s steps per second (training start to end) and torch's thread count on one line."""

    def _on_training_start(self) -> None:
        import torch as th

        self.threads = th.get_num_threads()
        self.start_steps = self.num_timesteps
        self.start = time.perf_counter()

    def _on_step(self) -> bool:
        return True

    def _on_training_end(self) -> None:
        seconds = time.perf_counter() - self.start
        steps = self.num_timesteps - self.start_steps
        result = {"steps": steps, "seconds": seconds, "steps_per_s": steps / seconds, "threads": self.threads}
        print(MARKER + json.dumps(result), flush=True)


def run_python_snippet(steps: int, folder: Path) -> None:
    """The README's "Use" snippet (plus ``seed=0``, the step count and the timing callback)."""
    import gymnasium as gym

    from sb3_hfo import SkillDDPG

    env = gym.make(ENV_ID)
    model = SkillDDPG(
        "HFOPolicy",
        env,
        policy_kwargs=dict(n_skills=2, skill_router="field_half", domain="hfo"),
        tensorboard_log=str(folder / "tb"),
        verbose=1,
        seed=0,
    )
    model.learn(steps, progress_bar=True, callback=LearnTimer())
    model.save(folder / "skill_ddpg_empty_goal")


def cli_command(steps: int, folder: Path) -> list[str]:
    """``python -m sb3_hfo.train`` with a config equivalent to the snippet (writes the YAML into ``folder``)."""
    config = folder / "use_snippet.yml"
    config.write_text(
        f"{ENV_ID}:\n"
        "  policy: HFOPolicy\n"
        f"  n_timesteps: {steps}\n"
        "  policy_kwargs: \"dict(n_skills=2, skill_router='field_half')\"\n"
        "  callback:\n"
        "    - python_vs_cli.LearnTimer\n"
    )
    command = [sys.executable, "-m", "sb3_hfo.train", "--env", ENV_ID, "--conf-file", str(config)]
    return command + [
        "--tensorboard-log",
        str(folder / "tb"),
        "-P",
        "--seed",
        "0",
        "-f",
        str(folder / "logs"),
    ]


def measure(name: str, steps: int, default_threads: int) -> dict[str, Any]:
    """Run contestant ``name`` in a fresh process and return its measurement."""
    env = {
        **os.environ,
        "PYTHONPATH": os.pathsep.join(filter(None, [str(REPO / "benchmarks"), os.environ.get("PYTHONPATH")])),
    }
    for variable in ("OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        env.pop(variable, None)
    with tempfile.TemporaryDirectory(prefix="python_vs_cli_") as tmp:
        folder = Path(tmp)
        if name == "cli":
            command = cli_command(steps, folder)
        else:
            command = [
                sys.executable,
                str(Path(__file__).resolve()),
                "--child",
                "--steps",
                str(steps),
                "--folder",
                tmp,
            ]
            if name == "python_torch_default_threads":
                env["OMP_NUM_THREADS"] = str(default_threads)
        completed = subprocess.run(command, capture_output=True, text=True, env=env, cwd=tmp)
    if completed.returncode != 0:
        raise SystemExit(f"{name} failed (exit {completed.returncode}):\n{completed.stderr[-3000:]}")
    lines = [line for line in completed.stdout.splitlines() if line.startswith(MARKER)]
    if not lines:
        raise SystemExit(f"{name} printed no result:\n{completed.stdout[-3000:]}")
    # rl-zoo3 may hand the same callback object to SB3 twice; the figures are the same learn call's.
    result = json.loads(lines[0][len(MARKER) :])
    print(f"  {name}: {result['steps_per_s']:.1f} steps/s", file=sys.stderr, flush=True)
    return result


def torch_default_threads() -> int:
    """torch's thread count in a fresh process without OMP_NUM_THREADS / MKL_NUM_THREADS."""
    env = {
        key: value for key, value in os.environ.items() if key not in ("OMP_NUM_THREADS", "MKL_NUM_THREADS")
    }
    command = [sys.executable, "-c", "import torch; print(torch.get_num_threads())"]
    return int(subprocess.run(command, capture_output=True, text=True, env=env, check=True).stdout)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--steps", type=int, default=3000, help="environment steps per learn call (default 3000)"
    )
    parser.add_argument(
        "--rounds", type=int, default=1, help="rounds of all contestants; medians are reported"
    )
    parser.add_argument(
        "--no-default-threads", action="store_true", help="leave out python_torch_default_threads"
    )
    parser.add_argument("--out", type=Path, default=None, help="write the results as JSON here")
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--folder", type=Path, default=None, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.steps < 1 or args.rounds < 1:
        parser.error("--steps and --rounds must be >= 1")
    if args.child:
        run_python_snippet(args.steps, args.folder)
        return 0

    names = ["python", "cli"] + ([] if args.no_default_threads else ["python_torch_default_threads"])
    default_threads = 0 if args.no_default_threads else torch_default_threads()
    load_before = os.getloadavg()[0]
    samples: dict[str, list[dict[str, Any]]] = {name: [] for name in names}
    for _ in range(args.rounds):
        for name in names:
            samples[name].append(measure(name, args.steps, default_threads))
    load_after = os.getloadavg()[0]
    rates = {name: statistics.median(s["steps_per_s"] for s in runs) for name, runs in samples.items()}
    results = {
        "steps": args.steps,
        "rounds": args.rounds,
        "cpu_count": os.cpu_count(),
        "torch_default_threads": default_threads or None,
        "load_average_1min_before": load_before,
        "load_average_1min_after": load_after,
        "steps_per_s": rates,
        "threads": {name: [s["threads"] for s in runs] for name, runs in samples.items()},
        "samples": samples,
        "ratio_python_vs_cli": rates["python"] / rates["cli"],
    }
    if "python_torch_default_threads" in rates:
        results["ratio_default_threads_vs_cli"] = rates["python_torch_default_threads"] / rates["cli"]
    print(
        f"{args.steps} steps, {args.rounds} round(s), load average {load_before:.2f} -> {load_after:.2f} "
        f"on {os.cpu_count()} CPUs"
    )
    for name in names:
        print(f"  {name:30s} {rates[name]:8.1f} steps/s  (torch threads {results['threads'][name]})")
    print(f"  python / cli = {results['ratio_python_vs_cli']:.2f}")
    if args.out is not None:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(json.dumps(results, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
