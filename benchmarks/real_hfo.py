"""hfo2d beside the real HFO, in one run: steps per second and goal rates.

For each task (1v0 ``empty_goal``, 1v1 ``keeper``) it measures, on hfo2d's envs and on the real HFO
(``hfo2d.real.RealHFOEnv``: rcssserver, HFO's trainer and agent2d's goalie, fullstate, noise on):

* ``throughput``: steps per second of ``gym.make(env_id)`` stepped with uniformly random flat actions (drawn in
  advance; episode resets included, the real session's start-up excluded), best of ``--repeat`` runs, and the
  ratio hfo2d / real;
* ``rates``: the goal rate with its Wilson 95 % interval, the end-status counts and the mean steps to a goal, over
  ``--episodes`` episodes, of the scripted striker :func:`hfo2d.heuristic.heuristic` and of every ``--model`` (a
  SkillDDPG ``.zip`` or rl-zoo3 run folder, played greedily by :func:`sb3_hfo.evaluation.evaluate` with its saved
  acting options, on the task its observation size names: 58 features empty goal, 66 keeper), and per pair the
  difference hfo2d - real (in points).

hfo2d's side of the keeper task is every id of ``--hfo2d-keeper`` (default: ``HFO/Keeper-v0``, hfo2d's own
goalie, and ``HFO/Keeper-v1``, its port of agent2d's, when registered). The first reset of every env uses
``--seed`` (for the real HFO that is bin/HFO's ``--seed``, which fixes its start positions).

The real servers must run in a loopback-only network namespace; the script refuses to run outside one. The
repository's runner makes one (the build: ``tools/real_hfo/build.sh``, docs/real_hfo.md)::

    tools/real_hfo/loopback.sh python benchmarks/real_hfo.py --hfo-dir /path/to/HFO --episodes 100 \\
        --model e6 --json benchmarks/results/real_hfo.json
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import sys
import time
from collections import Counter
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

import hfo2d
from hfo2d import real
from hfo2d.heuristic import heuristic
from hfo2d.hfo_env import FLAT_ACTION_SIZE

TASKS: tuple[str, ...] = ("empty_goal", "keeper")
TASK_NAMES = {"empty_goal": "1v0", "keeper": "1v1"}
HFO2D_EMPTY_GOAL = "HFO/EmptyGoal-v0"
DEFAULT_HFO2D_KEEPERS: tuple[str, ...] = ("HFO/Keeper-v0", "HFO/Keeper-v1")
REAL_IDS = {task: env_id for env_id, task in hfo2d.REAL_ENV_IDS.items()}
#: observation size -> task
TASK_OF_SIZE = {58: "empty_goal", 66: "keeper"}
HEURISTIC = "hfo2d.heuristic"


def wilson(goals: int, episodes: int) -> tuple[float, float]:
    from sb3_hfo.evaluation import wilson_interval  # no torch at import

    return wilson_interval(goals, episodes)


def throughput(env_id: str, env_kwargs: dict[str, Any], steps: int, seed: int, repeat: int) -> dict[str, Any]:
    """Best-of-``repeat`` steps/s of ``env_id`` under random flat actions (one env, made once)."""
    env = gym.make(env_id, **env_kwargs)
    actions = np.random.default_rng(seed).random((steps, FLAT_ACTION_SIZE), dtype=np.float32)
    best = math.inf
    episodes = 0
    try:
        env.reset(seed=seed)  # the real HFO starts its session here, outside the timing
        for _ in range(repeat):
            episodes = 0
            start = time.perf_counter()
            for action in actions:
                _, _, terminated, truncated, _ = env.step(action)
                if terminated or truncated:
                    episodes += 1
                    env.reset()
            best = min(best, time.perf_counter() - start)
            env.reset()
    finally:
        env.close()
    return {
        "env_id": env_id,
        "steps": steps,
        "seconds": best,
        "steps_per_s": steps / best,
        "episodes": episodes,
    }


def rate_row(
    agent: str, env_id: str, statuses: Sequence[str], goal_steps: Sequence[int], seconds: float
) -> dict[str, Any]:
    episodes = len(statuses)
    goals = sum(status == "GOAL" for status in statuses)
    low, high = wilson(goals, episodes)
    return {
        "agent": agent,
        "env_id": env_id,
        "episodes": episodes,
        "goals": goals,
        "goal_rate": goals / episodes if episodes else 0.0,
        "goal_rate_ci95": (low, high),
        "status_counts": dict(sorted(Counter(statuses).items())),
        "mean_steps_to_goal": sum(goal_steps) / len(goal_steps) if goal_steps else None,
        "seconds": seconds,
    }


def heuristic_rates(env_id: str, env_kwargs: dict[str, Any], episodes: int, seed: int) -> dict[str, Any]:
    """The scripted striker over ``episodes`` episodes of ``env_id``."""
    env = gym.make(env_id, **env_kwargs)
    statuses: list[str] = []
    goal_steps: list[int] = []
    start = time.perf_counter()
    try:
        obs, _ = env.reset(seed=seed)
        steps = 0
        while len(statuses) < episodes:
            obs, _, terminated, truncated, info = env.step(heuristic(env, obs))
            steps += 1
            if terminated or truncated:
                statuses.append(str(info["status"]))
                if info["status"] == "GOAL":
                    goal_steps.append(steps)
                steps = 0
                obs, _ = env.reset()
    finally:
        env.close()
    return rate_row(HEURISTIC, env_id, statuses, goal_steps, time.perf_counter() - start)


def model_rates(
    model: str, env_id: str, env_kwargs: dict[str, Any], episodes: int, seed: int
) -> dict[str, Any]:
    """A SkillDDPG model's greedy evaluation (sb3_hfo.evaluate) over ``episodes`` episodes of ``env_id``."""
    from sb3_hfo.evaluation import evaluate

    start = time.perf_counter()
    result = evaluate(model, env_id=env_id, episodes=episodes, seed=seed, env_kwargs=env_kwargs)
    statuses = [status for status, count in result.status_counts.items() for _ in range(count)]
    row = rate_row(model, env_id, statuses, [], time.perf_counter() - start)
    row["mean_steps_to_goal"] = result.mean_steps_to_goal
    row["kicks_per_goal"] = result.kicks_per_goal
    return row


