"""Greedy scoring rate of a trained SkillDDPG model when the critic, not the actor, picks the discrete action.

``actor`` mode plays the actor's own argmax (the paper; what ``evaluate`` does by default); ``critic`` mode plays
``HFOPolicy(discrete_choice="critic")``: each of DASH / TURN / KICK is tried at the actor's own parameters with
its preference +1 and the others -1, and the one the critic values most is played. Both modes run the same
episodes (same seed, one torch thread). Used for the session-5 and session-6 probes in benchmarks/RESULTS.md:

    python benchmarks/discrete_choice.py models/e1_empty_goal_fast_seed0 --episodes 200 --seed 0
"""

from __future__ import annotations

import argparse
from collections import Counter
from collections.abc import Sequence

from sb3_hfo.evaluate import load_for_evaluation, model_n_skills, run_episodes, wilson_interval
from sb3_hfo.skill_ddpg.policies import DISCRETE_CHOICES


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("model", help="SkillDDPG .zip or rl-zoo3 run folder")
    parser.add_argument("--env", default=None, help="environment id (default: the run's own)")
    parser.add_argument("--episodes", type=int, default=200)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)

    model, env, _, _, _ = load_for_evaluation(args.model, args.env)
    try:
        for mode in DISCRETE_CHOICES:
            model.policy.discrete_choice = mode
            records = run_episodes(model, env, args.episodes, args.seed, True, model_n_skills(model))
            counts = dict(Counter(record.status for record in records))
            goals = counts.get("GOAL", 0)
            low, high = wilson_interval(goals, args.episodes)
            print(
                f"{mode:>6} picks: scoring rate {goals / args.episodes:.3f} [{low:.3f}, {high:.3f}], {counts}"
            )
    finally:
        env.close()


if __name__ == "__main__":
    main()
