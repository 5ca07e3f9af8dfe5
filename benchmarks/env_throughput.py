"""Environment throughput of hfo2d: steps per second and memory.

Measures, for each environment id:

* ``random``: ``gym.make(env_id)`` stepped with uniformly random flat actions (drawn in advance, so the
  figure is the environment's cost, resets included);
* ``random-unwrapped``: the same on ``env.unwrapped`` (no Gymnasium wrappers);
* ``heuristic``: ``gym.make(env_id)`` driven by ``hfo2d.heuristic`` (the striker's cost included);
* ``DummyVecEnv`` / ``SubprocVecEnv`` with ``--n-envs`` environments (SB3), random actions; steps counted over
  all environments.

Each figure is the best of ``--repeat`` runs (like ``timeit``): the machine may be shared, and the best run is
the one least disturbed by other processes.

Peak memory: the process's maximum resident set size (``resource.getrusage``) and the peak of Python allocations
during one single-process run (``tracemalloc``, measured in a separate shorter run because tracing is slow).

Usage::

    python benchmarks/env_throughput.py --steps 20000 --out benchmarks/results/env_throughput.json
    python benchmarks/env_throughput.py --profile --steps 20000      # top cProfile entries, EmptyGoal
"""

from __future__ import annotations

import argparse
import cProfile
import json
import os
import platform
import pstats
import resource
import subprocess
import sys
import time
import tracemalloc
from collections.abc import Callable, Sequence
from typing import Any

import gymnasium as gym
import numpy as np

import hfo2d
from hfo2d.heuristic import heuristic

ENV_IDS = tuple(hfo2d.ENV_IDS)
# flat action: [pref_dash, pref_turn, pref_kick, dash_power, dash_dir, turn_dir, kick_power, kick_dir]
ACTION_SIZE = 8


def random_actions(steps: int, seed: int, n_envs: int | None = None) -> np.ndarray:
    """Uniform flat actions in [0, 1], shape (steps, 8) or (steps, n_envs, 8), float32."""
    shape = (steps, ACTION_SIZE) if n_envs is None else (steps, n_envs, ACTION_SIZE)
    return np.random.default_rng(seed).random(shape, dtype=np.float32)


def run_single(env: Any, steps: int, seed: int, policy: str) -> tuple[float, float, int]:
    """Step ``env`` for ``steps`` steps (resetting at episode ends).

    Returns:
        (wall-clock seconds, CPU seconds of this process, episodes finished).
    """
    actions = random_actions(steps, seed) if policy == "random" else None
    obs, _ = env.reset(seed=seed)
    episodes = 0
    step = env.step
    start_cpu = time.process_time()
    start = time.perf_counter()
    for index in range(steps):
        action = actions[index] if actions is not None else heuristic(env, obs)
        obs, _, terminated, truncated, _ = step(action)
        if terminated or truncated:
            episodes += 1
            obs, _ = env.reset()
    return time.perf_counter() - start, time.process_time() - start_cpu, episodes


def run_vec(vec_env: Any, steps: int, seed: int) -> tuple[float, float]:
    """Step an SB3 VecEnv (which resets its environments itself) for ``steps`` vector steps.

    Returns:
        (wall-clock seconds, CPU seconds of this process).
    """
    actions = random_actions(steps, seed, vec_env.num_envs)
    vec_env.seed(seed)
    vec_env.reset()
    start_cpu = time.process_time()
    start = time.perf_counter()
    for index in range(steps):
        vec_env.step(actions[index])
    return time.perf_counter() - start, time.process_time() - start_cpu


def peak_rss_mib(who: int = resource.RUSAGE_SELF) -> float:
    """Maximum resident set size in MiB (Linux reports ru_maxrss in KiB)."""
    return resource.getrusage(who).ru_maxrss / 1024.0


def traced_peak_mib(env_id: str, steps: int, seed: int) -> float:
    """Peak of Python allocations (MiB) while making ``env_id`` and stepping it with random actions."""
    tracemalloc.start()
    env = gym.make(env_id)
    run_single(env, steps, seed, "random")
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    env.close()
    return peak / 2**20


def make_env_fn(env_id: str) -> Callable[[], gym.Env]:
    def make() -> gym.Env:
        import hfo2d  # noqa: F401  (registers the ids in a fresh subprocess)

        return gym.make(env_id)

    return make


def machine_description() -> dict[str, Any]:
    model = ""
    try:
        lscpu = subprocess.run(["lscpu"], capture_output=True, text=True, check=False).stdout
        model = next(
            (line.split(":", 1)[1].strip() for line in lscpu.splitlines() if "Model name" in line), ""
        )
    except OSError:
        pass
    return {
        "cpu_model": model or platform.processor(),
        "nproc": os.cpu_count(),
        "python": platform.python_version(),
        "numpy": np.__version__,
        "gymnasium": gym.__version__,
    }


