"""Greedy scoring rate of a trained SkillDDPG model when the critic, not the actor, picks the discrete action.

The actor proposes a full flat HFO action; in ``critic`` mode each of the three discrete actions (DASH, TURN,
KICK) is tried with the actor's own parameters and its preference set to +1 and the others to -1 (the form in
which ``exploration_keep_parameters`` stores exploring steps in the replay buffer), and the one the critic values
most is played. ``actor`` mode plays the actor's own argmax (what ``evaluate`` does). Both modes run the same
episodes (same seed, one torch thread). Used for the session-5 probe in benchmarks/RESULTS.md:

    python benchmarks/discrete_choice.py models/e1_empty_goal_fast_seed0 --episodes 200 --seed 0
"""

from __future__ import annotations

import argparse
from collections import Counter

import gymnasium as gym
import numpy as np
import torch as th

from sb3_hfo import SkillDDPG
from sb3_hfo.evaluate import resolve_model, run_episodes, wilson_interval

N_DISCRETE_ACTIONS = 3  # hfo2d's flat action starts with the DASH, TURN and KICK preferences


def choose_action(model: SkillDDPG, obs: np.ndarray, mode: str) -> np.ndarray:
    """The environment action for ``obs (obs_dim,)``: the actor's, or with the critic's choice of discrete action."""
    policy = model.policy
    obs_tensor = th.as_tensor(obs, dtype=th.float32).view(1, -1)
    with th.no_grad():
        action = policy.actor.forward(obs_tensor, policy.route(obs_tensor))  # (1, 8) in [-1, 1]
        if mode == "critic":
            candidates = action.repeat(N_DISCRETE_ACTIONS, 1)
            candidates[:, :N_DISCRETE_ACTIONS] = 2.0 * th.eye(N_DISCRETE_ACTIONS) - 1.0
            q_values = policy.critic(
                obs_tensor.expand(N_DISCRETE_ACTIONS, -1), policy.critic_action(candidates)
            )
            action = candidates[int(q_values.argmax())].view(1, -1)
    return policy.unscale_action(action.numpy())[0]


class _Chooser:
    """``predict`` in SB3's form, so that :func:`sb3_hfo.evaluate.run_episodes` plays the episodes."""

    def __init__(self, model: SkillDDPG, mode: str) -> None:
        self.model, self.mode = model, mode

    def predict(self, obs: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
        return choose_action(self.model, obs, self.mode), None


def status_counts(model: SkillDDPG, env_id: str, episodes: int, seed: int, mode: str) -> dict[str, int]:
    """End-status counts of ``episodes`` greedy episodes (first reset with ``seed``)."""
    env = gym.make(env_id)
    try:
        records = run_episodes(_Chooser(model, mode), env, episodes, seed, deterministic=True, n_skills=1)
    finally:
        env.close()
    return dict(Counter(record.status for record in records))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("model", help="SkillDDPG .zip or rl-zoo3 run folder")
    parser.add_argument("--env", default=None, help="environment id (default: the run's own, else EmptyGoal)")
    parser.add_argument("--episodes", type=int, default=200)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()

    th.set_num_threads(1)
    resolved = resolve_model(args.model)
    env_id = args.env or resolved.env_id or "HFO/EmptyGoal-v0"
    model = SkillDDPG.load(str(resolved.path), device="cpu", buffer_size=1)
    for mode in ("actor", "critic"):
        counts = status_counts(model, env_id, args.episodes, args.seed, mode)
        goals = counts.get("GOAL", 0)
        low, high = wilson_interval(goals, args.episodes)
        print(f"{mode:>6} picks: scoring rate {goals / args.episodes:.3f} [{low:.3f}, {high:.3f}], {counts}")


if __name__ == "__main__":
    main()
