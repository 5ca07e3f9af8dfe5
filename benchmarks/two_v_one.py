"""Two learning strikers against agent2d's goalie (2v1) against one striker alone (1v1), on the same budget (issue
34 item 5).

Both arms start from one 1v1 HybridPPO policy (``--start``, e.g. ``benchmarks/rl_from_clone.py``'s ``final.zip``)
and train it further with the same recipe and the same number of **agent steps** (SB3's ``num_timesteps``: one
per learning striker per cycle, so both arms collect the same number of transitions and make the same PPO updates;
the 2v1 arm plays half as many game cycles, which ``curve.jsonl`` records as ``cycles``):

* ``1v1``: 16 games of ``TeamGame(offense_agents=1, defense_npcs=1)`` (agent2d's goalie; the game of
  ``HFO/Keeper-v1``) as one :class:`sb3_hfo.multi_agent.TeamVecEnv` of 16 slots;
* ``2v1``: 8 games of two strikers against agent2d's goalie, 16 slots, one policy for both strikers (parameter
  sharing). The start policy's first layers (actor and critic) are widened for the teammate's 8 features
  (:func:`sb3_hfo.multi_agent.widen_policy_inputs`, zero weights on them; hfo2d's paper layout puts the teammate's
  block between the 58 basic features and the goalie's), so at step 0 each striker plays exactly the 1v1 policy
  (``start.zip``: the zero-shot 2v1 team).

Recipe (both arms): rl_from_clone.py's fine-tuning settings (:data:`HP`), no pull toward a reference, a critic
warm-up (value loss only) over the first ``--critic-warmup`` steps, since the reward normaliser starts afresh and
the 2v1 critic meets states it has not valued; rewards scaled by a running std of the discounted return
(``VecNormalize``). Reward per striker: ``shaped_gap_refund`` (:mod:`hfo2d.reward`, not HFO's), each from its own
features with the goalie read where ``HFO/Keeper-v1`` has it: its own move-to-ball and first-kickable bonus, 3 x
the ball's progress to the gap beside the goalie (whoever moves it; a lost ball's progress since the agent last had
it is refunded), +5 to both on a goal.

Evaluation (``evaluate``): final models, not the best checkpoint; greedy; the start policy in 1v1, the zero-shot
2v1 team, and each arm's ``final.zip`` in its own team; team goal rate, 95 % Wilson interval, end statuses,
:func:`sb3_hfo.multi_agent.evaluate_team` on ``hfo2d.parallel_env(...)`` with ``--backend hfo2d`` or ``real``.

    python benchmarks/two_v_one.py train --arm 1v1 --start RUN/final.zip --out ~/runs/twovone/s0 --steps 1000000
    python benchmarks/two_v_one.py train --arm 2v1 --start RUN/final.zip --out ~/runs/twovone/s0 --steps 1000000
    python benchmarks/two_v_one.py evaluate --out ~/runs/twovone/s0 --backend hfo2d --episodes 1000
    HOME=/root HFO_DIR=/root/real_hfo/HFO tools/real_hfo/loopback.sh \\
        python benchmarks/two_v_one.py evaluate --out ~/runs/twovone/s0 --backend real --episodes 1000
    python benchmarks/two_v_one.py smoke --out /tmp/smoke   # seconds: what the test runs

Second pass (benchmarks/README.md): ``roles`` measures the ceiling of a scripted no-passing role split
(:class:`RoleSplitTeam`: the striker nearer the ball plays the 1v1 policy, the other idles); ``--reward
shaped_gap_refund_nearest`` pays the ball-pull terms to the striker nearest the ball alone (hfo2d.team); ``--start-rule
noop|clear`` distils that role split into the widened policy before RL (a taught start, ``teach.json``); a ``--start``
that already reads the arm's features (its ``final.zip``) continues the arm.

    python benchmarks/two_v_one.py roles --start RUN/final.zip --out ~/runs/twovone2/roles --episodes 500
    python benchmarks/two_v_one.py train --arm 2v1 --start RUN/final.zip --out OUT --reward shaped_gap_refund_nearest \
        --start-rule noop --teach-lr 3e-4 --teach-epochs 20 --teach-dagger 2
"""

from __future__ import annotations

import argparse
import functools
import json
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
import torch as th
from stable_baselines3.common.vec_env import VecNormalize
from torch import nn

sys.path.insert(0, str(Path(__file__).resolve().parent))  # the sibling script's recorder

from hybrid_ppo_runs import RunRecorder, load_average  # noqa: E402

