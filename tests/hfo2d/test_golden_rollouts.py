"""Golden rollouts: long episodes of every registered env hashed bit for bit, so that a speed-up (or any other
refactoring) of the simulator, the features, the rewards or agent2d's goalie cannot change behaviour unnoticed.

Each case steps an env for a fixed number of steps (resetting without a seed at every episode end, so that
Keeper-v1's goalie carries its state over as in real HFO) and feeds into one SHA-256, per step: the observation's
bytes, the reward, ``terminated`` / ``truncated``, ``info["status"]``, the player / ball / keeper tuples, the reward
terms and, for agent2d's goalie, its world model (the fullstate numbers it decided on), its command and the
world's random-number position. The expected digests were recorded on the code before the speed work (branch
``speed``); a change of any of them means the behaviour changed. If a change of behaviour is intended, re-record
them (``python tests/test_golden_rollouts.py`` prints the digests) and say why in the commit.
"""

from __future__ import annotations

import hashlib
import struct
from collections import Counter
from typing import Any

import numpy as np
import pytest

import hfo2d  # noqa: F401  (registers the ids)
from hfo2d.hfo_env import HFOEnv
from hfo2d.strikers import chase_ball, flat_action, make_striker, perceive

# the goalie's world-model numbers hashed each step (GoalieView fields; the attacker ones are lazy)
VIEW_FIELDS = (
    "cycle",
    "px",
    "py",
    "vx",
    "vy",
    "body",
    "stamina",
    "effort",
    "recovery",
    "bx",
    "by",
    "wx",
    "wy",
    "true_wx",
    "true_wy",
    "ox",
    "oy",
    "ux",
    "uy",
    "obody",
    "opp_tackle_count",
    "kick_opp",
    "self_kickable",
    "lk_not_ours",
    "play_on",
)

# (name, HFOEnv kwargs, seed, steps, policy): policy "random" (uniform flat actions), "wild" (runs to the ball and
# kicks it anywhere: out of bounds, at the goalie, into the goal) or a striker name of hfo2d.strikers
CASES: tuple[tuple[str, dict[str, Any], int, int, str], ...] = (
    ("v1-noise-random", {"task": "keeper", "goalie": "agent2d"}, 0, 1500, "random"),
    ("v1-nonoise-random", {"task": "keeper", "goalie": "agent2d", "noise": False}, 1, 1500, "random"),
    ("v1-noise-wild", {"task": "keeper", "goalie": "agent2d"}, 2, 1500, "wild"),
    ("v1-nonoise-wild", {"task": "keeper", "goalie": "agent2d", "noise": False}, 15, 1000, "wild"),
    ("v1-noise-mid_shot", {"task": "keeper", "goalie": "agent2d"}, 3, 1500, "mid_shot"),
    ("v1-noise-soft_dribble", {"task": "keeper", "goalie": "agent2d"}, 4, 1500, "soft_dribble"),
    ("v1-nonoise-cross_shot", {"task": "keeper", "goalie": "agent2d", "noise": False}, 5, 1200, "cross_shot"),
    ("v1-noise-goalie_runner", {"task": "keeper", "goalie": "agent2d"}, 6, 1200, "goalie_runner"),
    ("v1-nonoise-long_shot", {"task": "keeper", "goalie": "agent2d", "noise": False}, 7, 1000, "long_shot"),
    ("v1-noise-delayed_shot", {"task": "keeper", "goalie": "agent2d"}, 8, 1000, "delayed_shot"),
    (
        "v1-skill-hfo-brisk",
        {"task": "keeper", "goalie": "agent2d", "keeper_skill": 0.7, "feature_set": "hfo"},
        9,
        1000,
        "brisk_dribble",
    ),
    ("v0-noise-random", {"task": "keeper"}, 10, 1000, "random"),
    ("v0-noise-close_shot", {"task": "keeper"}, 11, 1000, "close_shot"),
    ("static-noise-mid_shot", {"task": "static_keeper"}, 12, 600, "mid_shot"),
    ("empty-noise-random", {"task": "empty_goal"}, 13, 1000, "random"),
    ("empty-nonoise-long_shot", {"task": "empty_goal", "noise": False}, 14, 600, "long_shot"),
)

