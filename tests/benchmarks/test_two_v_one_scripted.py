"""benchmarks/two_v_one_scripted.py: its scripted teams' roles, and the script end to end at tiny settings."""

from __future__ import annotations

import dataclasses
import importlib.util
import json
import math
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
    assert set(results) == {"alone", "both", "support", "tap_in", "pass", "screen"}
    for row in results.values():
        assert sum(row["status"].values()) == 2 and row["goals"] == row["status"].get("GOAL", 0)
        assert row["ci95"][0] <= row["rate"] <= row["ci95"][1]
        assert 0 <= row["out_over_goal_line"] <= row["status"].get("OUT_OF_BOUNDS", 0)


def test_the_screen_runs_beside_the_goalie_toward_the_far_post_then_pushes_into_it() -> None:
    script = load_script()
    team = script.ScriptedTeam("screen")
    ball = {"ball_x": 38.0, "ball_y": 3.0, "ball_vx": 0.0, "ball_vy": 0.0}
    goalie = (50.0, 1.0)  # above the centre: soft_dribble aims at the post below, at y -7.01
    player = Percept(x=37.0, y=3.0, body_deg=0.0, kickable=False, goalie=goalie, **ball)
    post = strikers.far_post(player, 0.0)
    assert post[1] < 0
    length = math.hypot(post[0] - goalie[0], post[1] - goalie[1])
    point = tuple(g + (q - g) / length * script.SCREEN_GAP for g, q in zip(goalie, post, strict=True))
    away = Percept(x=30.0, y=-10.0, body_deg=0.0, kickable=False, goalie=goalie, **ball)
    commands = team.commands([player, away], 0)
    assert commands[0] == strikers.make_striker("soft_dribble").decide(player)
    assert commands[1] == strikers.move_to(away, *point)
    there = dataclasses.replace(away, x=point[0], y=point[1])
    assert team.commands([player, there], 0)[1] == strikers.move_to(there, *goalie)


def test_the_pass_settings_reach_the_team_and_bad_ones_are_refused(tmp_path: Path) -> None:
    script = load_script()
    goalie = (47.0, -1.0)  # 5 m from the ball
    ball = {"ball_x": 42.0, "ball_y": -1.0, "ball_vx": 0.0, "ball_vy": 0.0}
    player = Percept(x=41.5, y=-1.0, body_deg=0.0, kickable=True, goalie=goalie, **ball)
    mate = Percept(x=46.0, y=8.0, body_deg=-90.0, kickable=False, goalie=goalie, **ball)
    dribble = strikers.make_striker("soft_dribble").decide(player)
    near_only = script.ScriptedTeam("pass", pass_goalie_range=3.0)
    assert near_only.commands([player, mate], 0)[0] == dribble and near_only.passes == 0
    wider = script.ScriptedTeam("pass", pass_goalie_range=6.0, pass_lane_clearance=1.0)
    assert wider.commands([player, mate], 0)[0] != dribble and wider.passes == 1
    moved = script.ScriptedTeam("support", support_spot=(46.0, 4.0))
    assert moved.commands([player, mate], 0)[1] == strikers.move_to(mate, 46.0, 4.0)
    command = [sys.executable, str(SCRIPT), "--support-spot", "60", "4", "--out", str(tmp_path / "x.json")]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert (
        completed.returncode == 2
        and "--support-spot X ABS_Y must lie in the offense half" in completed.stderr
    )
    assert not (tmp_path / "x.json").exists()
