"""hfo2d's layout for teams: the protocol module, the one referee, the NPC interface, and agent2d reading the world's
server parameters."""

from __future__ import annotations

import math
from collections.abc import Iterator

import gymnasium as gym
import numpy as np
import pytest

import hfo2d  # noqa: F401  (registers the ids)
from hfo2d import hfo_env, physics, protocol, referee
from hfo2d.agent2d import common as agent2d_common
from hfo2d.agent2d import decision as agent2d_decision
from hfo2d.agent2d.intercept import build_intercept_table
from hfo2d.npc import DefenseNPC, StillGoalie
from hfo2d.physics import ServerParams, World
from hfo2d.referee import Referee

DASH_AHEAD = np.array([1, 0, 0, 0.5, 0.5, 0.5, 0, 0.5], dtype=np.float32)


@pytest.fixture(autouse=True)
def default_agent2d_params() -> Iterator[None]:
    """Leave hfo2d.agent2d bound to the default parameters, whatever a test bound."""
    yield
    agent2d_common.bind_server_params(agent2d_common.canonical_params(ServerParams()))


def _goalie_ball_cache(env: hfo_env.HFOEnv) -> list[tuple[float, float]]:
    """The ball positions the goalie predicts on its last decision (librcsc's ball cache)."""
    return build_intercept_table(env._keeper_policy.last_view).ball_cache


def _keeper_v1(**server_params: float) -> hfo_env.HFOEnv:
    env = gym.make("HFO/Keeper-v1", server_params=server_params or None).unwrapped
    # a ball rolling toward the goal, the striker far from it: the goalie's view holds the true velocity
    env.reset(seed=3, options={"ball": (30.0, 4.0, 2.0, -0.4), "player": (10.0, -20.0, 0.0)})
    env.step(DASH_AHEAD)
    return env


def _assert_cache_decays(cache: list[tuple[float, float]], decay: float) -> None:
    (x0, y0), (x1, y1), (x2, y2) = cache[:3]
    # createBallCache: x += v; v *= decay, so the second step is the first times the decay
    assert x2 - x1 == pytest.approx((x1 - x0) * decay, rel=1e-9)
    assert y2 - y1 == pytest.approx((y1 - y0) * decay, rel=1e-9)


def test_server_params_reach_the_goalies_predictions() -> None:
    slow = _keeper_v1(ball_decay=0.5)
    cache = _goalie_ball_cache(slow)
    assert len(cache) > 3 and (cache[1][0] - cache[0][0]) ** 2 + (cache[1][1] - cache[0][1]) ** 2 > 1e-6
    _assert_cache_decays(cache, 0.5)
    # the default world's goalie predicts with rcssserver's 0.94
    _assert_cache_decays(_goalie_ball_cache(_keeper_v1()), 0.94)


def test_goalies_of_different_worlds_each_predict_with_their_own_params() -> None:
    slow = _keeper_v1(ball_decay=0.5)
    default = _keeper_v1()
    for _ in range(3):  # each decision binds its own world's parameters
        slow.step(DASH_AHEAD)
        _assert_cache_decays(_goalie_ball_cache(slow), 0.5)
        default.step(DASH_AHEAD)
        _assert_cache_decays(_goalie_ball_cache(default), 0.94)


def test_server_params_reach_the_goalies_catch_and_tackle_rules() -> None:
    _keeper_v1(catchable_area_l=2.0, tackle_dist=3.0)
    catch_dist, tackle_reach = agent2d_decision.CATCH_DIST, agent2d_decision._TACKLE_SURE_FAR
    assert catch_dist == pytest.approx(math.hypot(2.0, 0.5) - 0.05)
    assert tackle_reach > math.hypot(3.0, 1.25)
    _keeper_v1()
    catch_dist = agent2d_decision.CATCH_DIST
    assert catch_dist == pytest.approx(1.3 - 0.05)


def test_equal_params_share_one_binding() -> None:
    first, second = ServerParams.with_overrides({}), ServerParams.with_overrides(None)
    assert first is not second
    assert agent2d_common.canonical_params(first) is agent2d_common.canonical_params(second)


# --- the protocol ------------------------------------------------------------------------------------------------
def test_the_env_and_physics_offer_the_protocols_names() -> None:
    for name in (
        "IN_GAME",
        "GOAL",
        "OUT_OF_TIME",
        "OFFENSE_OFFSETS",
        "POWER_MAX",
        "DEFAULT_FRAMES_PER_TRIAL",
    ):
        assert getattr(hfo_env, name) is getattr(protocol, name)
    assert physics.HFO_CAPTURED_BY_DEFENSE == protocol.CAPTURED_BY_DEFENSE
    assert physics.HFO_TURNOVER_TIME == protocol.TURNOVER_TIME
    assert physics.HFOReferee is referee.Referee
    with pytest.raises(AttributeError, match="no attribute 'HFO_NOTHING'"):
        _ = physics.HFO_NOTHING


