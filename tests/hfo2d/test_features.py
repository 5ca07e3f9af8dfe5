"""Low-level features on hand-placed states, values worked out by hand (hfo2d.features, paper-era HFO)."""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np
import pytest

from hfo2d import features as F
from hfo2d.features import feature_names, low_level_feature_list, low_level_features, num_features
from hfo2d.hfo_env import HFOEnv

MAX_DIST = math.hypot(52.5, 34.0)  # 62.55 m, paper-era maxHFODist


def observe(task: str = "empty_goal", **options: tuple[float, ...]) -> np.ndarray:
    env = HFOEnv(task=task)
    obs, _ = env.reset(seed=0, options=options)
    return obs


def test_index_constants_match_hfo_layout() -> None:
    assert (F.KICKABLE, F.GOAL_CENTER_SIN, F.GOAL_CENTER_PROXIMITY) == (12, 13, 15)
    assert (F.CENTER_FIELD_SIN, F.CORNER_BOTTOM_LEFT_PROXIMITY) == (31, 45)
    assert (F.OUT_OF_BOUNDS_LEFT, F.OUT_OF_BOUNDS_BOTTOM) == (46, 49)
    assert (F.BALL_ANGLE_SIN, F.BALL_PROXIMITY, F.BALL_VEL_ANGLE_COS) == (51, 53, 57)
    assert (F.GOALIE_ANGLE_SIN, F.GOALIE_PROXIMITY, F.GOALIE_SPEED, F.GOALIE_VEL_ANGLE_COS) == (
        58,
        60,
        63,
        65,
    )
    assert num_features() == 58 and num_features(0, 1) == 66
    assert len(feature_names()) == 58 and len(feature_names(0, 1)) == 66
    assert feature_names()[F.BALL_PROXIMITY] == "ball_proximity"
    assert feature_names(0, 1)[F.GOALIE_BODY_COS] == "goalie_body_cos"
    assert math.isclose(F.MAX_HFO_DIST, 62.548, abs_tol=1e-3)


def test_agent_mid_half_facing_goal_ball_to_its_right() -> None:
    # Agent at (26.25, 0) facing 0 deg (toward the goal), ball 5 m along +y (the agent's right), all at rest.
    obs = observe(player=(26.25, 0.0, 0.0), ball=(26.25, 5.0))
    assert obs.dtype == np.float32 and obs.shape == (58,)
    # flags: position / velocity valid, frozen -1, no collisions, ball 5 m away is not kickable
    assert obs[[0, 1]].tolist() == [1.0, 1.0]
    assert obs[[8, 9, 10, 11, 12]].tolist() == [-1.0] * 5
    # body - velocity heading with zero velocity = body = 0 -> (0, 1); speed 0 over [0, 0.46] -> -1
    assert obs[2:5] == pytest.approx([0.0, 1.0, -1.0])
    # global body angle 0 -> (sin, cos) = (0, 1); stamina 8000 / 8000 -> +1
    assert obs[5:8] == pytest.approx([0.0, 1.0, 1.0])
    # goal centre straight ahead, 26.25 m: (0, 1), 1 - 2 * 26.25 / 62.55 = 0.1607
    assert obs[13:16] == pytest.approx([0.0, 1.0, 1.0 - 2.0 * 26.25 / MAX_DIST], abs=1e-6)
    # top post (52.5, -7.01): ahead and to the left (negative bearing)
    d_post = math.hypot(26.25, 7.01)
    assert obs[16:19] == pytest.approx(
        [-7.01 / d_post, 26.25 / d_post, 1.0 - 2.0 * d_post / MAX_DIST], abs=1e-6
    )
    # bottom post (52.5, +7.01): mirror image, to the right
    assert obs[19:22] == pytest.approx(
        [7.01 / d_post, 26.25 / d_post, 1.0 - 2.0 * d_post / MAX_DIST], abs=1e-6
    )
    # centre field (0, 0) directly behind: bearing 180 deg -> (0, -1), same distance as the goal
    assert obs[31:34] == pytest.approx([0.0, -1.0, 1.0 - 2.0 * 26.25 / MAX_DIST], abs=1e-6)
    # corner bottom-right (52.5, 34): 26.25 ahead, 34 right
    d_corner = math.hypot(26.25, 34.0)
    assert obs[40:43] == pytest.approx(
        [34.0 / d_corner, 26.25 / d_corner, 1.0 - 2.0 * d_corner / MAX_DIST], abs=1e-6
    )
    # out of bounds: x = 26.25 is half of 52.5 -> 0 and 0; y = 0 is half of 68 -> 0 and 0
    assert obs[46:50] == pytest.approx([0.0, 0.0, 0.0, 0.0], abs=1e-6)
    # ball: valid, bearing +90 deg (right) -> (1, 0), proximity 1 - 2 * 5 / 62.55
    assert obs[50] == 1.0
    assert obs[51:54] == pytest.approx([1.0, 0.0, 1.0 - 10.0 / MAX_DIST], abs=1e-6)
    # ball velocity valid, speed 0 over [0, 5] -> -1, heading of a zero velocity is 0 -> (0, 1)
    assert obs[54:58] == pytest.approx([1.0, -1.0, 0.0, 1.0], abs=1e-6)


