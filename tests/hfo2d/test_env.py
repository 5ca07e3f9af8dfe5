"""HFOEnv: API checks, determinism, episode rules, starting state, input validation."""

from __future__ import annotations

import importlib
import math
import os
import subprocess
import sys
import warnings

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")  # the render check opens a "human" window
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env as gym_check_env

import hfo2d
from hfo2d.hfo_env import OFFENSE_OFFSETS, HFOEnv

ENV_IDS = ("HFO/EmptyGoal-v0", "HFO/StaticKeeper-v0", "HFO/Keeper-v0")
TURN_NONE = np.array([0, 1, 0, 0, 0.5, 0.5, 0, 0.5], dtype=np.float32)
FAR_APART = {"player": (5.0, -20.0, 0.0), "ball": (40.0, 20.0)}


def snapshot(env: HFOEnv) -> tuple:
    world = env.world
    assert world is not None
    players = tuple(
        (p.x, p.y, p.vx, p.vy, p.body_deg, p.ax, p.ay, p.stamina, p.effort, p.recovery) for p in world.players
    )
    ball = world.ball
    return (
        players,
        (ball.x, ball.y, ball.vx, ball.vy, ball.ax, ball.ay),
        world.cycle,
        env.steps,
        env.np_random.bit_generator.state["state"]["state"],
    )


# --- API -------------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("env_id", ENV_IDS)
def test_registered_env_passes_gymnasium_s_checker(env_id: str) -> None:
    """(SB3's checker, which needs torch: tests/sb3_hfo/test_sb3_env_checker.py.)"""
    env = gym.make(env_id)
    assert env.spec is not None and env.spec.max_episode_steps is None  # no TimeLimit wrapper
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*symmetric and normalized.*")
        gym_check_env(env.unwrapped)
        gym_check_env(gym.make(env_id, action_format="parameterized").unwrapped, skip_render_check=True)
    expected = 58 if env_id == "HFO/EmptyGoal-v0" else 66
    assert env.observation_space.shape == (expected,)
    env.close()


