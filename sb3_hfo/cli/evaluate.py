"""Evaluate a trained SkillDDPG agent on an HFO task: scoring rate with a 95% CI and behaviour statistics.

``python -m sb3_hfo.evaluate MODEL --env HFO/EmptyGoal-v0 --episodes 100 --seed 0 --json out.json``

MODEL is a committed model's name (``models/manifest.json``: ``e1``, ...; its env id and env kwargs come from
the manifest), a SkillDDPG ``.zip`` (full or stripped; the suffix may be left out) or an rl-zoo3 run folder such as
``logs/skill_ddpg/HFO-EmptyGoal-v0_1`` (its final model ``HFO-EmptyGoal-v0.zip`` is used, else
``best_model.zip``). With a run folder, ``--env`` and the training ``env_kwargs`` default to the run's own, less
those the env no longer takes (:data:`REMOVED_ENV_KWARGS`).

Reported (per the paper's evaluation, Hausknecht & Stone's table: "scoring %" and "avg steps to goal"):

* ``scoring_rate`` with its Wilson score 95% interval (``scoring_rate_ci95``);
* ``mean_steps_to_goal``: mean episode length in env steps (100 ms cycles) over scoring episodes only;
* ``status_counts``: episodes per final ``info["status"]`` (GOAL, OUT_OF_BOUNDS, CAPTURED_BY_DEFENSE, OUT_OF_TIME);
* ``kicks_per_goal``: mean number of *executed* kicks (``info["action"] == "KICK"`` and
  ``info["action_success"]``) in scoring episodes; ``mean_kick_power``: mean ``info["kick_power"]`` over all
  executed kicks (rcssserver power units, [0, 100]);
* ``dribble_fraction``: fraction of all steps in which the ball is kickable (``info["kickable"]``) while the
  player moves faster than :data:`DRIBBLE_MIN_SPEED` (speed from ``info["player"]`` vx, vy);
* ``mean_shot_distance``: mean distance (m) from the ball to the goal centre (52.5, 0) just before each
  episode's last executed kick (episodes with at least one kick), and ``shots_by_distance``: those episodes
  binned by that distance (edges :data:`SHOT_DISTANCE_EDGES`) with their goals - whether misses come from long
  shots, where ball_rand's drift spreads the ball most;
* ``skill_fractions``: fraction of steps each skill acted, for models with more than one skill;
* ``out_of_bounds_exits``: OUT_OF_BOUNDS episodes by the line the ball left the HFO half over (from its final
  ``info["ball"]`` position): ``goal_line`` (x > 52.5: a shot wide of the posts), ``side_line`` (|y| > 34) or
  ``halfway_line`` (x < 0);
* ``acting``: the policy's acting strategies in their text form (:mod:`sb3_hfo.skill_ddpg.acting`, e.g.
  ``"critic,kick_mask,mirror:0.1"``; ``""``: the actor's greedy action as it is), set with
  ``--acting SPEC`` (default: the model's own).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections import Counter
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from sb3_hfo.cli.errors import OneLineArgumentParser, UserError, check_model_zip, non_negative_int

if TYPE_CHECKING:
    from sb3_hfo.skill_ddpg.acting import ActingSpec

#: Player speed (m/cycle) above which a step with the ball kickable counts as dribbling. The fastest a player
#: runs is player_speed_max = 1.05 m/cycle (rcssserver 15.2.2 default, via hfo_reference §4); 0.2 m/cycle (2 m/s)
#: excludes standing at the ball and slow turning while keeping any purposeful run with the ball.
DRIBBLE_MIN_SPEED = 0.2

#: Bin edges (m from the goal centre) of ``shots_by_distance``. A 2.8 m/cycle shot drifts sideways under ball_rand
#: 0.05 by ~0.7 m (std) over 20 m, ~1.3 m over 30 m and ~2.1 m over 40 m (research/probes/shot_spread.py, a Monte Carlo of the server's
#: ball noise), against a 7.01 m goal half-width and a 1.085 m keeper capture radius.
SHOT_DISTANCE_EDGES: tuple[float, ...] = (20.0, 30.0, 40.0)

#: Two-sided 95% standard normal quantile, for the Wilson score interval.
Z_95 = 1.959963984540054

GOAL_STATUS = "GOAL"
OUT_OF_BOUNDS_STATUS = "OUT_OF_BOUNDS"
#: The HFO half the ball must stay in (hfo_reference §1, ``HFORef::inHFOArea``): x in [0, 52.5], |y| <= 34 (m).
PITCH_HALF_LENGTH = 52.5
PITCH_HALF_WIDTH = 34.0
GOAL_CENTRE = (PITCH_HALF_LENGTH, 0.0)
EXIT_LINES: tuple[str, ...] = ("goal_line", "side_line", "halfway_line")
#: Env kwargs that older training runs may name but the env no longer takes (``random_start_fraction``, a
#: training aid no recommended config used): left out when a run folder's env is rebuilt.
REMOVED_ENV_KWARGS: tuple[str, ...] = ("random_start_fraction",)


def exit_line(ball_x: float, ball_y: float) -> str | None:
    """The line of the HFO half that a ball at (x, y) m lies beyond (checked in this order), or None inside."""
    if ball_x > PITCH_HALF_LENGTH:
        return "goal_line"
    if abs(ball_y) > PITCH_HALF_WIDTH:
        return "side_line"
    if ball_x < 0.0:
        return "halfway_line"
    return None


class EvaluationError(UserError):
    """A user error (bad path, damaged model, unknown env id, bad env kwargs): reported as one line, exit code 2."""


def wilson_interval(successes: int, trials: int, z: float = Z_95) -> tuple[float, float]:
    """Wilson score confidence interval for a binomial proportion.

    :param successes: number of successes (goals).
    :param trials: number of trials (episodes); 0 gives the uninformative (0, 1).
    :param z: normal quantile (1.96 for 95%).
    :return: (lower, upper), both in [0, 1].
    """
    if trials <= 0:
        return 0.0, 1.0
    p = successes / trials
    z2 = z * z
    denominator = 1.0 + z2 / trials
    centre = (p + z2 / (2 * trials)) / denominator
    half_width = z * math.sqrt(p * (1 - p) / trials + z2 / (4 * trials * trials)) / denominator
    # The bounds are exactly 0 (no successes) and 1 (all successes); rounding must not move them.
    low = 0.0 if successes == 0 else max(0.0, centre - half_width)
    high = 1.0 if successes == trials else min(1.0, centre + half_width)
    return low, high


@dataclass
class EpisodeRecord:
    """Statistics of one evaluation episode (steps are env steps = 100 ms server cycles)."""

    status: str
    steps: int
    reward: float
    kicks: int
    kick_powers: list[float]
    dribble_steps: int
    skill_steps: list[int]
    exit: str | None = None  # OUT_OF_BOUNDS episodes: exit_line() of the ball's final position
    start_ball: tuple[float, float] | None = None  # (x, y) m at reset, from info["ball"]
    start_player: tuple[float, float] | None = None  # (x, y) m at reset, from info["player"]
    shot_distance: float | None = None  # m from the goal centre to the ball before the last executed kick
    end_ball: tuple[float, float] | None = None  # (x, y) m after the last step, from info["ball"]
    end_keeper: tuple[float, float] | None = (
        None  # (x, y) m after the last step, from info["keeper"] (keeper tasks)
    )


@dataclass
class EvaluationResult:
    """Aggregate evaluation statistics (see the module docstring for definitions)."""

    model: str
    env_id: str
    episodes: int
    seed: int
    deterministic: bool
    goals: int
    scoring_rate: float
    scoring_rate_ci95: tuple[float, float]
    mean_steps_to_goal: float | None
    mean_episode_steps: float
    mean_episode_reward: float
    status_counts: dict[str, int]
    kicks_per_goal: float | None
    kicks_per_episode: float
    mean_kick_power: float | None
    dribble_fraction: float
    dribble_min_speed: float
    n_skills: int
    skill_fractions: list[float] | None
    out_of_bounds_exits: dict[str, int] = field(default_factory=dict)
    env_kwargs: dict[str, Any] = field(default_factory=dict)
    acting: str = ""
    mean_shot_distance: float | None = None
    shots_by_distance: dict[str, dict[str, int]] = field(default_factory=dict)


def shot_distance_labels() -> list[str]:
    """Names of the ``shots_by_distance`` bins, nearest first: "0-20 m", ..., ">= 40 m"."""
    lowers = (0.0, *SHOT_DISTANCE_EDGES[:-1])
    labels = [f"{low:g}-{high:g} m" for low, high in zip(lowers, SHOT_DISTANCE_EDGES, strict=True)]
    return [*labels, f">= {SHOT_DISTANCE_EDGES[-1]:g} m"]


def shot_distance_label(distance: float) -> str:
    """The ``shots_by_distance`` bin of a shot taken ``distance`` m from the goal centre."""
    below = sum(distance >= edge for edge in SHOT_DISTANCE_EDGES)
    return shot_distance_labels()[below]


def _shots_by_distance(records: Sequence[EpisodeRecord]) -> dict[str, dict[str, int]]:
    bins = {label: {"episodes": 0, "goals": 0} for label in shot_distance_labels()}
    for record in records:
        if record.shot_distance is not None:
            counts = bins[shot_distance_label(record.shot_distance)]
            counts["episodes"] += 1
            counts["goals"] += record.status == GOAL_STATUS
    return bins


def summarize(
    records: Sequence[EpisodeRecord],
    *,
    model: str,
    env_id: str,
    seed: int,
    deterministic: bool,
    n_skills: int,
    env_kwargs: dict[str, Any] | None = None,
    acting: str = "",
) -> EvaluationResult:
    """Aggregate per-episode records into an :class:`EvaluationResult`."""
    n = len(records)
    scoring = [r for r in records if r.status == GOAL_STATUS]
    goals = len(scoring)
    total_steps = sum(r.steps for r in records)
    kick_powers = [power for r in records for power in r.kick_powers]
    skill_totals = [sum(r.skill_steps[k] for r in records) for k in range(n_skills)]
    shot_distances = [r.shot_distance for r in records if r.shot_distance is not None]
    return EvaluationResult(
        model=model,
        env_id=env_id,
        episodes=n,
        seed=seed,
        deterministic=deterministic,
        goals=goals,
        scoring_rate=goals / n if n else 0.0,
        scoring_rate_ci95=wilson_interval(goals, n),
        mean_steps_to_goal=sum(r.steps for r in scoring) / goals if goals else None,
        mean_episode_steps=total_steps / n if n else 0.0,
        mean_episode_reward=sum(r.reward for r in records) / n if n else 0.0,
        status_counts=dict(sorted(Counter(r.status for r in records).items())),
        kicks_per_goal=sum(r.kicks for r in scoring) / goals if goals else None,
        kicks_per_episode=sum(r.kicks for r in records) / n if n else 0.0,
        mean_kick_power=sum(kick_powers) / len(kick_powers) if kick_powers else None,
        dribble_fraction=sum(r.dribble_steps for r in records) / total_steps if total_steps else 0.0,
        dribble_min_speed=DRIBBLE_MIN_SPEED,
        n_skills=n_skills,
        skill_fractions=[s / total_steps for s in skill_totals] if n_skills > 1 and total_steps else None,
        out_of_bounds_exits={
            line: sum(r.status == OUT_OF_BOUNDS_STATUS and r.exit == line for r in records)
            for line in EXIT_LINES
        },
        env_kwargs=dict(env_kwargs or {}),
        acting=acting,
        mean_shot_distance=sum(shot_distances) / len(shot_distances) if shot_distances else None,
        shots_by_distance=_shots_by_distance(records),
    )


# --------------------------------------------------------------------------------------------------------------
# Model and run-folder resolution


@dataclass
class ResolvedModel:
    """Where a model lives and what the training run knew about its environment."""

    path: Path
    env_id: str | None
    env_kwargs: dict[str, Any]


def _read_run_settings(run_folder: Path) -> tuple[str | None, dict[str, Any]]:
    """Env id and env_kwargs saved by rl-zoo3 in ``<run>/<env name>/{args,config}.yml`` (if present)."""
    import yaml

    env_id: str | None = None
    env_kwargs: dict[str, Any] = {}
    for args_file in sorted(run_folder.glob("*/args.yml")):
        with open(args_file) as f:
            saved_args = yaml.load(f, Loader=yaml.UnsafeLoader) or {}
        env_id = saved_args.get("env") or env_id
        config_file = args_file.with_name("config.yml")
        if config_file.is_file():
            with open(config_file) as f:
                config = yaml.load(f, Loader=yaml.UnsafeLoader) or {}
            env_kwargs.update(dict(config.get("env_kwargs") or {}))
        # Command-line --env-kwargs overrode the config's at training time.
        env_kwargs.update(dict(saved_args.get("env_kwargs") or {}))
        break
    return env_id, env_kwargs


def resolve_model(model: str) -> ResolvedModel:
    """Find the ``.zip`` for MODEL: a committed model's name (``models/manifest.json``, e.g. ``e1``), a file, a file
    without its suffix, an rl-zoo3 run folder, or a folder of runs (the newest).

    Raises:
        EvaluationError: nothing to load there.
    """
    path = Path(model)
    if not path.exists() and not path.with_name(path.name + ".zip").exists():
        from sb3_hfo.models import looks_like_name, manifest_entry, model_file, unknown_name_message

        if looks_like_name(model):
            entry = manifest_entry(model)
            if entry is None:
                raise EvaluationError(unknown_name_message(model))
            return ResolvedModel(model_file(entry), entry["env_id"], dict(entry["env_kwargs"]))
    if path.is_dir() and not any(path.glob("*.zip")):
        # A folder of rl-zoo3 runs (``logs/skill_ddpg``): take the newest run, ``<env name>_<N>`` with the largest N.
        runs = [
            p
            for p in path.iterdir()
            if p.is_dir() and p.name.rpartition("_")[2].isdigit() and any(p.glob("*.zip"))
        ]
        if runs:
            path = max(runs, key=lambda p: int(p.name.rpartition("_")[2]))
    if path.is_dir():
        finals = sorted(
            p for p in path.glob("*.zip") if p.name != "best_model.zip" and not p.name.startswith("rl_model_")
        )
        candidates = finals or sorted(path.glob("best_model.zip"))
        if not candidates:
            raise EvaluationError(f"no model .zip found in folder {model}")
        env_id, env_kwargs = _read_run_settings(path)
        return ResolvedModel(candidates[0], env_id, env_kwargs)
    if not path.is_file() and path.with_name(path.name + ".zip").is_file():
        path = path.with_name(path.name + ".zip")
    if not path.is_file():
        raise EvaluationError(f"model file not found: {model}")
    env_id, env_kwargs = _read_run_settings(path.parent)
    return ResolvedModel(path, env_id, env_kwargs)


def check_env_id(env_id: str) -> None:
    """Raise EvaluationError listing the registered HFO ids when ``env_id`` is not registered."""
    import gymnasium as gym

    from sb3_hfo.cli.zoo import hfo_env_ids

    known = hfo_env_ids()
    if env_id not in gym.registry:
        raise EvaluationError(f"unknown env id {env_id!r}; registered HFO ids: {', '.join(known)}")


# --------------------------------------------------------------------------------------------------------------
# Skill bookkeeping (models with n_skills > 1)


def model_n_skills(model: Any) -> int:
    """Number of skills (actor heads) of a SkillDDPG model; 1 for anything else."""
    policy = getattr(model, "policy", None)
    return int(getattr(policy, "n_skills", 1) or 1)


def skill_index(model: Any, obs: Any) -> int:
    """Index of the skill that acts on ``obs`` (shape (obs_dim,)), as the policy's ``skill_router`` decides."""
    import numpy as np

    router = model.policy.skill_router
    batch = np.asarray(obs, dtype=np.float32)[None, :]
    # SkillRouter subclasses offer numpy_route; any other router is a callable (batch, obs_dim) -> (batch,).
    skills = router.numpy_route(batch) if hasattr(router, "numpy_route") else router(batch)
    if hasattr(skills, "detach"):
        skills = skills.detach().cpu().numpy()
    return int(np.asarray(skills).reshape(-1)[0])


