"""How exactly hfo2d's goalie plays HFO's agent2d goalie, measured against a real HFO build.

Run it inside a loopback-only network namespace (the script refuses otherwise) with a real HFO build
(``--hfo-dir``, default ``$HFO_DIR``: the directory holding ``bin/HFO`` and ``hfo/hfo.py``)::

    tools/real_hfo/loopback.sh python benchmarks/keeper_fidelity.py deterministic --episodes 5 --out det.json
    tools/real_hfo/loopback.sh python benchmarks/keeper_fidelity.py noise --episodes 1000 --out noise.json
    tools/real_hfo/loopback.sh python benchmarks/keeper_fidelity.py shots --reps 7 --out shots.json

(``tools/real_hfo/loopback.sh``: ``unshare --net --pid --fork --mount-proc`` with only ``lo`` up.) Every real
session is one ``bin/HFO --offense-agents 1 --defense-npcs 1 --headless --fullstate --frames-per-trial 500
--untouched-time 100`` server, with this script's scripted striker (:mod:`hfo2d.strikers`) as the learning agent, each in its own process
(HFO's binding allows one ``connectToServer`` per process). The striker reads HFO master's 68 features converted
with :func:`hfo2d.features.paper_from_hfo`, and its flat action is sent as ``HFOEnv`` maps it (DASH power, dir;
TURN dir; KICK power, dir).

Subcommands (each writes ``--out`` JSON and prints a table):

``deterministic``
    Real HFO with ``--deterministic`` (no player, ball or kick noise) and game logging, each striker ``--episodes``
    episodes. The .rcg gives the true state per cycle, the .rcl the commands the agent (``base_left_11``) and the
    goalie (``base_right_1``) sent, the .hfo the episode boundaries and results. Each episode is then replayed in
    hfo2d (``noise=False``), started from the logged reset state (ball, agent with its body angle, goalie with
    its carried-over body angle), the agent fed its logged server commands as flat actions: turn
    ``desired = moment / (1 + inertia_moment * |v|)`` with hfo2d's current agent speed (``HFOEnv``'s TURN sends
    ``desired * (1 + 5 |v|)``), dash and kick with the logged power and direction, a cycle without a body command
    as a turn by 0. Reported per episode: whether the goalie's position stays within ``--tol`` (1e-3 m) of the
    log at every cycle both ran, the first cycle it does not, the first cycle whose goalie command differs (kind,
    or a number by more than 1e-3 relative and 0.005 absolute), the goalie's commands in both at those cycles, the end status and
    length in both, and what hfo2d's goalie policy exposes about that decision (``last_command``, ``last_view``).
    The agent's and the ball's first divergences are reported too, and each command mismatch says whether ball
    and agent still agreed within ``--tol`` when the goalie decided: a goalie difference after theirs is a
    consequence, not a cause. HFO's first episode is not replayed (the log has no ``show`` of its reset, cycle 0).
    HFO's own random start is logged rounded to 1e-4 m, which a kick amplifies to ~1e-3 m of ball error after
    20-30 cycles; ``--spots X,Y ...`` gives exact starts instead (the ball at X * 52.5, Y * 34, the agent on it,
    one session per striker and spot). ``--strikers aimed_shot --targets Y`` replays the identical shots.
``noise``
    Noise on, each striker ``--episodes`` episodes in real HFO (``--no-logging``) and in hfo2d: goal rate with a
    Wilson 95 % interval, end-status counts, the difference real - hfo2d and its standard error.
``shots``
    The identical-shot test: the striker starts on the ball (``--offense-on-ball 1``: HFO places it 0.1 m behind
    the ball) at 21, 15.75 and 10.5 m from the goal line, with the ball at y = -10.2, 0, +10.2 (each spot one
    session with ``--ball-x-min = --ball-x-max`` and ``--ball-y-min = --ball-y-max``), turns toward its target
    for 6 cycles and kicks at full power at (52.5, y) with y cycling through -5, 0, +5 by episode. Goal rates per
    spot, per distance and per target, both sides (``--deterministic``: noise off on both sides).

hfo2d's ``HFOEnv`` refuses hand placements that overlap, so an agent placed 0.1 m behind the ball (HFO's
``--offense-on-ball``) is put on the World right after the reset (:func:`reset_env`).

Timing rules that both sides follow (measured on this build, see the report of issue 23):

* after an episode ends, HFO's agent library takes three NOOPs (``turn 0``) before it returns the status
  (src/HFO.cpp ``HFOEnvironment::step``): one in the wait cycle, two in the next episode. The striker's first
  command of an episode therefore executes in the episode's third cycle. ``HFO/Keeper-v1`` plays those two
  cycles inside ``reset`` (``hfo_env.AGENT2D_FIRST_OBSERVATION_DELAY``: the goalie acts, the agent sends nothing),
  so the benchmark sends the striker's actions from the first step, replays the log from the placement plus that
  delay and compares the goalie's commands and positions of the delay cycles too (recorded by wrapping the
  World's methods during the reset); for ``HFO/Keeper-v0`` (no delay) it sends the two idle turns first
  (``LEAD_IDLE``). Lengths are cycles from the placement on both sides;
* HFO's first episode is special (the agent's first observation precedes the placement, the goalie's first body
  angle depends on its pre-kick-off scan turns); every real session plays one extra trial and drops the first.

The hfo2d goalie is ``--env-id`` (default ``HFO/Keeper-v1`` when it is registered and builds, else
``HFO/Keeper-v0``). Its server-level commands are recorded by wrapping the World's command methods for the goalie.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import os
import signal
import subprocess
import sys
import tempfile
import time
from collections import Counter
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager, suppress
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import real_hfo_logs  # noqa: E402  (the helper module next to this script)

import hfo2d  # noqa: E402, F401  (registers the HFO/* ids)
from hfo2d.features import paper_from_hfo  # noqa: E402
from hfo2d.strikers import STRIKERS, Striker, make_striker  # noqa: E402

STATUSES = ("GOAL", "CAPTURED_BY_DEFENSE", "OUT_OF_BOUNDS", "OUT_OF_TIME")
# HFO's hfo.py status codes: IN_GAME, GOAL, CAPTURED_BY_DEFENSE, OUT_OF_BOUNDS, OUT_OF_TIME, SERVER_DOWN
HFO_STATUS_NAMES = ("IN_GAME", "GOAL", "CAPTURED_BY_DEFENSE", "OUT_OF_BOUNDS", "OUT_OF_TIME", "SERVER_DOWN")
LEAD_IDLE = 2  # HFO src/HFO.cpp step(): three NOOPs after a terminal status, the last two in the new episode
FRAMES_PER_TRIAL = 500
UNTOUCHED_TIME = 100
DEFAULT_TOL = 1e-3  # m
COMMAND_REL_TOL = 1e-3
COMMAND_ABS_TOL = (
    5e-3  # degrees or power units: the log prints 6 significant digits, a 0.001-degree turn is noise
)
SHOT_DISTANCES = (21.0, 15.75, 10.5)  # m from the goal line
SHOT_BALL_YS = (-10.2, 0.0, 10.2)  # m (0.3 of the half width)
SHOT_TARGETS = (-5.0, 0.0, 5.0)  # m on the goal line
AIM_CYCLES = 6
HALF_LENGTH = 52.5
HALF_WIDTH = 34.0
CONFIG_DIR = "bin/teams/base/config/formations-dt"
Z95 = 1.959963984540054


# ---------------------------------------------------------------------------------------------------------------
# Statistics
# ---------------------------------------------------------------------------------------------------------------
def wilson(successes: int, n: int, z: float = Z95) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion (0, 1 for n = 0)."""
    if n == 0:
        return 0.0, 1.0
    p = successes / n
    denominator = 1.0 + z * z / n
    centre = (p + z * z / (2 * n)) / denominator
    half = z * math.sqrt(p * (1.0 - p) / n + z * z / (4 * n * n)) / denominator
    return max(0.0, centre - half), min(1.0, centre + half)


def rate_summary(statuses: Sequence[str]) -> dict[str, Any]:
    n = len(statuses)
    goals = sum(status == "GOAL" for status in statuses)
    low, high = wilson(goals, n)
    return {
        "n": n,
        "goals": goals,
        "rate": goals / n if n else math.nan,
        "wilson95": [low, high],
        "statuses": dict(Counter(statuses)),
    }