def test_bearings_follow_the_body_angle() -> None:
    # Facing +90 deg (down the screen, +y): the goal, straight along +x, is now on the agent's LEFT (-90 deg),
    # and a ball at +y lies straight ahead.
    obs = observe(player=(26.25, 0.0, 90.0), ball=(26.25, 5.0))
    assert obs[5:7] == pytest.approx([1.0, 0.0], abs=1e-6)  # global body angle 90
    assert obs[13:15] == pytest.approx([-1.0, 0.0], abs=1e-6)  # goal: sin(-90), cos(-90)
    assert obs[51:53] == pytest.approx([0.0, 1.0], abs=1e-6)  # ball ahead
    # Facing -135 deg; the goal at bearing 0 - (-135) = 135 deg: (sin, cos) = (0.7071, -0.7071)
    obs = observe(player=(26.25, 0.0, -135.0), ball=(30.0, 0.0))
    assert obs[13:15] == pytest.approx([math.sqrt(0.5), -math.sqrt(0.5)], abs=1e-6)


def test_own_velocity_and_ball_velocity() -> None:
    # Facing +90 deg, moving along +x at 0.23 m/cycle: body - heading = 90 -> (1, 0); 0.23 is half of 0.46 -> 0.
    # Ball moving at (0, -2.5): speed half of 5 -> 0, heading -90 -> (-1, 0).
    obs = observe(player=(20.0, 3.0, 90.0, 0.23, 0.0), ball=(10.0, 3.0, 0.0, -2.5))
    assert obs[2:5] == pytest.approx([1.0, 0.0, 0.0], abs=1e-6)
    assert obs[55:58] == pytest.approx([0.0, -1.0, 0.0], abs=1e-6)
    # speeds above the normaliser clip to +1
    obs = observe(player=(20.0, 3.0, 0.0, 0.6, 0.0), ball=(10.0, 3.0, 0.0, 6.0))
    assert obs[4] == 1.0 and obs[55] == 1.0


def test_kickable_flag_uses_librcsc_1_03_m() -> None:
    # kickable_area 1.085 - 0.055 = 1.03 m between centres
    assert observe(player=(30.0, 0.0, 0.0), ball=(31.02, 0.0))[F.KICKABLE] == 1.0
    assert observe(player=(30.0, 0.0, 0.0), ball=(31.04, 0.0))[F.KICKABLE] == -1.0
    # 1.04 m is still within the server's 1.085 m, but librcsc would not let the agent kick


def test_out_of_bounds_features_clip_and_use_paper_era_normalisers() -> None:
    # x = -0.1 (allowed start): left distance < 0 clips to proximity +1; right distance 52.6 > 52.5 clips to -1.
    # y = -17: top distance 17 of 68 -> 1 - 0.5 = 0.5; bottom distance 51 -> 1 - 1.5 = -0.5.
    obs = observe(player=(-0.1, -17.0, 0.0), ball=(5.0, 0.0))
    assert obs[46:50] == pytest.approx([1.0, -1.0, 0.5, -0.5], abs=1e-6)
    # obs[46] = 1 - 2 * x / 52.5: positive exactly in the half away from goal (x < 26.25)
    assert observe(player=(13.125, 0.0, 0.0), ball=(5.0, 0.0))[46] == pytest.approx(0.5, abs=1e-6)
    assert observe(player=(39.375, 0.0, 0.0), ball=(5.0, 0.0))[46] == pytest.approx(-0.5, abs=1e-6)


