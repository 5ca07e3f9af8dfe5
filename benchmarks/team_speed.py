"""Steps per second of hfo2d's team game (hfo2d.team.TeamGame) against the one-agent HFO/Keeper-v1, in one run.

Every configuration is stepped with uniformly random flat actions drawn in advance (so only the game is timed;
episode resets included), each the best of ``--repeat`` runs of ``--steps`` cycles, in the same process one after
the other, so the ratios compare like with like on a shared machine. A "step" is one server cycle of the whole
game (every agent acts); "agent steps/s" counts each learning agent's transition.

Configurations (bin/HFO's flags): 1v1 = ``--offense-agents 1 --defense-npcs 1`` (the team game's counterpart of
HFO/Keeper-v1), 2v1 = 2 agents against agent2d's goalie, 2v2 = 2 agents against the goalie and a second defender
(agent2d's field defender NPC when ``hfo2d.agent2d.defender`` is present, else a learning defense agent fed random
actions, which the table says), 4v5 likewise with four field defenders.

    python benchmarks/team_speed.py --steps 5000 --repeat 3 --out benchmarks/results/team_speed.json

With ``--real`` it also steps the real HFO (``hfo2d.parallel_env(..., backend="real")``: rcssserver, HFO's
trainer, agent2d's NPCs, one process per learning agent; needs ``$HFO_DIR`` and ``hfo2d.real_teams``) in the
configurations with agent2d's NPCs only (2v1 and 2v2: 2 offense agents against ``defense_npcs`` 1 or 2), for
``--real-steps`` cycles after its start-up, and prints hfo2d / real per configuration (hfo2d's 2v2 matches it only
when hfo2d has the field defenders' port), by wall clock and per CPU second: the real HFO spreads a game over
several processes (server, trainer, NPCs, agent workers) and so over the machine's cores, while hfo2d plays it in
one process, so the second ratio compares the work each spends on a cycle (all the session's processes' CPU, read
from /proc). The real servers must run in the repository's loopback runner::

    HFO_DIR=/path/to/HFO tools/real_hfo/loopback.sh nice -n 5 python benchmarks/team_speed.py --real
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import os
import platform
import sys
import time
from typing import Any

import gymnasium as gym
import numpy as np

import hfo2d  # noqa: F401  (registers the ids)
from hfo2d import accel
from hfo2d.team import TeamGame


def _defender_port_present() -> bool:
    return importlib.util.find_spec("hfo2d.agent2d.defender") is not None


def time_game(game: TeamGame, steps: int, seed: int) -> float:
    """Cycles per second of ``game`` under random flat actions (one process: on a quiet machine its CPU seconds
    are its wall-clock seconds)."""
    rng = np.random.default_rng(seed)
    actions = {agent.name: rng.random((steps, agent.layout.size), dtype=np.float32) for agent in game.agents}
    game.reset(seed=seed)
    start = time.perf_counter()
    for index in range(steps):
        _, _, terminated, truncated, _ = game.step({name: batch[index] for name, batch in actions.items()})
        if terminated or truncated:
            game.reset()
    return steps / (time.perf_counter() - start)


def time_keeper_v1(steps: int, seed: int) -> float:
    env = gym.make("HFO/Keeper-v1").unwrapped
    actions = np.random.default_rng(seed).random((steps, 8), dtype=np.float32)
    env.reset(seed=seed)
    start = time.perf_counter()
    for index in range(steps):
        _, _, terminated, truncated, _ = env.step(actions[index])
        if terminated or truncated:
            env.reset()
    return steps / (time.perf_counter() - start)


def descendant_cpu_seconds(root: int | None = None) -> float:
    """CPU seconds (user + system) used so far by the live descendants of process ``root`` (this one by default),
    read from /proc: the real HFO's server, trainer, NPCs and agent workers. 0.0 where /proc is missing."""
    root = os.getpid() if root is None else root
    ticks = os.sysconf("SC_CLK_TCK")
    parents: dict[int, int] = {}
    cpu: dict[int, float] = {}
    for entry in os.listdir("/proc") if os.path.isdir("/proc") else ():
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as handle:
                fields = handle.read().rsplit(")", 1)[1].split()
        except OSError:  # the process ended meanwhile
            continue
        # after the command's ")": state, ppid, ... utime (field 14 of stat(5)) and stime (15) at offsets 11, 12
        parents[int(entry)] = int(fields[1])
        cpu[int(entry)] = (int(fields[11]) + int(fields[12])) / ticks
    total = 0.0
    for pid in cpu:
        ancestor = parents.get(pid)
        while ancestor is not None and ancestor not in (root, 0, 1):
            ancestor = parents.get(ancestor)
        if ancestor == root and pid != root:
            total += cpu[pid]
    return total


def time_real(sizes: dict[str, int], steps: int, seed: int) -> tuple[float, float]:
    """(cycles per wall-clock second, cycles per CPU second) of the real HFO in these team sizes under random flat
    actions, start-up excluded. The CPU seconds are every process of the session (rcssserver, HFO's trainer,
    agent2d's NPCs, one worker per learning agent; their CPU read from /proc just before they are closed) plus
    this process's own: the real HFO spreads a game over several processes and cores, hfo2d plays it in one."""
    env = hfo2d.parallel_env(backend="real", seed=seed, **sizes)
    try:
        rng = np.random.default_rng(seed)
        env.reset(seed=seed)
        start, own_start, others_start = time.perf_counter(), time.process_time(), descendant_cpu_seconds()
        for _ in range(steps):
            if not env.agents:
                env.reset()
            env.step(
                {agent: rng.random(env.action_space(agent).shape, dtype=np.float32) for agent in env.agents}
            )
        wall = time.perf_counter() - start
        cpu = time.process_time() - own_start + descendant_cpu_seconds() - others_start
        return steps / wall, (steps / cpu if cpu > 0.0 else float("nan"))
    finally:
        env.close()