def difference(real: dict[str, Any], sim: dict[str, Any]) -> dict[str, float]:
    """real - sim goal rate and its standard error (independent binomials)."""
    p1, n1, p2, n2 = real["rate"], real["n"], sim["rate"], sim["n"]
    if not n1 or not n2:
        return {"diff": math.nan, "se": math.nan}
    return {"diff": p1 - p2, "se": math.sqrt(p1 * (1 - p1) / n1 + p2 * (1 - p2) / n2)}


# ---------------------------------------------------------------------------------------------------------------
# Real HFO sessions
# ---------------------------------------------------------------------------------------------------------------
def check_network_namespace() -> None:
    """Refuse to start servers unless loopback is the only network interface (``tools/real_hfo/loopback.sh``)."""
    with open("/proc/net/dev", encoding="ascii") as handle:  # the reading process's own network namespace
        interfaces = sorted(line.split(":")[0].strip() for line in handle if ":" in line)
    if interfaces != ["lo"]:
        raise SystemExit(
            f"keeper_fidelity: network interfaces {interfaces}; run this inside a loopback-only network namespace "
            "(e.g. with the repository's runner: tools/real_hfo/loopback.sh python benchmarks/keeper_fidelity.py ...)"
        )


def hfo_dir_of(arg: str | None) -> Path:
    path = Path(arg or os.environ.get("HFO_DIR", ""))
    if not arg and not os.environ.get("HFO_DIR"):
        raise SystemExit("keeper_fidelity: pass --hfo-dir or set HFO_DIR to a real HFO build")
    for needed in ("bin/HFO", "hfo/hfo.py", "hfo/libhfo_c.so", "bin/rcssserver"):
        if not (path / needed).exists():
            raise SystemExit(f"keeper_fidelity: {path / needed} is missing; is {path} a built HFO?")
    return path


@dataclass
class SessionConfig:
    """One real HFO server session and the striker that plays it."""

    hfo_dir: str
    port: int
    trials: int
    seed: int
    striker: str
    deterministic: bool = False
    logging: bool = False
    log_dir: str = ""
    ball_x: tuple[float, float] | None = None  # fractions of the half length, HFO's --ball-x-min/max
    ball_y: tuple[float, float] | None = None  # fractions of the half width
    offense_on_ball: bool = False
    targets: tuple[float, ...] = ()  # aimed_shot: target y by episode (cycled; episode 1 excluded)
    result_path: str = ""


# bin/HFO's Trainer prints this once the NPCs it needs are up and the agent's slot is free (bin/Trainer.py)
AGENT_WAIT_LINE = "Waiting for player-controlled agent"


def run_real_session(config: SessionConfig, timeout_s: float) -> dict[str, Any]:
    """Start bin/HFO, play ``config.trials`` trials with the striker in a child process, stop everything."""
    hfo_dir = Path(config.hfo_dir)
    command = [
        sys.executable,
        str(hfo_dir / "bin" / "HFO"),
        "--offense-agents",
        "1",
        "--defense-npcs",
        "1",
        "--headless",
        "--fullstate",
        "--frames-per-trial",
        str(FRAMES_PER_TRIAL),
        "--untouched-time",
        str(UNTOUCHED_TIME),
        "--trials",
        str(config.trials),
        "--port",
        str(config.port),
        "--seed",
        str(config.seed),
    ]
    if config.deterministic:
        command.append("--deterministic")
    if config.logging:
        command += ["--log-dir", config.log_dir]
    else:
        command.append("--no-logging")
    if config.offense_on_ball:
        command += ["--offense-on-ball", "1"]
    if config.ball_x is not None:
        command += ["--ball-x-min", repr(config.ball_x[0]), "--ball-x-max", repr(config.ball_x[1])]
    if config.ball_y is not None:
        command += ["--ball-y-min", repr(config.ball_y[0]), "--ball-y-max", repr(config.ball_y[1])]
    work = Path(config.result_path).parent
    server_out = open(work / f"hfo_{config.port}.out", "w")  # noqa: SIM115  (closed below)
    server = subprocess.Popen(
        command,
        stdout=server_out,
        stderr=subprocess.STDOUT,
        start_new_session=True,
        env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )
    agent: subprocess.Popen[bytes] | None = None
    try:
        deadline = time.monotonic() + 60.0
        while AGENT_WAIT_LINE not in Path(server_out.name).read_text(errors="replace"):
            if server.poll() is not None or time.monotonic() > deadline:
                raise RuntimeError(f"bin/HFO did not start; see {server_out.name}")
            time.sleep(0.1)
        config_path = work / f"session_{config.port}.json"
        config_path.write_text(json.dumps(asdict(config)))
        agent_out = open(work / f"agent_{config.port}.out", "w")  # noqa: SIM115
        agent = subprocess.Popen(
            [sys.executable, str(Path(__file__).resolve()), "_agent", str(config_path)],
            stdout=agent_out,
            stderr=subprocess.STDOUT,
        )
        agent.wait(timeout=timeout_s)
        agent_out.close()
        if agent.returncode != 0:
            raise RuntimeError(f"agent process failed ({agent.returncode}); see {agent_out.name}")
        with suppress(subprocess.TimeoutExpired):  # bin/HFO ends by itself; it once hung in its clean-up
            server.wait(timeout=15.0)
    finally:
        if agent is not None and agent.poll() is None:
            agent.kill()
        with suppress(ProcessLookupError):
            os.killpg(server.pid, signal.SIGKILL)
        server.wait()
        server_out.close()
    return json.loads(Path(config.result_path).read_text())


def hfo_action(hfo: Any, flat: np.ndarray) -> tuple[int, tuple[float, ...]]:
    """HFO low-level action for a flat action, mapped as ``HFOEnv`` maps it (ties: DASH, then TURN)."""
    values = [float(v) for v in flat]
    if values[0] >= values[1] and values[0] >= values[2]:
        return hfo.DASH, (100.0 * values[3], -180.0 + 360.0 * values[4])
    if values[1] >= values[2]:
        return hfo.TURN, (-180.0 + 360.0 * values[5],)
    return hfo.KICK, (100.0 * values[6], -180.0 + 360.0 * values[7])


def striker_for_episode(config: SessionConfig, episode: int) -> Striker:
    """The striker of 1-based ``episode`` (aimed shots cycle their targets from episode 2 on)."""
    if config.striker == "aimed_shot":
        target = config.targets[(episode - 2) % len(config.targets)] if config.targets else 0.0
        return make_striker("aimed_shot", target_y=target, aim_cycles=AIM_CYCLES)
    return make_striker(config.striker)


def agent_main(config_path: str) -> None:
    """The learning agent of one session (run as ``_agent CONFIG``): plays until the server goes down."""
    config = SessionConfig(**json.loads(Path(config_path).read_text()))
    sys.path.insert(0, str(Path(config.hfo_dir) / "hfo"))
    import hfo  # the HFO build's ctypes binding

    env = hfo.HFOEnvironment()
    env.connectToServer(
        hfo.LOW_LEVEL_FEATURE_SET,
        str(Path(config.hfo_dir) / CONFIG_DIR),
        config.port,
        "localhost",
        "base_left",
        False,
        "",
    )
    episodes: list[dict[str, Any]] = []
    episode = 1
    striker = striker_for_episode(config, episode)
    striker.reset()
    steps = kicks = 0
    while True:
        state = env.getState()
        obs = np.asarray(paper_from_hfo(state.tolist(), 0, 1), dtype=np.float32)
        kind, params = hfo_action(hfo, striker(obs))
        env.act(kind, *params)
        kicks += kind == hfo.KICK
        status = env.step()
        steps += 1
        if status == hfo.SERVER_DOWN:
            break
        if status != hfo.IN_GAME:
            episodes.append(
                {
                    "episode": episode,
                    "status": HFO_STATUS_NAMES[status],
                    "agent_steps": steps,
                    "kicks": kicks,
                    "striker": striker.name,
                }
            )
            episode += 1
            striker = striker_for_episode(config, episode)
            striker.reset()
            steps = kicks = 0
    Path(config.result_path).write_text(json.dumps({"episodes": episodes}))


