"""Evaluate a trained SkillDDPG agent on an HFO task: scoring rate with a 95% CI and behaviour statistics.

``python -m sb3_hfo.evaluate MODEL --env HFO/EmptyGoal-v0 --episodes 100 --seed 0 --json out.json``

MODEL is a committed model's name (``e1``, ...; see :mod:`sb3_hfo.models`), a SkillDDPG ``.zip`` or an rl-zoo3 run
folder; what is measured and how MODEL is found are described in :mod:`sb3_hfo.evaluation`, which does the work.
This module is its command line: the options, the table and the ``--json`` file. ``--acting SPEC`` sets the
policy's acting strategies for the run (default: the model's own).
"""

from __future__ import annotations

import argparse
import ast
import json
import sys
from collections.abc import Sequence
from dataclasses import asdict
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.table import Table

from sb3_hfo.cli.errors import OneLineArgumentParser, non_negative_int
from sb3_hfo.evaluation import OUT_OF_BOUNDS_STATUS, EvaluationError, EvaluationResult, evaluate
from sb3_hfo.skill_ddpg.acting import parse_acting


def _format(value: float | None, digits: int = 3) -> str:
    return "-" if value is None else f"{value:.{digits}f}"


def print_table(result: EvaluationResult) -> None:
    """Print the result as a rich table."""
    low, high = result.scoring_rate_ci95
    table = Table(
        title=f"{result.env_id}: {result.episodes} episodes (seed {result.seed})",
        caption=f"model: {result.model}",
    )
    table.add_column("metric")
    table.add_column("value", justify="right")
    table.add_row("scoring rate [95% CI]", f"{result.scoring_rate:.3f} [{low:.3f}, {high:.3f}]")
    table.add_row("goals", str(result.goals))
    table.add_row("mean steps to goal", _format(result.mean_steps_to_goal, 1))
    table.add_row("mean episode steps", _format(result.mean_episode_steps, 1))
    table.add_row("mean episode reward", _format(result.mean_episode_reward))
    for status, count in result.status_counts.items():
        table.add_row(f"episodes ending {status}", str(count))
        if status == OUT_OF_BOUNDS_STATUS:
            for line, exits in result.out_of_bounds_exits.items():
                table.add_row(f"  ball out over the {line.replace('_', ' ')}", str(exits))
    table.add_row("kicks per goal", _format(result.kicks_per_goal, 2))
    table.add_row("kicks per episode", _format(result.kicks_per_episode, 2))
    table.add_row("mean kick power", _format(result.mean_kick_power, 1))
    table.add_row(
        f"dribble fraction (speed > {result.dribble_min_speed} m/cycle)", _format(result.dribble_fraction)
    )
    table.add_row("mean shot distance (m, last kick)", _format(result.mean_shot_distance, 1))
    for label, counts in result.shots_by_distance.items():
        if counts["episodes"]:
            table.add_row(f"  goals / last kicks from {label}", f"{counts['goals']} / {counts['episodes']}")
    if result.skill_fractions is not None:
        for k, fraction in enumerate(result.skill_fractions):
            table.add_row(f"steps with skill {k}", _format(fraction))
    table.add_row("deterministic", str(result.deterministic))
    table.add_row("acting strategies", result.acting or "none (the actor's greedy action)")
    Console().print(table)


def _episode_count(text: str) -> int:
    """argparse type of ``--episodes``: an integer >= 1."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be an integer, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {value}")
    return value


def episodes_parser(description: str, default_episodes: int) -> argparse.ArgumentParser:
    """A parser with the arguments the benchmark scripts share: model, ``--env``, ``--episodes`` (>= 1), ``--seed``."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("model", help="SkillDDPG .zip or rl-zoo3 run folder")
    parser.add_argument("--env", default=None, help="environment id (default: the run's own)")
    parser.add_argument("--episodes", type=_episode_count, default=default_episodes)
    parser.add_argument("--seed", type=int, default=0, help="seed of the first env reset")
    return parser


