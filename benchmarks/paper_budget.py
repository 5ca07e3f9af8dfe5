"""The paper-budget runs of E1 and E2 (issue 35): their training curves from the runs' own logs.

The runs are rl-zoo3 runs of ``zoo_configs/e1_empty_goal.yml`` / ``e2_empty_goal_skills.yml`` (50,000 episodes,
``StopTrainingOnMaxEpisodes``), started and continued with ``python -m sb3_hfo.train ... --checkpoint-freq 10min``
and ``--resume RUN`` (benchmarks/README.md, "The paper's budget"). This script reads what such a run printed: SB3's
stdout table every ``log_interval`` episodes, whose ``rollout/success_rate`` is the goal rate of the last 100
training episodes (exploration on: the runs' epsilon-greedy and Gaussian noise) and ``rollout/episodes`` the
episode count. A resumed run repeats the rows logged after its checkpoint; the later row of an episode count wins
(the resumed run's, which continued the checkpoint exactly). It writes a table (every ``--every`` episodes) and, with
``--out``, a figure of the goal rate against episodes, one line per run.

    python benchmarks/paper_budget.py ~/runs/e1_paper/train.log ~/runs/e2_paper/train.log --labels E1 E2 \\
        --out docs/paper_budget.png

The final models are evaluated with ``python -m sb3_hfo.evaluate`` (1,000 greedy episodes, hfo2d and real HFO);
the figures are in benchmarks/README.md.
"""

from __future__ import annotations

import argparse
import re
from pathlib import Path

#: SB3's stdout table rows this script reads: ``|    episodes  | 1234 |`` and ``|    success_rate  | 0.87 |``, and
#: the section headers (``| rollout/  |  |``): the ``eval/`` section has a ``success_rate`` too (the periodic greedy
#: evaluation's, over 5 episodes), which is not the training curve
ROW = re.compile(r"^\|\s+(episodes|success_rate)\s+\|\s+([-0-9.e+]+)\s+\|")
SECTION = re.compile(r"^\|\s(\S+)/\s+\|")


def read_curve(log: Path) -> dict[int, float]:
    """``{episodes: success rate of the last 100}`` from one run's stdout log; the later row of an episode count
    wins. Each table has ``rollout/success_rate`` and then ``time/episodes`` (SB3 prints the sections in order and
    sorts the keys inside each), so a rate is paired with the next ``episodes`` row."""
    curve: dict[int, float] = {}
    rate: float | None = None
    section = ""
    for line in log.read_text(errors="replace").splitlines():
        header = SECTION.match(line)
        if header is not None:
            section = header.group(1)
            continue
        match = ROW.match(line)
        if match is None:
            continue
        key, value = match.groups()
        if key == "success_rate":
            rate = float(value) if section == "rollout" else rate
        elif rate is not None:
            curve[int(float(value))] = rate
            rate = None
    if not curve:
        raise SystemExit(f"error: {log} holds no SB3 table with rollout/episodes and rollout/success_rate")
    return dict(sorted(curve.items()))


def table(curves: dict[str, dict[int, float]], every: int) -> str:
    """A markdown table: for each window of ``every`` episodes, each run's mean logged rate in it (the rates are
    of the last 100 episodes, logged every few episodes, so the mean is the window's goal rate, smoothed)."""
    last = max(max(curve) for curve in curves.values())
    lines = ["| episodes | " + " | ".join(curves) + " |", "|---:|" + "---:|" * len(curves)]
    for mark in range(every, last + every, every):
        cells = []
        for curve in curves.values():
            rates = [rate for episodes, rate in curve.items() if mark - every < episodes <= mark]
            cells.append(f"{100 * sum(rates) / len(rates):.0f} %" if rates else "")
        lines.append(f"| {mark - every:,}-{mark:,} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("logs", nargs="+", type=Path, help="each run's stdout log (train.log)")
    parser.add_argument("--labels", nargs="+", default=None, help="one per log (default: the logs' folders)")
    parser.add_argument("--every", type=int, default=2500, help="episodes between the table's rows")
    parser.add_argument("--out", type=Path, default=None, help="a PNG of the curves")
    args = parser.parse_args(argv)
    labels = args.labels or [log.parent.name for log in args.logs]
    if len(labels) != len(args.logs):
        parser.error(f"{len(args.logs)} logs but {len(labels)} labels")
    if args.every < 1:
        parser.error(f"--every must be >= 1, got {args.every}")
    curves = {label: read_curve(log) for label, log in zip(labels, args.logs, strict=True)}
    print(table(curves, args.every))
    if args.out is not None:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        figure, axes = plt.subplots(figsize=(8, 4))
        for label, curve in curves.items():
            axes.plot(list(curve), [100 * rate for rate in curve.values()], label=label, linewidth=0.6)
        axes.set_xlabel("training episodes")
        axes.set_ylabel("goal rate of the last 100 training episodes (%)")
        axes.set_ylim(0, 100)
        axes.grid(alpha=0.3)
        axes.legend()
        figure.tight_layout()
        args.out.parent.mkdir(parents=True, exist_ok=True)
        figure.savefig(args.out, dpi=100)
        print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