# --------------------------------------------------------------------------------------------------------------
# Evaluation loop


def _position(state: Sequence[float] | None) -> tuple[float, float] | None:
    """(x, y) of an ``info["ball"]`` / ``info["player"]`` / ``info["keeper"]`` tuple, or None when there is none."""
    return None if state is None else (float(state[0]), float(state[1]))


def run_episodes(
    model: Any, env: Any, episodes: int, seed: int, deterministic: bool, n_skills: int
) -> list[EpisodeRecord]:
    """Play ``episodes`` episodes of ``env`` (a Gymnasium env, not vectorised) with ``model.predict``.

    The first reset uses ``seed``; later resets continue the env's random stream, so a (model, seed) pair always
    gives the same episodes (up to torch nondeterminism in stochastic prediction).
    """
    import numpy as np

    records: list[EpisodeRecord] = []
    obs, info = env.reset(seed=seed)
    # predict's recurrent state (HFOPolicy's mirror margin keeps a side in it), reset at each episode's first step
    state: Any = None
    for _ in range(episodes):
        start_ball, start_player = _position(info.get("ball")), _position(info.get("player"))
        steps = kicks = dribble_steps = 0
        reward_sum = 0.0
        kick_powers: list[float] = []
        shot_distance: float | None = None
        skill_steps = [0] * n_skills
        status = "IN_GAME"
        done = False
        episode_start = np.ones(1, dtype=bool)
        while not done:
            if n_skills > 1:
                skill_steps[skill_index(model, obs)] += 1
            action, state = model.predict(
                obs, state=state, episode_start=episode_start, deterministic=deterministic
            )
            episode_start = np.zeros(1, dtype=bool)
            ball_before = info.get("ball")
            obs, reward, terminated, truncated, info = env.step(action)
            steps += 1
            reward_sum += float(reward)
            status = str(info.get("status", status))
            if info.get("action") == "KICK" and info.get("action_success"):
                kicks += 1
                kick_powers.append(float(info.get("kick_power", 0.0)))
                if ball_before is not None:
                    shot_distance = math.dist(GOAL_CENTRE, (ball_before[0], ball_before[1]))
            player = info.get("player")
            if info.get("kickable") and player is not None:
                speed = float(np.hypot(player[2], player[3]))
                if speed > DRIBBLE_MIN_SPEED:
                    dribble_steps += 1
            done = bool(terminated or truncated)
        ball = info.get("ball")
        exit = exit_line(ball[0], ball[1]) if status == OUT_OF_BOUNDS_STATUS and ball is not None else None
        records.append(
            EpisodeRecord(
                status,
                steps,
                reward_sum,
                kicks,
                kick_powers,
                dribble_steps,
                skill_steps,
                exit,
                start_ball,
                start_player,
                shot_distance,
                _position(ball),
                _position(info.get("keeper")),
            )
        )
        obs, info = env.reset()
    return records


