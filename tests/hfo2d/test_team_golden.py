"""Golden rollouts of the team game (hfo2d.team.TeamGame), hashed bit for bit, so that a speed-up of the team game,
its features or agent2d's field defenders and goalie cannot change a decision or a number unnoticed.

Each case plays a seeded TeamGame for a fixed number of cycles (resetting without a seed at every episode end, so
that the NPCs' client state carries over as in real HFO) and feeds into one SHA-256, per cycle: every agent's
observation bytes, reward, reward terms, action name and status; ``terminated`` / ``truncated`` and the status;
every player's and the ball's full state (position, velocity, body, stamina, effort, recovery, tackle and catch
counters); the world's random-number position; and every NPC's command, its branch (field defenders) and home
position. The expected digests were recorded on main bb23766 before the team speed work (branch ``teamspeed``); a
change of any of them means the behaviour changed. If a change is intended, re-record them (``python
tests/hfo2d/test_team_golden.py`` prints them) and say why in the commit.

Policies: "random" (uniform flat actions, drawn in advance) and "wild" (offense agents run at the ball on the true
state and, once it is kickable, kick it with a random power and direction: tackles, catches, holds, force kicks,
goals and balls out happen; defense agents random).
"""

from __future__ import annotations

import hashlib
import math
import struct
from collections import Counter
from typing import Any

import numpy as np
import pytest

from hfo2d.team import TeamGame

# (name, TeamGame kwargs, seed, cycles, policy)
CASES: tuple[tuple[str, dict[str, Any], int, int, str], ...] = (
    ("2v2-noise-random", {"offense_agents": 2, "defense_npcs": 2}, 0, 1500, "random"),
    ("2v2-noise-wild", {"offense_agents": 2, "defense_npcs": 2}, 1, 1500, "wild"),
    ("2v2-nonoise-wild", {"offense_agents": 2, "defense_npcs": 2, "noise": False}, 2, 1200, "wild"),
    ("2v3-hfo-wild", {"offense_agents": 2, "defense_npcs": 3, "feature_set": "hfo"}, 3, 1000, "wild"),
    ("4v5-noise-random", {"offense_agents": 4, "defense_npcs": 5}, 4, 600, "random"),
    ("4v5-noise-wild", {"offense_agents": 4, "defense_npcs": 5}, 5, 800, "wild"),
    (
        "2v2-defense-agent-shaped",
        {"offense_agents": 2, "defense_agents": 1, "defense_npcs": 1, "defense_reward": "shaped"},
        6,
        800,
        "wild",
    ),
    (
        "1v2-scripted-defense-agent-hfo",
        {
            "offense_agents": 0,
            "scripted_strikers": 1,
            "defense_agents": 1,
            "defense_npcs": 1,
            "feature_set": "hfo",
        },
        7,
        800,
        "random",
    ),
    (
        "2v2-high-level-wild",
        {"offense_agents": 2, "defense_npcs": 2, "feature_set": "high_level"},
        8,
        800,
        "wild",
    ),
)

# (digest, episode ends) of each case, recorded on main bb23766 before the team speed work
GOLDEN: dict[str, tuple[str, dict[str, int]]] = {
    "2v2-noise-random": (
        "ccf70ebba839fa173d637a173ffbd2cd8facac08b8d337939cd50962d7747451",
        {"CAPTURED_BY_DEFENSE": 16, "OUT_OF_TIME": 5},
    ),
    "2v2-noise-wild": (
        "6a6b8e618e9ee7c9295a02ab8c94de26742a4f32341f97bb853a744b54283940",
        {"OUT_OF_BOUNDS": 27, "CAPTURED_BY_DEFENSE": 6},
    ),
    "2v2-nonoise-wild": (
        "40510a9b37e107e1b7cccefd2a082aa96f511937ea7c94f37ffeca2a42f35358",
        {"CAPTURED_BY_DEFENSE": 5, "OUT_OF_BOUNDS": 19},
    ),
    "2v3-hfo-wild": (
        "2e866bf6bf514b98891d93d944023157b0d74a6be49eb5adf2b145b0e669aa96",
        {"OUT_OF_BOUNDS": 20, "CAPTURED_BY_DEFENSE": 5},
    ),
    "4v5-noise-random": (
        "c7ea18c8f8a19851b57901eaeed53eab5cfd650cca368bc070b2f7c0479d8f08",
        {"OUT_OF_TIME": 4, "CAPTURED_BY_DEFENSE": 2},
    ),
    "4v5-noise-wild": (
        "bc4d279f50dffae6028889472de2725529201899058ee225761abaa429684ca5",
        {"OUT_OF_BOUNDS": 15, "CAPTURED_BY_DEFENSE": 6},
    ),
    "2v2-defense-agent-shaped": (
        "40d19e8d95079af41dde47f1ae6fbd04389e41b2062408d246c89319bd580c71",
        {"OUT_OF_BOUNDS": 11, "CAPTURED_BY_DEFENSE": 1},
    ),
    "1v2-scripted-defense-agent-hfo": (
        "711ea267119d3880d92638bf2b4f419fa38dd6d824c239d615347b0aedabac60",
        {"GOAL": 6, "CAPTURED_BY_DEFENSE": 1},
    ),
    "2v2-high-level-wild": (
        "cf68bca1c8c3f390e3a307982e0c18b92cc525c0393d71332016332fc8119b55",
        {"OUT_OF_BOUNDS": 13, "CAPTURED_BY_DEFENSE": 5},
    ),
}


