"""What each kind of episode pays a trained agent: mean return by the last kick's distance and the end status.

Plays greedy episodes through :func:`sb3_hfo.evaluate.run_episodes` and groups them by the distance from the goal
centre of the agent's last kick (evaluate's ``shots_by_distance`` bins) and by how the episode ended, printing the
count, mean (undiscounted) return, mean length in cycles and kicks per episode of each group. Used in
research/RESULTS.md (session 15) to show what the ``shaped_gap`` reward paid x24 for kicking the ball from
>= 40 m into the keeper's arms:

    python research/probes/return_by_outcome.py models/x24_keeper_skills_each_action_parameters_seed0 \\
        --episodes 300 --seed 0

``--reward`` replays the same episodes under another of hfo2d's rewards (the reward does not steer a trained
agent, so the episodes are the same), to see what a different reward would have paid for the same play.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path

from hfo2d.reward import REWARD_NAMES
from sb3_hfo.cli.evaluate import episodes_parser
from sb3_hfo.evaluation import (
    EpisodeRecord,
    load_for_evaluation,
    model_n_skills,
    run_episodes,
    shot_distance_label,
    shot_distance_labels,
)

NO_KICK = "no kick"


def group_rows(records: Sequence[EpisodeRecord]) -> list[dict[str, object]]:
    """One row per (last-kick distance bin, end status) present, nearest bin first, then statuses A-Z."""
    groups: dict[tuple[str, str], list[EpisodeRecord]] = {}
    for record in records:
        distance = NO_KICK if record.shot_distance is None else shot_distance_label(record.shot_distance)
        groups.setdefault((distance, record.status), []).append(record)
    order = [*shot_distance_labels(), NO_KICK]
    rows = []
    for distance, status in sorted(groups, key=lambda key: (order.index(key[0]), key[1])):
        members = groups[(distance, status)]
        rows.append(
            {
                "last_kick": distance,
                "status": status,
                "episodes": len(members),
                "mean_return": sum(r.reward for r in members) / len(members),
                "mean_steps": sum(r.steps for r in members) / len(members),
                "kicks_per_episode": sum(r.kicks for r in members) / len(members),
            }
        )
    return rows


def main(argv: Sequence[str] | None = None) -> None:
    parser = episodes_parser(__doc__.splitlines()[0], default_episodes=300)
    parser.add_argument(
        "--reward",
        choices=REWARD_NAMES,
        default=None,
        help="score the episodes with this reward (default: the run's)",
    )
    parser.add_argument("--json", type=Path, default=None, help="write the rows here as JSON")
    args = parser.parse_args(argv)

    model, env, env_id, env_kwargs, path = load_for_evaluation(
        args.model, args.env, None if args.reward is None else {"reward": args.reward}
    )
    try:
        records = run_episodes(model, env, args.episodes, args.seed, True, model_n_skills(model))
    finally:
        env.close()
    rows = group_rows(records)
    print(f"{path} on {env_id} {env_kwargs}, {args.episodes} greedy episodes, seed {args.seed}")
    print(f"{'last kick':>10} {'status':>20} {'episodes':>8} {'return':>7} {'cycles':>7} {'kicks':>6}")
    for row in rows:
        print(
            f"{row['last_kick']:>10} {row['status']:>20} {row['episodes']:>8} {row['mean_return']:>7.2f}"
            f" {row['mean_steps']:>7.1f} {row['kicks_per_episode']:>6.2f}"
        )
    if args.json is not None:
        payload = {"model": str(path), "env_id": env_id, "episodes": args.episodes, "seed": args.seed}
        args.json.write_text(json.dumps({**payload, "rows": rows}, indent=2))


if __name__ == "__main__":
    main()
