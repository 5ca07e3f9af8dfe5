"""Where a trained agent fails: end status by start geometry and by where the ball ends, as tables and a PNG.

Plays greedy episodes through :func:`sb3_hfo.evaluate.run_episodes` and groups them twice: by where the agent
started relative to the ball (HFO places it ``10.5 * (U(0, 1) + offset)`` m from the ball per axis, so some
episodes start with the agent 20-30 m closer to the goal than the ball), and by where the ball ended: in which
half of the goal, or how far from the goal centre (a caught ball: where the keeper caught it). The figure shows
each episode's ball start, the agent's start relative to the ball, and the ball's end position (with the
keeper's, on keeper tasks, for the episodes he ended), coloured by end status. Used for the failure analyses of
sessions 6 and 16 in research/RESULTS.md:

    python research/probes/failure_map.py models/e1_empty_goal_fast_seed0 --episodes 1000 --seed 0 \\
        --out research/figures/failure_map_e1.png
"""

from __future__ import annotations

import itertools
import math
from collections import Counter
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from hfo2d.physics import GOAL_HALF_WIDTH
from sb3_hfo.cli.evaluate import add_acting_argument, episodes_parser
from sb3_hfo.evaluation import (
    GOAL_CENTRE,
    EpisodeRecord,
    load_for_evaluation,
    model_n_skills,
    run_episodes,
    wilson_interval,
)
from sb3_hfo.skill_ddpg.acting import CriticChoice, MirrorChoice

#: Start classes by the agent's x minus the ball's x (m): the agent behind, level with, or ahead of the ball.
AHEAD_LIMITS = (-5.0, 5.0, 15.0)
#: End classes by the ball's final distance from the goal centre (m).
END_DISTANCE_LIMITS = (5.0, 10.0, 20.0)
#: Goals by the half of the goal the ball crossed the line in (rcssserver's y < 0 is the top post's half).
GOAL_END_LABELS = ("ball ends in the goal, top half (y < 0)", "ball ends in the goal, bottom half (y >= 0)")
STATUS_STYLE = {  # status: (colour, marker)
    "GOAL": ("tab:green", "."),
    "OUT_OF_BOUNDS": ("tab:orange", "x"),
    "OUT_OF_TIME": ("tab:red", "o"),
    "CAPTURED_BY_DEFENSE": ("tab:purple", "s"),
}


def _start_offset(record: EpisodeRecord) -> tuple[float, float] | None:
    """The agent's start minus the ball's (m), or None without positions."""
    if record.start_ball is None or record.start_player is None:
        return None
    return record.start_player[0] - record.start_ball[0], record.start_player[1] - record.start_ball[1]


def start_class(record: EpisodeRecord) -> str:
    """The agent's start relative to the ball along x, as a label (records without positions: 'unknown')."""
    offset = _start_offset(record)
    if offset is None:
        return "unknown"
    ahead = offset[0]
    low, mid, high = AHEAD_LIMITS
    if ahead < low:
        return f"agent > {-low:g} m behind the ball"
    if ahead < mid:
        return f"agent within {mid:g} m of the ball's x"
    if ahead < high:
        return f"agent {mid:g}-{high:g} m ahead of the ball"
    return f"agent > {high:g} m ahead of the ball"


def end_class_labels() -> list[str]:
    """``end_class``'s labels, nearest the goal first."""
    bounds = (0.0, *END_DISTANCE_LIMITS)
    labels = [*GOAL_END_LABELS] + [
        f"ball ends {low:g}-{high:g} m from goal" for low, high in itertools.pairwise(bounds)
    ]
    return [*labels, f"ball ends >= {bounds[-1]:g} m from goal"]


def end_class(record: EpisodeRecord) -> str:
    """Where the ball ended: in the goal, or its distance from the goal centre (no position recorded: 'unknown')."""
    if record.end_ball is None:
        return "unknown"
    if record.status == "GOAL":
        return GOAL_END_LABELS[record.end_ball[1] >= 0.0]
    distance = math.dist(GOAL_CENTRE, record.end_ball)
    below = sum(distance >= limit for limit in END_DISTANCE_LIMITS)
    return end_class_labels()[len(GOAL_END_LABELS) + below]


def table_rows(
    records: Sequence[EpisodeRecord], classify: Callable[[EpisodeRecord], str] = start_class
) -> list[tuple[str, int, float, float, float, dict[str, int]]]:
    """(class, episodes, goal rate, CI low, CI high, status counts) per ``classify`` class, then 'all'."""
    groups: dict[str, list[EpisodeRecord]] = {}
    for record in records:
        groups.setdefault(classify(record), []).append(record)
    rows = []
    # end classes read nearest-first; start classes (and 'unknown') alphabetically
    order = {label: index for index, label in enumerate(end_class_labels())}
    ranked = sorted(groups.items(), key=lambda item: (order.get(item[0], len(order)), item[0]))
    for name, members in [*ranked, ("all", list(records))]:
        counts = Counter(r.status for r in members)
        goals = counts.get("GOAL", 0)
        low, high = wilson_interval(goals, len(members))
        rows.append((name, len(members), goals / len(members), low, high, dict(sorted(counts.items()))))
    return rows


