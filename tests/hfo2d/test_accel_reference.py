"""hfo2d's optional C kernels (hfo2d._accel) against the pure-Python code they port, bit for bit.

Each kernel is compared with its Python reference on the same inputs (random states, edge values), and whole
games (team games with agent2d's goalie and field defenders, HFO/Keeper-v1) are played once with the extension and
once in a subprocess with ``HFO2D_PURE_PYTHON=1``: every observation, reward, status and player state must hash
the same. Skipped where the extension is not in use (not built: ``python setup.py build_ext --inplace``, or
``pip install`` with a C compiler; or ``HFO2D_PURE_PYTHON=1``); the golden tests (test_team_golden.py,
test_golden_rollouts.py) then check the Python alone.
"""

from __future__ import annotations

import copy
import hashlib
import json
import math
import os
import struct
import subprocess
import sys
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest

import hfo2d
from hfo2d import accel
from hfo2d.physics import BallState, PlayerState

_accel = accel.ACCEL  # hfo2d._accel while it is in use, else None

# (not built: python setup.py build_ext --inplace; or HFO2D_PURE_PYTHON=1, which the golden tests then check alone)
needs_extension = pytest.mark.skipif(not accel.in_use(), reason=f"no compiled kernels here: {accel.STATUS}")


def bits(values: Any) -> bytes:
    """The exact bytes of a float, or of a (nested) sequence of floats and ints (so that -0.0 and 0.0 differ)."""
    if isinstance(values, (bool, int)):
        return struct.pack("<q", int(values))
    if isinstance(values, float):
        return struct.pack("<d", values)
    return b"|".join(bits(v) for v in values)


# --- fullstate_value and hypot ---------------------------------------------------------------------------------
@needs_extension
def test_fullstate_value_kernel_is_the_python_conversion() -> None:
    from hfo2d.agent2d.goalie import fullstate_value_python

    rng = np.random.default_rng(0)
    numbers = np.concatenate(
        [
            rng.uniform(-60.0, 60.0, 20000),
            rng.uniform(-1.0, 1.0, 20000)
            * 10.0 ** rng.integers(-330, 6, 20000),  # every decade, tiny ones too
            np.round(rng.uniform(-100.0, 100.0, 5000), 4) + 5e-5,  # near ties of the sixth digit
            [0.0, -0.0, 5e-324, -5e-324, 1e-16, 9.99999e-17, 9999.995, 99999.95, 1e300, math.inf, -math.inf],
        ]
    ).tolist()
    mismatches = [x for x in numbers if bits(_accel.fullstate_value(x)) != bits(fullstate_value_python(x))]
    assert mismatches == []
    assert math.isnan(_accel.fullstate_value(math.nan))


@needs_extension
def test_hypot_kernel_is_pythons_math_hypot() -> None:
    rng = np.random.default_rng(1)
    xs = np.concatenate(
        [rng.uniform(-60, 60, 50000), rng.uniform(-1, 1, 20000) * 10.0 ** rng.integers(-320, 300, 20000)]
    )
    ys = np.concatenate(
        [rng.uniform(-40, 40, 50000), rng.uniform(-1, 1, 20000) * 10.0 ** rng.integers(-320, 300, 20000)]
    )
    pairs = list(zip(xs.tolist(), ys.tolist(), strict=True))
    pairs += [
        (0.0, -0.0),
        (3.0, 4.0),
        (5e-324, 1e-310),
        (1e308, 1e308),
        (math.inf, math.nan),
        (math.nan, 1.0),
    ]
    mismatches = [(x, y) for x, y in pairs if bits(_accel.hypot(x, y)) != bits(math.hypot(x, y))]
    assert [p for p in mismatches if not math.isnan(math.hypot(*p))] == []


