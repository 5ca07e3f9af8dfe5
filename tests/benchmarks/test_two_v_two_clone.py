"""benchmarks/two_v_two_clone.py: its teacher is the scripted rule, and the script end to end at tiny settings."""

from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import numpy as np
import torch as th

from hfo2d import strikers
from hfo2d.team import TeamGame

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "benchmarks" / "two_v_two_clone.py"


def test_the_teacher_labels_each_striker_as_the_scripted_rule_would_from_its_own_view(
    benchmark_script: Callable[[str], ModuleType],
) -> None:
    script = benchmark_script("two_v_two_clone")
    game = TeamGame(2, 0, 2, seed=5, feature_set="hfo")
    observations, _ = game.reset(seed=5)
    teacher = script.ScriptedPredictor("own_pass", 1)
    rule = script.ScriptedPair("own_pass")
    for _ in range(30):
        batch = np.stack([observations[name] for name in game.agent_names])
        actions, _ = teacher.predict(batch)
        for observation, action in zip(batch, actions, strict=True):
            expected = strikers.flat_action(rule.own_command(script.read_team_view(observation, 1, 2)))
            np.testing.assert_array_equal(action, expected)
        observations, _, terminated, truncated, _ = game.step(
            dict(zip(game.agent_names, actions, strict=True))
        )
        if terminated or truncated:
            observations, _ = game.reset()
    alone = script.ScriptedPredictor("alone", 0)
    single, _ = TeamGame(1, 0, 2, seed=5, feature_set="hfo").reset(seed=5)
    action, _ = alone.predict(single["offense_0"][None])
    view = script.read_team_view(single["offense_0"], 0, 2)
    np.testing.assert_array_equal(action[0], strikers.flat_action(rule.striker.decide(view.percept)))


def test_the_script_clones_an_arm_and_writes_its_student_and_figures(tmp_path: Path) -> None:
    subprocess.run(
        [sys.executable, str(SCRIPT), "--arm", "1v2", "--out", str(tmp_path), "--smoke"],
        check=True,
        capture_output=True,
        cwd=REPO,
        timeout=120,
    )
    record = json.loads((tmp_path / "arm_1v2" / "clone.json").read_text())
    assert (tmp_path / "arm_1v2" / "student.zip").is_file()
    assert record["teacher"] == "alone" and len(record["rounds"]) == 2  # the first round and one DAgger round
    assert record["rounds"][1]["states"] > record["rounds"][0]["states"]
    for name in ("student", "teacher_eval"):
        assert record[name]["episodes"] == 2 and sum(record[name]["status"].values()) == 2


def test_the_routed_student_sees_each_strikers_own_pass_role_and_plays_that_roles_head(
    benchmark_script: Callable[[str], ModuleType],
) -> None:
    script = benchmark_script("two_v_two_clone")
    game = TeamGame(2, 0, 2, seed=3, feature_set="hfo")
    observations, _ = game.reset(seed=3)
    batch = np.stack([observations[name] for name in game.agent_names])
    with_roles = script.with_roles(batch, 1)
    assert with_roles.shape == (2, 86 + len(script.ROLES))
    np.testing.assert_array_equal(with_roles[:, :86], batch)
    for observation, row in zip(batch, with_roles, strict=True):
        role = script.own_pass_role(script.read_team_view(observation, 1, 2))
        assert row[86:].tolist() == np.eye(len(script.ROLES))[role].tolist()
    model = script.student_model(2, seed=0, actor=[8], routed=True)
    assert model.observation_space.shape == (86 + len(script.ROLES),)
    skills = model.policy.routed_skills(th.as_tensor(with_roles))
    assert skills.tolist() == with_roles[:, 86:].argmax(axis=1).tolist()
    actions, _ = script.RolePredictor(model, 1).predict(batch, deterministic=True)
    assert actions.shape == (2, 8)


def test_the_role_wrapper_appends_roles_to_terminal_observations_too(
    benchmark_script: Callable[[str], ModuleType],
) -> None:
    script = benchmark_script("two_v_two_clone")
    from sb3_hfo.multi_agent import make_team_vec_env

    env = script.RoleObservations(
        make_team_vec_env(1, offense_agents=2, defense_npcs=2, feature_set="hfo"), 1
    )
    observations = env.reset()
    assert observations.shape == (2, 86 + len(script.ROLES))
    for _ in range(600):  # HFO's episodes end within 500 cycles of no touch; the idle strikers never touch
        observations, _, dones, infos = env.step(np.stack([strikers.flat_action(strikers.idle())] * 2))
        if dones.any():
            break
    assert dones.all()
    for info in infos:
        terminal = info["terminal_observation"]
        assert terminal.shape == (86 + len(script.ROLES),) and terminal[86:].sum() == 1.0
    assert (observations[:, 86:].sum(axis=1) == 1.0).all()


def test_the_script_clones_a_routed_arm(tmp_path: Path) -> None:
    subprocess.run(
        [sys.executable, str(SCRIPT), "--arm", "2v2", "--routed", "--out", str(tmp_path), "--smoke"],
        check=True,
        capture_output=True,
        cwd=REPO,
        timeout=120,
    )
    record = json.loads((tmp_path / "arm_2v2" / "clone.json").read_text())
    assert record["routed"] and record["teacher"] == "own_pass"
    assert record["student"]["episodes"] == 2
