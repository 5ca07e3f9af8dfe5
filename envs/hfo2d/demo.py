"""Watch the scripted striker (``hfo2d.heuristic``) play: ``python -m hfo2d.demo``.

Example::

    python -m hfo2d.demo --env HFO/Keeper-v1 --episodes 5 --render-mode human --seed 0

Prints each episode's outcome and, at the end, the scoring rate.
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence

import gymnasium as gym

import hfo2d  # (importing it registers the HFO/* environments)
from hfo2d.heuristic import heuristic

#: Every hfo2d task, HFO's own goalie (Keeper-v1) included.
ENV_IDS = tuple(hfo2d.ENV_IDS)


def run_demo(env_id: str, episodes: int, render_mode: str | None, seed: int, verbose: bool = True) -> float:
    """Play ``episodes`` episodes of ``env_id`` with the heuristic; returns the fraction that end in a goal."""
    env = gym.make(env_id, render_mode=render_mode)
    goals = 0
    try:
        for episode in range(episodes):
            obs, info = env.reset(seed=seed + episode)
            # "human" mode draws itself on reset/step (Gymnasium convention); rgb_array frames are requested.
            if render_mode == "rgb_array":
                env.render()
            steps = 0
            episode_return = 0.0
            while True:
                obs, reward, terminated, truncated, info = env.step(heuristic(env, obs))
                steps += 1
                episode_return += float(reward)
                if render_mode == "rgb_array":
                    env.render()
                if terminated or truncated:
                    break
            goals += info["status"] == "GOAL"
            if verbose:
                print(
                    f"episode {episode:3d}: {info['status']:<20s} steps {steps:4d} return {episode_return:7.2f}"
                )
    finally:
        env.close()
    rate = goals / max(episodes, 1)
    if verbose:
        print(f"{env_id}: scored {goals}/{episodes} = {rate:.1%}")
    return rate


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(
        description="Render hfo2d's scripted striker and print its scoring rate."
    )
    parser.add_argument("--env", default="HFO/EmptyGoal-v0", choices=ENV_IDS, help="environment id")
    parser.add_argument("--episodes", type=int, default=5, help="number of episodes")
    parser.add_argument(
        "--render-mode",
        default="human",
        choices=("human", "rgb_array", "none"),
        help="'human' opens a window; 'rgb_array' renders off-screen; 'none' does not render",
    )
    parser.add_argument("--seed", type=int, default=0, help="seed of the first episode (then seed + 1, ...)")
    args = parser.parse_args(argv)
    render_mode = None if args.render_mode == "none" else args.render_mode
    run_demo(args.env, args.episodes, render_mode, args.seed)


if __name__ == "__main__":
    main()