# --- the low-level features -----------------------------------------------------------------------------------
def random_player(rng: np.random.Generator, unum: int, side: str = "l") -> PlayerState:
    still = rng.random() < 0.2
    return PlayerState(
        side=side,
        unum=unum,
        x=float(rng.uniform(-10.0, 55.0)),
        y=float(rng.uniform(-36.0, 36.0)),
        vx=0.0 if still else float(rng.uniform(-1.0, 1.0)),
        vy=0.0 if still else float(rng.uniform(-1.0, 1.0)),
        body_deg=float(rng.uniform(-180.0, 180.0)),
        stamina=float(rng.choice([8000.0, 0.0, rng.uniform(0.0, 8000.0)])),
        collided_ball=bool(rng.random() < 0.3),
        collided_player=bool(rng.random() < 0.3),
        collided_post=bool(rng.random() < 0.3),
        tackle_cycles=int(rng.choice([0, 0, 3])),
    )


@needs_extension
@pytest.mark.parametrize("normalisers", ["paper", "master"])
def test_feature_kernel_is_the_python_features(normalisers: str) -> None:
    from hfo2d import features

    kwargs = {}
    if normalisers == "master":
        kwargs = {
            "max_dist": features.HFO_MASTER_MAX_DIST,
            "out_of_bounds_x_max": features.HFO_MASTER_OUT_OF_BOUNDS_X_DIST_MAX,
            "out_of_bounds_y_max": features.HFO_MASTER_OUT_OF_BOUNDS_Y_DIST_MAX,
        }
    rng = np.random.default_rng(2)
    for trial in range(3000):
        player = random_player(rng, 7)
        if trial % 50 == 0:  # on a landmark (the goal centre), and with the ball at its feet
            player.x, player.y = features.PITCH_HALF_LENGTH, 0.0
        ball = BallState(
            x=float(rng.uniform(-5, 55)), y=float(rng.uniform(-35, 35)), vx=float(rng.uniform(-3, 3))
        )
        if trial % 7 == 0:
            ball.x, ball.y, ball.vx = player.x, player.y, 0.0
        mates = [random_player(rng, 8 + k) for k in range(int(rng.integers(0, 4)))]
        opponents = [random_player(rng, 1 + k, "r") for k in range(int(rng.integers(0, 5)))]
        if len(opponents) > 2 and trial % 3 == 0:  # equal distances: the stable sort keeps the given order
            opponents[1].x, opponents[1].y = 2.0 * player.x - opponents[0].x, 2.0 * player.y - opponents[0].y
        want = features.low_level_feature_list_python(player, ball, 1.03, mates, opponents, **kwargs)
        got = _accel.low_level_feature_list(
            player,
            ball,
            1.03,
            mates,
            opponents,
            kwargs.get("max_dist", features.MAX_HFO_DIST),
            kwargs.get("out_of_bounds_x_max", features.OUT_OF_BOUNDS_X_DIST_MAX),
            kwargs.get("out_of_bounds_y_max", features.OUT_OF_BOUNDS_Y_DIST_MAX),
        )
        assert bits(got) == bits(want), trial
        if not kwargs:
            assert bits(features.paper_feature_list(player, ball, 1.03, mates, opponents)) == bits(want)


@needs_extension
def test_feature_kernel_refuses_bad_inputs_with_clear_errors() -> None:
    player = PlayerState(side="l", unum=7)
    with pytest.raises(TypeError, match="low_level_feature_list"):
        _accel.low_level_feature_list(player, BallState(), 1.03)
    with pytest.raises(AttributeError):
        _accel.low_level_feature_list(player, object(), 1.03, (), ())
    with pytest.raises(ValueError, match="at most"):
        _accel.low_level_feature_list(player, BallState(), 1.03, [player] * 65, ())


# --- agent2d: the intercept table's kernels --------------------------------------------------------------------
def random_ball_view(rng: np.random.Generator) -> SimpleNamespace:
    resting = rng.random() < 0.3
    return SimpleNamespace(
        bx=float(rng.uniform(-55, 55)),
        by=float(rng.uniform(-38, 38)),
        wx=0.0 if resting else float(rng.uniform(-3, 3)),
        wy=0.0 if resting else float(rng.uniform(-3, 3)),
        px=float(rng.uniform(-52, 52)),
        py=float(rng.uniform(-34, 34)),
        self_kickable=bool(rng.random() < 0.05),
    )


