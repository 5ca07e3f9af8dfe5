"""How exactly hfo2d's field defenders (:class:`hfo2d.agent2d.defender.Agent2dDefender`) decide as HFO's agent2d
field defenders do, on the real players' own inputs.

Two steps; the first needs a real HFO build and a loopback-only network namespace, the second only the logs::

    HOME=/root HFO_DIR=/root/real_hfo/HFO tools/real_hfo/loopback.sh \\
        python benchmarks/defender_fidelity.py run --work-dir /tmp/dfid --defense-npcs 2 --trials 100 --deterministic
    python benchmarks/defender_fidelity.py replay /tmp/dfid/logs_d2_det_s7 --out replay.json

``run`` starts ``bin/HFO --headless --fullstate --offense-npcs O --defense-npcs N --frames-per-trial 500
--untouched-time 100 --seed S [--deterministic]`` from a copy of the build whose base team writes librcsc's
offline client logs (``keeper_fidelity.client_logging_hfo``: every NPC records the messages it receives in
``LOG_DIR/base_right-U.ocl``). The offense is agent2d's own offense NPC (unum 11, then 7, 8, ...), so no
learning agent is needed and the defenders meet dribbles, passes and shots. The defence is the goalie (unum 1)
and field players 2 .. N.

``replay`` rebuilds, for every field defender U and every cycle of its client log, the world the client saw
(its fullstate message: every player and the ball to 6 significant digits, its own tackle freeze from
``sense_body``, the play mode from the referee messages), lets one :class:`Agent2dDefender` per unum decide on
it (carrying the client state from cycle to cycle: the defence line, the recover flag, GoalieCatch mode), and
compares the command it would send with the one the real client sent (the ``.rcl``'s ``Recv base_right_U``
line of that cycle): same kind and numbers within 1e-3 relative or the absolute tolerance of
``keeper_fidelity.commands_agree``. Physics plays no part. Rows are grouped by the port's branch
(``Agent2dDefender.last_branch``); the on-ball branches (``hold``, ``force_kick``) are this port's stand-in for
agent2d's action-chain planner and are expected to differ.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
from collections import Counter, defaultdict
from contextlib import suppress
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import keeper_fidelity  # noqa: E402  (benchmarks/ is not a package)
import real_hfo_logs  # noqa: E402

FRAMES_PER_TRIAL = 500
UNTOUCHED_TIME = 100


class _Player:
    """A player of a fullstate message with PlayerState's attributes (the server's frame, as printed)."""

    def __init__(self, side: str, unum: int, fs: real_hfo_logs.FullstatePlayer, tackle_cycles: int) -> None:
        self.side, self.unum = side, unum
        self.goalie = side == "r" and unum == 1
        self.x, self.y, self.vx, self.vy = fs.x, fs.y, fs.vx, fs.vy
        self.body_deg = fs.body
        self.stamina, self.effort, self.recovery = fs.stamina, fs.effort, fs.recovery
        self.tackle_cycles = tackle_cycles


class _World:
    """The World interface Agent2dDefender reads and commands, holding one fullstate message."""

    def __init__(
        self,
        cycle: real_hfo_logs.ClientCycle,
        params: Any,
        noise: bool,
        me: tuple[str, int],
        frozen: dict[tuple[str, int], int],
    ) -> None:
        self.cycle = cycle.time
        bx, by, bvx, bvy = cycle.ball
        self.ball = type("Ball", (), {"x": bx, "y": by, "vx": bvx, "vy": bvy})()
        self.players = []
        for key, fs in sorted(cycle.players.items()):
            tackle = cycle.tackle_expires if key == me else frozen.get(key, 0)
            self.players.append(_Player(key[0], key[1], fs, tackle))
        self.me = next(p for p in self.players if (p.side, p.unum) == me)
        self.params = params
        self.noise = noise
        self.sent: tuple[str, tuple[float, ...]] | None = None

    def turn(self, _p: Any, moment: float) -> None:
        self.sent = ("turn", (moment,))

    def dash(self, _p: Any, power: float, direction: float = 0.0) -> None:
        self.sent = ("dash", (power, direction))

    def kick(self, _p: Any, power: float, direction: float) -> None:
        self.sent = ("kick", (power, direction))

    def tackle(self, _p: Any, direction: float, foul: bool = False) -> None:
        self.sent = ("tackle", (direction, "on" if foul else "off"))


def _tackle_freezes(
    history: dict[tuple[str, int], int], players: dict[tuple[str, int], real_hfo_logs.FullstatePlayer]
) -> dict[tuple[str, int], int]:
    """The remaining tackle freeze of every other player: a fullstate "t" flag first seen shows a freeze of
    tackle_cycles - 1 = 9 (rcssserver), one less each later cycle with the flag."""
    out: dict[tuple[str, int], int] = {}
    for key, fs in players.items():
        if "t" in fs.flags:
            out[key] = history[key] - 1 if history.get(key, 0) > 1 else 9
    history.clear()
    history.update(out)
    return out


def _agree(real: real_hfo_logs.BodyCommand | None, sim: tuple[str, tuple[Any, ...]] | None) -> bool:
    if sim is not None and sim[0] == "tackle":
        # the foul flag is compared as a word; the direction with the usual tolerance
        if real is None or real.name != "tackle":
            return False
        real_foul = real.args[1] if len(real.args) > 1 else "off"
        if real_foul != sim[1][1]:
            return False
        return keeper_fidelity.commands_agree(
            real_hfo_logs.BodyCommand("tackle", real.args[:1]), ("tackle", (float(sim[1][0]),))
        )
    return keeper_fidelity.commands_agree(real, sim)


def _text(sim: tuple[str, tuple[Any, ...]] | None) -> str:
    if sim is not None and sim[0] == "tackle":
        return f"(tackle {float(sim[1][0]):.6g} {sim[1][1]})"
    return keeper_fidelity.command_text(sim)


def replay_defender(
    logs: real_hfo_logs.GameLogs,
    client: dict[int, real_hfo_logs.ClientCycle],
    unum: int,
    noise: bool,
    snapshots: dict[int, Any] | None = None,
) -> list[dict[str, Any]]:
    """One row per cycle of field defender ``unum`` inside an HFO episode: its real command and hfo2d's.
    ``snapshots``, if given, receives a copy of the defender (its carried client state) at every episode start,
    before that cycle's decision."""
    import copy

    from hfo2d.agent2d.defender import Agent2dDefender
    from hfo2d.physics import ServerParams

    params = ServerParams()
    defender = Agent2dDefender(params, np.random.default_rng(0), unum=unum)
    starts = {e.start for e in logs.episodes}
    episode_of: dict[int, real_hfo_logs.Episode] = {}
    for e in logs.episodes:
        for t in range(e.start, e.end + 1):
            episode_of[t] = e
    commands = logs.commands.get(f"base_right_{unum}", {})
    history: dict[tuple[str, int], int] = {}
    rows: list[dict[str, Any]] = []
    started = False
    for t in sorted(client):
        cycle = client[t]
        frozen = _tackle_freezes(history, cycle.players)
        started = started or cycle.mode == "play_on"
        if not started or ("r", unum) not in cycle.players:
            continue
        if t in starts:
            defender.reset()
            if snapshots is not None:
                snapshots[t] = copy.deepcopy(defender)
        if cycle.mode_changed and cycle.mode == "goalie_catch_ball_r":
            defender.goalie_caught()
        world = _World(cycle, params, noise, ("r", unum), frozen)
        defender.apply(world, world.me, defender.decide(world, world.me))
        episode = episode_of.get(t)
        if episode is None:
            continue
        real = commands.get(t)
        sim = world.sent
        real_text = real.text() if real else "(none)"
        agree = _agree(real, sim)
        rows.append(
            {
                "unum": unum,
                "cycle": t,
                "episode": episode.number,
                "k": t - episode.start,
                "branch": defender.last_branch,
                "real": real_text,
                "sim": _text(sim),
                "agree": agree,
                "exact": agree and (real_text == _text(sim) or (real is None and sim == ("turn", (0.0,)))),
            }
        )
    return rows


