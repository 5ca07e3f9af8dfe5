"""Where a trained agent fails: end status by start geometry, as a table and a two-panel PNG.

Plays greedy episodes through :func:`sb3_hfo.evaluate.run_episodes` and groups them by where the agent started
relative to the ball (HFO places it ``10.5 * (U(0, 1) + offset)`` m from the ball per axis, so some episodes
start with the agent 20-30 m closer to the goal than the ball). The figure shows each episode's ball start
(left) and the agent's start relative to the ball (right), coloured by end status. Used for the session-6
failure analysis in benchmarks/RESULTS.md:

    python benchmarks/failure_map.py models/e1_empty_goal_fast_seed0 --episodes 1000 --seed 0 \\
        --out benchmarks/figures/failure_map_e1.png
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence
from pathlib import Path

from sb3_hfo.evaluate import (
    EpisodeRecord,
    episodes_parser,
    load_for_evaluation,
    model_n_skills,
    run_episodes,
    wilson_interval,
)
from sb3_hfo.skill_ddpg.policies import DISCRETE_CHOICES

#: Start classes by the agent's x minus the ball's x (m): the agent behind, level with, or ahead of the ball.
AHEAD_LIMITS = (-5.0, 5.0, 15.0)
STATUS_STYLE = {  # status: (colour, marker)
    "GOAL": ("tab:green", "."),
    "OUT_OF_BOUNDS": ("tab:orange", "x"),
    "OUT_OF_TIME": ("tab:red", "o"),
    "CAPTURED_BY_DEFENSE": ("tab:purple", "s"),
}


def start_class(record: EpisodeRecord) -> str:
    """The agent's start relative to the ball along x, as a label (records without positions: 'unknown')."""
    if record.start_ball is None or record.start_player is None:
        return "unknown"
    ahead = record.start_player[0] - record.start_ball[0]
    low, mid, high = AHEAD_LIMITS
    if ahead < low:
        return f"agent > {-low:g} m behind the ball"
    if ahead < mid:
        return f"agent within {mid:g} m of the ball's x"
    if ahead < high:
        return f"agent {mid:g}-{high:g} m ahead of the ball"
    return f"agent > {high:g} m ahead of the ball"


def table_rows(
    records: Sequence[EpisodeRecord],
) -> list[tuple[str, int, float, float, float, dict[str, int]]]:
    """(class, episodes, goal rate, CI low, CI high, status counts) per start class, then 'all'."""
    groups: dict[str, list[EpisodeRecord]] = {}
    for record in records:
        groups.setdefault(start_class(record), []).append(record)
    rows = []
    for name, members in [*sorted(groups.items()), ("all", list(records))]:
        counts = Counter(r.status for r in members)
        goals = counts.get("GOAL", 0)
        low, high = wilson_interval(goals, len(members))
        rows.append((name, len(members), goals / len(members), low, high, dict(sorted(counts.items()))))
    return rows


def plot(records: Sequence[EpisodeRecord], title: str, out: Path) -> None:
    """Two panels: ball start positions, and the agent's start offset from the ball, coloured by end status."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_ball, ax_offset) = plt.subplots(1, 2, figsize=(12, 5.2))
    for status, (colour, marker) in STATUS_STYLE.items():
        chosen = [r for r in records if r.status == status and r.start_ball and r.start_player]
        if not chosen:
            continue
        label = f"{status} ({len(chosen)})"
        size = 6 if status == "GOAL" else 22
        ax_ball.scatter(
            [r.start_ball[0] for r in chosen],  # type: ignore[index]
            [r.start_ball[1] for r in chosen],  # type: ignore[index]
            s=size,
            c=colour,
            marker=marker,
            label=label,
        )
        ax_offset.scatter(
            [r.start_player[0] - r.start_ball[0] for r in chosen],  # type: ignore[index]
            [r.start_player[1] - r.start_ball[1] for r in chosen],  # type: ignore[index]
            s=size,
            c=colour,
            marker=marker,
            label=label,
        )
    ax_ball.set(xlabel="ball start x (m; goal at 52.5)", ylabel="ball start y (m)", title="Ball start")
    ax_ball.invert_yaxis()  # rcssserver's +y points down the screen
    ax_offset.set(
        xlabel="agent x - ball x (m; > 0: agent nearer the goal)",
        ylabel="agent y - ball y (m)",
        title="Agent start relative to the ball",
    )
    ax_offset.invert_yaxis()
    ax_offset.legend(loc="upper left", fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main(argv: Sequence[str] | None = None) -> None:
    parser = episodes_parser(__doc__.splitlines()[0], default_episodes=1000)
    parser.add_argument("--out", type=Path, default=None, help="PNG to write (default: none)")
    parser.add_argument(
        "--discrete-choice",
        choices=DISCRETE_CHOICES,
        default=None,
        help="actor or critic (default: the model's)",
    )
    args = parser.parse_args(argv)

    model, env, env_id, _, path = load_for_evaluation(args.model, args.env or None)
    if args.discrete_choice is not None:
        model.policy.discrete_choice = args.discrete_choice
    try:
        records = run_episodes(model, env, args.episodes, args.seed, True, model_n_skills(model))
    finally:
        env.close()
    choice = model.policy.discrete_choice
    print(
        f"{path} on {env_id}: {args.episodes} greedy episodes, seed {args.seed}, {choice} picks the discrete action"
    )
    for name, n, rate, low, high, counts in table_rows(records):
        print(f"  {name:<34} {n:>5} episodes  goal rate {rate:.3f} [{low:.3f}, {high:.3f}]  {counts}")
    if args.out is not None:
        title = (
            f"{Path(str(path)).parent.name}/{Path(str(path)).name}: {args.episodes} episodes, seed {args.seed}, "
            f"{choice} picks"
        )
        plot(records, title, args.out)
        print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