@needs_extension
@pytest.mark.parametrize("shortcuts", [True, False])
def test_ball_path_and_reach_kernels_are_the_python_predictions(
    monkeypatch: pytest.MonkeyPatch, shortcuts: bool
) -> None:
    from hfo2d.agent2d import intercept

    monkeypatch.setattr(intercept, "_RESTING_SHORTCUTS", shortcuts)
    rng = np.random.default_rng(3)
    for trial in range(2000):
        view = random_ball_view(rng)
        ball = intercept._ball_part_python(view)
        got_ball = intercept._ball_part(view)
        assert bits(got_ball[0]) == bits(ball[0]) and got_ball[1:] == ball[1:], trial
        assert bits(got_ball[2:]) == bits(ball[2:])
        players = [
            (
                float(rng.uniform(-55, 55)),
                float(rng.uniform(-38, 38)),
                float(rng.uniform(-1, 1)),
                float(rng.uniform(-1, 1)),
                float(rng.uniform(-400, 400)),
                int(rng.choice([0, 0, 0, 4, 9])),
            )
            for _ in range(int(rng.integers(0, 4)))
        ]
        for teammate in (False, True):
            for best in (1000, 3):
                want = intercept.fastest_reach_python(view, ball, players, teammate, best)
                assert intercept.fastest_reach(view, ball, players, teammate, best) == want, trial
        for x, y, vx, vy, body, frozen in players:
            resting = view.wx == 0.0 and view.wy == 0.0
            args = (
                x,
                y,
                vx,
                vy,
                body,
                frozen,
                resting,
                float(rng.uniform(0, 30)),
                ball[0],
                float(rng.uniform(-9, 9)),
            )
            assert intercept._predict_player(*args) == intercept._predict_player_python(*args), trial
    for dist in [
        0.0,
        0.001,
        0.0011,
        0.6,
        0.6012,
        9.3334,
        9.34,
        20.0,
        1000.0,
        *rng.uniform(0, 60, 500).tolist(),
    ]:
        assert _accel.cycles_to_reach_distance(dist) == intercept.cycles_to_reach_distance(dist)


def outcome(function: Any, *args: Any) -> Any:
    """The result of a call, or the type of the exception it raised."""
    try:
        return function(*args)
    except Exception as error:  # noqa: BLE001 (any exception is an outcome to compare)
        return type(error)


@needs_extension
def test_reach_kernels_fail_where_the_python_fails() -> None:
    """Non-finite inputs: the kernels return or raise as the Python does (no undefined conversion in C)."""
    from hfo2d.agent2d import intercept

    for dist in (math.nan, math.inf, -math.inf):
        assert outcome(_accel.cycles_to_reach_distance, dist) == outcome(
            intercept.cycles_to_reach_distance, dist
        )
    cache = [(10.0, 5.0), (11.0, 5.0)]
    for rel_y in (math.nan, math.inf):
        args = (0.0, 0.0, 0.0, 0.0, 0.0, 0, False, 0.0, cache, rel_y)
        assert outcome(intercept._predict_player, *args) == outcome(intercept._predict_player_python, *args)


@needs_extension
def test_final_entry_kernel_is_the_python_predict_final() -> None:
    from hfo2d.agent2d import intercept

    rng = np.random.default_rng(4)
    for trial in range(3000):
        vx, vy = (float(v) for v in rng.uniform(-1, 1, 2))
        stamina = float(rng.choice([8000.0, 2400.0, 100.0, rng.uniform(0, 8000)]))
        effort = float(rng.choice([1.0, 0.8, 0.6]))
        recovery = float(rng.choice([1.0, 0.7, 0.5]))
        args = (
            *(float(v) for v in rng.uniform(-50, 50, 2)),
            vx,
            vy,
            float(rng.uniform(-180, 180)),
            math.sqrt(vx * vx + vy * vy),
            bool(rng.random() < 0.5),
            *(float(v) for v in rng.uniform(-50, 50, 2)),
            *(float(v) for v in rng.uniform(-3, 3, 2)),
        )
        max_cycle = int(rng.integers(1, 31))
        player_rand = float(rng.choice([0.0, 0.1]))
        want = intercept._final_entry_python(*args, [(stamina, effort, recovery)], max_cycle, player_rand)
        got = intercept._final_entry(*args, [(stamina, effort, recovery)], max_cycle, player_rand)
        assert got == want and bits(got.stamina) == bits(want.stamina), trial