def test_registration_maps_ids_to_tasks_and_reimport_does_not_warn() -> None:
    tasks = [gym.make(env_id).unwrapped.task for env_id in ENV_IDS]
    assert tasks == ["empty_goal", "static_keeper", "keeper"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        importlib.reload(hfo2d)
    assert callable(hfo2d.heuristic) and hfo2d.HFOEnv is HFOEnv


def test_hfo2d_imports_without_torch() -> None:
    code = "import sys, hfo2d; assert 'torch' not in sys.modules and 'stable_baselines3' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)


def test_action_spaces() -> None:
    flat = HFOEnv().action_space
    assert isinstance(flat, gym.spaces.Box) and flat.shape == (8,)
    assert flat.low.tolist() == [0.0] * 8 and flat.high.tolist() == [1.0] * 8
    param = HFOEnv(action_format="parameterized").action_space
    assert isinstance(param, gym.spaces.Tuple) and param[0] == gym.spaces.Discrete(3)
    assert param[1].low.tolist() == [0.0, -180.0] and param[1].high.tolist() == [100.0, 180.0]
    assert param[2].low.tolist() == [-180.0] and param[3].high.tolist() == [100.0, 180.0]


def test_info_keys_every_step() -> None:
    env = HFOEnv(task="static_keeper")
    _, info = env.reset(seed=1)
    assert {"status", "player", "ball", "keeper", "kickable", "reward_terms"} <= set(info)
    _, _, _, _, info = env.step(env.action_space.sample())
    assert set(info) == {
        "status",
        "is_success",
        "player",
        "ball",
        "keeper",
        "kickable",
        "reward_terms",
        "action",
        "action_success",
        "kick_power",
    }
    assert len(info["player"]) == 5 and len(info["ball"]) == 4 and len(info["keeper"]) == 5
    assert info["action"] in ("DASH", "TURN", "KICK")
    assert "keeper" not in HFOEnv().reset(seed=1)[1]


# --- determinism -------------------------------------------------------------------------------------------------
def rollout(env_id: str, seed: int, steps: int) -> tuple[list[np.ndarray], list[float]]:
    env = gym.make(env_id)
    env.action_space.seed(seed)
    obs, _ = env.reset(seed=seed)
    observations, rewards = [obs], []
    for _ in range(steps):
        obs, reward, terminated, truncated, _ = env.step(env.action_space.sample())
        observations.append(obs)
        rewards.append(reward)
        if terminated or truncated:
            obs, _ = env.reset()
            observations.append(obs)
    return observations, rewards


@pytest.mark.parametrize("env_id", ["HFO/EmptyGoal-v0", "HFO/Keeper-v0"])
def test_same_seed_same_trajectory(env_id: str) -> None:
    obs_a, rew_a = rollout(env_id, 7, 1000)
    obs_b, rew_b = rollout(env_id, 7, 1000)
    assert rew_a == rew_b
    np.testing.assert_array_equal(np.stack(obs_a), np.stack(obs_b))
    obs_c, _ = rollout(env_id, 8, 50)
    assert not np.array_equal(obs_a[0], obs_c[0])


def test_reset_with_seed_restarts_the_random_stream() -> None:
    env = HFOEnv()
    first, _ = env.reset(seed=5)
    env.step(env.action_space.sample())
    again, _ = env.reset(seed=5)
    np.testing.assert_array_equal(first, again)
    different, _ = env.reset()  # no seed: the stream goes on
    assert not np.array_equal(first, different)


def test_reseeding_one_env_replays_noise_and_keeps_its_objects() -> None:
    env = HFOEnv(task="keeper")
    world, agent = env.world, env.agent
    actions = np.random.default_rng(3).random((300, 8), dtype=np.float32)

    def play() -> list[tuple]:
        env.reset(seed=9)
        infos = []
        for action in actions:
            _, _, terminated, truncated, info = env.step(action)
            infos.append((info["player"], info["ball"], info["keeper"]))
            if terminated or truncated:
                env.reset()
        return infos

    assert play() == play()  # motion, kick and keeper randomness all restart with the seed
    assert env.world is world and env.agent is agent


def test_step_before_reset_raises() -> None:
    with pytest.raises(RuntimeError, match="reset"):
        HFOEnv().step(TURN_NONE)


def test_noise_false_is_deterministic_whatever_the_seed() -> None:
    def run(seed: int) -> list[tuple]:
        env = HFOEnv(noise=False)
        env.reset(seed=seed, options={"player": (10.0, 0.0, 0.0), "ball": (11.5, 0.0)})
        action = np.array([1, 0, 0, 0.8, 0.5, 0.5, 0, 0.5], dtype=np.float32)
        return [env.step(action)[4]["player"] for _ in range(20)]

    assert HFOEnv(noise=False).noise is False
    assert run(1) == run(2)
    env = HFOEnv(noise=True)
    env.reset(seed=1, options={"player": (10.0, 0.0, 0.0), "ball": (30.0, 0.0)})
    noisy = [
        env.step(np.array([1, 0, 0, 0.8, 0.5, 0.5, 0, 0.5], dtype=np.float32))[4]["player"] for _ in range(5)
    ]
    assert noisy[-1][1] != 0.0  # motion noise pushes the agent off the x axis


# --- actions -----------------------------------------------------------------------------------------------------
def test_flat_action_mapping_turn_and_dash() -> None:
    env = HFOEnv(noise=False)
    env.reset(seed=0, options=FAR_APART)
    # TURN preferred, turn_dir 0.75 -> +90 deg; from rest the agent turns by exactly 90
    action = np.array([0.2, 0.9, 0.1, 0, 0, 0.75, 0, 0], dtype=np.float32)
    _, _, _, _, info = env.step(action)
    assert info["action"] == "TURN" and info["action_success"]
    assert info["player"][4] == pytest.approx(90.0)
    # DASH preferred, power 1.0 -> 100, dir 0.5 -> 0: accel 100 * 0.006 = 0.6 along +90, decayed by 0.4 -> 0.24
    action = np.array([0.9, 0.2, 0.1, 1.0, 0.5, 0, 0, 0], dtype=np.float32)
    _, _, _, _, info = env.step(action)
    x, y, vx, vy, body = info["player"]
    assert info["action"] == "DASH" and (vx, vy) == pytest.approx((0.0, 0.24))
    assert (x, y) == pytest.approx((5.0, -19.4))


def test_kick_success_and_failure() -> None:
    env = HFOEnv(noise=False)
    env.reset(seed=0, options={"player": (10.0, 0.0, 0.0), "ball": (12.0, 0.0)})
    kick = np.array([0, 0, 1, 0, 0, 0, 0.8, 0.5], dtype=np.float32)
    _, _, _, _, info = env.step(kick)  # 2 m away: refused
    assert info["action"] == "KICK" and not info["action_success"] and info["kick_power"] == 0.0
    env.reset(seed=0, options={"player": (10.0, 0.0, 0.0), "ball": (10.8, 0.0)})
    _, _, _, _, info = env.step(kick)
    assert info["action_success"] and info["kick_power"] == pytest.approx(80.0)
    assert info["ball"][2] > 0.5  # the ball left toward +x


def test_parameterized_actions() -> None:
    env = HFOEnv(action_format="parameterized", noise=False)
    env.reset(seed=0, options={"player": (10.0, 0.0, 0.0), "ball": (10.8, 0.0)})
    _, _, _, _, info = env.step((2, np.array([0.0, 0.0]), np.array([0.0]), np.array([50.0, 0.0])))
    assert info["action"] == "KICK" and info["action_success"] and info["kick_power"] == 50.0
    _, _, _, _, info = env.step((np.int64(1), [0.0, 0.0], [-45.0], [0.0, 0.0]))
    assert info["action"] == "TURN" and info["player"][4] < 0.0
    env.action_space.seed(0)
    for _ in range(20):
        env.step(env.action_space.sample())


@pytest.mark.parametrize(
    ("action", "message"),
    [
        (np.array([np.nan, 0, 0, 0, 0, 0, 0, 0], dtype=np.float32), "element 0 is not finite"),
        (np.array([0, 0, 0, np.inf, 0, 0, 0, 0]), "element 3 is not finite"),
        (np.array([0, 0, 0, 0, 1.5, 0, 0, 0], dtype=np.float32), "element 4 is outside"),
        (np.array([0, 0, 0, 0, 0, 0, 0, -0.1], dtype=np.float32), "element 7 is outside"),
        (np.zeros(7, dtype=np.float32), "shape"),
        (np.zeros((2, 8), dtype=np.float32), "1-D"),
        ("dash", "numbers"),
    ],
)
def test_bad_flat_action_raises_and_leaves_state_unchanged(action: object, message: str) -> None:
    env = HFOEnv(task="keeper")
    env.reset(seed=2)
    before = snapshot(env)
    with pytest.raises(ValueError, match=message):
        env.step(action)
    assert snapshot(env) == before


@pytest.mark.parametrize(
    ("action", "message"),
    [
        ((3, [0.0, 0.0], [0.0], [0.0, 0.0]), "kind"),
        ((0, [150.0, 0.0], [0.0], [0.0, 0.0]), "dash parameters"),
        ((0, [-1.0, 0.0], [0.0], [0.0, 0.0]), "dash parameters"),
        ((1, [0.0, 0.0], [200.0], [0.0, 0.0]), "turn parameters"),
        ((2, [0.0, 0.0], [0.0], [50.0, float("nan")]), "not finite"),
        ((2, [0.0, 0.0], [0.0], [50.0]), r"shape \(2,\)"),
        ((0, [0.0, 0.0], [0.0]), "tuple"),
        (np.zeros(8, dtype=np.float32), "tuple"),
    ],
)
def test_bad_parameterized_action_raises_and_leaves_state_unchanged(action: object, message: str) -> None:
    env = HFOEnv(action_format="parameterized")
    env.reset(seed=2)
    before = snapshot(env)
    with pytest.raises(ValueError, match=message):
        env.step(action)
    assert snapshot(env) == before


# --- episode rules -----------------------------------------------------------------------------------------------
def test_goal() -> None:
    env = HFOEnv(noise=False)
    env.reset(seed=0, options={"player": (40.0, 20.0, 0.0), "ball": (50.0, 0.0, 2.0, 0.0)})
    assert env.step(TURN_NONE)[4]["status"] == "IN_GAME"  # ball at 52.0
    _, reward, terminated, truncated, info = env.step(TURN_NONE)  # 52.0 -> 53.88 crosses 52.585 at y = 0
    assert (terminated, truncated, info["status"], reward) == (True, False, "GOAL", 5.0)


def test_goal_uses_the_interpolated_crossing_point() -> None:
    # From (51.6, 6.0) moving (2.0, 1.5): crosses x = 52.585 at y = 6.74 (inside 7.07), ends at y = 7.5 (outside)
    env = HFOEnv(noise=False)
    env.reset(seed=0, options={"player": (40.0, -20.0, 0.0), "ball": (51.6, 6.0, 2.0, 1.5)})
    assert env.step(TURN_NONE)[4]["status"] == "GOAL"
    # From (51.6, 8.0) moving (2.0, -1.5): crosses at y = 7.26 (outside), ends at y = 6.5: no goal, then out
    env.reset(seed=0, options={"player": (40.0, -20.0, 0.0), "ball": (51.6, 8.0, 2.0, -1.5)})
    statuses = [env.step(TURN_NONE)[4]["status"] for _ in range(2)]
    assert statuses == ["IN_GAME", "OUT_OF_BOUNDS"]


def test_out_of_bounds_uses_the_previous_ball_position() -> None:
    # Ball at (30, 33) moving +2 m/cycle in y: after step 1 it is at y = 35, but the referee looks at the
    # position of the previous cycle (33, in bounds); step 2 sees 35 -> OUT_OF_BOUNDS.
    env = HFOEnv(noise=False)
    env.reset(seed=0, options={"player": (10.0, 0.0, 0.0), "ball": (30.0, 33.0, 0.0, 2.0)})
    _, _, terminated, _, info = env.step(TURN_NONE)
    assert not terminated and info["status"] == "IN_GAME" and info["ball"][1] > 34.0
    _, reward, terminated, _, info = env.step(TURN_NONE)
    assert terminated and info["status"] == "OUT_OF_BOUNDS" and reward == 0.0
    # A shot wide of the post crosses x = 52.5 at |y| > 7.07: not a goal, out of bounds a cycle later.
    env.reset(seed=0, options={"player": (10.0, 0.0, 0.0), "ball": (50.0, 10.0, 2.0, 0.0)})
    assert [env.step(TURN_NONE)[4]["status"] for _ in range(3)] == ["IN_GAME", "IN_GAME", "OUT_OF_BOUNDS"]


@pytest.mark.parametrize("task", ["static_keeper", "keeper"])
def test_captured_by_defense_when_goalie_reaches_the_ball(task: str) -> None:
    # ball 1.0 m in front of the goalie (within 1.085): captured at once
    env = HFOEnv(task=task, noise=False)
    env.reset(seed=0, options={"player": (20.0, 0.0, 0.0), "ball": (51.5, 0.0), "keeper": (52.5, 0.0, 180.0)})
    _, reward, terminated, _, info = env.step(TURN_NONE)
    assert terminated and info["status"] == "CAPTURED_BY_DEFENSE" and reward == 0.0
    # 1.5 m away the static goalie does not reach it
    env = HFOEnv(task="static_keeper", noise=False)
    env.reset(seed=0, options={"player": (20.0, 0.0, 0.0), "ball": (51.0, 0.0), "keeper": (52.5, 0.0, 180.0)})
    assert env.step(TURN_NONE)[4]["status"] == "IN_GAME"


def test_out_of_time_after_100_untouched_cycles() -> None:
    env = HFOEnv()
    env.reset(seed=0, options=FAR_APART)
    for _ in range(100):
        _, _, terminated, truncated, info = env.step(TURN_NONE)
        assert not terminated and not truncated and info["status"] == "IN_GAME"
    _, reward, terminated, truncated, info = env.step(TURN_NONE)  # untouched = 101 > 100
    assert (terminated, truncated, info["status"], reward) == (True, False, "OUT_OF_TIME", 0.0)


def test_untouched_counter_resets_when_the_agent_is_on_the_ball() -> None:
    env = HFOEnv(untouched_time=5, noise=False)
    env.reset(seed=0, options={"player": (10.0, 0.0, 0.0), "ball": (11.0, 0.0)})  # 1.0 m: on the ball
    for _ in range(20):
        assert env.step(TURN_NONE)[4]["status"] == "IN_GAME"


def test_truncation_at_frames_per_trial() -> None:
    env = HFOEnv(untouched_time=1000)
    env.reset(seed=0, options=FAR_APART)
    for _ in range(499):
        _, _, terminated, truncated, _ = env.step(TURN_NONE)
        assert not terminated and not truncated
    _, reward, terminated, truncated, info = env.step(TURN_NONE)
    assert (terminated, truncated, info["status"], reward) == (False, True, "OUT_OF_TIME", 0.0)
    env = HFOEnv(frames_per_trial=20)
    env.reset(seed=0, options=FAR_APART)
    assert [env.step(TURN_NONE)[3] for _ in range(20)] == [False] * 19 + [True]


def test_random_policy_rarely_scores() -> None:
    env = HFOEnv()
    actions = np.random.default_rng(0).random((200 * 500, 8), dtype=np.float32)
    goals = steps = 0
    for episode in range(200):
        env.reset(seed=episode)
        done = False
        while not done:
            _, _, terminated, truncated, info = env.step(actions[steps])
            steps += 1
            done = terminated or truncated
        goals += info["status"] == "GOAL"
    assert goals <= 10  # <= 5 %


# --- starting state ----------------------------------------------------------------------------------------------
def test_starting_state_follows_hfo_reset_field() -> None:
    env = HFOEnv(task="static_keeper")
    env.reset(seed=0)
    bodies = []
    for _ in range(300):
        _, info = env.reset()
        bx, by, bvx, bvy = info["ball"]
        px, py, pvx, pvy, body = info["player"]
        assert 0.0 <= bx <= 10.5 and abs(by) <= 27.2 and (bvx, bvy) == (0.0, 0.0)
        assert -0.1 <= px <= 52.5 and abs(py) <= 27.2 and (pvx, pvy) == (0.0, 0.0)
        assert info["keeper"][:4] == (52.5, 0.0, 0.0, 0.0)
        # player = ball + 10.5 * (U(0, 1) + offset) per axis, before clamping
        clamped_x = px in (-0.1, 52.5)
        clamped_y = abs(py) == 27.2
        assert any(
            (clamped_x or 0.0 <= (px - bx) / 10.5 - ox <= 1.0)
            and (clamped_y or 0.0 <= (py - by) / 10.5 - oy <= 1.0)
            for ox, oy in OFFENSE_OFFSETS
        )
        bodies.append(body)
    assert min(bodies) < -150.0 and max(bodies) > 150.0  # body angle uniform over the circle
    world = env.world
    assert world is not None
    assert all(p.stamina == world.params.stamina_max and p.effort == 1.0 for p in world.players)


def test_reset_recovers_stamina() -> None:
    env = HFOEnv(untouched_time=1000)
    env.reset(seed=0, options=FAR_APART)
    dash = np.array([1, 0, 0, 1.0, 0.5, 0, 0, 0], dtype=np.float32)
    for _ in range(30):
        env.step(dash)
    assert env.agent is not None and env.agent.stamina < 8000.0
    env.reset()
    assert env.agent.stamina == 8000.0 and env.agent.recovery == 1.0


# --- constructor and reset-option validation ---------------------------------------------------------------------
@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"task": "penalty"}, "empty_goal"),
        ({"action_format": "discrete"}, "parameterized"),
        ({"reward": "dense"}, "sparse"),
        ({"keeper_skill": 1.5}, "keeper_skill"),
        ({"keeper_skill": -0.1}, "keeper_skill"),
        ({"server_params": {"ball_decy": 0.9}}, "ball_decy"),
        ({"server_params": {"ball_decay": float("nan")}}, "finite"),
        ({"frames_per_trial": 0}, "frames_per_trial"),
        ({"render_mode": "ascii"}, "render_mode"),
    ],
)
def test_constructor_rejects_bad_arguments(kwargs: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        HFOEnv(**kwargs)


def test_server_params_override() -> None:
    env = HFOEnv(server_params={"ball_decay": 0.5}, noise=False)
    assert env.params.ball_decay == 0.5
    env.reset(seed=0, options={"player": (10.0, 0.0, 0.0), "ball": (30.0, 0.0, 2.0, 0.0)})
    assert env.step(TURN_NONE)[4]["ball"][2] == pytest.approx(1.0)  # 2.0 * 0.5


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"goalie": (52.5, 0.0, 0.0)}, "'goalie'"),
        ({"player": (1.0, 2.0)}, "'player' needs 3 or 5"),
        ({"player": (1.0, 2.0, 3.0, 4.0)}, "'player' needs 3 or 5"),
        ({"ball": (1.0, 2.0, 3.0)}, "'ball' needs 2 or 4"),
        ({"ball": (1.0, float("nan"))}, "non-finite"),
        ({"ball": ("a", "b")}, "numbers"),
        ({"keeper": (52.5, 0.0, 0.0)}, "no keeper"),
    ],
)
def test_reset_options_rejected(options: dict, message: str) -> None:
    env = HFOEnv()
    with pytest.raises(ValueError, match=message):
        env.reset(seed=0, options=options)


