"""Regression tests for divergences between hfo2d's agent2d goalie and real HFO's, each built from the real state
(rcssserver's game log or the goalie's own fullstate message) where the divergence was measured with
benchmarks/keeper_fidelity.py, and the benchmark's readers of the goalie's client log."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

from hfo2d.agent2d import goalie as goalie_module
from hfo2d.agent2d.actions import client_dash, client_turn_moment
from hfo2d.agent2d.goalie import Agent2dGoalie, fullstate_value
from hfo2d.physics import ServerParams, World


def world_of(
    cycle: int,
    ball: tuple[float, float, float, float],
    agent: tuple[float, float, float, float, float],
    goalie: tuple[float, float, float, float, float],
    goalie_stamina: float = 8000.0,
) -> tuple[World, object]:
    """A deterministic World in the given state (global frame; players as x, y, vx, vy, body)."""
    world = World(ServerParams(), np.random.default_rng(0), noise=False)
    striker = world.add_player("l", 11)
    keeper = world.add_player("r", 1, goalie=True)
    x, y, vx, vy, body = agent
    world.place_player(striker, x, y, body, vx, vy)
    x, y, vx, vy, body = goalie
    world.place_player(keeper, x, y, body, vx, vy)
    keeper.stamina = goalie_stamina
    world.place_ball(*ball)
    world.cycle = cycle
    return world, keeper


def sent(goalie: Agent2dGoalie, world: World, keeper: object) -> tuple[str, float, float]:
    """The goalie's decision as the server command text's numbers (turn moment; dash power and direction)."""
    command = goalie.decide(world, keeper)
    assert command is not None
    view = goalie.last_view
    if command.kind == "turn":
        return "turn", client_turn_moment(view, command.a), 0.0
    if command.kind == "dash":
        power, direction = client_dash(view, command.a, command.b)
        return "dash", power, direction
    return command.kind, command.a, command.b


# --- the fullstate message's 6 significant digits -------------------------------------------------------------
def test_fullstate_values_have_six_significant_digits() -> None:
    assert fullstate_value(50.500917504) == 50.5009
    assert fullstate_value(-0.366847913) == -0.366848
    assert fullstate_value(-2.448169979957902e-16) == -2.44817e-16  # tiny values keep their sign and digits
    assert fullstate_value(7425.0) == 7425.0
    assert fullstate_value(179.99994101975) == 180.0


def test_the_goalie_decides_on_the_rounded_fullstate_a_turn_sign_at_ninety_degrees() -> None:
    """Identical shot from (42, 0) at y +5, cycle 9 (replayed hfo2d state, the same as the logged one to 1e-4 m):
    the ball line crosses the goalie's defence line almost exactly at its own x, so the catch point lies at
    +-90 degrees and the turn's sign rests on the last bits of the goalie's x. Real HFO sent (turn -90.248); on
    unrounded doubles hfo2d turned the other way (turn 90.248)."""
    world, keeper = world_of(
        36,
        (44.48698110933187, 1.1317792006791036, 2.2038122426779583, 1.0638724486383573),
        (41.757499999900006, 0.0, 0.0, 0.0, 25.769000000000005),
        (50.500917504, -2.448169979957902e-16, -0.0005505024000000003, -6.741710020829362e-20, -180.0),
    )
    kind, moment, _ = sent(Agent2dGoalie(world.params, np.random.default_rng(0)), world, keeper)
    assert (kind, moment) == ("turn", pytest.approx(-90.248, abs=1e-9))


def test_without_the_rounding_the_turn_flips(monkeypatch: pytest.MonkeyPatch) -> None:
    """The mutation check of the test above: the goalie reading the server's doubles turns the other way."""
    monkeypatch.setattr(goalie_module, "fullstate_value", lambda x: x)
    world, keeper = world_of(
        36,
        (44.48698110933187, 1.1317792006791036, 2.2038122426779583, 1.0638724486383573),
        (41.757499999900006, 0.0, 0.0, 0.0, 25.769000000000005),
        (50.500917504, -2.448169979957902e-16, -0.0005505024000000003, -6.741710020829362e-20, -180.0),
    )
    kind, moment, _ = sent(Agent2dGoalie(world.params, np.random.default_rng(0)), world, keeper)
    assert (kind, moment) == ("turn", pytest.approx(90.248, abs=1e-9))


# --- GoalieCatch mode -----------------------------------------------------------------------------------------
def caught(goalie: Agent2dGoalie, catch_cycle: int) -> Agent2dGoalie:
    """The goalie's client state after a successful catch command in ``catch_cycle``, announced by the referee."""
    goalie._last_body_kind = "catch"
    goalie._catch_command_cycle = catch_cycle
    goalie._catch_pending = True
    return goalie


def test_the_wait_frame_after_a_catch_with_the_ball_held_faces_the_halfway_spot() -> None:
    """Random start, mid_shot, the wait frame (cycle 160) after a catch at 159 that ended the episode: GoalieCatch
    mode with the ball within 1.03 m, so Bhv_GoalieFreeKick waits (Body_TurnToPoint to (0, 0) GF). Real HFO sent
    (turn -8.511); hfo2d ran the basic move and tackled, which froze it into the next episode."""
    world, keeper = world_of(
        160,
        (39.2805, -2.3082, 0.0046, 0.0008),
        (38.9848, -2.0615, -0.0391, -0.0084, 12.074),
        (39.6977, -2.2522, 0.0, 0.0, -174.736),
        goalie_stamina=7540.0,
    )
    goalie = caught(Agent2dGoalie(world.params, np.random.default_rng(0)), 159)
    assert sent(goalie, world, keeper) == ("turn", pytest.approx(-8.511, abs=1e-9), 0.0)