def real_episodes(args: argparse.Namespace, work: Path, configs: list[SessionConfig]) -> list[dict[str, Any]]:
    """Run the sessions one after another; each result gets its ``episodes`` list (first trial dropped)."""
    results = []
    for config in configs:
        started = time.monotonic()
        result = run_real_session(config, timeout_s=120.0 + 3.0 * config.trials)
        # the agent's steps of an episode after the first start LEAD_IDLE cycles into it
        result["episodes"] = [
            {**e, "length": e["agent_steps"] + LEAD_IDLE} for e in result["episodes"] if e["episode"] >= 2
        ]
        result["seconds"] = time.monotonic() - started
        results.append(result)
        print(
            f"  real {config.striker} port {config.port}: {len(result['episodes'])} episodes "
            f"in {result['seconds']:.0f} s",
            flush=True,
        )
    return results


def session_config(
    args: argparse.Namespace, work: Path, index: int, striker: str, trials: int, **kw: Any
) -> SessionConfig:
    port = args.port + 10 * index
    return SessionConfig(
        hfo_dir=str(args.hfo_dir),
        port=port,
        trials=trials,
        seed=args.seed + index,
        striker=striker,
        result_path=str(work / f"result_{port}.json"),
        **kw,
    )


# ---------------------------------------------------------------------------------------------------------------
# hfo2d side
# ---------------------------------------------------------------------------------------------------------------
def default_env_id() -> str:
    """HFO/Keeper-v1 when registered and constructible, else HFO/Keeper-v0."""
    if "HFO/Keeper-v1" in gym.registry:
        try:
            gym.make("HFO/Keeper-v1").close()
            return "HFO/Keeper-v1"
        except Exception as error:  # noqa: BLE001  (any failure: the port is not ready)
            print(f"HFO/Keeper-v1 does not build yet ({type(error).__name__}: {error}); using HFO/Keeper-v0")
    return "HFO/Keeper-v0"


def make_env(env_id: str, noise: bool) -> Any:
    return gym.make(
        env_id, noise=noise, frames_per_trial=FRAMES_PER_TRIAL, untouched_time=UNTOUCHED_TIME
    ).unwrapped


def idle_flat() -> np.ndarray:
    flat = np.full(8, 0.5)
    flat[0:3] = (0.0, 1.0, 0.0)  # TURN by 0 degrees
    return flat


def first_observation_delay(env: Any) -> int:
    """Cycles ``env.reset`` itself plays between the placement and the first observation (the goalie acts, the
    agent sends nothing): ``AGENT2D_FIRST_OBSERVATION_DELAY`` for ``goalie="agent2d"`` (HFO/Keeper-v1), else 0."""
    if getattr(env, "goalie", None) != "agent2d":
        return 0
    from hfo2d import hfo_env

    return int(getattr(hfo_env, "AGENT2D_FIRST_OBSERVATION_DELAY", 0))


def sim_idle_turns(env: Any) -> int:
    """Idle turns the benchmark sends before the striker's first command: HFO's ``LEAD_IDLE`` less the cycles the
    env already plays in its reset."""
    return max(0, LEAD_IDLE - first_observation_delay(env))


def reset_env(env: Any, options: dict[str, Any] | None, seed: int | None) -> np.ndarray:
    """``env.reset`` with hand placements; the first observation. HFO's ``--offense-on-ball`` puts the agent 0.1 m
    behind the ball, which ``HFOEnv`` refuses as overlapping; such a player is checked at a place away from the
    ball and then placed where HFO puts it *inside* the reset (before the cycles the env plays in its reset, in
    which the goalie already sees the agent)."""
    player = (options or {}).get("player")
    ball = (options or {}).get("ball")
    overlap = (
        player is not None
        and ball is not None
        and math.dist(player[:2], ball[:2]) < env.params.player_size + env.params.ball_size
    )
    if not overlap:
        return env.reset(seed=seed, options=options)[0]
    assert options is not None and player is not None and ball is not None
    away = {**options, "player": (ball[0] - 1.0, ball[1], *player[2:])}
    parse = env._parse_reset_options
    padded = tuple(float(v) for v in player) + (0.0,) * (5 - len(player))

    def parse_then_overlap(raw: Any) -> dict[str, tuple[float, ...]]:
        return {**parse(raw), "player": padded}

    env._parse_reset_options = parse_then_overlap  # an instance attribute, removed below
    try:
        return env.reset(seed=seed, options=away)[0]
    finally:
        del env._parse_reset_options


def play_sim_episode(
    env: Any, striker: Striker, options: dict[str, Any] | None, seed: int | None
) -> dict[str, Any]:
    """One hfo2d episode: the idle turns HFO's agent sends first (:func:`sim_idle_turns`), then the striker; end
    status and length in cycles from the placement (the env's first-observation delay included)."""
    obs = reset_env(env, options, seed)
    striker.reset()
    idle = sim_idle_turns(env)
    steps = 0
    while True:
        action = idle_flat() if steps < idle else striker(obs)
        obs, _, terminated, truncated, info = env.step(action)
        steps += 1
        if terminated or truncated:
            return {"status": info["status"], "steps": steps + first_observation_delay(env)}


# ---------------------------------------------------------------------------------------------------------------
# deterministic: replay logged episodes in hfo2d
# ---------------------------------------------------------------------------------------------------------------
@dataclass
class CycleRecord:
    """What one server step of hfo2d did for the goalie: its command(s), its policy's decision, the positions."""

    commands: list[tuple[str, tuple[float, ...]]]
    decision: dict[str, Any] | None = None
    goalie: tuple[float, float] = (0.0, 0.0)  # after the step
    agent: tuple[float, float] = (0.0, 0.0)
    ball: tuple[float, float] = (0.0, 0.0)


@contextmanager
def recording_goalie_commands(
    env: Any, cycles: list[CycleRecord] | None = None
) -> Iterator[list[tuple[str, tuple[float, ...]]]]:
    """Record the server commands the World receives for the goalie (turn, dash, kick, catch, tackle).

    With ``cycles``, ``World.step`` is wrapped too: each step appends a :class:`CycleRecord` of the commands sent
    since the previous step, the goalie policy's decision and the positions after the step (for the cycles that
    ``env.reset`` plays itself)."""
    world, keeper = env.world, env.keeper
    record: list[tuple[str, tuple[float, ...]]] = []
    originals: dict[str, Callable[..., Any]] = {}
    for name in ("turn", "dash", "kick", "catch", "tackle"):
        method = getattr(world, name, None)
        if method is None:
            continue
        originals[name] = method

        def wrapper(p: Any, *args: Any, _name: str = name, _method: Callable[..., Any] = method) -> Any:
            if p is keeper:
                record.append((_name, tuple(float(a) for a in args)))
            return _method(p, *args)

        setattr(world, name, wrapper)
    if cycles is not None:
        step = world.step
        originals["step"] = step

        def step_wrapper(*args: Any, **kwargs: Any) -> Any:
            decision = policy_snapshot(env)
            result = step(*args, **kwargs)
            cycles.append(
                CycleRecord(
                    list(record),
                    decision,
                    (keeper.x, keeper.y),
                    (env.agent.x, env.agent.y),
                    (world.ball.x, world.ball.y),
                )
            )
            record.clear()
            return result

        world.step = step_wrapper
    try:
        yield record
    finally:
        for name in originals:
            delattr(world, name)


def policy_snapshot(env: Any) -> dict[str, Any] | None:
    """What hfo2d's goalie policy exposes about its last decision (``last_command``, ``last_view``), as JSON."""
    policy = getattr(env, "_keeper_policy", None)
    snapshot: dict[str, Any] = {}
    for name in ("last_command", "last_view"):
        value = getattr(policy, name, None)
        if value is None:
            continue
        if dataclasses.is_dataclass(value) and not isinstance(value, type):
            value = dataclasses.asdict(value)
        elif hasattr(value, "__slots__") or hasattr(value, "__dict__"):
            slots = getattr(value, "__slots__", None) or list(vars(value))
            value = {slot: getattr(value, slot, None) for slot in slots}
        snapshot[name] = {
            k: v
            for k, v in (value.items() if isinstance(value, dict) else [("value", value)])
            if isinstance(v, (int, float, str, bool)) or v is None
        }
    return snapshot or None


def command_text(command: tuple[str, tuple[float, ...]] | None) -> str:
    if command is None:
        return "(none)"
    name, args = command
    if name == "dash" and len(args) == 2 and args[1] == 0.0:
        args = args[:1]
    return "(" + " ".join([name, *(f"{a:.6g}" for a in args)]) + ")"


