"""benchmarks/two_v_one.py's scripted role split (RoleSplitTeam) and its taught start (--start-rule)."""

from __future__ import annotations

import argparse
import importlib.util
import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import torch as th

from hfo2d.features import MAX_HFO_DIST
from sb3_hfo.hybrid_ppo import HybridPPO

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "benchmarks" / "two_v_one.py"


def load_script() -> Any:
    spec = importlib.util.spec_from_file_location("two_v_one_under_test", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class RecordingPolicy:
    """Answers every observation with a KICK and remembers what it was shown."""

    action = np.array([0.0, 0.0, 1.0, 0.1, 0.2, 0.3, 0.9, 0.7], dtype=np.float32)

    def __init__(self) -> None:
        self.seen: list[np.ndarray] = []

    def predict(self, observations: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
        self.seen.append(observations.copy())
        return np.repeat(self.action[None], len(observations), axis=0), None


def striker(ball_proximity: float, ball_bearing_deg: float, fill: float) -> np.ndarray:
    observation = np.full(74, fill, dtype=np.float32)
    observation[58:66] = 5.0  # the teammate's block: the 1v1 policy must not see it
    observation[51] = np.sin(np.radians(ball_bearing_deg))
    observation[52] = np.cos(np.radians(ball_bearing_deg))
    observation[53] = ball_proximity
    return observation


@pytest.mark.parametrize("idle", ["noop", "clear"])
def test_the_striker_nearer_the_ball_plays_the_policy_alone_and_the_other_idles(idle: str) -> None:
    module = load_script()
    policy = RecordingPolicy()
    team = module.RoleSplitTeam(policy, idle)
    near = 1.0 - 2.0 * 3.0 / MAX_HFO_DIST  # 3 m from the ball
    far_but_close = 1.0 - 2.0 * 6.0 / MAX_HFO_DIST  # 6 m: inside CLEAR_DISTANCE
    far = 1.0 - 2.0 * 20.0 / MAX_HFO_DIST  # 20 m: outside it
    batch = np.stack(
        [
            striker(far_but_close, 90.0, 0.1),  # game 0: the second striker is nearer
            striker(near, 0.0, 0.2),
            striker(near, 0.0, 0.3),  # game 1: the first one is
            striker(far, -45.0, 0.4),
        ]
    )
    actions, _ = team.predict(batch)
    shown = policy.seen[-1]
    assert shown.shape == (2, 66)  # the 1v1 view: the teammate's block left out
    np.testing.assert_array_equal(shown, np.delete(batch[[1, 2]], np.s_[58:66], axis=1))
    np.testing.assert_array_equal(actions[[1, 2]], np.repeat(policy.action[None], 2, axis=0))
    np.testing.assert_array_equal(actions[3], module.NOOP_ACTION)  # far from the ball: stands either way
    if idle == "noop":
        np.testing.assert_array_equal(actions[0], module.NOOP_ACTION)
    else:  # 6 m from a ball at +90 degrees: full dash toward -90 degrees
        np.testing.assert_allclose(actions[0][:5], [1.0, 0.0, 0.0, 1.0, 0.25], atol=1e-6)


def test_bad_idle_behaviours_and_batches_are_refused() -> None:
    module = load_script()
    with pytest.raises(ValueError, match="unknown idle behaviour"):
        module.RoleSplitTeam(RecordingPolicy(), "wander")
    with pytest.raises(ValueError, match="games x 2"):
        module.RoleSplitTeam(RecordingPolicy(), "noop").predict(np.zeros((3, 74), dtype=np.float32))


def test_a_taught_start_is_distilled_before_rl_and_named_so(tmp_path: Path) -> None:
    out = tmp_path / "run"
    command = [
        sys.executable, str(SCRIPT), "train", "--arm", "2v1", "--out", str(out), "--steps", "512",
        "--n-envs", "4", "--eval-every", "512", "--eval-episodes", "2", "--critic-warmup", "256",
        "--hp", json.dumps({"batch_size": 256, "n_steps": 64}), "--reward", "shaped_gap_refund_nearest",
        "--start-rule", "clear", "--teach-episodes", "4", "--teach-epochs", "1", "--teach-eval-episodes", "4",
        "--games", "2",
    ]  # fmt: skip
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    run = json.loads((out / "arm_2v1" / "run.json").read_text())
    assert (run["start_rule"], run["reward"]) == ("clear", "shaped_gap_refund_nearest")
    teach = json.loads((out / "arm_2v1" / "teach.json").read_text())
    first, dagger = teach["rounds"]
    assert dagger["states"] > first["states"] > 0  # the DAgger round adds the student's states
    assert teach["greedy_eval"]["episodes"] == teach["teacher_eval"]["episodes"] == 4
    # teaching moved the widened policy off its zero weights on the teammate's block
    start = HybridPPO.load(out / "arm_2v1" / "start.zip", device="cpu").policy.state_dict()
    trunk = next(key for key in start if key.endswith("trunk.0.weight"))
    assert th.count_nonzero(start[trunk][:, 58:66]) > 0
    evaluation = [
        sys.executable,
        str(SCRIPT),
        "evaluate",
        "--out",
        str(out),
        "--episodes",
        "2",
        "--games",
        "2",
    ]
    evaluation += ["--which", "zero_shot_2v1"]
    completed = subprocess.run(evaluation, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    assert (out / "eval_hfo2d_taught_start_2v1.json").exists()
    assert not (out / "eval_hfo2d_zero_shot_2v1.json").exists()
    refused = subprocess.run(
        [*command[:4], "1v1", *command[5:]], capture_output=True, text=True, timeout=300, cwd=tmp_path
    )
    assert refused.returncode != 0 and "--start-rule" in refused.stderr


def with_teammate(observation: np.ndarray, proximity: float, bearing_deg: float) -> np.ndarray:
    observation = observation.copy()
    observation[58:66] = 0.0
    observation[58] = np.sin(np.radians(bearing_deg))
    observation[59] = np.cos(np.radians(bearing_deg))
    observation[60] = proximity
    return observation


def test_a_striker_judges_from_its_own_features_whether_it_is_nearer_the_ball() -> None:
    """The decentralised rule of OwnFeaturesRoleSplitTeam: the teammate's distance to the ball from the two
    bearings and proximities in the striker's own frame; an unlisted teammate (an all-zero block) is farther."""
    module = load_script()

    def proximity(metres: float) -> float:
        return 1.0 - 2.0 * metres / MAX_HFO_DIST

    ball_5m_ahead = striker(proximity(5.0), 0.0, 0.0)
    cases = [
        (
            with_teammate(ball_5m_ahead, proximity(5.0), 90.0),
            True,
        ),  # the teammate is sqrt(50) m from the ball
        (with_teammate(ball_5m_ahead, proximity(8.0), 0.0), False),  # 3 m beyond the ball
        (with_teammate(ball_5m_ahead, proximity(7.0), 10.0), False),  # ~2.1 m from the ball
        (with_teammate(ball_5m_ahead, proximity(2.0), 0.0), False),  # 3 m short of it
        (with_teammate(ball_5m_ahead, proximity(9.0), 180.0), True),  # behind the striker: 14 m from the ball
    ]
    # a ball 1 m short of MAX_HFO_DIST / 2 ahead, where an unlisted teammate's zeros (proximity 0, no bearing)
    # read as an angle of 0 would put the teammate 1 m from the ball
    unlisted = striker(proximity(MAX_HFO_DIST / 2.0 - 1.0), 0.0, 0.0)
    unlisted[58:66] = 0.0
    cases.append((unlisted, True))
    observations = np.stack([observation for observation, _ in cases])
    judged = module.judges_itself_nearer(observations)
    assert judged.tolist() == [expected for _, expected in cases]


def test_the_own_features_rule_agrees_with_the_pair_comparison_on_played_states() -> None:
    """On the states of 2v1 hfo2d games (from HFO's starts; the ball player only kicks), the decentralised rule
    picks the same ball player as comparing the two strikers' ball proximities wherever the teammate is listed,
    and never lets both strikers idle (an unlisted teammate, behind the halfway line, makes both play)."""
    module = load_script()
    team = module.RoleSplitTeam(RecordingPolicy(), "noop")
    observations = module.play_pairs(team, 16, 0, 8)
    own = module.judges_itself_nearer(observations)
    listed = np.hypot(observations[:, 58], observations[:, 59]) > 0.5
    assert len(observations) > 500 and 0.5 < listed.mean() < 1.0  # both kinds of state are checked
    assert (own == team.nearer(observations))[listed].mean() > 0.99
    assert not (~own.reshape(-1, 2).any(axis=1)).any()  # never both idle


def test_the_routed_start_plays_the_ball_as_the_start_and_its_support_head_stands(tmp_path: Path) -> None:
    """train --router ball_player: the striker that judges itself nearer plays exactly the widened start (heads 0
    and 1 copied), the other one the new support head, whose greedy action is a TURN by 0 degrees."""
    module = load_script()
    start_env = module.make_team_vec_env(1, offense_agents=1, defense_npcs=1)
    start = module.fresh_start_model(start_env, seed=3)
    env = module.make_team_vec_env(2, offense_agents=2, defense_npcs=1, seed=0)
    arguments = {"seed": 0, "smoke": True, "out": tmp_path, "arm": "2v1", "critic_warmup": 0, "hp": module.HP}
    plain = module.build_arm_model(start, env, 2, argparse.Namespace(**arguments, router=None))
    routed = module.build_arm_model(start, env, 2, argparse.Namespace(**arguments, router="ball_player"))
    assert (plain.policy.n_skills, routed.policy.n_skills) == (2, 3)
    observations = module.play_pairs(module.RoleSplitTeamBoth(start), 8, 0, 4)
    nearer = module.judges_itself_nearer(observations)
    assert 0.2 < nearer.mean() < 0.8  # both roles occur
    routed_actions, _ = routed.predict(observations, deterministic=True)
    plain_actions, _ = plain.predict(observations, deterministic=True)
    np.testing.assert_array_equal(routed_actions[nearer], plain_actions[nearer])
    support = routed_actions[~nearer]
    assert (support[:, :3].argmax(axis=1) == 1).all()  # TURN
    np.testing.assert_allclose(support[:, 5], 0.5, atol=1e-6)  # by 0 degrees
    # the values are the widened start's too (the critic is copied)
    tensor = th.as_tensor(observations)
    np.testing.assert_allclose(
        routed.policy.predict_values(tensor).detach(), plain.policy.predict_values(tensor).detach(), atol=1e-6
    )
    with pytest.raises(SystemExit, match="1v1 arm has none"):
        module.main(["train", "--arm", "1v1", "--router", "ball_player", "--out", str(tmp_path / "x")])
    env.close()
    start_env.close()