def _cause(row: dict[str, Any], kicks: set[int], catches: set[int]) -> str | None:
    """Why a cycle's commands differ, as far as the logs tell (None: they agree)."""
    if row["agree"]:
        return None
    if row["branch"] in ("hold", "force_kick"):
        return "on the ball (this port's hold stand-in for agent2d's action chain)"
    if any(t in kicks for t in range(row["cycle"] - ON_BALL_AFTERMATH, row["cycle"])):
        return f"within {ON_BALL_AFTERMATH} cycles of a real field defender's kick (queued intentions, heard pass)"
    if row["cycle"] in catches:
        return "in the cycle of the goalie's catch command (nothing in the fullstate tells it yet)"
    real, sim = row["real"].split(), row["sim"].split()
    if (
        real[0] == sim[0] == "(turn"
        and abs(abs(float(real[1].rstrip(")"))) - 180.0) < 0.5
        and abs(abs(float(sim[1].rstrip(")"))) - 180.0) < 0.5
    ):
        return "a turn by 180 degrees either way (a tie)"
    return "other"


ON_BALL_AFTERMATH = 10


def field_defenders(log_dir: Path) -> list[int]:
    """The unums of the field defenders that played a session: HFO starts all 11 NPCs of a team and sends the
    unwanted ones away before play, so only the players' client logs (.ocl) hold the referee's play_on."""
    found = []
    for path in sorted(log_dir.glob("base_right-*.ocl"), key=lambda p: int(p.stem.split("-")[1])):
        unum = int(path.stem.split("-")[1])
        if unum != 1 and "referee play_on)" in path.read_text(encoding="ascii", errors="replace"):
            found.append(unum)
    return found