def model_task(model: str) -> str:
    """The task a model plays, from its observation size (58: empty goal, 66: keeper)."""
    from sb3_hfo.evaluation import resolve_model
    from sb3_hfo.models import load_model

    path = resolve_model(model).path
    loaded = load_model(path, device="cpu", buffer_size=1)
    size = int(loaded.observation_space.shape[0])
    if size not in TASK_OF_SIZE:
        raise SystemExit(f"error: {model} expects {size} features; hfo2d and the real HFO give 58 or 66")
    return TASK_OF_SIZE[size]


def hfo2d_ids(task: str, keepers: Sequence[str]) -> list[str]:
    if task == "empty_goal":
        return [HFO2D_EMPTY_GOAL]
    return [env_id for env_id in keepers if env_id in gym.registry]


def _fmt_rate(row: dict[str, Any]) -> str:
    low, high = row["goal_rate_ci95"]
    return f"{100 * row['goal_rate']:5.1f} % [{100 * low:4.1f}, {100 * high:5.1f}]"


def _fmt_counts(row: dict[str, Any]) -> str:
    short = {"GOAL": "G", "CAPTURED_BY_DEFENSE": "CAP", "OUT_OF_BOUNDS": "OOB", "OUT_OF_TIME": "OOT"}
    return " ".join(f"{short.get(k, k)} {v}" for k, v in row["status_counts"].items())


