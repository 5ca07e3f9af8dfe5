"""Scripted strikers against agent2d's goalie and field defender, in hfo2d and in a real HFO build (issue 34 item 2).

Each configuration is bin/HFO's ``--offense-agents N --defense-npcs 2`` (agent2d's goalie, unum 1, and one agent2d
field defender): ``1v2`` (N = 1) and ``2v2`` (N = 2). Every offense agent is one scripted striker of
:mod:`hfo2d.strikers` (all of them the same kind in one run), fed by :func:`hfo2d.strikers.goalie_view_from_hfo`:
HFO master's low-level vector (``feature_set="hfo"``, fullstate, which both backends give) cut to the basic
features and the goalie's block, found by its uniform number. So a striker acts on the same numbers in both
backends, and it is what hfo2d's own ``scripted_strikers`` read. Both backends are driven through
``hfo2d.parallel_env(..., backend=...)``: hfo2d's team game (``HFOTeamParallelEnv``) and the real HFO's
(``RealTeamParallelEnv``, its own start-up and end-of-episode timing). Noise is on in both; HFO's default
``--frames-per-trial 500 --untouched-time 100``.

Per (configuration, striker, backend) the script plays ``--episodes`` episodes (the real HFO one more: a session's
first episode is special, its goalie's first body angle comes from the pre-kick-off scan, and is dropped, as
``keeper_fidelity.py noise`` does), and records each end status and length. ``report`` joins result files into one
table: the goal rate with its Wilson 95 % interval, the end-status counts (GOAL / CAPTURED_BY_DEFENSE /
OUT_OF_BOUNDS / OUT_OF_TIME) on both sides, and the difference real - hfo2d with its standard error.

Commands::

    # hfo2d only, a few episodes (no HFO build needed): what the tests run
    python benchmarks/team_fidelity.py play --backends hfo2d --episodes 5 --smoke
    # both backends (the real one inside a loopback-only network namespace, which the script checks)
    HFO_DIR=/path/to/HFO tools/real_hfo/loopback.sh python benchmarks/team_fidelity.py play --backends real \\
        --episodes 1000 --out real.json
    python benchmarks/team_fidelity.py play --backends hfo2d --episodes 1000 --out sim.json
    python benchmarks/team_fidelity.py report real.json sim.json --out benchmarks/results/team_fidelity.json

``play --out`` rewrites its file after every finished cell, so a long run that is stopped keeps what it finished.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from keeper_fidelity import (  # noqa: E402  (the benchmark module next to this script)
    STATUSES,
    check_network_namespace,
    difference,
    hfo2d_version,
    rate_summary,
)

import hfo2d  # noqa: E402
from hfo2d.strikers import STRIKERS, goalie_view_from_hfo, make_striker  # noqa: E402

#: configuration name -> offense agents (each against --defense-npcs 2: the goalie and one field defender)
CONFIGS: dict[str, int] = {"1v2": 1, "2v2": 2}
DEFENSE_NPCS = 2
BACKENDS = ("hfo2d", "real")
DEFAULT_STRIKERS = ("soft_dribble", "mid_shot")
SMOKE_EPISODES = 3


def cell_seed(base: int, config: str, striker: str) -> int:
    """One seed per (configuration, striker), the same for both backends (they use it differently)."""
    return base + 1000 * list(CONFIGS).index(config) + 100 * sorted(STRIKERS).index(striker)


def play_cell(
    config: str,
    striker: str,
    backend: str,
    episodes: int,
    seed: int,
    hfo_dir: str | None = None,
    max_seconds: float | None = None,
) -> dict[str, Any]:
    """Play ``episodes`` episodes of one configuration with one kind of striker on every offense agent (fewer
    when ``max_seconds`` of wall clock run out first: the episode in progress is finished, then the cell stops)."""
    offense = CONFIGS[config]
    kwargs: dict[str, Any] = {"feature_set": "hfo", "reward": "sparse"}
    if backend == "real":
        kwargs["hfo_dir"] = hfo_dir
    env = hfo2d.parallel_env(offense_agents=offense, defense_npcs=DEFENSE_NPCS, backend=backend, **kwargs)
    dropped = 1 if backend == "real" else 0
    records: list[dict[str, Any]] = []
    started = time.monotonic()
    steps_total = 0
    try:
        strikers = {name: make_striker(striker) for name in env.possible_agents}
        for episode in range(episodes + dropped):
            observations, _ = env.reset(seed=seed if episode == 0 else None)
            for scripted in strikers.values():
                scripted.reset()
            steps = 0
            info: dict[str, Any] = {}
            while env.agents:
                actions = {
                    name: strikers[name](goalie_view_from_hfo(observations[name], offense - 1, DEFENSE_NPCS))
                    for name in env.agents
                }
                observations, _, _, _, infos = env.step(actions)
                info = infos["offense_0"]
                steps += 1
            steps_total += steps
            if episode >= dropped:
                records.append({"status": info["status"], "steps": steps})
            if max_seconds is not None and time.monotonic() - started > max_seconds:
                break
    finally:
        env.close()
    wall = time.monotonic() - started
    valid = [r["status"] for r in records if r["status"] in STATUSES]
    return {
        "config": config,
        "offense_agents": offense,
        "defense_npcs": DEFENSE_NPCS,
        "striker": striker,
        "backend": backend,
        "seed": seed,
        "episodes": len(records),
        "episodes_asked": episodes,
        "max_seconds": max_seconds,
        "dropped_first": dropped,
        "server_down": sum(r["status"] == "SERVER_DOWN" for r in records),
        "summary": rate_summary(valid),
        "mean_steps": float(np.mean([r["steps"] for r in records])) if records else math.nan,
        "wall_s": wall,
        "steps_per_s": steps_total / wall if wall > 0 else math.nan,
        "statuses": [r["status"] for r in records],
    }


def load_1min() -> float:
    return os.getloadavg()[0]


def cmd_play(args: argparse.Namespace) -> dict[str, Any]:
    if "real" in args.backends:
        check_network_namespace()
    result: dict[str, Any] = {
        "command": " ".join(sys.argv),
        "hfo2d_version": hfo2d_version(),
        "machine": {"cpus": os.cpu_count(), "load_1min_before": load_1min()},
        "cells": [],
    }
    started = time.monotonic()
    for config in args.configs:
        for striker in args.strikers:
            for backend in args.backends:
                load_before = load_1min()
                cell = play_cell(
                    config,
                    striker,
                    backend,
                    args.episodes,
                    cell_seed(args.seed, config, striker),
                    args.hfo_dir,
                    args.max_seconds,
                )
                cell["load_1min"] = [load_before, load_1min()]
                result["cells"].append(cell)
                summary = cell["summary"]
                print(
                    f"{config} {striker:<14} {backend:<6} goals {100 * summary['rate']:5.1f}% "
                    f"of {summary['n']} ({_counts(summary)}) {cell['wall_s']:.0f} s, "
                    f"{cell['steps_per_s']:.0f} steps/s, load {cell['load_1min'][1]:.1f}",
                    flush=True,
                )
                result["machine"]["load_1min_after"] = load_1min()
                result["seconds"] = time.monotonic() - started
                if args.out:
                    Path(args.out).write_text(json.dumps(result, indent=1))
    return result


def _counts(summary: dict[str, Any]) -> str:
    return "/".join(str(summary["statuses"].get(status, 0)) for status in STATUSES)


def _rate(summary: dict[str, Any]) -> str:
    low, high = summary["wilson95"]
    return f"{100 * summary['rate']:.1f} [{100 * low:.1f}, {100 * high:.1f}]"


def join_cells(cells: Sequence[dict[str, Any]]) -> list[dict[str, Any]]:
    """One row per (configuration, striker) with both backends: rates, intervals, counts and real - hfo2d."""
    by_key: dict[tuple[str, str], dict[str, dict[str, Any]]] = {}
    for cell in cells:
        by_key.setdefault((cell["config"], cell["striker"]), {})[cell["backend"]] = cell
    rows = []
    for (config, striker), sides in sorted(
        by_key.items(), key=lambda kv: (list(CONFIGS).index(kv[0][0]), kv[0][1])
    ):
        row: dict[str, Any] = {"config": config, "striker": striker}
        for backend in BACKENDS:
            cell = sides.get(backend)
            row[backend] = (
                None
                if cell is None
                else {
                    key: cell[key]
                    for key in ("summary", "episodes", "server_down", "mean_steps", "wall_s", "load_1min")
                }
            )
        if row["hfo2d"] and row["real"]:
            row.update(difference(row["real"]["summary"], row["hfo2d"]["summary"]))
        rows.append(row)
    return rows


def print_table(rows: Sequence[dict[str, Any]]) -> None:
    print(
        "| config | striker | hfo2d goals % [95 %] | real goals % [95 %] | real - hfo2d (± se) | statuses hfo2d | "
        "statuses real (G/C/B/T) | episodes hfo2d / real | mean length hfo2d / real |"
    )
    print("|---|---|---:|---:|---:|---|---|---:|---:|")
    for row in rows:
        sim, real = row["hfo2d"], row["real"]
        diff = f"{100 * row['diff']:+.1f} ± {100 * row['se']:.1f}" if "diff" in row else "-"
        print(
            f"| {row['config']} | {row['striker']} | {_rate(sim['summary']) if sim else '-'} | "
            f"{_rate(real['summary']) if real else '-'} | {diff} | {_counts(sim['summary']) if sim else '-'} | "
            f"{_counts(real['summary']) if real else '-'} | {sim['episodes'] if sim else 0} / "
            f"{real['episodes'] if real else 0} | {sim['mean_steps'] if sim else math.nan:.1f} / "
            f"{real['mean_steps'] if real else math.nan:.1f} |"
        )


def cmd_report(args: argparse.Namespace) -> dict[str, Any]:
    runs = [json.loads(Path(path).read_text()) for path in args.results]
    # the per-episode status lists stay in the play files; the joined file keeps their counts (summary)
    cells = [
        {key: value for key, value in cell.items() if key != "statuses"}
        for run in runs
        for cell in run["cells"]
    ]
    rows = join_cells(cells)
    print_table(rows)
    return {
        "rows": rows,
        "runs": [
            {key: run.get(key) for key in ("command", "hfo2d_version", "machine", "seconds")} | {"file": path}
            for path, run in zip(args.results, runs, strict=True)
        ],
        "cells": cells,
    }


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    play = sub.add_parser("play", help="play episodes in one or both backends")
    play.add_argument("--configs", nargs="+", choices=tuple(CONFIGS), default=list(CONFIGS))
    play.add_argument("--strikers", nargs="+", choices=sorted(STRIKERS), default=list(DEFAULT_STRIKERS))
    play.add_argument("--backends", nargs="+", choices=BACKENDS, default=list(BACKENDS))
    play.add_argument("--episodes", type=int, default=1000)
    play.add_argument("--seed", type=int, default=0)
    play.add_argument(
        "--max-seconds",
        type=float,
        default=None,
        help="wall-clock budget per cell: stop early (a slow machine)",
    )
    play.add_argument("--hfo-dir", default=None, help="real HFO build (default $HFO_DIR)")
    play.add_argument("--smoke", action="store_true", help=f"{SMOKE_EPISODES} episodes per cell (tests)")
    play.add_argument("--out", default=None)
    report = sub.add_parser("report", help="join play results into one table")
    report.add_argument("results", nargs="+")
    report.add_argument("--out", default=None)
    return parser


def main(argv: Sequence[str] | None = None) -> dict[str, Any]:
    args = build_parser().parse_args(argv)
    if args.command == "play":
        if args.smoke:
            args.episodes = SMOKE_EPISODES
        if args.episodes < 1:
            raise SystemExit("team_fidelity: --episodes must be >= 1")
        result = cmd_play(args)
    else:
        result = cmd_report(args)
        if args.out:
            Path(args.out).write_text(json.dumps(result, indent=1))
            print(f"wrote {args.out}")
    return result


if __name__ == "__main__":
    main()
