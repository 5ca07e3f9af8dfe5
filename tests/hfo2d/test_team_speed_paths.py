"""The team game's fast paths against their slow references (branch ``teamspeed``): each shortcut must give the
very numbers of the computation it replaces. The golden rollouts (test_team_golden.py) pin whole games; these
tests pin each shortcut on its own, on states where it matters."""

from __future__ import annotations

import dataclasses
import math
import pickle

import numpy as np

from hfo2d.agent2d import formation_data
from hfo2d.agent2d.common import norm_deg
from hfo2d.agent2d.defender import Agent2dDefender
from hfo2d.agent2d.formation import Formation, normal_formation
from hfo2d.agent2d.goalie import fullstate_value, opponent_may_kick
from hfo2d.agent2d.intercept import (
    build_intercept_table,
    fastest_reach,
    full_self_cache,
    predict_player_reach,
)
from hfo2d.physics import ServerParams, World
from hfo2d.protocol import DEFENSE_SIDE, OFFENSE_SIDE
from hfo2d.team import TeamGame


def _defender_views(cycles: int, seed: int) -> list[object]:
    """The field defender's views along a seeded 2v2 game whose strikers run at the ball and kick it about."""
    game = TeamGame(offense_agents=2, defense_npcs=2, seed=seed)
    rng = np.random.default_rng(seed)
    defender = next(npc for _, npc in game.defense_npcs if isinstance(npc, Agent2dDefender))
    views = []
    game.reset(seed=seed)
    for _ in range(cycles):
        actions = {}
        for agent in game.agents:
            action = rng.random(agent.layout.size).astype(np.float32)
            ball, player = game.world.ball, agent.player
            if math.hypot(ball.x - player.x, ball.y - player.y) < 1.0:
                action[:3] = (0.0, 0.0, 1.0)  # kick somewhere
            actions[agent.name] = action
        _, _, terminated, truncated, _ = game.step(actions)
        views.append(defender.last_view)
        if terminated or truncated:
            game.reset()
    return views


def _entries(table_cache: list) -> list[tuple]:
    return [
        (
            e.mode,
            e.turn_cycle,
            e.dash_cycle,
            e.dash_power,
            e.dash_dir,
            e.self_x,
            e.self_y,
            e.ball_dist,
            e.stamina,
        )
        for e in table_cache
    ]


def test_full_self_cache_of_a_lazy_table_is_the_full_tables() -> None:
    views = _defender_views(400, seed=3)
    assert len(views) == 400
    checked = 0
    for view in views:
        lazy = build_intercept_table(view, full=False)
        _ = lazy.self_min, lazy.opp_min  # what a decision reads before it needs the whole cache
        reference = build_intercept_table(view)
        assert _entries(full_self_cache(lazy)) == _entries(reference.self_cache)
        checked += bool(reference.self_cache)
    assert checked > 100  # most states have candidates (the ball not kickable)


def test_full_self_cache_after_the_forced_kickable_rule_is_empty_as_the_full_tables() -> None:
    view = next(v for v in _defender_views(200, seed=4) if not v.self_kickable)
    lazy = build_intercept_table(view, full=False)
    _ = lazy.ball_cache  # the ball cache is read while the view is not kickable
    view.self_kickable = True  # as Agent2dDefender._forced_kickable sets it afterwards
    assert full_self_cache(lazy) == build_intercept_table(view).self_cache == []


def test_formation_memo_gives_the_computed_position_for_every_unum() -> None:
    formation = normal_formation()
    reference = Formation.__new__(Formation)
    reference.__dict__.update(formation.__dict__)  # the same triangulation, its own (empty) memo
    reference._memo = {}
    rng = np.random.default_rng(0)
    points = [tuple(p) for p in rng.uniform((-56.0, -38.0), (56.0, 38.0), size=(300, 2))]
    points += [(0.0, 0.0), (-0.0, 0.0), (0.0, -0.0), (-52.5, 0.0), (54.5, 36.0)]  # zeros, a hull corner
    for fx, fy in points + points:  # the second round comes from the memo
        for unum in range(1, 12):
            expected = reference._position(unum - 1, fx, fy)
            assert formation.position(unum, fx, fy) == expected
            assert math.copysign(1.0, formation.position(unum, fx, fy)[0]) == math.copysign(1.0, expected[0])


def test_formation_memo_stays_bounded() -> None:
    formation = Formation(formation_data.SAMPLES)
    for k in range(5000):
        formation.position(2, -50.0 + k * 0.01, 0.0)
    assert len(formation._memo) <= 4096


