"""Which skill a two-skill HybridPPO model plays in each field half (issue 33, item 4: the learned router).

For a model with ``skills=2`` (``router="learned"`` or ``"field_half"``), plays ``--episodes`` greedy episodes
on 16 games of ``--env`` (hfo2d's batch) and counts, over every step, the skill that acted against the half of
the attacked half-field the agent stood in, and against whether the ball was kickable (the split of the seed paper's field-half router, x = 26.25 m; the
column and threshold come from the policy's domain adapter, :data:`sb3_hfo.hfo.HFO_DOMAIN`). With the learned
router the skill is its greedy choice (the argmax of the router's categorical, what ``predict(deterministic=True)``
plays); with ``field_half`` the table is diagonal by construction (a check of the bookkeeping).

    python benchmarks/router_usage.py RUN/final.zip --env HFO/EmptyGoal-v0 --episodes 200 --json OUT.json
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from sb3_hfo.common.domain import resolve_domain
from sb3_hfo.hybrid_ppo import HybridPPO
from sb3_hfo.vec_env import make_hfo_vec_env

HALVES = ("far half (x < 26.25 m)", "near half (x >= 26.25 m)")
POSSESSION = ("ball not kickable", "ball kickable")


def router_usage(model: HybridPPO, env_id: str, episodes: int, seed: int) -> dict:
    """Steps per (field half, skill) over ``episodes`` greedy episodes, with the goals scored."""
    policy = model.policy
    if policy.n_skills < 2:
        raise ValueError(f"router_usage needs a model with skills > 1; this one has {policy.n_skills}")
    domain = resolve_domain(policy.domain)
    if domain.field_half_column is None:
        raise ValueError(f"the model's domain ({domain.name}) names no field-half column to split on")
    n_games = min(16, episodes)
    env = make_hfo_vec_env(env_id, n_games, seed=seed, monitor=False)
    counts = np.zeros((2, policy.n_skills), dtype=np.int64)
    by_possession = np.zeros((2, policy.n_skills), dtype=np.int64)
    started, finished, goals = n_games, 0, 0
    active = np.ones(n_games, dtype=bool)
    obs = env.reset()
    while active.any():
        skills = np.asarray(policy.skill_router(obs.astype(np.float32)), dtype=np.int64)
        # feature above the threshold: the half away from the goal (row 0), as FieldHalfRouter splits
        near = (obs[:, domain.field_half_column] <= domain.field_half_threshold).astype(np.int64)
        np.add.at(counts, (near[active], skills[active]), 1)
        if domain.kickable_column is not None:  # the kickable feature is +1 with the ball in reach, else -1
            kickable = (obs[:, domain.kickable_column] > 0).astype(np.int64)
            np.add.at(by_possession, (kickable[active], skills[active]), 1)
        actions, _ = model.predict(obs, deterministic=True)
        obs, _, dones, infos = env.step(actions)
        for game in np.flatnonzero(dones & active):
            finished += 1
            goals += infos[game]["status"] == "GOAL"
            if started < episodes:
                started += 1
            else:
                active[game] = False
    env.close()
    return {
        "env_id": env_id,
        "episodes": finished,
        "goals": int(goals),
        "router": str(policy.router),
        "steps": {half: [int(c) for c in row] for half, row in zip(HALVES, counts, strict=True)},
        "skill_share": {
            half: [round(float(c) / max(int(row.sum()), 1), 4) for c in row]
            for half, row in zip(HALVES, counts, strict=True)
        },
        "steps_by_possession": {
            state: [int(c) for c in row] for state, row in zip(POSSESSION, by_possession, strict=True)
        },
    }


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("model", type=Path)
    parser.add_argument("--env", default="HFO/EmptyGoal-v0")
    parser.add_argument("--episodes", type=int, default=200)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--json", type=Path, default=None)
    args = parser.parse_args(argv)
    if args.episodes < 1:
        parser.error(f"--episodes must be >= 1, got {args.episodes}")
    result = router_usage(HybridPPO.load(args.model, device="cpu"), args.env, args.episodes, args.seed)
    result["model"] = str(args.model)
    text = json.dumps(result, indent=1)
    print(text)
    if args.json is not None:
        args.json.write_text(text)


if __name__ == "__main__":
    main()