import hfo2d  # noqa: E402
from hfo2d.features import BALL_ANGLE_COS, BALL_ANGLE_SIN, BALL_PROXIMITY, proximity_distance  # noqa: E402
from hfo2d.team import TeamGame  # noqa: E402
from sb3_hfo.common.routers import BallPlayerRouter  # noqa: E402
from sb3_hfo.hfo import hfo_ball_player_router  # noqa: E402
from sb3_hfo.hybrid_ppo import HybridPPO  # noqa: E402
from sb3_hfo.hybrid_ppo.distill import distill  # noqa: E402
from sb3_hfo.multi_agent import (  # noqa: E402
    evaluate_team,
    evaluate_team_games,
    make_team_vec_env,
    teammate_block_insertion,
    widen_policy_inputs,
)

REWARD = "shaped_gap_refund"
#: the offense rewards a run may choose (--reward): the default; hfo2d's sparse goal reward (1 to every striker on a
#: goal), a team reward that pays no striker for going to the ball itself; or the role-aware team reward
#: (hfo2d.team.NEAREST_PULL_REWARDS: the ball-pull terms to the striker nearest the ball alone; in 1v1 the default);
#: the carry-and-shot reward e6_from_clone_shot was trained with (hfo2d.reward), per striker or role-aware
REWARDS: tuple[str, ...] = (REWARD, "sparse", "shaped_gap_refund_nearest", "carry_shot", "carry_shot_nearest")
#: learning strikers per game in each arm; the goalie is agent2d's (defense_npcs=1) in both
ARMS: dict[str, int] = {"1v1": 1, "2v1": 2}
#: rl_from_clone.py's fine-tuning settings (its s0 run's learning rate)
HP: dict[str, Any] = {
    "n_steps": 256,
    "batch_size": 1024,
    "n_epochs": 10,
    "learning_rate": 2e-4,
    "gamma": 0.99,
    "gae_lambda": 0.95,
    "clip_range": 0.1,
    "ent_coef": 0.0,
    "target_kl": 0.02,
}
#: the evaluations: name -> (arm whose folder holds the model, model file, strikers in the evaluated team)
EVALUATIONS: dict[str, tuple[str, str, int]] = {
    "start_1v1": ("1v1", "start.zip", 1),
    "zero_shot_2v1": ("2v1", "start.zip", 2),
    "final_1v1": ("1v1", "final.zip", 1),
    "final_2v1": ("2v1", "final.zip", 2),
}


#: what the striker that is not nearest the ball does in the scripted role split (``roles``): "noop" dashes with power
#: 0 (stands); "clear" runs straight away from the ball while nearer than CLEAR_DISTANCE, then stands
IDLE_BEHAVIOURS: tuple[str, ...] = ("noop", "clear")
CLEAR_DISTANCE = 10.0  # m; the "clear" idle striker's distance from the ball
#: the flat action's DASH with power 0 (HFO_FLAT_ACTION_LAYOUT: 3 preferences, then DASH power and direction, TURN
#: direction, KICK power and direction, all in [0, 1]; direction 0.5 is 0 degrees)
NOOP_ACTION = np.array([1.0, 0.0, 0.0, 0.0, 0.5, 0.5, 0.0, 0.5], dtype=np.float32)


