"""HFOEnv refuses bad input with an error naming it, and leaves its state as it was.

Cases: stepping after the episode ended, hand placements off the pitch or overlapping, ``server_params`` that
are not a mapping or out of range, a non-bool ``noise``, boolean or complex actions, ``keeper_skill`` for a task
without a scripted goalie, and kwargs that would turn a registered id into another environment.
"""

from __future__ import annotations

import math
import warnings

import gymnasium as gym
import numpy as np
import pytest

import hfo2d  # noqa: F401  (registers the environments)
from hfo2d.hfo_env import PLACEMENT_MAX_X, PLACEMENT_MAX_Y, HFOEnv
from hfo2d.physics import SERVER_PARAM_RANGES, ServerParams

TURN_NONE = np.array([0, 1, 0, 0, 0.5, 0.5, 0, 0.5], dtype=np.float32)
KICK_TO_GOAL = np.array([0, 0, 1, 0, 0.5, 0.5, 1.0, 0.5], dtype=np.float32)  # full power straight ahead
NEAR_GOAL = {"player": (48.0, 0.0, 0.0), "ball": (48.6, 0.0)}


def snapshot(env: HFOEnv) -> tuple:
    world = env.world
    players = tuple(
        (p.x, p.y, p.vx, p.vy, p.body_deg, p.stamina, p.effort, p.recovery) for p in world.players
    )
    ball = world.ball
    return (
        players,
        (ball.x, ball.y, ball.vx, ball.vy),
        world.cycle,
        env.steps,
        env.status,
        env.np_random.bit_generator.state["state"]["state"],
    )


# --- stepping after the end ---------------------------------------------------------------------------------------
def test_step_after_termination_says_call_reset_and_changes_nothing() -> None:
    env = HFOEnv(noise=False)
    env.reset(seed=0, options=NEAR_GOAL)
    _, _, terminated, truncated, info = env.step(KICK_TO_GOAL)
    for _ in range(10):
        if terminated:
            break
        _, _, terminated, truncated, info = env.step(TURN_NONE)
    assert terminated and not truncated and info["status"] == "GOAL"
    before = snapshot(env)
    with pytest.raises(RuntimeError, match=r"the episode has ended \(GOAL\): call reset\(\) before step\(\)"):
        env.step(TURN_NONE)
    assert snapshot(env) == before
    env.reset(seed=1)
    env.step(TURN_NONE)  # a new episode steps again


def test_step_after_truncation_says_call_reset() -> None:
    env = HFOEnv(frames_per_trial=2)
    env.reset(seed=0, options={"player": (10.0, 0.0, 0.0), "ball": (30.0, 0.0)})
    assert env.step(TURN_NONE)[3] is False
    assert env.step(TURN_NONE)[3] is True
    before = snapshot(env)
    with pytest.raises(RuntimeError, match=r"ended \(OUT_OF_TIME\): call reset\(\)"):
        env.step(TURN_NONE)
    assert snapshot(env) == before
    assert env.render_mode is None and env.status == "OUT_OF_TIME"


# --- hand placements ----------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("task", "options", "message"),
    [
        ("empty_goal", {"player": (200.0, 0.0, 0.0)}, r"'player' at \(200, 0\) is off the pitch"),
        ("empty_goal", {"ball": (10.0, 100.0)}, r"'ball' at \(10, 100\) is off the pitch"),
        ("keeper", {"keeper": (-60.0, 0.0, 0.0)}, r"'keeper' at \(-60, 0\) is off the pitch"),
        ("empty_goal", {"ball": (57.6, 0.0)}, "x must lie in \\[-57.5, 57.5\\] and y in \\[-39, 39\\]"),
        ("empty_goal", {"player": (20.0, 5.0, 0.0), "ball": (20.1, 5.0)}, "'player' and 'ball' 0.1 m apart"),
        ("empty_goal", {"player": (20.0, 5.0, 0.0), "ball": (20.0, 5.0)}, "at least 0.385 m apart"),
        ("static_keeper", {"player": (52.2, 0.0, 0.0)}, "'player' and 'keeper start' 0.3 m apart"),
        ("keeper", {"ball": (52.5, 0.2)}, "'ball' and 'keeper start'"),
        ("keeper", {"ball": (40.0, 0.0), "keeper": (40.1, 0.3, 0.0)}, "'ball' and 'keeper'"),
        ("keeper", {"player": (30.0, 0.0, 0.0), "keeper": (30.5, 0.0, 0.0)}, "at least 0.6 m apart"),
    ],
)
def test_bad_placements_are_refused_and_change_nothing(task: str, options: dict, message: str) -> None:
    env = HFOEnv(task=task)
    env.reset(seed=0)
    env.step(TURN_NONE)
    before = snapshot(env)
    with pytest.raises(ValueError, match=message):
        env.reset(seed=5, options=options)
    assert snapshot(env) == before
    env.step(TURN_NONE)  # the episode goes on


