"""Do the machine's cores slow each other? One process stepping a single hfo2d env, then N such processes at once.

Each process steps ``gym.make(ID).unwrapped`` with actions sampled from its action space (seeded) for ``--seconds``
and reports its steps per second of wall clock and of its own CPU time. If N processes side by side each keep the
rate of one alone, the cores are independent and a parallel batch's missing speed-up lies in its own hand-over
between processes (benchmarks/README.md, "Many games in one process").

    python benchmarks/core_scaling.py --seconds 15 --processes 2
"""

from __future__ import annotations

import argparse
import json
import multiprocessing
import time

import gymnasium as gym

import hfo2d  # noqa: F401  (registers the ids)


def step_rate(env_id: str, seconds: float, seed: int) -> dict[str, float]:
    """Steps per wall-clock second and per CPU second of one env stepped for ``seconds``."""
    env = gym.make(env_id).unwrapped
    env.action_space.seed(seed)
    actions = [env.action_space.sample() for _ in range(512)]
    env.reset(seed=seed)
    steps, wall, cpu = 0, time.perf_counter(), time.process_time()
    while time.perf_counter() - wall < seconds:
        for action in actions:
            _, _, terminated, truncated, _ = env.step(action)
            steps += 1
            if terminated or truncated:
                env.reset()
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    return {"steps_per_s": steps / wall, "steps_per_cpu_s": steps / max(cpu, 1e-9)}


def _worker(args: tuple[str, float, int]) -> dict[str, float]:
    return step_rate(*args)


def main(argv: list[str] | None = None) -> dict[str, list[dict[str, float]]]:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--env", default="HFO/Keeper-v1")
    parser.add_argument("--seconds", type=float, default=15.0)
    parser.add_argument("--processes", type=int, default=2)
    args = parser.parse_args(argv)
    if args.seconds <= 0 or args.processes < 1:
        parser.error("--seconds must be > 0 and --processes >= 1")
    results = {"alone": [step_rate(args.env, args.seconds, 0)]}
    with multiprocessing.get_context("spawn").Pool(args.processes) as pool:
        results["side_by_side"] = pool.map(
            _worker, [(args.env, args.seconds, i) for i in range(args.processes)]
        )
    results["alone_again"] = [step_rate(args.env, args.seconds, 0)]
    for name, rows in results.items():
        print(f"{name:13s} " + ", ".join(f"{row['steps_per_s']:,.0f} steps/s" for row in rows))
    print(json.dumps(results))
    return results


if __name__ == "__main__":
    main()
