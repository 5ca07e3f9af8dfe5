"""HybridPPO experiments on the batched hfo2d (issue 33): E1 from scratch and E6 from reward alone.

A training run of :class:`sb3_hfo.hybrid_ppo.HybridPPO` on ``n_envs`` games of one hfo2d id stepped in one process
(:func:`sb3_hfo.vec_env.make_hfo_vec_env`), with what the experiments need and rl-zoo3 does not give:

* a wall-clock budget (``--minutes``) besides the step budget (``--steps``), and the wall clock and load average
  recorded with every row; ``--stop-at N`` ends a run at N steps while its learning-rate schedule still runs
  over ``--steps`` (a leg cut at the same step count as an earlier leg that ``--minutes`` cut, whatever the
  machine's load: ``--steps 4000000`` instead would decay the rate to 0 by 4M);
* periodic greedy evaluations against the *evaluation* env (``--eval-every`` steps, ``--eval-episodes``
  episodes; for E6 the full-strength goalie whatever the training curriculum says), written to ``curve.jsonl``
  with the end-status counts, and a checkpoint of each evaluated model, so curves show where a run stalls;
* an optional curriculum on the goalie's strength (``--curriculum START:END:FRACTION``: ``keeper_skill`` rises
  linearly from START to END over the first FRACTION of the steps, by
  :class:`sb3_hfo.callbacks.KeeperSkillCurriculumCallback`);
* or a curriculum paced by the agent (``--paced START:STEP:THRESHOLD:WINDOW``: ``keeper_skill`` rises by STEP
  whenever the training goal rate over WINDOW episodes at the current skill reaches THRESHOLD,
  :class:`sb3_hfo.callbacks.GoalRateKeeperCurriculumCallback`), and a start-distance curriculum
  (``--paced-start SHIFT:STEP:THRESHOLD:WINDOW``: the ball starts SHIFT m closer to the goal than HFO's starts,
  hfo2d's ``start_shift``, and moves back by STEP at the same kind of pace, once a ``--paced`` goalie is at full
  strength; :class:`sb3_hfo.callbacks.GoalRateStartShiftCallback`); the curricula's values go into every row;
* the final model (``final.zip``: the figures that count come from it, evaluated over 1,000 episodes with
  ``python -m sb3_hfo.evaluate RUN/final.zip --env ID --episodes 1000 --seed 0``).

``--init RUN/model_N.zip`` starts a run from an earlier run's policy weights (its optimizers and reward
normaliser start afresh): a run continued with other settings, e.g. a shorter curriculum; its wall clock adds to
the earlier run's. ``--reset-log-std V`` (with ``--init``) sets every parameter head's log standard deviation to V
after loading: the continued run explores the parameters again (research/e6_from_reward.md Part D, seed 1: its
kick-power deviation had shrunk to ~2 power units before it ever kicked hard near the goal).

How the model is made: from reward alone. No demonstrations, no scripted labels, no imitation term.

    python benchmarks/hybrid_ppo_runs.py e1 --seed 0 --out ~/runs/hppo/e1_s0
    python benchmarks/hybrid_ppo_runs.py e6 --seed 0 --out ~/runs/hppo/e6_s0 --minutes 110
    python benchmarks/hybrid_ppo_runs.py e1 --smoke --out /tmp/smoke   # seconds: what the test runs

Presets (``--hp JSON`` overrides any hyperparameter; ``--env-kwargs JSON`` the env's):

* ``e1``: HFO/EmptyGoal-v0, HFO's shaped reward, zoo_configs/hybrid_ppo_empty_goal.yml's recipe.
* ``e2_field_half`` / ``e2_learned``: E1's recipe with the paper's two skills (``policy_kwargs`` ``skills=2``,
  ``domain="hfo"``), routed by the field half (the paper's rule) or by a learned categorical over the skills.
* ``e6``: HFO/Keeper-v1 (agent2d's goalie), the shaped reward toward the goalie gap with lost shots refunded
  (``reward="shaped_gap_refund"``, hfo2d.reward; not HFO's own reward, documented there), and a curriculum from a
  goalie that never moves (``keeper_skill`` 0) to the full goalie over the first half of the steps.
* ``e6_carry``: ``e6``'s recipe with the carry reward (``reward="carry"``, hfo2d.reward: the ball's progress paid
  only as new records set with the ball within 2 m of the agent, 0.002 a cycle, 5 a goal) and the full goalie from
  HFO's own starts from the first step (no curriculum: a weak goalie pays long shots); research/e6_from_reward.md
  Part D.
* ``e6_carry_shot``: ``e6_carry`` with the reward ``"carry_shot"`` (the carry reward plus a record of the shot
  speed at the goal mouth, paid for kicks within 12 m of the goal centre); research/e6_from_reward.md Part E.
* ``e6_carry_sd``: ``e6_carry`` with state-dependent parameter deviations (``policy_kwargs``
  ``state_dependent_std=True``: a dribble's touches and a shot need not share one kick-power spread); Part E.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from collections import Counter
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import torch as th
from stable_baselines3.common.callbacks import BaseCallback, CallbackList
from stable_baselines3.common.vec_env import VecNormalize

from sb3_hfo.callbacks import (
    GoalRateKeeperCurriculumCallback,
    GoalRateStartShiftCallback,
    KeeperSkillCurriculumCallback,
)
from sb3_hfo.common.schedules import parse_schedule
from sb3_hfo.evaluation import goal_rate_summary
from sb3_hfo.hybrid_ppo import HybridPPO
from sb3_hfo.vec_env import make_hfo_vec_env

#: The experiments' presets: env id, env kwargs, hyperparameters, curriculum and step budget.
PRESETS: dict[str, dict[str, Any]] = {
    "e1": {
        "env_id": "HFO/EmptyGoal-v0",
        "env_kwargs": {},
        "steps": 1_600_000,
        "curriculum": None,
        "hp": {
            "n_envs": 16,
            "n_steps": 256,
            "batch_size": 512,
            "n_epochs": 10,
            "learning_rate": "lin_5e-4",
            "gamma": 0.99,
            "gae_lambda": 0.95,
            "ent_coef": 0.0,
            "norm_reward": True,
            "policy_kwargs": {"net_arch": [64, 64], "log_std_init": -0.5},
        },
    },
    "e6": {
        "env_id": "HFO/Keeper-v1",
        "env_kwargs": {"reward": "shaped_gap_refund"},
        "steps": 30_000_000,
        "curriculum": (0.0, 1.0, 0.5),
        "hp": {
            "n_envs": 16,
            "n_steps": 256,
            "batch_size": 1024,
            "n_epochs": 10,
            "learning_rate": "lin_5e-4",
            "gamma": 0.99,
            "gae_lambda": 0.95,
            "ent_coef": 0.001,
            "norm_reward": True,
            "policy_kwargs": {"net_arch": [128, 128], "log_std_init": -0.5},
        },
    },
}

# E6 with the carry reward (research/e6_from_reward.md Part D): the full goalie from the start, since carrying the
# ball, not a long shot, is what the reward pays.
PRESETS["e6_carry"] = json.loads(json.dumps(PRESETS["e6"]))  # a deep copy
PRESETS["e6_carry"]["env_kwargs"] = {"reward": "carry"}
PRESETS["e6_carry"]["curriculum"] = None
# E6 with the carry reward and its shot record (research/e6_from_reward.md Part E): ``e6_carry`` otherwise.
PRESETS["e6_carry_shot"] = json.loads(json.dumps(PRESETS["e6_carry"]))
PRESETS["e6_carry_shot"]["env_kwargs"] = {"reward": "carry_shot"}
# ... and with state-dependent parameter deviations (sb3_hfo.hybrid_ppo.policies.SkillHead), Part E.
PRESETS["e6_carry_sd"] = json.loads(json.dumps(PRESETS["e6_carry"]))
PRESETS["e6_carry_sd"]["hp"]["policy_kwargs"]["state_dependent_std"] = True

# E2 (issue 33, item 4: the learned router against the hand-coded one): E1's recipe with the paper's two skills (one
# actor head and one Adam each); ``field_half`` routes by the ball's field half (the paper's rule), ``learned`` adds
# a categorical over the skills that PPO learns as a first-level choice.
for _router in ("field_half", "learned"):
    _preset = json.loads(json.dumps(PRESETS["e1"]))  # a deep copy
    _preset["hp"]["policy_kwargs"].update(skills=2, router=_router, domain="hfo")
    PRESETS[f"e2_{_router}"] = _preset

#: Tiny settings for ``--smoke`` (CI runs the script for seconds).
SMOKE = {
    "steps": 2048,
    "eval_every": 1024,
    "eval_episodes": 4,
    "hp": {"n_envs": 4, "n_steps": 256, "batch_size": 256},
}


def load_average() -> float:
    """The 1-minute load average (other jobs on the machine slow a run down; every row records it)."""
    return os.getloadavg()[0]


def batched_episodes(
    act: Callable[[np.ndarray], np.ndarray],
    env_id: str,
    env_kwargs: dict[str, Any],
    episodes: int,
    seed: int,
) -> dict:
    """``episodes`` episodes on 16 (or fewer) batched games of ``env_id``, ``act`` mapping a batch of observations
    to env actions: goals, end statuses, Wilson interval. Every episode started is played to its end and counted."""
    n_games = min(16, episodes)
    env = make_hfo_vec_env(env_id, n_games, seed=seed, monitor=False, **env_kwargs)
    statuses: Counter[str] = Counter()
    started = n_games
    active = np.ones(n_games, dtype=bool)
    obs = env.reset()
    while active.any():
        obs, _, dones, infos = env.step(act(obs))
        for game in np.flatnonzero(dones):
            if not active[game]:
                continue
            statuses[infos[game]["status"]] += 1
            if started < episodes:
                started += 1  # the game's auto-reset episode counts
            else:
                active[game] = False
    env.close()
    return goal_rate_summary(statuses, episodes)


def greedy_evaluation(
    model: HybridPPO, env_id: str, env_kwargs: dict[str, Any], episodes: int, seed: int
) -> dict:
    """``episodes`` greedy episodes on 16 (or fewer) games of ``env_id``: goals, end statuses, Wilson interval."""
    return batched_episodes(
        lambda obs: model.predict(obs, deterministic=True)[0], env_id, env_kwargs, episodes, seed
    )


class RunRecorder(BaseCallback):
    """Stops the run at its wall-clock budget; every ``eval_every`` steps evaluates the greedy policy on the
    evaluation env, saves that model and appends a row (steps, seconds, steps/s, load, training goal rate, the
    evaluation) to ``curve.jsonl``."""

    def __init__(
        self,
        out: Path,
        minutes: float,
        eval_every: int,
        evaluate: Any,
        curricula: list[BaseCallback] | None = None,
        stop_at: int | None = None,
    ) -> None:
        super().__init__()
        self.curricula = (
            curricula or []
        )  # their training settings (keeper_skill, start_shift) go into every row
        self.out, self.budget_s, self.eval_every, self.evaluate = out, minutes * 60.0, eval_every, evaluate
        self.stop_at = stop_at  # a step cap that leaves the schedules over the step budget
        self.started = time.time()
        self.next_eval = eval_every
        self.train_seconds = 0.0  # wall clock without the periodic evaluations
        self._eval_seconds = 0.0

    def _on_step(self) -> bool:
        if self.stop_at is not None and self.num_timesteps >= self.stop_at:
            return False  # like the wall-clock cap: the unfinished rollout is not trained on
        return self.train_seconds_now() < self.budget_s

    def train_seconds_now(self) -> float:
        return time.time() - self.started - self._eval_seconds

    def _on_rollout_end(self) -> None:
        if self.num_timesteps < self.next_eval:
            return
        self.next_eval += self.eval_every
        self.row(final=False)

    def row(self, final: bool) -> dict[str, Any]:
        seconds = self.train_seconds_now()
        eval_started = time.time()
        evaluation = self.evaluate(self.model)
        self._eval_seconds += time.time() - eval_started
        buffer = self.model.ep_success_buffer
        row = {
            "steps": int(self.num_timesteps),
            "train_seconds": round(seconds, 1),
            "steps_per_s": round(self.num_timesteps / max(seconds, 1e-9), 1),
            "load1": round(load_average(), 2),
            "train_goal_rate": round(float(np.mean(buffer)), 3) if len(buffer) else None,
            **{
                getattr(curriculum, "logged_name", "keeper_skill"): getattr(
                    curriculum, "value", getattr(curriculum, "skill", None)
                )
                for curriculum in self.curricula
            },
            "eval": evaluation,
            "final": final,
        }
        name = "final.zip" if final else f"model_{self.num_timesteps}.zip"
        self.model.save(self.out / name)
        with open(self.out / "curve.jsonl", "a") as file:
            file.write(json.dumps(row) + "\n")
        for key in ("rate", "goals"):
            self.logger.record(f"eval/greedy_{key}", evaluation[key])
        print(json.dumps(row), flush=True)
        return row


def reset_log_std(model: HybridPPO, value: float) -> int:
    """Set every parameter head's state-independent log standard deviation (normalised scale) to ``value``; the
    number of heads changed. The means, the categoricals and the critic are untouched."""
    if not np.isfinite(value):
        raise ValueError(f"reset_log_std: value must be finite, got {value!r}")
    changed = 0
    with th.no_grad():
        for name, parameter in model.policy.named_parameters():
            if name.endswith("log_std"):
                parameter.fill_(value)
                changed += 1
    if changed == 0:
        raise ValueError("reset_log_std: the policy has no log_std parameter")
    return changed


def load_policy_weights(model: HybridPPO, path: Path) -> None:
    """Copy the policy weights of the model saved at ``path`` into ``model`` (same architecture). A policy with
    ``state_dependent_std`` may start from one without: its state-dependent layers keep their zero start, so it
    first acts exactly as the loaded policy. Any other mismatch is an error."""
    missing, unexpected = model.policy.load_state_dict(
        HybridPPO.load(path, device="cpu").policy.state_dict(), strict=False
    )
    missing = [key for key in missing if ".std_linear." not in key]
    if missing or unexpected:
        raise ValueError(
            f"--init {path}: not the same policy architecture (missing {missing}, unexpected {unexpected})"
        )


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("preset", choices=sorted(PRESETS))
    parser.add_argument("--out", type=Path, required=True, help="run folder (created; must not hold a curve)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--steps", type=int, default=None, help="step budget (default: the preset's)")
    parser.add_argument("--minutes", type=float, default=600.0, help="wall-clock budget of training")
    parser.add_argument(
        "--stop-at",
        type=int,
        default=None,
        help="end the run once it has taken this many steps; the learning-rate schedule still runs over the step "
        "budget (--steps or the preset's)",
    )
    parser.add_argument("--eval-every", type=int, default=1_000_000)
    parser.add_argument("--eval-episodes", type=int, default=100)
    parser.add_argument("--hp", default="{}", help="JSON: hyperparameters over the preset's")
    parser.add_argument("--env-kwargs", default="{}", help="JSON: env kwargs over the preset's")
    parser.add_argument("--curriculum", default=None, help="START:END:FRACTION of keeper_skill, or 'none'")
    parser.add_argument(
        "--paced",
        default=None,
        help="START:STEP:THRESHOLD:WINDOW: keeper_skill from START, raised by STEP whenever the training goal rate "
        "over WINDOW episodes at the current skill reaches THRESHOLD (replaces --curriculum)",
    )
    parser.add_argument(
        "--paced-start",
        default=None,
        help="SHIFT:STEP:THRESHOLD:WINDOW: a start-distance curriculum, the ball's start moved SHIFT m toward the "
        "goal (hfo2d's start_shift), lowered by STEP down to 0 whenever the training goal rate over WINDOW episodes "
        "at the current shift reaches THRESHOLD (with --paced: once the goalie is at full strength)",
    )
    parser.add_argument("--threads", type=int, default=1, help="torch threads")
    parser.add_argument(
        "--init",
        type=Path,
        default=None,
        help="start from this HybridPPO zip's policy weights (a run continued)",
    )
    parser.add_argument(
        "--reset-log-std",
        type=float,
        default=None,
        help="with --init: set the loaded policy's parameter log standard deviations to this value (explore again)",
    )
    parser.add_argument("--smoke", action="store_true", help="a few seconds: tiny budget and evaluation")
    args = parser.parse_args(argv)

    preset = json.loads(json.dumps(PRESETS[args.preset]))  # a deep copy
    hp = {**preset["hp"], **json.loads(args.hp)}
    env_kwargs = {**preset["env_kwargs"], **json.loads(args.env_kwargs)}
    steps, eval_every, eval_episodes = args.steps or preset["steps"], args.eval_every, args.eval_episodes
    if args.smoke:
        hp.update(SMOKE["hp"])
        steps, eval_every, eval_episodes = SMOKE["steps"], SMOKE["eval_every"], SMOKE["eval_episodes"]
    curriculum = preset["curriculum"]
    if args.curriculum is not None:
        curriculum = (
            None if args.curriculum == "none" else tuple(float(v) for v in args.curriculum.split(":"))
        )
    paced = None
    if args.paced is not None:
        try:
            start, step, threshold, window = args.paced.split(":")
            paced = (float(start), float(step), float(threshold), int(window))
        except ValueError:
            parser.error(
                f"--paced takes START:STEP:THRESHOLD:WINDOW (e.g. 0:0.1:0.7:200), got {args.paced!r}"
            )
        curriculum = None
    paced_start = None
    if args.paced_start is not None:
        try:
            shift, step, threshold, window = args.paced_start.split(":")
            paced_start = (float(shift), float(step), float(threshold), int(window))
        except ValueError:
            parser.error(
                f"--paced-start takes SHIFT:STEP:THRESHOLD:WINDOW (e.g. 30:5:0.7:200), got {args.paced_start!r}"
            )
    if args.stop_at is not None and not 0 < args.stop_at <= steps:
        parser.error(f"--stop-at must lie in (0, {steps}] (the step budget), got {args.stop_at}")
    if args.reset_log_std is not None and args.init is None:
        parser.error("--reset-log-std resets a loaded policy: it needs --init")
    if (args.out / "curve.jsonl").exists():
        parser.error(f"{args.out} already holds a run (curve.jsonl); choose another --out")
    args.out.mkdir(parents=True, exist_ok=True)
    th.set_num_threads(args.threads)

    record = {
        "preset": args.preset,
        "env_id": preset["env_id"],
        "env_kwargs": env_kwargs,
        "hp": hp,
        "seed": args.seed,
        "steps": steps,
        "minutes": args.minutes,
        "stop_at": args.stop_at,
        "curriculum": curriculum,
        "paced_curriculum": paced,
        "paced_start_curriculum": paced_start,
        "torch_threads": args.threads,
        "command": " ".join([Path(sys.argv[0]).name, *(argv if argv is not None else sys.argv[1:])]),
        "load1_at_start": load_average(),
        "method": "reinforcement learning from reward (no demonstrations, no imitation)",
        "init": None if args.init is None else str(args.init),
        "reset_log_std": args.reset_log_std,
    }
    (args.out / "run.json").write_text(json.dumps(record, indent=1))

    n_envs = hp.pop("n_envs")
    norm_reward = hp.pop("norm_reward", False)
    hp["learning_rate"] = parse_schedule(hp["learning_rate"])
    train_kwargs = dict(env_kwargs)
    if curriculum is not None or paced is not None:
        train_kwargs["keeper_skill"] = curriculum[0] if curriculum is not None else paced[0]
    if paced_start is not None:
        train_kwargs["start_shift"] = paced_start[0]
    env = make_hfo_vec_env(preset["env_id"], n_envs, seed=args.seed, **train_kwargs)
    if norm_reward:  # rewards scaled by a running std of the discounted return; HFO's features are in [-1, 1]
        env = VecNormalize(env, norm_obs=False, norm_reward=True, gamma=hp.get("gamma", 0.99))
    model = HybridPPO("MlpPolicy", env, seed=args.seed, tensorboard_log=str(args.out / "tb"), **hp)
    if (
        args.init is not None
    ):  # the weights of an earlier run of the same architecture (optimizers start afresh)
        load_policy_weights(model, args.init)
        if args.reset_log_std is not None:
            reset_log_std(model, args.reset_log_std)

    def evaluate(policy_model: HybridPPO) -> dict:
        # the evaluation env has the id's own goalie strength (the full goalie for Keeper-v1)
        return greedy_evaluation(
            policy_model, preset["env_id"], env_kwargs, eval_episodes, seed=10_000 + args.seed
        )

    callbacks: list[BaseCallback] = []
    if curriculum is not None:
        start, end, fraction = curriculum
        callbacks.append(KeeperSkillCurriculumCallback(start, end, ramp_fraction=fraction))
    if paced is not None:
        start, step, threshold, window = paced
        callbacks.append(
            GoalRateKeeperCurriculumCallback(
                start, 1.0, skill_step=step, threshold=threshold, window=window, verbose=1
            )
        )
    if paced_start is not None:
        shift, step, threshold, window = paced_start
        # with a paced goalie too, the starts move away from the goal once the goalie is at full strength
        keeper = next((c for c in callbacks if isinstance(c, GoalRateKeeperCurriculumCallback)), None)
        callbacks.append(
            GoalRateStartShiftCallback(
                shift, 0.0, step, threshold=threshold, window=window, verbose=1, wait_for=keeper
            )
        )
    recorder = RunRecorder(
        args.out, args.minutes, eval_every, evaluate, curricula=list(callbacks), stop_at=args.stop_at
    )
    callbacks.insert(0, recorder)
    model.learn(steps, callback=CallbackList(callbacks), progress_bar=False)
    recorder.row(final=True)
    env.close()


if __name__ == "__main__":
    main()