def test_agent_on_a_landmark_and_far_from_the_ball() -> None:
    # Agent exactly at centre field (0, 0) facing 30 deg: the landmark's direction is taken as 0 (rcsc's th() of
    # the zero vector), so the bearing is -30 deg -> (-0.5, 0.866), proximity +1.
    # Ball at (52.5, 34): 62.55 m away = maxHFODist -> proximity -1.
    obs = observe(player=(0.0, 0.0, 30.0), ball=(52.5, 34.0))
    assert obs[31:34] == pytest.approx([-0.5, math.sqrt(3) / 2, 1.0], abs=1e-6)
    assert obs[53] == pytest.approx(-1.0, abs=1e-6)


def test_goalie_block() -> None:
    # Agent at (26.25, 0) facing 0; goalie at (52.5, 0) facing 180 at rest.
    obs = observe("static_keeper", player=(26.25, 0.0, 0.0), ball=(20.0, 0.0), keeper=(52.5, 0.0, 180.0))
    assert obs.shape == (66,)
    # landmark: straight ahead (0, 1), 26.25 m; body 180 -> (0, -1); speed 0 over [0, 0.75] -> -1; heading 0 -> (0, 1)
    expected = [0.0, 1.0, 1.0 - 2.0 * 26.25 / MAX_DIST, 0.0, -1.0, -1.0, 0.0, 1.0]
    assert obs[58:66] == pytest.approx(expected, abs=1e-6)
    # goalie to the agent's right, facing +90, moving at (0, 0.375): speed half of 0.75 -> 0, heading 90 -> (1, 0)
    env = HFOEnv(task="static_keeper")
    env.reset(seed=0, options={"player": (40.0, 0.0, 0.0), "ball": (20.0, 0.0), "keeper": (40.0, 3.0, 90.0)})
    assert env.keeper is not None
    env.keeper.vy = 0.375
    obs = low_level_features(env.world, env.agent)
    expected = [1.0, 0.0, 1.0 - 6.0 / MAX_DIST, 1.0, 0.0, 0.0, 1.0, 0.0]
    assert obs[58:66] == pytest.approx(expected, abs=1e-6)


def test_goalie_block_is_zero_when_goalie_leaves_the_hfo_half() -> None:
    # HFO lists a player only while its x > 0
    obs = observe("static_keeper", player=(26.25, 0.0, 0.0), ball=(20.0, 0.0), keeper=(-1.0, 0.0, 0.0))
    assert obs[58:66].tolist() == [0.0] * 8
    obs = observe("static_keeper", player=(26.25, 0.0, 0.0), ball=(20.0, 0.0), keeper=(0.5, 0.0, 0.0))
    assert obs[60] != 0.0


def test_collision_and_stamina_features() -> None:
    env = HFOEnv()
    env.reset(seed=0, options={"player": (30.0, 0.0, 0.0), "ball": (35.0, 0.0)})
    agent = env.agent
    assert agent is not None
    agent.stamina = 4000.0  # half of 8000 -> 0
    agent.collided_ball = True
    agent.collided_post = True
    obs = low_level_features(env.world, agent)
    assert obs[7] == pytest.approx(0.0)
    assert obs[[9, 10, 11]].tolist() == [1.0, -1.0, 1.0]
    # a new episode starts without collisions
    obs, _ = env.reset(options={"player": (30.0, 0.0, 0.0), "ball": (35.0, 0.0)})
    assert obs[[7, 9, 10, 11]].tolist() == [1.0, -1.0, -1.0, -1.0]


def test_array_api_matches_list_and_fills_out() -> None:
    env = HFOEnv(task="keeper")
    obs, _ = env.reset(seed=3)
    world, agent = env.world, env.agent
    assert world is not None and agent is not None
    out = np.zeros(66, dtype=np.float32)
    result = low_level_features(world, agent, out=out)
    assert result is out
    np.testing.assert_array_equal(out, obs)
    kick_range = world.params.kickable_area - F.KICKABLE_BUFFER
    listed = low_level_feature_list(agent, world.ball, kick_range, (), (env.keeper,))
    np.testing.assert_allclose(out, listed, atol=1e-6)
    with pytest.raises(ValueError, match="shape"):
        low_level_features(world, agent, out=np.zeros(58, dtype=np.float32))


