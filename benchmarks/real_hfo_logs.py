"""Readers for the logs of a real HFO run: rcssserver's game log (.rcg), text log (.rcl) and HFO's episode log (.hfo).

Formats (rcssserver 15.2.2 as HFO builds it; facts from its sources, no code):

* ``.rcg``, version 5 (``ULG5``; src/serializermonitor.cpp): one ``(show T ...)`` line per cycle T, holding the ball
  ``((b) x y vx vy)`` and every player ``((side unum) type state x y vx vy body neck [arm_x arm_y] (v ...) (s ...)
  ...)``. Positions and velocities are quantised to 1e-4, angles (degrees) to 1e-3 (``PREC``, ``DPREC``), then
  printed with the stream's default 6 significant digits. ``show T`` is the state after the server's step to T
  and the referee's reaction to it (an HFO reset at T is already in ``show T``). Disabled players (HFO parks the
  unused NPCs off the pitch) have state 0.
* ``.rcl`` (src/logger.cpp): ``T,sub<TAB>Recv NAME: (cmd ...)(cmd ...)`` for every message a client sent in cycle
  T; the body command among them is executed in the step T -> T+1. librcsc prints the numbers with the stream's
  default 6 significant digits, and the server parses that text, so the logged value is the executed one.
  Referee messages appear as ``T,sub<TAB>(referee MSG)``.
* ``.ocl``, a client's offline log (librcsc ``offline_logging``; the player.conf of HFO's base team has it commented
  out): every message the client received, one per line, in order. Per cycle T: ``(sense_body T ...)``, ``(fullstate
  T ...)`` (numbers printed with 6 significant digits, rcssserver serializerplayerstdv1.cpp), ``(see T ...)``,
  ``(hear T referee MSG)`` and ``(think)``, the synch_see mode's signal to decide. rcssserver's HFO mode keeps its
  own play mode PlayOn, so the client's game mode comes from the referee messages it hears
  (``goalie_catch_ball_r``, ``before_kick_off``, ``play_on``). A client killed at the end of a session loses the
  last few kB of it.
* ``.hfo`` (src/referee.cpp HFORef::logEpisode): ``episode<TAB>start<TAB>end<TAB>duration<TAB>result`` per episode;
  ``start`` is the cycle of the reset (``show start`` has the new placement), ``end`` the cycle after whose step
  the referee ended it. The result is ``GOAL-unum``, ``CAPTURED_BY_DEFENSE-unum``, ``OUT_OF_BOUNDS`` or
  ``OUT_OF_TIME``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

BODY_COMMANDS = ("dash", "turn", "kick", "catch", "tackle", "move")
_NUMBER = r"(-?[0-9.]+(?:e[-+]?[0-9]+)?)"
_SHOW = re.compile(r"^\(show (\d+) ")
_BALL = re.compile(r"\(\(b\) " + " ".join([_NUMBER] * 4) + r"\)")
_RECV = re.compile(r"^(\d+),\d+\tRecv ([^:]+): (.*)$")
_COMMAND = re.compile(r"\((\w+)((?: [^()\s]+)*)\)")


@dataclass(frozen=True)
class PlayerShow:
    """A player in one ``show``: position, velocity (m, m/cycle), body and neck angle (deg), state flags."""

    x: float
    y: float
    vx: float
    vy: float
    body: float
    neck: float
    state: int


@dataclass(frozen=True)
class Show:
    """One cycle of the game log: the ball (x, y, vx, vy) and the players by (side, unum)."""

    time: int
    ball: tuple[float, float, float, float]
    players: dict[tuple[str, int], PlayerShow]


@dataclass(frozen=True)
class BodyCommand:
    """A body command as the server received it: name and its arguments (numbers where they parse)."""

    name: str
    args: tuple[float | str, ...]

    def text(self) -> str:
        return "(" + " ".join([self.name, *(_fmt(a) for a in self.args)]) + ")"


@dataclass
class Episode:
    """One HFO episode: reset cycle ``start``, end cycle ``end``, HFO's result (suffix dropped)."""

    number: int
    start: int
    end: int
    result: str