def cmd_replay(args: argparse.Namespace) -> dict[str, Any]:
    sessions = []
    all_rows: list[dict[str, Any]] = []
    for log_dir in map(Path, args.log_dirs):
        logs = real_hfo_logs.read_logs(log_dir)
        unums = field_defenders(log_dir)
        clients = tuple(f"base_right_{u}" for u in unums)
        logs.commands = real_hfo_logs.parse_rcl(next(log_dir.glob("*.rcl")), (*clients, "base_right_1"))
        noise = not (log_dir / "deterministic").exists()
        catches = {t for t, cmd in logs.commands["base_right_1"].items() if cmd.name == "catch"}
        # cycles in which a real field defender kicked: agent2d's on-ball play queues intentions (dribble turns and
        # dashes, turn to forward) and says pass messages that its teammates act on in the next cycles
        kicks = {t for c in clients for t, cmd in logs.commands[c].items() if cmd.name == "kick"}
        for unum in unums:
            client = real_hfo_logs.parse_client_log(log_dir / f"base_right-{unum}.ocl")
            rows = replay_defender(logs, client, unum, noise)
            for row in rows:
                row["session"] = log_dir.name
                row["cause"] = _cause(row, kicks, catches)
            all_rows.extend(rows)
            if not rows:
                continue  # an NPC that HFO sent away before play (it may have sent commands before kick-off)
            sessions.append(
                {
                    "session": log_dir.name,
                    "noise": noise,
                    "unum": unum,
                    "cycles": len(rows),
                    "agree": sum(r["agree"] for r in rows),
                    "exact": sum(r["exact"] for r in rows),
                }
            )
    by_branch: dict[str, list[int]] = defaultdict(lambda: [0, 0])
    for r in all_rows:
        by_branch[r["branch"]][0] += 1
        by_branch[r["branch"]][1] += r["agree"]
    mismatches = [r for r in all_rows if not r["agree"]]
    kinds = Counter(f"{r['branch']}: {r['real'].split()[0]}) | {r['sim'].split()[0]})" for r in mismatches)
    n = len(all_rows)
    agree = sum(r["agree"] for r in all_rows)
    print(
        "\nhfo2d's field defenders on the real defenders' own fullstate inputs (no physics), cycle by cycle"
    )
    print(f"{'session':<22}{'noise':>6}{'unum':>5}{'cycles':>8}{'agree':>8}{'rate':>9}{'exact':>8}")
    for s in sessions:
        rate = s["agree"] / max(1, s["cycles"])
        print(
            f"{s['session']:<22}{'on' if s['noise'] else 'off':>6}{s['unum']:>5}{s['cycles']:>8}{s['agree']:>8}"
            f"{rate:>9.2%}{s['exact']:>8}"
        )
    print(f"all: {agree}/{n} cycles agree ({agree / max(1, n):.2%})")
    print(f"\n{'port branch':<16}{'cycles':>8}{'agree':>8}{'rate':>9}")
    for branch, (count, ok) in sorted(by_branch.items(), key=lambda item: -item[1][0]):
        print(f"{branch:<16}{count:>8}{ok:>8}{ok / max(1, count):>9.2%}")
    causes = Counter(r["cause"] for r in mismatches)
    print("\nmismatches by cause:")
    for cause, count in causes.most_common():
        print(f"  {count:>6}  {cause}")
    print("\nmismatches by branch and kind (real | hfo2d):")
    for kind, count in kinds.most_common():
        print(f"  {count:>6}  {kind}")
    for r in [r for r in mismatches if r["cause"] == "other"][: args.show]:
        print(
            f"  {r['session']} u{r['unum']} cycle {r['cycle']:>5} ep {r['episode']:>3} k {r['k']:>3} "
            f"[{r['branch']}]: {r['real']} | {r['sim']}"
        )
    result = {
        "summary": {
            "cycles": n,
            "agree": agree,
            "by_branch": dict(by_branch),
            "kinds": dict(kinds),
            "causes": dict(causes),
        },
        "sessions": sessions,
        "mismatches": mismatches,
    }
    if args.out:
        Path(args.out).write_text(json.dumps(result, indent=1))
    return result


