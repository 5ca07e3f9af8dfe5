"""Gradient updates per second: SkillDDPG vs Stable-Baselines3's own DDPG, same networks, same batch, same run.

Usage::

    python benchmarks/update_throughput.py --threads 1 --updates 300 --repeats 5 --out /tmp/update_throughput.json
    python benchmarks/update_throughput.py --threads 1 2 --updates 300 --repeats 5 --out /tmp/update_throughput.json

What is measured (all on ``HFO/EmptyGoal-v0``: 58 observation features, 8 action entries; batch 32):

* ``train``: the replay buffer is filled with ``--fill`` random-action transitions, then ``train(gradient_steps=
  --updates, batch_size=32)`` is timed (sampling included: that is what one update costs inside ``learn``);
* ``learn``: ``learn(--learn-steps)`` with one update per environment step (the paper's schedule: train_freq 1,
  gradient_steps 1), i.e. environment stepping + acting + updating, after ``learning_starts`` warm-up steps that
  are excluded by measuring only the second ``learn`` call.

Contestants: SkillDDPG with 1 and 2 skills (the paper's nets: actor 400-300-200, critic 400 -> [+action] -> 300 ->
200 -> 1, LeakyReLU 0.01) and SB3's ``DDPG`` with ``net_arch=dict(pi=[400, 300, 200], qf=[400, 300, 200])`` and
LeakyReLU(0.01). SB3's critic concatenates the action with the state at its *input* (66 -> 400 -> 300 -> 200 -> 1)
while the paper's concatenates it at the second layer (58 -> 400, 408 -> 300, ...): the multiply-adds differ by
under 1 % (8 x 400 vs 8 x 300 weights). The algorithms are otherwise the same maths (DDPG: one critic, no target
smoothing, actor updated every step).

Measurements are interleaved (contestant A, B, C, A, B, C, ...) and the median of ``--repeats`` rounds is reported
so that load from other processes affects all contestants alike. ``torch.set_num_threads`` applies to all; with
several ``--threads`` values every contestant is timed at each of them within the same rounds, ratios are given per
thread count, and also with each contestant at its own fastest count (the issue lists the thread count among the
levers, and a user picks it).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import gymnasium as gym
import torch as th
from stable_baselines3 import DDPG
from stable_baselines3.common.base_class import BaseAlgorithm
from torch import nn

import sb3_hfo  # noqa: F401  (registers HFO/EmptyGoal-v0)
from sb3_hfo import SkillDDPG

ENV_ID = "HFO/EmptyGoal-v0"
PAPER_ARCH = [400, 300, 200]
BATCH_SIZE = 32
#: The contestant every ratio is taken against.
BASELINE = "sb3_ddpg"


def make_contestants(buffer_size: int, learning_starts: int) -> dict[str, Callable[[], BaseAlgorithm]]:
    """Model factories by name; every model uses batch 32, tau 1e-4 and one update per environment step."""
    common: dict[str, Any] = dict(
        buffer_size=buffer_size,
        learning_starts=learning_starts,
        batch_size=BATCH_SIZE,
        tau=1e-4,
        seed=0,
        device="cpu",
    )

    def skill_ddpg(n_skills: int) -> Callable[[], BaseAlgorithm]:
        return lambda: SkillDDPG(
            "HFOPolicy",
            gym.make(ENV_ID),
            policy_kwargs=dict(net_arch=PAPER_ARCH, n_skills=n_skills, domain="hfo"),
            **common,
        )

    sb3_policy_kwargs = dict(net_arch=dict(pi=PAPER_ARCH, qf=PAPER_ARCH), activation_fn=nn.LeakyReLU)

    def sb3_ddpg() -> BaseAlgorithm:
        return DDPG(
            "MlpPolicy", gym.make(ENV_ID), learning_rate=1e-3, policy_kwargs=sb3_policy_kwargs, **common
        )

    return {
        "sb3_ddpg": sb3_ddpg,
        "skill_ddpg_1_skill": skill_ddpg(1),
        "skill_ddpg_2_skills": skill_ddpg(2),
    }


def time_train(model: BaseAlgorithm, updates: int) -> float:
    """Updates per second of ``model.train(updates, 32)`` (buffer already filled)."""
    start = time.perf_counter()
    model.train(gradient_steps=updates, batch_size=BATCH_SIZE)  # type: ignore[attr-defined]
    return updates / (time.perf_counter() - start)


def time_learn(model: BaseAlgorithm, steps: int) -> float:
    """Environment steps (= updates) per second of ``learn(steps)`` continuing a warmed-up model."""
    start = time.perf_counter()
    model.learn(steps, reset_num_timesteps=False)
    return steps / (time.perf_counter() - start)


def ratios(rates: dict[str, float], baseline: str = BASELINE) -> dict[str, float]:
    return {name: rate / rates[baseline] for name, rate in rates.items()}


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument(
        "--threads",
        type=int,
        nargs="+",
        default=[1],
        help="torch.set_num_threads values; every contestant is timed at each, interleaved in the same rounds",
    )
    parser.add_argument("--updates", type=int, default=300, help="updates per timed train() call")
    parser.add_argument(
        "--learn-steps", type=int, default=300, help="environment steps per timed learn() call"
    )
    parser.add_argument("--repeats", type=int, default=5, help="interleaved rounds; the median is reported")
    parser.add_argument(
        "--fill", type=int, default=2000, help="random transitions in the buffer before timing"
    )
    parser.add_argument("--out", type=Path, default=None, help="write the results as JSON here")
    args = parser.parse_args()
    if any(n < 1 for n in args.threads):
        parser.error(f"--threads must be >= 1, got {args.threads}")

    th.set_num_threads(args.threads[0])
    contestants = make_contestants(buffer_size=max(10 * args.fill, 100_000), learning_starts=args.fill)
    models: dict[str, BaseAlgorithm] = {}
    for name, factory in contestants.items():
        model = factory()
        model.learn(args.fill + 1)  # random warm-up fills the buffer, then one update
        model.train(gradient_steps=20, batch_size=BATCH_SIZE)  # type: ignore[attr-defined]  # warm caches
        models[name] = model

    train_rates = {t: {name: [] for name in models} for t in args.threads}
    learn_rates = {t: {name: [] for name in models} for t in args.threads}
    for _ in range(args.repeats):
        for threads in args.threads:
            th.set_num_threads(threads)
            for name, model in models.items():
                train_rates[threads][name].append(time_train(model, args.updates))
            for name, model in models.items():
                learn_rates[threads][name].append(time_learn(model, args.learn_steps))

    by_threads: dict[str, Any] = {}
    for threads in args.threads:
        train = {name: statistics.median(rates) for name, rates in train_rates[threads].items()}
        learn = {name: statistics.median(rates) for name, rates in learn_rates[threads].items()}
        by_threads[str(threads)] = {
            "train_updates_per_s": train,
            "learn_steps_per_s": learn,
            "train_ratio_vs_sb3_ddpg": ratios(train),
            "learn_ratio_vs_sb3_ddpg": ratios(learn),
            "train_updates_per_s_all": train_rates[threads],
            "learn_steps_per_s_all": learn_rates[threads],
        }
    results: dict[str, Any] = {
        "machine": {
            "platform": platform.platform(),
            "processor": platform.processor() or platform.machine(),
            "cpu_count": os.cpu_count(),
            "torch": th.__version__,
            "python": platform.python_version(),
        },
        "settings": vars(args) | {"out": str(args.out) if args.out else None, "batch_size": BATCH_SIZE},
        "by_threads": by_threads,
    }
    print(f"torch {th.__version__}, batch {BATCH_SIZE}, median of {args.repeats} interleaved rounds")
    print(
        f"{'threads':>7}  {'contestant':<22}{'train upd/s':>13}{'ratio':>8}{'learn steps/s':>15}{'ratio':>8}"
    )
    for threads, row in by_threads.items():
        for name in models:
            print(
                f"{threads:>7}  {name:<22}{row['train_updates_per_s'][name]:>13.1f}"
                f"{row['train_ratio_vs_sb3_ddpg'][name]:>8.2f}"
                f"{row['learn_steps_per_s'][name]:>15.1f}{row['learn_ratio_vs_sb3_ddpg'][name]:>8.2f}"
            )
    if len(args.threads) > 1:
        # Each contestant at its own fastest thread count: what a user who picks the setting gets.
        best: dict[str, Any] = {}
        for kind in ("train_updates_per_s", "learn_steps_per_s"):
            fastest = {
                name: max((row[kind][name], int(t)) for t, row in by_threads.items()) for name in models
            }
            best[kind] = {name: rate for name, (rate, _) in fastest.items()}
            best[kind.replace("per_s", "threads")] = {name: t for name, (_, t) in fastest.items()}
            best[kind.split("_per_s")[0] + "_ratio_vs_sb3_ddpg"] = ratios(best[kind])
        results["each_at_its_fastest_thread_count"] = best
        print("each at its fastest thread count (threads in brackets):")
        for name in models:
            print(
                f"         {name:<22}{best['train_updates_per_s'][name]:>9.1f} "
                f"[{best['train_updates_threads'][name]}]{best['train_updates_ratio_vs_sb3_ddpg'][name]:>8.2f}"
                f"{best['learn_steps_per_s'][name]:>11.1f} "
                f"[{best['learn_steps_threads'][name]}]{best['learn_steps_ratio_vs_sb3_ddpg'][name]:>8.2f}"
            )
    if args.out is not None:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(json.dumps(results, indent=2))
        print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