@needs_extension
def test_short_step_kernels_are_the_python_predictions() -> None:
    """predictTurnCycleShort and predictDashCycleShort (forward and back dashes, tired and fresh players)."""
    from hfo2d.agent2d import intercept

    rng = np.random.default_rng(7)
    for trial in range(4000):
        px, py, bx, by = (float(v) for v in rng.uniform(-50, 50, 4))
        vx, vy = (float(v) for v in rng.uniform(-0.8, 0.8, 2))
        me = (px, py, vx, vy, float(rng.uniform(-180, 180)), math.hypot(vx, vy), False, bx, by, 0.0, 0.0, 1.0)
        target_angle = float(rng.uniform(-180, 180))
        target_dist = float(rng.choice([0.5, rng.uniform(0, 10)]))
        speed = float(rng.uniform(0, 1))
        area = float(rng.choice([0.1, 0.685, 0.935, 1.15]))
        turn = intercept._turn_short_python(target_angle, target_dist, me[4], speed, area)
        assert bits(intercept._turn_short(target_angle, target_dist, me[4], speed, area)) == bits(turn), trial
        cycle = int(rng.integers(1, 6))
        n_turn = int(rng.integers(0, cycle + 1))
        stamina = float(rng.choice([8000.0, 2500.0, 600.0, rng.uniform(0, 8000)]))
        wt = [(stamina, float(rng.choice([1.0, 0.7])), float(rng.choice([1.0, 0.6])))]
        near = rng.random() < 0.5  # the ball within a few dashes, so that candidates are found
        xbx = px + float(rng.uniform(-3, 3)) if near else float(rng.uniform(-50, 50))
        xby = py + float(rng.uniform(-3, 3)) if near else float(rng.uniform(-50, 50))
        args = (
            cycle,
            n_turn,
            float(rng.uniform(-180, 180)),
            bool(rng.random() < 0.5),
            xbx,
            xby,
            float(rng.choice([1.085, 1.3])),
            px + vx,
            py + vy,
            float(rng.uniform(-180, 180)),
        )
        want: list[tuple] = []
        got: list[tuple] = []
        intercept._dash_short_python(me, list(wt), *args, want)
        intercept._dash_short(me, list(wt), *args, got)
        assert got == want and bits(got) == bits(want), trial


@needs_extension
def test_server_params_reach_the_bound_kernels() -> None:
    """The kernels read the constants intercept._bind gives them: a game with another ball decay and kickable
    margin predicts as its Python reference does."""
    from hfo2d.agent2d import common, intercept
    from hfo2d.agent2d.common import bind_server_params, canonical_params
    from hfo2d.physics import ServerParams

    rng = np.random.default_rng(5)
    previous = common.BOUND_PARAMS
    odd = canonical_params(
        ServerParams.with_overrides({"ball_decay": 0.5, "kickable_margin": 1.2, "tackle_cycles": 6})
    )
    bind_server_params(odd)
    try:
        for _ in range(300):
            view = random_ball_view(rng)
            ball = intercept._ball_part_python(view)
            player = (
                *rng.uniform(-50, 50, 4).tolist(),
                float(rng.uniform(-180, 180)),
                int(rng.choice([0, 4])),
            )
            for teammate in (False, True):
                got = intercept.fastest_reach(view, ball, [player], teammate)
                assert got == intercept.fastest_reach_python(view, ball, [player], teammate)
    finally:
        bind_server_params(previous)