def test_features_stay_in_range_under_random_play() -> None:
    for task in ("empty_goal", "keeper"):
        env = HFOEnv(task=task)
        obs, _ = env.reset(seed=11)
        env.action_space.seed(11)
        for _ in range(600):
            obs, _, terminated, truncated, _ = env.step(env.action_space.sample())
            assert obs.dtype == np.float32
            assert np.all(obs >= -1.0) and np.all(obs <= 1.0)
            if terminated or truncated:
                obs, _ = env.reset()


# --- HFO master's layout (59 / 68) and its conversion into the paper layout ------------------------------------
HFO_MASTER_MAX_DIST = math.hypot(52.5, 68.0)  # 85.908 m: HFO master's maxHFODist (half length, full width)


def hfo_vector(env: HFOEnv, last_action_succeeded: bool = True) -> list[float]:
    """HFO master's vector of ``env``'s current state, computed by hfo2d."""
    return F.hfo_feature_list(
        env.agent,
        env.world.ball,
        env.world.params.kickable_area - F.KICKABLE_BUFFER,
        (),
        (env.keeper,) if env.keeper is not None else (),
        last_action_succeeded,
    )


def random_states(task: str, count: int, seed: int) -> Iterator[HFOEnv]:
    """One env of ``task`` put in ``count`` states in turn: placed anywhere on (and a little off) the HFO half,
    moving, then up to 3 random steps."""
    rng = np.random.default_rng(seed)
    env = HFOEnv(task=task)
    env.action_space.seed(seed)
    for index in range(count):
        options = {
            "player": (rng.uniform(-2.0, 56.0), rng.uniform(-38.0, 38.0), rng.uniform(-180, 180), 0.3, -0.2),
            "ball": (
                rng.uniform(0.0, 52.5),
                rng.uniform(-34.0, 34.0),
                rng.uniform(-3, 3),
                rng.uniform(-3, 3),
            ),
        }
        if env.has_keeper:
            options["keeper"] = (rng.uniform(-3.0, 52.5), rng.uniform(-20.0, 20.0), rng.uniform(-180, 180))
        env.reset(seed=seed + index, options=options)
        for _ in range(int(rng.integers(0, 4))):
            _, _, terminated, truncated, _ = env.step(env.action_space.sample())
            if terminated or truncated:
                break
        yield env


def test_hfo_master_sizes_and_extra_entries() -> None:
    assert F.hfo_num_features() == 59 and F.hfo_num_features(0, 1) == 68
    assert F.hfo_num_features(2, 3) == 58 + 9 * 5 + 1
    master_max = F.HFO_MASTER_MAX_DIST
    assert master_max == pytest.approx(HFO_MASTER_MAX_DIST, abs=1e-5)
    assert master_max == float(np.sqrt(np.float32(52.5**2 + 68.0**2)))  # HFO's float32 sqrtf
    env = HFOEnv(task="static_keeper")
    env.reset(
        seed=0, options={"player": (26.25, 0.0, 0.0), "ball": (20.0, 0.0), "keeper": (52.5, 0.0, 180.0)}
    )
    features = hfo_vector(env, last_action_succeeded=False)
    assert len(features) == 68
    # the goalie's uniform number 1 / 100, then the failed last action
    assert features[66:] == [0.01, -1.0]
    assert hfo_vector(env, True)[67] == 1.0
    # master's normalisers: goal centre 26.25 m over 85.908 m; out of bounds x 26.25 over 57.75, y 34 over 71.4
    assert features[15] == pytest.approx(1.0 - 2.0 * 26.25 / HFO_MASTER_MAX_DIST, abs=1e-6)
    assert features[60] == pytest.approx(1.0 - 2.0 * 26.25 / HFO_MASTER_MAX_DIST, abs=1e-6)
    assert features[46:50] == pytest.approx(
        [1 - 52.5 / 57.75, 1 - 52.5 / 57.75, 1 - 68 / 71.4, 1 - 68 / 71.4]
    )
    # a goalie outside the HFO half is not listed: zeros, uniform number -1
    env.reset(options={"player": (26.25, 0.0, 0.0), "ball": (20.0, 0.0), "keeper": (-1.0, 0.0, 0.0)})
    features = hfo_vector(env)
    assert features[58:66] == [0.0] * 8 and features[66:] == [-1.0, 1.0]
    env = HFOEnv()
    env.reset(seed=1)
    features = hfo_vector(env, False)
    assert len(features) == 59 and features[58] == -1.0