# (digest, episode ends) of each case, recorded on main 6a888af before the speed work
GOLDEN: dict[str, tuple[str, dict[str, int]]] = {
    "v1-noise-random": (
        "095b475f8ef470988094ab8a40d56fb7836bc0be1cfb058b10d9d8b23a625f5a",
        {"OUT_OF_TIME": 15},
    ),
    "v1-nonoise-random": (
        "cb7dd34c28cf20e921db36fb01b643667a3f8b8bf09b7ebbf37563160fb6a59d",
        {"OUT_OF_TIME": 15},
    ),
    "v1-noise-wild": (
        "aa1c52306092b54774e864cbaff980fb9dfb1159d5e2dbeb4e7fec8399f975fd",
        {"OUT_OF_BOUNDS": 17, "CAPTURED_BY_DEFENSE": 2},
    ),
    "v1-nonoise-wild": (
        "422fece906df5b6cee2faf7e2b7e85228c0139e9664af53fabec156847cc1a10",
        {"OUT_OF_BOUNDS": 17, "CAPTURED_BY_DEFENSE": 2},
    ),
    "v1-noise-mid_shot": (
        "0fe442a6efab3cec7685095b47161d69e68340f9aa1153f8f48207ec0558a259",
        {"CAPTURED_BY_DEFENSE": 22, "GOAL": 1},
    ),
    "v1-noise-soft_dribble": (
        "74f162259a363447250df6beb31ec5acb3bd2e98c907be538084da916a1db013",
        {"GOAL": 14},
    ),
    "v1-nonoise-cross_shot": (
        "125c5ebe6e603de46690aff44d1a09cfa4ee81ca22c2adb3aa1830a0146db19d",
        {"CAPTURED_BY_DEFENSE": 12, "GOAL": 4},
    ),
    "v1-noise-goalie_runner": (
        "d82481ce0527e4a26c61793ad6c5ca3615e3f7354d1f15032d7d6e0a6c0fcde0",
        {"CAPTURED_BY_DEFENSE": 16},
    ),
    "v1-nonoise-long_shot": (
        "635c211a8a62c93a70588c41f6f96cb03794be895acc7b54474b6cc6d141fddd",
        {"CAPTURED_BY_DEFENSE": 14, "GOAL": 1},
    ),
    "v1-noise-delayed_shot": (
        "6a1261b567ffe665e60aa9347ad9e59fd399cef70feddea33bd0cfd8c7028dca",
        {"CAPTURED_BY_DEFENSE": 11, "GOAL": 3},
    ),
    "v1-skill-hfo-brisk": (
        "faaa8afbb88ffa97ef8caa54de81e05f43a338a1f7a167299ce24bb17a1c90fc",
        {"CAPTURED_BY_DEFENSE": 11},
    ),
    "v0-noise-random": (
        "a9453be0c8c050b31f8acc80a666c682b2700ba71d6335bb36124fde38b3531b",
        {"OUT_OF_TIME": 9},
    ),
    "v0-noise-close_shot": (
        "e8437fd523908c0ba27735d845758042859a0ddedea6ae4481a1be94bd2baade",
        {"CAPTURED_BY_DEFENSE": 14},
    ),
    "static-noise-mid_shot": (
        "066d24b67910f6f8e74dcd1a980419c1734582b749cd6041454c21aa757557c8",
        {"GOAL": 5, "CAPTURED_BY_DEFENSE": 3},
    ),
    "empty-noise-random": (
        "f6a7ab7dd439e1574dc58e2e21b9eb28d00f520a14c00c9499e93d0dcca1d050",
        {"OUT_OF_TIME": 9},
    ),
    "empty-nonoise-long_shot": (
        "5b2fa7ff8944bacd04569c07a53df18eb573b1d2fb9e5cd035e16145f837a7e0",
        {"GOAL": 9},
    ),
}