def test_placements_on_the_margin_and_just_touching_are_accepted() -> None:
    env = HFOEnv(task="keeper")
    params = env.params
    touching = params.player_size + params.ball_size
    _, info = env.reset(
        seed=0,
        options={
            "player": (-PLACEMENT_MAX_X, PLACEMENT_MAX_Y, 0.0),
            "ball": (30.0, 0.0),
            "keeper": (30.0 + touching, 0.0, 180.0),
        },
    )
    assert info["player"][:2] == (-57.5, 39.0) and math.isclose(info["keeper"][0] - info["ball"][0], touching)


# --- constructor kwargs -------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("overrides", "message"),
    [
        ({"ball_decay": -0.5}, "'ball_decay' must be in \\[0, 1\\], got -0.5"),
        ({"ball_decay": 1.5}, "'ball_decay' must be in \\[0, 1\\], got 1.5"),
        ({"player_size": 0}, "'player_size' must be > 0"),
        ({"inertia_moment": -1}, "'inertia_moment' must be >= 0"),
        ({"dash_angle_step": 0}, "'dash_angle_step' must be in \\(0, 360\\]"),
        ({"ball_decay": True}, "'ball_decay' must be a real number, got True"),
        ({"ball_decay": "0.9"}, "'ball_decay' must be a real number, got '0.9'"),
        ({"min_moment": 10}, "'min_moment' must be in \\[-180, 0\\]"),
        ({"maxpower": 0}, "'maxpower' must be > 0"),
    ],
)
def test_server_params_out_of_range(overrides: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        HFOEnv(server_params=overrides)


def test_every_server_param_has_a_range_that_holds_its_default_and_is_checked() -> None:
    defaults = ServerParams()
    assert set(SERVER_PARAM_RANGES) == set(ServerParams.field_names())
    for name in ServerParams.field_names():
        allowed = SERVER_PARAM_RANGES[name]
        assert allowed.contains(getattr(defaults, name)), name
        outside = [allowed.low] if allowed.low_open else [allowed.low - 1.0]
        outside.append(allowed.high + 1.0)
        for value in outside:
            if math.isfinite(value):
                with pytest.raises(ValueError, match=name):
                    ServerParams.with_overrides({name: value})
        ServerParams.with_overrides({name: getattr(defaults, name)})  # its own default is accepted


def test_server_params_must_be_a_mapping() -> None:
    with pytest.raises(ValueError, match="server_params must be a mapping") as error:
        HFOEnv(server_params="ball_decay=0.9")  # type: ignore[arg-type]
    assert "unknown" not in str(error.value)
    with pytest.raises(ValueError, match="server_params must be a mapping"):
        HFOEnv(server_params=[("ball_decay", 0.9)])  # type: ignore[arg-type]
    assert HFOEnv(server_params={}).params == ServerParams()


@pytest.mark.parametrize("noise", ["no", 0, 1, None, 0.0])
def test_noise_must_be_a_bool(noise: object) -> None:
    with pytest.raises(ValueError, match="noise must be True or False"):
        HFOEnv(noise=noise)  # type: ignore[arg-type]


def test_noise_accepts_numpy_bools() -> None:
    assert HFOEnv(noise=np.bool_(False)).noise is False


@pytest.mark.parametrize("task", ["empty_goal", "static_keeper"])
def test_keeper_skill_without_a_scripted_goalie_is_an_error(task: str) -> None:
    with pytest.raises(ValueError, match=f"keeper_skill is for task 'keeper'.*task '{task}'"):
        HFOEnv(task=task, keeper_skill=0.5)
    assert HFOEnv(task=task).keeper_skill == 1.0
    assert HFOEnv(task="keeper", keeper_skill=0.5).keeper_skill == 0.5


# --- registered ids -----------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("env_id", "kwargs", "message"),
    [
        ("HFO/EmptyGoal-v0", {"task": "keeper"}, "HFO/EmptyGoal-v0 is task='empty_goal'.*make HFO/Keeper-v0"),
        ("HFO/StaticKeeper-v0", {"task": "empty_goal"}, "make HFO/EmptyGoal-v0"),
        ("HFO/Keeper-v1", {"goalie": "hfo2d"}, "HFO/Keeper-v1 is goalie='agent2d'.*make HFO/Keeper-v0"),
        ("HFO/Keeper-v0", {"goalie": "agent2d"}, "make HFO/Keeper-v1"),
        ("HFO/Keeper-v0", {"task": "penalty"}, r"use hfo2d.HFOEnv\(task='penalty', ...\)"),
        ("HFO/EmptyGoal-v0", {"keeper_skill": 0.5}, "keeper_skill is for task 'keeper'"),
    ],
)
def test_kwargs_that_change_a_registered_id_are_refused(env_id: str, kwargs: dict, message: str) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)  # HFO/Keeper-v0 has a newer version
        with pytest.raises(ValueError, match=message):
            gym.make(env_id, **kwargs)


