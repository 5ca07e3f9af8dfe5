"""RL from the clone (issue 33): HybridPPO on HFO/Keeper-v1 started from the committed ``e6_imitation`` clone, pulled toward it.

``e6_imitation`` (named ``e6`` until this script's model took that name) is a SkillDDPG skills actor (two heads
routed by ``field_half``) that DAgger taught to play like the scripted striker ``hfo2d.strikers.soft_dribble`` (an
imitation, not RL); below it is called e6. This run:

1. **Distils** e6's actor into a :class:`sb3_hfo.hybrid_ppo.HybridPPO` policy of the same shape (trunk
   ``[256, 128, 64]`` with LeakyReLU, two heads routed by ``field_half``): the student's trunk and heads start as
   copies of e6's (e6's preferences, times ``--logit-scale``, become the discrete logits; its pre-``tanh``
   parameters the parameter means), then :func:`sb3_hfo.hybrid_ppo.distill.distill` fits them to e6's greedy
   actions (its kick mask included) on states of e6's own greedy games, then of the student's (DAgger rounds,
   ``--dagger-rounds``). The distilled policy's greedy score over ``--distill-eval-episodes`` games is recorded in
   ``distill.json``; the policy is saved as ``distilled.zip``.
2. **PPO** on ``--n-envs`` batched games (:func:`sb3_hfo.vec_env.make_hfo_vec_env`) with the reward
   ``shaped_gap_refund`` (hfo2d.reward, documented there; not HFO's own), a critic warm-up (value loss only for the
   first ``--critic-warmup`` steps) and a pull ``reference_coef(t) * KL(distilled(.|s) || pi(.|s))`` toward the
   frozen distilled policy whose coefficient falls linearly from ``--pull`` to 0 over the first
   ``--pull-fraction`` of the steps (:class:`sb3_hfo.common.schedules.DecayToZero`). Options for the recipe
   variants of benchmarks/README.md (all off by default): ``--reward sparse`` (1 per goal) instead of
   ``shaped_gap_refund``; ``--log-std-final`` (the parameters' log std moved linearly from ``--log-std`` to it,
   not learned: :class:`sb3_hfo.hybrid_ppo.noise.LogStdSchedule`); ``--lr-schedule linear`` (the learning rate
   falling linearly to 0).
With ``--router learned`` (issue 33 item 4: the learned router against ``field_half``) the student has
``skills=2, router="learned"``: its trunk and heads start as the same copies of e6's, and distillation also fits
its router (a linear layer on the actor trunk) to the skill ``field_half`` picks in the same states
(cross-entropy, weight ``--router-weight``), so both arms start from the same behaviour and differ only in whether PPO may change the routing.
Its pull is toward the distilled policy routed by ``field_half`` (the distilled trunk and heads without the
router): the KL over the joint (skill, action), ``-log rho(field_half(s)) + KL`` of the head field_half picks
(:meth:`sb3_hfo.hybrid_ppo.HybridPPO.reference_kl`), so once the pull has decayed the router is free. The router
reads the actor trunk's last layer, where e6's copied trunk does not hold the field half linearly (a linear probe
on a distilled field_half student's latent agrees with field_half on 77 % of states), so the trunk must learn it:
the learned arm distils longer and faster (``--distill-epochs 40 --distill-lr 3e-4``, benchmarks/README.md).

3. Records like ``hybrid_ppo_runs.py``: ``curve.jsonl`` with greedy evaluations against the full goalie every
   ``--eval-every`` steps, ``run.json``, ``final.zip`` (``distill.json`` holds the distilled policy's score).

Method: reinforcement learning from reward, started from the imitation clone (the pull decays to zero).

    python benchmarks/rl_from_clone.py --seed 0 --out ~/runs/fromclone/s0 --steps 4000000 --minutes 30
    # the recipe of e6_from_clone_shot (>= 93 % in real HFO on three seeds of three; benchmarks/README.md)
    python benchmarks/rl_from_clone.py --seed 0 --out ~/runs/fromclone5/A_s0 --steps 8000000 --minutes 50 \
        --pull-fraction 0.25 --eval-every 500000 --critic-warmup 200000 --distill-eval-episodes 0 \
        --hp '{"learning_rate": 2e-4}' --log-std -2.5 --lr-schedule linear --reward carry_shot
    python benchmarks/rl_from_clone.py --smoke --out /tmp/smoke   # seconds: what the test runs

Figures that count come from ``final.zip``:
``python -m sb3_hfo.evaluate RUN/final.zip --env HFO/Keeper-v1 --episodes 1000 --seed 0`` (and ``--env
HFO/RealKeeper-v0`` under tools/real_hfo/loopback.sh).
"""