def test_the_ball_velocity_is_not_zeroed_when_goalie_catch_begins() -> None:
    """cross_shot with noise, cycle 1071, the goalie's own fullstate message: a catch at 1070 that did not end the
    episode puts the client in GoalieCatch mode (basic move only). librcsc keeps the fullstate's ball velocity,
    so the target point is the near post's (-49.8, 6.91) GF and real HFO sent (turn 69.858); with the velocity
    zeroed hfo2d aimed at (-49.8, 3.26) and side-dashed (dash 100 90)."""
    world, keeper = world_of(
        1071,
        (49.4419, -3.38033, 0.58786, -0.980575),
        (43.533, 6.6961, 0.261318, -0.289709, -52.5856),
        (49.1569, -2.15733, 0.0, 0.0, -152.152),
        goalie_stamina=6850.0,
    )
    world.noise = True  # a noise-on session: the client reads ball_rand 0.05 and player_rand 0.1
    goalie = caught(Agent2dGoalie(world.params, np.random.default_rng(0)), 1070)
    assert sent(goalie, world, keeper) == ("turn", pytest.approx(69.858, abs=1e-9), 0.0)
    assert goalie.last_view is not None and not goalie.last_view.play_on


def test_a_held_ball_long_after_the_catch_gives_the_free_kicks_first_move() -> None:
    """cross_shot with noise, cycle 462 (the goalie's fullstate): a catch at 452 that did not end the episode,
    then a capture at 462 with the ball within 1.03 m; 10 cycles after the catch Bhv_GoalieFreeKick makes its
    first move, away from the ball's side. Real HFO sent (move -37.5 -13), which rcssserver ignores in PlayOn."""
    world, keeper = world_of(
        462,
        (50.3388, -3.71674, -0.372435, 0.584729),
        (47.7322, 0.757543, 0.15665, -0.317409, -66.3281),
        (49.7344, -3.86308, 0.0450503, 0.340979, 83.9395),
        goalie_stamina=6610.0,
    )
    world.noise = True
    goalie = caught(Agent2dGoalie(world.params, np.random.default_rng(0)), 452)
    command = goalie.decide(world, keeper)
    assert command is not None and (command.kind, command.a, command.b) == ("move", -37.5, -13.0)
    goalie.apply(world, keeper, command)  # nothing reaches the World
    assert (keeper.x, keeper.y) == (49.7344, -3.86308)


# --- the benchmark's readers of the goalie's client log -------------------------------------------------------
def test_fullstate_and_client_log_parsing(
    tmp_path: Path, benchmark_script: Callable[[str], ModuleType]
) -> None:
    real_hfo_logs = benchmark_script("real_hfo_logs")  # benchmarks/real_hfo_logs.py
    line = (
        "(fullstate 49 (pmode play_on) (vmode high normal) (count 0 0 0 0 0 0 0 0) (arm (movable 0) (expires 0) "
        "(target 0 0) (count 0)) (score 0 0) ((b) 44.487 1.13178 2.20381 1.06387) ((p l 11 0) 41.7575 0 0 0 "
        "25.769 34 (stamina 8000 1 1 130600) k) ((p r 1 g 0) 50.5009 -5.1878e-05 -0.000550502 -1.4286e-08 "
        "-179.999 -10 (stamina 8000 1 1 130400)))"
    )
    time, ball, players = real_hfo_logs.parse_fullstate(line)
    assert (time, ball) == (49, (44.487, 1.13178, 2.20381, 1.06387))
    assert players[("l", 11)].flags == "k"
    goalie = players[("r", 1)]
    assert (goalie.x, goalie.y, goalie.vy, goalie.body, goalie.stamina) == (
        50.5009,
        -5.1878e-05,
        -1.4286e-08,
        -179.999,
        8000.0,
    )
    log = tmp_path / "base_right-1.ocl"
    log.write_text(
        "(sense_body 48 (stamina 8000 1 130400) (tackle (expires 3) (count 0)))\n"
        + line.replace("fullstate 49", "fullstate 48")
        + "\n(think)\n(hear 48 referee goalie_catch_ball_r)\n(sense_body 49 (tackle (expires 2) (count 0)))\n"
        + line
        + "\n(think)\n(sense_body 50 (tackle (expires 0) (count 0)))\n"
        + line[:60]  # cut short by the end of the log
    )
    cycles = real_hfo_logs.parse_client_log(log)
    assert sorted(cycles) == [48, 49]
    assert (cycles[48].tackle_expires, cycles[48].mode, cycles[48].mode_changed) == (3, "", False)
    assert (cycles[49].tackle_expires, cycles[49].mode, cycles[49].mode_changed) == (
        2,
        "goalie_catch_ball_r",
        True,
    )
    assert cycles[49].referee == ("goalie_catch_ball_r",)
