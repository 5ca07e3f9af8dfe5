"""Training env steps per second on HFO/Keeper-v1: HybridPPO on hfo2d's batch against SkillDDPG (E6), in one run.

Usage::

    python benchmarks/training_throughput.py --rounds 3 --seconds 60 --out benchmarks/results/training_throughput.json

Issue 33 (item 3) asks that HybridPPO train on ``HFO/Keeper-v1`` with 16 games at >= 20x SkillDDPG's env steps per
second, measured in the same run. The contestants train through ``python -m sb3_hfo.train`` (rl-zoo3, one torch
thread: the CLI's default), each in a fresh process, with their configs' hyperparameters on ``HFO/Keeper-v1``:

* ``hybrid_ppo``: ``zoo_configs/hybrid_ppo_empty_goal.yml``'s recipe (16 games on hfo2d's batch, ``vec_env: batch``:
  ``sb3_hfo.vec_env.make_hfo_vec_env``; 256 steps per game per rollout, minibatches of 512, 10 epochs,
  64-64 networks, reward normalisation), its ``HFO/EmptyGoal-v0`` section written under ``HFO/Keeper-v1`` into a
  temporary config (``--num-workers 2``: the batch on two processes);
* ``skill_ddpg``: the paper's E6 config ``zoo_configs/e6_keeper_skills_fast.yml`` as it is (4 envs in rl-zoo3's
  ``DummyVecEnv``, one batch-128 update per step of the 4 envs, 2 skills).

Each runs ``--seconds`` of wall-clock time after its warm-up (SkillDDPG: its ``learning_starts`` random steps and
1,000 more with updates; HybridPPO: its first two rollouts and updates), timed by a callback (:class:`SliceTimer`)
from one rollout's start to a later rollout's start, so that a PPO slice holds whole collect-and-update cycles and
process start-up, env creation and saving are left out. Periodic evaluation is off (``--eval-freq -1``). The
contestants alternate in each of ``--rounds`` rounds, so that load from other processes affects both alike; the
report gives each round's steps/s, steps per CPU-second of the training process, the medians and their ratio,
torch's thread count during training, the CPU model and the load average (``uptime``) before and after.

``--smoke`` shrinks both (tiny networks, short warm-up) for tests: its figures mean nothing. ``--profile`` instead
prints where HybridPPO's time goes: cProfile of ``learn`` over ``--profile-rollouts`` rollouts (after one of warm-up),
the same recipe built in this process from Python (``make_hfo_vec_env`` in ``VecNormalize``, one torch thread).
"""

from __future__ import annotations

import argparse
import cProfile
import json
import os
import platform
import pstats
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import yaml
from stable_baselines3.common.callbacks import BaseCallback

REPO = Path(__file__).resolve().parents[1]
ENV_ID = "HFO/Keeper-v1"
HYBRID_PPO_CONFIG = REPO / "zoo_configs" / "hybrid_ppo_empty_goal.yml"
HYBRID_PPO_SECTION = "HFO/EmptyGoal-v0"
SKILL_DDPG_CONFIG = REPO / "zoo_configs" / "e6_keeper_skills_fast.yml"
CONTESTANTS = ("hybrid_ppo", "skill_ddpg")
#: The line a contestant's process prints its measurement on (JSON after the marker).
MARKER = "TRAINING_THROUGHPUT_RESULT "
#: rl-zoo3's step budget: far more than a slice takes, so that no schedule ends and nothing stops early.
BUDGET_STEPS = 10**9
#: Steps with updates that SkillDDPG plays after its random warm-up before the slice starts.
SKILL_DDPG_WARMUP_UPDATES = 1_000