def benchmark(
    env_ids: Sequence[str], steps: int, n_envs: int, seed: int, vec: bool, repeat: int
) -> list[dict[str, Any]]:
    rows: list[dict[str, Any]] = []

    def best(
        run: Callable[[], tuple[float, float | None, int | None]],
    ) -> tuple[float, float | None, int | None]:
        """Fastest wall-clock and fastest CPU time over ``repeat`` runs."""
        results = [run() for _ in range(repeat)]
        cpu_times = [result[1] for result in results if result[1] is not None]
        return min(r[0] for r in results), min(cpu_times) if cpu_times else None, results[0][2]

    def add(env_id: str, mode: str, total_steps: int, timing: tuple[float, float | None, int | None]) -> None:
        seconds, cpu_seconds, episodes = timing
        row = {
            "env_id": env_id,
            "mode": mode,
            "steps": total_steps,
            "seconds": round(seconds, 4),
            "steps_per_s": round(total_steps / seconds, 1),
            "us_per_step": round(1e6 * seconds / total_steps, 2),
            # Steps per CPU-second of the measuring process: less sensitive to other load on a shared machine;
            # not given for SubprocVecEnv, whose work happens in the worker processes.
            "steps_per_cpu_s": round(total_steps / cpu_seconds, 1) if cpu_seconds else None,
            "episodes": episodes,
        }
        rows.append(row)
        print(f"  {env_id:<22s} {mode:<22s} {row['steps_per_s']:>10,.0f} steps/s", flush=True)

    for env_id in env_ids:
        env = gym.make(env_id)
        run_single(env, min(steps, 500), seed + 1, "random")  # warm-up (imports, caches)
        add(env_id, "random", steps, best(lambda env=env: run_single(env, steps, seed, "random")))
        add(
            env_id,
            "random-unwrapped",
            steps,
            best(lambda env=env: run_single(env.unwrapped, steps, seed, "random")),
        )
        add(env_id, "heuristic", steps, best(lambda env=env: run_single(env, steps, seed, "heuristic")))
        env.close()

        if vec:
            from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv

            vec_steps = max(1, steps // n_envs)
            for name, vec_cls in (("DummyVecEnv", DummyVecEnv), ("SubprocVecEnv", SubprocVecEnv)):
                vec_env = vec_cls([make_env_fn(env_id) for _ in range(n_envs)])
                run_vec(vec_env, min(vec_steps, 200), seed + 1)  # warm-up
                in_process = vec_cls is DummyVecEnv

                def run(
                    vec_env: Any = vec_env, vec_steps: int = vec_steps, in_process: bool = in_process
                ) -> Any:
                    wall, cpu = run_vec(vec_env, vec_steps, seed)
                    return wall, cpu if in_process else None, None

                timing = best(run)
                vec_env.close()
                add(env_id, f"{name} x{n_envs}", vec_steps * n_envs, timing)
    return rows


def profile(env_id: str, steps: int, seed: int, top: int) -> None:
    env = gym.make(env_id)
    run_single(env, 500, seed + 1, "random")
    profiler = cProfile.Profile()
    profiler.enable()
    seconds, _, _ = run_single(env, steps, seed, "random")
    profiler.disable()
    print(
        f"{env_id}: {steps} random steps in {seconds:.3f} s under cProfile ({steps / seconds:,.0f} steps/s)"
    )
    pstats.Stats(profiler).sort_stats("tottime").print_stats(top)


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--steps", type=int, default=20_000, help="environment steps per measurement")
    parser.add_argument("--env", nargs="*", default=list(ENV_IDS), choices=ENV_IDS, help="environment ids")
    parser.add_argument("--n-envs", type=int, default=2, help="environments in the vectorised runs")
    parser.add_argument("--no-vec", action="store_true", help="skip the SB3 VecEnv measurements")
    parser.add_argument("--repeat", type=int, default=3, help="runs per measurement; the fastest is reported")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", default=None, help="write the results as JSON to this path")
    parser.add_argument("--profile", action="store_true", help="print the top cProfile entries instead")
    parser.add_argument("--top", type=int, default=25, help="number of cProfile entries to print")
    args = parser.parse_args(argv)

    if args.profile:
        profile(args.env[0], args.steps, args.seed, args.top)
        return

    machine = machine_description()
    print(f"machine: {machine['cpu_model']}, {machine['nproc']} CPUs, python {machine['python']}")
    load_before = os.getloadavg()
    rows = benchmark(args.env, args.steps, args.n_envs, args.seed, vec=not args.no_vec, repeat=args.repeat)
    load_after = os.getloadavg()
    memory = {
        "peak_rss_mib_main": round(peak_rss_mib(), 1),
        "peak_rss_mib_children": round(peak_rss_mib(resource.RUSAGE_CHILDREN), 1),
        "tracemalloc_peak_mib": {
            env_id: round(traced_peak_mib(env_id, min(args.steps, 5_000), args.seed), 2)
            for env_id in args.env
        },
    }

    print()
    print("| env | mode | steps/s | µs/step | steps per CPU-s |")
    print("|---|---|---:|---:|---:|")
    for row in rows:
        per_cpu = f"{row['steps_per_cpu_s']:,.0f}" if row["steps_per_cpu_s"] else "-"
        print(
            f"| {row['env_id']} | {row['mode']} | {row['steps_per_s']:,.0f} | {row['us_per_step']:.1f} | {per_cpu} |"
        )
    print()
    print(f"1-min load average: {load_before[0]:.2f} before, {load_after[0]:.2f} after")
    print(
        f"peak RSS: main process {memory['peak_rss_mib_main']} MiB, "
        f"largest SubprocVecEnv worker {memory['peak_rss_mib_children']} MiB"
    )
    for env_id, peak in memory["tracemalloc_peak_mib"].items():
        print(f"tracemalloc peak while stepping {env_id}: {peak} MiB")

    if args.out:
        os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
        with open(args.out, "w") as handle:
            json.dump(
                {
                    "machine": machine,
                    "argv": sys.argv[1:],
                    "repeat": args.repeat,
                    "load_average_1min": {"before": load_before[0], "after": load_after[0]},
                    "results": rows,
                    "memory": memory,
                },
                handle,
                indent=2,
            )
        print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
