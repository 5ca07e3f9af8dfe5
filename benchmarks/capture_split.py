"""Where a striker loses the ball to the goalie: captured while carrying it, or after kicking it away (a shot).

E6 from reward alone (research/e6_from_reward.md Part D) stalls, for some seeds, with the agent captured by the
goalie in 90 % of its episodes; ``sb3_hfo.evaluate`` counts the captures but cannot say whether the goalie took the
ball off the agent's feet (the carry went on too long) or caught a shot. This script plays a HybridPPO model
greedily on batched hfo2d games (the goalie of the id: agent2d's full goalie on ``HFO/Keeper-v1``) and, for every
episode, records its last executed kick: its power, the ball's distance to the goal centre just before it, and the
ball's speed on the step after it (the kick's step included: rcssserver moves the ball in the cycle of the kick).
It then splits the captured episodes:

* ``on_the_ball``: at the capture the agent is within ``CARRY_RADIUS_M`` of the ball, or its last kick left the
  ball slower than ``SHOT_SPEED`` (a dribbling touch): the goalie took the ball in a carry;
* ``after_a_shot``: the agent is farther than ``CARRY_RADIUS_M`` from the ball and its last kick sent the ball at
  ``SHOT_SPEED`` or faster: the goalie caught or blocked a kick away from the agent.

Goals' last kicks are shots by definition; their speeds, printed beside the captures', show where the threshold
sits. Thresholds (metres, metres per cycle): a dribbling touch (kick power ~10-20 of 100 at rcssserver's
``kick_power_rate`` 0.027) sends the ball at ~0.3-0.6 m/cycle; ``ball_speed_max`` is 3.0 m/cycle.

    python benchmarks/capture_split.py RUN/final.zip --episodes 500 --seed 0 [--json OUT.json]
"""

from __future__ import annotations

import argparse
import json
import math
from collections import Counter
from pathlib import Path
from typing import Any

import numpy as np

from sb3_hfo.evaluation import wilson_interval
from sb3_hfo.hybrid_ppo import HybridPPO
from sb3_hfo.vec_env import make_hfo_vec_env

#: Goal centre (rcssserver's pitch: the goal line at x = 52.5 m).
GOAL_CENTRE = (52.5, 0.0)
#: A last kick at or above this ball speed (m/cycle) is a shot, below it a dribbling touch.
SHOT_SPEED = 1.2
#: At a capture, an agent within this distance (m) of the ball was still carrying it.
CARRY_RADIUS_M = 2.0
#: Edges (m/cycle) of the last-kick ball-speed histogram.
SPEED_EDGES = (0.6, 1.2, 1.8, 2.4)


def _distance(a: tuple[float, ...], b: tuple[float, ...]) -> float:
    return math.hypot(a[0] - b[0], a[1] - b[1])


def play(model_path: Path, env_id: str, episodes: int, seed: int, env_kwargs: dict[str, Any]) -> list[dict]:
    """``episodes`` greedy episodes of the model on 16 (or fewer) batched games; one record per episode."""
    model = HybridPPO.load(model_path, device="cpu")
    n_games = min(16, episodes)
    env = make_hfo_vec_env(env_id, n_games, seed=seed, monitor=False, **env_kwargs)
    obs = env.reset()
    ball_before: list[tuple[float, ...] | None] = [
        None
    ] * n_games  # the ball at the start of each game's step
    last_kick: list[dict | None] = [None] * n_games
    steps = [0] * n_games
    records: list[dict] = []
    started, active = n_games, np.ones(n_games, dtype=bool)
    while active.any():
        actions = model.predict(obs, deterministic=True)[0]
        obs, _, dones, infos = env.step(actions)
        for game, info in enumerate(infos):
            if not active[game]:
                continue
            steps[game] += 1
            if info.get("action") == "KICK" and info.get("action_success"):
                before = ball_before[game] or info["ball"]
                last_kick[game] = {
                    "power": float(info["kick_power"]),
                    "distance_m": _distance(before, GOAL_CENTRE),
                    "ball_speed": math.hypot(info["ball"][2], info["ball"][3]),
                    "step": steps[game],
                }
            ball_before[game] = tuple(info["ball"])
            if not dones[game]:
                continue
            kick = last_kick[game]
            records.append(
                {
                    "status": info["status"],
                    "steps": steps[game],
                    "agent_ball_m": _distance(info["player"], info["ball"]),
                    "ball_goal_m": _distance(info["ball"], GOAL_CENTRE),
                    "last_kick": None
                    if kick is None
                    else {**kick, "cycles_before_end": steps[game] - kick["step"]},
                }
            )
            ball_before[game], last_kick[game], steps[game] = None, None, 0
            if started < episodes:
                started += 1
            else:
                active[game] = False
    env.close()
    return records