def configurations() -> list[tuple[str, dict[str, int]]]:
    """(label, TeamGame sizes); field defenders are NPCs when their port exists, else defense agents."""
    npcs = _defender_port_present()

    def sizes(offense: int, defenders: int) -> dict[str, int]:
        if npcs:
            return {"offense_agents": offense, "defense_agents": 0, "defense_npcs": defenders}
        return {"offense_agents": offense, "defense_agents": defenders - 1, "defense_npcs": 1}

    return [("1v1", sizes(1, 1)), ("2v1", sizes(2, 1)), ("2v2", sizes(2, 2)), ("4v5", sizes(4, 5))]


def main(argv: list[str] | None = None) -> dict[str, Any]:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--steps", type=int, default=5000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", default=None, help="write the results as JSON here")
    parser.add_argument("--real", action="store_true", help="also step the real HFO (needs $HFO_DIR)")
    parser.add_argument(
        "--real-steps", type=int, default=1000, help="cycles of the real HFO per configuration"
    )
    args = parser.parse_args(argv)

    load_before = os.getloadavg()[0]
    keeper = max(time_keeper_v1(args.steps, args.seed) for _ in range(args.repeat))
    rows = [
        {
            "config": "HFO/Keeper-v1 (HFOEnv)",
            "steps_per_s": keeper,
            "agent_steps_per_s": keeper,
            "vs_keeper_v1": 1.0,
        }
    ]
    for label, sizes in configurations():
        game = TeamGame(**sizes)
        rate = max(time_game(game, args.steps, args.seed) for _ in range(args.repeat))
        npc_count = len(game.defense_npcs)
        rows.append(
            {
                "config": f"{label} ({sizes['offense_agents']} offense agents, {sizes['defense_agents']} defense "
                f"agents, {npc_count} defense NPCs)",
                "steps_per_s": rate,
                "agent_steps_per_s": rate * len(game.agents),
                "vs_keeper_v1": rate / keeper,
            }
        )
    real_rows = []
    if args.real:
        hfo2d_rates = {row["config"].split(" ")[0]: row["steps_per_s"] for row in rows}
        for label, defense_npcs in (("2v1", 1), ("2v2", 2)):
            sizes = {"offense_agents": 2, "defense_agents": 0, "defense_npcs": defense_npcs}
            rate, rate_per_cpu_s = time_real(sizes, args.real_steps, args.seed)
            real_rows.append(
                {
                    "config": f"{label} real HFO (2 offense agents, {defense_npcs} agent2d defense NPCs)",
                    "steps_per_s": rate,
                    "hfo2d_over_real": hfo2d_rates[label] / rate,
                    # the real HFO's cycles per CPU second of all its processes; hfo2d's one process per CPU second
                    # is its wall-clock rate (a quiet machine), so this ratio compares the work per cycle
                    "steps_per_cpu_s": rate_per_cpu_s,
                    "hfo2d_over_real_per_cpu_s": hfo2d_rates[label] / rate_per_cpu_s,
                }
            )
    result = {
        "command": " ".join(
            ["python", "benchmarks/team_speed.py", *(sys.argv[1:] if argv is None else argv)]
        ),
        "steps": args.steps,
        "repeat": args.repeat,
        "defender_npc_port": _defender_port_present(),
        # whether hfo2d's compiled kernels (hfo2d._accel) ran, and why not (hfo2d.accel; HFO2D_PURE_PYTHON=1)
        "accel_in_use": accel.in_use(),
        "accel_status": accel.STATUS,
        "machine": {
            "cpus": os.cpu_count(),
            "python": platform.python_version(),
            "load_1min_before": load_before,
            "load_1min_after": os.getloadavg()[0],
        },
        "rows": rows,
        "real_rows": real_rows,
    }
    print(f"{'config':70s} {'steps/s':>10s} {'agent steps/s':>14s} {'x Keeper-v1':>12s}")
    for row in rows:
        print(
            f"{row['config']:70s} {row['steps_per_s']:10,.0f} {row['agent_steps_per_s']:14,.0f} "
            f"{row['vs_keeper_v1']:12.2f}"
        )
    for row in real_rows:
        print(
            f"{row['config']:70s} {row['steps_per_s']:10,.0f}   hfo2d / real {row['hfo2d_over_real']:.1f}   "
            f"per CPU second: real {row['steps_per_cpu_s']:,.0f}, hfo2d / real {row['hfo2d_over_real_per_cpu_s']:.1f}"
        )
    print(f"compiled kernels: {'in use' if accel.in_use() else 'NOT in use'} ({accel.STATUS})")
    print(f"load average (1 min) before {load_before:.2f}, after {result['machine']['load_1min_after']:.2f}")
    if args.out:
        with open(args.out, "w") as handle:
            json.dump(result, handle, indent=2)
    return result


if __name__ == "__main__":
    main()