def commands_agree(real: real_hfo_logs.BodyCommand | None, sim: tuple[str, tuple[float, ...]] | None) -> bool:
    """Same kind and numbers within COMMAND_REL_TOL relative or COMMAND_ABS_TOL absolute; nothing sent counts
    as a turn by 0."""

    def normal(name: str | None, args: Sequence[Any]) -> tuple[str | None, list[float]]:
        numbers = [float(a) for a in args if not isinstance(a, str)]
        if name is None:  # librcsc sends (turn 0) when a decision sets no body command
            return "turn", [0.0]
        if name == "dash" and len(numbers) == 1:
            numbers.append(0.0)
        return name, numbers

    real_name, real_numbers = normal(real.name if real else None, real.args if real else ())
    sim_name, sim_numbers = normal(sim[0] if sim else None, sim[1] if sim else ())
    if real_name != sim_name or len(real_numbers) != len(sim_numbers):
        return False
    return all(
        abs(a - b) <= max(COMMAND_ABS_TOL, COMMAND_REL_TOL * abs(a))
        for a, b in zip(real_numbers, sim_numbers, strict=True)
    )


def agent_flat(env: Any, command: real_hfo_logs.BodyCommand | None) -> np.ndarray:
    """Flat action (float64, exact) that makes hfo2d send the agent's logged server command."""
    flat = np.full(8, 0.5)
    flat[0:3] = 0.0
    if command is None:
        flat[1] = 1.0
        return flat
    args = [float(a) for a in command.args if not isinstance(a, str)]
    if command.name == "turn":
        agent = env.agent
        speed = math.hypot(agent.vx, agent.vy)
        desired = args[0] / (1.0 + env.params.inertia_moment * speed)
        flat[1] = 1.0
        flat[5] = (desired + 180.0) / 360.0
    elif command.name == "dash":
        direction = args[1] if len(args) > 1 else 0.0
        flat[0] = 1.0
        flat[3] = args[0] / 100.0
        flat[4] = (direction + 180.0) / 360.0
    elif command.name == "kick":
        flat[2] = 1.0
        flat[6] = args[0] / 100.0
        flat[7] = (args[1] + 180.0) / 360.0
    else:
        raise ValueError(f"the agent sent {command.text()}, which a flat action cannot express")
    return np.clip(flat, 0.0, 1.0)


def view_input_error(
    view: dict[str, Any] | None, cycle: real_hfo_logs.ClientCycle | None
) -> dict[str, float] | None:
    """How far hfo2d's goalie view was from what the real goalie read in the same cycle (its fullstate message,
    mirrored into GF): the largest position (m), velocity (m/cycle) and body angle (deg) differences."""
    if view is None or cycle is None or ("r", 1) not in cycle.players or ("l", 11) not in cycle.players:
        return None
    me, opp = cycle.players[("r", 1)], cycle.players[("l", 11)]
    bx, by, bvx, bvy = cycle.ball
    positions = [(view["px"], -me.x), (view["py"], -me.y), (view["bx"], -bx), (view["by"], -by)]
    positions += [(view["ox"], -opp.x), (view["oy"], -opp.y)]
    velocities = [
        (view["vx"], -me.vx),
        (view["vy"], -me.vy),
        (view["true_wx"], -bvx),
        (view["true_wy"], -bvy),
    ]
    velocities += [(view["ux"], -opp.vx), (view["uy"], -opp.vy)]
    body = abs((view["body"] - (me.body + 180.0) + 180.0) % 360.0 - 180.0)
    return {
        "position": max(abs(a - b) for a, b in positions),
        "velocity": max(abs(a - b) for a, b in velocities),
        "body": body,
        "stamina": abs(view["stamina"] - me.stamina),
    }


def replay_episode(
    env: Any,
    logs: real_hfo_logs.GameLogs,
    episode: real_hfo_logs.Episode,
    first: bool,
    tol: float,
    client: dict[int, real_hfo_logs.ClientCycle] | None = None,
) -> dict[str, Any] | None:
    """Replay one logged episode in hfo2d; None when its reset is not in the log. With the goalie's client log
    (``client``), the start state comes from the goalie's fullstate message of the reset cycle (6 significant
    digits: finer than the game log's 1e-4 m and 1e-3 degrees wherever |x| < 10 or |angle| < 100), and a command
    mismatch also reports how far hfo2d's goalie view was from the real goalie's."""
    start = logs.shows.get(episode.start)
    if start is None or ("l", 11) not in start.players or ("r", 1) not in start.players:
        return None
    agent_show, goalie_show = start.players[("l", 11)], start.players[("r", 1)]
    options = {
        "ball": start.ball,
        "player": (agent_show.x, agent_show.y, agent_show.body, agent_show.vx, agent_show.vy),
        "keeper": (goalie_show.x, goalie_show.y, goalie_show.body),
    }
    fs = (client or {}).get(episode.start)
    if fs is not None and ("l", 11) in fs.players and ("r", 1) in fs.players:
        a, g = fs.players[("l", 11)], fs.players[("r", 1)]
        options = {"ball": fs.ball, "player": (a.x, a.y, a.body, a.vx, a.vy), "keeper": (g.x, g.y, g.body)}
    delay = first_observation_delay(env)
    reset_cycles: list[CycleRecord] = []
    with recording_goalie_commands(env, reset_cycles):
        reset_env(env, options, 0 if first else None)
    # the last `delay` steps of the reset are the episode's first cycles (a carried-over goalie's wait frame of
    # the last episode comes before them)
    delay_cycles = reset_cycles[len(reset_cycles) - delay :] if delay else []
    agent_cmds = logs.commands["base_left_11"]
    goalie_cmds = logs.commands["base_right_1"]
    wait_frame = (
        None  # the goalie's command in the wait cycle before this reset (the last episode's end cycle)
    )
    if len(reset_cycles) > delay:
        wait = reset_cycles[len(reset_cycles) - delay - 1]
        real_wait = goalie_cmds.get(episode.start - 1)
        wait_frame = {
            "real": real_wait.text() if real_wait else "(none)",
            "sim": command_text(wait.commands[0] if wait.commands else None),
            "agree": commands_agree(real_wait, wait.commands[0] if wait.commands else None),
            "view_error": view_input_error(
                (wait.decision or {}).get("last_view"), (client or {}).get(episode.start - 1)
            ),
        }
    length = episode.end - episode.start
    first_div: dict[str, int | None] = {"goalie": None, "agent": None, "ball": None}
    max_err = {"goalie": 0.0, "agent": 0.0, "ball": 0.0}
    err = {
        "goalie": 0.0,
        "agent": 0.0,
        "ball": 0.0,
    }  # of the state the cycle's decisions see (0 at the reset)
    first_cmd_mismatch: dict[str, Any] | None = None
    sim_goalie_commands: list[str] = []
    status = "IN_GAME"

    def compare_command(k: int, sim_cmd: tuple[str, tuple[float, ...]] | None, decision: Any) -> None:
        nonlocal first_cmd_mismatch
        real_cmd = goalie_cmds.get(episode.start + k)
        sim_goalie_commands.append(command_text(sim_cmd))
        if first_cmd_mismatch is None and not commands_agree(real_cmd, sim_cmd):
            first_cmd_mismatch = {
                "cycle": k,
                "real": real_cmd.text() if real_cmd else "(none)",
                "sim": command_text(sim_cmd),
                "input_error": dict(err),  # how far hfo2d's state was from the log when the goalie decided
                "inputs_agree": err["ball"] <= tol and err["agent"] <= tol and err["goalie"] <= tol,
                "sim_decision": decision,
                "view_error": view_input_error(
                    (decision or {}).get("last_view"), (client or {}).get(episode.start + k)
                ),
            }

    def compare_state(k: int, positions: dict[str, tuple[float, float]]) -> None:
        """Positions after the step k -> k + 1 against ``show start + k + 1``."""
        show = logs.shows.get(episode.start + k + 1)
        if show is None:
            return
        for key, logged in (
            ("goalie", show.players.get(("r", 1))),
            ("agent", show.players.get(("l", 11))),
            ("ball", None),
        ):
            if key != "ball" and logged is None:
                continue
            rx, ry = show.ball[:2] if logged is None else (logged.x, logged.y)
            sim_xy = positions[key]
            err[key] = math.hypot(rx - sim_xy[0], ry - sim_xy[1])
            max_err[key] = max(max_err[key], err[key])
            if first_div[key] is None and err[key] > tol:
                first_div[key] = k + 1

    for k, cycle in enumerate(delay_cycles):  # the cycles env.reset played: the goalie alone acts
        compare_command(k, cycle.commands[0] if cycle.commands else None, cycle.decision)
        compare_state(k, {"goalie": cycle.goalie, "agent": cycle.agent, "ball": cycle.ball})
    steps = delay
    for k in range(delay, length):
        t = episode.start + k
        action = agent_flat(env, agent_cmds.get(t))
        with recording_goalie_commands(env) as record:
            _, _, terminated, truncated, info = env.step(action)
        steps += 1
        compare_command(k, record[0] if record else None, policy_snapshot(env))
        compare_state(k, {"goalie": info["keeper"], "agent": info["player"], "ball": info["ball"]})
        if terminated or truncated:
            status = info["status"]
            break
    div = first_div["goalie"]
    at_divergence = None
    if div is not None:  # the command executed in the step into the first divergent cycle
        real_cmd = goalie_cmds.get(episode.start + div - 1)
        at_divergence = {
            "cycle": div - 1,
            "real": real_cmd.text() if real_cmd else "(none)",
            "sim": sim_goalie_commands[div - 1],
        }
    return {
        "episode": episode.number,
        "start": episode.start,
        "real_status": episode.result,
        "real_length": length,
        "sim_status": status,
        "sim_length": steps,
        "status_agrees": status == episode.result and steps == length,
        "goalie_agrees": div is None,
        "first_divergence": first_div,
        "max_error": max_err,
        "goalie_command_at_divergence": at_divergence,
        "first_goalie_command_mismatch": first_cmd_mismatch,
        "wait_frame_before": wait_frame,
        "start_goalie_body": goalie_show.body,
        "start_ball": list(start.ball[:2]),
    }