def capture_kind(record: dict) -> str:
    """``on_the_ball`` or ``after_a_shot`` for a captured episode (module docstring)."""
    kick = record["last_kick"]
    if record["agent_ball_m"] <= CARRY_RADIUS_M or kick is None or kick["ball_speed"] < SHOT_SPEED:
        return "on_the_ball"
    return "after_a_shot"


def _speed_bin(speed: float) -> str:
    lowers = (0.0, *SPEED_EDGES)
    for low, high in zip(lowers, (*SPEED_EDGES, math.inf), strict=True):
        if low <= speed < high:
            return f"{low:g}-{high:g}" if high != math.inf else f">= {low:g}"
    raise ValueError(f"negative ball speed {speed}")


def _mean(values: list[float]) -> float | None:
    return round(float(np.mean(values)), 2) if values else None


def summarize(records: list[dict]) -> dict:
    """Status counts, the captures split by kind, and last-kick figures for goals and for each kind of capture."""
    statuses = Counter(r["status"] for r in records)
    goals = statuses.get("GOAL", 0)
    groups: dict[str, list[dict]] = {"goal": [r for r in records if r["status"] == "GOAL"]}
    for record in records:
        if record["status"] == "CAPTURED_BY_DEFENSE":
            groups.setdefault(capture_kind(record), []).append(record)
    figures = {}
    for name, group in groups.items():
        kicks = [r["last_kick"] for r in group if r["last_kick"] is not None]
        figures[name] = {
            "episodes": len(group),
            "mean_last_kick_power": _mean([k["power"] for k in kicks]),
            "mean_last_kick_distance_m": _mean([k["distance_m"] for k in kicks]),
            "mean_last_kick_ball_speed": _mean([k["ball_speed"] for k in kicks]),
            "mean_cycles_last_kick_to_end": _mean([k["cycles_before_end"] for k in kicks]),
            "mean_agent_ball_m_at_end": _mean([r["agent_ball_m"] for r in group]),
            "mean_ball_goal_m_at_end": _mean([r["ball_goal_m"] for r in group]),
            "last_kick_ball_speed_bins": dict(
                sorted(Counter(_speed_bin(k["ball_speed"]) for k in kicks).items())
            ),
        }
    return {
        "episodes": len(records),
        "goals": goals,
        "rate": goals / len(records),
        "ci95": list(wilson_interval(goals, len(records))),
        "status": dict(sorted(statuses.items())),
        "thresholds": {"shot_speed_m_per_cycle": SHOT_SPEED, "carry_radius_m": CARRY_RADIUS_M},
        "by_kind": figures,
    }


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("model", type=Path, help="a HybridPPO zip")
    parser.add_argument("--env", default="HFO/Keeper-v1")
    parser.add_argument(
        "--env-kwargs", default="{}", help="JSON: env kwargs (the reward does not matter here)"
    )
    parser.add_argument("--episodes", type=int, default=500)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--json", type=Path, default=None, help="also write the summary here")
    args = parser.parse_args(argv)
    if args.episodes < 1:
        parser.error(f"--episodes must be >= 1, got {args.episodes}")
    summary = {
        "model": str(args.model),
        "env_id": args.env,
        "seed": args.seed,
        **summarize(play(args.model, args.env, args.episodes, args.seed, json.loads(args.env_kwargs))),
    }
    text = json.dumps(summary, indent=1)
    print(text)
    if args.json is not None:
        args.json.write_text(text + "\n")


if __name__ == "__main__":
    main()