def trajectory_episode(
    logs: real_hfo_logs.GameLogs,
    start_state: real_hfo_logs.ClientCycle,
    episode: real_hfo_logs.Episode,
    defenders: dict[int, Any],
    tol: float,
    frozen: dict[tuple[str, int], int] | None = None,
) -> dict[str, Any]:
    """Replay one episode of a ``--deterministic`` session in hfo2d (noise off) from the reset state of a
    defender's fullstate message: hfo2d's goalie and field defenders decide and move; every offense NPC is fed
    its logged commands. Reports, per object, the first cycle its position is more than ``tol`` from the game
    log, and each defender's first command that differs from the real one. ``frozen``: each player's tackle
    freeze at the reset (rcssserver's placement keeps it), from its own client log."""
    from hfo2d.agent2d.goalie import Agent2dGoalie
    from hfo2d.physics import ServerParams, World

    params = ServerParams()
    world = World(params, np.random.default_rng(0), noise=False)
    players = {}
    for (side, unum), fs in sorted(start_state.players.items()):  # server slot order: left, then right
        p = world.add_player(side, unum, goalie=(side == "r" and unum == 1))
        world.place_player(p, fs.x, fs.y, fs.body, fs.vx, fs.vy)
        p.stamina, p.effort, p.recovery = fs.stamina, fs.effort, fs.recovery
        p.tackle_cycles = (frozen or {}).get((side, unum), 0)
        players[(side, unum)] = p
    world.place_ball(*start_state.ball)
    goalie = Agent2dGoalie(params, np.random.default_rng(0))
    goalie.reset()
    for d in defenders.values():
        d.reset()
    first_div: dict[str, int | None] = {f"{side}{unum}": None for side, unum in players}
    first_div["ball"] = None
    first_cmd: dict[int, dict[str, Any] | None] = {u: None for u in defenders}
    length = episode.end - episode.start
    for k in range(length):
        t = episode.start + k
        decisions = {}
        if ("r", 1) in players:
            goalie.decide(world, players[("r", 1)])
        for u, d in defenders.items():
            decisions[u] = d.decide(world, players[("r", u)])
        for (side, unum), p in players.items():
            if side != "l":
                continue
            cmd = logs.commands.get(f"base_left_{unum}", {}).get(t)
            if cmd is None:
                continue
            args = [float(a) for a in cmd.args if not isinstance(a, str)]
            if cmd.name == "dash":
                world.dash(p, args[0], args[1] if len(args) > 1 else 0.0)
            elif cmd.name == "turn":
                world.turn(p, args[0])
            elif cmd.name == "kick":
                world.kick(p, args[0], args[1])
            elif cmd.name == "tackle":
                world.tackle(p, args[0], len(cmd.args) > 1 and cmd.args[1] == "on")
        if ("r", 1) in players:
            goalie.apply(world, players[("r", 1)])
        for u, d in defenders.items():
            stub = _Recorder(world)
            d.apply(stub, players[("r", u)])
            real = logs.commands.get(f"base_right_{u}", {}).get(t)
            if first_cmd[u] is None and not _agree(real, stub.sent):
                first_cmd[u] = {
                    "k": k,
                    "branch": d.last_branch,
                    "real": real.text() if real else "(none)",
                    "sim": _text(stub.sent),
                }
        world.step()
        show = logs.shows.get(t + 1)
        if show is None:
            break
        for (side, unum), p in players.items():
            key = f"{side}{unum}"
            real_p = show.players.get((side, unum))
            if (
                first_div[key] is None
                and real_p is not None
                and math.hypot(p.x - real_p.x, p.y - real_p.y) > tol
            ):
                first_div[key] = k + 1
        if (
            first_div["ball"] is None
            and math.hypot(world.ball.x - show.ball[0], world.ball.y - show.ball[1]) > tol
        ):
            first_div["ball"] = k + 1
    return {"episode": episode.number, "length": length, "first_div": first_div, "first_cmd": first_cmd}


