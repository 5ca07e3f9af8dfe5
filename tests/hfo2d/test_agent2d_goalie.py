"""HFO/Keeper-v1 as a whole: the agent2d goalie inside HFOEnv (fast path, seeds, carry-over, skill, catches)."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import hfo2d  # noqa: F401  (registers the envs)
import hfo2d.agent2d.decision as decision_module
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
    wait_frame = env._wait_frame
    bodies_after_wait: list[float] = []

    def wait_and_record() -> None:
        wait_frame()
        bodies_after_wait.append(env.keeper.body_deg)

    env._wait_frame = wait_and_record
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


# --- the speed paths (memo, string-free conversion, lazy table and view) decide exactly as the plain ones ------
def _random_play(env, steps: int, seed: int) -> list[tuple]:
    """Goalie state and command of every step under uniform random flat actions (the throughput benchmark's)."""
    actions = np.random.default_rng(seed).random((steps, 8), dtype=np.float32)
    trace: list[tuple] = []
    env.reset(seed=seed)
    for action in actions:
        _, _, terminated, truncated, info = env.step(action)
        command = env._keeper_policy.last_command
        trace.append((info["keeper"], None if command is None else (command.kind, command.a, command.b)))
        if terminated or truncated:
            env.reset()
    return trace


def _plain(monkeypatch: pytest.MonkeyPatch) -> None:
    """The unoptimised goalie: fullstate numbers through strings (no memo), the eager full intercept table, and
    none of the resting-ball shortcuts."""
    import hfo2d.agent2d.intercept as intercept_module

    monkeypatch.setattr(goalie_module, "fullstate_value", lambda x: float(f"{x:.6g}"))

    def full_table(view, player_rand=None, ball_rand=None, full=True):
        return build_intercept_table(view, player_rand, ball_rand, full=True)

    monkeypatch.setattr(goalie_module, "build_intercept_table", full_table)
    monkeypatch.setattr(intercept_module, "_RESTING_SHORTCUTS", False)
    monkeypatch.setattr(decision_module, "_RESTING_SHORTCUTS", False)


@pytest.mark.parametrize("noise", [False, True])
def test_the_speed_paths_play_exactly_as_the_plain_goalie(
    monkeypatch: pytest.MonkeyPatch, noise: bool
) -> None:
    fast_random = _random_play(gym.make("HFO/Keeper-v1", noise=noise).unwrapped, 1500, seed=4)
    fast_heuristic = play(gym.make("HFO/Keeper-v1", noise=noise).unwrapped, 4, seed=8)
    _plain(monkeypatch)
    assert _random_play(gym.make("HFO/Keeper-v1", noise=noise).unwrapped, 1500, seed=4) == fast_random
    assert play(gym.make("HFO/Keeper-v1", noise=noise).unwrapped, 4, seed=8) == fast_heuristic
    kinds = {step[1][0] for step in fast_random if step[1] is not None}
    assert {"turn", "dash"} <= kinds


def test_the_lazy_view_holds_the_fullstate_numbers() -> None:
    """Every field of the goalie's view (attacker numbers converted on first read, the kickable-opponent test
    decided from the raw position when surely far) equals the view built plainly from the fullstate's digits."""
    env = gym.make("HFO/Keeper-v1").unwrapped
    obs, _ = env.reset(seed=2)
    goalie = env._keeper_policy
    fs = lambda x: float(f"{x:.6g}")  # noqa: E731
    kickable = 0
    for _ in range(600):
        keeper, attacker, ball = env.keeper, env.agent, env.world.ball
        raw = (keeper.x, keeper.y, ball.x, ball.y, attacker.x, attacker.y, attacker.vx, attacker.vy)
        raw_body = attacker.body_deg
        obs, _, terminated, truncated, _ = env.step(heuristic(env, obs))
        view = goalie.last_view
        px, py, bx, by, ox, oy, ux, uy = (-fs(x) for x in raw)
        assert (view.px, view.py, view.ox, view.oy, view.ux, view.uy) == (px, py, ox, oy, ux, uy)
        assert view.obody == goalie_module.norm_deg(fs(raw_body) + 180.0)
        d_b, d_o, d_s = (
            math.hypot(bx - px, by - py),
            math.hypot(ox - bx, oy - by),
            math.hypot(ox - px, oy - py),
        )
        expected = bool(d_o < 1.085 + min(0.25, 0.02 * d_b) + min(0.25, 0.02 * d_s))
        assert view.kick_opp == expected or view.opp_tackle_count > 0
        kickable += view.kick_opp
        if terminated or truncated:
            obs, _ = env.reset()
    assert kickable > 20  # the heuristic striker dribbles: both answers of the test occur


def test_fullstate_value_is_the_six_digit_string_round_trip() -> None:
    """The memoised, string-free conversion gives the very doubles of float(f"{x:.6g}"), ties (half to even on
    the exact binary value), decade boundaries, tiny and huge numbers, zeros and NaN included."""
    import struct

    rng = np.random.default_rng(7)
    values = [0.0, -0.0, 1234.375, -1234.375, 1234.125, 0.0001234565, 99999.95, 9999.995, 0.001, 1e-16, 1e-17]
    values += [math.inf, -math.inf, math.nan, 5e-324, 1e300, 8000.0, 0.999999, 0.9999995, 179.99994101975]
    for e in range(-18, 6):
        for base in (10.0**e, 9.999995 * 10.0**e, 1.000005 * 10.0**e):
            values += [base, math.nextafter(base, math.inf), math.nextafter(base, -math.inf)]
    values += list(rng.uniform(-60.0, 60.0, 3000)) + list(
        rng.uniform(-1.0, 1.0, 1000) * 0.4 ** rng.integers(0, 60, 1000)
    )
    values += list(rng.integers(1, 2**24, 1000) / 2.0 ** rng.integers(0, 30, 1000))  # exact binary ties
    # below 1e-16 (scaled in several steps, divided in integers): every decade down to the subnormals
    values += list(rng.uniform(-1.0, 1.0, 3000) * 10.0 ** rng.integers(-323, -15, 3000).astype(float))
    for e in range(-323, -16):
        for base in (10.0**e, 9.999995 * 10.0**e, 1.234565 * 10.0**e):
            values += [base, math.nextafter(base, math.inf), math.nextafter(base, -math.inf)]
    values += [1e-323, -2.5e-323, 2.2250738585072014e-308, 2.225073858507201e-308]
    for x in values:
        x = float(x)
        want = struct.pack("<d", float(f"{x:.6g}"))
        for _ in range(2):  # the first call computes, the second reads the memo
            got = goalie_module.fullstate_value(x)
            assert struct.pack("<d", got) == want or (got != got and x != x), x


def _resting_views(n: int, seed: int) -> list:
    """Goalie views with a resting ball (W = +-0), near and far, in and out of the area, some with the ball off
    the cached field, the attacker anywhere up to 12 m from the ball."""
    from hfo2d.agent2d.common import GoalieView

    rng = np.random.default_rng(seed)
    views = []
    for _ in range(n):
        px, py = rng.uniform(-52.5, -30.0), rng.uniform(-15.0, 15.0)
        d = rng.choice([rng.uniform(0.0, 3.0), rng.uniform(3.0, 8.0), rng.uniform(8.0, 60.0)])
        a = rng.uniform(-math.pi, math.pi)
        bx, by = px + d * math.cos(a), py + d * math.sin(a)
        if rng.random() < 0.05:
            bx = -57.6  # off createBallCache's area
        wx, wy = float(rng.choice([0.0, -0.0])), float(rng.choice([0.0, -0.0]))
        views.append(
            GoalieView(
                int(rng.integers(0, 500)),
                px,
                py,
                rng.uniform(-0.5, 0.5) * 0.4 ** int(rng.integers(0, 40)),
                rng.uniform(-0.5, 0.5),
                rng.uniform(-180, 180),
                float(rng.choice([8000.0, rng.uniform(2300, 8000)])),
                1.0,
                float(rng.choice([1.0, rng.uniform(0.5, 1.0)])),
                bx,
                by,
                wx,
                wy,
                wx,
                wy,
                True,
                bx + rng.uniform(-12, 12),
                by + rng.uniform(-12, 12),
                rng.uniform(-1, 1),
                rng.uniform(-1, 1),
                rng.uniform(-180, 180),
                int(rng.choice([0, 0, 0, 3])),
                False,
                math.hypot(bx - px, by - py) <= 1.03,
                bool(rng.random() < 0.9),
                True,
                float(rng.choice([0.05, 0.0])),
                float(rng.choice([0.1, 0.0])),
            )
        )
    return views


def _table_numbers(t) -> tuple:
    entries = tuple(
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
        for e in t.self_cache
    )
    return t.self_min, t.opp_min, tuple(t.ball_cache), entries


def test_the_resting_ball_shortcuts_build_the_general_tables(monkeypatch: pytest.MonkeyPatch) -> None:
    import struct

    import hfo2d.agent2d.intercept as intercept_module

    def bits(x):
        if isinstance(x, float):
            return struct.pack("<d", x)  # tells -0.0 from 0.0
        if isinstance(x, tuple):
            return tuple(bits(y) for y in x)
        return x

    views = _resting_views(1500, seed=3)
    fast = [bits(_table_numbers(build_intercept_table(v, full=f))) for v in views for f in (True, False)]
    monkeypatch.setattr(intercept_module, "_RESTING_SHORTCUTS", False)
    plain = [bits(_table_numbers(build_intercept_table(v, full=f))) for v in views for f in (True, False)]
    assert fast == plain
    assert len({t[0] for t in fast}) > 10 and len({t[1] for t in fast}) > 5


def test_basic_move_turns_sideways_when_nothing_else_acts() -> None:
    """doCorrectBodyDir's second call (step 8): the opponent near the ball blocks step 6, the goalie is within
    doGoToMovePoint's threshold (step 7 passes) but not facing sideways, so it turns to +-90."""
    from hfo2d.agent2d.common import Effector, GoalieView, InterceptTable
    from hfo2d.agent2d.decision import basic_move, target_point

    def goalie_at(py: float, body: float) -> GoalieView:
        return GoalieView(
            100,
            -49.8,
            py,
            0.0,
            0.0,
            body,
            8000.0,
            1.0,
            1.0,
            -34.0,
            2.0,
            0.0,
            0.0,
            0.0,
            0.0,
            True,
            -31.0,
            3.0,
            0.0,
            0.0,
            180.0,
            0,
            False,
            False,
            True,
            True,
            0.05,
            0.1,
        )

    table = InterceptTable([(-34.0, 2.0)], [], 30, 20)
    mx, my = target_point(goalie_at(0.0, 0.0), table)
    assert mx == -49.8
    view = goalie_at(my - 1.1, 0.0)  # |my - py| = 1.1 >= 1 but below thr = 0.08 * |B - P| (about 1.3)
    assert 0.08 * view.ball_dist > 1.1 and view.ball_dist < 20.0
    eff = Effector()
    basic_move(eff, view, table)
    assert eff.command is not None and (eff.command.kind, eff.command.a) == ("turn", 90.0)
    eff = Effector()
    basic_move(eff, goalie_at(my - 1.1, 90.0), table)  # already sideways: the last resort, turn 0
    assert (eff.command.kind, eff.command.a) == ("turn", 0.0)


def test_the_resting_ball_decisions_match_the_general_rules(monkeypatch: pytest.MonkeyPatch) -> None:
    """The decision tree's resting-ball shortcuts (ballAt(n) without n, so without the lazy table's reach
    cycles) give the commands of the general rules, on varied views around the goal."""
    from hfo2d.agent2d.common import Effector

    def commands() -> list:
        out = []
        for v in views:
            eff = Effector()
            decision_module.decide(eff, v, build_intercept_table(v, full=False), -1000)
            c = eff.command
            out.append(None if c is None else (c.kind, c.a, c.b, c.foul))
        return out

    views = _resting_views(1500, seed=9)
    rng = np.random.default_rng(10)
    for v in views[::2]:  # half of them with the ball just around the penalty-area line
        v.bx = -36.0 + float(rng.uniform(-3.0, 3.0))
        v.self_kickable = math.hypot(v.bx - v.px, v.by - v.py) <= 1.03
    fast = commands()
    monkeypatch.setattr(decision_module, "_RESTING_SHORTCUTS", False)
    assert commands() == fast
    assert len({c[0] for c in fast if c}) >= 3
