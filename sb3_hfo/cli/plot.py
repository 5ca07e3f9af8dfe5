"""Training curves in the style of the seed paper's Figures 3 and 4, from TensorBoard event files.

``python -m sb3_hfo.plot runs/tb/HFO-EmptyGoal-v0/SkillDDPG_1 runs/tb/HFO-EmptyGoal-v0/SkillDDPG_2
--labels "no skills" "skills" --smooth 10 --out figure3.png``

Four panels against training episodes: average critic loss (``train/critic_loss``), maximum Q-value
(``train/max_q``), accumulated reward per episode (``rollout/ep_rew_mean``, SB3's mean over the last 100
episodes) and goal rate (``rollout/success_rate``, SB3's, from HFO's ``info["is_success"]``; older runs'
``rollout/goal_rate``), with the greedy evaluations ``eval/success_rate`` dashed when rl-zoo3's ``--eval-freq``
wrote them). Each LOGDIR is searched recursively; every folder holding ``events.out.tfevents.*`` files is one run
(one curve).

The x axis is episodes: ``rollout/episodes`` (or ``time/episodes``) when logged; otherwise episodes are estimated
from the step counter as sum(delta steps / ep_len_mean), and failing that the axis is environment steps.

With ``--summary`` a table is printed too: for each run, the last greedy evaluation (``eval/success_rate``, written
by rl-zoo3's evaluation callback, ``--eval-freq``/``--eval-episodes``), the best one, and the environment step and
wall-clock (seconds since the run's first logged event) at which it first reached each ``--targets`` rate.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from sb3_hfo.cli.errors import OneLineArgumentParser, UserError, check_installed, one_line

#: The training goal rate (with exploration; SB3's, from HFO's ``info["is_success"]``); its panel also shows the
#: greedy evaluations (EVAL_SUCCESS_TAG).
GOAL_RATE_TAG = "rollout/success_rate"

#: Tags older runs logged the training goal rate under (SkillDDPG and HFOEpisodeStatsCallback before they left it
#: to SB3): read as GOAL_RATE_TAG when a run has no GOAL_RATE_TAG.
LEGACY_GOAL_RATE_TAGS: tuple[str, ...] = ("rollout/goal_rate",)

#: (tag, panel title) of the four panels, in the paper's order plus the goal rate.
PANELS: tuple[tuple[str, str], ...] = (
    ("train/critic_loss", "Average loss"),
    ("train/max_q", "Max Q-value"),
    ("rollout/ep_rew_mean", "Accumulated reward"),
    (GOAL_RATE_TAG, "Goal rate (dashed: greedy evaluations)"),
)

#: The greedy-evaluation tag (rl-zoo3's EvalCallback; HFOEnv sets ``is_success``): ``--summary`` reads it and the
#: goal-rate panel draws it dashed.
EVAL_SUCCESS_TAG = "eval/success_rate"

#: Tags that count finished episodes, by preference.
EPISODE_TAGS: tuple[str, ...] = ("rollout/episodes", "time/episodes")


class PlotError(Exception):
    """A user error (no event files, label count mismatch): reported as one line, exit code 2."""


@dataclass
class Run:
    """Scalars of one training run: tag -> (steps, values), both 1-D arrays sorted by step."""

    label: str
    scalars: dict[str, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)
    #: tag -> wall-clock seconds since the run's first event, aligned with ``scalars[tag]``'s steps.
    wall_clock: dict[str, np.ndarray] = field(default_factory=dict)

    def episodes_at(self, steps: np.ndarray) -> tuple[np.ndarray, str]:
        """Map environment steps onto finished episodes; returns (x values, x-axis name)."""
        for tag in EPISODE_TAGS:
            if tag in self.scalars:
                episode_steps, episode_counts = self.scalars[tag]
                return np.interp(steps, episode_steps, episode_counts), "episodes"
        if "rollout/ep_len_mean" in self.scalars:
            length_steps, lengths = self.scalars["rollout/ep_len_mean"]
            # Episodes finished between two log points ~= steps between them / mean episode length.
            increments = np.diff(length_steps, prepend=0.0) / np.maximum(lengths, 1.0)
            return np.interp(steps, length_steps, np.cumsum(increments)), "episodes (estimated)"
        return steps.astype(float), "environment steps"


def find_run_dirs(logdir: Path) -> list[Path]:
    """Folders under (or equal to) ``logdir`` that hold TensorBoard event files, sorted."""
    if logdir.is_file():
        return [logdir.parent] if logdir.name.startswith("events.out.tfevents") else []
    return sorted({event_file.parent for event_file in logdir.rglob("events.out.tfevents.*")})


def load_run(run_dir: Path, label: str) -> Run:
    """Read every scalar of the event files in ``run_dir`` (not recursive; all points kept)."""
    from tensorboard.backend.event_processing.event_accumulator import EventAccumulator

    merged: dict[str, dict[int, tuple[float, float]]] = {}
    for event_file in sorted(run_dir.glob("events.out.tfevents.*")):
        accumulator = EventAccumulator(str(event_file), size_guidance={"scalars": 0})
        accumulator.Reload()
        for tag in accumulator.Tags().get("scalars", []):
            # A resumed run writes a second file; later files win on equal steps.
            merged.setdefault(tag, {}).update(
                {event.step: (event.value, event.wall_time) for event in accumulator.Scalars(tag)}
            )
    run = Run(label)
    start = min((wall for points in merged.values() for _, wall in points.values()), default=0.0)
    for tag, points in merged.items():
        steps = np.array(sorted(points), dtype=float)
        run.scalars[tag] = (steps, np.array([points[int(s)][0] for s in steps], dtype=float))
        run.wall_clock[tag] = np.array([points[int(s)][1] - start for s in steps], dtype=float)
    for legacy in LEGACY_GOAL_RATE_TAGS:
        if GOAL_RATE_TAG not in run.scalars and legacy in run.scalars:
            run.scalars[GOAL_RATE_TAG] = run.scalars[legacy]
            run.wall_clock[GOAL_RATE_TAG] = run.wall_clock[legacy]
    return run


def time_to_targets(run: Run, targets: Sequence[float]) -> dict[str, Any]:
    """Last and best ``eval/success_rate`` of ``run`` and, per target rate, the first (step, wall-clock seconds)
    at which an evaluation reached it (``None`` if none did, or if the run has no evaluations)."""
    summary: dict[str, Any] = {"label": run.label, "last": None, "best": None, "last_step": None}
    if EVAL_SUCCESS_TAG not in run.scalars:
        summary.update({f"first_{target:g}": None for target in targets})
        return summary
    steps, rates = run.scalars[EVAL_SUCCESS_TAG]
    seconds = run.wall_clock[EVAL_SUCCESS_TAG]
    summary.update(last=float(rates[-1]), best=float(rates.max()), last_step=int(steps[-1]))
    for target in targets:
        # TensorBoard stores float32: 0.9 comes back as 0.89999998
        reached = np.flatnonzero(rates >= target - 1e-6)
        first = int(reached[0]) if reached.size else None
        summary[f"first_{target:g}"] = None if first is None else (int(steps[first]), float(seconds[first]))
    return summary


def print_summary(runs: Sequence[Run], targets: Sequence[float]) -> None:
    """One table row per run: last / best greedy success rate and the time to each target."""
    header = ["run", "last eval", "best eval", "at step", *(f"first >= {target:.0%}" for target in targets)]
    rows = []
    for run in runs:
        summary = time_to_targets(run, targets)
        cells = [run.label]
        for key in ("last", "best"):
            cells.append("-" if summary[key] is None else f"{summary[key]:.1%}")
        cells.append("-" if summary["last_step"] is None else str(summary["last_step"]))
        for target in targets:
            hit = summary[f"first_{target:g}"]
            cells.append("not reached" if hit is None else f"step {hit[0]}, {hit[1] / 60:.1f} min")
        rows.append(cells)
    widths = [max(len(row[i]) for row in [header, *rows]) for i in range(len(header))]
    for row in [header, *rows]:
        print("  ".join(cell.ljust(width) for cell, width in zip(row, widths, strict=True)))


def moving_average(values: np.ndarray, window: int) -> np.ndarray:
    """Trailing moving average over ``window`` points (shorter at the start); ``window <= 1`` is a no-op."""
    if window <= 1 or values.size == 0:
        return values
    cumulative = np.cumsum(np.insert(values, 0, 0.0))
    counts = np.minimum(np.arange(1, values.size + 1), window)
    starts = np.arange(1, values.size + 1) - counts
    return (cumulative[1:] - cumulative[starts]) / counts


def collect_runs(logdirs: Sequence[str], labels: Sequence[str] | None) -> list[Run]:
    """Load all runs under ``logdirs``; ``labels`` (one per LOGDIR) name them, numbered if a LOGDIR has several."""
    if labels and len(labels) != len(logdirs):
        raise PlotError(f"got {len(labels)} labels for {len(logdirs)} log folders")
    runs: list[Run] = []
    for index, logdir in enumerate(logdirs):
        path = Path(logdir)
        if not path.exists():
            raise PlotError(f"log folder not found: {logdir}")
        run_dirs = find_run_dirs(path)
        if not run_dirs:
            raise PlotError(f"no TensorBoard event files under {logdir}")
        for number, run_dir in enumerate(run_dirs, start=1):
            if labels:
                label = labels[index] if len(run_dirs) == 1 else f"{labels[index]} ({number})"
            else:
                label = str(run_dir)
            runs.append(load_run(run_dir, label))
    return runs


def plot_runs(runs: Sequence[Run], out: Path, smooth: int = 1, title: str | None = None) -> None:
    """Draw the four panels for ``runs`` (overlaid, labelled) into a PNG at ``out``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(2, 2, figsize=(11, 7.5))
    x_names: set[str] = set()
    for axis, (tag, panel_title) in zip(axes.flat, PANELS, strict=True):
        drawn = False
        for run in runs:
            if tag not in run.scalars:
                continue
            steps, values = run.scalars[tag]
            x, x_name = run.episodes_at(steps)
            x_names.add(x_name)
            # Markers keep short runs (a single log point) visible.
            marker = "o" if len(x) < 20 else None
            (line,) = axis.plot(
                x, moving_average(values, smooth), label=run.label, linewidth=1.2, marker=marker, markersize=3
            )
            drawn = True
            if tag == GOAL_RATE_TAG and EVAL_SUCCESS_TAG in run.scalars:
                # The training goal rate includes exploration; the greedy evaluations are what a user gets.
                eval_steps, eval_values = run.scalars[EVAL_SUCCESS_TAG]
                eval_x, _ = run.episodes_at(eval_steps)
                axis.plot(
                    eval_x,
                    eval_values,
                    label=f"{run.label} (greedy eval)",
                    color=line.get_color(),
                    linestyle="--",
                    marker="o",
                    markersize=3,
                    linewidth=1.0,
                )
        axis.set_title(panel_title)
        axis.grid(alpha=0.3)
        if not drawn:
            axis.text(0.5, 0.5, f"{tag}\nnot logged", ha="center", va="center", transform=axis.transAxes)
    x_label = " / ".join(sorted(x_names)) or "episodes"
    for axis in axes[1]:
        axis.set_xlabel(x_label)
    if title:
        figure.suptitle(title)
    # One legend below the panels: inside a panel it covers the curves once several runs are overlaid.
    labelled: dict[str, Any] = {}
    for axis in axes.flat:
        for handle, label in zip(*axis.get_legend_handles_labels(), strict=True):
            labelled.setdefault(label, handle)
    # Each run's column holds its training curve above its greedy evaluations (legends fill column by column).
    order = [name for run in runs for name in (run.label, f"{run.label} (greedy eval)") if name in labelled]
    legend_rows = 0
    if order:
        columns = min(len(runs) if len(order) > len(runs) else len(order), 4)
        legend_rows = -(-len(order) // columns)
        handles = [labelled[name] for name in order]
        figure.legend(handles, order, loc="lower center", ncol=columns, fontsize="small")
    figure.tight_layout(rect=(0.0, 0.03 * legend_rows + 0.01 * bool(legend_rows), 1.0, 1.0))
    out.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(out, dpi=120)
    plt.close(figure)


def check_out(out: Path) -> str | None:
    """What is wrong with ``out`` as the figure's file (a folder, a format matplotlib cannot write), or None."""
    from matplotlib.backend_bases import FigureCanvasBase

    if out.is_dir():
        return "is a folder; give a file name such as figure.png"
    formats = FigureCanvasBase.get_supported_filetypes()
    suffix = out.suffix.lstrip(".").lower()
    if suffix not in formats:
        return f"unknown image format {out.suffix or '(none)'!r}; use one of .{', .'.join(sorted(formats))}"
    return None


def build_parser() -> argparse.ArgumentParser:
    parser = OneLineArgumentParser(
        prog="python -m sb3_hfo.plot",
        description="Plot loss, max Q, accumulated reward and goal rate against episodes (paper Figures 3/4).",
    )
    parser.add_argument(
        "logdirs", nargs="+", metavar="LOGDIR", help="TensorBoard log folder(s), searched recursively"
    )
    parser.add_argument(
        "--out", default="training_curves.png", help="output PNG (default training_curves.png)"
    )
    parser.add_argument("--labels", nargs="+", default=None, help="one legend label per LOGDIR")
    parser.add_argument(
        "--smooth", type=int, default=1, help="moving-average window in log points (default 1: none)"
    )
    parser.add_argument("--title", default=None, help="figure title")
    parser.add_argument(
        "--summary",
        action="store_true",
        help="also print each run's greedy evaluation rate (eval/success_rate) and time to --targets",
    )
    parser.add_argument(
        "--targets",
        type=float,
        nargs="+",
        default=[0.95, 0.98],
        help="success rates for --summary (default 0.95 0.98)",
    )
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """CLI entry point; returns the exit code (0 ok, 2 user error)."""
    args = build_parser().parse_args(argv)
    try:
        check_installed("zoo", ("matplotlib",), "python -m sb3_hfo.plot")
    except UserError as error:
        print(f"error: {one_line(error)}", file=sys.stderr)
        return 2
    try:
        runs = collect_runs(args.logdirs, args.labels)
    except PlotError as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    if any(not 0.0 < target <= 1.0 for target in args.targets):
        print(f"error: --targets must lie in (0, 1], got {args.targets}", file=sys.stderr)
        return 2
    out_problem = check_out(Path(args.out))
    if out_problem:
        print(f"error: --out {args.out}: {out_problem}", file=sys.stderr)
        return 2
    plot_runs(runs, Path(args.out), smooth=args.smooth, title=args.title)
    print(f"wrote {args.out} ({len(runs)} run(s))")
    if args.summary:
        print_summary(runs, args.targets)
    return 0


if __name__ == "__main__":
    sys.exit(main())