class RoleSplitTeam:
    """A scripted 2v1 team built from a 1v1 policy: in each game the striker nearer the ball (higher ball proximity,
    feature 53; a tie goes to the first) plays ``policy`` on its features without the teammate's block, i.e.
    exactly as alone against the goalie; the other one does ``idle`` (:data:`IDLE_BEHAVIOURS`). No passing. With
    ``margin`` (m) > 0 both play while their distances to the ball differ by less than it, so that a learner that
    misjudges who is nearer errs toward both going to the ball (the zero-shot team) rather than both idling.

    It acts like a model for :func:`sb3_hfo.multi_agent.evaluate_team_games`, whose batches hold each game's two
    strikers next to each other."""

    def __init__(self, policy: Any, idle: str, margin: float = 0.0) -> None:
        if idle not in IDLE_BEHAVIOURS:
            raise ValueError(f"unknown idle behaviour {idle!r}; choose one of {IDLE_BEHAVIOURS}")
        if not margin >= 0.0:
            raise ValueError(f"margin must be >= 0 metres, got {margin!r}")
        self.policy = policy
        self.idle = idle
        self.margin = float(margin)
        position, count = teammate_block_insertion(0, 1)
        self.teammate_block = np.arange(position, position + count)

    def idle_action(self, observation: np.ndarray) -> np.ndarray:
        """The idle striker's flat action from its own features."""
        action = NOOP_ACTION.copy()
        if self.idle == "clear":
            distance = proximity_distance(float(observation[BALL_PROXIMITY]))
            if distance < CLEAR_DISTANCE:
                ball_deg = np.degrees(np.arctan2(observation[BALL_ANGLE_SIN], observation[BALL_ANGLE_COS]))
                away_deg = (
                    ball_deg + 360.0
                ) % 360.0 - 180.0  # the ball's bearing turned round, in [-180, 180)
                action[3], action[4] = 1.0, (away_deg + 180.0) / 360.0
        return action

    def nearer(self, observations: np.ndarray) -> np.ndarray:
        """For a batch of (games x 2) observations, whether each striker is its game's ball player."""
        proximity = observations[:, BALL_PROXIMITY].reshape(-1, 2)
        first = proximity[:, 0] >= proximity[:, 1]
        nearer = np.stack([first, ~first], axis=1)
        # a distance gap below the margin makes both ball players
        close = (
            np.abs(proximity_distance(proximity[:, 0]) - proximity_distance(proximity[:, 1])) < self.margin
        )
        nearer[close] = True
        return nearer.reshape(-1)

    def predict(
        self, observations: np.ndarray, deterministic: bool = True, **_: Any
    ) -> tuple[np.ndarray, None]:
        observations = np.asarray(observations, dtype=np.float32)
        if observations.ndim != 2 or observations.shape[0] % 2:
            raise ValueError(
                f"RoleSplitTeam needs (games x 2, features) observations, got {observations.shape}"
            )
        playing = self.nearer(observations)
        actions = np.stack([self.idle_action(observation) for observation in observations])
        alone = np.delete(observations[playing], self.teammate_block, axis=1)
        actions[playing], _ = self.policy.predict(alone, deterministic=deterministic)
        return actions, None


def play_pairs(predictor: Any, episodes: int, seed: int, games: int) -> np.ndarray:
    """The observations of ``episodes`` greedy 2v1 hfo2d episodes of ``predictor`` (``games`` at once; game ``g``
    seeded ``seed + g``), each cycle's two strikers in adjacent rows (what :class:`RoleSplitTeam` labels)."""
    tables = [TeamGame(2, 0, 1) for _ in range(games)]
    names = list(tables[0].agent_names)
    observations = [table.reset(seed=seed + index)[0] for index, table in enumerate(tables)]
    active = [index < episodes for index in range(games)]
    started, rows = sum(active), []
    while any(active):
        playing = [index for index, on in enumerate(active) if on]
        batch = np.stack([observations[index][name] for index in playing for name in names])
        rows.append(batch)
        actions, _ = predictor.predict(batch, deterministic=True)
        for position, index in enumerate(playing):
            chosen = dict(zip(names, actions[2 * position : 2 * position + 2], strict=True))
            observations[index], _, terminated, truncated, _ = tables[index].step(chosen)
            if terminated or truncated:
                if started < episodes:
                    started += 1
                    observations[index], _ = tables[index].reset()
                else:
                    active[index] = False
    return np.concatenate(rows)