# --- agent2d: the NPCs' fullstate conversions ------------------------------------------------------------------
@needs_extension
def test_conversion_kernels_are_the_python_conversions() -> None:
    from hfo2d.agent2d import goalie

    rng = np.random.default_rng(6)
    for trial in range(1000):
        players = [random_player(rng, k, "lr"[k % 2]) for k in range(int(rng.integers(1, 7)))]
        for p in players:
            if rng.random() < 0.3:
                p.vx, p.vy = 1e-17 * rng.random(), -3e-200  # the tiny velocities of a standing player
        ball = BallState(x=float(rng.uniform(-55, 55)), y=float(rng.uniform(-35, 35)))
        skip = players[0] if trial % 2 else None
        args = (players, skip, float(rng.uniform(-50, 50)), float(rng.uniform(-30, 30)), 1.5, -2.5)
        got = _accel.mirrored_players(*args)
        want = goalie.mirrored_players_python(*args)
        assert [entry[3] for entry in got] == [entry[3] for entry in want]
        assert bits([entry[:3] for entry in got]) == bits([entry[:3] for entry in want]), trial
        assert bits(_accel.mirrored_self(players[-1], ball)) == bits(
            goalie.mirrored_self_python(players[-1], ball)
        )


# --- physics ---------------------------------------------------------------------------------------------------
def random_world(seed: int, noise: bool):
    from hfo2d.physics import ServerParams, World

    rng = np.random.default_rng(seed)
    world = World(ServerParams(), np.random.default_rng(seed + 100), noise=noise)
    for k in range(5):
        p = world.add_player("lr"[k % 2], k + 1)
        template = random_player(rng, k + 1)
        p.x, p.y, p.vx, p.vy, p.body_deg = template.x, template.y, template.vx, template.vy, template.body_deg
        p.ax, p.ay = (float(v) for v in rng.uniform(-1.5, 1.5, 2)) if rng.random() < 0.7 else (0.0, 0.0)
        p.recovery = float(rng.choice([1.0, 0.6]))
        p.effort = float(rng.choice([1.0, 0.7, 0.6]))
        p.stamina = float(rng.choice([8000.0, 2000.0, 5000.0, 100.0]))
        p.catch_ban = int(rng.choice([0, 2]))
        p.tackle_cycles = int(rng.choice([0, 0, 3]))
    world.players[0].x, world.players[0].y = 52.0, 7.2  # next to a post
    world.ball.x, world.ball.y = float(rng.uniform(-50, 52)), float(rng.uniform(-30, 30))
    world.ball.vx, world.ball.vy = (float(v) for v in rng.uniform(-2.5, 2.5, 2))
    return world


def world_state(world) -> list[Any]:
    fields = ("x", "y", "vx", "vy", "ax", "ay", "stamina", "effort", "recovery", "capacity", "catch_ban")
    state = [
        [getattr(p, f) for f in fields] + [p.collided_post, p.collided_ball, p.collided_player]
        for p in world.players
    ]
    ball = world.ball
    state.append(
        [ball.x, ball.y, ball.vx, ball.vy, ball.ax, ball.ay, ball.collided_post, ball.collided_player]
    )
    state.append([world._next_uniform, len(world._uniforms), world.cycle])
    return state


@needs_extension
@pytest.mark.parametrize("noise", [True, False])
def test_world_steps_with_the_kernels_as_with_the_python(noise: bool) -> None:
    """World.step (move, stamina, overlap kernels) against the same world stepped by the Python references, over
    enough cycles that the random-number buffer is refilled mid-cycle."""
    from hfo2d import physics

    for seed in range(4):
        fast = random_world(seed, noise)
        slow = copy.deepcopy(fast)
        for cycle in range(300):
            if cycle % 5 == 0:
                for a, b in zip(fast.players, slow.players, strict=True):
                    a.ax = b.ax = 0.3 * math.cos(cycle)
                    a.ay = b.ay = 0.3 * math.sin(cycle)
            fast.step()
            with pytest.MonkeyPatch.context() as patch:
                patch.setattr(physics, "_ACCEL", None)
                patch.setattr(physics, "_ACCEL_MOVE", None)
                patch.setattr(physics, "_any_overlap", physics._any_overlap_python)
                slow.step()
            assert bits(world_state(fast)) == bits(world_state(slow)), (seed, cycle)