class SliceTimer(BaseCallback):
    """Time ``seconds`` of training after ``warmup_steps`` env steps, from one rollout's start to a later one's
    (SB3 updates between rollouts, so the slice holds whole collect-and-update cycles), then stop ``learn`` and
    print the measurement on one line (:data:`MARKER`)."""

    def __init__(self, seconds: float, warmup_steps: int, verbose: int = 0) -> None:
        super().__init__(verbose)
        self.seconds = float(seconds)
        self.warmup_steps = int(warmup_steps)
        self.start: tuple[float, float, int] | None = None  # wall-clock s, CPU s, env steps
        self.finished = False

    def _on_rollout_start(self) -> None:
        if self.finished:
            return
        now = (time.perf_counter(), time.process_time(), self.num_timesteps)
        if self.start is None:
            if self.num_timesteps >= self.warmup_steps:
                self.start = now
            return
        seconds = now[0] - self.start[0]
        if seconds < self.seconds:
            return
        import torch as th

        steps = now[2] - self.start[2]
        result = {
            "steps": steps,
            "seconds": seconds,
            "cpu_seconds": now[1] - self.start[1],
            "steps_per_s": steps / seconds,
            "steps_per_cpu_s": steps / max(now[1] - self.start[1], 1e-9),
            "warmup_steps": self.start[2],
            "torch_threads": th.get_num_threads(),
            "n_envs": self.training_env.num_envs,
            "vec_env": _vec_env_chain(self.training_env),
        }
        print(MARKER + json.dumps(result), flush=True)
        self.finished = True

    def _on_step(self) -> bool:
        return not self.finished


def _vec_env_chain(vec_env: Any) -> str:
    """``VecNormalize < VecMonitor < HFOVecEnv``: what the contestant trained on."""
    names = []
    while vec_env is not None:
        names.append(type(vec_env).__name__)
        vec_env = getattr(vec_env, "venv", None)
    return " < ".join(names)


def _section(config: Path, env_id: str) -> dict[str, Any]:
    with open(config) as f:
        return dict(yaml.safe_load(f)[env_id])


def write_config(
    name: str,
    folder: Path,
    seconds: float,
    smoke: bool,
    num_workers: int,
    skill_ddpg_config: Path = SKILL_DDPG_CONFIG,
) -> Path:
    """The contestant's config for ``HFO/Keeper-v1`` with :class:`SliceTimer` added to its callbacks."""
    if name == "hybrid_ppo":
        hyperparams = _section(HYBRID_PPO_CONFIG, HYBRID_PPO_SECTION)
        if num_workers > 1:
            hyperparams["num_workers"] = num_workers
        if smoke:
            hyperparams.update(n_steps=32, batch_size=128, n_epochs=1)
            hyperparams["policy_kwargs"] = {**hyperparams["policy_kwargs"], "net_arch": [8, 8]}
        warmup = 2 * int(hyperparams["n_steps"]) * int(hyperparams["n_envs"])
    else:
        hyperparams = _section(skill_ddpg_config, ENV_ID)
        if smoke:
            hyperparams.update(learning_starts=64, buffer_size=2_000, batch_size=16)
            hyperparams["policy_kwargs"] = {**hyperparams["policy_kwargs"], "net_arch": [8, 8]}
        warmup = int(hyperparams["learning_starts"]) + (16 if smoke else SKILL_DDPG_WARMUP_UPDATES)
    timer = {"training_throughput.SliceTimer": {"seconds": seconds, "warmup_steps": warmup}}
    hyperparams["callback"] = [*(hyperparams.get("callback") or []), timer]
    config = folder / f"{name}.yml"
    config.write_text(yaml.safe_dump({ENV_ID: hyperparams}, sort_keys=False))
    return config