def teach_role_rule(start: HybridPPO, model: HybridPPO, args: argparse.Namespace) -> dict[str, Any]:
    """``--start-rule IDLE``: before RL, distil :class:`RoleSplitTeam` (``start`` as the ball player, IDLE for the
    other striker) into the widened ``model``'s actor (:func:`sb3_hfo.hybrid_ppo.distill.distill`, the actor only;
    the critic is left to the warm-up): the teacher's own states, then DAgger rounds on the student's states,
    both labelled by the teacher (``--teach-dagger`` rounds). Returns what ``teach.json`` records."""
    teacher = RoleSplitTeam(start, args.start_rule, args.teach_margin)
    adapter = model.policy.adapter
    started = time.time()
    observations = play_pairs(teacher, args.teach_episodes, 30_000 + args.seed, args.games)
    record: dict[str, Any] = {
        "idle": args.start_rule,
        "margin": args.teach_margin,
        "episodes_per_round": args.teach_episodes,
        "lr": args.teach_lr,
        "epochs": args.teach_epochs,
        "rounds": [],
    }
    for round_index in range(1 + args.teach_dagger):
        if round_index > 0:  # DAgger: where the student goes, labelled by the teacher
            seed = 30_000 + 1_000 * round_index + args.seed
            student = play_pairs(model, args.teach_episodes, seed, args.games)
            observations = np.concatenate([observations, student])
        labels = adapter.from_env(teacher.predict(observations)[0])
        history = distill(
            model.policy,
            observations,
            labels[:, 0].astype(np.int64),
            labels[:, 1:],
            epochs=args.teach_epochs,
            batch_size=512,
            learning_rate=args.teach_lr,
            parameter_weight=100.0,  # rl_from_clone.py's default
            seed=args.seed + round_index,
        )
        record["rounds"].append({"states": len(observations), "last_epoch": history[-1]})
        print(json.dumps({"teach_round": round_index, **record["rounds"][-1]}), flush=True)
    record["seconds"] = round(time.time() - started, 1)
    games = [TeamGame(2, 0, 1) for _ in range(args.games)]
    record["greedy_eval"] = evaluate_team_games(
        model, games, args.teach_eval_episodes, seed=40_000 + args.seed
    )
    record["teacher_eval"] = evaluate_team_games(
        teacher, games, args.teach_eval_episodes, seed=40_000 + args.seed
    )
    print(json.dumps({"taught": record["greedy_eval"], "teacher": record["teacher_eval"]}), flush=True)
    return record


def team_env(strikers: int, backend: str, **kwargs: Any) -> Any:
    """The evaluated team: ``strikers`` agents against agent2d's goalie, as a PettingZoo parallel env."""
    return hfo2d.parallel_env(offense_agents=strikers, defense_npcs=1, backend=backend, **kwargs)


def fresh_start_model(env: Any, seed: int) -> HybridPPO:
    """A start policy of rl_from_clone.py's shape (trunk [256, 128, 64], two heads routed by field_half), untrained:
    what ``smoke`` widens and trains when no ``--start`` is given."""
    policy_kwargs = {
        "net_arch": {"pi": [256, 128, 64], "vf": [256, 128]},
        "activation_fn": nn.LeakyReLU,
        "skills": 2,
        "router": "field_half",
        "domain": "hfo",
        "squash_mean": True,
    }
    return HybridPPO("MlpPolicy", env, seed=seed, policy_kwargs=policy_kwargs, **HP)


def build_arm_model(start: HybridPPO, env: Any, strikers: int, args: argparse.Namespace) -> HybridPPO:
    """A HybridPPO on ``env`` with ``start``'s networks, widened for ``strikers - 1`` teammates (zero weights); a
    ``start`` that already reads this team's features (an arm's ``final.zip``, to continue it) is copied as it is,
    with a fresh optimizer, reward normaliser and critic warm-up. With ``--router ball_player`` a two-skill start
    gets the hand-coded role router and a third head (:func:`add_support_skill`)."""
    start_features = start.observation_space.shape[0]
    position, count = teammate_block_insertion(0, strikers - 1)
    if (
        env.observation_space.shape[0] == start_features
    ):  # already this team's policy (a run continued): a copy
        position = 0
    elif env.observation_space.shape[0] != start_features + count:
        raise ValueError(
            f"the start policy reads {start_features} features; a {strikers}-striker team gives "
            f"{env.observation_space.shape[0]}, not {start_features} + {count}: is it a 1v1 policy against the goalie "
            "(or this arm's own model, to continue it)?"
        )

    def new_model(policy_kwargs: dict[str, Any]) -> HybridPPO:
        return HybridPPO(
            "MlpPolicy",
            env,
            seed=args.seed,
            policy_kwargs=policy_kwargs,
            tensorboard_log=None if args.smoke else str(args.out / f"arm_{args.arm}" / "tb"),
            critic_warmup_steps=args.critic_warmup,
            **args.hp,
        )

    model = new_model(start.policy_kwargs)
    widen_policy_inputs(start.policy, model.policy, position)
    if args.router == "ball_player" and model.policy.n_skills == 2:
        router = hfo_ball_player_router(strikers - 1)
        routed = new_model({**start.policy_kwargs, "skills": router.n_skills, "router": router})
        add_support_skill(model.policy, routed.policy)
        return routed
    if args.router == "ball_player" and not isinstance(model.policy.skill_router, BallPlayerRouter):
        raise ValueError(
            f"--router ball_player adds a support skill to a two-skill field-half start; this start has "
            f"{model.policy.n_skills} skill(s) routed by {model.policy.skill_router!r}"
        )
    return model


