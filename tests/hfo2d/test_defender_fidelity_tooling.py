"""benchmarks/defender_fidelity.py without a real HFO: logs in real HFO's formats written from an hfo2d game, read
back and replayed. The replay must find every logged command again, and report a changed one with its cause."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import numpy as np

from hfo2d.agent2d.defender import Agent2dDefender
from hfo2d.agent2d.goalie import Agent2dGoalie
from hfo2d.physics import PlayerState, ServerParams, World

CYCLES = 40


def _g(v: float) -> str:
    return f"{v:.6g}"


def _fullstate_player(p: PlayerState) -> str:
    tag = f"(p {p.side} {p.unum}{' g' if p.goalie else ''} 0)"
    numbers = " ".join(_g(v) for v in (p.x, p.y, p.vx, p.vy, p.body_deg, 0.0))
    flags = " t" if p.tackle_cycles > 0 else ""
    return f"({tag} {numbers} (stamina {_g(p.stamina)} {_g(p.effort)} {_g(p.recovery)} 130600){flags})"


def _write_session(log_dir: Path) -> list[str]:
    """A real-HFO-like log directory of one episode (cycles 1..CYCLES) of hfo2d's goalie and field defender 2
    against a dribbling attacker: the defender's client log (.ocl), the server's text log (.rcl) with its commands,
    a game log (.rcg) and the episode log (.hfo). Returns the defender's command texts."""
    params = ServerParams()
    world = World(params, np.random.default_rng(0), noise=False)
    attacker = world.add_player("l", 11)
    goalie = world.add_player("r", 1, goalie=True)
    me = world.add_player("r", 2)
    world.place_player(attacker, 30.0, 6.0, 0.0)
    world.place_ball(30.6, 6.0)
    world.place_player(goalie, 52.5, 0.0, 180.0)
    world.place_player(me, 44.0, -8.0, 180.0)
    keeper = Agent2dGoalie(params, np.random.default_rng(0))
    defender = Agent2dDefender(params, np.random.default_rng(0), unum=2)
    ocl, rcl, rcg, texts = [], [], [], []
    for t in range(1, CYCLES + 1):
        world.cycle = t
        ball = world.ball
        players = " ".join(_fullstate_player(p) for p in world.players)
        ocl.append(f"(sense_body {t} (view_mode high normal) (stamina 8000 1 130600))")
        if t == 1:
            ocl.append(f"(hear {t} referee play_on)")
        ocl.append(
            f"(fullstate {t} (pmode play_on) ((b) {' '.join(_g(v) for v in (ball.x, ball.y, ball.vx, ball.vy))}) {players})"
        )
        ocl.append("(think)")
        rcg.append(f"(show {t} ((b) {_g(ball.x)} {_g(ball.y)} {_g(ball.vx)} {_g(ball.vy)}))")
        keeper.decide(world, goalie)
        command = defender.decide(world, me)
        recorder = _Recorder()
        defender.apply(recorder, me)
        texts.append(recorder.text)
        rcl.append(f"{t},0\tRecv base_right_2: {recorder.text}(turn_neck 0)(done)")
        if math.hypot(ball.x - attacker.x, ball.y - attacker.y) < 1.0:
            world.kick(
                attacker, 20.0, math.degrees(math.atan2(-attacker.y, 52.5 - attacker.x)) - attacker.body_deg
            )
        else:
            world.dash(attacker, 70.0, 0.0)
        keeper.apply(world, goalie)
        defender.apply(world, me, command)
        world.step()
    (log_dir / "base_right-2.ocl").write_text("\n".join(ocl) + "\n")
    (log_dir / "session.rcl").write_text("\n".join(rcl) + "\n")
    (log_dir / "session.rcg").write_text("\n".join(rcg) + "\n")
    (log_dir / "session.hfo").write_text(f"# episodes\n1\t1\t{CYCLES}\t{CYCLES - 1}\tOUT_OF_TIME\n")
    (log_dir / "deterministic").write_text("test\n")
    return texts


class _Recorder:
    """The World commands a defender sends, written as librcsc writes them (6 significant digits)."""

    text = "(turn 0)"

    def turn(self, _p: object, moment: float) -> None:
        self.text = f"(turn {_g(moment)})"

    def dash(self, _p: object, power: float, direction: float = 0.0) -> None:
        self.text = f"(dash {_g(power)})" if direction == 0.0 else f"(dash {_g(power)} {_g(direction)})"

    def kick(self, _p: object, power: float, direction: float) -> None:
        self.text = f"(kick {_g(power)} {_g(direction)})"

    def tackle(self, _p: object, direction: float, foul: bool = False) -> None:
        self.text = f"(tackle {_g(direction)} {'on' if foul else 'off'})"


def test_replay_finds_the_logged_commands_again(
    tmp_path: Path, benchmark_script: Callable[[str], ModuleType]
) -> None:
    fidelity = benchmark_script("defender_fidelity")
    texts = _write_session(tmp_path)
    assert len(set(texts)) > 5  # the defender did several things
    args = fidelity.build_parser().parse_args(["replay", str(tmp_path), "--show", "0"])
    summary = fidelity.cmd_replay(args)["summary"]
    assert summary["cycles"] == CYCLES and summary["agree"] == CYCLES

    # one logged command changed: one disagreement, whose cause the logs do not explain
    rcl = tmp_path / "session.rcl"
    lines = rcl.read_text().splitlines()
    lines[9] = "10,0\tRecv base_right_2: (dash 13.5 90)(turn_neck 0)(done)"
    rcl.write_text("\n".join(lines) + "\n")
    result = fidelity.cmd_replay(args)
    assert result["summary"]["agree"] == CYCLES - 1
    (mismatch,) = result["mismatches"]
    assert mismatch["cycle"] == 10 and mismatch["real"] == "(dash 13.5 90)" and mismatch["cause"] == "other"


def test_tackle_freezes_count_down_from_the_first_flag(benchmark_script: Callable[[str], ModuleType]) -> None:
    fidelity = benchmark_script("defender_fidelity")
    logs = benchmark_script("real_hfo_logs")

    def player(flags: str) -> object:
        return logs.FullstatePlayer(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 8000.0, 1.0, 1.0, flags)

    history: dict[tuple[str, int], int] = {}
    seen = [
        fidelity._tackle_freezes(history, {("l", 11): player(f)}).get(("l", 11), 0)
        for f in ("", "t", "t", "")
    ]
    assert seen == [0, 9, 8, 0]
