"""HFO/Keeper-v1 as a whole: the agent2d goalie inside HFOEnv (fast path, seeds, carry-over, skill, catches)."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import hfo2d  # noqa: F401  (registers the envs)
import hfo2d.agent2d.goalie as goalie_module
from hfo2d.agent2d.intercept import build_intercept_table
from hfo2d.heuristic import heuristic


def play(env, episodes: int, seed: int) -> list[tuple]:
    """Goalie positions and commands of ``episodes`` heuristic-striker episodes."""
    trace: list[tuple] = []
    obs, _ = env.reset(seed=seed)
    for episode in range(episodes):
        if episode:
            obs, _ = env.reset()
        done = False
        while not done:
            obs, _, terminated, truncated, info = env.step(heuristic(env, obs))
            command = env._keeper_policy.last_command
            trace.append((info["keeper"], None if command is None else (command.kind, command.a, command.b)))
            done = terminated or truncated
        trace.append(info["status"])
    return trace


@pytest.mark.parametrize("noise", [False, True])
def test_the_fast_intercept_path_decides_exactly_as_the_full_table(monkeypatch, noise: bool) -> None:
    """The goalie builds a table that stops at its fastest entry and the full one only for Body_Intercept;
    with the full table in every cycle the play must be identical."""
    fast = play(gym.make("HFO/Keeper-v1", noise=noise).unwrapped, 6, seed=3)

    def full_table(view, player_rand=None, ball_rand=None, full=True):
        return build_intercept_table(view, player_rand, ball_rand, full=True)

    monkeypatch.setattr(goalie_module, "build_intercept_table", full_table)
    slow = play(gym.make("HFO/Keeper-v1", noise=noise).unwrapped, 6, seed=3)
    assert fast == slow
    assert any(step[1] is not None and step[1][0] == "dash" for step in fast if isinstance(step, tuple))


def test_seeds_repeat_and_the_goalie_body_carries_over_without_one() -> None:
    env = gym.make("HFO/Keeper-v1").unwrapped
    first = play(env, 2, seed=11)
    again = play(env, 2, seed=11)  # reset(seed=...) starts the goalie afresh
    assert first == again
    # without a seed the next episode starts from the body angle the goalie ended with (after the wait frame)
    env.reset(seed=5)
    for _ in range(30):
        _, _, terminated, truncated, _ = env.step(env.action_space.sample())
        if terminated or truncated:
            break
    placed: list[float] = []
    place = env.world.place_player

    def record(player, x, y, body_deg, vx=0.0, vy=0.0):
        if player is env.keeper:
            placed.append(body_deg)
        place(player, x, y, body_deg, vx, vy)

    env.world.place_player = record
    wait_frame = env._agent2d_wait_frame
    bodies_after_wait: list[float] = []

    def wait_and_record() -> None:
        wait_frame()
        bodies_after_wait.append(env.keeper.body_deg)

    env._agent2d_wait_frame = wait_and_record
    env.reset()
    assert placed == bodies_after_wait and len(placed) == 1
    env.reset(seed=5)  # a seed: the first-episode rule (facing its own goal or the field)
    assert placed[-1] in (0.0, -180.0) and len(bodies_after_wait) == 1


def test_skill_zero_is_a_goalie_that_never_acts() -> None:
    env = gym.make("HFO/Keeper-v1", keeper_skill=0.0).unwrapped
    obs, _ = env.reset(seed=0)
    start = env.keeper.x, env.keeper.y, env.keeper.body_deg
    for _ in range(60):
        obs, _, terminated, truncated, _ = env.step(heuristic(env, obs))
        assert env._keeper_policy.last_command is None
        if terminated or truncated:
            break
    assert (env.keeper.x, env.keeper.y, env.keeper.body_deg) == start


def test_the_goalie_catches_a_ball_in_reach_and_the_referee_captures() -> None:
    """A ball 1.2 m in front of the goalie inside its area: agent2d sends a catch (the ban being over), the server
    puts the goalie 0.385 m from the ball, and the referee captures at the next step."""
    env = gym.make("HFO/Keeper-v1", noise=False).unwrapped
    env.reset(
        seed=0, options={"player": (20.0, 20.0, 0.0), "ball": (30.0, 0.0), "keeper": (52.5, 0.0, 180.0)}
    )
    world, keeper = env.world, env.keeper
    world.place_player(keeper, 49.8, 0.3, 180.0)
    world.place_ball(48.6, 0.3 + 0.05, 0.1, 0.0)
    command = env._keeper_policy.decide(world, keeper)
    assert command is not None and command.kind == "catch"
    env._keeper_policy.apply(world, keeper, command)
    assert world.ball_distance(keeper) == pytest.approx(0.385, abs=1e-9)
    assert keeper.catch_ban == 5
    _, _, terminated, _, info = env.step(np.zeros(8, dtype=np.float32))
    assert terminated and info["status"] == "CAPTURED_BY_DEFENSE"


def test_keeper_v0_keeps_its_own_goalie() -> None:
    from hfo2d.keeper import ScriptedKeeper

    env = gym.make("HFO/Keeper-v0").unwrapped
    assert env.goalie == "hfo2d" and isinstance(env._keeper_policy, ScriptedKeeper)
    env1 = gym.make("HFO/Keeper-v1").unwrapped
    assert env1.goalie == "agent2d" and isinstance(env1._keeper_policy, goalie_module.Agent2dGoalie)
    with pytest.raises(ValueError, match="goalie"):
        gym.make("HFO/EmptyGoal-v0", goalie="agent2d")
    with pytest.raises(ValueError, match="goalie"):
        gym.make("HFO/Keeper-v1", goalie="nobody")
