"""agent2d's goalie (hfo2d.agent2d.goalie) against two strikers: its world model reads every opponent, as librcsc's
does (the attacker is the one nearest the ball, the opponents' reach is the fastest of them), not the first in
server order; and the scripted strikers' team view (hfo2d.strikers.goalie_view_from_hfo)."""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np
import pytest

import hfo2d
from hfo2d.agent2d import common as agent2d_common
from hfo2d.agent2d.goalie import Agent2dGoalie
from hfo2d.agent2d.intercept import build_intercept_table
from hfo2d.physics import PlayerState, ServerParams, World
from hfo2d.strikers import goalie_view_from_hfo


@pytest.fixture(autouse=True)
def default_agent2d_params() -> Iterator[None]:
    yield
    agent2d_common.bind_server_params(agent2d_common.canonical_params(ServerParams()))


Spot = tuple[float, float, float]  # x, y, body (deg)


def _world(strikers: list[Spot], ball: tuple[float, float, float, float]) -> tuple[World, PlayerState]:
    """A noise-free world in server order: the strikers l7, l11 (as many as given), then the goalie r1."""
    world = World(ServerParams(), np.random.default_rng(0), noise=False)
    players = [world.add_player("l", unum) for unum in (7, 11)[: len(strikers)]]
    goalie = world.add_player("r", 1, goalie=True)
    for player, (x, y, body) in zip(players, strikers, strict=True):
        world.place_player(player, x, y, body)
    world.place_player(goalie, 50.0, 0.0, 180.0)
    world.place_ball(*ball)
    return world, goalie


def _decide(world: World, goalie: PlayerState) -> tuple[Agent2dGoalie, object]:
    policy = Agent2dGoalie(ServerParams(), np.random.default_rng(1))
    command = policy.decide(world, goalie)
    return policy, command


FAR: Spot = (10.0, 25.0, 0.0)  # a striker far from the ball and the goal
DRIBBLER: Spot = (39.4, 4.0, 0.0)  # on the ball at (40, 4)
HELD_BALL = (40.0, 4.0, 0.0, 0.0)


@pytest.mark.parametrize("dribbler_first", [False, True])
def test_it_watches_the_striker_on_the_ball_whatever_the_server_order(dribbler_first: bool) -> None:
    strikers = [DRIBBLER, FAR] if dribbler_first else [FAR, DRIBBLER]
    world, goalie = _world(strikers, HELD_BALL)
    policy, command = _decide(world, goalie)
    view = policy.last_view
    # the goalie's frame is mirrored: the dribbler at (-39.4, -4)
    assert (view.ox, view.oy) == pytest.approx((-DRIBBLER[0], -DRIBBLER[1]))
    assert view.kick_opp and view.wx == 0.0 and view.wy == 0.0
    assert view.opp_self_dist == pytest.approx(math.hypot(50.0 - 39.4, 4.0))
    # the far striker changes nothing here: the same decision as against the dribbler alone
    alone, alone_command = _decide(*_world([DRIBBLER], HELD_BALL))
    assert command == alone_command
    assert (alone.last_view.ox, alone.last_view.kick_opp) == (view.ox, view.kick_opp)


def test_the_opponents_reach_is_the_fastest_striker() -> None:
    # a free ball rolling toward the second striker, away from the one nearest to it now
    ball = (30.0, 0.0, 1.2, 0.6)
    near_now: Spot = (28.5, -1.5, 0.0)
    ahead: Spot = (38.0, 5.0, 200.0)
    reaches = []
    for strikers in ([near_now, ahead], [near_now], [ahead]):
        world, goalie = _world(strikers, ball)
        policy, _ = _decide(world, goalie)
        reaches.append(build_intercept_table(policy.last_view).opp_min)
    both, first_alone, second_alone = reaches
    assert second_alone < first_alone  # the striker ahead of the ball gets there first ...
    assert both == second_alone  # ... and the goalie of the team game knows it
    world, goalie = _world([near_now, ahead], ball)
    policy, _ = _decide(world, goalie)
    assert (policy.last_view.ox, policy.last_view.oy) == pytest.approx((-near_now[0], -near_now[1]))


def test_one_striker_leaves_the_team_fields_unset() -> None:
    world, goalie = _world([DRIBBLER], HELD_BALL)
    policy, _ = _decide(world, goalie)
    assert getattr(policy.last_view, "other_opponents", None) is None
    assert getattr(policy.last_view, "opp_self_dist", None) is None


@pytest.mark.parametrize("offense", [1, 2])
def test_the_strikers_team_view_is_what_the_team_game_gives_its_own_strikers(offense: int) -> None:
    env = hfo2d.parallel_env(offense_agents=offense, defense_npcs=2, feature_set="hfo")
    game = env.game
    observations, _ = env.reset(seed=3)
    checked = 0
    for _ in range(15):
        for name in env.agents:
            view = goalie_view_from_hfo(observations[name], offense - 1, 2)
            assert view.shape == (66,) and view.dtype == np.float32
            expected = game._striker_observation(game.agent(name).player)
            np.testing.assert_allclose(view, expected, atol=1e-6)
            checked += 1
        observations, *_ = env.step({name: env.action_space(name).sample() for name in env.agents})
        if not env.agents:
            break
    assert checked >= offense


def test_the_strikers_team_view_without_a_goalie_is_zeros_and_checks_lengths() -> None:
    env = hfo2d.parallel_env(offense_agents=2, defense_npcs=0, defense_agents=0, feature_set="hfo")
    observations, _ = env.reset(seed=0)
    view = goalie_view_from_hfo(observations["offense_0"], 1, 0)
    assert not view[58:].any() and view[:58].any()
    with pytest.raises(ValueError, match="features"):
        goalie_view_from_hfo(observations["offense_0"], 1, 1)