class _Recorder:
    """Passes a defender's command on to the world and keeps it (as _World.sent)."""

    def __init__(self, world: Any) -> None:
        self.world = world
        self.sent: tuple[str, tuple[Any, ...]] | None = None

    def turn(self, p: Any, moment: float) -> None:
        self.sent = ("turn", (moment,))
        self.world.turn(p, moment)

    def dash(self, p: Any, power: float, direction: float = 0.0) -> None:
        self.sent = ("dash", (power, direction))
        self.world.dash(p, power, direction)

    def kick(self, p: Any, power: float, direction: float) -> None:
        self.sent = ("kick", (power, direction))
        self.world.kick(p, power, direction)

    def tackle(self, p: Any, direction: float, foul: bool = False) -> None:
        self.sent = ("tackle", (direction, "on" if foul else "off"))
        self.world.tackle(p, direction, foul)


def cmd_trajectories(args: argparse.Namespace) -> dict[str, Any]:
    import copy

    results = []
    for log_dir in map(Path, args.log_dirs):
        if not (log_dir / "deterministic").exists():
            raise SystemExit(f"defender_fidelity: {log_dir} is not a --deterministic session")
        rcg = next(log_dir.glob("*.rcg"))
        logs = real_hfo_logs.read_logs(log_dir)
        keys = [(s, u) for s in ("l", "r") for u in range(1, 12)]
        logs.shows = real_hfo_logs.parse_rcg(rcg, tuple(keys))
        unums = field_defenders(log_dir)
        clients = tuple(f"base_right_{u}" for u in [1, *unums]) + tuple(
            f"base_left_{u}" for u in range(1, 12)
        )
        logs.commands = real_hfo_logs.parse_rcl(next(log_dir.glob("*.rcl")), clients)
        snapshots: dict[int, dict[int, Any]] = defaultdict(dict)
        client_logs = {}
        # every NPC's own client log, for its tackle freeze (sense_body) at each reset
        freezes: dict[int, dict[tuple[str, int], int]] = defaultdict(dict)
        starts = {e.start for e in logs.episodes}
        for path in log_dir.glob("base_*.ocl"):
            side = "l" if path.name.startswith("base_left") else "r"
            unum = int(path.stem.split("-")[1])
            if not logs.commands.get(f"base_{'left' if side == 'l' else 'right'}_{unum}"):
                continue  # not a player of the session
            for t, cycle in real_hfo_logs.parse_client_log(path).items():
                if t in starts and cycle.tackle_expires > 0:
                    freezes[t][(side, unum)] = cycle.tackle_expires
        for unum in unums:
            client_logs[unum] = real_hfo_logs.parse_client_log(log_dir / f"base_right-{unum}.ocl")
            per_unum: dict[int, Any] = {}
            replay_defender(logs, client_logs[unum], unum, False, per_unum)
            for t, d in per_unum.items():
                snapshots[t][unum] = d
        for episode in logs.episodes:
            if episode.number < 2 or episode.start not in snapshots or episode.end - episode.start < 2:
                continue
            start_state = client_logs[unums[0]].get(episode.start)
            if start_state is None or len(snapshots[episode.start]) != len(unums):
                continue
            defenders = {u: copy.deepcopy(d) for u, d in snapshots[episode.start].items()}
            row = trajectory_episode(logs, start_state, episode, defenders, args.tol, freezes[episode.start])
            row["session"] = log_dir.name
            results.append(row)
            if args.episodes and len(results) >= args.episodes:
                break
    _print_trajectories(results, args.tol)
    if args.out:
        Path(args.out).write_text(json.dumps(results, indent=1))
    return {"episodes": results}


