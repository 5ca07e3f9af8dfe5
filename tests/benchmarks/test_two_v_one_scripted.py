"""benchmarks/two_v_one_scripted.py: its scripted teams' roles, and the script end to end at tiny settings."""

from __future__ import annotations

import dataclasses
import importlib.util
import json
import subprocess
import sys
from pathlib import Path

import pytest

from hfo2d import strikers
from hfo2d.strikers import Percept

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "benchmarks" / "two_v_one_scripted.py"


def load_script():
    spec = importlib.util.spec_from_file_location("two_v_one_scripted_under_test", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_an_unknown_team_is_a_value_error_naming_the_choices() -> None:
    with pytest.raises(ValueError, match="unknown team 'trio'"):
        load_script().ScriptedTeam("trio")


def test_in_the_support_team_the_nearer_striker_plays_soft_dribble_and_the_other_runs_to_its_spot() -> None:
    script = load_script()
    team = script.ScriptedTeam("support")
    ball = {"ball_x": 31.0, "ball_y": 2.0, "ball_vx": 0.0, "ball_vy": 0.0}
    near = Percept(x=30.0, y=2.0, body_deg=0.0, kickable=False, goalie=(50.0, -1.0), **ball)
    far = Percept(x=20.0, y=-20.0, body_deg=90.0, kickable=False, goalie=(50.0, -1.0), **ball)
    spot = script.ScriptedTeam._spot(near)
    # the goalie stands below the centre (y -1), so soft_dribble aims at the post above it, and the spot is there
    assert spot == script.SUPPORT_SPOT
    for nearer, percepts in ((0, [near, far]), (1, [far, near])):
        commands = team.commands(percepts, nearer)
        assert commands[nearer] == strikers.make_striker("soft_dribble").decide(near)
        assert commands[1 - nearer] == strikers.move_to(far, *spot)
        assert commands[1 - nearer] != strikers.make_striker("soft_dribble").decide(far)


def test_the_tap_in_supporter_steps_onto_a_wide_shot_and_holds_for_one_on_target() -> None:
    script = load_script()
    team = script.ScriptedTeam("tap_in")
    spot = (script.SUPPORT_SPOT[0], script.SUPPORT_SPOT[1])
    wide = Percept(
        x=49.0,
        y=12.0,
        body_deg=-90.0,
        ball_x=42.0,
        ball_y=0.0,
        ball_vx=2.0,
        ball_vy=1.8,
        kickable=False,
        goalie=(51.0, -1.0),
    )
    on_target = dataclasses.replace(wide, ball_vy=0.4)  # crosses the goal line at y 3.3
    assert team._onto_wide_shot(on_target, spot) == team._hold(on_target, spot)
    stepping = team._onto_wide_shot(wide, spot)
    assert stepping != team._hold(wide, spot)
    # the point it runs to lies on the ball's line (y - 0 = 0.9 (x - 42)), ahead of the ball
    ahead = ((49.0 - 42.0) * 2.0 + 12.0 * 1.8) / (2.0**2 + 1.8**2)
    assert stepping == strikers.move_to(wide, 42.0 + 2.0 * ahead, 1.8 * ahead)


def test_the_script_plays_every_team_and_writes_its_figures(tmp_path: Path) -> None:
    out = tmp_path / "scripted.json"
    command = [sys.executable, str(SCRIPT), "--episodes", "2", "--out", str(out)]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    results = json.loads(out.read_text())["results"]
    assert set(results) == {"alone", "both", "support", "tap_in", "pass"}
    for row in results.values():
        assert sum(row["status"].values()) == 2 and row["goals"] == row["status"].get("GOAL", 0)
        assert row["ci95"][0] <= row["rate"] <= row["ci95"][1]
        assert 0 <= row["out_over_goal_line"] <= row["status"].get("OUT_OF_BOUNDS", 0)