def _pack_floats(values: Any) -> bytes:
    return struct.pack(f"<{len(values)}d", *[float(v) for v in values])


def _wild_action(obs: np.ndarray, draw: np.ndarray) -> np.ndarray:
    """Chase the ball; once it is kickable, kick it with the random power and direction of ``draw`` (8 uniforms)."""
    percept = perceive(obs)
    if percept.kickable:
        action = draw.copy()
        action[:3] = (0.0, 0.0, 1.0)
        return action
    return flat_action(chase_ball(percept, 52.5, 0.0))


def rollout(kwargs: dict[str, Any], seed: int, steps: int, policy: str) -> tuple[str, Counter[str]]:
    """The digest of ``steps`` steps of ``HFOEnv(**kwargs)`` under ``policy``, and the end statuses seen."""
    env = HFOEnv(**kwargs)
    digest = hashlib.sha256()
    statuses: Counter[str] = Counter()
    rng = np.random.default_rng(1000 + seed)
    draws = rng.random((steps, 8), dtype=np.float32)
    striker = make_striker(policy) if policy not in ("random", "wild") else None
    obs, info = env.reset(seed=seed)
    if striker is not None:
        striker.reset()
    digest.update(obs.tobytes())
    goalie = env._keeper_policy if env.goalie == "agent2d" else None
    for index in range(steps):
        if striker is not None:
            action = striker(obs)
        elif policy == "wild":
            action = _wild_action(obs, draws[index])
        else:
            action = draws[index]
        obs, reward, terminated, truncated, info = env.step(action)
        digest.update(obs.tobytes())
        digest.update(_pack_floats((reward,)))
        digest.update(bytes((terminated, truncated, info["action_success"], info["kickable"])))
        digest.update(info["status"].encode())
        digest.update(info["action"].encode())
        digest.update(_pack_floats(info["player"] + info["ball"] + info.get("keeper", ())))
        digest.update(_pack_floats(tuple(info["reward_terms"].values()) + (info["kick_power"],)))
        digest.update(struct.pack("<q", env.world._next_uniform))
        if goalie is not None:
            view = goalie.last_view
            if view is not None:
                digest.update(_pack_floats(tuple(getattr(view, name) for name in VIEW_FIELDS)))
            command = goalie.last_command
            if command is None:
                digest.update(b"none")
            else:
                digest.update(command.kind.encode() + _pack_floats((command.a, command.b, command.foul)))
        if terminated or truncated:
            statuses[info["status"]] += 1
            obs, info = env.reset()
            if striker is not None:
                striker.reset()
            digest.update(obs.tobytes())
    env.close()
    return digest.hexdigest(), statuses


@pytest.mark.parametrize("case", CASES, ids=[case[0] for case in CASES])
def test_golden_rollout(case: tuple[str, dict[str, Any], int, int, str]) -> None:
    name, kwargs, seed, steps, policy = case
    digest, statuses = rollout(kwargs, seed, steps, policy)
    assert (digest, dict(statuses)) == GOLDEN[name], (
        f"{name}: behaviour changed (digest {digest}, {statuses})"
    )


def test_golden_rollouts_cover_every_ending() -> None:
    """The Keeper-v1 cases together end episodes in every way (goals, catches, out of bounds, timeouts)."""
    seen: Counter[str] = Counter()
    for name, (_, statuses) in GOLDEN.items():
        if name.startswith("v1-"):
            seen.update(statuses)
    assert {"GOAL", "CAPTURED_BY_DEFENSE", "OUT_OF_BOUNDS", "OUT_OF_TIME"} <= set(seen), seen


if __name__ == "__main__":  # print the digests (to re-record GOLDEN)
    for name, kwargs, seed, steps, policy in CASES:
        digest, statuses = rollout(kwargs, seed, steps, policy)
        print(f'    "{name}": ("{digest}", {dict(statuses)}),')