#: the support head's start (``--router ball_player``): a near-certain TURN (logit SUPPORT_TURN_LOGIT against 0)
#: by 0 degrees, which leaves the striker where it stands, as the scripted role split's NOOP idle does; its
#: parameter means are tanh(bias) on the policy's [-1, 1] scale: DASH power at -3 (a soft dash, about 0.25 of 100,
#: if a DASH is drawn), every direction at 0 (0 degrees), KICK power at 0
SUPPORT_TURN_LOGIT = 6.0
SUPPORT_BIAS = {"DASH": 0.0, "TURN": SUPPORT_TURN_LOGIT, "KICK": 0.0}
SUPPORT_DASH_POWER_BIAS = -3.0


def add_support_skill(source: Any, target: Any) -> None:
    """Copy ``source`` (a widened two-skill field-half policy) into ``target`` (the same networks with three skills,
    routed by a :class:`~sb3_hfo.common.routers.BallPlayerRouter`): the trunks, critic and skill heads 0 and 1 as
    they are, so the striker that judges itself nearest the ball plays exactly as ``source`` does; the support head
    (skill 2) starts at zero weights and :data:`SUPPORT_BIAS` (stand still) with ``source``'s skill-0 log standard
    deviations. PPO then trains all three heads.

    :raises ValueError: networks that differ elsewhere, or a layout without DASH, TURN and KICK.
    """
    support = target.skill_router.support_skill
    source_state, target_state = source.state_dict(), target.state_dict()
    extra = {key for key in target_state if key.startswith(f"heads.{support}.")}
    if source_state.keys() != target_state.keys() - extra:
        raise ValueError(
            f"the policies differ beyond the support head: {sorted(source_state.keys() ^ (target_state.keys() - extra))}"
        )
    names = list(target.adapter.names)
    if names != list(SUPPORT_BIAS):
        raise ValueError(f"the support head's start is for HFO's DASH, TURN, KICK; this layout is {names}")
    state = dict(source_state)
    linear_bias = th.zeros_like(target_state[f"heads.{support}.linear.bias"])
    linear_bias[: len(names)] = th.tensor(list(SUPPORT_BIAS.values()))
    linear_bias[len(names)] = SUPPORT_DASH_POWER_BIAS  # DASH's power comes first among the parameters
    state[f"heads.{support}.linear.bias"] = linear_bias
    state[f"heads.{support}.linear.weight"] = th.zeros_like(target_state[f"heads.{support}.linear.weight"])
    state[f"heads.{support}.log_std"] = source_state["heads.0.log_std"].clone()
    for key in extra - set(state):  # e.g. a state-dependent std layer: zero, as a new head's is
        state[key] = th.zeros_like(target_state[key])
    target.load_state_dict(state)


def train(args: argparse.Namespace) -> Path:
    """One arm: widen, save ``start.zip``, train ``--steps`` agent steps, save ``final.zip``; returns its folder."""
    strikers = ARMS[args.arm]
    folder = args.out / f"arm_{args.arm}"
    if args.start_rule is not None and strikers != 2:
        raise SystemExit("error: --start-rule teaches the 2v1 role split; the 1v1 arm has no teammate")
    if args.router is not None and strikers < 2:
        raise SystemExit("error: --router splits roles between teammates; the 1v1 arm has none")
    if args.router is not None and args.start_rule is not None:
        raise SystemExit("error: --router and --start-rule are two ways to the role split; choose one")
    if (folder / "curve.jsonl").exists():
        raise SystemExit(f"error: {folder} already holds a run (curve.jsonl); choose another --out")
    folder.mkdir(parents=True, exist_ok=True)
    th.set_num_threads(args.threads)
    slots = args.n_envs
    if slots % strikers:
        raise SystemExit(
            f"error: --n-envs ({slots}) must be a multiple of the strikers per game ({strikers})"
        )
    env = make_team_vec_env(
        slots // strikers, offense_agents=strikers, defense_npcs=1, seed=args.seed, reward=args.reward
    )
    env = VecNormalize(env, norm_obs=False, norm_reward=True, gamma=args.hp["gamma"])
    if args.start is None:
        start = fresh_start_model(make_team_vec_env(1, offense_agents=1, defense_npcs=1), args.seed)
    else:
        start = HybridPPO.load(args.start, device="cpu")
    model = build_arm_model(start, env, strikers, args)
    if args.start_rule is not None:
        (folder / "teach.json").write_text(json.dumps(teach_role_rule(start, model, args), indent=1))
    model.save(folder / "start.zip")
    record = {
        "arm": args.arm,
        "strikers": strikers,
        "games": slots // strikers,
        "slots": slots,
        "budget": "agent steps (num_timesteps); game cycles = agent steps / strikers",
        "reward": args.reward,
        "start": str(args.start) if args.start else "untrained (smoke)",
        "start_rule": args.start_rule,
        "router": args.router,
        "skills": model.policy.n_skills,
        "hp": args.hp,
        "critic_warmup": args.critic_warmup,
        "steps": args.steps,
        "seed": args.seed,
        "command": " ".join([Path(sys.argv[0]).name, *sys.argv[1:]]),
        "load1_at_start": load_average(),
        "torch_threads": args.threads,
    }
    (folder / "run.json").write_text(json.dumps(record, indent=1))

    def curve_evaluation(policy_model: HybridPPO) -> dict[str, Any]:  # the arm's own team, hfo2d
        env_ = team_env(strikers, "hfo2d")
        try:
            result = evaluate_team(policy_model, env_, args.eval_episodes, seed=10_000 + args.seed)
        finally:
            env_.close()
        result["cycles"] = int(policy_model.num_timesteps) // strikers
        return result

    recorder = RunRecorder(folder, args.minutes, args.eval_every, curve_evaluation)
    model.learn(args.steps, callback=recorder, progress_bar=False)
    recorder.row(final=True)
    env.close()
    return folder