def load_for_evaluation(
    model_path: str, env_id: str | None = None, env_kwargs: dict[str, Any] | None = None
) -> tuple[Any, Any, str, dict[str, Any], Path]:
    """Load a SkillDDPG model (one torch thread, CPU) and make the env to evaluate it on.

    The env id and ``env_kwargs`` default to the run folder's own, less :data:`REMOVED_ENV_KWARGS`.

    :return: ``(model, env, env_id, env_kwargs used, model path)``; the caller closes the env.
    :raises EvaluationError: no model there, no or unknown env id, or observations of another shape.
    """
    resolved = resolve_model(model_path)
    try:
        check_model_zip(resolved.path)
    except UserError as error:
        raise EvaluationError(str(error)) from None
    env_id = env_id or resolved.env_id
    if env_id is None:
        raise EvaluationError("--env is required (the model is not inside an rl-zoo3 run folder)")
    check_env_id(env_id)
    run_kwargs = {k: v for k, v in resolved.env_kwargs.items() if k not in REMOVED_ENV_KWARGS}
    kwargs = {**run_kwargs, **(env_kwargs or {})}
    kwargs.pop("render_mode", None)

    import gymnasium as gym
    import torch

    from sb3_hfo.cli.zoo import skill_ddpg_class
    from sb3_hfo.models import load_model

    # Small networks, one observation at a time: extra torch threads only contend for the cores.
    torch.set_num_threads(1)
    # A 1-transition replay buffer: evaluation never trains.
    try:
        model = load_model(resolved.path, skill_ddpg_class(), device="cpu", buffer_size=1)
    except ValueError as error:  # SB3: data that is not a model's
        raise EvaluationError(f"cannot load {resolved.path}: {error}") from None
    try:
        env = gym.make(env_id, **kwargs)
    except FileNotFoundError as error:  # e.g. HFO/Real*: no HFO build in hfo_dir / $HFO_DIR (hfo2d.real)
        raise EvaluationError(str(error)) from error
    except (TypeError, ValueError) as error:  # HFOEnv names the bad kwarg
        raise EvaluationError(f"cannot make {env_id} with env kwargs {kwargs}: {error}") from None
    if env.observation_space.shape != model.observation_space.shape:
        env.close()
        raise EvaluationError(
            f"model expects observations of shape {model.observation_space.shape} but {env_id} gives "
            f"{env.observation_space.shape}: was it trained on another task?"
        )
    return model, env, env_id, kwargs, resolved.path


