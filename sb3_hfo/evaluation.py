"""Evaluate a trained SkillDDPG agent on an HFO task: scoring rate with a 95% CI and behaviour statistics.

The library behind ``python -m sb3_hfo.evaluate`` (:mod:`sb3_hfo.cli.evaluate`): :func:`evaluate` loads a model
and plays it, :func:`run_episodes` plays any model on any env, :func:`summarize` aggregates the episodes and
:func:`wilson_interval` gives the confidence interval. It imports neither argparse-based tools nor rl-zoo3.

MODEL is a committed model's name (:mod:`sb3_hfo.models`: ``e1``, ...; its env id and env kwargs come from
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

import math
from collections import Counter
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import torch
import yaml

import hfo2d  # noqa: F401  (registers the HFO/* Gymnasium ids)
from sb3_hfo.errors import UserError
from sb3_hfo.models import (
    check_model_zip,
    load_model,
    looks_like_name,
    manifest_entry,
    model_file,
    unknown_name_message,
)
from sb3_hfo.skill_ddpg import SkillDDPG
from sb3_hfo.skill_ddpg.acting import ActingSpec, format_acting

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


def goal_rate_summary(statuses: Mapping[str, int], episodes: int) -> dict[str, Any]:
    """Goals, goal rate and its Wilson 95 % interval, and the end-status counts of ``episodes`` episodes."""
    goals = int(statuses.get(GOAL_STATUS, 0))
    low, high = wilson_interval(goals, episodes)
    return {
        "episodes": episodes,
        "goals": goals,
        "rate": goals / episodes,
        "ci95": [low, high],
        "status": dict(statuses),
    }


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
    """Find the ``.zip`` for MODEL: a committed model's name (:mod:`sb3_hfo.models`, e.g. ``e1``), a file, a file
    without its suffix, an rl-zoo3 run folder, or a folder of runs (the newest).

    Raises:
        EvaluationError: nothing to load there.
    """
    path = Path(model)
    if not path.exists() and not path.with_name(path.name + ".zip").exists() and looks_like_name(model):
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


def hfo_env_ids() -> list[str]:
    """Registered Gymnasium ids of the HFO tasks (:mod:`hfo2d` registers them on import)."""
    return sorted(env_id for env_id in gym.registry if env_id.startswith("HFO/"))


def check_env_id(env_id: str) -> None:
    """Raise EvaluationError listing the registered HFO ids when ``env_id`` is not registered."""
    if env_id not in gym.registry:
        raise EvaluationError(f"unknown env id {env_id!r}; registered HFO ids: {', '.join(hfo_env_ids())}")


# --------------------------------------------------------------------------------------------------------------
# Skill bookkeeping (models with n_skills > 1)


def model_n_skills(model: Any) -> int:
    """Number of skills (actor heads) of a SkillDDPG model; 1 for anything else."""
    policy = getattr(model, "policy", None)
    return int(getattr(policy, "n_skills", 1) or 1)


def skill_index(model: Any, obs: Any) -> int:
    """Index of the skill that acts on ``obs`` (shape (obs_dim,)), as the policy's ``skill_router`` decides."""
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

    # Small networks, one observation at a time: extra torch threads only contend for the cores.
    torch.set_num_threads(1)
    # A 1-transition replay buffer: evaluation never trains.
    try:
        model = load_model(resolved.path, SkillDDPG, device="cpu", buffer_size=1)
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