def measure(
    name: str, seconds: float, smoke: bool, num_workers: int, skill_ddpg_config: Path = SKILL_DDPG_CONFIG
) -> dict[str, Any]:
    """Train contestant ``name`` in a fresh ``python -m sb3_hfo.train`` process and return its measurement."""
    env = {
        **os.environ,
        "PYTHONPATH": os.pathsep.join(filter(None, [str(REPO / "benchmarks"), os.environ.get("PYTHONPATH")])),
    }
    with tempfile.TemporaryDirectory(prefix="training_throughput_") as tmp:
        folder = Path(tmp)
        config = write_config(name, folder, seconds, smoke, num_workers, skill_ddpg_config)
        command = [sys.executable, "-m", "sb3_hfo.train", "--algo", name, "--env", ENV_ID]
        command += ["--conf-file", str(config), "--seed", "0", "-n", str(BUDGET_STEPS), "--eval-freq", "-1"]
        command += ["-f", str(folder / "logs"), "--log-interval", "1000000"]
        completed = subprocess.run(command, capture_output=True, text=True, env=env, cwd=folder)
    if completed.returncode != 0:
        raise SystemExit(f"{name} failed (exit {completed.returncode}):\n{completed.stderr[-3000:]}")
    lines = [line for line in completed.stdout.splitlines() if line.startswith(MARKER)]
    if not lines:
        raise SystemExit(f"{name} printed no result:\n{completed.stdout[-3000:]}\n{completed.stderr[-3000:]}")
    result = json.loads(lines[0][len(MARKER) :])
    print(
        f"  {name}: {result['steps_per_s']:,.0f} steps/s ({result['steps']:,} steps in {result['seconds']:.1f} s, "
        f"{result['steps_per_cpu_s']:,.0f} per CPU-s)",
        file=sys.stderr,
        flush=True,
    )
    return result


def profile_hybrid_ppo(rollouts: int, top: int = 25) -> None:
    """cProfile of HybridPPO's ``learn`` on Keeper-v1 with the recipe of :data:`HYBRID_PPO_CONFIG`, printed."""
    import torch as th
    from stable_baselines3.common.vec_env import VecNormalize

    from sb3_hfo import HybridPPO
    from sb3_hfo.common.schedules import parse_schedule
    from sb3_hfo.vec_env import make_hfo_vec_env

    th.set_num_threads(1)
    hyperparams = _section(HYBRID_PPO_CONFIG, HYBRID_PPO_SECTION)
    normalize = eval(hyperparams.pop("normalize", "{}"))  # rl-zoo3 evaluates this string the same way
    n_envs = int(hyperparams.pop("n_envs"))
    for key in ("n_timesteps", "policy", "callback", "vec_env", "num_workers"):
        hyperparams.pop(key, None)
    hyperparams["learning_rate"] = parse_schedule(hyperparams["learning_rate"])
    env = VecNormalize(
        make_hfo_vec_env(ENV_ID, n_envs, seed=0), gamma=hyperparams.get("gamma", 0.99), **normalize
    )
    model = HybridPPO("MlpPolicy", env, seed=0, **hyperparams)
    steps_per_rollout = model.n_steps * n_envs
    model.learn(steps_per_rollout)  # warm-up
    profiler = cProfile.Profile()
    wall, cpu = time.perf_counter(), time.process_time()
    profiler.enable()
    model.learn(rollouts * steps_per_rollout, reset_num_timesteps=False)
    profiler.disable()
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    steps = rollouts * steps_per_rollout
    print(
        f"HybridPPO on {ENV_ID}: {steps:,} steps in {wall:.1f} s ({cpu:.1f} CPU-s) under cProfile; {uptime()}"
    )
    pstats.Stats(profiler).sort_stats("cumulative").print_stats(top)


