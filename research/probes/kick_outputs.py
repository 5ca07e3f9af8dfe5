"""Print a trained SkillDDPG actor's raw action at the first kickable state of a few greedy HFO episodes.

Shows whether the actor's tanh outputs sit at their bounds (+-1 on SB3's buffer scale): for the flat HFO action
[pref_dash, pref_turn, pref_kick, dash_power, dash_dir, turn_dir, kick_power, kick_dir], a kick direction of +1
means +180 degrees (kicking backwards). Used for the saturation remarks in research/RESULTS.md:

    python research/probes/kick_outputs.py models/e1_empty_goal_fast_seed0/HFO-EmptyGoal-v0.zip --episodes 6
"""

from __future__ import annotations

import argparse

import gymnasium as gym
import numpy as np
import torch as th

from sb3_hfo.models import load_model

KICKABLE_FEATURE_INDEX = 12  # hfo2d's low-level features: +1 when the ball is kickable


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("model", help="SkillDDPG .zip")
    parser.add_argument("--env", default="HFO/EmptyGoal-v0")
    parser.add_argument("--episodes", type=int, default=6)
    parser.add_argument("--first-seed", type=int, default=1000, help="episode i is reset with first_seed + i")
    args = parser.parse_args()

    model = load_model(args.model, buffer_size=1)
    env = gym.make(args.env)
    np.set_printoptions(precision=2, suppress=True)
    for episode in range(args.episodes):
        obs, _ = env.reset(seed=args.first_seed + episode)
        for step in range(1, 501):
            if obs[KICKABLE_FEATURE_INDEX] > 0:
                with th.no_grad():
                    raw = model.policy.actor(th.as_tensor(obs[None], dtype=th.float32))[0].numpy()
                print(f"episode {episode} step {step}: actor output {raw}")
                break
            action, _ = model.predict(obs, deterministic=True)
            obs, _, terminated, truncated, _ = env.step(action)
            if terminated or truncated:
                print(f"episode {episode}: ended before the ball was kickable")
                break


if __name__ == "__main__":
    main()