def test_keeper_option_places_the_keeper() -> None:
    env = HFOEnv(task="keeper")
    _, info = env.reset(seed=0, options={"keeper": (48.0, 3.0, 90.0)})
    assert info["keeper"] == (48.0, 3.0, 0.0, 0.0, 90.0)
    with pytest.raises(ValueError, match="'keeper' needs 3"):
        env.reset(options={"keeper": (48.0, 3.0)})


# --- rendering ---------------------------------------------------------------------------------------------------
def test_set_keeper_skill_takes_effect_at_the_next_reset() -> None:
    def keeper_travel(env: HFOEnv) -> float:
        env.reset(seed=3, options={"ball": (40.0, 10.0), "player": (30.0, 0.0, 0.0)})
        start = (env.keeper.x, env.keeper.y)
        for _ in range(15):
            env.step(
                np.array([0.0, 1.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0], dtype=np.float32)
            )  # turn by 0 degrees
        return math.dist(start, (env.keeper.x, env.keeper.y))

    env = HFOEnv(task="keeper")
    assert keeper_travel(env) > 1.0  # the full keeper moves toward the ball's side
    env.set_keeper_skill(0.0)
    assert env._keeper_policy.skill == 1.0  # the episode in progress keeps its keeper
    assert keeper_travel(env) < 0.05  # skill 0 only turns to face the ball
    env.set_keeper_skill(1.0)
    assert keeper_travel(env) > 1.0
    with pytest.raises(ValueError, match="keeper_skill must lie in"):
        env.set_keeper_skill(1.5)
    with pytest.raises(ValueError, match="keeper_skill must lie in"):
        env.set_keeper_skill(float("nan"))
    assert env.keeper_skill == 1.0
    with pytest.raises(ValueError, match="needs task 'keeper'"):
        HFOEnv(task="static_keeper").set_keeper_skill(0.5)


def test_render_modes() -> None:
    env = HFOEnv()
    env.reset(seed=0)
    with pytest.warns(UserWarning, match="render mode"):
        assert env.render() is None  # no render mode: warns, draws nothing
    pytest.importorskip("pygame")
    env = HFOEnv(render_mode="rgb_array")
    env.reset(seed=0)
    frame = env.render()
    assert (
        isinstance(frame, np.ndarray) and frame.ndim == 3 and frame.shape[2] == 3 and frame.dtype == np.uint8
    )
    env.close()


def test_episode_lengths_are_plausible() -> None:
    # random play ends mostly by OUT_OF_TIME after ~101 steps; every episode ends by 500 steps
    env = gym.make("HFO/EmptyGoal-v0")
    env.reset(seed=4)
    env.action_space.seed(4)
    lengths, steps = [], 0
    while len(lengths) < 10:
        _, _, terminated, truncated, _ = env.step(env.action_space.sample())
        steps += 1
        if terminated or truncated:
            lengths.append(steps)
            steps = 0
            env.reset()
    assert all(1 <= n <= 500 for n in lengths) and math.isfinite(sum(lengths))