from __future__ import annotations

import argparse
import copy
import json
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
import torch as th
from stable_baselines3.common.vec_env import VecNormalize
from torch import nn

sys.path.insert(0, str(Path(__file__).resolve().parent))  # the sibling script's recorder and evaluation

from hybrid_ppo_runs import RunRecorder, greedy_evaluation, load_average  # noqa: E402

from sb3_hfo.common.routers import make_router  # noqa: E402
from sb3_hfo.common.schedules import DecayToZero, LinearToZero  # noqa: E402
from sb3_hfo.hybrid_ppo import HybridPPO  # noqa: E402
from sb3_hfo.hybrid_ppo.distill import distill  # noqa: E402
from sb3_hfo.hybrid_ppo.noise import LogStdSchedule  # noqa: E402
from sb3_hfo.models import load_model  # noqa: E402
from sb3_hfo.vec_env import make_hfo_vec_env  # noqa: E402

ENV_ID = "HFO/Keeper-v1"
REWARD = "shaped_gap_refund"
#: the training rewards offered (hfo2d.reward): the default, or HFO's sparse goal reward (1 per goal), whose
#: discounted return is the goal probability (times the discount of the time to the goal) that the evaluation counts,
#: or the carry-and-shoot reward that E6 from reward alone learns with (research/e6_from_reward.md Part E)
REWARDS = (REWARD, "sparse", "carry_shot")
METHOD = "reinforcement learning from reward, started from the imitation clone"

#: HybridPPO's settings (a fine-tuning recipe: small steps, clipped at 0.1, stopped early on a large KL).
HP: dict[str, Any] = {
    "n_steps": 256,
    "batch_size": 1024,
    "n_epochs": 10,
    "learning_rate": 1e-4,
    "gamma": 0.99,
    "gae_lambda": 0.95,
    "clip_range": 0.1,
    "ent_coef": 0.0,
    "target_kl": 0.02,
}
#: e6's actor: the student copies it (zoo_configs/keeper_v1_skills_cloned_striker.yml).
ACTOR_ARCH = [256, 128, 64]
#: the student's routers: e6's hand-coded one, or one PPO learns (started as a copy of it by distillation)
ROUTERS = ("field_half", "learned")
#: PPO's learning rate over the run: as given, or falling linearly to 0 at the last step (rl-zoo3's ``lin_``)
LR_SCHEDULES = ("constant", "linear")


def student_model(env: Any, args: argparse.Namespace, hp: dict[str, Any]) -> HybridPPO:
    policy_kwargs = {
        "net_arch": {"pi": ACTOR_ARCH, "vf": [256, 128]},
        "activation_fn": nn.LeakyReLU,
        "skills": 2,
        "router": args.router,
        "domain": "hfo",
        "log_std_init": args.log_std,
        "squash_mean": True,  # e6's tanh output: its parameters copy exactly
    }
    if args.lr_schedule == "linear":
        hp = {**hp, "learning_rate": LinearToZero(hp["learning_rate"])}
    return HybridPPO(
        "MlpPolicy",
        env,
        seed=args.seed,
        policy_kwargs=policy_kwargs,
        tensorboard_log=str(args.out / "tb"),
        reference_coef=DecayToZero(args.pull, args.pull_fraction) if args.pull > 0 else 0.0,
        critic_warmup_steps=args.critic_warmup,
        **hp,
    )


def copy_teacher_weights(teacher: Any, model: HybridPPO, logit_scale: float) -> None:
    """The student's actor trunk and heads as e6's: same linear layers, e6's preferences (whose largest is the
    greedy choice) times ``logit_scale`` as logits, its parameters (``tanh``, as the student's squashed means) as
    the means. The student then plays e6's greedy actions exactly, except where e6's kick mask replaces a KICK
    out of reach (distillation teaches that)."""
    teacher_linears = [m for m in teacher.policy.actor.trunk if isinstance(m, nn.Linear)]
    student_linears = [m for m in model.policy.actor_trunk if isinstance(m, nn.Linear)]
    if [m.weight.shape for m in teacher_linears] != [m.weight.shape for m in student_linears]:
        raise ValueError("the teacher's actor trunk differs from the student's; cannot copy it")
    n_discrete = model.policy.adapter.n_discrete
    with th.no_grad():
        for source, target in zip(teacher_linears, student_linears, strict=True):
            target.weight.copy_(source.weight)
            target.bias.copy_(source.bias)
        for source, head in zip(teacher.policy.actor.heads, model.policy.heads, strict=True):
            scale = th.ones(source.weight.shape[0], 1)
            scale[:n_discrete] = logit_scale
            head.linear.weight.copy_(source.weight * scale)
            head.linear.bias.copy_(source.bias * scale.squeeze(1))


