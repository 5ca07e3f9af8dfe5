"""agent2d's field defenders as hfo2d NPCs (hfo2d.agent2d.defender), in a small world of their own: one attacker,
agent2d's goalie and one or two field defenders."""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np
import pytest

from hfo2d.agent2d import common as agent2d_common
from hfo2d.agent2d.defender import Agent2dDefender
from hfo2d.agent2d.formation import normal_formation
from hfo2d.agent2d.formation_data import GOALIE_CATCH_OUR
from hfo2d.agent2d.goalie import Agent2dGoalie
from hfo2d.npc import DefenseNPC
from hfo2d.physics import PlayerState, ServerParams, World


@pytest.fixture(autouse=True)
def default_agent2d_params() -> Iterator[None]:
    """Leave hfo2d.agent2d bound to the default parameters, whatever a test bound."""
    yield
    agent2d_common.bind_server_params(agent2d_common.canonical_params(ServerParams()))


def _world(
    params: ServerParams | None = None, defenders: int = 1
) -> tuple[World, PlayerState, PlayerState, list[PlayerState]]:
    """A noise-free world in server slot order: the attacker l11, the goalie r1 on its line, field players r2..."""
    world = World(params or ServerParams(), np.random.default_rng(0), noise=False)
    attacker = world.add_player("l", 11)
    goalie = world.add_player("r", 1, goalie=True)
    field = [world.add_player("r", 2 + i) for i in range(defenders)]
    world.place_player(attacker, 10.0, 25.0, 0.0)
    world.place_player(goalie, 52.5, 0.0, 180.0)
    return world, attacker, goalie, field


def _defender(unum: int = 2, params: ServerParams | None = None) -> Agent2dDefender:
    return Agent2dDefender(params or ServerParams(), np.random.default_rng(1), unum=unum)


def _face(world: World, p: PlayerState, x: float, y: float) -> None:
    world.place_player(p, p.x, p.y, math.degrees(math.atan2(y - p.y, x - p.x)))


def test_it_is_a_defense_npc_and_checks_its_arguments() -> None:
    d = _defender(3)
    assert isinstance(d, DefenseNPC) and d.unum == 3 and d.carries_over
    for unum in (1, 12, True, 2.0, "2"):
        with pytest.raises(ValueError, match="unum"):
            Agent2dDefender(ServerParams(), np.random.default_rng(0), unum=unum)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="skill"):
        Agent2dDefender(ServerParams(), np.random.default_rng(0), skill=1.5)
    with pytest.raises(ValueError, match="skill"):
        d.set_skill(-0.1)


def test_against_a_ball_holder_it_runs_to_its_formation_position_at_the_ball() -> None:
    world, attacker, _, (me,) = _world()
    world.place_player(attacker, 30.0, 5.0, 0.0)
    world.place_ball(30.5, 5.0)  # the attacker can kick it: the defender's world model stops the ball
    world.place_player(me, 45.0, -10.0, 0.0)
    # home: the formation at the ball itself (opp_min 0), in the defender's frame (x, y negated)
    hx, hy = normal_formation().position(2, -30.5, -5.0)
    _face(world, me, -hx, -hy)
    d = _defender()
    command = d.decide(world, me)
    assert d.last_view.kick_opp and d.last_view.wx == 0.0 and d.last_table.opp_min == 0
    assert d.last_home == pytest.approx((hx, hy))
    assert d.last_branch == "move"
    # Strategy::get_normal_dash_power's normal rule: 1.7 * stamina_inc_max * recovery
    assert command is not None and command.kind == "dash" and command.a == pytest.approx(76.5)


def test_a_free_ball_it_reaches_first_is_intercepted() -> None:
    world, attacker, _, (me,) = _world()
    world.place_player(attacker, 5.0, 25.0, 0.0)
    world.place_ball(40.0, -6.0, 0.8, -0.5)
    world.place_player(me, 44.0, -9.0, 180.0)
    d = _defender()
    d.decide(world, me)
    assert d.last_table.self_min <= 3 < d.last_table.opp_min
    assert d.last_branch == "intercept"


def test_a_kickable_goalie_stops_it_from_chasing_but_its_reach_does_not() -> None:
    world, attacker, goalie, (me,) = _world()
    world.place_player(attacker, 5.0, 25.0, 0.0)
    world.place_ball(49.0, 3.0)
    world.place_player(me, 47.0, 3.0, 0.0)
    d = _defender()
    world.place_player(goalie, 49.9, 3.0, 180.0)  # within 1.085 of the ball: existKickableTeammate
    d.decide(world, me)
    assert d.last_view.mate_kick and d.last_table.mate_min == 0 and d.last_branch != "intercept"
    world.place_player(goalie, 50.3, 3.0, 180.0)  # faster to the ball than the defender, but not kickable
    d.decide(world, me)
    # the goalie never enters teammateReachCycle: with no other field player it stays 1000
    assert not d.last_view.mate_kick and d.last_table.mate_min == 1000
    assert d.last_branch == "intercept"


def test_the_other_field_defender_enters_mate_min() -> None:
    world, attacker, _, (me, mate) = _world(defenders=2)
    world.place_player(attacker, 5.0, 25.0, 0.0)
    world.place_ball(40.0, 0.0)
    world.place_player(me, 48.0, 10.0, 0.0)
    world.place_player(mate, 41.5, 0.0, 180.0)
    d = _defender(2)
    d.decide(world, me)
    assert d.last_table.mate_min < d.last_table.self_min < 1000
    assert d.last_branch != "intercept"  # its teammate is faster and it needs more than 3 cycles
    other = _defender(3)
    other.decide(world, mate)
    assert other.last_branch == "intercept"


