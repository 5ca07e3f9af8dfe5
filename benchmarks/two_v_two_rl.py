"""PPO from the clones of ``two_v_two_clone.py``: two strikers against one, each arm from its own clone, one recipe
and one budget, against agent2d's goalie and one field defender (issue 34 item 5, from demonstrations then reward).

``two_v_two_clone.py --routed`` fits one HybridPPO policy per arm by imitation: ``2v2``, both strikers, one head
per ``own_pass`` role (the role appended to each striker's observation and routed by
:class:`sb3_hfo.common.routers.OneHotRouter`, as the paper's skills are routed by ``field_half``); ``1v2``, one
striker, ``soft_dribble`` (always the ``play`` role). This script continues each clone with PPO from the reward:

* ``train``: the clone's networks in a fresh HybridPPO on ``--n-envs`` learning-striker slots
  (:func:`sb3_hfo.multi_agent.make_team_vec_env`, HFO master's vector with the roles appended:
  :class:`two_v_two_clone.RoleObservations`), ``two_v_one.py``'s fine-tuning settings (:data:`two_v_one.HP`,
  ``--lr`` for the learning rate), every head's parameter log std set to ``--log-std`` (distillation leaves them at
  0, and a 2v2 clone played with log std -2.5 scores 1.5 % against 16.5 % greedy, 14.5 % at -3.5), value-only updates for the first ``--critic-warmup`` agent steps (the clone's
  critic is untrained), rewards scaled by ``VecNormalize``; the budget is agent steps (one per learning striker per
  cycle), so both arms collect the same transitions and make the same updates. Every ``--eval-every`` steps,
  ``--eval-episodes`` greedy hfo2d episodes of the arm's own team go to ``curve.jsonl``; ``final.zip`` at the end.
* ``evaluate``: ``start`` (the clone) and ``final`` of each arm in ``--out`` over ``--episodes`` greedy
  episodes, in hfo2d (``evaluate_team_games``) or a real HFO build (``--backend real``: ``hfo2d.parallel_env``,
  ``HFO_DIR``, under tools/real_hfo/loopback.sh), to ``OUT/eval_{backend}_{arm}_{which}.json``.

    python benchmarks/two_v_two_rl.py train --arm 2v2 --start ~/runs/twovtwo_routed/s0/arm_2v2/student.zip \\
        --out ~/runs/twovtwo_rl/s0 --steps 1000000
    python benchmarks/two_v_two_rl.py evaluate --out ~/runs/twovtwo_rl/s0 --episodes 1000
    python benchmarks/two_v_two_rl.py train --arm 2v2 --out /tmp/rl --smoke      # seconds: what the test runs

How the figures are used: benchmarks/README.md, "A second striker against the goalie and a field defender".
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
import torch as th
from stable_baselines3.common.vec_env import VecNormalize

sys.path.insert(0, str(Path(__file__).resolve().parent))
from hybrid_ppo_runs import RunRecorder, load_average  # noqa: E402
from two_v_one import HP  # noqa: E402
from two_v_two_clone import (  # noqa: E402
    ARMS,
    RoleObservations,
    RolePredictor,
    ScriptedPredictor,
    student_model,
    team_games,
    with_roles,
)
from two_v_two_scripted import DEFENSE_NPCS, ROLES  # noqa: E402

import hfo2d  # noqa: E402
from hfo2d.features import FEATURES_PER_PLAYER, NUM_BASIC_FEATURES, hfo_num_features  # noqa: E402
from hfo2d.team import TEAM_OFFENSE_REWARDS  # noqa: E402
from sb3_hfo.hybrid_ppo import HybridPPO  # noqa: E402
from sb3_hfo.multi_agent import evaluate_team, evaluate_team_games, make_team_vec_env  # noqa: E402

MODELS: tuple[str, ...] = ("start", "final")


def train(args: argparse.Namespace) -> Path:
    """One arm: copy the clone into a fresh HybridPPO, save ``start.zip``, train, save ``final.zip``."""
    strikers = ARMS[args.arm][0]
    folder = args.out / f"arm_{args.arm}"
    if (folder / "curve.jsonl").exists():
        raise SystemExit(f"error: {folder} already holds a run (curve.jsonl); choose another --out")
    if args.n_envs % strikers:
        raise SystemExit(
            f"error: --n-envs ({args.n_envs}) must be a multiple of the strikers per game ({strikers})"
        )
    folder.mkdir(parents=True, exist_ok=True)
    th.set_num_threads(args.threads)
    env = make_team_vec_env(
        args.n_envs // strikers,
        offense_agents=strikers,
        defense_npcs=DEFENSE_NPCS,
        seed=args.seed,
        reward=args.reward,
        feature_set="hfo",
    )
    env = VecNormalize(
        RoleObservations(env, strikers - 1), norm_obs=False, norm_reward=True, gamma=HP["gamma"]
    )
    start = (
        student_model(strikers, args.seed, [16], routed=True)
        if args.start is None
        else HybridPPO.load(args.start, device="cpu")
    )
    if start.observation_space.shape != env.observation_space.shape:
        raise SystemExit(
            f"error: the start reads {start.observation_space.shape[0]} features, the {args.arm} arm with roles gives "
            f"{env.observation_space.shape[0]}: is it this arm's routed clone (two_v_two_clone.py --routed)?"
        )
    model = HybridPPO(
        "MlpPolicy",
        env,
        seed=args.seed,
        policy_kwargs=start.policy_kwargs,
        tensorboard_log=None if args.smoke else str(folder / "tb"),
        critic_warmup_steps=args.critic_warmup,
        **{**HP, "learning_rate": args.lr},
    )
    model.policy.load_state_dict(start.policy.state_dict())
    with th.no_grad():  # distillation leaves the log stds at their init (std 1 on the [-1, 1] scale): noise
        for head in model.policy.heads:
            head.log_std.fill_(args.log_std)
    model.save(folder / "start.zip")
    record = {
        "arm": args.arm,
        "strikers": strikers,
        "slots": args.n_envs,
        "budget": "agent steps (num_timesteps); game cycles = agent steps / strikers",
        "reward": args.reward,
        "start": str(args.start) if args.start else "untrained (smoke)",
        "hp": {**HP, "learning_rate": args.lr},
        "critic_warmup": args.critic_warmup,
        "log_std": args.log_std,
        "steps": args.steps,
        "seed": args.seed,
        "command": " ".join([Path(sys.argv[0]).name, *sys.argv[1:]]),
        "load1_at_start": load_average(),
    }
    (folder / "run.json").write_text(json.dumps(record, indent=1))
    games = team_games(strikers, args.games)

    def curve_evaluation(policy_model: HybridPPO) -> dict[str, Any]:  # the arm's own team, hfo2d
        result = evaluate_team_games(
            RolePredictor(policy_model, strikers - 1), games, args.eval_episodes, seed=10_000 + args.seed
        )
        result["cycles"] = int(policy_model.num_timesteps) // strikers
        return result

    recorder = RunRecorder(folder, args.minutes, args.eval_every, curve_evaluation)
    model.learn(args.steps, callback=recorder, progress_bar=False)
    recorder.row(final=True)
    env.close()
    return folder


def evaluate(args: argparse.Namespace) -> dict[str, Any]:
    """``--which`` models of every arm in ``--out`` over ``--episodes`` greedy episodes with ``--backend``."""
    th.set_num_threads(1)
    results: dict[str, Any] = {}
    for arm, (strikers, _) in sorted(ARMS.items()):
        for which in args.which:
            path = args.out / f"arm_{arm}" / f"{which}.zip"
            if not path.exists():
                print(f"skipping {arm} {which}: no {path}", flush=True)
                continue
            player = RolePredictor(HybridPPO.load(path, device="cpu"), strikers - 1)
            started = time.time()
            if args.backend == "hfo2d":
                result = evaluate_team_games(
                    player, team_games(strikers, args.games), args.episodes, args.seed
                )
            else:
                env = hfo2d.parallel_env(
                    offense_agents=strikers,
                    defense_npcs=DEFENSE_NPCS,
                    backend="real",
                    feature_set="hfo",
                    reward="sparse",
                )
                try:
                    result = evaluate_team(player, env, args.episodes, seed=args.seed)
                finally:
                    env.close()
            result.update(model=str(path), backend=args.backend, seed=args.seed)
            result.update(seconds=round(time.time() - started, 1), load1=round(load_average(), 2))
            results[f"{arm}_{which}"] = result
            (args.out / f"eval_{args.backend}_{arm}_{which}.json").write_text(json.dumps(result, indent=1))
            print(json.dumps({f"{arm}_{which}": result}), flush=True)
    return results


class MixedTeam:
    """The ``own_pass`` pair with some roles played by models: each striker's role from :func:`own_pass_role`;
    the roles in ``team_roles`` by ``team_model`` (a 2v2 routed model), ``play`` by ``play_model`` if given (a 1v2
    routed striker, reading the striker's vector without its teammate's block and uniform number), every other
    role by the scripted rule. Shows which role's model loses goals, or what a trained lone striker gets from
    teammates that play the other roles."""

    def __init__(self, team_model: Any, team_roles: list[str], play_model: Any = None) -> None:
        if play_model is not None and "play" in team_roles:
            raise ValueError("the play role goes to --play-model or to the team model, not both")
        self.team_model, self.play_model = team_model, play_model
        self.team_roles = np.array([name in team_roles for name in ROLES])
        self.teacher = ScriptedPredictor("own_pass", 1)
        # the same striker's vector without a teammate (HFO master's layout, hfo2d.features.hfo_num_features): the
        # teammate's 8-feature block after the 58 basic features, and its uniform number after the player blocks
        teammate_block = range(NUM_BASIC_FEATURES, NUM_BASIC_FEATURES + FEATURES_PER_PLAYER)
        teammate_unum = NUM_BASIC_FEATURES + FEATURES_PER_PLAYER * (1 + DEFENSE_NPCS)
        self.alone_columns = [
            column
            for column in range(hfo_num_features(1, DEFENSE_NPCS))
            if column not in teammate_block and column != teammate_unum
        ]

    def predict(self, observations: np.ndarray, **kwargs: Any) -> tuple[np.ndarray, None]:
        routed = with_roles(observations, 1)
        roles = routed[:, -len(ROLES) :].argmax(axis=1)
        actions = self.teacher.predict(observations)[0]
        if self.team_model is not None and self.team_roles[roles].any():
            team_actions = self.team_model.predict(routed, deterministic=True)[0]
            actions = np.where(self.team_roles[roles][:, None], team_actions, actions)
        if self.play_model is not None:
            alone = with_roles(np.asarray(observations)[:, self.alone_columns], 0)
            play_actions = self.play_model.predict(alone, deterministic=True)[0]
            actions = np.where((roles == ROLES.index("play"))[:, None], play_actions, actions)
        return actions, None


def mixed(args: argparse.Namespace) -> dict[str, Any]:
    """The :class:`MixedTeam` of ``--team-model``, ``--team-roles`` and ``--play-model`` over ``--episodes``."""
    th.set_num_threads(1)
    load = lambda path: None if path is None else HybridPPO.load(path, device="cpu")  # noqa: E731
    team = MixedTeam(load(args.team_model), args.team_roles, load(args.play_model))
    started = time.time()
    result = evaluate_team_games(team, team_games(2, args.games), args.episodes, args.seed)
    result.update(
        team_model=str(args.team_model),
        team_roles=args.team_roles,
        play_model=str(args.play_model),
        seconds=round(time.time() - started, 1),
    )
    print(json.dumps(result), flush=True)
    if args.json is not None:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(result, indent=1))
    return result


def main(argv: list[str] | None = None) -> Any:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)
    trainer = commands.add_parser("train", help="PPO from one arm's clone")
    trainer.add_argument("--arm", choices=sorted(ARMS), required=True)
    trainer.add_argument("--start", type=Path, help="the arm's routed clone (two_v_two_clone.py --routed)")
    trainer.add_argument("--out", type=Path, required=True, help="the run folder (one sub-folder per arm)")
    trainer.add_argument("--steps", type=int, default=1_000_000, help="agent steps")
    trainer.add_argument("--reward", default="sparse", choices=TEAM_OFFENSE_REWARDS)
    trainer.add_argument("--lr", type=float, default=HP["learning_rate"])
    trainer.add_argument(
        "--log-std",
        type=float,
        default=-3.5,
        help="every head's parameter log std at the start (rl_from_clone.py's default)",
    )
    trainer.add_argument(
        "--critic-warmup", type=int, default=100_000, help="agent steps of value-only updates"
    )
    trainer.add_argument("--n-envs", type=int, default=16, help="learning-striker slots")
    trainer.add_argument("--eval-every", type=int, default=250_000)
    trainer.add_argument("--eval-episodes", type=int, default=200)
    trainer.add_argument("--games", type=int, default=16, help="hfo2d games played at once in evaluations")
    trainer.add_argument("--minutes", type=float, default=600.0, help="wall-clock cap on training")
    trainer.add_argument("--seed", type=int, default=0)
    trainer.add_argument("--threads", type=int, default=1, help="torch threads")
    trainer.add_argument("--smoke", action="store_true", help="tiny settings, seconds")
    evaluator = commands.add_parser("evaluate", help="the arms' start and final models")
    evaluator.add_argument("--out", type=Path, required=True)
    evaluator.add_argument("--which", nargs="+", choices=MODELS, default=list(MODELS))
    evaluator.add_argument("--backend", choices=("hfo2d", "real"), default="hfo2d")
    evaluator.add_argument("--episodes", type=int, default=1000)
    evaluator.add_argument("--games", type=int, default=16, help="hfo2d games played at once")
    evaluator.add_argument("--seed", type=int, default=0)
    mix = commands.add_parser("mixed", help="the own_pass pair with some roles played by models")
    mix.add_argument(
        "--team-model", type=Path, help="a 2v2 routed model (two_v_two_clone.py --routed or train)"
    )
    mix.add_argument("--team-roles", nargs="*", choices=ROLES, default=[], help="the roles it plays")
    mix.add_argument("--play-model", type=Path, help="a 1v2 routed striker for the play role")
    mix.add_argument("--episodes", type=int, default=1000)
    mix.add_argument("--games", type=int, default=16, help="hfo2d games played at once")
    mix.add_argument(
        "--seed", type=int, default=20_000, help="two_v_two_clone.py's evaluation seed for its seed 0"
    )
    mix.add_argument("--json", type=Path, help="also write the result here")
    args = parser.parse_args(argv)
    if args.command == "mixed":
        if args.team_roles and args.team_model is None:
            parser.error("--team-roles needs --team-model")
        if args.episodes < 1 or args.games < 1:
            parser.error(f"--episodes and --games must be >= 1, got {args.episodes} and {args.games}")
        try:
            return mixed(args)
        except ValueError as error:
            parser.error(str(error))
    if args.command == "evaluate":
        if args.episodes < 1 or args.games < 1:
            parser.error(f"--episodes and --games must be >= 1, got {args.episodes} and {args.games}")
        return evaluate(args)
    if args.smoke:
        args.steps, args.eval_every, args.eval_episodes, args.games, args.critic_warmup = 512, 256, 2, 2, 256
    for name in ("steps", "n_envs", "eval_every", "eval_episodes", "games"):
        if getattr(args, name) < 1:
            parser.error(f"--{name.replace('_', '-')} must be >= 1, got {getattr(args, name)}")
    if args.start is None and not args.smoke:
        parser.error("--start is required (an untrained start is for --smoke only)")
    return train(args)


if __name__ == "__main__":
    main()