def test_paper_from_hfo_inverts_hfo2d_master_features() -> None:
    worst = 0.0
    for task in ("empty_goal", "static_keeper", "keeper"):
        for env in random_states(task, 40, seed=5):
            paper = low_level_feature_list(
                env.agent,
                env.world.ball,
                env.world.params.kickable_area - F.KICKABLE_BUFFER,
                (),
                env._opponents,
            )
            opponents = 1 if env.has_keeper else 0
            converted = F.paper_from_hfo(hfo_vector(env), 0, opponents)
            assert len(converted) == len(paper) == F.num_features(0, opponents)
            worst = max(worst, float(np.max(np.abs(np.subtract(converted, paper)))))
            # float32 input (an observation) converts as well
            converted32 = F.paper_from_hfo(np.array(hfo_vector(env), dtype=np.float32), 0, opponents)
            np.testing.assert_allclose(converted32, paper, atol=1e-5)
    assert worst < 1e-9


def test_paper_from_hfo_several_players_and_empty_slots() -> None:
    from hfo2d.physics import BallState, PlayerState

    me = PlayerState("l", 11, x=20.0, y=5.0, body_deg=30.0)
    mate = PlayerState("l", 7, x=30.0, y=-10.0, body_deg=-60.0, vx=0.2, vy=0.1)
    near = PlayerState("r", 3, x=24.0, y=8.0, body_deg=170.0)
    far = PlayerState("r", 1, goalie=True, x=50.0, y=0.0, body_deg=180.0)
    gone = PlayerState("r", 5, x=-4.0, y=0.0)  # outside the HFO half: not listed
    ball = BallState(x=21.0, y=5.5, vx=1.0, vy=-0.5)
    teammates, opponents = (mate,), (far, gone, near)
    master = F.hfo_feature_list(me, ball, 1.03, teammates, opponents, True)
    assert len(master) == F.hfo_num_features(1, 3) == 58 + 32 + 4 + 1
    # blocks: the teammate, then the opponents nearest first, the unlisted one last as zeros; then the uniform
    # numbers in the same order (-1 for the empty slot), then the flag
    assert master[82:90] == [0.0] * 8
    assert master[90:] == [0.07, 0.03, 0.01, -1.0, 1.0]
    paper = low_level_feature_list(me, ball, 1.03, teammates, opponents)
    np.testing.assert_allclose(F.paper_from_hfo(master, 1, 3), paper, atol=1e-12)
    # a proximity at the clip: 85.9 m in master's units is beyond 62.55 m, -1 in the paper's
    clipped = list(master)
    clipped[F.BALL_PROXIMITY] = 1.0 - 2.0 * 70.0 / F.HFO_MASTER_MAX_DIST
    assert F.paper_from_hfo(clipped, 1, 3)[F.BALL_PROXIMITY] == -1.0


def test_paper_from_hfo_rejects_a_wrong_length() -> None:
    with pytest.raises(ValueError, match="68 features, got 66"):
        F.paper_from_hfo([0.0] * 66, 0, 1)
    with pytest.raises(ValueError, match="59 features, got 58"):
        F.paper_from_hfo([0.0] * 58)
    with pytest.raises(ValueError, match="slot counts"):
        F.paper_from_hfo([0.0] * 59, -1, 0)


def test_env_feature_set_hfo_matches_paper_twin() -> None:
    # Two envs, same seed and actions: the "hfo" one's observations convert into the "paper" one's; rewards and
    # info (kickable included) do not depend on the feature set.
    for task in ("empty_goal", "static_keeper", "keeper"):
        paper_env, hfo_env = HFOEnv(task=task), HFOEnv(task=task, feature_set="hfo")
        size = 68 if paper_env.has_keeper else 59
        assert hfo_env.observation_space.shape == (size,)
        assert paper_env.observation_space.shape == (F.num_features(0, 1 if paper_env.has_keeper else 0),)
        actions = np.random.default_rng(4).random((150, 8), dtype=np.float32)
        paper_obs, paper_info = paper_env.reset(seed=2)
        hfo_obs, hfo_info = hfo_env.reset(seed=2)
        opponents = 1 if paper_env.has_keeper else 0
        for action in actions:
            assert hfo_obs.dtype == np.float32 and hfo_env.observation_space.contains(hfo_obs)
            np.testing.assert_allclose(F.paper_from_hfo(hfo_obs, 0, opponents), paper_obs, atol=1e-5)
            assert hfo_info["kickable"] == paper_info["kickable"]
            paper_obs, paper_reward, paper_end, paper_cut, paper_info = paper_env.step(action)
            hfo_obs, hfo_reward, hfo_end, hfo_cut, hfo_info = hfo_env.step(action)
            assert (hfo_reward, hfo_end, hfo_cut) == (paper_reward, paper_end, paper_cut)
            assert hfo_info["reward_terms"] == paper_info["reward_terms"]
            assert hfo_obs[-1] == (1.0 if hfo_info["action_success"] else -1.0)
            if paper_end or paper_cut:
                paper_obs, paper_info = paper_env.reset()
                hfo_obs, hfo_info = hfo_env.reset()