@dataclass
class GameLogs:
    """Everything read from one server session's logs."""

    shows: dict[int, Show] = field(default_factory=dict)
    commands: dict[str, dict[int, BodyCommand]] = field(default_factory=dict)
    episodes: list[Episode] = field(default_factory=list)


def _fmt(value: float | str) -> str:
    return value if isinstance(value, str) else f"{value:.6g}"


def _player_pattern(side: str, unum: int) -> re.Pattern[str]:
    return re.compile(
        r"\(\(" + side + " " + str(unum) + r"\) \d+ (0x[0-9a-f]+|\d+) " + " ".join([_NUMBER] * 6) + r"[ )]"
    )


def parse_rcg(path: Path, players: tuple[tuple[str, int], ...] = (("l", 11), ("r", 1))) -> dict[int, Show]:
    """The ``show`` lines of a game log, keeping only ``players`` (default: HFO's agent l11 and goalie r1)."""
    patterns = {key: _player_pattern(*key) for key in players}
    shows: dict[int, Show] = {}
    with open(path, encoding="ascii", errors="replace") as handle:
        for line in handle:
            match = _SHOW.match(line)
            if match is None:
                continue
            time = int(match.group(1))
            ball_match = _BALL.search(line)
            if ball_match is None:
                continue
            ball = tuple(float(v) for v in ball_match.groups())
            found: dict[tuple[str, int], PlayerShow] = {}
            for key, pattern in patterns.items():
                m = pattern.search(line)
                if m is None:
                    continue
                state = int(m.group(1), 16) if m.group(1).startswith("0x") else int(m.group(1))
                x, y, vx, vy, body, neck = (float(v) for v in m.groups()[1:])
                found[key] = PlayerShow(x, y, vx, vy, body, neck, state)
            shows[time] = Show(time, ball, found)  # type: ignore[arg-type]
    return shows


def parse_commands(text: str) -> list[BodyCommand]:
    """All commands of one client message, e.g. ``(dash 100 -45)(turn_neck 0)(done)``, body or not."""
    commands = []
    for name, raw in _COMMAND.findall(text):
        args: list[float | str] = []
        for token in raw.split():
            try:
                args.append(float(token))
            except ValueError:
                args.append(token)
        commands.append(BodyCommand(name, tuple(args)))
    return commands


def parse_rcl(
    path: Path, clients: tuple[str, ...] = ("base_left_11", "base_right_1")
) -> dict[str, dict[int, BodyCommand]]:
    """The body command each of ``clients`` sent per cycle (the first one of the cycle; None-free dict)."""
    result: dict[str, dict[int, BodyCommand]] = {client: {} for client in clients}
    with open(path, encoding="ascii", errors="replace") as handle:
        for line in handle:
            match = _RECV.match(line.rstrip("\n"))
            if match is None or match.group(2) not in result:
                continue
            time = int(match.group(1))
            per_time = result[match.group(2)]
            if time in per_time:
                continue
            for command in parse_commands(match.group(3)):
                if command.name in BODY_COMMANDS:
                    per_time[time] = command
                    break
    return result


def parse_hfo(path: Path) -> list[Episode]:
    """HFO's episode log: one :class:`Episode` per line; the result without its ``-unum`` suffix."""
    episodes = []
    with open(path, encoding="ascii", errors="replace") as handle:
        for line in handle:
            if line.startswith("#") or not line.strip():
                continue
            number, start, end, _, result = line.rstrip("\n").split("\t")[:5]
            episodes.append(Episode(int(number), int(start), int(end), result.split("-")[0]))
    return episodes


@dataclass(frozen=True)
class FullstatePlayer:
    """A player of a fullstate message, in the server's (left-team) frame, as printed."""

    x: float
    y: float
    vx: float
    vy: float
    body: float
    neck: float
    stamina: float
    effort: float
    recovery: float
    flags: str  # "t" tackling, "k" kicked, "f" charged (fullstate v13+), "" else


@dataclass(frozen=True)
class ClientCycle:
    """What a client knew when it decided in cycle ``time`` (at its ``(think)``), from its offline log."""

    time: int
    ball: tuple[float, float, float, float]
    players: dict[tuple[str, int], FullstatePlayer]
    tackle_expires: int  # sense_body (tackle (expires N)): cycles the client stays frozen by its own tackle
    mode: str  # the last play-mode message heard (referee): "play_on", "goalie_catch_ball_r", ...
    mode_changed: bool  # a play-mode message changed the mode since the previous decision
    referee: tuple[str, ...]  # the referee messages heard since the previous decision