STATUS_SHORT = {
    "GOAL": "G",
    "CAPTURED_BY_DEFENSE": "C",
    "OUT_OF_BOUNDS": "B",
    "OUT_OF_TIME": "T",
    "IN_GAME": "-",
}


def parse_spots(texts: Sequence[str] | None) -> list[tuple[float, float] | None]:
    """``--spots X,Y`` (fractions of the half length / half width, HFO's --ball-x/y-min = max): ball positions."""
    if not texts:
        return [None]
    spots: list[tuple[float, float] | None] = []
    for text in texts:
        x, y = (float(v) for v in text.split(","))
        spots.append((x, y))
    return spots


def run_deterministic_sessions(args: argparse.Namespace) -> list[SessionConfig]:
    """The logged real sessions of ``deterministic``: one per striker and spot."""
    check_network_namespace()
    work = Path(tempfile.mkdtemp(prefix="keeper_fidelity_", dir=args.work_dir))
    configs = []
    for name in args.strikers:
        for spot in parse_spots(args.spots):
            index = len(configs)
            log_dir = work / f"logs_{index}_{name}"
            log_dir.mkdir()
            placement: dict[str, Any] = {}
            if spot is not None:  # exact start: the ball at a round position, the agent 0.1 m behind it
                placement = {
                    "ball_x": (spot[0], spot[0]),
                    "ball_y": (spot[1], spot[1]),
                    "offense_on_ball": True,
                }
            config = session_config(
                args,
                work,
                index,
                name,
                args.episodes + 1,
                deterministic=True,
                logging=True,
                log_dir=str(log_dir),
                targets=tuple(args.targets) if name == "aimed_shot" else (),
            )
            configs.append(SessionConfig(**{**asdict(config), **placement}))
    if getattr(args, "client_logs", False):  # the goalie's client log too, for `views --replay-dir WORK`
        copy_dir = str(client_logging_hfo(Path(args.hfo_dir), work))
        configs = [SessionConfig(**{**asdict(c), "hfo_dir": copy_dir}) for c in configs]
    real_episodes(args, work, configs)
    return configs


def cmd_deterministic(args: argparse.Namespace) -> dict[str, Any]:
    if args.replay_dir:  # replay the logs of an earlier run; no server is started
        work = Path(args.replay_dir)
        sessions = sorted(work.glob("session_*.json"), key=lambda path: int(path.stem.split("_")[1]))
        configs = [SessionConfig(**json.loads(path.read_text())) for path in sessions]
        if not configs:
            raise SystemExit(f"keeper_fidelity: no session_*.json in {work}")
    else:
        configs = run_deterministic_sessions(args)
        work = Path(configs[0].result_path).parent
    env = make_env(args.env_id, noise=False)
    rows: list[dict[str, Any]] = []
    for config in configs:
        logs = real_hfo_logs.read_logs(Path(config.log_dir))
        client_log = Path(config.log_dir) / GOALIE_CLIENT_LOG
        client = real_hfo_logs.parse_client_log(client_log) if client_log.exists() else None
        first = True  # each session's first replayed episode starts a fresh hfo2d goalie (reset with a seed)
        for episode in logs.episodes:
            replay = replay_episode(env, logs, episode, first=first, tol=args.tol, client=client)
            if replay is not None:
                first = False
                target = None
                if config.striker == "aimed_shot" and config.targets:
                    target = config.targets[(episode.number - 2) % len(config.targets)]
                rows.append(
                    {"striker": config.striker, "session_port": config.port, "target": target, **replay}
                )
    mismatches = [r["first_goalie_command_mismatch"] for r in rows if r["first_goalie_command_mismatch"]]
    waits = [
        r["wait_frame_before"]
        for previous, r in zip(rows, rows[1:], strict=False)
        if r["wait_frame_before"]
        and previous["status_agrees"]
        and (previous["session_port"], previous["episode"] + 1) == (r["session_port"], r["episode"])
    ]
    summary = {
        "episodes": len(rows),
        "goalie_agrees": sum(r["goalie_agrees"] for r in rows),
        "status_agrees": sum(r["status_agrees"] for r in rows),
        "agent_diverged": sum(r["first_divergence"]["agent"] is not None for r in rows),
        "ball_diverged": sum(r["first_divergence"]["ball"] is not None for r in rows),
        "goalie_command_mismatches": len(mismatches),
        "mismatches_with_agreeing_inputs": sum(m["inputs_agree"] for m in mismatches),
        "median_first_goalie_divergence": _median([r["first_divergence"]["goalie"] for r in rows]),
        # the wait cycle before an episode whose previous one ended alike on both sides
        "wait_frames_compared": len(waits),
        "wait_frames_agree": sum(w["agree"] for w in waits),
    }
    print(f"\ndeterministic replay, hfo2d goalie {args.env_id}, tolerance {args.tol:g} m")
    print("cycle k = the state after k steps of the episode; a command at k is executed in the step k -> k+1")
    print(
        "columns: ball start (aimed_shot: > target y), end status and length, first cycle of a divergence > tol"
    )
    print(
        f"{'striker':<14}{'ep':>4}{'ball start':>14}{'real':>9}{'hfo2d':>9}{'goalie':>8}{'agent':>7}{'ball':>6}"
        f"{'cmd k':>7}  first differing goalie command: real | hfo2d (inputs' error, m)"
    )
    for r in rows:
        d = r["first_divergence"]
        m = r["first_goalie_command_mismatch"]
        where = ""
        if m:
            where = f"{m['real']} | {m['sim']} (ball {m['input_error']['ball']:.1e}, agent {m['input_error']['agent']:.1e})"
            if m.get("view_error"):
                ve = m["view_error"]
                where += f" view: pos {ve['position']:.1e} vel {ve['velocity']:.1e} body {ve['body']:.1e}"
        start = f"{r['start_ball'][0]:.1f},{r['start_ball'][1]:.1f}"
        if r["target"] is not None:
            start += f">{r['target']:+g}"
        print(
            f"{r['striker']:<14}{r['episode']:>4}{start:>14}"
            f"{STATUS_SHORT[r['real_status']] + ' ' + str(r['real_length']):>9}"
            f"{STATUS_SHORT[r['sim_status']] + ' ' + str(r['sim_length']):>9}"
            f"{_opt(d['goalie']):>8}{_opt(d['agent']):>7}{_opt(d['ball']):>6}{_opt(m['cycle'] if m else None):>7}  {where}"
        )
    n = max(1, summary["episodes"])
    print(
        f"goalie within {args.tol:g} m at every cycle: {summary['goalie_agrees']}/{summary['episodes']} "
        f"({summary['goalie_agrees'] / n:.1%}); same end status and length: {summary['status_agrees']}/"
        f"{summary['episodes']}; first goalie divergence, median cycle {summary['median_first_goalie_divergence']}"
    )
    print(
        f"goalie commands differ in {summary['goalie_command_mismatches']} episodes, "
        f"{summary['mismatches_with_agreeing_inputs']} of them while ball and agent still agreed within "
        f"{args.tol:g} m; the agent diverged in {summary['agent_diverged']}, the ball in {summary['ball_diverged']}"
    )
    print(
        f"wait-cycle commands (after an episode that ended alike): {summary['wait_frames_agree']}/"
        f"{summary['wait_frames_compared']} agree"
    )
    return {
        "env_id": args.env_id,
        "tol": args.tol,
        "summary": summary,
        "episodes": rows,
        "work_dir": str(work),
    }