def evaluate(args: argparse.Namespace) -> dict[str, Any]:
    """Each chosen evaluation (:data:`EVALUATIONS`) over ``--episodes`` greedy episodes with ``--backend``, each
    written to ``OUT/eval_{backend}_{name}.json`` (so that several can run at once); returns them by name."""
    th.set_num_threads(1)
    results = {}
    for name in args.which:
        arm, file, strikers = EVALUATIONS[name]
        model_path = args.out / f"arm_{arm}" / file
        if not model_path.exists():
            print(f"skipping {name}: no {model_path}", flush=True)
            continue
        model = HybridPPO.load(model_path, device="cpu")
        run_record = args.out / f"arm_{arm}" / "run.json"
        run = json.loads(run_record.read_text()) if run_record.exists() else {}
        if name == "zero_shot_2v1" and run.get("start_rule"):
            name = "taught_start_2v1"  # the 2v1 start of a --start-rule run is the taught one, not zero-shot
        elif name == "zero_shot_2v1" and run.get("router"):
            name = "routed_start_2v1"  # the start of a --router run splits roles by its hand-coded router
        started = time.time()
        if args.backend == "hfo2d" and args.games > 1:  # many games per predict call: the same statistics
            games = [TeamGame(strikers, 0, 1) for _ in range(args.games)]
            result = evaluate_team_games(model, games, args.episodes, seed=args.seed)
            result.update(games=args.games, model=str(model_path), backend=args.backend, seed=args.seed)
            result.update(seconds=round(time.time() - started, 1), load1=round(load_average(), 2))
            results[name] = result
            (args.out / f"eval_{args.backend}_{name}.json").write_text(json.dumps(result, indent=1))
            print(json.dumps({name: result}), flush=True)
            continue
        env = team_env(strikers, args.backend)
        goals = 0

        def tally(played: int, status: str, name: str = name) -> None:  # a running count for long real runs
            nonlocal goals
            goals += status == "GOAL"
            if played % 100 == 0:
                print(json.dumps({name: {"episodes": played, "goals": goals}}), flush=True)

        try:
            result = evaluate_team(model, env, args.episodes, seed=args.seed, on_episode=tally)
        finally:
            env.close()
        result.update(
            model=str(model_path),
            backend=args.backend,
            seed=args.seed,
            seconds=round(time.time() - started, 1),
            load1=round(load_average(), 2),
        )
        results[name] = result
        (args.out / f"eval_{args.backend}_{name}.json").write_text(json.dumps(result, indent=1))
        print(json.dumps({name: result}), flush=True)
    return results