_FS_HEAD = re.compile(r"^\(fullstate (\d+) ")
_FS_PLAYER = re.compile(
    r"\(\(p ([lr]) (\d+)(?: g)? \d+\) "
    + " ".join([_NUMBER] * 6)
    + r"(?: [-0-9.e+]+ [-0-9.e+]+)? \(stamina "
    + " ".join([_NUMBER] * 3)
    + r"(?: [-0-9.e+]+)?\)((?: [tkfyr])*)\)"
)
_SENSE_HEAD = re.compile(r"^\(sense_body (\d+) ")
_TACKLE_EXPIRES = re.compile(r"\(tackle \(expires (\d+)\)")
_HEAR_REFEREE = re.compile(r"^\(hear (\d+) referee ([^)\s]+)\)")
# referee messages that set a play mode in librcsc (the others, such as HFO's IN_GAME-L11, set none)
PLAY_MODES = ("play_on", "before_kick_off", "goalie_catch_ball_l", "goalie_catch_ball_r", "time_over")


def parse_fullstate(
    line: str,
) -> tuple[int, tuple[float, float, float, float], dict[tuple[str, int], FullstatePlayer]]:
    """One ``(fullstate T ...)`` line: its time, the ball and the players."""
    head = _FS_HEAD.match(line)
    if head is None:
        raise ValueError(f"not a fullstate message: {line[:40]!r}")
    ball_match = _BALL.search(line)
    if ball_match is None:
        raise ValueError(f"fullstate without a ball: {line[:80]!r}")
    ball = tuple(float(v) for v in ball_match.groups())
    players = {}
    for m in _FS_PLAYER.finditer(line):
        side, unum = m.group(1), int(m.group(2))
        values = [float(v) for v in m.groups()[2:11]]
        players[(side, unum)] = FullstatePlayer(*values, flags=m.group(12).replace(" ", ""))
    return int(head.group(1)), ball, players  # type: ignore[return-value]


def parse_client_log(path: Path) -> dict[int, ClientCycle]:
    """A client's offline log (.ocl): what it knew at each of its decisions, by cycle."""
    cycles: dict[int, ClientCycle] = {}
    fullstate: (
        tuple[int, tuple[float, float, float, float], dict[tuple[str, int], FullstatePlayer]] | None
    ) = None
    tackle_expires = 0
    mode = ""
    changed = False
    referee: list[str] = []
    with open(path, encoding="ascii", errors="replace") as handle:
        for line in handle:
            if line.startswith("(fullstate "):
                try:
                    fullstate = parse_fullstate(line)
                except ValueError:
                    fullstate = None  # a line cut short by the end of the log
            elif line.startswith("(sense_body "):
                m = _TACKLE_EXPIRES.search(line)
                tackle_expires = int(m.group(1)) if m else 0
            elif line.startswith("(hear "):
                m = _HEAR_REFEREE.match(line)
                if m is not None:
                    referee.append(m.group(2))
                    if m.group(2) in PLAY_MODES:
                        changed = changed or m.group(2) != mode
                        mode = m.group(2)
            elif line.startswith("(think)") and fullstate is not None:
                time, ball, players = fullstate
                cycles[time] = ClientCycle(time, ball, players, tackle_expires, mode, changed, tuple(referee))
                changed = False
                referee = []
    return cycles


def read_logs(log_dir: Path) -> GameLogs:
    """The .rcg, .rcl and .hfo files of one session's log directory (exactly one of each)."""
    found = {}
    for suffix in (".rcg", ".rcl", ".hfo"):
        files = sorted(log_dir.glob("*" + suffix))
        if len(files) != 1:
            raise FileNotFoundError(
                f"expected one {suffix} file in {log_dir}, found {[f.name for f in files]}"
            )
        found[suffix] = files[0]
    return GameLogs(
        shows=parse_rcg(found[".rcg"]), commands=parse_rcl(found[".rcl"]), episodes=parse_hfo(found[".hfo"])
    )
