"""Where a keeper task's last kicks were aimed: the intended crossing point on the goal line, by episode outcome.

``python research/probes/shot_aim.py MODEL [--env HFO/StaticKeeper-v0] [--episodes 300] [--seed 0]``

For each episode the greedy agent plays, the script keeps its last executed kick and computes, from the ball's
position before the kick, where the ball would cross the goal line (x = 52.5 m):

* ``intended``: along the commanded direction (body angle + kick direction, the action's last entry);
* ``actual``: along the ball's velocity after the kick (the kick noise included; the ball noise of later cycles not).

It prints, per outcome (GOAL, CAPTURED_BY_DEFENSE), the number of episodes, the mean distance of the kick from the
goal centre and quantiles of |intended y| and |actual y| (m from the goal's centre line), plus the std of
actual - intended. A keeper standing at the goal centre catches the ball within 1.085 m of him, so captures with
|intended y| near 0 are shots aimed at him, not shots the noise pushed into him.
Session 10 (300 episodes, seed 0): x11 (seed 0) captured 55 with median |intended y| 0.76 m, goals 2.67 m;
x12 (the "shaped_gap" reward, seed 0) captured 28, goals aimed at a median 3.53 m.
"""

from __future__ import annotations

import argparse
import math
from dataclasses import dataclass

import gymnasium as gym
import numpy as np

import hfo2d  # noqa: F401  (registers the HFO/* ids)
from hfo2d.features import PITCH_HALF_LENGTH
from sb3_hfo import SkillDDPG
from sb3_hfo.models import load_model

QUANTILES = (10, 25, 50, 75, 90)
OUTCOMES = ("GOAL", "CAPTURED_BY_DEFENSE")
KICK_DIRECTION_INDEX = 7  # flat action layout: [..., kick_power, kick_direction], direction in [0, 1]


@dataclass
class LastKick:
    """An episode's last executed kick: ball position before it (m), intended and actual goal-line y (m)."""

    ball_x: float
    ball_y: float
    intended_y: float
    actual_y: float


def goal_line_y(x: float, y: float, heading_rad: float) -> float:
    """y where a ray from (x, y) along ``heading_rad`` crosses x = 52.5; NaN if it does not head toward the goal."""
    cos_heading = math.cos(heading_rad)
    if cos_heading <= 1e-3 or x >= PITCH_HALF_LENGTH:
        return math.nan
    return y + (PITCH_HALF_LENGTH - x) * math.tan(heading_rad)


def play(model: SkillDDPG, env: gym.Env, episodes: int, seed: int) -> dict[str, list[LastKick]]:
    """Greedy episodes; each outcome's list of last kicks (episodes without a kick are left out)."""
    kicks: dict[str, list[LastKick]] = {outcome: [] for outcome in OUTCOMES}
    obs, info = env.reset(seed=seed)
    for _ in range(episodes):
        last: LastKick | None = None
        done = False
        while not done:
            action, _ = model.predict(obs, deterministic=True)
            ball_x, ball_y = info["ball"][:2]
            body_deg = info["player"][4]
            obs, _, terminated, truncated, info = env.step(action)
            if info["action"] == "KICK" and info["action_success"]:
                kick_deg = -180.0 + 360.0 * float(np.asarray(action).reshape(-1)[KICK_DIRECTION_INDEX])
                velocity_x, velocity_y = info["ball"][2:4]
                last = LastKick(
                    ball_x,
                    ball_y,
                    goal_line_y(ball_x, ball_y, math.radians(body_deg + kick_deg)),
                    goal_line_y(ball_x, ball_y, math.atan2(velocity_y, velocity_x)),
                )
            done = terminated or truncated
        if last is not None and info["status"] in kicks:
            kicks[info["status"]].append(last)
        obs, info = env.reset()
    return kicks


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("model", help="SkillDDPG .zip")
    parser.add_argument("--env", default="HFO/StaticKeeper-v0")
    parser.add_argument("--episodes", type=int, default=300)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    model = load_model(args.model, device="cpu", buffer_size=1)
    env = gym.make(args.env)
    kicks = play(model, env, args.episodes, args.seed)
    env.close()
    print(f"{args.model}: {args.episodes} episodes of {args.env} (seed {args.seed})")
    print(f"quantiles {QUANTILES} of |y| at the goal line (m)")
    for outcome, rows in kicks.items():
        if not rows:
            print(f"{outcome}: none")
            continue
        distance = np.mean([math.hypot(PITCH_HALF_LENGTH - k.ball_x, k.ball_y) for k in rows])
        intended = np.array([k.intended_y for k in rows])
        actual = np.array([k.actual_y for k in rows])
        print(
            f"{outcome}: {len(rows)} episodes, kicked from {distance:.1f} m (mean)\n"
            f"  |intended y| {np.round(np.nanpercentile(np.abs(intended), QUANTILES), 2)}\n"
            f"  |actual y|   {np.round(np.nanpercentile(np.abs(actual), QUANTILES), 2)}\n"
            f"  std(actual - intended) {np.nanstd(actual - intended):.2f} m"
        )


if __name__ == "__main__":
    main()