def test_it_tackles_a_dribbler_in_front_of_it() -> None:
    world, attacker, _, (me,) = _world()
    world.place_player(attacker, 40.0, 0.0, 0.0)
    world.place_ball(40.6, 0.0)
    world.place_player(me, 42.1, 0.0, 180.0)  # the ball 1.5 m straight ahead: tackle probability 0.82
    d = _defender()
    command = d.decide(world, me)
    assert d.last_branch == "tackle"
    # inside its penalty area it never fouls
    assert command is not None and command.kind == "tackle" and not command.foul
    d.apply(world, me)
    assert me.tackle_cycles > 0  # the server froze it
    assert d.decide(world, me) is None and d.last_branch == "frozen"


def test_with_the_ball_and_an_attacker_on_it_it_kicks_upfield() -> None:
    world, attacker, _, (me,) = _world()
    world.place_player(attacker, 39.5, 0.0, 0.0)
    world.place_ball(40.2, 0.0)
    world.place_player(me, 41.0, 0.0, 180.0)
    d = _defender()
    command = d.decide(world, me)
    assert d.last_branch == "force_kick" and command is not None and command.kind == "kick"
    d.apply(world, me)
    world.step()
    assert world.ball.vx < -1.0  # toward the opponent goal, away from its own


def test_with_the_ball_alone_it_keeps_it_within_reach() -> None:
    world, attacker, _, (me,) = _world()
    world.place_player(attacker, 5.0, 25.0, 0.0)
    world.place_ball(40.0, 0.0, 0.6, 0.2)
    world.place_player(me, 40.8, 0.3, 180.0)
    d = _defender()
    for _ in range(4):
        d.act(world, me)
        assert d.last_branch == "hold"
        world.step()
        assert math.hypot(world.ball.x - me.x, world.ball.y - me.y) < world.params.kickable_area


def test_the_recover_flag_outlives_an_episode_until_a_restart() -> None:
    world, attacker, _, (me,) = _world()
    world.place_player(attacker, 30.0, 5.0, 0.0)
    world.place_ball(30.5, 5.0)
    world.place_player(me, 45.0, -10.0, 0.0)
    hx, hy = normal_formation().position(2, -30.5, -5.0)
    _face(world, me, -hx, -hy)
    d = _defender()
    me.stamina = 3000.0  # below half the stamina: the static recover flag goes on
    assert d.decide(world, me).a == pytest.approx(20.0)  # stamina_inc_max * recovery - 25
    d.reset()
    me.stamina = 5000.0  # between 0.5 and 0.7 of stamina_max: the flag keeps its value
    assert d.decide(world, me).a == pytest.approx(20.0)
    d.restart()
    assert d.decide(world, me).a == pytest.approx(76.5)


def test_after_its_goalies_catch_it_walks_to_the_goalie_catch_position() -> None:
    world, attacker, _, (me,) = _world()
    world.place_player(attacker, 30.0, 5.0, 0.0)
    world.place_ball(51.0, 0.0)
    world.place_player(me, 45.0, -10.0, 0.0)
    d = _defender()
    d.goalie_caught()
    d.decide(world, me)
    assert d.last_branch == "set_play_move" and d.last_home == pytest.approx(GOALIE_CATCH_OUR[2])
    d.reset()
    d.decide(world, me)
    assert d.last_branch != "set_play_move"


def test_server_params_reach_its_predictions() -> None:
    slow = ServerParams.with_overrides({"ball_decay": 0.5})
    for params, decay in ((slow, 0.5), (ServerParams(), 0.94)):
        world, _, _, (me,) = _world(params)
        world.place_ball(35.0, 0.0, -2.0, 0.4)
        world.place_player(me, 45.0, -10.0, 0.0)
        d = _defender(params=params)
        d.decide(world, me)
        (x0, y0), (x1, _), (x2, _) = d.last_table.ball_cache[:3]
        assert x2 - x1 == pytest.approx((x1 - x0) * decay, rel=1e-9)


def _play(seed: int, cycles: int = 60) -> list[tuple[float, ...]]:
    """A striker dribbling at the goal against the goalie and two field defenders; the states it passes."""
    world, attacker, goalie, field = _world(defenders=2)
    world.rng = np.random.default_rng(seed)
    world.noise = True
    world.place_player(attacker, 25.0, 8.0, 0.0)
    world.place_ball(25.6, 8.0)
    world.place_player(field[0], 44.0, -6.0, 180.0)
    world.place_player(field[1], 46.0, 9.0, 180.0)
    npcs = [
        (Agent2dGoalie(world.params, np.random.default_rng(seed)), goalie),
        (Agent2dDefender(world.params, np.random.default_rng(seed), unum=2), field[0]),
        (Agent2dDefender(world.params, np.random.default_rng(seed), unum=3), field[1]),
    ]
    states = []
    for _ in range(cycles):
        for npc, p in npcs:
            npc.decide(world, p)
        if math.hypot(world.ball.x - attacker.x, world.ball.y - attacker.y) < 1.0:
            world.kick(
                attacker, 25.0, math.degrees(math.atan2(-attacker.y, 52.5 - attacker.x)) - attacker.body_deg
            )
        else:
            world.dash(attacker, 80.0, 0.0)
        for npc, p in npcs:
            npc.apply(world, p)
        world.step()
        states.append(tuple(v for p in world.players for v in (p.x, p.y)) + (world.ball.x, world.ball.y))
    return states


def test_games_repeat_with_their_seed() -> None:
    first = _play(4)
    assert first == _play(4)
    assert first != _play(5)
    # the defenders moved (they are not idle)
    assert math.hypot(first[-1][4] - 44.0, first[-1][5] + 6.0) > 1.0
