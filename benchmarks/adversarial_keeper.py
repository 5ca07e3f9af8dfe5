"""An adversarial keeper (issue 34 item 7): a learned goalie and a learned striker trained against each other.

Alternate rounds in hfo2d, each side against the other side's latest policy, frozen
(:class:`sb3_hfo.multi_agent.FrozenOpponent`, played greedily, one batched call per step):

1. **Goalie**: :class:`sb3_hfo.hybrid_ppo.HybridPPO` from scratch in round 1, continued in later rounds, as the
   defense agent with unum 1 of ``--n-games`` 1v1 team games (``hfo2d.team.TeamGame(1, 1, 0)``: DASH, TURN,
   TACKLE, KICK, CATCH). Its opponents: half of the games the current striker, the other half spread over the
   earlier strikers (round 1: the starting striker and ``e6_imitation``), so that it does not forget how the older ones
   play. Its reward is ``defense_reward`` (``--goalie-reward``; hfo2d.team's module docstring): ``"shaped"``
   (default) is +1 on the last step when the episode ends in the defense's favour (CAPTURED_BY_DEFENSE,
   OUT_OF_BOUNDS, OUT_OF_TIME), -1 on a GOAL, plus the rise of the goalie's own ball proximity since its last
   step (DQNHFO's move-to-ball term, feature 53); ``"sparse"`` the +1 / -1 alone.
2. **Striker**: HybridPPO continued from ``--striker`` (default: the RL-from-clone model, trained on
   HFO/Keeper-v1, whose observation a striker gets unchanged against a goalie agent:
   tests/hfo2d/test_goalie_agent_view.py), in half of its games against the frozen learned goalie and in the
   other half against agent2d's goalie (so that it keeps its Keeper-v1 play), with its training reward
   ``shaped_gap_refund`` (hfo2d.reward; not HFO's own) and rl_from_clone.py's fine-tuning settings.

Every round's final models go to ``OUT/round<k>/goalie.zip`` and ``striker.zip`` (outside the repo), each round's
quick figures (``--round-episodes`` greedy episodes) to ``OUT/rounds.jsonl``. The report (``OUT/report.json`` and
a table on stdout), every row ``--episodes`` greedy episodes with Wilson 95 % intervals and end statuses:

* the goal rate each striker gets (lower is better for the goalie): the final learned goalie and agent2d's
  goalie against ``e6_imitation``, the starting striker, the final learned striker and every scripted striker
  (:data:`hfo2d.strikers.STRIKERS`);
* the final learned striker, its starting point and ``e6_imitation`` against agent2d's goalie (``TeamGame(1, 0, 1)``,
  which plays HFO/Keeper-v1's games bit for bit: tests/hfo2d/test_team_game.py).

    python benchmarks/adversarial_keeper.py --out ~/runs/advkeeper --rounds 3 --goalie-minutes 6 \\
        --striker-minutes 4
    python benchmarks/adversarial_keeper.py --report-only --out ~/runs/advkeeper   # the report of a finished run
    python benchmarks/adversarial_keeper.py --smoke --out /tmp/advkeeper_smoke     # seconds: what the test runs
"""

from __future__ import annotations

import argparse
import json
import os
import time
from pathlib import Path
from typing import Any

import numpy as np
import torch as th
from stable_baselines3.common.callbacks import BaseCallback

from hfo2d.strikers import STRIKERS
from hfo2d.team import TeamGame
from sb3_hfo.evaluation import wilson_interval
from sb3_hfo.hybrid_ppo import HybridPPO
from sb3_hfo.models import load_model
from sb3_hfo.multi_agent import MatchResult, TeamVecEnv, play_matches