def test_registered_ids_keep_their_own_kwargs() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        v1 = gym.make("HFO/Keeper-v1").unwrapped
        v0 = gym.make("HFO/Keeper-v0", task="keeper", goalie="hfo2d", keeper_skill=0.5).unwrapped
    assert (v1.task, v1.goalie) == ("keeper", "agent2d")
    assert (v0.task, v0.goalie, v0.keeper_skill) == ("keeper", "hfo2d", 0.5)
    assert gym.make("HFO/EmptyGoal-v0", task="empty_goal", noise=False).unwrapped.noise is False


# --- actions ------------------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "action",
    [
        np.array([0, 1, 0, 0, 0.5, 0.5, 0, 0.5], dtype=np.complex64),
        np.array([0, 1, 0, 0, 1, 1, 0, 1], dtype=bool),
        [False, True, False, False, 0.5, 0.5, 0.0, 0.5],
        [0, 1, 0, 0, 0.5 + 0j, 0.5, 0, 0.5],
    ],
    ids=["complex array", "bool array", "list with bools", "list with a complex"],
)
def test_flat_actions_must_be_real(action: object) -> None:
    env = HFOEnv()
    env.reset(seed=0)
    before = snapshot(env)
    with pytest.raises(ValueError, match="flat action must be real numbers, not booleans or complex numbers"):
        env.step(action)
    assert snapshot(env) == before


def test_parameterized_action_parameters_must_be_real() -> None:
    env = HFOEnv(action_format="parameterized")
    env.reset(seed=0)
    before = snapshot(env)
    with pytest.raises(ValueError, match="dash parameters must be real numbers"):
        env.step((0, np.array([50.0, 0.0], dtype=np.complex128), np.array([0.0]), np.array([0.0, 0.0])))
    with pytest.raises(ValueError, match="turn parameters must be real numbers"):
        env.step((1, np.array([50.0, 0.0]), np.array([True]), np.array([0.0, 0.0])))
    assert snapshot(env) == before
    env.step((1, np.array([50.0, 0.0]), np.array([0.0]), np.array([0.0, 0.0])))


def test_reset_options_must_be_real() -> None:
    env = HFOEnv()
    with pytest.raises(ValueError, match="reset option 'ball' must be real numbers"):
        env.reset(seed=0, options={"ball": (True, 3.0)})