@needs_extension
def test_stamina_and_overlap_kernels_are_the_python_rules() -> None:
    from hfo2d import physics

    for seed in range(50):
        fast = random_world(seed, True)
        slow = copy.deepcopy(fast)
        sp = fast.params
        thresholds = (sp.recover_dec_thr * 8000.0, sp.effort_dec_thr * 8000.0, sp.effort_inc_thr * 8000.0)
        constants = (
            *thresholds,
            sp.stamina_max,
            sp.recover_min,
            sp.recover_dec,
            sp.effort_min,
            sp.effort_dec,
            sp.effort_init,
            sp.effort_inc,
            sp.stamina_inc_max,
        )
        for limited in (True, False):
            _accel.update_stamina(fast.players, *constants, limited)
            physics._update_stamina_python(slow.players, *constants, limited)
            assert bits(world_state(fast)) == bits(world_state(slow)), seed
        for limits in ((0.385**2, 0.6**2), (30.0**2, 0.0), (0.0, 30.0**2), (0.0, 0.0)):
            assert _accel.any_overlap(fast.players, fast.ball, *limits) == physics._any_overlap_python(
                fast.players, fast.ball, *limits
            )


# --- the team game's flat actions ------------------------------------------------------------------------------
@needs_extension
def test_flat_action_kernel_decodes_as_the_python(monkeypatch: pytest.MonkeyPatch) -> None:
    """TeamGame._parse_action through the kernel and through the Python alone: the same (kind, parameters), and
    the same error for what the kernel hands back (other dtypes, byte orders, shapes, strides, values)."""
    from hfo2d import team as team_module
    from hfo2d.team import TeamGame

    game = TeamGame(offense_agents=1, defense_agents=1, defense_npcs=1)
    rng = np.random.default_rng(8)
    kernel = team_module._ACCEL_DECODE_FLAT
    assert kernel is not None
    for agent in game.agents:
        size = agent.layout.size
        actions: list[Any] = []
        for _ in range(300):
            actions.append(rng.random(size, dtype=np.float32))
            actions.append(rng.random(size))
        ties = np.full(size, 0.5, dtype=np.float32)
        actions += [ties, np.zeros(size), np.ones(size, dtype=np.float32)]
        actions += [
            rng.random(size).astype(">f8"),  # another byte order
            rng.random(size).astype(np.float16),
            rng.random(2 * size)[::2],  # strided
            rng.random(size + 1),
            rng.random((1, size)),
            np.full(size, np.nan),
            np.full(size, 1.5, dtype=np.float32),
            rng.random(size).tolist(),
        ]
        for action in actions:
            fast = outcome(game._parse_action, agent, action)
            with monkeypatch.context() as patch:
                patch.setattr(team_module, "_ACCEL_DECODE_FLAT", None)
                slow = outcome(game._parse_action, agent, action)
            assert fast == slow and bits([fast[0], fast[1]] if isinstance(fast, tuple) else []) == bits(
                [slow[0], slow[1]] if isinstance(slow, tuple) else []
            )
        assert kernel(rng.random(size + 1), size, agent.flat_decoding) is None
        assert kernel(np.full(size, np.nan), size, agent.flat_decoding) is None


# --- whole games, with the extension and without ---------------------------------------------------------------
GAMES: tuple[tuple[str, dict[str, Any], int, int], ...] = (
    ("2v2", {"offense_agents": 2, "defense_npcs": 2}, 0, 600),
    ("2v2-no-noise", {"offense_agents": 2, "defense_npcs": 2, "noise": False}, 1, 400),
    ("1v1-hfo", {"offense_agents": 1, "defense_npcs": 1, "feature_set": "hfo"}, 2, 400),
    ("3v4-defense-agent", {"offense_agents": 3, "defense_agents": 1, "defense_npcs": 3}, 3, 300),
)