def cpu_model() -> str:
    """The CPU's model name (``/proc/cpuinfo``), or the platform's processor string."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def uptime() -> str:
    """``uptime``'s line (the load averages), or the load averages alone where there is no ``uptime``."""
    try:
        return subprocess.run(["uptime"], capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "load average: " + ", ".join(f"{load:.2f}" for load in os.getloadavg())


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=60.0, help="timed slice per contestant (default 60)")
    parser.add_argument(
        "--rounds", type=int, default=3, help="rounds of both contestants; medians are reported"
    )
    parser.add_argument(
        "--num-workers", type=int, default=1, help="processes stepping HybridPPO's batch (default 1)"
    )
    parser.add_argument(
        "--skill-ddpg-config",
        type=Path,
        default=SKILL_DDPG_CONFIG,
        help="SkillDDPG's config (default zoo_configs/e6_keeper_skills_fast.yml; the paper's own E6 recipe is "
        "zoo_configs/e6_keeper_skills.yml: one env, batch 32, 400-300-200 networks)",
    )
    parser.add_argument("--smoke", action="store_true", help="tiny networks and warm-up (for tests)")
    parser.add_argument("--out", type=Path, default=None, help="write the results as JSON here")
    parser.add_argument(
        "--profile", action="store_true", help="profile HybridPPO's learn instead (see above)"
    )
    parser.add_argument("--profile-rollouts", type=int, default=6, help="rollouts profiled (default 6)")
    args = parser.parse_args(argv)
    if args.seconds <= 0 or args.rounds < 1 or args.num_workers < 1 or args.profile_rollouts < 1:
        parser.error("--seconds must be > 0, --rounds, --num-workers and --profile-rollouts >= 1")
    if not args.skill_ddpg_config.is_file():
        parser.error(f"--skill-ddpg-config {args.skill_ddpg_config}: no such file")
    with open(args.skill_ddpg_config) as f:
        if ENV_ID not in (yaml.safe_load(f) or {}):
            parser.error(f"--skill-ddpg-config {args.skill_ddpg_config} has no {ENV_ID} section")
    if args.profile:
        profile_hybrid_ppo(args.profile_rollouts)
        return 0

    command = " ".join(
        ["python", "benchmarks/training_throughput.py", *(sys.argv[1:] if argv is None else argv)]
    )
    uptime_before = uptime()
    load_before = os.getloadavg()
    samples: dict[str, list[dict[str, Any]]] = {name: [] for name in CONTESTANTS}
    for round_index in range(args.rounds):
        print(f"round {round_index + 1}/{args.rounds}", file=sys.stderr, flush=True)
        for name in CONTESTANTS:
            samples[name].append(
                measure(name, args.seconds, args.smoke, args.num_workers, args.skill_ddpg_config)
            )
    load_after = os.getloadavg()
    uptime_after = uptime()
    rates = {name: statistics.median(s["steps_per_s"] for s in runs) for name, runs in samples.items()}
    cpu_rates = {
        name: statistics.median(s["steps_per_cpu_s"] for s in runs) for name, runs in samples.items()
    }
    results = {
        "command": command,
        "env_id": ENV_ID,
        "seconds": args.seconds,
        "rounds": args.rounds,
        "num_workers": args.num_workers,
        "skill_ddpg_config": str(Path(args.skill_ddpg_config).resolve().relative_to(REPO))
        if Path(args.skill_ddpg_config).resolve().is_relative_to(REPO)
        else str(args.skill_ddpg_config),
        "smoke": args.smoke,
        "cpu_model": cpu_model(),
        "cpu_count": os.cpu_count(),
        "python": platform.python_version(),
        "uptime_before": uptime_before,
        "uptime_after": uptime_after,
        "load_average_before": list(load_before),
        "load_average_after": list(load_after),
        "torch_threads": {name: sorted({s["torch_threads"] for s in runs}) for name, runs in samples.items()},
        "n_envs": {name: runs[0]["n_envs"] for name, runs in samples.items()},
        "vec_env": {name: runs[0]["vec_env"] for name, runs in samples.items()},
        "steps_per_s": rates,
        "steps_per_cpu_s": cpu_rates,
        "ratio_hybrid_ppo_vs_skill_ddpg": rates["hybrid_ppo"] / rates["skill_ddpg"],
        "ratio_per_round": [
            ppo["steps_per_s"] / ddpg["steps_per_s"]
            for ppo, ddpg in zip(samples["hybrid_ppo"], samples["skill_ddpg"], strict=True)
        ],
        "samples": samples,
    }
    print(f"{ENV_ID}, {args.rounds} round(s) of {args.seconds:g} s; {cpu_model()}, {os.cpu_count()} CPUs")
    print(f"  before: {uptime_before}\n  after:  {uptime_after}")
    for name in CONTESTANTS:
        print(
            f"  {name:10s} {rates[name]:10,.0f} steps/s  {cpu_rates[name]:10,.0f} per CPU-s  "
            f"(median; torch threads {results['torch_threads'][name]}, {results['vec_env'][name]})"
        )
    print(f"  hybrid_ppo / skill_ddpg = {results['ratio_hybrid_ppo_vs_skill_ddpg']:.1f}x")
    if args.out is not None:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(json.dumps(results, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
