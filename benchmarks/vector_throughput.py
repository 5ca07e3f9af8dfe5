"""Throughput of hfo2d's batch (hfo2d.vector) against the single unwrapped env, in one run.

Contestants, each stepped with uniformly random flat actions drawn in advance (episode ends reset as usual), for
every id:

* ``single``: ``gym.make(id).unwrapped`` stepped in a plain loop, ``reset()`` at episode ends (the reference);
* ``batch xN``: ``gym.make_vec(id, N, vectorization_mode="vector_entry_point")``, Gymnasium's ``step`` (the vector
  info dict is built only when read, and this loop does not read it);
* ``batch xN, info read``: the same, reading ``info["status"]`` every step (builds the whole vector info);
* ``sb3 xN``: ``sb3_hfo.vec_env.make_hfo_vec_env(id, N, monitor=False)``, SB3's ``step`` (infos with
  ``terminal_observation`` and ``TimeLimit.truncated``);
* ``sharded xN/W``: ``hfo2d.vector.ShardedHFOVectorEnv(id, N, W)`` (W shards: this process steps one, W - 1
  worker processes the others); ``, all in workers``: the same with ``in_process_shard=False`` (W workers);
* ``sb3 sharded xN/W``: ``make_hfo_vec_env(id, N, num_workers=W, monitor=False)``;
* ``DummyVecEnv xN`` (``--dummy``): SB3's ``DummyVecEnv`` of ``gym.make(id)``, for comparison.

Rounds interleave the contestants (round r runs each once, for a fraction of a second), so background load hits them
alike; each round's ratio to ``single`` is taken within the round, and the medians over rounds are reported. Steps
count every game's step. Besides the wall clock, the CPU time per game step of this process and of the busiest
worker process (Linux /proc) are reported: on a loaded machine a sharded step waits for every worker, and the CPU
times show what the sharding itself costs.

Usage::

    python benchmarks/vector_throughput.py --steps 4800 --rounds 15 --out benchmarks/results/vector_throughput.json
    python benchmarks/vector_throughput.py --ids HFO/Keeper-v1 --profile      # cProfile of the one-process batch
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
import time
from collections.abc import Callable
from typing import Any

import gymnasium as gym
import numpy as np

import hfo2d
from hfo2d.vector import ShardedHFOVectorEnv

ACTION_SIZE = 8


def uptime() -> str:
    try:
        return subprocess.run(["uptime"], capture_output=True, text=True, check=False).stdout.strip()
    except OSError:
        return ""


def process_cpu_seconds(pid: int) -> float:
    """User + system CPU seconds of process ``pid`` (Linux /proc; 0 elsewhere)."""
    try:
        with open(f"/proc/{pid}/stat") as handle:
            fields = handle.read().rsplit(")", 1)[1].split()
    except OSError:
        return 0.0
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def worker_pids(env: Any) -> list[int]:
    """The worker processes of a sharded batch (also under SB3's adapter), else none."""
    batch = getattr(env, "batch", env)
    return [process.pid for process in getattr(batch, "_processes", [])]


def time_single(env_id: str, steps: int, seed: int) -> tuple[float, float, float]:
    env = gym.make(env_id).unwrapped
    actions = np.random.default_rng(seed).random((steps, ACTION_SIZE), dtype=np.float32)
    env.reset(seed=seed)
    step = env.step
    start_cpu, start = time.process_time(), time.perf_counter()
    for action in actions:
        _, _, terminated, truncated, _ = step(action)
        if terminated or truncated:
            env.reset()
    wall, cpu = time.perf_counter() - start, time.process_time() - start_cpu
    env.close()
    return wall, cpu, 0.0


def time_vector(
    env: Any, steps: int, seed: int, read_info: bool = False, sb3: bool = False
) -> tuple[float, float]:
    """``steps`` game steps (steps // num_envs batch steps) of a Gymnasium VectorEnv or an SB3 VecEnv."""
    num_envs = env.num_envs
    actions = np.random.default_rng(seed).random((steps // num_envs, num_envs, ACTION_SIZE), dtype=np.float32)
    if sb3:
        env.seed(seed)
        env.reset()
    else:
        env.reset(seed=seed)
    step = env.step
    pids = worker_pids(env)
    workers_before = [process_cpu_seconds(pid) for pid in pids]
    start_cpu, start = time.process_time(), time.perf_counter()
    if read_info:
        for action in actions:
            step(action)[4]["status"]
    else:
        for action in actions:
            step(action)
    wall, cpu = time.perf_counter() - start, time.process_time() - start_cpu
    workers = [process_cpu_seconds(pid) - before for pid, before in zip(pids, workers_before, strict=True)]
    return wall, cpu, max(workers, default=0.0)


def contestants(env_id: str, num_envs: int, workers: list[int], dummy: bool) -> dict[str, Callable[..., Any]]:
    """name -> a maker of (run(steps, seed) -> (wall, cpu), close())."""
    from sb3_hfo.vec_env import make_hfo_vec_env

    def vector(make: Callable[[], Any], **kwargs: Any) -> Callable[[], Any]:
        def maker() -> Any:
            env = make()
            return (lambda steps, seed: time_vector(env, steps, seed, **kwargs)), env.close

        return maker

    makers: dict[str, Callable[[], Any]] = {
        "single": lambda: ((lambda steps, seed: time_single(env_id, steps, seed)), lambda: None),
        f"batch x{num_envs}": vector(
            lambda: gym.make_vec(env_id, num_envs, vectorization_mode="vector_entry_point")
        ),
        f"batch x{num_envs}, info read": vector(
            lambda: gym.make_vec(env_id, num_envs, vectorization_mode="vector_entry_point"), read_info=True
        ),
        f"sb3 x{num_envs}": vector(lambda: make_hfo_vec_env(env_id, num_envs, monitor=False), sb3=True),
    }
    for count in workers:
        makers[f"sharded x{num_envs}/{count}"] = vector(
            lambda count=count: ShardedHFOVectorEnv(env_id, num_envs, count)
        )
        makers[f"sharded x{num_envs}/{count}, all in workers"] = vector(
            lambda count=count: ShardedHFOVectorEnv(env_id, num_envs, count, in_process_shard=False)
        )
        makers[f"sb3 sharded x{num_envs}/{count}"] = vector(
            lambda count=count: make_hfo_vec_env(env_id, num_envs, num_workers=count, monitor=False), sb3=True
        )
    if dummy:
        from stable_baselines3.common.vec_env import DummyVecEnv

        makers[f"DummyVecEnv x{num_envs}"] = vector(
            lambda: DummyVecEnv([lambda: gym.make(env_id) for _ in range(num_envs)]), sb3=True
        )
    return makers


def benchmark(
    env_id: str, steps: int, rounds: int, num_envs: int, workers: list[int], dummy: bool, seed: int
) -> dict:
    made = {name: maker() for name, maker in contestants(env_id, num_envs, workers, dummy).items()}
    try:
        for run, _ in made.values():  # warm-up: imports, caches, worker start
            run(min(steps, 2 * num_envs * 50), seed + 1)
        walls: dict[str, list[float]] = {name: [] for name in made}
        cpus: dict[str, list[float]] = {name: [] for name in made}
        worker_cpus: dict[str, list[float]] = {name: [] for name in made}
        for round_index in range(rounds):
            for name, (run, _) in made.items():
                wall, cpu, worker_cpu = run(steps, seed + round_index)
                walls[name].append(wall)
                cpus[name].append(cpu)
                worker_cpus[name].append(worker_cpu)
    finally:
        for _, close in made.values():
            close()
    rows = []
    for name in made:
        counted = steps if name == "single" else (steps // num_envs) * num_envs
        rates = [counted / wall for wall in walls[name]]
        ratios = [
            (counted / wall) / (steps / single)
            for wall, single in zip(walls[name], walls["single"], strict=True)
        ]
        rows.append(
            {
                "env_id": env_id,
                "contestant": name,
                "steps": counted,
                "steps_per_s_median": round(statistics.median(rates), 1),
                "steps_per_s_rounds": [round(rate, 1) for rate in rates],
                "ratio_to_single_median": round(statistics.median(ratios), 3),
                "ratio_to_single_rounds": [round(ratio, 3) for ratio in ratios],
                # CPU time per game step, of this process and (sharded) of the busiest worker: on a loaded machine
                # these say more than the wall clock (a sharded step waits for every worker)
                "process_cpu_us_per_step_median": round(1e6 * statistics.median(cpus[name]) / counted, 2),
                "worker_cpu_us_per_step_median": round(
                    1e6 * statistics.median(worker_cpus[name]) / counted, 2
                ),
                "cpu_ratio_to_single_median": round(
                    statistics.median(
                        (single_cpu / steps) / (cpu / counted)
                        for cpu, single_cpu in zip(cpus[name], cpus["single"], strict=True)
                    ),
                    3,
                ),
            }
        )
        print(
            f"  {env_id:<20s} {name:<36s} {rows[-1]['steps_per_s_median']:>9,.0f} steps/s "
            f"x{rows[-1]['ratio_to_single_median']:.2f} (CPU x{rows[-1]['cpu_ratio_to_single_median']:.2f}, "
            f"{rows[-1]['process_cpu_us_per_step_median']:.1f} + worker {rows[-1]['worker_cpu_us_per_step_median']:.1f}"
            " CPU-us/step)",
            flush=True,
        )
    return {"env_id": env_id, "rows": rows}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--ids",
        nargs="+",
        default=["HFO/Keeper-v1", "HFO/Keeper-v0", "HFO/StaticKeeper-v0", "HFO/EmptyGoal-v0"],
    )
    parser.add_argument("--steps", type=int, default=4800, help="game steps per contestant and round")
    parser.add_argument("--rounds", type=int, default=15)
    parser.add_argument("--num-envs", type=int, default=16)
    parser.add_argument(
        "--workers", type=int, nargs="*", default=[2], help="worker counts of the sharded runs"
    )
    parser.add_argument("--dummy", action="store_true", help="also SB3's DummyVecEnv of gym.make(id)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--profile", action="store_true", help="cProfile the one-process batch instead")
    parser.add_argument("--out", default=None, help="JSON results file")
    args = parser.parse_args()
    unknown = [env_id for env_id in args.ids if env_id not in hfo2d.ENV_IDS]
    if unknown:
        parser.error(f"unknown ids {unknown}; choose from {tuple(hfo2d.ENV_IDS)}")

    if args.profile:
        env = gym.make_vec(args.ids[0], args.num_envs, vectorization_mode="vector_entry_point")
        profiler = cProfile.Profile()
        profiler.runcall(time_vector, env, args.steps, args.seed)
        pstats.Stats(profiler).sort_stats("tottime").print_stats(20)
        return

    load_before = uptime()
    print(f"load before: {load_before}", flush=True)
    started = time.strftime("%Y-%m-%d %H:%M:%S")
    results = [
        benchmark(env_id, args.steps, args.rounds, args.num_envs, args.workers, args.dummy, args.seed)
        for env_id in args.ids
    ]
    load_after = uptime()
    print(f"load after: {load_after}", flush=True)
    report = {
        "command": "python benchmarks/vector_throughput.py "
        + " ".join(
            [f"--ids {' '.join(args.ids)}", f"--steps {args.steps}", f"--rounds {args.rounds}"]
            + [f"--num-envs {args.num_envs}", f"--workers {' '.join(map(str, args.workers))}"]
            + (["--dummy"] if args.dummy else [])
        ),
        "started": started,
        "uptime_before": load_before,
        "uptime_after": load_after,
        "machine": {
            "nproc": os.cpu_count(),
            "python": platform.python_version(),
            "numpy": np.__version__,
            "gymnasium": gym.__version__,
        },
        "results": results,
    }
    if args.out:
        with open(args.out, "w") as handle:
            json.dump(report, handle, indent=1)
        print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