def game_digests() -> dict[str, str]:
    """SHA-256 of every observation, reward, status and player / ball state of the games above and of
    HFO/Keeper-v1, every agent acting uniformly at random (episode resets included)."""
    import gymnasium as gym

    from hfo2d.team import TeamGame

    digests = {}
    for name, kwargs, seed, cycles in GAMES:
        game = TeamGame(**kwargs)
        rng = np.random.default_rng(seed)
        digest = hashlib.sha256()
        observations, _ = game.reset(seed=seed)
        for _ in range(cycles):
            actions = {agent.name: rng.random(agent.layout.size, dtype=np.float32) for agent in game.agents}
            observations, rewards, terminated, truncated, infos = game.step(actions)
            for agent_name in sorted(observations):
                digest.update(observations[agent_name].tobytes())
                digest.update(struct.pack("<d", rewards[agent_name]))
                digest.update(str(infos[agent_name]["status"]).encode())
            for p in (*game.world.players, game.world.ball):
                digest.update(bits([p.x, p.y, p.vx, p.vy]))
            if terminated or truncated:
                game.reset()
        digests[name] = digest.hexdigest()
    env = gym.make("HFO/Keeper-v1").unwrapped
    rng = np.random.default_rng(9)
    digest = hashlib.sha256()
    env.reset(seed=9)
    for _ in range(600):
        observation, reward, terminated, truncated, _ = env.step(rng.random(8, dtype=np.float32))
        digest.update(observation.tobytes() + struct.pack("<d", reward))
        if terminated or truncated:
            env.reset()
    digests["Keeper-v1"] = digest.hexdigest()
    return digests


@needs_extension
def test_games_play_the_same_with_the_extension_and_without() -> None:
    assert accel.in_use(), accel.STATUS
    envs_dir = os.path.dirname(os.path.dirname(os.path.abspath(hfo2d.__file__)))
    env = {**os.environ, accel.PURE_PYTHON_ENV: "1"}
    env["PYTHONPATH"] = os.pathsep.join([envs_dir, env.get("PYTHONPATH", "")])
    pure = subprocess.run(
        [sys.executable, os.path.abspath(__file__)],
        env=env,
        capture_output=True,
        text=True,
        check=True,
        timeout=300,
    )
    reported = json.loads(pure.stdout.strip().splitlines()[-1])
    assert reported["in_use"] is False and accel.PURE_PYTHON_ENV in reported["status"]
    assert reported["digests"] == game_digests()


_WITHOUT_EXTENSION = """
import importlib.abc, sys

class NoExtension(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path, target=None):
        if name == "hfo2d._accel":
            raise ImportError("hidden by the test")
        return None

sys.meta_path.insert(0, NoExtension())
from hfo2d import accel
from hfo2d.team import TeamGame

assert not accel.in_use() and "not available" in accel.STATUS, accel.STATUS
game = TeamGame(offense_agents=2, defense_npcs=2)
game.reset(seed=0)
for _ in range(50):
    game.step({agent.name: [0.6, 0.1, 0.1, 0.5, 0.5, 0.5, 0.5, 0.5] for agent in game.agents})
print("played")
"""


def test_hfo2d_runs_without_the_extension() -> None:
    """A machine without a C compiler installs hfo2d without hfo2d._accel: it imports and plays in pure Python
    (the extension hidden from the import system here, whether it is built or not)."""
    envs_dir = os.path.dirname(os.path.dirname(os.path.abspath(hfo2d.__file__)))
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([envs_dir, os.environ.get("PYTHONPATH", "")])}
    env.pop(accel.PURE_PYTHON_ENV, None)
    run = subprocess.run(
        [sys.executable, "-c", _WITHOUT_EXTENSION], env=env, capture_output=True, text=True, timeout=120
    )
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip().endswith("played")


if __name__ == "__main__":  # the subprocess of the test above (and a way to print the digests)
    print(json.dumps({"in_use": accel.in_use(), "status": accel.STATUS, "digests": game_digests()}))
