"""Cost of one SkillDDPG update with ``parameter_loss="each_action"`` against ``"chosen"``, same run, interleaved.

Both models use x15 / x19's networks and options (256-128-64, masked parameters, critic's choice, no kick without
the ball, direction features relative to the keeper, P-DQN's max target, Monte Carlo mixing 0.2, batch 128) on
``HFO/StaticKeeper-v0``, one torch thread. Each fills its replay buffer with ``--fill`` steps of ``learn``, then
``train(--updates)`` is timed for each in turn, ``--repeats`` rounds; medians are reported (session 12):

    python research/probes/parameter_loss_cost.py --updates 200 --repeats 5
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Sequence

import gymnasium as gym
import torch as th

import sb3_hfo  # noqa: F401  (registers the HFO/* environments)
from sb3_hfo import SkillDDPG
from sb3_hfo.skill_ddpg.acting import CriticChoice, KickMask
from sb3_hfo.skill_ddpg.encoding import DirectionFeatures
from sb3_hfo.skill_ddpg.skill_ddpg import PARAMETER_LOSSES

POLICY_KWARGS = dict(
    net_arch=[256, 128, 64],
    weight_init_std=0.08,
    mask_unused_parameters=True,
    acting=(CriticChoice(), KickMask()),
    critic_action_encoding=DirectionFeatures(
        frequencies=(1, 2, 4, 8, 16, 32), relative_to=("goalie", "goal_post_top", "goal_post_bottom")
    ),
    domain="hfo",
)
BATCH_SIZE = 128


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--updates", type=int, default=200, help="updates per timed train() call")
    parser.add_argument("--repeats", type=int, default=5, help="interleaved rounds; the median is reported")
    parser.add_argument(
        "--fill", type=int, default=2100, help="learn() steps before timing (>= 2000 warm-up)"
    )
    args = parser.parse_args(argv)
    th.set_num_threads(1)
    models = {}
    for loss in PARAMETER_LOSSES:
        model = SkillDDPG(
            "HFOPolicy",
            gym.make("HFO/StaticKeeper-v0"),
            batch_size=BATCH_SIZE,
            learning_starts=min(2000, args.fill - 1),
            buffer_size=10_000,
            discrete_target="max",
            mc_mixing=0.2,
            parameter_loss=loss,
            policy_kwargs=POLICY_KWARGS,
            seed=0,
        )
        model.learn(args.fill)
        models[loss] = model
    seconds: dict[str, list[float]] = {loss: [] for loss in models}
    for _ in range(args.repeats):
        for loss, model in models.items():
            start = time.perf_counter()
            model.train(args.updates, BATCH_SIZE)
            seconds[loss].append((time.perf_counter() - start) / args.updates)
    medians = {loss: statistics.median(values) for loss, values in seconds.items()}
    for loss, median in medians.items():
        print(f"{loss:>11}: {median * 1e3:.2f} ms per update")
    print(f"each_action / chosen: {medians['each_action'] / medians['chosen']:.2f}")


if __name__ == "__main__":
    main()
