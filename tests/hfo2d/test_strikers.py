"""Scripted strikers (hfo2d.strikers): valid flat actions, deterministic, each scores on the empty goal."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest

from hfo2d.hfo_env import HFOEnv
from hfo2d.strikers import (
    KICK,
    STRIKERS,
    TURN,
    AimedShot,
    flat_action,
    make_striker,
    perceive,
)

EPISODES = 6


def play(env: HFOEnv, name: str, seeds: range) -> tuple[list[str], list[list[float]]]:
    """End statuses and every flat action of ``name`` over seeded episodes."""
    striker = make_striker(name)
    statuses: list[str] = []
    actions: list[list[float]] = []
    for seed in seeds:
        obs, _ = env.reset(seed=seed)
        striker.reset()
        while True:
            action = striker(obs)
            assert env.action_space.contains(action), (name, action)
            actions.append(action.tolist())
            obs, _, terminated, truncated, info = env.step(action)
            if terminated or truncated:
                break
        statuses.append(info["status"])
    return statuses, actions


@pytest.mark.parametrize("name", sorted(STRIKERS))
def test_scores_sometimes_and_is_deterministic(name: str) -> None:
    env = HFOEnv("empty_goal")  # noise on
    statuses, actions = play(env, name, range(EPISODES))
    assert statuses.count("GOAL") >= EPISODES // 2, (name, statuses)
    again, actions_again = play(env, name, range(EPISODES))
    assert (again, actions_again) == (statuses, actions)


def test_perceive_reads_the_true_state() -> None:
    env = HFOEnv("static_keeper", noise=False)
    obs, _ = env.reset(
        seed=0,
        options={
            "player": (30.0, -12.0, 37.0),
            "ball": (33.0, -10.0, 1.2, -0.4),
            "keeper": (51.0, 3.0, 170.0),
        },
    )
    p = perceive(obs)
    for got, want in (
        (p.x, 30.0),
        (p.y, -12.0),
        (p.body_deg, 37.0),
        (p.ball_x, 33.0),
        (p.ball_y, -10.0),
        (p.ball_vx, 1.2),
        (p.ball_vy, -0.4),
    ):
        assert got == pytest.approx(want, abs=1e-4)
    assert p.goalie == pytest.approx((51.0, 3.0), abs=1e-4)
    assert not p.kickable


def test_flat_action_maps_back_onto_the_command() -> None:
    env = HFOEnv("empty_goal")
    for command in ((0, 73.0, -45.0), (1, 120.0, 0.0), (2, 100.0, 33.5)):
        flat = flat_action(command)
        kind, power, direction = env._parse_action(flat)
        assert kind == command[0]
        if kind == TURN:
            assert direction == pytest.approx(command[1], abs=1e-4)
        else:
            assert (power, direction) == pytest.approx(command[1:], abs=1e-4)


@pytest.mark.parametrize("target_y", [-5.0, 0.0, 5.0])
def test_aimed_shot_turns_then_kicks_along_the_line(target_y: float) -> None:
    env = HFOEnv("empty_goal", noise=False)
    ball = (36.75, 0.0)
    obs, _ = env.reset(seed=0, options={"player": (ball[0] - 0.4, ball[1], 150.0), "ball": ball})
    striker = AimedShot(target_y=target_y, aim_cycles=6)
    striker.reset()
    kinds = []
    for _ in range(7):
        command = striker.command(obs)
        kinds.append(command[0])
        obs, _, terminated, _, info = env.step(flat_action(command))
        assert not terminated
    assert kinds == [TURN] * 6 + [KICK]
    vx, vy = info["ball"][2], info["ball"][3]
    assert math.hypot(vx, vy) > 2.0
    heading = math.atan2(vy, vx)
    assert heading == pytest.approx(math.atan2(target_y - ball[1], 52.5 - ball[0]), abs=0.02)


def test_unknown_striker() -> None:
    with pytest.raises(ValueError, match="unknown striker"):
        make_striker("nope")
    with pytest.raises(ValueError, match="takes no options"):
        make_striker("mid_shot", target_y=1.0)
    assert np.all(np.isfinite(make_striker("aimed_shot", target_y=5.0)(np.zeros(66, dtype=np.float32))))


# ---------------------------------------------------------------------------------------------------------------
# benchmarks/keeper_fidelity.py: the log readers and the replay's command conversions (no HFO build needed)
# ---------------------------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def fidelity(benchmark_script: Callable[[str], ModuleType]) -> ModuleType:
    return benchmark_script("keeper_fidelity")


def test_log_readers(tmp_path: Path, fidelity: Any) -> None:
    logs = fidelity.real_hfo_logs
    # the line formats of rcssserver 15.2.2 (serializermonitor.cpp, logger.cpp) and HFORef::logEpisode
    (tmp_path / "a.rcg").write_text(
        "ULG5\n(playmode 61 play_on)\n"
        "(show 61 ((b) 36.75 0 0 0) ((l 1) 0 0 -3 -37 0 0 0 0 (v h 120) (s 8000 1 1 130600)) "
        "((l 11) 0 0x1 36.65 0 0 0 174 89 (v h 180) (s 8000 1 1 130600) (c 0 0 0 0 0 0 0 0 0 0 0)) "
        "((r 1) 0 0x9 52.5 0 -0.0726 0.08 -170 -90 (v h 90) (s 8000 1 1 130600)))\n"
    )
    (tmp_path / "a.rcl").write_text(
        "61,0\t(referee play_on)\n"
        "61,0\tRecv base_right_1: (turn 80)(turn_neck 20)(change_view narrow)(done)\n"
        "61,0\tRecv base_left_11: (turn_neck -179)(kick 57.104 -1.81621)(done)\n"
        "62,0\tRecv base_right_1: (dash 100 -45)(done)\n"
        "62,0\tRecv base_right_1: (dash 1)(done)\n"
    )
    (tmp_path / "a.hfo").write_text("# Offense: 1\n2\t61\t179\t118\tCAPTURED_BY_DEFENSE-1\n")
    read = logs.read_logs(tmp_path)
    show = read.shows[61]
    assert show.ball == (36.75, 0.0, 0.0, 0.0)
    assert set(show.players) == {("l", 11), ("r", 1)}
    goalie = show.players[("r", 1)]
    assert (goalie.x, goalie.vx, goalie.vy, goalie.body, goalie.state) == (52.5, -0.0726, 0.08, -170.0, 9)
    assert read.commands["base_left_11"][61] == logs.BodyCommand("kick", (57.104, -1.81621))
    assert read.commands["base_right_1"][61].text() == "(turn 80)"
    assert read.commands["base_right_1"][62].text() == "(dash 100 -45)"  # the first of the cycle
    assert read.episodes == [logs.Episode(2, 61, 179, "CAPTURED_BY_DEFENSE")]


def test_replayed_commands_are_the_logged_server_commands(fidelity: Any) -> None:
    env = HFOEnv("static_keeper", noise=False)
    BodyCommand = fidelity.real_hfo_logs.BodyCommand
    env.reset(seed=0, options={"player": (30.0, 0.0, 20.0, 0.3, 0.2), "ball": (30.5, 0.0)})
    speed = math.hypot(0.3, 0.2)
    env.step(fidelity.agent_flat(env, BodyCommand("turn", (50.0,))))
    # the server turns by moment / (1 + inertia_moment * speed): the flat TURN sent exactly the moment 50
    assert env.agent.body_deg == pytest.approx(20.0 + 50.0 / (1.0 + 5.0 * speed), abs=1e-9)
    with fidelity.recording_goalie_commands(env) as record:
        env.world.turn(env.keeper, 12.5)
        env.world.turn(env.agent, 3.0)
    assert record == [("turn", (12.5,))]  # only the goalie's commands are recorded
    kind, power, direction = env._parse_action(
        fidelity.agent_flat(env, BodyCommand("kick", (57.104, -1.81621)))
    )
    assert (kind, power, direction) == (
        2,
        pytest.approx(57.104, abs=1e-12),
        pytest.approx(-1.81621, abs=1e-12),
    )
    kind, power, direction = env._parse_action(fidelity.agent_flat(env, BodyCommand("dash", (100.0,))))
    assert (kind, power, direction) == (0, pytest.approx(100.0), pytest.approx(0.0, abs=1e-12))


def test_command_agreement_and_rates(fidelity: Any) -> None:
    BodyCommand = fidelity.real_hfo_logs.BodyCommand
    agree = fidelity.commands_agree
    assert agree(BodyCommand("turn", (49.758,)), ("turn", (49.7585,)))
    assert not agree(BodyCommand("turn", (49.758,)), ("turn", (49.929,)))
    assert agree(BodyCommand("turn", (-0.001,)), None)  # nothing sent is a turn by 0
    assert agree(BodyCommand("dash", (45.0,)), ("dash", (45.0, 0.0)))
    assert not agree(BodyCommand("dash", (0.0,)), ("dash", (-100.0, 0.0)))
    assert not agree(BodyCommand("catch", (22.6233,)), ("turn", (22.6233,)))
    low, high = fidelity.wilson(8, 10)
    assert (round(low, 4), round(high, 4)) == (0.4902, 0.9433)
    diff = fidelity.difference(
        fidelity.rate_summary(["GOAL"] * 3 + ["OUT_OF_TIME"]), fidelity.rate_summary(["GOAL"])
    )
    assert diff["diff"] == pytest.approx(-0.25)
    assert diff["se"] == pytest.approx(math.sqrt(0.75 * 0.25 / 4))


def test_segment_distance_measures_to_the_nearest_point_of_the_segment() -> None:
    from hfo2d.strikers import segment_distance

    assert segment_distance(1.0, 2.0, 0.0, 0.0, 4.0, 0.0) == pytest.approx(2.0)  # beside the segment
    assert segment_distance(-3.0, 4.0, 0.0, 0.0, 4.0, 0.0) == pytest.approx(
        5.0
    )  # beyond its start: to the end
    assert segment_distance(7.0, -4.0, 0.0, 0.0, 4.0, 0.0) == pytest.approx(5.0)  # beyond its end
    assert segment_distance(3.0, 4.0, 1.0, 1.0, 1.0, 1.0) == pytest.approx(math.hypot(2.0, 3.0))  # a point