def print_tables(payload: dict[str, Any]) -> None:
    print(
        f"\nSteps per second, random flat actions ({payload['settings']['steps']} steps, best of "
        f"{payload['settings']['repeat']})"
    )
    print(f"{'task':5} {'hfo2d id':20} {'hfo2d':>10} {'real HFO':>10} {'hfo2d/real':>11}")
    for row in payload["throughput"]:
        print(
            f"{row['task']:5} {row['hfo2d_id']:20} {row['hfo2d_steps_per_s']:10,.0f} "
            f"{row['real_steps_per_s']:10,.0f} {row['ratio']:10.1f}x"
        )
    print(f"\nGoal rates ({payload['settings']['episodes']} episodes each, Wilson 95 % CI)")
    for row in payload["rates"]:
        print(f"{row['task']} {row['agent']}")
        for part in (row["real"], *row["hfo2d"]):
            steps = part["mean_steps_to_goal"]
            steps_text = "-" if steps is None else f"{steps:.1f}"
            difference = row["differences"].get(part["env_id"])
            versus = "" if difference is None else f"  ({100 * difference:+.1f} points vs real)"
            print(
                f"  {part['env_id']:22} {_fmt_rate(part)}  steps/goal {steps_text:>5}  {_fmt_counts(part)}{versus}"
            )


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--hfo-dir", default=None, help="the HFO build (folder with bin/HFO); default $HFO_DIR"
    )
    parser.add_argument("--tasks", nargs="+", choices=TASKS, default=list(TASKS))
    parser.add_argument("--steps", type=int, default=3000, help="random steps per throughput run")
    parser.add_argument("--repeat", type=int, default=1, help="throughput runs per env (the best is kept)")
    parser.add_argument("--episodes", type=int, default=100, help="episodes per goal rate")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--model", nargs="*", default=[], help="SkillDDPG .zip or rl-zoo3 run folder")
    parser.add_argument(
        "--no-heuristic", dest="heuristic", action="store_false", help="skip the scripted striker"
    )
    parser.add_argument(
        "--no-throughput", dest="throughput", action="store_false", help="skip steps per second"
    )
    parser.add_argument(
        "--hfo2d-keeper", nargs="+", default=list(DEFAULT_HFO2D_KEEPERS), help="hfo2d ids of the keeper task"
    )
    parser.add_argument("--json", type=Path, default=None, help="write the results here")
    args = parser.parse_args(argv)
    if not real.in_loopback_namespace():
        print(
            "error: run this inside a loopback-only network namespace, e.g. with the repository's runner: "
            "tools/real_hfo/loopback.sh python benchmarks/real_hfo.py ...",
            file=sys.stderr,
        )
        return 2
    try:
        hfo_dir = real.find_hfo_dir(args.hfo_dir)
    except real.HFOBuildNotFound as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    real_kwargs = {"hfo_dir": str(hfo_dir)}
    payload: dict[str, Any] = {
        "settings": {
            "hfo_dir": str(hfo_dir),
            "steps": args.steps,
            "repeat": args.repeat,
            "episodes": args.episodes,
            "seed": args.seed,
            "tasks": args.tasks,
            "real_env": "RealHFOEnv defaults: fullstate, noise on, 500 frames per trial, untouched time 100",
        },
        "machine": {
            "nproc": os.cpu_count(),
            "python": platform.python_version(),
            "gymnasium": gym.__version__,
        },
        "throughput": [],
        "rates": [],
    }

    if args.throughput:
        for task in args.tasks:
            real_row = throughput(REAL_IDS[task], real_kwargs, args.steps, args.seed, args.repeat)
            for env_id in hfo2d_ids(task, args.hfo2d_keeper):
                hfo2d_row = throughput(env_id, {}, args.steps, args.seed, args.repeat)
                payload["throughput"].append(
                    {
                        "task": TASK_NAMES[task],
                        "hfo2d_id": env_id,
                        "real_id": REAL_IDS[task],
                        "hfo2d_steps_per_s": hfo2d_row["steps_per_s"],
                        "real_steps_per_s": real_row["steps_per_s"],
                        "ratio": hfo2d_row["steps_per_s"] / real_row["steps_per_s"],
                        "hfo2d": hfo2d_row,
                        "real": real_row,
                    }
                )

    agents: list[tuple[str, str]] = []
    if args.heuristic:
        agents += [(HEURISTIC, task) for task in args.tasks]
    agents += [(model, model_task(model)) for model in args.model]
    for agent, task in agents:
        if agent == HEURISTIC:
            real_row = heuristic_rates(REAL_IDS[task], real_kwargs, args.episodes, args.seed)
        else:
            real_row = model_rates(agent, REAL_IDS[task], real_kwargs, args.episodes, args.seed)
        hfo2d_rows = []
        for env_id in hfo2d_ids(task, args.hfo2d_keeper):
            if agent == HEURISTIC:
                hfo2d_rows.append(heuristic_rates(env_id, {}, args.episodes, args.seed))
            else:
                hfo2d_rows.append(model_rates(agent, env_id, {}, args.episodes, args.seed))
        payload["rates"].append(
            {
                "task": TASK_NAMES[task],
                "agent": agent,
                "real": real_row,
                "hfo2d": hfo2d_rows,
                # hfo2d's goal rate minus the real HFO's, per hfo2d id
                "differences": {
                    row["env_id"]: row["goal_rate"] - real_row["goal_rate"] for row in hfo2d_rows
                },
            }
        )

    print_tables(payload)
    if args.json is not None:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(payload, indent=2) + "\n")
        print(f"\nwrote {args.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