# --- the referee -------------------------------------------------------------------------------------------------
def _world_with(*players: tuple[str, int, float, float]) -> World:
    world = World(ServerParams(), np.random.default_rng(0), noise=False)
    world.place_ball(40.0, 0.0)
    for side, unum, x, y in players:
        world.place_player(world.add_player(side, unum, goalie=unum == 1), x, y, 0.0)
    return world


@pytest.mark.parametrize("rules", referee.REFEREE_RULES)
def test_any_defender_captures_after_the_turnover_time_the_goalie_at_once(rules: str) -> None:
    world = _world_with(("l", 11, 20.0, 0.0), ("r", 2, 40.5, 0.0))  # a field defender on the ball
    judge = Referee(world.params, rules=rules)
    judge.reset(world)
    statuses = [judge.analyse(world) for _ in range(3)]
    # rcssserver counts a cycle's possession after its checks, hfo2d v0 before them
    expected_cycle = 2 if rules == "hfo2d_v0" else 3
    assert statuses[expected_cycle - 1] == protocol.CAPTURED_BY_DEFENSE
    assert set(statuses[: expected_cycle - 1]) == {protocol.IN_GAME}
    goalie_world = _world_with(("l", 11, 20.0, 0.0), ("r", 1, 40.5, 0.0))
    judge = Referee(goalie_world.params, rules=rules)
    judge.reset(goalie_world)
    assert judge.analyse(goalie_world) == protocol.CAPTURED_BY_DEFENSE


@pytest.mark.parametrize("rules", referee.REFEREE_RULES)
def test_the_referee_judges_only_the_players_it_is_given(rules: str) -> None:
    world = _world_with(("l", 11, 20.0, 0.0), ("r", 1, 40.5, 0.0))
    judge = Referee(world.params, rules=rules, players=world.players[:1])
    judge.reset(world)
    assert [judge.analyse(world) for _ in range(3)] == [protocol.IN_GAME] * 3


@pytest.mark.parametrize("rules", referee.REFEREE_RULES)
def test_the_trial_time_is_a_truncation(rules: str) -> None:
    world = _world_with(("l", 11, 20.0, 0.0))
    judge = Referee(world.params, untouched_time=1000, trial_time=4, rules=rules)
    judge.reset(world)
    statuses = []
    while not statuses or statuses[-1] == protocol.IN_GAME:
        statuses.append(judge.analyse(world))
    assert statuses[-1] == protocol.OUT_OF_TIME and judge.truncated
    # hfo2d v0 ends on the trial's last cycle, rcssserver on the one after it
    assert len(statuses) == (4 if rules == "hfo2d_v0" else 5)


def test_unknown_referee_rules_are_refused() -> None:
    with pytest.raises(ValueError, match="unknown referee rules 'fifa'"):
        Referee(ServerParams(), rules="fifa")


# --- the NPCs ----------------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("env_id", "npc_class"),
    [
        ("HFO/EmptyGoal-v0", None),
        ("HFO/StaticKeeper-v0", "StillGoalie"),
        ("HFO/Keeper-v0", "ScriptedKeeper"),
        ("HFO/Keeper-v1", "Agent2dGoalie"),
    ],
)
def test_every_goalie_is_a_defense_npc_of_the_env(env_id: str, npc_class: str | None) -> None:
    env = gym.make(env_id).unwrapped
    if npc_class is None:
        assert env.defense_npcs == []
        return
    ((player, npc),) = env.defense_npcs
    assert player is env.keeper and type(npc).__name__ == npc_class and isinstance(npc, DefenseNPC)
    assert npc.params is env.params


def test_the_still_goalie_never_moves() -> None:
    env = gym.make("HFO/StaticKeeper-v0").unwrapped
    env.reset(seed=0)
    assert isinstance(env._keeper_policy, StillGoalie)
    for _ in range(20):
        _, _, terminated, truncated, info = env.step(DASH_AHEAD)
        assert info["keeper"][:2] == (52.5, 0.0)
        if terminated or truncated:
            break


def test_an_unpickled_goalie_shares_the_binding_of_equal_params() -> None:
    import pickle

    env = _keeper_v1()
    copy = pickle.loads(pickle.dumps(env))
    assert copy._keeper_policy._server_params is env._keeper_policy._server_params
    copy.step(DASH_AHEAD)
    _assert_cache_decays(_goalie_ball_cache(copy), 0.94)