def _pack_floats(values: Any) -> bytes:
    return struct.pack(f"<{len(values)}d", *[float(v) for v in values])


def _wild_action(game: TeamGame, name: str, draw: np.ndarray) -> np.ndarray:
    """An offense agent's flat action: kick with the random power and direction of ``draw`` when the ball is
    within the kickable distance, else dash at the ball (true state, relative to the body)."""
    player = game.agent(name).player
    ball = game.world.ball
    dx, dy = ball.x - player.x, ball.y - player.y
    relative = math.degrees(math.atan2(dy, dx)) - player.body_deg
    relative = (relative + 180.0) % 360.0 - 180.0
    action = draw.copy()
    if math.hypot(dx, dy) < game.params.kickable_area:
        action[:3] = (0.0, 0.0, 1.0)
    else:
        action[:3] = (1.0, 0.0, 0.0)
        action[3] = 1.0
        action[4] = (relative + 180.0) / 360.0
    return action


def _hash_world(digest: Any, game: TeamGame) -> None:
    world = game.world
    for player in world.players:
        digest.update(
            _pack_floats(
                (
                    player.x,
                    player.y,
                    player.vx,
                    player.vy,
                    player.body_deg,
                    player.stamina,
                    player.effort,
                    player.recovery,
                    player.tackle_cycles,
                    player.catch_ban,
                )
            )
        )
    ball = world.ball
    digest.update(_pack_floats((ball.x, ball.y, ball.vx, ball.vy, world.cycle)))
    digest.update(struct.pack("<q", world._next_uniform))
    for _, npc in game.defense_npcs:
        command = npc.last_command
        if command is None:
            digest.update(b"none")
        else:
            digest.update(command.kind.encode() + _pack_floats((command.a, command.b, command.foul)))
        digest.update(getattr(npc, "last_branch", "").encode())
        home = getattr(npc, "last_home", None)
        digest.update(b"-" if home is None else _pack_floats(home))


def rollout(kwargs: dict[str, Any], seed: int, cycles: int, policy: str) -> tuple[str, Counter[str]]:
    """The digest of ``cycles`` cycles of ``TeamGame(**kwargs)`` under ``policy``, and the end statuses seen."""
    game = TeamGame(**kwargs, seed=seed)
    rng = np.random.default_rng(2000 + seed)
    draws = {agent.name: rng.random((cycles, agent.layout.size), dtype=np.float32) for agent in game.agents}
    digest = hashlib.sha256()
    statuses: Counter[str] = Counter()
    observations, _ = game.reset(seed=seed)
    for name in game.agent_names:
        digest.update(observations[name].tobytes())
    _hash_world(digest, game)
    for index in range(cycles):
        actions = {}
        for agent in game.agents:
            draw = draws[agent.name][index]
            wild = policy == "wild" and agent.offense
            actions[agent.name] = _wild_action(game, agent.name, draw) if wild else draw
        observations, rewards, terminated, truncated, infos = game.step(actions)
        for name in game.agent_names:
            info = infos[name]
            digest.update(observations[name].tobytes())
            digest.update(_pack_floats((rewards[name], *info["reward_terms"].values())))
            digest.update(
                f"{info['status']}|{info['action']}|{info['action_success']}|{info['kickable']}".encode()
            )
        digest.update(bytes((terminated, truncated)))
        _hash_world(digest, game)
        if terminated or truncated:
            statuses[game.status] += 1
            observations, _ = game.reset()
            for name in game.agent_names:
                digest.update(observations[name].tobytes())
            _hash_world(digest, game)
    game.close()
    return digest.hexdigest(), statuses


@pytest.mark.parametrize("case", CASES, ids=[case[0] for case in CASES])
def test_team_golden_rollout(case: tuple[str, dict[str, Any], int, int, str]) -> None:
    name, kwargs, seed, cycles, policy = case
    digest, statuses = rollout(kwargs, seed, cycles, policy)
    assert (digest, dict(statuses)) == GOLDEN[name], (
        f"{name}: behaviour changed (digest {digest}, {statuses})"
    )


def test_team_golden_rollouts_cover_the_defenders_play() -> None:
    """The cases together end episodes in every way, so the hashes pin the referee's every rule."""
    seen: Counter[str] = Counter()
    for _, statuses in GOLDEN.values():
        seen.update(statuses)
    assert {"GOAL", "CAPTURED_BY_DEFENSE", "OUT_OF_BOUNDS", "OUT_OF_TIME"} <= set(seen), seen


if __name__ == "__main__":  # print the digests (to re-record GOLDEN)
    for name, kwargs, seed, cycles, policy in CASES:
        digest, statuses = rollout(kwargs, seed, cycles, policy)
        print(f'    "{name}": ("{digest}", {dict(statuses)}),')