def test_the_defenders_kept_conversions_are_the_fullstate_numbers() -> None:
    """Agent2dDefender._view keeps the last ball and (body, stamina, effort, recovery) conversions by their server
    bits: its view must hold fullstate_value's numbers whether they were kept or converted afresh."""
    params = ServerParams()
    world = World(params, np.random.default_rng(0), noise=False)
    attacker = world.add_player(OFFENSE_SIDE, 11)
    goalie = world.add_player(DEFENSE_SIDE, 1, goalie=True)
    me = world.add_player(DEFENSE_SIDE, 2)
    world.place_ball(30.0, 5.0)
    world.place_player(attacker, 25.0, 3.0, 0.0)
    world.place_player(goalie, 52.5, 0.0, 180.0)
    world.place_player(me, 40.0, -4.0, 170.0)
    defender = Agent2dDefender(params, np.random.default_rng(1), unum=2)
    fs = fullstate_value
    for step in range(12):
        if step == 6:
            world.ball.vx, world.ball.vy = -0.0, 0.0  # a signed zero must not reuse +0's numbers
            me.body_deg = 0.0
        view = defender._view(world, me)
        ball = world.ball
        assert (view.bx, view.by, view.wx, view.wy) == (-fs(ball.x), -fs(ball.y), -fs(ball.vx), -fs(ball.vy))
        assert math.copysign(1.0, view.wx) == math.copysign(1.0, -fs(ball.vx))
        assert view.body == norm_deg(fs(me.body_deg) + 180.0)
        assert (view.stamina, view.effort, view.recovery) == (fs(me.stamina), fs(me.effort), fs(me.recovery))
        if step % 3 == 2:
            world.step()  # the ball and the players move; otherwise the numbers repeat (kept)


def test_a_pickled_defender_without_kept_conversions_still_decides() -> None:
    defender = Agent2dDefender(ServerParams(), np.random.default_rng(0), unum=3)
    state = pickle.loads(pickle.dumps(defender)).__dict__
    for name in ("_ball_key", "_ball_numbers", "_body_key", "_body_numbers"):
        state.pop(name)
    old = Agent2dDefender.__new__(Agent2dDefender)
    old.__setstate__(state)
    assert old._ball_key is None and old._body_key is None


def test_team_observations_are_writable_arrays_of_their_own() -> None:
    game = TeamGame(offense_agents=2, defense_npcs=1, seed=0)
    observations, _ = game.reset(seed=0)
    first = observations["offense_0"]
    assert first.dtype == np.float32 and first.flags.writeable
    kept = first.copy()
    first[:] = 0.0  # a user may scribble on it
    observations, *_ = game.step(
        {agent.name: np.full(agent.layout.size, 0.5, np.float32) for agent in game.agents}
    )
    assert observations["offense_0"].flags.writeable
    assert not np.shares_memory(observations["offense_0"], observations["offense_1"])
    assert kept.any()


def test_fastest_reach_is_the_smallest_predict_player_reach() -> None:
    """intercept.fastest_reach reuses the ball part's frame for every player: the same reach cycles as
    predict_player_reach, which computes the frame again for each (moving and resting balls alike)."""
    rng = np.random.default_rng(7)
    views = []
    for view in _defender_views(300, seed=5):
        views.append(view)
        # the same players with the ball moving in any direction (these games' ball mostly rests)
        wx, wy = rng.uniform(-2.0, 2.0, size=2)
        views.append(
            dataclasses.replace(view, wx=float(wx), wy=float(wy), true_wx=float(wx), true_wy=float(wy))
        )
    reached = 0
    for view in views:
        table = build_intercept_table(view, full=False)
        ball = table.ball_part()
        for players, teammate in ((view.opponents, False), (view.teammates, True), (view.opponents, True)):
            reaches = [predict_player_reach(view, ball[0], p, teammate=teammate) for p in players]
            assert fastest_reach(view, ball, players, teammate) == min([1000, *reaches])
            assert fastest_reach(view, ball, players, teammate, best=3) == min([3, *reaches])
            reached += min([1000, *reaches]) < 1000
    assert reached > 500  # most predictions find a cycle


def test_the_defenders_view_ranks_the_players_as_the_reference() -> None:
    """Agent2dDefender._view computes each player's distances once for its sorts and tests: the same order
    (stable by distance from the ball), kickable flag and nearest-opponent distance as computing them anew."""
    views = _defender_views(300, seed=6)
    assert len(views) == 300
    for view in views:
        ball_dist = [math.hypot(o[0] - view.bx, o[1] - view.by) for o in view.opponents]
        assert ball_dist == sorted(ball_dist)
        assert view.opp_self_dist == min(math.hypot(o[0] - view.px, o[1] - view.py) for o in view.opponents)
        first = next(o for o in view.opponents if o[5] <= 0)
        expected = opponent_may_kick(
            math.hypot(first[0] - view.bx, first[1] - view.by),
            math.hypot(first[0] - view.px, first[1] - view.py),
            math.hypot(view.bx - view.px, view.by - view.py),
        )
        assert view.kick_opp == expected
        assert (view.ox, view.oy) == view.opponents[0][:2]
