"""BallPlayerRouter (a team's role split as a hand-coded skill router) and HFO's instance of it."""

from __future__ import annotations

import pickle

import numpy as np
import pytest
import torch as th

from hfo2d.features import BALL_ANGLE_COS, BALL_ANGLE_SIN, BALL_PROXIMITY, MAX_HFO_DIST, SELF_X
from sb3_hfo.common.routers import BallPlayerRouter, FieldHalfRouter, SingleSkillRouter
from sb3_hfo.hfo import hfo_ball_player_router
from sb3_hfo.hybrid_ppo import HybridPPO
from sb3_hfo.multi_agent import make_team_vec_env


def proximity(metres: float) -> float:
    """HFO's proximity of a distance (hfo2d.features): 1 - 2 d / MAX_HFO_DIST."""
    return 1.0 - 2.0 * metres / MAX_HFO_DIST


def striker(
    ball_metres: float, ball_deg: float, teammates: list[tuple[float, float]], self_x: float
) -> np.ndarray:
    """A 2v1-or-larger paper-era observation: the ball and each teammate by (distance, bearing), zeros elsewhere."""
    observation = np.zeros(58 + 8 * (len(teammates) + 1), dtype=np.float32)
    observation[SELF_X] = self_x
    observation[BALL_ANGLE_SIN], observation[BALL_ANGLE_COS] = (
        np.sin(np.radians(ball_deg)),
        np.cos(np.radians(ball_deg)),
    )
    observation[BALL_PROXIMITY] = proximity(ball_metres)
    for index, (metres, degrees) in enumerate(teammates):
        block = 58 + 8 * index
        observation[block : block + 3] = (
            np.sin(np.radians(degrees)),
            np.cos(np.radians(degrees)),
            proximity(metres),
        )
    return observation


def test_the_nearest_striker_plays_the_field_half_skills_and_the_others_support() -> None:
    router = hfo_ball_player_router(1)
    assert router.n_skills == 3 and router.support_skill == 2
    observations = np.stack(
        [
            striker(
                5.0, 0.0, [(5.0, 90.0)], self_x=0.5
            ),  # teammate sqrt(50) m from the ball: nearest, far half
            striker(5.0, 0.0, [(5.0, 90.0)], self_x=-0.5),  # the same in the half near the goal: shoot skill
            striker(5.0, 0.0, [(7.0, 10.0)], self_x=0.5),  # teammate ~2.1 m from the ball: support
            striker(5.0, 0.0, [(9.0, 180.0)], self_x=-0.5),  # teammate behind the striker: nearest
            striker(30.0, 0.0, [(0.0, 0.0)], self_x=0.5),  # an unlisted teammate (zeros, no bearing): nearest
        ]
    )
    observations[4, 58:66] = 0.0
    expected = [0, 1, 2, 1, 0]
    assert router(observations).tolist() == expected
    routed = router(th.as_tensor(observations))
    assert routed.dtype == th.long and routed.tolist() == expected


def test_with_two_teammates_a_striker_must_be_nearer_than_both() -> None:
    router = hfo_ball_player_router(2)
    nearest = striker(5.0, 0.0, [(20.0, 90.0), (20.0, -90.0)], self_x=0.5)
    second = striker(5.0, 0.0, [(20.0, 90.0), (6.0, 5.0)], self_x=0.5)
    assert router(np.stack([nearest, second])).tolist() == [0, 2]


def test_numpy_and_torch_agree_on_random_observations() -> None:
    rng = np.random.default_rng(0)
    observations = rng.uniform(-1, 1, (500, 74)).astype(np.float32)
    router = hfo_ball_player_router(1)
    np.testing.assert_array_equal(router(observations), router(th.as_tensor(observations)).numpy())
    assert 0 < (router(observations) == 2).mean() < 1  # both roles occur


def test_bad_arguments_are_named() -> None:
    with pytest.raises(ValueError, match="at least one teammate"):
        BallPlayerRouter(SingleSkillRouter(), (51, 52, 53), (), 31.0)
    with pytest.raises(ValueError, match="triples"):
        BallPlayerRouter(SingleSkillRouter(), (51, 52), ((58, 59, 60),), 31.0)
    with pytest.raises(ValueError, match="distance_scale"):
        BallPlayerRouter(SingleSkillRouter(), (51, 52, 53), ((58, 59, 60),), 0.0)
    with pytest.raises(ValueError, match="SkillRouter"):
        BallPlayerRouter(object(), (51, 52, 53), ((58, 59, 60),), 31.0)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="teammates must be"):
        hfo_ball_player_router(0)
    with pytest.raises(ValueError, match="opponents must be"):
        hfo_ball_player_router(1, -1)
    with pytest.raises(ValueError, match="of 74 features, got 66"):
        hfo_ball_player_router(1)(np.zeros((2, 66), dtype=np.float32))  # a 1v1 observation: no teammate block


def test_the_router_pickles_and_travels_with_a_saved_model(tmp_path) -> None:
    router = hfo_ball_player_router(1)
    assert pickle.loads(pickle.dumps(router)) == router
    assert isinstance(router.ball_router, FieldHalfRouter)
    env = make_team_vec_env(2, offense_agents=2, defense_npcs=1, seed=0)
    policy_kwargs = {"net_arch": [32], "skills": 3, "router": router}
    model = HybridPPO("MlpPolicy", env, n_steps=16, batch_size=32, seed=0, policy_kwargs=policy_kwargs)
    model.learn(32)
    observations = env.reset()
    actions, _ = model.predict(observations, deterministic=True)
    model.save(tmp_path / "routed.zip")
    loaded = HybridPPO.load(tmp_path / "routed.zip", device="cpu")
    assert loaded.policy.skill_router == router
    np.testing.assert_array_equal(loaded.predict(observations, deterministic=True)[0], actions)
    env.close()