def roles(args: argparse.Namespace) -> dict[str, Any]:
    """The ceiling of a no-passing role split: ``--start`` as :class:`RoleSplitTeam` with each idle behaviour, the
    zero-shot team (both strikers play it) and the policy alone in 1v1 (the last two unless ``--no-zero-shot``), over ``--episodes`` greedy hfo2d 2v1 episodes each
    (``--games`` at once); written to ``OUT/roles.json``."""
    th.set_num_threads(1)
    policy = HybridPPO.load(args.start, device="cpu")
    suffix = f", both within {args.margin:g} m" if args.margin else ""
    teams: dict[str, Any] = {
        f"nearer plays, other {idle}{suffix}": RoleSplitTeam(policy, idle, args.margin) for idle in args.idle
    }
    if args.own_features:
        for idle in args.idle:
            teams[f"each judges from its own features, other {idle}"] = OwnFeaturesRoleSplitTeam(policy, idle)
    if args.zero_shot:
        teams["both play (zero-shot)"] = RoleSplitTeamBoth(policy)
    if args.zero_shot:
        teams["alone (1v1)"] = policy
    results: dict[str, Any] = {}
    for name, team in teams.items():
        started = time.time()
        games = [TeamGame(1 if team is policy else 2, 0, 1) for _ in range(args.games)]
        result = evaluate_team_games(team, games, args.episodes, seed=args.seed)
        result.update(seconds=round(time.time() - started, 1), load1=round(load_average(), 2))
        results[name] = result
        print(json.dumps({name: result}), flush=True)
    record = {"start": str(args.start), "episodes": args.episodes, "seed": args.seed, "games": args.games}
    record["margin"] = args.margin
    args.out.mkdir(parents=True, exist_ok=True)
    file = f"roles_margin{args.margin:g}.json" if args.margin else "roles.json"
    (args.out / file).write_text(json.dumps({**record, "results": results}, indent=1))
    return results


class RoleSplitTeamBoth(RoleSplitTeam):
    """The zero-shot team as a :class:`RoleSplitTeam`: both strikers play the 1v1 policy on their 1v1 features."""

    def __init__(self, policy: Any) -> None:
        super().__init__(policy, "noop")

    def nearer(self, observations: np.ndarray) -> np.ndarray:
        return np.ones(observations.shape[0], dtype=bool)


@functools.cache
def _pair_router() -> BallPlayerRouter:
    """The 2v1 pair's role router, built once (``judges_itself_nearer`` runs every step of a roles evaluation)."""
    return hfo_ball_player_router(1)


def judges_itself_nearer(observations: np.ndarray) -> np.ndarray:
    """Whether each striker of a 2v1 game is nearer the ball than its teammate, from its **own** features only
    (paper layout, 66 features): :meth:`sb3_hfo.common.routers.BallPlayerRouter.nearest` of the very router that
    ``train --router ball_player`` gives the pair (:func:`sb3_hfo.hfo.hfo_ball_player_router`). A tie counts as
    nearer (both play), so the rule errs toward the zero-shot team rather than both idling. A teammate that HFO does
    not list (outside the HFO half, x <= 0: an all-zero block, whose bearing is no unit vector) counts as farther,
    said outright rather than left to what its zeros happen to compute (a first version that read the bearing as an
    angle put such a teammate 'MAX_HFO_DIST / 2' straight ahead, and both strikers judged the other nearer and
    idled until the time ran out in 73 of 1,000 games)."""
    return np.asarray(_pair_router().nearest(np.asarray(observations, dtype=np.float64)))


