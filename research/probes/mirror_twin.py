"""A trained policy against its mirror twin, by whether the start's mirror image is a start HFO draws.

The twin plays the policy in the mirror image of the state (y -> -y) and mirrors its action back
(:mod:`hfo2d.symmetry`). HFO's dynamics are symmetric, its start distribution is not: for half of its starts the
agent's y offset from the ball has a mirror image HFO never draws (``hfo2d.symmetry.start_offset_is_drawn``), so
on those the twin starts from states the policy never trained on. This script plays greedy episodes with the
policy held on each side for whole episodes (``HFOPolicy``'s acting ``MirrorChoice(inf)`` and the side set in
``predict``'s state) and tables the goal rate by that start class. Used in research/RESULTS.md, session 17, to find
why the mirror choice (``--acting ...,mirror``) costs some empty-goal models points:

    python research/probes/mirror_twin.py models/x21_empty_goal_each_action_parameters_fast_seed0 --episodes 1000

The two sides play the same number of episodes from the same seed, not necessarily the same starts (the random
stream follows the play).
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from hfo2d.symmetry import start_offset_is_drawn, start_y_is_clamped
from sb3_hfo.cli.evaluate import episodes_parser
from sb3_hfo.evaluation import (
    EpisodeRecord,
    load_for_evaluation,
    model_n_skills,
    run_episodes,
    wilson_interval,
)
from sb3_hfo.skill_ddpg.acting import MirrorChoice

START_CLASSES = (
    "mirror image of the start drawn by HFO",
    "mirror image never drawn",
    "agent on the start's side-line clamp",
)
SIDES = {"plain": 0.0, "twin": 1.0}  # predict-state values of HFOPolicy's mirror side: 1.0 = mirrored side


def mirror_start_class(record: EpisodeRecord) -> str:
    """Which of :data:`START_CLASSES` an episode's start belongs to."""
    assert record.start_ball is not None and record.start_player is not None
    if start_y_is_clamped(record.start_player[1]):
        return START_CLASSES[2]
    offset_y = record.start_player[1] - record.start_ball[1]
    return START_CLASSES[0] if start_offset_is_drawn(-offset_y) else START_CLASSES[1]


class OneSide:
    """``model`` held on one side (plain or twin) for every step: its policy's side never switches."""

    def __init__(self, model: Any, side: float) -> None:
        self.model, self.policy, self.side = model, model.policy, side

    def predict(
        self, obs: np.ndarray, state: Any = None, episode_start: Any = None, deterministic: bool = True
    ) -> tuple[np.ndarray, Any]:
        held = (np.array([self.side], dtype=np.float32),)
        return self.model.predict(
            obs, state=held, episode_start=np.zeros(1, dtype=bool), deterministic=deterministic
        )


def by_class(records: Sequence[EpisodeRecord]) -> dict[str, dict[str, int]]:
    """Episodes and goals per start class, then 'all'."""
    table = {name: {"episodes": 0, "goals": 0} for name in (*START_CLASSES, "all")}
    for record in records:
        for name in (mirror_start_class(record), "all"):
            table[name]["episodes"] += 1
            table[name]["goals"] += record.status == "GOAL"
    return table


def main(argv: Sequence[str] | None = None) -> None:
    parser = episodes_parser(__doc__.splitlines()[0], default_episodes=1000)
    parser.add_argument("--json", type=Path, default=None, help="write the tables as JSON to this file")
    args = parser.parse_args(argv)

    model, env, env_id, _, path = load_for_evaluation(args.model, args.env or None)
    # the model's own strategies, with the mirror choice that never switches sides within an episode
    own = tuple(strategy for strategy in model.policy.acting if not isinstance(strategy, MirrorChoice))
    model.policy.acting = (*own, MirrorChoice(float("inf")))
    try:
        tables = {
            side: by_class(
                run_episodes(
                    OneSide(model, value), env, args.episodes, args.seed, True, model_n_skills(model)
                )
            )
            for side, value in SIDES.items()
        }
    finally:
        env.close()
    print(f"{path} on {env_id}: {args.episodes} greedy episodes per side, seed {args.seed}")
    width = max(len(name) for name in (*START_CLASSES, "all"))
    print(f"{'start class':{width}s}  {'plain policy':>26s}  {'mirror twin':>26s}")
    for name in (*START_CLASSES, "all"):
        cells = []
        for side in SIDES:
            goals, episodes = tables[side][name]["goals"], tables[side][name]["episodes"]
            low, high = wilson_interval(goals, episodes)
            rate = (
                f"{100 * goals / episodes:5.1f} % [{100 * low:4.1f}, {100 * high:5.1f}]" if episodes else "-"
            )
            cells.append(f"{goals:4d}/{episodes:<4d} {rate}")
        print(f"{name:{width}s}  {cells[0]:>26s}  {cells[1]:>26s}")
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        payload = {
            "model": str(path),
            "env_id": env_id,
            "episodes": args.episodes,
            "seed": args.seed,
            **tables,
        }
        args.json.write_text(json.dumps(payload, indent=2) + "\n")


if __name__ == "__main__":
    main()