def plot(records: Sequence[EpisodeRecord], title: str, out: Path) -> None:
    """Three panels coloured by end status: ball starts, the agent's start offset from the ball, ball ends."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_ball, ax_offset, ax_end) = plt.subplots(1, 3, figsize=(18, 5.2))
    panels: list[tuple[Any, Callable[[EpisodeRecord], tuple[float, float] | None]]] = [
        (ax_ball, lambda r: r.start_ball),
        (ax_offset, _start_offset),
        (ax_end, lambda r: r.end_ball),
    ]
    for status, (colour, marker) in STATUS_STYLE.items():
        chosen = [r for r in records if r.status == status and r.start_ball and r.start_player]
        if not chosen:
            continue
        label = f"{status} ({len(chosen)})"
        size = 6 if status == "GOAL" else 22
        for axis, point in panels:
            points = [p for p in map(point, chosen) if p is not None]
            axis.scatter(
                [x for x, _ in points], [y for _, y in points], s=size, c=colour, marker=marker, label=label
            )
    caught = [r for r in records if r.status == "CAPTURED_BY_DEFENSE" and r.end_keeper]
    if caught:
        ax_end.scatter(
            [r.end_keeper[0] for r in caught],  # type: ignore[index]
            [r.end_keeper[1] for r in caught],  # type: ignore[index]
            s=10,
            facecolors="none",
            edgecolors="black",
            linewidths=0.5,
            label=f"keeper when he caught it ({len(caught)})",
        )
    goal_x, _ = GOAL_CENTRE
    ax_end.plot([goal_x, goal_x], [-GOAL_HALF_WIDTH, GOAL_HALF_WIDTH], color="black", linewidth=3)
    ax_ball.set(xlabel="ball start x (m; goal at 52.5)", ylabel="ball start y (m)", title="Ball start")
    ax_ball.invert_yaxis()  # rcssserver's +y points down the screen
    ax_offset.set(
        xlabel="agent x - ball x (m; > 0: agent nearer the goal)",
        ylabel="agent y - ball y (m)",
        title="Agent start relative to the ball",
    )
    ax_offset.invert_yaxis()
    ax_offset.legend(loc="upper left", fontsize=8)
    ax_end.set(
        xlabel="ball end x (m; goal mouth drawn)", ylabel="ball end y (m)", title="Where the ball ends"
    )
    ax_end.set_aspect("equal", adjustable="datalim")
    ax_end.invert_yaxis()
    ax_end.legend(loc="upper left", fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main(argv: Sequence[str] | None = None) -> None:
    parser = episodes_parser(__doc__.splitlines()[0], default_episodes=1000)
    parser.add_argument("--out", type=Path, default=None, help="PNG to write (default: none)")
    add_acting_argument(parser)  # --acting SPEC, e.g. critic,kick_mask,mirror:0.1 (default: the model's own)
    args = parser.parse_args(argv)

    model, env, env_id, _, path = load_for_evaluation(args.model, args.env or None)
    try:
        if args.acting is not None:
            model.policy.acting = args.acting
        records = run_episodes(model, env, args.episodes, args.seed, True, model_n_skills(model))
    finally:
        env.close()
    acting = model.policy.acting
    choice = "critic" if any(isinstance(strategy, CriticChoice) for strategy in acting) else "actor"
    mirror = next((strategy for strategy in acting if isinstance(strategy, MirrorChoice)), None)
    if mirror is not None:
        choice += " (better of state and mirror image"
        choice += f", margin {mirror.margin:g})" if mirror.margin else ")"
    print(
        f"{path} on {env_id}: {args.episodes} greedy episodes, seed {args.seed}, {choice} picks the discrete action"
    )
    for classify in (start_class, end_class):
        rows = table_rows(records, classify)
        width = max(len(row[0]) for row in rows)
        for name, n, rate, low, high, counts in rows:
            print(
                f"  {name:<{width}} {n:>5} episodes  goal rate {rate:.3f} [{low:.3f}, {high:.3f}]  {counts}"
            )
    if args.out is not None:
        title = (
            f"{Path(str(path)).parent.name}/{Path(str(path)).name}: {args.episodes} episodes, seed {args.seed}, "
            f"{choice} picks"
        )
        plot(records, title, args.out)
        print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