def _median(values: Sequence[int | None]) -> float | None:
    present = [v for v in values if v is not None]
    return float(np.median(present)) if present else None


def _opt(value: Any) -> str:
    return "-" if value is None else str(value)


# ---------------------------------------------------------------------------------------------------------------
# views: hfo2d's goalie decision on the real goalie's own inputs
# ---------------------------------------------------------------------------------------------------------------
GOALIE_CLIENT_LOG = "base_right-1.ocl"  # the goalie's offline client log (librcsc: LOG_DIR/TEAM-UNUM + ext)


def client_logging_hfo(hfo_dir: Path, work: Path) -> Path:
    """A copy of the HFO build (symbolic links; bin/*.py copied so that bin/HFO finds the copy's teams) whose
    base team's player.conf has librcsc's ``offline_logging`` on: every NPC writes the messages it receives to
    ``LOG_DIR/TEAM-UNUM.ocl``. The real build is not touched."""
    copy = work / "hfo_client_logging"
    if (copy / "bin" / "HFO").exists():
        return copy

    def mirror(src: Path, dst: Path, real: set[str]) -> None:
        dst.mkdir(parents=True, exist_ok=True)
        for entry in src.iterdir():
            if entry.name not in real:
                (dst / entry.name).symlink_to(entry.resolve())

    mirror(hfo_dir, copy, {"bin"})
    mirror(hfo_dir / "bin", copy / "bin", {"teams", "HFO", *(f.name for f in (hfo_dir / "bin").glob("*.py"))})
    for script in ["HFO", *(f.name for f in (hfo_dir / "bin").glob("*.py"))]:
        (copy / "bin" / script).write_bytes((hfo_dir / "bin" / script).read_bytes())
        (copy / "bin" / script).chmod(0o755)
    mirror(hfo_dir / "bin" / "teams", copy / "bin" / "teams", {"base"})
    base = hfo_dir / "bin" / "teams" / "base"
    mirror(base, copy / "bin" / "teams" / "base", {"config"})
    mirror(base / "config", copy / "bin" / "teams" / "base" / "config", {"player.conf"})
    conf = (base / "config" / "player.conf").read_text()
    conf = conf.replace("#offline_logging", "offline_logging").replace("#offline_log_ext", "offline_log_ext")
    (copy / "bin" / "teams" / "base" / "config" / "player.conf").write_text(conf)
    return copy


class _StubPlayer:
    """A player of a fullstate message as hfo2d's goalie policy reads it (PlayerState's attributes)."""

    def __init__(self, side: str, unum: int, fs: real_hfo_logs.FullstatePlayer, tackle_cycles: int) -> None:
        self.side, self.unum = side, unum
        self.x, self.y, self.vx, self.vy = fs.x, fs.y, fs.vx, fs.vy
        self.body_deg = fs.body
        self.stamina, self.effort, self.recovery = fs.stamina, fs.effort, fs.recovery
        self.tackle_cycles = tackle_cycles


class _StubWorld:
    """The World interface Agent2dGoalie uses, holding one fullstate message; records the goalie's command."""

    def __init__(self, cycle: real_hfo_logs.ClientCycle, params: Any, noise: bool) -> None:
        self.cycle = cycle.time
        bx, by, bvx, bvy = cycle.ball
        self.ball = type("Ball", (), {"x": bx, "y": by, "vx": bvx, "vy": bvy})()
        self.players = [
            _StubPlayer(side, unum, fs, cycle.tackle_expires if (side, unum) == ("r", 1) else 0)
            for (side, unum), fs in sorted(cycle.players.items())
        ]
        self.params = params
        self.noise = noise
        self.sent: tuple[str, tuple[float, ...]] | None = None

    @property
    def keeper(self) -> _StubPlayer:
        return next(p for p in self.players if (p.side, p.unum) == ("r", 1))

    def turn(self, _p: Any, moment: float) -> None:
        self.sent = ("turn", (moment,))

    def dash(self, _p: Any, power: float, direction: float = 0.0) -> None:
        self.sent = ("dash", (power, direction))

    def catch(self, _p: Any, direction: float) -> bool:
        self.sent = ("catch", (direction,))
        return False  # the referee's goalie_catch_ball message, heard next cycle, tells the client

    def tackle(self, _p: Any, direction: float, foul: bool = False) -> None:
        self.sent = ("tackle", (direction,))


def decision_path(goalie: Any, world: _StubWorld) -> list[str]:
    """The public functions of hfo2d.agent2d's decision modules that one decision of ``goalie`` (a copy taken
    before the decision) calls: the branch taken, for a mismatch report."""
    calls: list[str] = []
    keep = ("decision.py", "actions.py", "tackle.py")

    def tracer(frame: Any, event: str, arg: Any) -> Any:
        if event == "call" and frame.f_code.co_filename.endswith(keep):
            name = frame.f_code.co_name
            if not name.startswith("_") or name in (
                "_go_to_point_look_ball",
                "_go_to_move_point",
                "_wait_turn",
            ):
                calls.append(name)
        return tracer

    sys.settrace(tracer)
    try:
        goalie.decide(world, world.keeper)
    finally:
        sys.settrace(None)
    return calls


def replay_views(
    logs: real_hfo_logs.GameLogs, client: dict[int, real_hfo_logs.ClientCycle], noise: bool
) -> list[dict[str, Any]]:
    """hfo2d's goalie decision on each of the real goalie's fullstate inputs, against the real goalie's command.

    One Agent2dGoalie carries the client state (catch time, last body command, last kicker, game mode) from cycle
    to cycle: ``reset`` at every episode start (the referee's before_kick_off / play_on), GoalieCatch from the
    heard ``goalie_catch_ball_r``. Physics plays no part: every decision sees exactly what the real goalie saw.
    One row per cycle of the episodes after HFO's first (their wait frames included)."""
    import copy

    from hfo2d.agent2d.goalie import Agent2dGoalie
    from hfo2d.physics import ServerParams

    params = ServerParams()
    goalie = Agent2dGoalie(params, np.random.default_rng(0))
    starts = {e.start for e in logs.episodes}
    episode_of: dict[int, real_hfo_logs.Episode] = {}
    for e in logs.episodes:
        for t in range(e.start, e.end + 1):  # the end cycle is the wait frame (decided before the next reset)
            episode_of[t] = e
    goalie_cmds = logs.commands["base_right_1"]
    rows: list[dict[str, Any]] = []
    started = False
    for t in sorted(client):
        cycle = client[t]
        started = started or cycle.mode == "play_on"
        if not started:
            continue
        if t in starts:
            goalie.reset()
        if cycle.mode_changed and cycle.mode == "goalie_catch_ball_r":
            goalie._catch_pending = True
        world = _StubWorld(cycle, params, noise)
        before = copy.deepcopy(goalie)
        goalie.apply(world, world.keeper, goalie.decide(world, world.keeper))
        episode = episode_of.get(t)
        if episode is None or episode.number < 2:
            continue
        real = goalie_cmds.get(t)
        sim = world.sent
        last = goalie.last_command
        if sim is None and last is not None and last.kind == "move":
            # Bhv_GoalieFreeKick's move: the client sends it, rcssserver ignores it in PlayOn, hfo2d sends nothing
            sim = ("move", (last.a, last.b))
        real_text = real.text() if real else "(none)"
        agree = commands_agree(real, sim)
        exact = real_text == command_text(sim) or (real is None and sim == ("turn", (0.0,)))
        row: dict[str, Any] = {
            "cycle": t,
            "episode": episode.number,
            "k": t - episode.start,
            "wait_frame": t == episode.end,
            "real": real_text,
            "sim": command_text(sim),
            "agree": agree,
            "exact": agree and exact,
        }
        if not agree:
            view = goalie.last_view
            row["view"] = dataclasses.asdict(view) if view is not None else None
            row["path"] = decision_path(before, _StubWorld(cycle, params, noise))
        rows.append(row)
    return rows