class OwnFeaturesRoleSplitTeam(RoleSplitTeam):
    """:class:`RoleSplitTeam` decided per striker from its own features (:func:`judges_itself_nearer`), as a
    decentralised rule (a hand-coded router, like the paper's ``field_half``) would decide, instead of comparing
    the two strikers' ball proximities across the pair."""

    def nearer(self, observations: np.ndarray) -> np.ndarray:
        return judges_itself_nearer(observations)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)
    training = commands.add_parser("train", help="train one arm")
    smoke = commands.add_parser("smoke", help="seconds: both arms and their evaluation at tiny budgets")
    for sub in (training, smoke):
        sub.add_argument("--out", type=Path, required=True, help="the run folder (one sub-folder per arm)")
        sub.add_argument("--seed", type=int, default=0)
        sub.add_argument(
            "--start", type=Path, default=None, help="the 1v1 HybridPPO policy both arms start from"
        )
        sub.add_argument("--steps", type=int, default=1_000_000, help="agent steps per arm")
        sub.add_argument(
            "--minutes", type=float, default=120.0, help="wall-clock budget of an arm's training"
        )
        sub.add_argument("--n-envs", type=int, default=16, help="slots (learning strikers) per rollout step")
        sub.add_argument("--eval-every", type=int, default=250_000)
        sub.add_argument("--eval-episodes", type=int, default=100)
        sub.add_argument(
            "--critic-warmup", type=int, default=100_000, help="agent steps of value-only updates"
        )
        sub.add_argument("--hp", default="{}", help="JSON: HybridPPO hyperparameters over the defaults")
        sub.add_argument("--threads", type=int, default=1, help="torch threads")
        sub.add_argument("--reward", choices=REWARDS, default=REWARD, help="every striker's reward")
        sub.add_argument(
            "--start-rule",
            choices=IDLE_BEHAVIOURS,
            default=None,
            help="2v1: before RL, distil the scripted role split (the nearer striker plays the start policy, the "
            "other this idle behaviour) into the widened policy: a taught start",
        )
        sub.add_argument(
            "--router",
            choices=("ball_player",),
            default=None,
            help="2v1: the hand-coded role router (sb3_hfo.hfo.hfo_ball_player_router): the striker that judges "
            "itself nearer the ball from its own features plays the start's two field-half heads, the other a "
            "third, support head that starts standing still; PPO trains all three",
        )
        sub.add_argument("--teach-episodes", type=int, default=400, help="episodes per distillation round")
        sub.add_argument("--teach-epochs", type=int, default=10)
        sub.add_argument("--teach-margin", type=float, default=0.0, help="m: the taught rule's margin")
        sub.add_argument(
            "--teach-dagger", type=int, default=1, help="DAgger rounds after the teacher's states"
        )
        sub.add_argument("--teach-lr", type=float, default=1e-4)
        sub.add_argument("--teach-eval-episodes", type=int, default=300)
        sub.add_argument("--games", type=int, default=16, help="hfo2d games at once while teaching")
    training.add_argument("--arm", choices=sorted(ARMS), required=True)
    evaluating = commands.add_parser("evaluate", help="evaluate the start, zero-shot and final models")
    evaluating.add_argument("--out", type=Path, required=True, help="the run folder that train wrote")
    evaluating.add_argument("--backend", choices=("hfo2d", "real"), default="hfo2d")
    evaluating.add_argument("--episodes", type=int, default=1000)
    evaluating.add_argument("--seed", type=int, default=0)
    evaluating.add_argument(
        "--games",
        type=int,
        default=16,
        help="hfo2d: games played at once (game g seeded seed + g; 1: one game)",
    )
    evaluating.add_argument("--which", nargs="+", choices=sorted(EVALUATIONS), default=list(EVALUATIONS))
    role_split = commands.add_parser("roles", help="the scripted role split's 2v1 goal rate (no training)")
    role_split.add_argument("--start", type=Path, required=True, help="the 1v1 HybridPPO policy")
    role_split.add_argument("--out", type=Path, required=True, help="folder for roles.json")
    role_split.add_argument("--episodes", type=int, default=500)
    role_split.add_argument("--seed", type=int, default=0)
    role_split.add_argument("--games", type=int, default=16, help="hfo2d games played at once")
    role_split.add_argument("--idle", nargs="+", choices=IDLE_BEHAVIOURS, default=list(IDLE_BEHAVIOURS))
    role_split.add_argument("--no-zero-shot", dest="zero_shot", action="store_false")
    role_split.add_argument(
        "--own-features",
        action="store_true",
        help="also the split decided by each striker from its own features (OwnFeaturesRoleSplitTeam)",
    )
    role_split.add_argument(
        "--margin", type=float, default=0.0, help="m: both play within it (RoleSplitTeam)"
    )
    args = parser.parse_args(argv)
    if args.command == "roles":
        roles(args)
        return
    if args.command == "evaluate":
        evaluate(args)
        return
    args.hp = {**HP, **json.loads(args.hp)}
    args.smoke = args.command == "smoke"
    if args.smoke:
        args.steps, args.eval_every, args.eval_episodes, args.n_envs, args.critic_warmup = (
            2048,
            1024,
            4,
            4,
            1024,
        )
        args.hp["batch_size"] = 256
        args.teach_episodes, args.teach_epochs, args.teach_eval_episodes, args.games = 4, 1, 4, 2
        start_rule, router = args.start_rule, args.router
        for arm in ARMS:
            args.arm = arm
            args.start_rule = start_rule if ARMS[arm] == 2 else None  # the taught start is the 2v1 arm's
            args.router = router if ARMS[arm] == 2 else None  # as is the routed one
            train(args)
        evaluate(
            argparse.Namespace(
                out=args.out, backend="hfo2d", episodes=4, seed=0, games=2, which=list(EVALUATIONS)
            )
        )
        return
    train(args)


if __name__ == "__main__":
    main()
