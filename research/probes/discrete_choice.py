"""Greedy scoring rate of a trained SkillDDPG model when the critic, not the actor, picks the discrete action.

``actor`` mode plays the actor's own argmax (the paper; what ``evaluate`` does by default); ``critic`` mode plays
``HFOPolicy(acting=(CriticChoice(), ...))``: each of DASH / TURN / KICK is tried at the actor's own parameters with
its preference +1 and the others -1, and the one the critic values most is played. Both modes run the same
episodes (same seed, one torch thread), each with the model's other acting strategies. Used for the session-5 and session-6 probes in research/RESULTS.md:

    python research/probes/discrete_choice.py models/e1_empty_goal_fast_seed0 --episodes 200 --seed 0

``--agreement`` then plays ``--episodes`` more greedy episodes with the critic choosing and tabulates, over their
steps, the actor's own preferred discrete action against the one played. Under ``parameter_loss="chosen"`` the
actor trains only its preferred action's parameters, so where the two differ the parameters played are ones it
never trained in that state (session 12):

    python research/probes/discrete_choice.py models/x15_static_keeper_relative_kick_seed0 --episodes 100 --agreement
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence
from typing import Any

import numpy as np
import torch as th

from sb3_hfo.cli.evaluate import episodes_parser
from sb3_hfo.evaluation import load_for_evaluation, model_n_skills, run_episodes, wilson_interval
from sb3_hfo.skill_ddpg.acting import ActingStrategy, CriticChoice

ACTION_NAMES = ("DASH", "TURN", "KICK")
MODES = ("actor", "critic")


def acting_with(acting: Sequence[ActingStrategy], mode: str) -> tuple[ActingStrategy, ...]:
    """``acting`` with the critic's choice on (``mode="critic"``) or off (``"actor"``), its other strategies kept."""
    others = tuple(strategy for strategy in acting if not isinstance(strategy, CriticChoice))
    return (CriticChoice(), *others) if mode == "critic" else others


def preference_agreement(model: Any, env: Any, episodes: int, seed: int) -> Counter[tuple[int, int]]:
    """Steps of greedy critic's-choice episodes counted by (the actor's preferred action, the action played)."""
    policy = model.policy
    policy.acting = acting_with(policy.acting, "critic")
    pairs: Counter[tuple[int, int]] = Counter()
    obs, _ = env.reset(seed=seed)
    for _ in range(episodes):
        done = False
        while not done:
            observation = th.as_tensor(np.asarray(obs, dtype=np.float32)[None])
            with th.no_grad():
                actions = policy.actor.forward(observation, policy.route(observation))
                played = policy.critic_choice(observation, actions)
            pairs[(int(actions[0, :3].argmax()), int(played[0, :3].argmax()))] += 1
            obs, _, terminated, truncated, _ = env.step(model.predict(obs, deterministic=True)[0])
            done = bool(terminated or truncated)
        obs, _ = env.reset()
    return pairs


def main(argv: Sequence[str] | None = None) -> None:
    parser = episodes_parser(__doc__.splitlines()[0], default_episodes=200)
    parser.add_argument(
        "--agreement",
        action="store_true",
        help="also tabulate the actor's preferred action against the played one",
    )
    args = parser.parse_args(argv)

    model, env, _, _, _ = load_for_evaluation(args.model, args.env)
    try:
        for mode in MODES:
            model.policy.acting = acting_with(model.policy.acting, mode)
            records = run_episodes(model, env, args.episodes, args.seed, True, model_n_skills(model))
            counts = dict(Counter(record.status for record in records))
            goals = counts.get("GOAL", 0)
            low, high = wilson_interval(goals, args.episodes)
            print(
                f"{mode:>6} picks: scoring rate {goals / args.episodes:.3f} [{low:.3f}, {high:.3f}], {counts}"
            )
        if args.agreement:
            pairs = preference_agreement(model, env, args.episodes, args.seed)
            total = sum(pairs.values())
            for (preferred, played), count in sorted(pairs.items()):
                print(
                    f"agreement: actor prefers {ACTION_NAMES[preferred]:<4} critic plays "
                    f"{ACTION_NAMES[played]:<4} {count / total:6.1%}"
                )
            differ = sum(count for (preferred, played), count in pairs.items() if preferred != played)
            print(
                f"agreement: {total} steps, the played action is not the actor's preferred one in {differ / total:.1%}"
            )
    finally:
        env.close()


if __name__ == "__main__":
    main()