def cmd_views(args: argparse.Namespace) -> dict[str, Any]:
    """Run (or re-read) logged sessions with the goalie's client log and replay its decisions in hfo2d."""
    if args.replay_dir:
        work = Path(args.replay_dir)
        sessions = sorted(work.glob("session_*.json"), key=lambda path: int(path.stem.split("_")[1]))
        configs = [SessionConfig(**json.loads(path.read_text())) for path in sessions]
    else:
        check_network_namespace()
        work = Path(tempfile.mkdtemp(prefix="keeper_fidelity_", dir=args.work_dir))
        copy_dir = client_logging_hfo(Path(args.hfo_dir), work)
        configs = []
        for name in args.strikers:
            for spot in parse_spots(args.spots):
                index = len(configs)
                log_dir = work / f"logs_{index}_{name}"
                log_dir.mkdir()
                placement: dict[str, Any] = {}
                if spot is not None:
                    placement = {
                        "ball_x": (spot[0], spot[0]),
                        "ball_y": (spot[1], spot[1]),
                        "offense_on_ball": True,
                    }
                config = session_config(
                    args,
                    work,
                    index,
                    name,
                    args.episodes + 1,
                    deterministic=args.deterministic,
                    logging=True,
                    log_dir=str(log_dir),
                    targets=tuple(args.targets) if name == "aimed_shot" else (),
                )
                configs.append(SessionConfig(**{**asdict(config), "hfo_dir": str(copy_dir), **placement}))
        real_episodes(args, work, configs)
    sessions_out = []
    all_rows: list[dict[str, Any]] = []
    for config in configs:
        log_dir = Path(config.log_dir)
        client_log = log_dir / GOALIE_CLIENT_LOG
        if not client_log.exists():
            raise SystemExit(
                f"keeper_fidelity: no goalie client log {client_log} (run `views` without --replay-dir)"
            )
        logs = real_hfo_logs.read_logs(log_dir)
        rows = replay_views(logs, real_hfo_logs.parse_client_log(client_log), noise=not config.deterministic)
        for row in rows:
            row["striker"] = config.striker
        all_rows.extend(rows)
        sessions_out.append(
            {
                "striker": config.striker,
                "port": config.port,
                "deterministic": config.deterministic,
                "cycles": len(rows),
                "agree": sum(r["agree"] for r in rows),
                "exact": sum(r["exact"] for r in rows),
            }
        )
    mismatches = [r for r in all_rows if not r["agree"]]
    n = len(all_rows)
    summary = {
        "cycles": n,
        "agree": sum(r["agree"] for r in all_rows),
        "exact": sum(r["exact"] for r in all_rows),
        "mismatches": len(mismatches),
        "mismatch_kinds": dict(
            Counter(f"{r['real'].split()[0]}) | {r['sim'].split()[0]})" for r in mismatches)
        ),
    }
    print("\nhfo2d's goalie decision on the real goalie's own fullstate inputs (no physics), cycle by cycle")
    print(f"{'striker':<14}{'port':>6}{'noise':>7}{'cycles':>8}{'agree':>8}{'exact':>8}")
    for row in sessions_out:
        print(
            f"{row['striker']:<14}{row['port']:>6}{'off' if row['deterministic'] else 'on':>7}{row['cycles']:>8}"
            f"{row['agree']:>8}{row['exact']:>8}"
        )
    print(
        f"commands agree in {summary['agree']}/{n} cycles ({summary['agree'] / max(1, n):.2%}), "
        f"identical text in {summary['exact']}/{n}; mismatches by kind (real | hfo2d): {summary['mismatch_kinds']}"
    )
    for r in mismatches[:40]:
        print(
            f"  {r['striker']:<14} cycle {r['cycle']:>5} ep {r['episode']:>3} k {r['k']:>3}"
            f"{' (wait frame)' if r['wait_frame'] else ''}: {r['real']} | {r['sim']}  via {' > '.join(r['path'])}"
        )
    return {"summary": summary, "sessions": sessions_out, "mismatches": mismatches, "work_dir": str(work)}


# ---------------------------------------------------------------------------------------------------------------
# noise: goal rates per striker, both sides
# ---------------------------------------------------------------------------------------------------------------
def cmd_noise(args: argparse.Namespace) -> dict[str, Any]:
    check_network_namespace()
    work = Path(tempfile.mkdtemp(prefix="keeper_fidelity_", dir=args.work_dir))
    configs = [session_config(args, work, i, name, args.episodes + 1) for i, name in enumerate(args.strikers)]
    real = real_episodes(args, work, configs)
    env = make_env(args.env_id, noise=True)
    rows = []
    for index, (config, result) in enumerate(zip(configs, real, strict=True)):
        striker = make_striker(config.striker)
        sim = [
            play_sim_episode(env, striker, None, args.seed + 1000 * index if e == 0 else None)
            for e in range(args.episodes)
        ]
        real_summary = rate_summary([e["status"] for e in result["episodes"]])
        sim_summary = rate_summary([e["status"] for e in sim])
        rows.append(
            {
                "striker": config.striker,
                "real": real_summary,
                "sim": sim_summary,
                **difference(real_summary, sim_summary),
                "real_mean_length": float(np.mean([e["length"] for e in result["episodes"]] or [0])),
                "sim_mean_length": float(np.mean([e["steps"] for e in sim])),
            }
        )
    print(f"\nnoise on, {args.episodes} episodes per striker and side; hfo2d goalie {args.env_id}")
    print_rate_table(rows, "striker")
    return {"env_id": args.env_id, "episodes": args.episodes, "rows": rows, "work_dir": str(work)}


def print_rate_table(rows: list[dict[str, Any]], key: str) -> None:
    print(
        f"{key:<26}{'real goals [95%]':>24}{'hfo2d goals [95%]':>24}{'diff ± se':>16}   statuses real | hfo2d "
        "(G/C/B/T)"
    )
    for row in rows:
        print(
            f"{str(row[key]):<26}{_rate(row['real']):>24}{_rate(row['sim']):>24}"
            f"{100 * row['diff']:>+8.1f} ± {100 * row['se']:<5.1f}   {_counts(row['real'])} | {_counts(row['sim'])}"
        )


def _rate(summary: dict[str, Any]) -> str:
    low, high = summary["wilson95"]
    return f"{100 * summary['rate']:.1f}% [{100 * low:.1f}, {100 * high:.1f}] /{summary['n']}"


def _counts(summary: dict[str, Any]) -> str:
    return "/".join(str(summary["statuses"].get(status, 0)) for status in STATUSES)


