"""PPO from the clones of ``two_v_two_clone.py``: two strikers against one, each arm from its own clone, one recipe
and one budget, against agent2d's goalie and one field defender (issue 34 item 5, from demonstrations then reward).

``two_v_two_clone.py --routed`` fits one HybridPPO policy per arm by imitation: ``2v2``, both strikers, one head
per ``own_pass`` role (the role appended to each striker's observation and routed by
:class:`sb3_hfo.common.routers.OneHotRouter`, as the paper's skills are routed by ``field_half``); ``1v2``, one
striker, ``soft_dribble`` (always the ``play`` role). This script continues each clone with PPO from the reward:

* ``train``: the clone's networks in a fresh HybridPPO on ``--n-envs`` learning-striker slots
  (:func:`sb3_hfo.multi_agent.make_team_vec_env`, HFO master's vector with the roles appended:
  :class:`two_v_two_clone.RoleObservations`), ``two_v_one.py``'s fine-tuning settings (:data:`two_v_one.HP`,
  ``--lr`` for the learning rate), value-only updates for the first ``--critic-warmup`` agent steps (the clone's
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

import torch as th
from stable_baselines3.common.vec_env import VecNormalize

sys.path.insert(0, str(Path(__file__).resolve().parent))
from hybrid_ppo_runs import RunRecorder, load_average  # noqa: E402
from two_v_one import HP  # noqa: E402
from two_v_two_clone import ARMS, RoleObservations, RolePredictor, student_model, team_games  # noqa: E402
from two_v_two_scripted import DEFENSE_NPCS  # noqa: E402

import hfo2d  # noqa: E402
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
    args = parser.parse_args(argv)
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