def build_parser() -> argparse.ArgumentParser:
    parser = OneLineArgumentParser(
        prog="python -m sb3_hfo.evaluate",
        description="Evaluate a SkillDDPG model on an HFO task (scoring rate with Wilson 95% CI, kicks, dribbling).",
    )
    parser.add_argument(
        "model",
        help="committed model name (e.g. e1), model .zip (suffix optional) or rl-zoo3 run folder "
        "(logs/skill_ddpg/<env>_<n>)",
    )
    parser.add_argument(
        "--env", default=None, help="env id, e.g. HFO/EmptyGoal-v0 (default: the run folder's)"
    )
    parser.add_argument("--episodes", type=int, default=100, help="number of episodes (default 100)")
    parser.add_argument(
        "--seed", type=non_negative_int, default=0, help="seed of the first env reset, >= 0 (default 0)"
    )
    # Greedy by default, like SB3's evaluate_policy and rl-zoo3's enjoy (which has --stochastic to opt out).
    parser.add_argument(
        "--stochastic",
        dest="deterministic",
        action="store_false",
        help="predict(deterministic=False) (SkillDDPG's actor is greedy either way; for other algorithms)",
    )
    parser.add_argument(
        "--deterministic",
        dest="deterministic",
        action="store_true",
        help="predict(deterministic=True), the default (kept so that older command lines still run)",
    )
    parser.add_argument("--json", default=None, help="write the result as JSON to this file")
    add_acting_argument(parser)
    parser.add_argument(
        "--env-kwargs",
        nargs="+",
        default=[],
        metavar="KEY:VALUE",
        help="env constructor overrides, values as Python literals (e.g. noise:False keeper_skill:0.5)",
    )
    return parser


def _acting_spec(text: str) -> str:
    """argparse type of ``--acting``: the text form of acting strategies, checked here so that a bad token is a
    usage error naming it."""
    try:
        parse_acting(text)
    except ValueError as error:
        raise argparse.ArgumentTypeError(str(error)) from None
    return text


def add_acting_argument(parser: argparse.ArgumentParser) -> None:
    """Add ``--acting SPEC``, the policy's acting strategies for the run."""
    parser.add_argument(
        "--acting",
        type=_acting_spec,
        default=None,
        metavar="SPEC",
        help="acting strategies, comma-separated: critic (the critic picks DASH / TURN / KICK), kick_mask (no KICK "
        "while the ball is out of reach), mirror or mirror:M (play the better, by the critic, of the state and its "
        "mirror image; with M > 0 keep the side through an episode unless the other is better by more than M; "
        "inf: never switch); '' or actor: none (default: the model's own)",
    )


def parse_env_kwargs(items: Sequence[str]) -> dict[str, Any]:
    """``["noise:False", "reward:'sparse'"]`` -> ``{"noise": False, "reward": "sparse"}`` (bare words stay strings)."""
    kwargs: dict[str, Any] = {}
    for item in items:
        key, sep, raw = item.partition(":")
        if not sep or not key:
            raise EvaluationError(f"--env-kwargs expects KEY:VALUE, got {item!r}")
        try:
            kwargs[key] = ast.literal_eval(raw)
        except (ValueError, SyntaxError):
            kwargs[key] = raw
    return kwargs


def main(argv: Sequence[str] | None = None) -> int:
    """CLI entry point; returns the exit code (0 ok, 2 user error)."""
    args = build_parser().parse_args(argv)
    if args.episodes < 1:
        print("error: --episodes must be at least 1", file=sys.stderr)
        return 2
    if args.json and Path(args.json).is_dir():
        print(f"error: --json {args.json} is a folder; give a file name", file=sys.stderr)
        return 2
    try:
        result = evaluate(
            args.model,
            env_id=args.env,
            episodes=args.episodes,
            seed=args.seed,
            deterministic=args.deterministic,
            env_kwargs=parse_env_kwargs(args.env_kwargs),
            acting=args.acting,
        )
    except EvaluationError as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    print_table(result)
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(asdict(result), indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