# ---------------------------------------------------------------------------------------------------------------
# shots: the identical-shot test
# ---------------------------------------------------------------------------------------------------------------
def cmd_shots(args: argparse.Namespace) -> dict[str, Any]:
    check_network_namespace()
    work = Path(tempfile.mkdtemp(prefix="keeper_fidelity_", dir=args.work_dir))
    spots = [(d, y) for d in args.distances for y in args.ball_ys]
    targets = tuple(args.targets)
    trials = args.reps * len(targets) + 1
    configs = []
    for index, (distance, ball_y) in enumerate(spots):
        bx = (HALF_LENGTH - distance) / HALF_LENGTH
        by = ball_y / HALF_WIDTH
        configs.append(
            session_config(
                args,
                work,
                index,
                "aimed_shot",
                trials,
                deterministic=args.deterministic,
                ball_x=(bx, bx),
                ball_y=(by, by),
                offense_on_ball=True,
                targets=targets,
            )
        )
    real = real_episodes(args, work, configs)
    env = make_env(args.env_id, noise=not args.deterministic)
    rows = []
    for index, ((distance, ball_y), result) in enumerate(zip(spots, real, strict=True)):
        ball = (HALF_LENGTH - distance, ball_y)
        real_by_target: dict[float, list[str]] = {t: [] for t in targets}
        real_lengths: dict[float, list[int]] = {t: [] for t in targets}
        for e in result["episodes"]:
            target = targets[(e["episode"] - 2) % len(targets)]
            real_by_target[target].append(e["status"])
            real_lengths[target].append(e["length"])
        sim_by_target: dict[float, list[str]] = {t: [] for t in targets}
        sim_lengths: dict[float, list[int]] = {t: [] for t in targets}
        body = 0.0
        for e in range(args.reps * len(targets)):
            target = targets[e % len(targets)]
            striker = make_striker("aimed_shot", target_y=target, aim_cycles=AIM_CYCLES)
            # HFO places the agent 0.1 m behind the ball (HFORef::resetField) and keeps its body angle
            options = {"ball": ball, "player": (ball[0] - 0.1, ball[1], body)}
            outcome = play_sim_episode(env, striker, options, args.seed + 1000 * index if e == 0 else None)
            sim_by_target[target].append(outcome["status"])
            sim_lengths[target].append(outcome["steps"])
            body = env.agent.body_deg
        for target in targets:
            real_summary, sim_summary = (
                rate_summary(real_by_target[target]),
                rate_summary(sim_by_target[target]),
            )
            rows.append(
                {
                    "spot": f"{distance:g} m, y {ball_y:+g} -> {target:+g}",
                    "distance": distance,
                    "ball_y": ball_y,
                    "target": target,
                    "real": real_summary,
                    "sim": sim_summary,
                    **difference(real_summary, sim_summary),
                    "real_lengths": real_lengths[target],
                    "sim_lengths": sim_lengths[target],
                }
            )
    by_distance = []
    for distance in args.distances:
        real_s = [s for r in rows if r["distance"] == distance for s in _expand(r["real"])]
        sim_s = [s for r in rows if r["distance"] == distance for s in _expand(r["sim"])]
        rs, ss = rate_summary(real_s), rate_summary(sim_s)
        by_distance.append({"distance": f"{distance:g} m", "real": rs, "sim": ss, **difference(rs, ss)})
    by_target = []
    for target in targets:
        rs = rate_summary([s for r in rows if r["target"] == target for s in _expand(r["real"])])
        ss = rate_summary([s for r in rows if r["target"] == target for s in _expand(r["sim"])])
        by_target.append({"target": f"y {target:+g}", "real": rs, "sim": ss, **difference(rs, ss)})
    noise = "off (--deterministic)" if args.deterministic else "on"
    print(f"\nidentical shots, noise {noise}, {args.reps} per spot and target; hfo2d goalie {args.env_id}")
    print_rate_table(rows, "spot")
    print()
    print_rate_table(by_distance, "distance")
    print()
    print_rate_table(by_target, "target")
    return {
        "env_id": args.env_id,
        "reps": args.reps,
        "deterministic": args.deterministic,
        "rows": rows,
        "by_distance": by_distance,
        "by_target": by_target,
        "work_dir": str(work),
    }


def _expand(summary: dict[str, Any]) -> list[str]:
    return [status for status, count in summary["statuses"].items() for _ in range(count)]


# ---------------------------------------------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------------------------------------------
def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)

    def common(p: argparse.ArgumentParser) -> None:
        p.add_argument(
            "--hfo-dir", default=None, help="real HFO build (bin/HFO, hfo/hfo.py); default $HFO_DIR"
        )
        p.add_argument(
            "--env-id", default=None, help="hfo2d goalie env (default: HFO/Keeper-v1 if it builds)"
        )
        p.add_argument("--seed", type=int, default=0, help="HFO --seed of the first session (+1 per session)")
        p.add_argument("--port", type=int, default=6000, help="port of the first session (+10 per session)")
        p.add_argument(
            "--work-dir", default=None, help="where logs and session files go (default: a temp dir)"
        )
        p.add_argument("--out", default=None, help="JSON output path")

    def strikers(p: argparse.ArgumentParser, episodes: int, extra: tuple[str, ...] = ()) -> None:
        p.add_argument("--episodes", type=int, default=episodes, help="episodes per striker and side")
        p.add_argument("--strikers", nargs="+", default=list(STRIKERS), choices=[*STRIKERS, *extra])

    det = sub.add_parser("deterministic", help="replay deterministic real episodes in hfo2d, cycle by cycle")
    common(det)
    strikers(det, 3, extra=("aimed_shot",))
    det.add_argument(
        "--targets",
        type=float,
        nargs="+",
        default=list(SHOT_TARGETS),
        help="aimed_shot: goal-line y of the shots, cycled by episode (use it with --spots)",
    )
    det.add_argument("--tol", type=float, default=DEFAULT_TOL, help="position tolerance (m)")
    det.add_argument(
        "--replay-dir",
        default=None,
        help="replay the logs of an earlier run (its work directory, printed in the JSON as work_dir) instead of "
        "running HFO; needs neither a network namespace nor --hfo-dir",
    )
    det.add_argument(
        "--spots",
        nargs="+",
        default=None,
        metavar="X,Y",
        help="exact starts: the ball at X * 52.5, Y * 34 with the agent on it, one session per striker and spot "
        "(default: HFO's random start, whose logged reset state is rounded to 1e-4 m)",
    )
    views = sub.add_parser(
        "views",
        help="hfo2d's goalie decisions on the real goalie's own inputs (its client log), cycle by cycle",
    )
    common(views)
    strikers(views, 5, extra=("aimed_shot",))
    views.add_argument("--deterministic", action="store_true", help="HFO --deterministic (default: noise on)")
    views.add_argument(
        "--spots", nargs="+", default=None, metavar="X,Y", help="exact starts, as for deterministic"
    )
    views.add_argument(
        "--targets", type=float, nargs="+", default=list(SHOT_TARGETS), help="aimed_shot targets"
    )
    views.add_argument("--replay-dir", default=None, help="re-read an earlier `views` run's work directory")
    det.add_argument(
        "--client-logs",
        action="store_true",
        help="also write the NPCs' client logs (an HFO copy with librcsc offline_logging on), for `views`",
    )
    noise = sub.add_parser("noise", help="goal rates with noise on, real vs hfo2d")
    common(noise)
    strikers(noise, 1000)
    shots = sub.add_parser("shots", help="the identical-shot test, real vs hfo2d")
    common(shots)
    shots.add_argument("--reps", type=int, default=7, help="shots per spot and target, each side")
    shots.add_argument("--distances", type=float, nargs="+", default=list(SHOT_DISTANCES))
    shots.add_argument("--ball-ys", type=float, nargs="+", default=list(SHOT_BALL_YS))
    shots.add_argument("--targets", type=float, nargs="+", default=list(SHOT_TARGETS))
    shots.add_argument("--deterministic", action="store_true", help="HFO --deterministic and hfo2d noise off")
    agent = sub.add_parser("_agent", help=argparse.SUPPRESS)
    agent.add_argument("config")
    return parser


def hfo2d_version() -> dict[str, Any]:
    """The repository commit and whether envs/hfo2d has uncommitted changes (the goalie port evolves)."""
    repo = Path(__file__).resolve().parents[1]
    try:
        commit = subprocess.run(
            ["git", "-C", str(repo), "rev-parse", "HEAD"], capture_output=True, text=True, check=True
        ).stdout.strip()
        dirty = subprocess.run(
            ["git", "-C", str(repo), "status", "--porcelain", "envs/hfo2d"],
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return {"commit": None, "hfo2d_dirty": None, "hfo2d_imported_from": str(Path(hfo2d.__file__).parent)}
    return {
        "commit": commit,
        "hfo2d_dirty": bool(dirty),
        "hfo2d_imported_from": str(Path(hfo2d.__file__).parent),
    }


def main(argv: Sequence[str] | None = None) -> None:
    args = build_parser().parse_args(argv)
    if args.command == "_agent":
        agent_main(args.config)
        return
    if not getattr(args, "replay_dir", None):
        args.hfo_dir = hfo_dir_of(args.hfo_dir)
    args.env_id = args.env_id or default_env_id()
    started = time.monotonic()
    commands = {
        "deterministic": cmd_deterministic,
        "views": cmd_views,
        "noise": cmd_noise,
        "shots": cmd_shots,
    }
    result = commands[args.command](args)
    result["command"] = " ".join(sys.argv)
    result["hfo2d_version"] = hfo2d_version()
    result["seconds"] = time.monotonic() - started
    if args.out:
        Path(args.out).write_text(json.dumps(result, indent=1))
        print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