def evaluate(
    model_path: str,
    env_id: str | None = None,
    episodes: int = 100,
    seed: int = 0,
    deterministic: bool = True,
    env_kwargs: dict[str, Any] | None = None,
    acting: ActingSpec | None = None,
) -> EvaluationResult:
    """Load a SkillDDPG model and evaluate it; see the module docstring. Raises EvaluationError on user errors.

    :param acting: the policy's acting strategies for this run (``HFOPolicy.acting``: strategy objects or their
        text form, e.g. ``"critic,kick_mask,mirror:0.1"``; ``""``: none); ``None`` keeps the model's own.
    """
    from sb3_hfo.skill_ddpg.acting import format_acting

    model, env, env_id, kwargs, path = load_for_evaluation(model_path, env_id, env_kwargs)
    try:
        if acting is not None:
            model.policy.acting = acting
    except ValueError as error:
        env.close()
        raise EvaluationError(str(error)) from error
    n_skills = model_n_skills(model)
    try:
        records = run_episodes(model, env, episodes, seed, deterministic, n_skills)
    finally:
        env.close()
    return summarize(
        records,
        model=str(path),
        env_id=env_id,
        seed=seed,
        deterministic=deterministic,
        n_skills=n_skills,
        env_kwargs=kwargs,
        acting=format_acting(getattr(model.policy, "acting", ())),  # () for algorithms without strategies
    )


def _format(value: float | None, digits: int = 3) -> str:
    return "-" if value is None else f"{value:.{digits}f}"


def print_table(result: EvaluationResult) -> None:
    """Print the result as a rich table."""
    from rich.console import Console
    from rich.table import Table

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
    from sb3_hfo.skill_ddpg.acting import parse_acting

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
    import ast

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