#: The goalie's HybridPPO settings (from scratch: SB3's PPO defaults but for the batch of games).
GOALIE_HP: dict[str, Any] = {
    "n_steps": 256,
    "batch_size": 1024,
    "n_epochs": 10,
    "learning_rate": 3e-4,
    "gamma": 0.99,
    "gae_lambda": 0.95,
    "clip_range": 0.2,
    "ent_coef": 0.0,
    "policy_kwargs": {"net_arch": {"pi": [128, 128], "vf": [128, 128]}},
}
#: The striker's: rl_from_clone.py's fine-tuning settings (small steps, clipped at 0.1, stopped on a large KL).
STRIKER_HP: dict[str, Any] = {
    "n_steps": 256,
    "batch_size": 1024,
    "n_epochs": 10,
    "learning_rate": 2e-4,
    "clip_range": 0.1,
    "target_kl": 0.02,
}
STRIKER_REWARD = "shaped_gap_refund"
DEFAULT_STRIKER = "e6_from_clone"  # the RL-from-clone model (benchmarks/rl_from_clone.py seed 0); named e6 when these runs ran
SMOKE_HP: dict[str, Any] = {"n_steps": 16, "batch_size": 32, "n_epochs": 1}


class WallClockBudget(BaseCallback):
    """Stops ``learn`` after ``minutes`` of wall clock (or its step budget, whichever comes first)."""

    def __init__(self, minutes: float) -> None:
        super().__init__()
        self.budget_s = minutes * 60.0
        self.started = time.time()

    def _on_step(self) -> bool:
        return time.time() - self.started < self.budget_s


