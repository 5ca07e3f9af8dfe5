"""benchmarks/two_v_two_scripted.py: what its strikers read, when the pair passes, and the script end to end."""

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
from hfo2d.team import TeamGame

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "benchmarks" / "two_v_two_scripted.py"


def load_script():
    spec = importlib.util.spec_from_file_location("two_v_two_scripted_under_test", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclass looks its module up while the class is built
    spec.loader.exec_module(module)
    return module


def test_an_unknown_team_is_a_value_error_naming_the_choices() -> None:
    with pytest.raises(ValueError, match="unknown team 'trio'"):
        load_script().ScriptedPair("trio")


def test_each_striker_reads_its_teammate_and_the_field_defender_where_they_are() -> None:
    script = load_script()
    game = TeamGame(2, 0, 2, seed=3, feature_set="hfo")
    observations, _ = game.reset(seed=3)
    for _ in range(5):  # a few cycles of play, so that bodies turn and players move
        observations, *_ = game.step(
            {name: strikers.flat_action(strikers.idle()) for name in game.agent_names}
        )
    goalie = next(p for p in game.defense_players if p.goalie)
    defender = next(p for p in game.defense_players if not p.goalie)
    for index, name in enumerate(game.agent_names):
        view = script.read_team_view(observations[name], 1, 2)
        me, mate = game.offense_players[index], game.offense_players[1 - index]
        assert math.hypot(view.percept.x - me.x, view.percept.y - me.y) < 0.05
        assert view.percept.goalie is not None
        assert math.hypot(view.percept.goalie[0] - goalie.x, view.percept.goalie[1] - goalie.y) < 0.05
        assert len(view.teammates) == 1 and len(view.field_defenders) == 1
        assert math.hypot(view.teammates[0][0] - mate.x, view.teammates[0][1] - mate.y) < 0.05
        fx, fy = view.field_defenders[0]
        assert math.hypot(fx - defender.x, fy - defender.y) < 0.05


def _views(script, defender: tuple[float, float]):
    ball = {"ball_x": 36.3, "ball_y": 5.0, "ball_vx": 0.0, "ball_vy": 0.0}
    player = Percept(x=35.8, y=5.0, body_deg=0.0, kickable=True, goalie=(50.0, 2.0), **ball)
    mate = Percept(x=38.0, y=-13.0, body_deg=90.0, kickable=False, goalie=(50.0, 2.0), **ball)
    return [
        script.TeamView(player, ((mate.x, mate.y),), (defender,)),
        script.TeamView(mate, ((player.x, player.y),), (defender,)),
    ]


def test_the_ball_player_passes_when_the_defender_presses_and_the_supporter_is_open() -> None:
    script = load_script()
    team = script.ScriptedPair("pass")
    commands = team.commands(_views(script, defender=(39.0, 6.0)))  # 2.9 m from the ball, 19 m from the mate
    kind, power, direction = commands[0]
    assert kind == strikers.KICK and power > 0.0
    # the kick's direction (body frame, the body faces +x) points to the mate: down-field and to the -y side
    assert -90.0 < direction < -30.0
    assert team.receiver == 1 and team.passes == 1
    # while the pass is on its way (both strikers see the ball moving) the receiver chases it and the passer stands
    passer, receiver = (
        dataclasses.replace(view.percept, ball_vx=0.3, ball_vy=-1.5, kickable=False)
        for view in _views(script, defender=(39.0, 6.0))
    )
    views = _views(script, defender=(39.0, 6.0))
    after = team.commands(
        [dataclasses.replace(views[0], percept=passer), dataclasses.replace(views[1], percept=receiver)]
    )
    assert after[0] == strikers.idle()
    assert after[1] == strikers.chase_ball(receiver, *strikers.GOAL_CENTRE)
    assert team.receiver == 1


@pytest.mark.parametrize(
    "defender, why",
    [
        ((45.0, 12.0), "not pressing: 11.2 m from the ball"),
        ((36.8, 1.0), "pressing (4.0 m), but in the passing lane"),
    ],
)
def test_no_pass_without_pressure_or_with_the_supporter_marked(defender, why) -> None:
    script = load_script()
    team = script.ScriptedPair("pass")
    commands = team.commands(_views(script, defender=defender))
    assert commands[0] == team.striker.decide(_views(script, defender)[0].percept), why
    assert team.receiver is None and team.passes == 0
    # the split team never passes, whatever the defender does
    split = script.ScriptedPair("split")
    split.commands(_views(script, defender=(39.0, 6.0)))
    assert split.passes == 0


def test_the_supporter_runs_to_the_far_side_goalward_of_the_ball() -> None:
    script = load_script()
    views = _views(script, defender=(45.0, 12.0))
    spot = script.support_spot(views[0].percept)
    assert spot == (36.3 + script.SUPPORT_DEPTH, -script.SUPPORT_WIDTH)
    # the supporter of _views stands 0.3 m from that spot: it turns to the ball; 5 m away, it runs to the spot
    commands = script.ScriptedPair("split").commands(views)
    assert commands[1] == strikers.turn_to(views[1].percept, 36.3, 5.0)
    away = dataclasses.replace(views[1].percept, x=33.0)
    commands = script.ScriptedPair("split").commands([views[0], dataclasses.replace(views[1], percept=away)])
    assert commands[1] == strikers.move_to(away, *spot) and commands[1][0] == strikers.TURN


def test_the_script_plays_every_team_and_writes_its_figures(tmp_path: Path) -> None:
    out = tmp_path / "two_v_two.json"
    subprocess.run(
        [sys.executable, str(SCRIPT), "--episodes", "2", "--seed", "1", "--out", str(out)],
        check=True,
        capture_output=True,
        cwd=REPO,
        timeout=120,
    )
    record = json.loads(out.read_text())
    assert set(record["results"]) == {"alone", "both", "split", "pass", "own_pass"}
    for team, result in record["results"].items():
        assert result["episodes"] == 2 and sum(result["status"].values()) == 2, team
        assert result["backend"] == "hfo2d"


def test_own_pass_decides_from_each_striker_s_own_view() -> None:
    script = load_script()
    team = script.ScriptedPair("own_pass")
    pressed = _views(script, defender=(39.0, 6.0))
    # the ball player (nearer by its own view) passes as the pass team's ball player does
    ball_player_command = team.own_command(pressed[0])
    assert ball_player_command == script.ScriptedPair("pass").commands(pressed)[0]
    assert ball_player_command[0] == strikers.KICK and team.passes == 1
    # the supporter, farther by its own view, holds its spot facing the ball
    assert team.own_command(pressed[1]) == strikers.turn_to(pressed[1].percept, 36.3, 5.0)
    # with the pass on its way (the ball heading from (36.3, 5) to (38, -13) at 1.5 m/cycle), the receiver chases
    # it and the passer, though still nearer, leaves it alone
    velocity = {"ball_vx": 1.7 / 18.08 * 1.5, "ball_vy": -18.0 / 18.08 * 1.5, "kickable": False}
    passer = dataclasses.replace(pressed[0].percept, **velocity)
    receiver = dataclasses.replace(pressed[1].percept, **velocity)
    assert team.own_command(dataclasses.replace(pressed[0], percept=passer)) == strikers.idle()
    assert team.own_command(dataclasses.replace(pressed[1], percept=receiver)) == strikers.chase_ball(
        receiver, *strikers.GOAL_CENTRE
    )
    # a slow ball is no pass: the nearer striker plays it
    slow = dataclasses.replace(passer, ball_vx=0.1, ball_vy=-0.3)
    assert team.own_command(dataclasses.replace(pressed[0], percept=slow)) == team.striker.decide(slow)
    # without a listed teammate a striker plays alone
    alone = dataclasses.replace(pressed[0], teammates=())
    assert team.own_command(alone) == team.striker.decide(alone.percept)