def test_env_feature_set_hfo_flag_and_uniform_number() -> None:
    env = HFOEnv(task="static_keeper", feature_set="hfo")
    options = {"player": (30.0, 0.0, 0.0), "ball": (30.5, 0.0), "keeper": (52.5, 0.0, 180.0)}
    obs, _ = env.reset(seed=0, options=options)
    assert obs.shape == (68,) and obs[66] == np.float32(0.01) and obs[67] == -1.0  # HFO starts "failed"
    dash, turn = [1, 0, 0, 0.5, 0.5, 0.5, 0, 0], [0, 1, 0, 0, 0, 0.5, 0, 0]
    kick = [0, 0, 1, 0, 0, 0, 1.0, 0.5]  # full power straight ahead
    assert env.step(np.array(kick, dtype=np.float32))[0][67] == 1.0  # the ball 0.5 m away: kickable
    obs, *_ = env.step(np.array(kick, dtype=np.float32))
    assert obs[67] == -1.0 and obs[F.KICKABLE] == -1.0  # the ball has left: a kick out of reach fails
    assert env.step(np.array(turn, dtype=np.float32))[0][67] == 1.0
    assert env.step(np.array(dash, dtype=np.float32))[0][67] == 1.0
    env1v0 = HFOEnv(feature_set="hfo")
    assert env1v0.reset(seed=0)[0].shape == (59,)


def test_env_rejects_an_unknown_feature_set() -> None:
    with pytest.raises(ValueError, match="'master'"):
        HFOEnv(feature_set="master")


def test_unrolled_landmarks_equal_the_loop() -> None:
    """low_level_feature_list's unrolled landmark block gives the loop's floats bit for bit (signed zeros too),
    also on the landmarks' own lines and points."""
    import struct

    from hfo2d.features import _LANDMARK_POINTS, FIRST_LANDMARK, LANDMARKS, _landmark_features
    from hfo2d.physics import BallState, PlayerState

    rng = np.random.default_rng(7)
    points = [(float(x), float(y)) for x, y in rng.uniform((-60.0, -45.0), (60.0, 45.0), size=(300, 2))]
    for lx, ly in _LANDMARK_POINTS:  # on a landmark, and on its lines
        points += [(lx, ly), (lx, float(rng.uniform(-40, 40))), (float(rng.uniform(-10, 60)), ly)]
    bodies = [0.0, 90.0, -180.0, *rng.uniform(-180.0, 180.0, size=3).tolist()]
    end = FIRST_LANDMARK + 3 * len(LANDMARKS)
    for x, y in points:
        for body in bodies:
            player = PlayerState("l", 11, x=x, y=y, body_deg=body)
            features = low_level_feature_list(player, BallState(x=1.0, y=2.0), 1.03)
            rad = body * (math.pi / 180.0)  # as low_level_feature_list forms it
            expected = _landmark_features(x, y, math.cos(rad), math.sin(rad))
            got = features[FIRST_LANDMARK:end]
            assert struct.pack(f"{len(got)}d", *got) == struct.pack(f"{len(expected)}d", *expected), (
                x,
                y,
                body,
            )


def test_proximity_distance_reads_back_the_metres_of_a_landmark() -> None:
    # the ball 5 m to the right and the goal centre 26.25 m ahead, as in the state above
    obs = observe(player=(26.25, 0.0, 0.0), ball=(26.25, 5.0))
    assert F.proximity_distance(float(obs[F.BALL_PROXIMITY])) == pytest.approx(5.0, abs=1e-4)
    assert F.proximity_distance(float(obs[15])) == pytest.approx(26.25, abs=1e-4)
    assert F.proximity_distance(np.array([1.0, -1.0])) == pytest.approx([0.0, MAX_DIST])
