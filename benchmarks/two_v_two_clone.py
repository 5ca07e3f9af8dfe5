"""Two strikers cloned from the passing pair against one cloned from ``soft_dribble``, against agent2d's goalie and
one field defender (issue 34 item 5, by imitation).

``two_v_two_scripted.py`` shows that a second striker pays once a field defender has to be beaten: its ``own_pass``
pair, each striker deciding from its own view, scores about twice what ``soft_dribble`` does alone. ``own_pass``
is a function of one striker's observation, so one network can learn it for both strikers (parameter sharing).
This script clones each rule into a HybridPPO policy and compares the clones, arm by arm, with one recipe:

* ``2v2``: the teacher is ``own_pass``; the student is one policy acting for both strikers of 2v2 games
  (``TeamGame(2, 0, 2)``: agent2d's goalie and one field defender), reading HFO master's vector (86 features);
* ``1v2``: the teacher is ``soft_dribble`` alone; the student plays 1v2 games (77 features).

Recipe (both arms): a fresh HybridPPO ``MlpPolicy`` (actor ``--actor``, by default ``[256, 128, 64]``, LeakyReLU, squashed means, as
``rl_from_clone.py``'s striker); :func:`sb3_hfo.hybrid_ppo.distill.distill` on ``--episodes`` teacher episodes, then
``--dagger-rounds`` rounds that add ``--episodes`` episodes of the student's own play, every state labelled by the
teacher (its discrete action and parameters). The teacher and the final student are then evaluated greedily on the
same seeds (``sb3_hfo.multi_agent.evaluate_team_games``, ``--games`` hfo2d games at once). The students learn by
imitation only: no reward is used.

    python benchmarks/two_v_two_clone.py --arm 2v2 --out ~/runs/twovtwo_clone/s0 --seed 0
    python benchmarks/two_v_two_clone.py --arm 1v2 --out ~/runs/twovtwo_clone/s0 --seed 0
    python benchmarks/two_v_two_clone.py --arm 2v2 --out /tmp/clone --smoke      # seconds: what the test runs

Each arm writes ``ARM/student.zip`` and ``ARM/clone.json`` (settings, every round's fit, the evaluations).
How the figures are used: benchmarks/README.md, "A second striker against the goalie and a field defender".
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import torch as th
from stable_baselines3.common.vec_env import VecEnv, VecEnvWrapper
from torch import nn

sys.path.insert(0, str(Path(__file__).resolve().parent))
from two_v_two_scripted import (  # noqa: E402  (the sibling script)
    DEFENSE_NPCS,
    ROLES,
    ScriptedPair,
    own_pass_role,
    read_team_view,
)

from hfo2d import strikers  # noqa: E402
from hfo2d.team import TeamGame  # noqa: E402
from sb3_hfo.common.routers import OneHotRouter  # noqa: E402
from sb3_hfo.hybrid_ppo import HybridPPO  # noqa: E402
from sb3_hfo.hybrid_ppo.distill import distill  # noqa: E402
from sb3_hfo.multi_agent import evaluate_team_games, make_team_vec_env  # noqa: E402

#: arm -> (learning strikers per game, the teacher: a team of two_v_two_scripted.py)
ARMS: dict[str, tuple[int, str]] = {"2v2": (2, "own_pass"), "1v2": (1, "alone")}
ACTOR_ARCH = [256, 128, 64]  # rl_from_clone.py's striker
PARAMETER_WEIGHT = 100.0  # distillation's parameter term, rl_from_clone.py's default


class ScriptedPredictor:
    """A scripted rule as an SB3-style predictor over a batch of single-striker observations (HFO master's vector)."""

    def __init__(self, team: str, teammates: int) -> None:
        self.pair = ScriptedPair(team)
        self.teammates = teammates

    def act(self, observation: np.ndarray) -> np.ndarray:
        view = read_team_view(observation, self.teammates, DEFENSE_NPCS)
        if self.pair.team == "own_pass":
            return strikers.flat_action(self.pair.own_command(view))
        return strikers.flat_action(self.pair.striker.decide(view.percept))

    def predict(
        self,
        observations: np.ndarray,
        state: Any = None,
        episode_start: Any = None,
        deterministic: bool = True,
    ) -> tuple[np.ndarray, None]:
        return np.stack([self.act(observation) for observation in observations]), None


def with_roles(observations: np.ndarray, teammates: int) -> np.ndarray:
    """``observations`` (a batch of HFO-master vectors) with ``own_pass``'s role of each striker appended as
    ``len(ROLES)`` one-hot columns (:func:`two_v_two_scripted.own_pass_role`; with no teammate always ``play``)."""
    observations = np.asarray(observations, dtype=np.float32)
    roles = np.zeros((len(observations), len(ROLES)), dtype=np.float32)
    for row, observation in enumerate(observations):
        roles[row, own_pass_role(read_team_view(observation, teammates, DEFENSE_NPCS))] = 1.0
    return np.concatenate([observations, roles], axis=1)


class RoleObservations(VecEnvWrapper):
    """A team VecEnv whose observations carry ``own_pass``'s roles (:func:`with_roles`), terminal ones included,
    so that a policy routed by :class:`sb3_hfo.common.routers.OneHotRouter` can act and train on it."""

    def __init__(self, venv: VecEnv, teammates: int) -> None:
        space = venv.observation_space
        low = np.concatenate([space.low, np.zeros(len(ROLES), dtype=np.float32)])
        high = np.concatenate([space.high, np.ones(len(ROLES), dtype=np.float32)])
        super().__init__(venv, observation_space=gym.spaces.Box(low, high, dtype=np.float32))
        self.teammates = teammates

    def reset(self) -> np.ndarray:
        return with_roles(self.venv.reset(), self.teammates)

    def step_wait(self) -> Any:
        observations, rewards, dones, infos = self.venv.step_wait()
        for info in infos:
            if "terminal_observation" in info:
                info["terminal_observation"] = with_roles(info["terminal_observation"][None], self.teammates)[
                    0
                ]
        return with_roles(observations, self.teammates), rewards, dones, infos


class RolePredictor:
    """A role-routed model acting on plain HFO-master vectors: the roles are appended before ``model.predict``."""

    def __init__(self, model: Any, teammates: int) -> None:
        self.model = model
        self.teammates = teammates

    def predict(self, observations: np.ndarray, **kwargs: Any) -> tuple[np.ndarray, Any]:
        return self.model.predict(with_roles(observations, self.teammates), **kwargs)


class Recorder:
    """Wraps a predictor and keeps every batch of observations it is asked about."""

    def __init__(self, predictor: Any) -> None:
        self.predictor = predictor
        self.batches: list[np.ndarray] = []

    def predict(self, observations: np.ndarray, **kwargs: Any) -> tuple[np.ndarray, Any]:
        self.batches.append(np.array(observations, copy=True))
        return self.predictor.predict(observations, **kwargs)


def agreement_by_role(
    policy: Any, inputs: np.ndarray, roles: np.ndarray, discrete: np.ndarray
) -> dict[str, dict[str, float]]:
    """For each ``own_pass`` role: how many of the states have it (``roles``: one-hot rows, :func:`with_roles`'s
    columns), and in what fraction the policy's most likely discrete action on ``inputs`` (what it reads) is the
    teacher's ``discrete``."""
    role_index = roles.argmax(axis=1)
    greedy = np.concatenate(
        [
            policy.action_distribution(th.as_tensor(inputs[start : start + 4096]))
            .log_pi.argmax(dim=-1)
            .numpy()
            for start in range(0, len(inputs), 4096)
        ]
    )
    return {
        name: {
            "states": int((role_index == role).sum()),
            "agreement": float((greedy == discrete)[role_index == role].mean()),
        }
        for role, name in enumerate(ROLES)
        if (role_index == role).any()
    }


def team_games(strikers_per_game: int, games: int) -> list[TeamGame]:
    return [TeamGame(strikers_per_game, 0, DEFENSE_NPCS, feature_set="hfo") for _ in range(games)]


def student_model(strikers_per_game: int, seed: int, actor: list[int], routed: bool = False) -> HybridPPO:
    """A fresh student; ``routed``: one head per ``own_pass`` role, picked by the role columns of
    :class:`RoleObservations`."""
    env = make_team_vec_env(1, offense_agents=strikers_per_game, defense_npcs=DEFENSE_NPCS, feature_set="hfo")
    policy_kwargs: dict[str, Any] = {
        "net_arch": {"pi": actor, "vf": [256, 128]},
        "activation_fn": nn.LeakyReLU,
        "squash_mean": True,
    }
    if routed:
        policy_kwargs |= {
            "skills": len(ROLES),
            "router": OneHotRouter(env.observation_space.shape[0], len(ROLES)),
        }
        env = RoleObservations(env, strikers_per_game - 1)
    return HybridPPO("MlpPolicy", env, seed=seed, policy_kwargs=policy_kwargs)


def clone(args: argparse.Namespace) -> dict[str, Any]:
    strikers_per_game, teacher_team = ARMS[args.arm]
    th.manual_seed(args.seed)
    th.set_num_threads(args.threads)
    teacher = ScriptedPredictor(teacher_team, strikers_per_game - 1)
    model = student_model(strikers_per_game, args.seed, args.actor, args.routed)
    player: Any = RolePredictor(model, strikers_per_game - 1) if args.routed else model
    adapter = model.policy.adapter
    games = team_games(strikers_per_game, args.games)
    record: dict[str, Any] = {
        "arm": args.arm,
        "teacher": teacher_team,
        "seed": args.seed,
        "episodes_per_round": args.episodes,
        "dagger_rounds": args.dagger_rounds,
        "epochs": args.epochs,
        "lr": args.lr,
        "actor": args.actor,
        "routed": args.routed,
        "rounds": [],
    }
    started = time.time()
    recorder = Recorder(teacher)
    record["teacher_play"] = evaluate_team_games(recorder, games, args.episodes, seed=10_000 + args.seed)
    teammates = strikers_per_game - 1

    def labelled(batches: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """New states with the teacher's labels and their roles (each computed once: the rule is deterministic)."""
        states = np.concatenate(batches)
        return (
            states,
            adapter.from_env(teacher.predict(states)[0]),
            with_roles(states, teammates)[:, -len(ROLES) :],
        )

    observations, labels, roles = labelled(recorder.batches)
    for round_index in range(args.dagger_rounds + 1):
        if round_index > 0:  # DAgger: the student's own states, labelled by the teacher
            recorder = Recorder(player)
            play = evaluate_team_games(
                recorder, games, args.episodes, seed=10_000 + 1_000 * round_index + args.seed
            )
            record["rounds"][-1]["student_play_after"] = play
            new = labelled(recorder.batches)
            observations, labels, roles = (
                np.concatenate([old, extra])
                for old, extra in zip((observations, labels, roles), new, strict=True)
            )
        inputs = np.concatenate([observations, roles], axis=1) if args.routed else observations
        history = distill(
            model.policy,
            inputs,
            labels[:, 0].astype(np.int64),
            labels[:, 1:],
            epochs=args.epochs,
            batch_size=512,
            learning_rate=args.lr,
            parameter_weight=PARAMETER_WEIGHT,
            seed=args.seed + round_index,
        )
        record["rounds"].append({"states": len(observations), "last_epoch": history[-1]})
        print(json.dumps({"arm": args.arm, "round": round_index, **record["rounds"][-1]}), flush=True)
    with th.no_grad():
        record["agreement_by_role"] = agreement_by_role(
            model.policy, inputs, roles, labels[:, 0].astype(np.int64)
        )
    print(json.dumps({"arm": args.arm, "agreement_by_role": record["agreement_by_role"]}), flush=True)
    record["seconds_cloning"] = round(time.time() - started, 1)
    out = args.out / f"arm_{args.arm}"
    out.mkdir(parents=True, exist_ok=True)
    model.save(out / "student.zip")
    evaluation_seed = 20_000 + args.seed
    record["evaluation_seed"] = evaluation_seed
    record["student"] = evaluate_team_games(player, games, args.eval_episodes, seed=evaluation_seed)
    record["teacher_eval"] = evaluate_team_games(teacher, games, args.eval_episodes, seed=evaluation_seed)
    record["seconds"] = round(time.time() - started, 1)
    for name in ("student", "teacher_eval"):
        print(json.dumps({"arm": args.arm, name: record[name]}), flush=True)
    (out / "clone.json").write_text(json.dumps(record, indent=1))
    return record


def main(argv: list[str] | None = None) -> dict[str, Any]:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--arm", choices=sorted(ARMS), required=True)
    parser.add_argument("--out", type=Path, required=True, help="the run folder (one sub-folder per arm)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--episodes", type=int, default=300, help="episodes per distillation round")
    parser.add_argument("--dagger-rounds", type=int, default=6)
    parser.add_argument("--epochs", type=int, default=20)
    parser.add_argument("--lr", type=float, default=1e-3)
    parser.add_argument(
        "--actor", type=int, nargs="+", default=ACTOR_ARCH, help="the actor's hidden layer sizes"
    )
    parser.add_argument(
        "--routed",
        action="store_true",
        help="one actor head per own_pass role, the role appended to the observation and routed by it",
    )
    parser.add_argument("--eval-episodes", type=int, default=1000)
    parser.add_argument("--games", type=int, default=16, help="hfo2d games played at once")
    parser.add_argument("--threads", type=int, default=1, help="torch threads")
    parser.add_argument("--smoke", action="store_true", help="tiny settings, seconds")
    args = parser.parse_args(argv)
    if args.smoke:
        args.episodes, args.dagger_rounds, args.epochs, args.eval_episodes, args.games = 2, 1, 1, 2, 2
    for name in ("episodes", "epochs", "eval_episodes", "games"):
        if getattr(args, name) < 1:
            parser.error(f"--{name.replace('_', '-')} must be >= 1, got {getattr(args, name)}")
    if min(args.actor) < 1:
        parser.error(f"--actor sizes must be >= 1, got {args.actor}")
    if args.dagger_rounds < 0:
        parser.error(f"--dagger-rounds must be >= 0, got {args.dagger_rounds}")
    return clone(args)


if __name__ == "__main__":
    main()
