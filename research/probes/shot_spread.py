"""How far the server's ball noise scatters a shot sideways, by distance: the figures behind evaluate's shot bins.

``python research/probes/shot_spread.py [--speed 2.8] [--shots 20000] [--seed 0]``

Each cycle, as rcssserver moves the ball (hfo2d.physics): v += polar(U(0, ball_rand*|v|), U(-pi, pi)), then
p += v, then v *= ball_decay. A shot starts at the origin along +x; the script prints, for each distance, the share
of shots that reach that x and the standard deviation of their y there (m). Session 9 (speed 2.8 m/cycle, seed 0):
20 m 0.73 m, 30 m 1.35 m, 40 m 2.15 m, 45 m 2.54 m with 72 % reaching.
"""

from __future__ import annotations

import argparse

import numpy as np

from hfo2d.physics import ServerParams

DISTANCES_M = (10.0, 20.0, 30.0, 40.0, 45.0)
MAX_CYCLES = 200


def spread(distance: float, speed: float, shots: int, rng: np.random.Generator) -> tuple[float, float]:
    """(share of shots reaching x = distance, std of their y there in m) for shots of ``speed`` m/cycle."""
    params = ServerParams()
    position = np.zeros((shots, 2))
    velocity = np.tile([speed, 0.0], (shots, 1))
    y_at = np.full(shots, np.nan)
    for _ in range(MAX_CYCLES):
        noise = params.ball_rand * np.hypot(velocity[:, 0], velocity[:, 1]) * rng.random(shots)
        angle = rng.uniform(-np.pi, np.pi, shots)
        velocity = velocity + np.stack([noise * np.cos(angle), noise * np.sin(angle)], axis=1)
        moved = position + velocity
        crossing = (position[:, 0] < distance) & (moved[:, 0] >= distance) & np.isnan(y_at)
        fraction = (distance - position[crossing, 0]) / (moved[crossing, 0] - position[crossing, 0])
        y_at[crossing] = position[crossing, 1] + fraction * (moved[crossing, 1] - position[crossing, 1])
        position = moved
        velocity *= params.ball_decay
    reached = ~np.isnan(y_at)
    return float(reached.mean()), float(np.std(y_at[reached])) if reached.any() else float("nan")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speed", type=float, default=2.8, help="initial ball speed, m/cycle")
    parser.add_argument("--shots", type=int, default=20000)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    print(f"{'distance (m)':>12} {'reaching':>9} {'sideways std (m)':>17}")
    for distance in DISTANCES_M:
        reaching, std = spread(distance, args.speed, args.shots, rng)
        print(f"{distance:12.0f} {reaching:9.1%} {std:17.2f}")


if __name__ == "__main__":
    main()