class OpponentPool:
    """A batched opponent that plays game ``g``'s rows with ``policies[assignment[g]]`` (each played greedily).

    ``rows_per_game`` is the number of rows each game contributes to a batch (its agents of the opponent's side);
    the batch lists the games in order, as :class:`sb3_hfo.multi_agent.TeamVecEnv` stacks them.
    """

    def __init__(self, policies: list[Any], assignment: list[int], rows_per_game: int = 1) -> None:
        self.policies = policies
        self.rows = np.repeat(np.asarray(assignment), rows_per_game)
        self.observation_space = policies[0].observation_space
        self.action_space = policies[0].action_space

    def predict(self, observations: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
        actions = np.zeros((len(observations), *self.action_space.shape), dtype=np.float32)
        for index, policy in enumerate(self.policies):
            chosen = self.rows == index
            if chosen.any():
                actions[chosen] = policy.predict(observations[chosen], deterministic=deterministic)[0]
        return actions, None


def pool_assignment(n_games: int, n_policies: int) -> list[int]:
    """Half the games (rounded up) to the last policy (the current one), the rest round-robin over the others."""
    if n_policies == 1:
        return [0] * n_games
    current = (n_games + 1) // 2
    return [n_policies - 1] * current + [k % (n_policies - 1) for k in range(n_games - current)]


def load_striker(path: str) -> Any:
    """A striker by a committed name (``e6_from_clone``, ``e6_imitation``) or a zip path (``~`` expanded), on the CPU."""
    expanded = os.path.expanduser(path)
    return load_model(expanded if Path(expanded).is_file() else path, device="cpu")


def result_row(label: str, result: MatchResult) -> dict[str, Any]:
    low, high = wilson_interval(result.goals, result.episodes)
    return {
        "match": label,
        "episodes": result.episodes,
        "goals": result.goals,
        "goal_rate": result.goal_rate,
        "goal_rate_ci95": [low, high],
        "statuses": result.counts(),
    }


def train_goalie(
    goalie: HybridPPO | None,
    strikers: list[Any],
    args: argparse.Namespace,
    seed: int,
    hp: dict[str, Any],
) -> HybridPPO:
    pool = OpponentPool(strikers, pool_assignment(args.n_games, len(strikers)))
    games = [TeamGame(1, 1, 0, defense_reward=args.goalie_reward) for _ in range(args.n_games)]
    env = TeamVecEnv(games, side="defense", opponent=pool)
    env.seed(seed)
    if goalie is None:
        goalie = HybridPPO("MlpPolicy", env, seed=seed, device="cpu", **hp)
    else:
        goalie.set_env(env)
    goalie.learn(args.goalie_steps, callback=WallClockBudget(args.goalie_minutes), reset_num_timesteps=False)
    return goalie


def train_striker(
    start: str, goalie: HybridPPO, args: argparse.Namespace, seed: int, hp: dict[str, Any]
) -> HybridPPO:
    """Continue the striker saved at ``start`` against ``goalie`` (frozen) in half the games, agent2d's goalie in
    the rest. The saved model's settings give way to ``hp``; the reference pull and the critic warm-up of the
    RL-from-clone run are off (its reference is not saved with it)."""
    half = (args.n_games + 1) // 2
    games = [TeamGame(1, 1, 0, reward=STRIKER_REWARD) for _ in range(half)]
    games += [TeamGame(1, 0, 1, reward=STRIKER_REWARD) for _ in range(args.n_games - half)]
    env = TeamVecEnv(games, side="offense", opponent=goalie)
    env.seed(seed)
    striker = HybridPPO.load(
        os.path.expanduser(start),
        env=env,
        device="cpu",
        tensorboard_log=None,
        reference_coef=0.0,
        critic_warmup_steps=0,
        **hp,
    )
    striker.learn(
        args.striker_steps, callback=WallClockBudget(args.striker_minutes), reset_num_timesteps=False
    )
    return striker


def matches(label: str, args: argparse.Namespace, episodes: int, **kwargs: Any) -> dict[str, Any]:
    started = time.time()
    row = result_row(label, play_matches(args.eval_games, episodes, seed=args.eval_seed, **kwargs))
    row["seconds"] = round(time.time() - started, 1)
    print(
        f"{label:58s} {row['goal_rate']:6.1%} [{row['goal_rate_ci95'][0]:.3f}, {row['goal_rate_ci95'][1]:.3f}] "
        f"{row['statuses']}",
        flush=True,
    )
    return row


def report(args: argparse.Namespace, out: Path) -> dict[str, Any]:
    """The final models against the other side's fixed opponents (module docstring)."""
    last = max(int(path.name[5:]) for path in out.glob("round*") if path.name[5:].isdigit())
    goalie = HybridPPO.load(out / f"round{last}" / "goalie.zip", device="cpu")
    learned_striker = load_striker(str(out / f"round{last}" / "striker.zip"))
    start = load_striker(args.striker)
    e6 = load_striker("e6_imitation")
    episodes = args.episodes
    rows: list[dict[str, Any]] = []
    started = time.time()
    strikers = [
        ("e6_imitation", e6),
        ("RL-from-clone (start)", start),
        (f"learned striker (round {last})", learned_striker),
    ]
    for name, model in strikers:
        rows.append(
            matches(
                f"{name} vs learned goalie",
                args,
                episodes,
                offense=model,
                defense=goalie,
                offense_agents=1,
                defense_agents=1,
            )
        )
        rows.append(
            matches(
                f"{name} vs agent2d goalie", args, episodes, offense=model, offense_agents=1, defense_npcs=1
            )
        )
    scripted = list(STRIKERS) if not args.smoke else list(STRIKERS)[:1]
    for name in scripted:
        rows.append(
            matches(
                f"scripted {name} vs learned goalie",
                args,
                episodes,
                defense=goalie,
                offense_agents=0,
                defense_agents=1,
                scripted_strikers=1,
                striker=name,
            )
        )
        rows.append(
            matches(
                f"scripted {name} vs agent2d goalie",
                args,
                episodes,
                offense_agents=0,
                defense_npcs=1,
                scripted_strikers=1,
                striker=name,
            )
        )
    result = {
        "final_round": last,
        "episodes": episodes,
        "seed": args.eval_seed,
        "rows": rows,
        "seconds": round(time.time() - started, 1),
        "load1_at_end": os.getloadavg()[0],
        "command": "python benchmarks/adversarial_keeper.py --report-only --out " + str(args.out),
    }
    (out / "report.json").write_text(json.dumps(result, indent=1))
    return result


def real_matches(
    episodes: int, seed: int, offense: Any = None, defense: Any = None, **team: Any
) -> MatchResult:
    """``episodes`` episodes of one real HFO game (``hfo2d.parallel_env(..., backend="real")``, under
    tools/real_hfo/loopback.sh), ``offense`` playing its offense agent and ``defense`` its defense agent (an SB3
    model, greedily, or a per-observation scripted striker with ``reset``); the end statuses in order. An episode
    that the server loses (SERVER_DOWN) is counted under that status, not dropped."""
    import hfo2d

    env = hfo2d.parallel_env(backend="real", seed=seed, **team)
    players = {"offense_0": offense, "defense_0": defense}
    statuses: list[str] = []
    try:
        for _ in range(episodes):
            observations, _ = env.reset()
            for player in players.values():
                if hasattr(player, "reset"):
                    player.reset()
            while env.agents:
                actions = {}
                for name in env.agents:
                    player = players[name]
                    if hasattr(player, "predict"):
                        actions[name] = player.predict(observations[name][None], deterministic=True)[0][0]
                    else:
                        actions[name] = player(observations[name])
                observations, _, _, _, infos = env.step(actions)
            statuses.append(next(iter(infos.values()))["status"])
    finally:
        env.close()
    return MatchResult(tuple(statuses))


def real_report(args: argparse.Namespace, out: Path) -> dict[str, Any]:
    """The final learned goalie against e6_imitation, the starting striker, the final learned striker or a scripted striker
    in real HFO, or the final learned striker against agent2d's goalie there (RealKeeper-v0's game)."""
    from hfo2d.strikers import make_striker

    last = max(int(path.name[5:]) for path in out.glob("round*") if path.name[5:].isdigit())
    goalie = HybridPPO.load(out / f"round{last}" / "goalie.zip", device="cpu")
    opponents = {
        "e6_imitation": lambda: load_striker("e6_imitation"),
        "start": lambda: load_striker(args.striker),
        "learned_striker": lambda: load_striker(str(out / f"round{last}" / "striker.zip")),
        **{name: (lambda name=name: make_striker(name)) for name in STRIKERS},
    }
    rows = []
    for which in args.real:
        started = time.time()
        if which == "learned_striker_vs_agent2d":
            result = real_matches(
                args.episodes,
                args.eval_seed,
                offense=opponents["learned_striker"](),
                offense_agents=1,
                defense_npcs=1,
            )
            label = f"real HFO: learned striker (round {last}) vs agent2d goalie"
        else:
            result = real_matches(
                args.episodes,
                args.eval_seed,
                offense=opponents[which](),
                defense=goalie,
                offense_agents=1,
                defense_agents=1,
            )
            label = f"real HFO: {which} vs learned goalie (round {last})"
        row = result_row(label, result)
        row["seconds"] = round(time.time() - started, 1)
        row["load1_at_end"] = os.getloadavg()[0]
        print(
            label,
            f"{row['goal_rate']:.1%}",
            row["goal_rate_ci95"],
            row["statuses"],
            row["seconds"],
            flush=True,
        )
        rows.append(row)
        name = "real_" + "_".join(args.real) + ".json"
        (out / name).write_text(
            json.dumps({"episodes": args.episodes, "seed": args.eval_seed, "rows": rows}, indent=1)
        )
    return {"rows": rows}


REAL_CHOICES = ("e6_imitation", "start", "learned_striker", "learned_striker_vs_agent2d", *STRIKERS)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", required=True, help="folder for the models and records (outside the repo)")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--goalie-minutes", type=float, default=6.0, help="wall clock per goalie round")
    parser.add_argument("--striker-minutes", type=float, default=4.0, help="wall clock per striker round")
    parser.add_argument("--goalie-steps", type=int, default=4_000_000, help="step budget per goalie round")
    parser.add_argument("--striker-steps", type=int, default=2_000_000, help="step budget per striker round")
    parser.add_argument("--n-games", type=int, default=16, help="games per training VecEnv")
    parser.add_argument("--striker", default=DEFAULT_STRIKER, help="the starting striker (a HybridPPO zip)")
    parser.add_argument("--goalie-reward", choices=("shaped", "sparse"), default="shaped")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--episodes", type=int, default=1000, help="greedy episodes per report row")
    parser.add_argument("--round-episodes", type=int, default=300, help="greedy episodes per round figure")
    parser.add_argument("--eval-games", type=int, default=16)
    parser.add_argument("--eval-seed", type=int, default=0)
    parser.add_argument("--threads", type=int, default=1, help="torch threads")
    parser.add_argument("--report-only", action="store_true", help="only the report of the run in --out")
    parser.add_argument("--smoke", action="store_true", help="a tiny run (seconds): the test's")
    parser.add_argument(
        "--real",
        nargs="+",
        choices=REAL_CHOICES,
        help="only real-HFO matches of the run in --out (under tools/real_hfo/loopback.sh, HFO_DIR set): the "
        "learned goalie against these strikers, or learned_striker_vs_agent2d",
    )
    args = parser.parse_args(argv)
    th.set_num_threads(args.threads)
    out = Path(os.path.expanduser(args.out))
    out.mkdir(parents=True, exist_ok=True)
    if args.real:
        return real_report(args, out)
    goalie_hp, striker_hp = dict(GOALIE_HP), dict(STRIKER_HP)
    if args.smoke:
        args.rounds, args.n_games, args.eval_games = 1, 2, 2
        args.goalie_steps = args.striker_steps = 64
        args.episodes = args.round_episodes = 2
        goalie_hp.update(SMOKE_HP)
        striker_hp.update(SMOKE_HP)
        striker_hp.pop("target_kl")
    if not args.report_only:
        (out / "run.json").write_text(
            json.dumps(
                {
                    "args": vars(args),
                    "goalie_hp": goalie_hp,
                    "striker_hp": striker_hp,
                    "striker_reward": STRIKER_REWARD,
                    "load1_at_start": os.getloadavg()[0],
                },
                indent=1,
                default=str,
            )
        )
        striker_path = args.striker
        pool: list[Any] = [load_striker("e6_imitation"), load_striker(args.striker)]
        goalie: HybridPPO | None = None
        for round_number in range(1, args.rounds + 1):
            folder = out / f"round{round_number}"
            folder.mkdir(exist_ok=True)
            started = time.time()
            goalie = train_goalie(goalie, pool, args, args.seed + 1000 * round_number, goalie_hp)
            goalie_seconds = time.time() - started
            goalie.save(folder / "goalie.zip")
            frozen_goalie = HybridPPO.load(folder / "goalie.zip", device="cpu")
            started = time.time()
            striker = train_striker(
                striker_path, frozen_goalie, args, args.seed + 1000 * round_number + 500, striker_hp
            )
            striker_seconds = time.time() - started
            striker_path = str(folder / "striker.zip")
            striker.save(striker_path)
            pool.append(load_striker(str(folder / "striker.zip")))
            row = {
                "round": round_number,
                "goalie_steps": goalie.num_timesteps,
                "goalie_seconds": round(goalie_seconds, 1),
                "striker_steps": striker.num_timesteps,
                "striker_seconds": round(striker_seconds, 1),
                "load1": os.getloadavg()[0],
                "rows": [
                    matches(
                        f"round {round_number}: start striker vs its goalie",
                        args,
                        args.round_episodes,
                        offense=pool[1],
                        defense=frozen_goalie,
                        offense_agents=1,
                        defense_agents=1,
                    ),
                    matches(
                        f"round {round_number}: its striker vs its goalie",
                        args,
                        args.round_episodes,
                        offense=pool[-1],
                        defense=frozen_goalie,
                        offense_agents=1,
                        defense_agents=1,
                    ),
                    matches(
                        f"round {round_number}: its striker vs agent2d goalie",
                        args,
                        args.round_episodes,
                        offense=pool[-1],
                        offense_agents=1,
                        defense_npcs=1,
                    ),
                ],
            }
            with open(out / "rounds.jsonl", "a") as stream:
                stream.write(json.dumps(row) + "\n")
    return report(args, out)


if __name__ == "__main__":
    main()