def play(policy_predict: Any, episodes: int, seed: int, n_games: int) -> tuple[np.ndarray, dict[str, int]]:
    """Observations of ``episodes`` greedy games of ``policy_predict`` on Keeper-v1 and their end statuses."""
    env = make_hfo_vec_env(ENV_ID, n_games, seed=seed, monitor=False)
    observations, statuses, finished = [], {}, 0
    obs = env.reset()
    while finished < episodes:
        observations.append(obs.copy())
        obs, _, dones, infos = env.step(policy_predict(obs))
        for game in np.flatnonzero(dones):
            statuses[infos[game]["status"]] = statuses.get(infos[game]["status"], 0) + 1
            finished += 1
    env.close()
    return np.concatenate(observations), statuses


def distil_clone(teacher: Any, model: HybridPPO, args: argparse.Namespace) -> dict[str, Any]:
    """Step 1 of the module docstring; returns what ``distill.json`` records."""
    adapter = model.policy.adapter

    def teacher_predict(obs: np.ndarray) -> np.ndarray:
        return teacher.predict(obs, deterministic=True)[0]

    def student_predict(obs: np.ndarray) -> np.ndarray:
        return model.predict(obs, deterministic=True)[0]

    def labels(obs: np.ndarray) -> np.ndarray:  # e6's greedy action (kick mask included) as [k, parameters]
        return adapter.from_env(teacher_predict(obs))

    # a learned router's labels: the skill e6's own router (field_half) picks in each state
    field_half = make_router("field_half", 2, "hfo") if model.policy.learned_router else None

    started = time.time()
    copy_teacher_weights(teacher, model, args.logit_scale)
    observations, teacher_statuses = play(
        teacher_predict, args.dagger_episodes, 20_000 + args.seed, args.n_envs
    )
    record: dict[str, Any] = {"teacher_statuses": teacher_statuses, "rounds": []}
    for round_index in range(args.dagger_rounds + 1):
        if round_index > 0:  # DAgger: the student's own states, labelled by the teacher
            seed = 20_000 + args.seed + 1_000 * round_index
            student_states, student_statuses = play(student_predict, args.dagger_episodes, seed, args.n_envs)
            observations = np.concatenate([observations, student_states])
            record["rounds"][-1]["student_statuses_after"] = student_statuses
        internal = labels(observations)
        history = distill(
            model.policy,
            observations,
            internal[:, 0].astype(np.int64),
            internal[:, 1:],
            epochs=args.distill_epochs,
            batch_size=512,
            learning_rate=args.distill_lr,
            parameter_weight=args.parameter_weight,
            seed=args.seed + round_index,
            skills=None if field_half is None else field_half.numpy_route(observations),
            router_weight=args.router_weight,
        )
        record["rounds"].append({"states": len(observations), "last_epoch": history[-1]})
        print(json.dumps({"distill_round": round_index, **record["rounds"][-1]}), flush=True)
    record["seconds"] = round(time.time() - started, 1)
    if args.distill_eval_episodes:
        record["greedy_eval"] = greedy_evaluation(model, ENV_ID, {}, args.distill_eval_episodes, seed=0)
    record["greedy_eval_seed"] = 0
    return record


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, required=True, help="run folder (created; must not hold a curve)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument(
        "--teacher", default="e6_imitation", help="the clone: a manifest name or a SkillDDPG zip"
    )
    parser.add_argument("--steps", type=int, default=4_000_000, help="PPO's step budget")
    parser.add_argument("--minutes", type=float, default=30.0, help="wall-clock budget of PPO's training")
    parser.add_argument("--n-envs", type=int, default=16)
    parser.add_argument("--eval-every", type=int, default=500_000)
    parser.add_argument("--eval-episodes", type=int, default=100)
    parser.add_argument("--pull", type=float, default=1.0, help="initial weight of the KL pull (0: none)")
    parser.add_argument("--pull-fraction", type=float, default=0.5, help="share of the steps it decays over")
    parser.add_argument("--critic-warmup", type=int, default=300_000, help="steps of value-only updates")
    parser.add_argument("--log-std", type=float, default=-3.5, help="the parameters' initial log std")
    parser.add_argument(
        "--log-std-final",
        type=float,
        default=None,
        help="if given, the parameters' log std is not learned but moves linearly from --log-std to this at the "
        "last step (sb3_hfo.hybrid_ppo.noise.LogStdSchedule; the pull reference's alike)",
    )
    parser.add_argument(
        "--lr-schedule",
        choices=LR_SCHEDULES,
        default="constant",
        help="PPO's learning rate: the --hp value throughout, or falling linearly from it to 0",
    )
    parser.add_argument("--logit-scale", type=float, default=10.0)
    parser.add_argument("--dagger-rounds", type=int, default=1)
    parser.add_argument("--dagger-episodes", type=int, default=400)
    parser.add_argument("--distill-epochs", type=int, default=10)
    parser.add_argument("--distill-lr", type=float, default=1e-4)
    parser.add_argument("--parameter-weight", type=float, default=100.0, help="distillation's parameter term")
    parser.add_argument("--distill-eval-episodes", type=int, default=1000)
    parser.add_argument(
        "--router",
        choices=ROUTERS,
        default="field_half",
        help="the student's skill router (module docstring)",
    )
    parser.add_argument(
        "--router-weight", type=float, default=3.0, help="distillation's router term (--router learned)"
    )
    parser.add_argument(
        "--reward", choices=REWARDS, default=REWARD, help="PPO's training reward (hfo2d.reward)"
    )
    parser.add_argument("--hp", default="{}", help="JSON: HybridPPO hyperparameters over the defaults")
    parser.add_argument("--threads", type=int, default=1, help="torch threads")
    parser.add_argument("--smoke", action="store_true", help="a few seconds: tiny budgets everywhere")
    args = parser.parse_args(argv)
    hp = {**HP, **json.loads(args.hp)}
    for name in ("log_std", "log_std_final"):
        value = getattr(args, name)
        if value is not None and not np.isfinite(value):
            parser.error(f"--{name.replace('_', '-')} must be a finite number, got {value}")
    if args.lr_schedule == "linear" and not isinstance(hp["learning_rate"], (int, float)):
        parser.error(f"--lr-schedule linear needs a numeric learning_rate, got {hp['learning_rate']!r}")
    if args.smoke:
        args.steps, args.eval_every, args.eval_episodes, args.n_envs = 2048, 1024, 4, 4
        args.critic_warmup, args.dagger_episodes, args.distill_epochs, args.distill_eval_episodes = (
            1024,
            4,
            1,
            4,
        )
        hp["batch_size"] = 256
    if (args.out / "curve.jsonl").exists():
        parser.error(f"{args.out} already holds a run (curve.jsonl); choose another --out")
    args.out.mkdir(parents=True, exist_ok=True)
    th.set_num_threads(args.threads)
    record = {
        "env_id": ENV_ID,
        "reward": args.reward,
        "teacher": args.teacher,
        "hp": hp,
        "options": {k: (str(v) if isinstance(v, Path) else v) for k, v in vars(args).items()},
        "command": " ".join([Path(sys.argv[0]).name, *(argv if argv is not None else sys.argv[1:])]),
        "load1_at_start": load_average(),
        "method": METHOD,
    }
    (args.out / "run.json").write_text(json.dumps(record, indent=1))

    teacher = load_model(args.teacher)
    env = make_hfo_vec_env(ENV_ID, args.n_envs, seed=args.seed, reward=args.reward)
    # rewards scaled by a running std of the discounted return (as hybrid_ppo_runs.py's e6)
    env = VecNormalize(env, norm_obs=False, norm_reward=True, gamma=hp["gamma"])
    model = student_model(env, args, hp)
    distilled = distil_clone(teacher, model, args)
    (args.out / "distill.json").write_text(json.dumps(distilled, indent=1))
    model.save(args.out / "distilled.zip")
    if args.router == "field_half":
        model.set_reference(copy.deepcopy(model.policy))
    else:
        model.set_reference(model.policy.hand_routed_copy("field_half"))

    def evaluate(policy_model: HybridPPO) -> dict:  # the full goalie, HFO's own statuses
        return greedy_evaluation(policy_model, ENV_ID, {}, args.eval_episodes, seed=10_000 + args.seed)

    recorder = RunRecorder(args.out, args.minutes, args.eval_every, evaluate)
    callbacks: list[Any] = [recorder]
    if args.log_std_final is not None:  # after set_reference: the schedule sets the reference's log std too
        callbacks.insert(0, LogStdSchedule(args.log_std, args.log_std_final))
    # the recorder alone without a schedule: the run is then the recipe's as before the option, call for call
    model.learn(args.steps, callback=callbacks if len(callbacks) > 1 else recorder, progress_bar=False)
    recorder.row(final=True)
    env.close()


if __name__ == "__main__":
    main()
