"""What a trained critic thinks of shooting past the keeper: Q against the kick direction at the agent's shots.

For each model, plays greedy episodes on a goalie task and keeps each episode's last successful kick (the shot)
when the episode ended in a GOAL or CAPTURED_BY_DEFENSE. At every shot it asks the critic for Q(s, KICK at the
actor's power, direction = goalie bearing + offset) for offsets of -30..30 degrees, and records the offset the
actor chose. Both angles are relative to the agent's body, as rcssserver's kick direction and HFO's bearing
features are (observation 58, 59: sin, cos of the goalie's bearing). Prints, per model and outcome, the mean
critic profile (Q minus its maximum over the offsets) and where the actor aimed, and writes a two-panel PNG.

Session 8 (research/RESULTS.md) compared x3's critic with x9's (Fourier features of the directions):

    python research/probes/critic_kick_scan.py models/x3_static_keeper_critic_choice_fast_seed0/HFO-StaticKeeper-v0.zip \
        MODEL2.zip --labels x3 x9 --episodes 300 --out research/figures/critic_kick_scan.png
"""

from __future__ import annotations

import argparse
from dataclasses import dataclass, field
from pathlib import Path

import gymnasium as gym
import numpy as np
import torch as th

import hfo2d  # noqa: F401  (registers the HFO/* environments)
from hfo2d.action_layout import HFO_FLAT_ACTION_LAYOUT
from hfo2d.features import feature_names
from hfo2d.hfo_env import KICK
from sb3_hfo import SkillDDPG
from sb3_hfo.models import load_model

_FEATURES = feature_names(num_opponents=1)
GOALIE_BEARING_SIN, GOALIE_BEARING_COS = (
    _FEATURES.index("goalie_angle_sin"),
    _FEATURES.index("goalie_angle_cos"),
)
KICK_DIRECTION_INDEX = HFO_FLAT_ACTION_LAYOUT.action_direction(KICK)  # the kick direction in the flat action
OFFSETS_DEG = np.arange(-30, 31, 1)
OUTCOMES = ("GOAL", "CAPTURED_BY_DEFENSE")


@dataclass
class Shots:
    """Per outcome: critic profiles ``(n, len(OFFSETS_DEG))`` (Q minus the profile's max) and the actor's offsets."""

    profiles: dict[str, list[np.ndarray]] = field(default_factory=lambda: {o: [] for o in OUTCOMES})
    actor_offsets: dict[str, list[float]] = field(default_factory=lambda: {o: [] for o in OUTCOMES})


def wrap_degrees(angle: np.ndarray | float) -> np.ndarray | float:
    return (np.asarray(angle) + 180.0) % 360.0 - 180.0


def scan_shot(model: SkillDDPG, obs: np.ndarray) -> tuple[np.ndarray, float]:
    """The critic's profile over ``OFFSETS_DEG`` around the goalie bearing, and the actor's own offset (degrees)."""
    policy = model.policy
    obs_t = th.as_tensor(obs[None], dtype=th.float32)
    goalie_deg = float(np.degrees(np.arctan2(obs[GOALIE_BEARING_SIN], obs[GOALIE_BEARING_COS])))
    with th.no_grad():
        action = policy.actor(obs_t)
        kick = action.repeat(len(OFFSETS_DEG), 1)
        kick[:, :3] = -1.0
        kick[:, KICK] = 1.0
        directions = wrap_degrees(goalie_deg + OFFSETS_DEG) / 180.0
        kick[:, KICK_DIRECTION_INDEX] = th.as_tensor(directions, dtype=th.float32)
        q = policy.critic(obs_t.repeat(len(OFFSETS_DEG), 1), policy.critic_action(kick)).squeeze(1).numpy()
    actor_offset = float(wrap_degrees(action[0, KICK_DIRECTION_INDEX].item() * 180.0 - goalie_deg))
    return q - q.max(), actor_offset


def collect(model_path: str, env_id: str, episodes: int, seed: int) -> Shots:
    model = load_model(model_path, device="cpu", buffer_size=1)
    env = gym.make(env_id)
    shots = Shots()
    obs, info = env.reset(seed=seed)
    for _ in range(episodes):
        shot_obs = None
        done = False
        while not done:
            action, _ = model.predict(obs, deterministic=True)
            before = obs
            obs, _, terminated, truncated, info = env.step(action)
            if info["action"] == "KICK" and info["action_success"]:
                shot_obs = before
            done = terminated or truncated
        if shot_obs is not None and info["status"] in OUTCOMES and shot_obs[GOALIE_BEARING_COS] != 0:
            profile, offset = scan_shot(model, shot_obs)
            shots.profiles[info["status"]].append(profile)
            shots.actor_offsets[info["status"]].append(offset)
        obs, info = env.reset()
    env.close()
    return shots


def report(label: str, shots: Shots) -> None:
    shown = OFFSETS_DEG[::5]
    print(f"\n{label}")
    print(
        "  outcome               shots  |actor offset| median  mean Q - max Q at offset "
        + " ".join(f"{d:+d}" for d in shown)
    )
    for outcome in OUTCOMES:
        profiles, offsets = shots.profiles[outcome], np.abs(shots.actor_offsets[outcome])
        if not profiles:
            print(f"  {outcome:<20} {0:>6}")
            continue
        mean = np.mean(profiles, axis=0)[::5]
        print(
            f"  {outcome:<20} {len(profiles):>6}  {np.median(offsets):>19.1f}  "
            + " ".join(f"{v:.2f}" for v in mean)
        )


def plot(results: list[tuple[str, Shots]], out: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4))
    bins = np.arange(-30, 31, 2.5)
    for (label, shots), color in zip(
        results, ("tab:blue", "tab:orange", "tab:green", "tab:red"), strict=False
    ):
        for outcome, style in zip(OUTCOMES, ("-", "--"), strict=True):
            if shots.profiles[outcome]:
                name = f"{label}, {outcome.lower().replace('_', ' ')} ({len(shots.profiles[outcome])})"
                left.plot(
                    OFFSETS_DEG, np.mean(shots.profiles[outcome], axis=0), style, color=color, label=name
                )
                right.hist(
                    np.clip(shots.actor_offsets[outcome], -30, 30),
                    bins=bins,
                    histtype="step",
                    linestyle=style,
                    color=color,
                    label=name,
                )
    left.set(
        xlabel="kick direction - goalie bearing (deg)",
        ylabel="critic: Q - max over offsets",
        title="critic's value of the shot by direction",
    )
    right.set(
        xlabel="actor's kick direction - goalie bearing (deg)", ylabel="shots", title="where the actor aims"
    )
    left.legend(fontsize=7)
    right.legend(fontsize=7)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110)
    print(f"\nwrote {out}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("models", nargs="+", help="SkillDDPG .zip files")
    parser.add_argument("--labels", nargs="+", help="one per model (default: file names)")
    parser.add_argument("--env", default="HFO/StaticKeeper-v0")
    parser.add_argument("--episodes", type=int, default=300)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", type=Path, help="PNG to write (default: none)")
    args = parser.parse_args()
    labels = args.labels or [Path(m).parent.name for m in args.models]
    if len(labels) != len(args.models):
        parser.error(f"--labels: {len(labels)} labels for {len(args.models)} models")
    results = [
        (label, collect(m, args.env, args.episodes, args.seed))
        for label, m in zip(labels, args.models, strict=True)
    ]
    for label, shots in results:
        report(label, shots)
    if args.out is not None:
        plot(results, args.out)


if __name__ == "__main__":
    main()