def _print_trajectories(results: list[dict[str, Any]], tol: float) -> None:
    print(f"\nnoise-off trajectories from the logged resets (position tolerance {tol} m)")
    if not results:
        print("no episode")
        return
    keys = sorted({key for r in results for key in r["first_div"]})
    print(f"{'object':<8}{'episodes':>9}{'exact to end':>14}{'median first div (cycles)':>28}")
    for key in keys:
        values = [r["first_div"][key] for r in results if key in r["first_div"]]
        exact = sum(v is None for v in values)
        divs = sorted(v for v in values if v is not None)
        median = divs[len(divs) // 2] if divs else None
        print(f"{key:<8}{len(values):>9}{exact:>14}{median if median is not None else '-':>28}")
    # a defender's first divergence: did the ball (or an attacker fed open-loop) diverge first?
    causes: Counter[str] = Counter()
    for r in results:
        fd = r["first_div"]
        for key, v in fd.items():
            if not key.startswith("r") or key == "r1" or v is None:
                continue
            others = [fd[o] for o in fd if o != key and fd[o] is not None and fd[o] <= v]
            causes["after the ball, an attacker or the goalie" if others else "defender first"] += 1
    print(f"defender divergences: {dict(causes)}")
    # a defender's first command mismatch: on the logged state (nothing diverged yet), or after a divergence
    on_state: Counter[str] = Counter()
    after: Counter[str] = Counter()
    for r in results:
        for m in r["first_cmd"].values():
            if m is None:
                continue
            diverged = any(v is not None and v <= m["k"] for v in r["first_div"].values())
            (after if diverged else on_state)[m["branch"]] += 1
    print(
        "first command mismatch per defender and episode, by the port's branch: "
        f"on the logged state {dict(on_state)}; after a divergence {dict(after)}"
    )
    for r in results:
        for u, m in r["first_cmd"].items():
            if m is not None and not any(v is not None and v <= m["k"] for v in r["first_div"].values()):
                print(
                    f"  {r['session']} ep {r['episode']} u{u} k {m['k']} [{m['branch']}]: {m['real']} | {m['sim']}"
                )


def cmd_run(args: argparse.Namespace) -> None:
    keeper_fidelity.check_network_namespace()
    hfo_dir = keeper_fidelity.hfo_dir_of(args.hfo_dir)
    work = Path(args.work_dir)
    work.mkdir(parents=True, exist_ok=True)
    copy = keeper_fidelity.client_logging_hfo(hfo_dir, work)
    name = f"logs_d{args.defense_npcs}_{'det' if args.deterministic else 'noise'}_s{args.seed}"
    log_dir = work / name
    log_dir.mkdir(exist_ok=False)
    if args.deterministic:
        (log_dir / "deterministic").write_text("bin/HFO --deterministic\n")
    command = [
        sys.executable,
        str(copy / "bin" / "HFO"),
        "--headless",
        "--fullstate",
        "--offense-npcs",
        str(args.offense_npcs),
        "--defense-npcs",
        str(args.defense_npcs),
        "--trials",
        str(args.trials),
        "--frames-per-trial",
        str(FRAMES_PER_TRIAL),
        "--untouched-time",
        str(UNTOUCHED_TIME),
        "--seed",
        str(args.seed),
        "--port",
        str(args.port),
        "--log-dir",
        str(log_dir),
    ]
    if args.deterministic:
        command.append("--deterministic")
    with open(log_dir / "hfo.out", "w") as out:
        server = subprocess.Popen(
            command, stdout=out, stderr=subprocess.STDOUT, cwd=log_dir, start_new_session=True
        )
        try:
            server.wait(timeout=args.timeout)
        finally:
            if server.poll() is None:
                with suppress(ProcessLookupError):
                    os.killpg(server.pid, 9)
                server.wait()
    print(f"logs in {log_dir}")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="one real HFO session with client logs (needs HFO_DIR and loopback.sh)")
    run.add_argument("--hfo-dir", default=None)
    run.add_argument("--work-dir", required=True)
    run.add_argument("--offense-npcs", type=int, default=1)
    run.add_argument("--defense-npcs", type=int, default=2)
    run.add_argument("--trials", type=int, default=100)
    run.add_argument("--seed", type=int, default=7)
    run.add_argument("--port", type=int, default=6600)
    run.add_argument("--deterministic", action="store_true")
    run.add_argument("--timeout", type=float, default=1800.0)
    replay = sub.add_parser("replay", help="replay the field defenders of logged sessions in hfo2d")
    replay.add_argument("log_dirs", nargs="+")
    replay.add_argument("--out", default=None)
    replay.add_argument("--show", type=int, default=30, help='mismatches of cause "other" to print')
    traj = sub.add_parser("trajectories", help="noise-off trajectories of --deterministic sessions in hfo2d")
    traj.add_argument("log_dirs", nargs="+")
    traj.add_argument("--tol", type=float, default=1e-3)
    traj.add_argument("--episodes", type=int, default=0, help="at most this many episodes (0: all)")
    traj.add_argument("--out", default=None)
    return parser


def main(argv: list[str] | None = None) -> None:
    args = build_parser().parse_args(argv)
    if args.command == "run":
        cmd_run(args)
    elif args.command == "trajectories":
        cmd_trajectories(args)
    else:
        cmd_replay(args)


if __name__ == "__main__":
    main()
