"""Gymnasium environments over a local build of the real RoboCup Half Field Offense (LARG/HFO).

:class:`RealHFOEnv` plays the same task as :class:`hfo2d.hfo_env.HFOEnv` (one striker, left side, against an empty
goal or a goalie) in the real rcssserver, with HFO's own launcher, trainer and agent2d NPCs. Its observation and
action spaces, its action mapping and its rewards are hfo2d's, so a model trained on hfo2d runs on it unchanged:
``python -m sb3_hfo.evaluate MODEL --env HFO/RealKeeper-v0`` (with ``HFO_DIR`` set).

Nothing is imported from the HFO build until an env is made, and this module needs neither torch nor a build to be
imported. A build is the directory holding ``bin/HFO`` and ``hfo/libhfo_c.so`` (``hfo_dir``, else the environment
variable ``HFO_DIR``); the error raised without one says how to build it (``tools/real_hfo/build.sh``, guide:
docs/real_hfo.md).

Process model (one HFO session per env, started lazily by the first ``reset``):

* ``bin/HFO`` (HFO's launcher: rcssserver, the trainer, the NPCs), in its own process group;
* a worker: ``python -m hfo2d.real --worker ...``, which loads HFO's ctypes binding, calls ``connectToServer``
  (allowed once per process, HFO's strategy.cpp refuses a second) and then serves one ``act`` + ``step`` per
  request over a socket pair, in its own process group;
* for task ``"static_keeper"`` (``bin/HFO --defense-agents 1 --agent-play-goalie``, no NPC goalie) a second
  worker, ``python -m hfo2d.real --goalie ...``, connected as the defence goalie (team base_right, unum 1, HFO's
  ``play_goalie``), in a third process group. It plays on its own: every cycle it turns its body to face the field
  (global 180 degrees, toward -x) when it is off by more than GOALIE_TURN_THRESHOLD_DEG, read from its own
  features, and otherwise sends NOOP (:func:`still_goalie_command`). rcssserver's sync mode keeps it in lock-step
  with the learning agent (the server advances a cycle once both players have sent their command). HFO's referee
  places a goalie at (52.5, 0) every episode without touching its body angle (rcssserver Player::place(pos)), so
  it turns only at the start of a session (HFO's initial body angle faces its own goal) and after anything else
  turned it.

All process groups are killed on ``close()``, when the env is garbage collected and at interpreter exit; on Linux
they also receive SIGTERM when the thread that made the env dies. A session that goes down (HFO's SERVER_DOWN, a
dead worker, no answer) ends the episode (truncated, ``info["status"] == "SERVER_DOWN"``) with a warning, and the
next ``reset`` starts a new session.

Run real servers in a network namespace with only loopback (HFO's players talk UDP on ``port`` .. ``port + 2``):
``tools/real_hfo/loopback.sh python ...``.

Seeds (rcssserver 15.2.2's src/stadium.cpp and src/referee.cpp, HFO's bin/HFO). HFO's ``--seed`` becomes
rcssserver's ``server::random_seed``, which seeds two generators:

* the referee's: the start positions, from the first kick-off on;
* the simulator's noise: seeded at server start.

How many cycles the server runs before kick-off, while the players connect, depends on the wall clock. Each of
them draws from the noise generator (Stadium::turnMovableObjects shuffles the objects) and lets the players turn.
So the noise and the players' body and neck angles at kick-off differ from run to run (seen in rcssserver's game
logs): two sessions of one seed repeat the start positions, not the episodes. Re-seeding the noise at kick-off (a
one-line rcssserver change, tried) does not fix this, since the goalie's first command still differs; without noise
(``noise=False``) it happens less often (3 of 6 measured pairs of sessions differed from their first observation).
A real-HFO figure is therefore one sample: docs/real_hfo.md gives the spread and how to pool runs.

Episode timing (HFO's src/HFO.cpp and rcssserver's HFORef, src/referee.cpp):

* the referee resets the field one cycle after an episode ends, and HFO's ``step()`` plays three NOOPs after an
  episode's last cycle before it returns, so each episode's first observation is taken two cycles after the
  placement; the first episode of a session is started the same way (its very first observation, taken at
  connection, precedes the placement and is discarded);
* an episode's last observation is therefore lost: on the step that ends an episode this env returns the
  observation the final action was taken from (``info["stale_observation"]`` is True) and keeps HFO's refreshed
  state as the next episode's first observation;
* HFO ends an episode ``frames_per_trial`` cycles after the placement (OUT_OF_TIME); such an episode has
  ``frames_per_trial - 1`` steps here and is reported ``truncated``, every other end ``terminated``;
* a session's first episode is one cycle shorter on HFO's clock (measured: ``frames_per_trial - 2`` steps, and
  one step less before an untouched ball ends it), although after the three start NOOPs the goalie has moved as
  far as at the start of later episodes: HFO's referee starts counting it at the trainer's kick-off, one cycle
  before the players act on the placement.
"""

from __future__ import annotations

import atexit
import contextlib
import math
import os
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import time
import warnings
import weakref
from collections.abc import Sequence
from pathlib import Path
from typing import IO, Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from hfo2d.action_layout import hfo_flat_action_space
from hfo2d.features import (
    BALL_ANGLE_COS,
    BALL_ANGLE_SIN,
    BALL_POS_VALID,
    BALL_PROXIMITY,
    BALL_SPEED,
    BALL_SPEED_MAX,
    BALL_VEL_ANGLE_COS,
    BALL_VEL_ANGLE_SIN,
    BALL_VEL_VALID,
    FEATURES_PER_PLAYER,
    FIRST_LANDMARK,
    HFO_MASTER_MAX_DIST,
    KICKABLE,
    LANDMARKS,
    NUM_BASIC_FEATURES,
    PLAYER_ANGLE_COS,
    PLAYER_ANGLE_SIN,
    PLAYER_BODY_COS,
    PLAYER_BODY_SIN,
    PLAYER_PROXIMITY,
    PLAYER_SPEED,
    PLAYER_SPEED_MAX,
    PLAYER_VEL_ANGLE_COS,
    PLAYER_VEL_ANGLE_SIN,
    SELF_BODY_COS,
    SELF_BODY_SIN,
    SELF_POS_VALID,
    SELF_SPEED,
    SELF_SPEED_MAX,
    SELF_VEL_ANGLE_COS,
    SELF_VEL_ANGLE_SIN,
    hfo_num_features,
    num_features,
    paper_from_hfo,
)
from hfo2d.hfo_env import ACTION_FORMATS, HFOEnv
from hfo2d.protocol import (
    ACTION_NAMES,
    CAPTURED_BY_DEFENSE,
    DASH,
    DEFAULT_FRAMES_PER_TRIAL,
    DEFAULT_UNTOUCHED_TIME,
    DIRECTION_MAX,
    DIRECTION_MIN,
    GOAL,
    IN_GAME,
    KICK,
    OUT_OF_BOUNDS,
    OUT_OF_TIME,
    POWER_MAX,
    POWER_MIN,
    TURN,
)
from hfo2d.reward import REWARD_NAMES, make_reward

# ---------------------------------------------------------------------------------------------------------------
# Tasks, HFO's numbers, session settings
# ---------------------------------------------------------------------------------------------------------------
TASKS: tuple[str, ...] = ("empty_goal", "static_keeper", "keeper")
#: Defense NPCs per task: the keeper task is HFO's agent2d goalie (bin/HFO --defense-npcs 1: unum 1 plays goalie).
DEFENSE_NPCS: dict[str, int] = {"empty_goal": 0, "static_keeper": 0, "keeper": 1}
#: Defense agents per task: the static keeper is this module's still goalie (bin/HFO --defense-agents 1).
DEFENSE_AGENTS: dict[str, int] = {"empty_goal": 0, "static_keeper": 1, "keeper": 0}
HFO_DIR_ENV = "HFO_DIR"

# HFO's action codes (hfo/hfo.py and src/common.hpp: DASH, TURN, TACKLE, KICK, ..., CATCH = 12, NOOP = 13,
# QUIT = 14)
HFO_DASH, HFO_TURN, HFO_TACKLE, HFO_KICK, HFO_CATCH, HFO_NOOP = 0, 1, 2, 3, 12, 13
#: How many parameters HFO's act() takes per low-level action code (src/common.hpp NumParams); the worker sends a
#: NOOP for any other code.
HFO_ACTION_PARAMS: dict[int, int] = {HFO_DASH: 2, HFO_TURN: 1, HFO_TACKLE: 1, HFO_KICK: 2, HFO_CATCH: 0}
#: hfo2d's action kind -> HFO's action code
HFO_ACTION_CODES: dict[int, int] = {DASH: HFO_DASH, TURN: HFO_TURN, KICK: HFO_KICK}
# HFO's game statuses (hfo/hfo.py: IN_GAME, GOAL, CAPTURED_BY_DEFENSE, OUT_OF_BOUNDS, OUT_OF_TIME, SERVER_DOWN)
HFO_SERVER_DOWN = 5
SERVER_DOWN = "SERVER_DOWN"
#: HFO's status code -> hfo2d's status name (SERVER_DOWN is HFO's own, for a session that went down)
STATUS_NAMES: tuple[str, ...] = (IN_GAME, GOAL, CAPTURED_BY_DEFENSE, OUT_OF_BOUNDS, OUT_OF_TIME, SERVER_DOWN)
# HFO's sides (hfo/hfo.py: RIGHT, NEUTRAL, LEFT = -1, 0, 1) as the letters of the referee's messages
SIDE_LETTERS: dict[int, str] = {-1: "R", 0: "U", 1: "L"}
HFO_LOW_LEVEL_FEATURE_SET = 0  # hfo/hfo.py LOW_LEVEL_FEATURE_SET
HFO_HIGH_LEVEL_FEATURE_SET = 1  # hfo/hfo.py HIGH_LEVEL_FEATURE_SET
HFO_TEAM_NAME = "base_left"  # the offense team of bin/HFO's Trainer.py (agent2d, "base")
HFO_DEFENSE_TEAM_NAME = "base_right"  # its defense team (bin/Trainer.py createTeam: 'base_' + 'right')
HFO_CONFIG_SUBDIR = "bin/teams/base/config/formations-dt"  # the config dir bin/HFO gives its agents
#: NOOPs HFO's step() plays after an episode's last cycle (src/HFO.cpp); the first episode is started alike.
START_NOOPS = 3
#: bin/HFO's --trials: episodes before the server stops (rcssserver hfo_max_trials; an int server parameter)
SESSION_TRIALS = 2_000_000_000
#: A line bin/HFO's Trainer.py prints when it waits for the learning agent to connect.
WAITING_FOR_AGENT = "Waiting for player-controlled agent"
#: ... and for the defense agent, which it waits for once the offense agent has connected (bin/Trainer.py run:
#: offense first, then defense; the agent's team and its number in the team, from 0).
WAITING_FOR_GOALIE = f"{WAITING_FOR_AGENT} {HFO_DEFENSE_TEAM_NAME}-0"
#: A line bin/HFO prints when rcssserver did not start (e.g. its port is taken).
SERVER_FAILED = "Failed to launch Server"
START_TIMEOUT_S = 90.0  # bin/HFO start-up, agent connection (several processes start on a loaded 2-core box)
STEP_TIMEOUT_S = 60.0  # one synchronous cycle; HFO's own client gives up on a silent server sooner
PORT_RANGE = (20000, 60000)  # where a free port (and the two after it) is looked for
PORT_TRIES = 3  # sessions started on freshly picked ports before giving up (another program may take one)
MAX_SEED = 2**31 - 1  # rcssserver's random_seed is an int
#: The still goalie's body, global: facing the field (toward -x), as hfo2d's HFO/StaticKeeper-v0 keeper.
GOALIE_BODY_DEG = 180.0
#: ... in its own features: librcsc's world model turns a right-side player's world round (its team always
#: attacks +x), so facing the field is 0 degrees there (HFO's lowlevel_feature_extractor.cpp: wm.self().body()).
GOALIE_OWN_BODY_DEG = 0.0
#: The still goalie turns while its body is further than this from GOALIE_OWN_BODY_DEG. A turn at rest turns by
#: the moment times 1 + U(-player_rand, player_rand) (rcssserver player.cpp Player::turn; player_rand 0.1), so
#: from HFO's initial body (facing its own goal) it takes at most three turns: 180 -> 18 -> 1.8 -> 0.18 degrees.
GOALIE_TURN_THRESHOLD_DEG = 0.5

# Wire format between env and worker (little-endian): request (code, param0, param1); reply (status, side of the
# player on the ball, its unum) + the state as float32; handshake (state size, teammates, opponents, own unum) + state.
_REQUEST = struct.Struct("<iff")
_REPLY_HEAD = struct.Struct("<iii")
_HANDSHAKE_HEAD = struct.Struct("<iiii")
_QUIT = -1


class HFOBuildNotFound(FileNotFoundError):
    """No HFO build where RealHFOEnv looked (``hfo_dir`` / ``HFO_DIR``)."""


class HFOSessionError(RuntimeError):
    """An HFO session could not be started."""


BUILD_HINT = (
    "Build the real HFO (LARG/HFO with its rcssserver and librcsc forks, about 7 CPU-minutes) with the "
    "repository's script `tools/real_hfo/build.sh DEST` (it clones github.com/LARG/HFO, mhauskn/rcssserver and "
    "mhauskn/librcsc; --help shows how to build from local clones), then pass hfo_dir=DEST/HFO or set "
    f"{HFO_DIR_ENV}=DEST/HFO; run the servers under tools/real_hfo/loopback.sh. Guide: docs/real_hfo.md."
)


def find_hfo_dir(hfo_dir: str | os.PathLike[str] | None = None) -> Path:
    """The HFO build to use: ``hfo_dir``, else ``$HFO_DIR``; it must hold ``bin/HFO`` and ``hfo/libhfo_c.so``.

    Raises:
        HFOBuildNotFound: neither is given, or the directory is not a complete build (the message says how to
            build one).
    """
    source = "hfo_dir"
    if hfo_dir is None:
        hfo_dir = os.environ.get(HFO_DIR_ENV) or None
        source = f"${HFO_DIR_ENV}"
    if hfo_dir is None:
        raise HFOBuildNotFound(f"no HFO build given: pass hfo_dir=... or set {HFO_DIR_ENV}. {BUILD_HINT}")
    path = Path(hfo_dir).expanduser()
    missing = [name for name in ("bin/HFO", "hfo/hfo.py", "hfo/libhfo_c.so") if not (path / name).is_file()]
    if missing:
        raise HFOBuildNotFound(
            f"{source}={str(hfo_dir)!r} is not a complete HFO build (missing {', '.join(missing)}). {BUILD_HINT}"
        )
    return path.resolve()


def in_loopback_namespace() -> bool:
    """True when this process's network namespace has no interface but loopback (as under
    tools/real_hfo/loopback.sh)."""
    try:
        names = [name for _, name in socket.if_nameindex()]
    except OSError:
        return False
    return names == ["lo"]


def hfo_command(kind: int, power: float, direction: float) -> tuple[int, float, float]:
    """HFO's ``act`` call for hfo2d's (kind, power, direction): (action code, param0, param1); unused params 0.

    DASH -> ``act(DASH, power, direction)``, TURN -> ``act(TURN, direction)``, KICK -> ``act(KICK, power,
    direction)``; HFO's agent (librcsc's doDash / doTurn / doKick) then processes them as hfo2d's client does.
    """
    if kind == TURN:
        return HFO_TURN, float(direction), 0.0
    return HFO_ACTION_CODES[kind], float(power), float(direction)


def bin_hfo_args(
    *,
    offense_agents: int,
    defense_npcs: int,
    offense_npcs: int = 0,
    defense_agents: int = 0,
    agent_play_goalie: bool = False,
    frames_per_trial: int = DEFAULT_FRAMES_PER_TRIAL,
    untouched_time: int = DEFAULT_UNTOUCHED_TIME,
    fullstate: bool = True,
    noise: bool = True,
    seed: int | None = None,
    log_dir: Path | None = None,
) -> list[str]:
    """bin/HFO's arguments (less ``--port``) for a headless session of :data:`SESSION_TRIALS` episodes.

    ``--offense-npcs`` and ``--defense-agents`` are written only when not 0, bin/HFO's default for every team count
    (its parseArgs); ``noise=False`` is ``--deterministic``; ``log_dir`` None is ``--no-logging``.
    """
    args = ["--headless", "--offense-agents", str(offense_agents)]
    if offense_npcs:
        args += ["--offense-npcs", str(offense_npcs)]
    if defense_agents:
        args += ["--defense-agents", str(defense_agents)]
    args += [
        "--defense-npcs",
        str(defense_npcs),
        "--frames-per-trial",
        str(frames_per_trial),
        "--untouched-time",
        str(untouched_time),
        "--trials",
        str(SESSION_TRIALS),
    ]
    if agent_play_goalie:
        args.append("--agent-play-goalie")
    if fullstate:
        args.append("--fullstate")
    if not noise:
        args.append("--deterministic")
    if seed is not None:
        args += ["--seed", str(seed)]
    if log_dir is None:
        args.append("--no-logging")
    else:
        args += ["--log-dir", str(log_dir)]
    return args


# ---------------------------------------------------------------------------------------------------------------
# The state behind HFO master's features (fullstate): positions for ``info``
# ---------------------------------------------------------------------------------------------------------------
_DEG = 180.0 / math.pi


def _distance(proximity: float) -> float:
    """Metres of an HFO master proximity ``1 - 2 d / maxHFODist`` (src/feature_extractor.cpp)."""
    return (1.0 - proximity) * 0.5 * HFO_MASTER_MAX_DIST


def state_from_hfo_features(vec: Sequence[float], num_opponents: int) -> dict[str, tuple[float, ...] | None]:
    """Global ``player`` (x, y, vx, vy, body_deg), ``ball`` (x, y, vx, vy) and, with an opponent, ``keeper`` (x, y,
    vx, vy, body_deg) recovered from HFO master's low-level vector (``hfo_num_features(0, num_opponents)`` long).

    The agent's position comes from its nearest landmark (bearing relative to the body, HFO master's proximity over
    85.9 m, the global body angle); the ball and the goalie from their bearings and proximities. Exact to a few
    millimetres with fullstate (float32 features), except the speeds, which the features cap: own speed at
    0.46 m/cycle, the goalie's at 0.75. A part whose valid flag is off (no fullstate) is None, and so is
    ``keeper`` while HFO does not list the goalie (its uniform-number entry is -1).
    """
    if vec[SELF_POS_VALID] <= 0.0:
        return (
            {"player": None, "ball": None, "keeper": None}
            if num_opponents
            else {"player": None, "ball": None}
        )
    body_sin = float(vec[SELF_BODY_SIN])
    body_cos = float(vec[SELF_BODY_COS])
    body = math.atan2(body_sin, body_cos)
    # nearest landmark: the largest proximity
    best = max(range(len(LANDMARKS)), key=lambda k: vec[FIRST_LANDMARK + 3 * k + 2])
    base = FIRST_LANDMARK + 3 * best
    landmark_x, landmark_y = LANDMARKS[best][1]
    heading = body + math.atan2(float(vec[base]), float(vec[base + 1]))
    dist = _distance(float(vec[base + 2]))
    x = landmark_x - dist * math.cos(heading)
    y = landmark_y - dist * math.sin(heading)
    # own velocity: heading = body - (body - heading); speed over [0, 0.46]
    speed = (float(vec[SELF_SPEED]) + 1.0) * 0.5 * SELF_SPEED_MAX
    vel_heading = body - math.atan2(float(vec[SELF_VEL_ANGLE_SIN]), float(vec[SELF_VEL_ANGLE_COS]))
    state: dict[str, tuple[float, ...] | None] = {
        "player": (x, y, speed * math.cos(vel_heading), speed * math.sin(vel_heading), body * _DEG)
    }
    ball: tuple[float, ...] | None = None
    if vec[BALL_POS_VALID] > 0.0:
        heading = body + math.atan2(float(vec[BALL_ANGLE_SIN]), float(vec[BALL_ANGLE_COS]))
        dist = _distance(float(vec[BALL_PROXIMITY]))
        ball_speed = (
            (float(vec[BALL_SPEED]) + 1.0) * 0.5 * BALL_SPEED_MAX if vec[BALL_VEL_VALID] > 0.0 else 0.0
        )
        ball_heading = math.atan2(float(vec[BALL_VEL_ANGLE_SIN]), float(vec[BALL_VEL_ANGLE_COS]))
        ball = (
            x + dist * math.cos(heading),
            y + dist * math.sin(heading),
            ball_speed * math.cos(ball_heading),
            ball_speed * math.sin(ball_heading),
        )
    state["ball"] = ball
    if num_opponents:
        keeper: tuple[float, ...] | None = None
        start = NUM_BASIC_FEATURES  # the nearest opponent's block (no teammates); the unum entries follow the blocks
        if vec[NUM_BASIC_FEATURES + FEATURES_PER_PLAYER * num_opponents] > 0.0:
            heading = body + math.atan2(
                float(vec[start + PLAYER_ANGLE_SIN]), float(vec[start + PLAYER_ANGLE_COS])
            )
            dist = _distance(float(vec[start + PLAYER_PROXIMITY]))
            keeper_speed = (float(vec[start + PLAYER_SPEED]) + 1.0) * 0.5 * PLAYER_SPEED_MAX
            keeper_heading = math.atan2(
                float(vec[start + PLAYER_VEL_ANGLE_SIN]), float(vec[start + PLAYER_VEL_ANGLE_COS])
            )
            keeper = (
                x + dist * math.cos(heading),
                y + dist * math.sin(heading),
                keeper_speed * math.cos(keeper_heading),
                keeper_speed * math.sin(keeper_heading),
                math.atan2(float(vec[start + PLAYER_BODY_SIN]), float(vec[start + PLAYER_BODY_COS])) * _DEG,
            )
        state["keeper"] = keeper
    return state


# ---------------------------------------------------------------------------------------------------------------
# Processes
# ---------------------------------------------------------------------------------------------------------------
def _free_port(rng: np.random.Generator) -> int:
    """A UDP port p with p + 1 and p + 2 also free (bin/HFO: server, coach, online coach)."""
    for _ in range(200):
        port = int(rng.integers(PORT_RANGE[0], PORT_RANGE[1] - 2))
        sockets: list[socket.socket] = []
        try:
            for offset in range(3):
                sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
                sockets.append(sock)
                sock.bind(("127.0.0.1", port + offset))
            return port
        except OSError:
            continue
        finally:
            for sock in sockets:
                sock.close()
    raise HFOSessionError(f"no free UDP port triple found in {PORT_RANGE}")


def _die_with_parent() -> None:
    """preexec_fn: SIGTERM this child when the thread that started it dies (Linux prctl PR_SET_PDEATHSIG)."""
    try:
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGTERM)  # 1 = PR_SET_PDEATHSIG
    except (OSError, AttributeError):  # not Linux: close() and atexit still clean up
        pass


def _kill_group(process: subprocess.Popen[bytes] | None, grace_s: float = 1.0) -> None:
    """SIGTERM the process group led by ``process``, wait up to ``grace_s`` for the leader, then SIGKILL the group."""
    if process is None:
        return
    for sig, wait_s in ((signal.SIGTERM, grace_s), (signal.SIGKILL, 5.0)):
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.killpg(process.pid, sig)
        with contextlib.suppress(subprocess.TimeoutExpired):
            process.wait(timeout=wait_s)


def _shutdown(
    workers: Sequence[tuple[subprocess.Popen[bytes] | None, socket.socket | None]],
    server: subprocess.Popen[bytes] | None,
    log: IO[bytes] | None,
    log_path: str | None,
    delete_log: bool,
    workdir: str | None,
) -> None:
    """Stop a session: ask the workers to quit, kill every process group, close the sockets and the log, remove
    the working directory."""
    for _, sock in workers:
        if sock is not None:
            with contextlib.suppress(OSError):
                sock.settimeout(0.5)
                sock.sendall(_REQUEST.pack(_QUIT, 0.0, 0.0))
            with contextlib.suppress(OSError):
                sock.close()
    for worker, _ in workers:
        if worker is not None:
            with contextlib.suppress(subprocess.TimeoutExpired):
                worker.wait(timeout=0.5)
        _kill_group(worker, grace_s=0.5)
    _kill_group(server)
    if log is not None:
        with contextlib.suppress(OSError):
            log.close()
    if delete_log and log_path is not None:
        with contextlib.suppress(OSError):
            os.unlink(log_path)
    if workdir is not None:
        shutil.rmtree(workdir, ignore_errors=True)


class SessionDown(Exception):
    """The HFO session stopped answering or reported SERVER_DOWN."""


class _Session:
    """One running HFO: ``bin/HFO``, the worker connected to it as the offense agent and, with ``still_goalie``,
    the still goalie's worker connected as the defense goalie (``args`` must then ask bin/HFO for that agent)."""

    def __init__(
        self,
        hfo_dir: Path,
        args: list[str],
        port: int | None,
        log_dir: Path | None,
        rng: np.random.Generator,
        still_goalie: bool = False,
    ) -> None:
        self.hfo_dir = hfo_dir
        self.still_goalie = bool(still_goalie)
        self.worker: subprocess.Popen[bytes] | None = None
        self.server: subprocess.Popen[bytes] | None = None
        self.sock: socket.socket | None = None
        self.goalie: subprocess.Popen[bytes] | None = None
        self.goalie_sock: socket.socket | None = None
        # the launcher's and the worker's output: kept in log_dir, else a temporary file removed at close
        if log_dir is not None:
            log_dir.mkdir(parents=True, exist_ok=True)
        handle, self.log_path = tempfile.mkstemp(
            prefix=f"hfo_session_{time.strftime('%Y%m%d-%H%M%S')}_", suffix=".log", dir=log_dir
        )
        self.log: IO[bytes] = os.fdopen(handle, "wb")
        delete_log = log_dir is None
        # bin/HFO's working directory: rcssserver writes its configuration under a literal "~" folder there
        self.workdir = tempfile.mkdtemp(prefix="hfo_run_")
        self._finalizer: weakref.finalize[Any, _Session] | None = None
        self._delete_log = delete_log
        try:
            self._start(args, port, rng)
        except BaseException:
            self.close()
            raise

    # --- start-up -------------------------------------------------------------------------------------------------
    def _start(self, args: list[str], port: int | None, rng: np.random.Generator) -> None:
        self._launch(args, port, rng)
        self.worker, self.sock = self._spawn_worker("--worker")
        if self.still_goalie:
            # bin/HFO asks for the defense agent once the offense agent has joined (its connectToServer then
            # waits for the game to start, which needs the goalie)
            self._wait_for_line(WAITING_FOR_GOALIE, "wait for the goalie agent")
            self.goalie, self.goalie_sock = self._spawn_worker("--goalie")
        self._arm_finalizer()
        self._handshake()
        if self.goalie_sock is not None:
            head = self._receive(
                _HANDSHAKE_HEAD.size,
                START_TIMEOUT_S,
                "the goalie's connection to HFO",
                self.goalie_sock,
                self.goalie,
            )
            size, _, goalie_opponents, goalie_unum = _HANDSHAKE_HEAD.unpack(head)
            self._receive(
                4 * size, START_TIMEOUT_S, "the goalie's first state", self.goalie_sock, self.goalie
            )
            if goalie_unum != 1 or goalie_opponents != 1:
                raise HFOSessionError(
                    f"the still goalie joined as unum {goalie_unum} against {goalie_opponents} opponent(s); expected"
                    f" unum 1 (HFO's goalie) against 1:\n{self.log_tail()}"
                )

    def _launch(self, args: list[str], port: int | None, rng: np.random.Generator) -> int:
        """Start bin/HFO on ``port``, else on up to PORT_TRIES free ports; the log's offset where the launch that
        worked starts (HFOSessionError when none did)."""
        for _ in range(1 if port is not None else PORT_TRIES):
            self.port = port if port is not None else _free_port(rng)
            offset = self.log.tell()
            if self._start_server(args):
                return offset
            _kill_group(self.server)
        raise HFOSessionError(f"rcssserver did not start on port {self.port}:\n{self.log_tail()}")

    def _arm_finalizer(self) -> None:
        """Stop the session's processes when it is garbage collected (once all its workers are started)."""
        self._finalizer = weakref.finalize(
            self,
            _shutdown,
            self._workers(),
            self.server,
            self.log,
            self.log_path,
            self._delete_log,
            self.workdir,
        )

    def _workers(self) -> list[tuple[subprocess.Popen[bytes] | None, socket.socket | None]]:
        return [(self.worker, self.sock), (self.goalie, self.goalie_sock)]

    def _environment(self) -> dict[str, str]:
        env = dict(os.environ)
        env["PYTHONUNBUFFERED"] = "1"  # bin/HFO's progress lines reach the log at once
        package_root = str(Path(__file__).resolve().parent.parent)  # the folder holding hfo2d
        env["PYTHONPATH"] = os.pathsep.join(p for p in (package_root, env.get("PYTHONPATH", "")) if p)
        return env

    def _start_server(self, args: list[str]) -> bool:
        """Launch bin/HFO; True once it waits for the agent, False if rcssserver failed (port taken)."""
        offset = self.log.tell()
        command = [sys.executable, str(self.hfo_dir / "bin" / "HFO"), *args, "--port", str(self.port)]
        self.log.write(("$ " + " ".join(command) + "\n").encode())
        self.log.flush()
        self.server = subprocess.Popen(
            command,
            stdin=subprocess.DEVNULL,
            stdout=self.log,
            stderr=subprocess.STDOUT,
            cwd=self.workdir,
            env=self._environment(),
            start_new_session=True,
            preexec_fn=_die_with_parent,  # noqa: PLW1509  (a one-call prctl, no Python state touched)
        )
        deadline = time.monotonic() + START_TIMEOUT_S
        while time.monotonic() < deadline:
            text = self._log_text(offset)
            if WAITING_FOR_AGENT in text:
                return True
            if SERVER_FAILED in text:
                return False
            if self.server.poll() is not None:
                if SERVER_FAILED in self._log_text(offset):
                    return False
                raise HFOSessionError(
                    f"bin/HFO exited ({self.server.returncode}) during start-up:\n{self.log_tail()}"
                )
            time.sleep(0.02)
        raise HFOSessionError(
            f"bin/HFO did not wait for an agent within {START_TIMEOUT_S:g} s:\n{self.log_tail()}"
        )

    def _wait_for_line(self, line: str, what: str) -> None:
        """Wait until bin/HFO's output holds ``line``; HFOSessionError when it exits or takes too long."""
        assert self.server is not None
        deadline = time.monotonic() + START_TIMEOUT_S
        while time.monotonic() < deadline:
            if line in self._log_text():
                return
            if self.server.poll() is not None:
                raise HFOSessionError(
                    f"bin/HFO exited ({self.server.returncode}) during start-up:\n{self.log_tail()}"
                )
            time.sleep(0.02)
        raise HFOSessionError(f"bin/HFO did not {what} within {START_TIMEOUT_S:g} s:\n{self.log_tail()}")

    def _spawn_worker(
        self, role: str, extra: Sequence[str] = ()
    ) -> tuple[subprocess.Popen[bytes], socket.socket]:
        """Start ``python -m hfo2d.real ROLE FD HFO_DIR PORT [EXTRA...]`` in its own process group, with a socket
        pair."""
        parent, child = socket.socketpair()
        command = [
            sys.executable,
            "-m",
            "hfo2d.real",
            role,
            str(child.fileno()),
            str(self.hfo_dir),
            str(self.port),
            *extra,
        ]
        try:
            worker = subprocess.Popen(
                command,
                stdin=subprocess.DEVNULL,
                stdout=self.log,
                stderr=subprocess.STDOUT,
                cwd=self.workdir,
                env=self._environment(),
                pass_fds=(child.fileno(),),
                start_new_session=True,
                preexec_fn=_die_with_parent,  # noqa: PLW1509
            )
        except BaseException:
            parent.close()
            raise
        finally:
            child.close()
        return worker, parent

    def _handshake(self) -> None:
        """The offense worker's handshake (state size, team sizes, unum) and first state."""
        head = self._receive(_HANDSHAKE_HEAD.size, START_TIMEOUT_S, "the worker's connection to HFO")
        self.state_size, self.num_teammates, self.num_opponents, self.unum = _HANDSHAKE_HEAD.unpack(head)
        # one buffer for a reply: the head, then the state (float32, aligned at 12 bytes)
        self._reply = bytearray(_REPLY_HEAD.size + 4 * self.state_size)
        self._reply_view = memoryview(self._reply)
        self.state = np.frombuffer(self._reply, dtype=np.float32, offset=_REPLY_HEAD.size)
        self._receive_into(self._reply_view[_REPLY_HEAD.size :], START_TIMEOUT_S, "the first state")

    # --- talking to the worker ----------------------------------------------------------------------------------------
    def _receive(
        self,
        size: int,
        timeout_s: float,
        what: str,
        sock: socket.socket | None = None,
        worker: subprocess.Popen[bytes] | None = None,
    ) -> bytes:
        buffer = bytearray(size)
        self._receive_into(memoryview(buffer), timeout_s, what, sock, worker)
        return bytes(buffer)

    def _receive_into(
        self,
        view: memoryview,
        timeout_s: float,
        what: str,
        sock: socket.socket | None = None,
        worker: subprocess.Popen[bytes] | None = None,
    ) -> None:
        """Fill ``view`` from a worker (default: the offense worker); SessionDown when it exits, closes the socket
        or stays silent, or when the still goalie's worker exits."""
        if sock is None:
            sock, worker = self.sock, self.worker
        assert sock is not None
        got = 0
        size = len(view)
        deadline = time.monotonic() + timeout_s
        sock.settimeout(1.0)
        while got < size:
            try:
                count = sock.recv_into(view[got:], size - got)
            except TimeoutError:
                if time.monotonic() >= deadline:
                    raise SessionDown(
                        f"no answer from HFO within {timeout_s:g} s waiting for {what}"
                    ) from None
                for name, process in (("HFO worker", worker), ("still goalie's worker", self.goalie)):
                    if process is not None and process.poll() is not None:
                        raise SessionDown(
                            f"the {name} exited ({process.returncode}) waiting for {what}"
                        ) from None
                continue
            if count == 0:
                raise SessionDown(f"the HFO worker closed the connection waiting for {what}")
            got += count

    def step(self, code: int, param0: float, param1: float) -> tuple[int, int, int]:
        """One ``act`` + ``step``: (HFO status code, side on ball, unum on ball); the state lands in ``self.state``."""
        sock = self.sock
        if sock is None:
            raise SessionDown("the session is closed")
        try:
            sock.sendall(_REQUEST.pack(code, param0, param1))
            # the common case, the whole reply in one read
            count = sock.recv_into(self._reply_view)
            if count == 0:
                raise SessionDown("the HFO worker closed the connection waiting for a step")
            if count < len(self._reply):
                self._receive_into(self._reply_view[count:], STEP_TIMEOUT_S, "a step")
        except TimeoutError:  # the first read's 1 s passed: keep waiting, as _receive_into does
            self._receive_into(self._reply_view, STEP_TIMEOUT_S - 1.0, "a step")
        except OSError as error:
            raise SessionDown(f"connection to the HFO worker failed: {error}") from error
        # A dead still goalie need not stop the server (rcssserver may stop waiting for a player it cannot
        # reach), so check it every cycle (a waitpid, microseconds).
        if self.goalie is not None and self.goalie.poll() is not None:
            raise SessionDown(f"the still goalie's worker exited ({self.goalie.returncode})")
        return _REPLY_HEAD.unpack_from(self._reply)

    # --- diagnostics, shutdown ------------------------------------------------------------------------------------
    def _log_text(self, offset: int = 0) -> str:
        try:
            with open(self.log_path, "rb") as f:
                f.seek(offset)
                return f.read().decode(errors="replace")
        except OSError:
            return ""

    def log_tail(self, lines: int = 20) -> str:
        return "\n".join(self._log_text().splitlines()[-lines:])

    def close(self) -> None:
        if self._finalizer is not None:
            self._finalizer()
        else:  # start-up failed before the finalizer existed
            _shutdown(self._workers(), self.server, self.log, self.log_path, self._delete_log, self.workdir)
        self.sock = None
        self.goalie_sock = None


# ---------------------------------------------------------------------------------------------------------------
# The environment
# ---------------------------------------------------------------------------------------------------------------
def _is_int(value: Any) -> bool:
    """An integer that is not a bool (numpy integers count)."""
    return not isinstance(value, bool) and isinstance(value, (int, np.integer))


class _SessionEnv:
    """What the real-HFO envs share (:class:`RealHFOEnv`, :class:`hfo2d.real_teams.RealTeamParallelEnv`): their
    session's options, its start on the first ``reset`` and on a new seed, its end, and the recovery when it goes
    down.

    A subclass calls :meth:`_set_session_options` in its constructor and provides ``_start_session`` (a new session,
    adopted with :meth:`_adopt_session`, whose next episode's first observation it leaves in ``_pending``) and
    ``_finish_episode`` (NOOPs until HFO ends the episode in progress: its end in ``_pending``, which stays None
    when the session went down, the reason in ``_down_reason``).
    """

    _session: _Session | None
    _pending: Any

    def _set_session_options(
        self,
        *,
        hfo_dir: str | os.PathLike[str] | None,
        noise: bool,
        seed: int | None,
        frames_per_trial: int,
        untouched_time: int,
        port: int | None,
        log_dir: str | os.PathLike[str] | None,
        fullstate: bool,
    ) -> None:
        """Check and keep the session's options (ValueError names a bad one), find the build, clear the counters."""
        for name, value in (("frames_per_trial", frames_per_trial), ("untouched_time", untouched_time)):
            if not _is_int(value) or value < 1:
                raise ValueError(f"{name} must be a positive integer, got {value!r}")
        if seed is not None:
            _check_seed(seed)
        if port is not None and (not _is_int(port) or not 1024 <= port <= 65533):
            raise ValueError(
                f"port must be an integer in [1024, 65533] (the server uses port .. port + 2), got {port!r}"
            )
        for name, flag in (("noise", noise), ("fullstate", fullstate)):
            if not isinstance(flag, (bool, np.bool_)):
                raise ValueError(f"{name} must be True or False, got {flag!r}")
        self.hfo_dir = find_hfo_dir(hfo_dir)
        self.noise = bool(noise)
        self.hfo_seed = None if seed is None else int(seed)
        self.frames_per_trial = int(frames_per_trial)
        self.untouched_time = int(untouched_time)
        self.port = None if port is None else int(port)
        self.log_dir = None if log_dir is None else Path(log_dir).expanduser().absolute()
        self.fullstate = bool(fullstate)

        self._session = None
        self._session_seed = self.hfo_seed
        self._port_rng = np.random.default_rng()
        self._pending = None  # the next episode's first observation, once HFO has sent it
        self._steps = 0
        self._episode = 0
        self._restarts = 0
        self._status = IN_GAME
        self._down_reason = "HFO reported SERVER_DOWN"
        self._session_episodes = 0  # episodes started in the running session
        self._frame_limit_steps = self.frames_per_trial - 1

    def _start_session(self) -> None:
        raise NotImplementedError

    def _finish_episode(self) -> None:
        raise NotImplementedError

    @property
    def session_port(self) -> int | None:
        """The UDP port of the running session (None before the first reset)."""
        return None if self._session is None else self._session.port

    @property
    def status(self) -> str:
        """Status of the last step ("IN_GAME" after reset, "SERVER_DOWN" for a session that went down)."""
        return self._status

    @property
    def steps(self) -> int:
        """Steps taken in the current episode."""
        return self._steps

    def _bin_hfo_args(self, seed: int | None, **teams: Any) -> list[str]:
        """:func:`bin_hfo_args` for ``teams`` (its team counts and ``agent_play_goalie``) with this env's
        options."""
        return bin_hfo_args(
            **teams,
            frames_per_trial=self.frames_per_trial,
            untouched_time=self.untouched_time,
            fullstate=self.fullstate,
            noise=self.noise,
            seed=seed,
            log_dir=self.log_dir,
        )

    def _adopt_session(self, session: _Session) -> None:
        """``session`` (checked) becomes the running one; it is closed at interpreter exit at the latest."""
        self._session = session
        self._session_episodes = 0
        _LIVE_ENVS.add(self)

    def _close_session(self) -> None:
        if self._session is not None:
            self._session.close()
            self._session = None
        self._pending = None

    def _session_down(self) -> None:
        tail = self._session.log_tail(8) if self._session is not None else ""
        warnings.warn(
            f"the HFO session went down in episode {self._episode} ({self._down_reason}); the next reset() starts "
            "a new one." + (f" Last lines of its log:\n{tail}" if tail else ""),
            RuntimeWarning,
            stacklevel=3,
        )
        self._close_session()
        self._restarts += 1
        self._down_reason = "HFO reported SERVER_DOWN"

    def _next_episode(self, seed: int | None) -> Any:
        """The first observation of the next episode, which this starts: a new session on the first call, for a
        ``seed`` other than the running session's, and after a session went down; else NOOPs to the end of the
        episode in progress. The episode's counters are set."""
        if seed is not None:
            hfo_seed = int(seed) % (MAX_SEED + 1)  # rcssserver's random_seed is an int
            if self._session is None or hfo_seed != self._session_seed:
                self._session_seed = hfo_seed
                self._close_session()
        if self._session is None:
            self._start_session()
        elif self._pending is None:
            self._finish_episode()
            if self._pending is None:  # the session went down while the episode was being finished
                self._session_down()
                self._start_session()
        assert self._pending is not None
        pending, self._pending = self._pending, None
        self._steps = 0
        self._episode += 1
        # Steps of an episode that HFO ends at frames_per_trial (see the module docstring); HFO's referee starts
        # a session's first episode one cycle earlier relative to its first observation.
        self._frame_limit_steps = self.frames_per_trial - (2 if self._session_episodes == 0 else 1)
        self._session_episodes += 1
        self._status = IN_GAME
        return pending

    def _stop(self) -> None:
        """Close the session; the env is no longer closed at exit."""
        self._close_session()
        _LIVE_ENVS.discard(self)


class RealHFOEnv(_SessionEnv, gym.Env):
    """HFO's 1v0 / 1v1 task in the real rcssserver, with hfo2d's observations, actions and rewards.

    Tasks (``task``): ``"empty_goal"`` (``HFO/RealEmptyGoal-v0``), ``"keeper"`` (``HFO/RealKeeper-v0``: HFO's
    agent2d goalie, ``bin/HFO --defense-npcs 1``) and ``"static_keeper"`` (``HFO/RealStaticKeeper-v0``: a goalie
    that stands still on the goal line facing the field, as hfo2d's ``HFO/StaticKeeper-v0``: a second worker
    connected as HFO's defense goalie, ``bin/HFO --defense-agents 1``; see the module docstring).

    Observation: ``Box(-1, 1, (58,), float32)``, ``(66,)`` with the goalie: hfo2d's paper-era features (see
    :class:`hfo2d.hfo_env.HFOEnv`), converted from HFO master's 59 / 68 by :func:`hfo2d.features.paper_from_hfo`.
    Without ``fullstate`` they come from librcsc's noisy world model (valid flags may be off).

    Action (``action_format``): hfo2d's ``"flat"`` 8-vector or gym-soccer's ``"parameterized"`` tuple, parsed by
    :class:`~hfo2d.hfo_env.HFOEnv`'s own code (largest preference, ties to the first; power [0, 100], direction
    [-180, 180] degrees; invalid actions raise ValueError) and sent as HFO's ``act(DASH, power, dir)``,
    ``act(TURN, dir)`` or ``act(KICK, power, dir)``.

    Reward (``reward``): hfo2d's rewards (:mod:`hfo2d.reward`), computed from the features.

    Episodes: HFO's referee ends them (GOAL, CAPTURED_BY_DEFENSE, OUT_OF_BOUNDS, OUT_OF_TIME after
    ``untouched_time`` untouched cycles: ``terminated``; OUT_OF_TIME at ``frames_per_trial``: ``truncated``). HFO
    places the players itself; ``seed`` (or the seed given to ``reset``, which starts a new session when it differs
    from the running one's) is HFO's ``--seed`` (rcssserver's ``server::random_seed``). It fixes the sequence of
    start positions, not the noise nor the state of the players at kick-off, so two runs of one seed are two
    samples (see the module docstring).
    ``reset(options=...)`` is not supported. A ``reset`` in the middle of an episode plays NOOPs until HFO ends it.
    See the module docstring for the timing of first and last observations.

    Info: ``status`` (hfo2d's names, or ``"SERVER_DOWN"``), ``is_success``, ``kickable``, ``player``, ``ball`` and
    ``keeper`` (global state recovered from the features, :func:`state_from_hfo_features`), ``player_on_ball``
    (HFO's: side letter "L" / "R" / "U" and unum), ``episode`` (episodes started by this env, from 1),
    ``session_restarts``; after a step also ``reward_terms``, ``action``, ``action_success`` (HFO's last-action flag;
    on an episode's last step, when HFO's flag is lost, a KICK counts as executed when the ball was kickable),
    ``kick_power`` and ``stale_observation`` (True on an episode's last step).

    Args:
        task: one of TASKS.
        hfo_dir: the HFO build (folder with ``bin/HFO``); None: ``$HFO_DIR``.
        action_format: "flat" or "parameterized".
        reward: one of hfo2d's REWARD_NAMES.
        noise: False runs HFO ``--deterministic`` (no player, ball, kick or wind noise).
        seed: HFO's ``--seed`` (start positions), an int in [0, 2**31 - 1]; None: the seed of the first
            ``reset(seed=...)``, else HFO's own (time).
        frames_per_trial: HFO's ``--frames-per-trial``.
        untouched_time: HFO's ``--untouched-time``.
        port: the server's UDP port (it also uses the next two); None: a free one.
        log_dir: HFO writes its game logs (.rcg, .rcl) and its launcher's output there; None: ``--no-logging``.
        fullstate: HFO's ``--fullstate`` (exact features); False: the agent's noisy visual world model.
        render_mode: only None (HFO's monitor is not started).
    """

    metadata = {"render_modes": []}

    _parse_action = HFOEnv._parse_action  # hfo2d's action parsing, shared so that the two cannot drift apart
    _parse_flat_action = HFOEnv._parse_flat_action
    _parse_parameterized_action = HFOEnv._parse_parameterized_action

    def __init__(
        self,
        task: str = "empty_goal",
        hfo_dir: str | os.PathLike[str] | None = None,
        action_format: str = "flat",
        reward: str = "shaped",
        noise: bool = True,
        seed: int | None = None,
        frames_per_trial: int = DEFAULT_FRAMES_PER_TRIAL,
        untouched_time: int = DEFAULT_UNTOUCHED_TIME,
        port: int | None = None,
        log_dir: str | os.PathLike[str] | None = None,
        fullstate: bool = True,
        render_mode: str | None = None,
    ) -> None:
        if task not in TASKS:
            raise ValueError(f"unknown task {task!r}; choose one of {TASKS}")
        if action_format not in ACTION_FORMATS:
            raise ValueError(f"unknown action_format {action_format!r}; choose one of {ACTION_FORMATS}")
        if reward not in REWARD_NAMES:
            raise ValueError(f"unknown reward {reward!r}; choose one of {REWARD_NAMES}")
        if render_mode is not None:
            raise ValueError(
                f"RealHFOEnv does not render (render_mode={render_mode!r}); use HFO's own monitor"
            )
        self._set_session_options(
            hfo_dir=hfo_dir,
            noise=noise,
            seed=seed,
            frames_per_trial=frames_per_trial,
            untouched_time=untouched_time,
            port=port,
            log_dir=log_dir,
            fullstate=fullstate,
        )
        self.task = task
        self.render_mode = render_mode
        self.action_format = action_format
        self.reward_name = reward
        self.has_keeper = task != "empty_goal"
        self.num_opponents = DEFENSE_NPCS[task] + DEFENSE_AGENTS[task]
        self._reward_fn = make_reward(reward)

        self.observation_space = spaces.Box(
            -1.0, 1.0, shape=(num_features(0, self.num_opponents),), dtype=np.float32
        )
        if action_format == "flat":
            self.action_space: spaces.Space = hfo_flat_action_space()
        else:
            power_direction = spaces.Box(
                np.array([POWER_MIN, DIRECTION_MIN], dtype=np.float32),
                np.array([POWER_MAX, DIRECTION_MAX], dtype=np.float32),
                dtype=np.float32,
            )
            turn = spaces.Box(
                np.array([DIRECTION_MIN], dtype=np.float32),
                np.array([DIRECTION_MAX], dtype=np.float32),
                dtype=np.float32,
            )
            self.action_space = spaces.Tuple((spaces.Discrete(3), power_direction, turn, power_direction))

        # _pending (set above): the next episode's first (HFO state, side on ball, unum on ball)
        self._raw: list[float] = []  # HFO master's vector of the current observation
        self._features: list[float] = []
        self._on_ball: tuple[str, int] = ("U", -1)
        self._needs_reset = True

    # --- the HFO session ------------------------------------------------------------------------------------------
    def hfo_args(self, seed: int | None = None) -> list[str]:
        """bin/HFO's arguments for this env (less ``--port``), with ``seed`` as ``--seed`` when not None."""
        return self._bin_hfo_args(
            seed,
            offense_agents=1,
            defense_npcs=DEFENSE_NPCS[self.task],
            # the still goalie: a defense agent playing goalie (unum 1)
            defense_agents=DEFENSE_AGENTS[self.task],
            agent_play_goalie=DEFENSE_AGENTS[self.task] > 0,
        )

    def _start_session(self) -> None:
        self._close_session()
        session = _Session(
            self.hfo_dir,
            self.hfo_args(self._session_seed),
            self.port,
            self.log_dir,
            self._port_rng,
            still_goalie=DEFENSE_AGENTS[self.task] > 0,
        )
        expected = hfo_num_features(0, self.num_opponents)
        if session.state_size != expected or session.num_opponents != self.num_opponents:
            session.close()
            raise HFOSessionError(
                f"HFO gave {session.state_size} features for {session.num_opponents} opponent(s); expected {expected}"
                f" for {self.num_opponents} (is this HFO master, b8b2a1d or later?)"
            )
        self._adopt_session(session)
        # The first observation precedes the placement; play the NOOPs HFO plays between later episodes.
        pending: tuple[list[float], int, int] | None = None
        for _ in range(START_NOOPS):
            status, side, unum = self._hfo_step(HFO_NOOP, 0.0, 0.0)
            pending = (session.state.tolist(), side, unum)
            if status == HFO_SERVER_DOWN:
                raise HFOSessionError(f"HFO went down while starting:\n{session.log_tail()}")
        self._pending = pending

    def _hfo_step(self, code: int, param0: float, param1: float) -> tuple[int, int, int]:
        assert self._session is not None
        try:
            return self._session.step(code, param0, param1)
        except SessionDown as error:
            self._down_reason = str(error)
            return HFO_SERVER_DOWN, 0, -1

    # --- Gymnasium API ----------------------------------------------------------------------------------------------
    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        """Start the next HFO episode (the session itself on the first call, or when ``seed`` asks for another)."""
        super().reset(seed=seed)
        if options:
            raise ValueError(
                "RealHFOEnv cannot place players by hand: HFO's referee places them (no reset options)"
            )
        raw, side, unum = self._next_episode(seed)
        self._set_current(raw, side, unum)
        self._needs_reset = False
        self._reward_fn.reset(self._features)
        info = self._info()
        info["reward_terms"] = dict.fromkeys(self._reward_fn.term_names, 0.0)
        return np.array(self._features, dtype=np.float32), info

    def _finish_episode(self) -> None:
        """NOOPs until HFO ends the episode in progress (at most ``frames_per_trial`` cycles); its end becomes pending."""
        assert self._session is not None
        for _ in range(self.frames_per_trial + START_NOOPS + 1):
            status, side, unum = self._hfo_step(HFO_NOOP, 0.0, 0.0)
            if status == HFO_SERVER_DOWN:
                return
            if status != 0:
                self._pending = (self._session.state.tolist(), side, unum)
                return
        self._down_reason = f"HFO did not end an episode within {self.frames_per_trial} NOOP cycles"

    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        """One server cycle: hfo2d's action as HFO's ``act``, then HFO's ``step``."""
        if self._needs_reset:
            raise RuntimeError("call reset() before step()")
        kind, power, direction = self._parse_action(action)
        code, param0, param1 = hfo_command(kind, power, direction)
        was_kickable = self._features[KICKABLE] > 0.0
        status_code, side, unum = self._hfo_step(code, param0, param1)
        self._steps += 1
        if status_code == HFO_SERVER_DOWN or not 0 <= status_code < len(STATUS_NAMES):
            self._session_down()
            self._status = SERVER_DOWN
            self._needs_reset = True
            info = self._info()
            info.update(
                reward_terms={},
                action=ACTION_NAMES[kind],
                action_success=False,
                kick_power=0.0,
                stale_observation=True,
            )
            return np.array(self._features, dtype=np.float32), 0.0, False, True, info
        status = STATUS_NAMES[status_code]
        assert self._session is not None
        truncated = False
        if status == IN_GAME:
            self._set_current(self._session.state.tolist(), side, unum)
            success = self._raw[-1] > 0.0  # HFO master's last entry: the last action succeeded (+1 / -1)
            terminated = False
        else:
            # HFO's step() has already played three NOOPs into the next episode: keep that state for reset().
            self._pending = (self._session.state.tolist(), side, unum)
            success = kind != KICK or was_kickable
            truncated = status == OUT_OF_TIME and self._steps >= self._frame_limit_steps
            terminated = not truncated
            self._needs_reset = True
        self._status = status
        reward, terms = self._reward_fn(self._features, status, terminated or truncated)
        info = self._info()
        info["reward_terms"] = terms
        info["action"] = ACTION_NAMES[kind]
        info["action_success"] = bool(success)
        info["kick_power"] = min(max(power, POWER_MIN), POWER_MAX) if kind == KICK and success else 0.0
        info["stale_observation"] = status != IN_GAME
        return np.array(self._features, dtype=np.float32), float(reward), terminated, truncated, info

    def close(self) -> None:
        """Stop the HFO session (server, trainer, NPCs, worker)."""
        self._stop()
        self._needs_reset = True

    # --- internals ------------------------------------------------------------------------------------------------
    def _set_current(self, raw: list[float], side: int, unum: int) -> None:
        self._raw = raw
        self._features = paper_from_hfo(raw, 0, self.num_opponents)
        self._on_ball = (SIDE_LETTERS.get(side, "U"), int(unum))

    def _info(self) -> dict[str, Any]:
        info: dict[str, Any] = {
            "status": self._status,
            "is_success": self._status == GOAL,
            "kickable": self._features[KICKABLE] > 0.0,
        }
        info.update(state_from_hfo_features(self._raw, self.num_opponents))
        info["player_on_ball"] = self._on_ball
        info["episode"] = self._episode
        info["session_restarts"] = self._restarts
        return info


def _check_seed(seed: Any) -> None:
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not 0 <= seed <= MAX_SEED:
        raise ValueError(f"seed must be an integer in [0, {MAX_SEED}] (HFO's --seed), got {seed!r}")


#: Envs with a running session (RealHFOEnv's and hfo2d.real_teams'), closed at interpreter exit (their sessions'
#: finalizers would also run).
_LIVE_ENVS: weakref.WeakSet[_SessionEnv] = weakref.WeakSet()


@atexit.register
def _close_live_envs() -> None:
    for env in list(_LIVE_ENVS):
        with contextlib.suppress(Exception):
            env.close()


# ---------------------------------------------------------------------------------------------------------------
# The worker process: ``python -m hfo2d.real --worker FD HFO_DIR PORT``
# ---------------------------------------------------------------------------------------------------------------
def _connect_worker(
    argv: Sequence[str], team: str, play_goalie: bool, feature_set: int = HFO_LOW_LEVEL_FEATURE_SET
) -> tuple[socket.socket, Any, Any]:
    """A worker's start: its socket (argv FD), HFO's ctypes binding from argv HFO_DIR, and one connectToServer on
    argv PORT with ``feature_set`` (it exits the process when it fails; the env then sees the socket close)."""
    fd, hfo_dir, port = int(argv[0]), argv[1], int(argv[2])
    sock = socket.socket(fileno=fd)
    sys.path.insert(0, hfo_dir)
    import hfo  # HFO's ctypes binding (DEST/HFO/hfo), loads libhfo_c.so

    env = hfo.HFOEnvironment()
    env.connectToServer(
        feature_set,
        os.path.join(hfo_dir, HFO_CONFIG_SUBDIR),
        port,
        "localhost",
        team,
        play_goalie,
        "",
    )
    return sock, hfo, env


def worker_main(argv: Sequence[str]) -> int:
    """Connect to the HFO server on PORT and serve act + step requests on socket FD.

    ``argv`` is ``FD HFO_DIR PORT`` (RealHFOEnv's offense agent: team base_left, low-level features, not the
    goalie) or ``FD HFO_DIR PORT TEAM FEATURE_SET PLAY_GOALIE`` (hfo2d.real_teams: any agent of a team game;
    FEATURE_SET is HFO's code, PLAY_GOALIE 0 or 1). A request's code is HFO's action code, sent with as many of
    its two parameters as HFO's act() takes (HFO_ACTION_PARAMS); any other code plays a NOOP.
    """
    team, feature_set, play_goalie = HFO_TEAM_NAME, HFO_LOW_LEVEL_FEATURE_SET, False
    if len(argv) == 6:
        team, feature_set, play_goalie = argv[3], int(argv[4]), argv[5] == "1"
    sock, hfo, env = _connect_worker(argv[:3], team, play_goalie=play_goalie, feature_set=feature_set)
    size = env.getStateSize()
    reply = bytearray(_REPLY_HEAD.size + 4 * size)  # head + state, sent in one piece
    state = np.frombuffer(reply, dtype=np.float32, offset=_REPLY_HEAD.size)
    env.getState(state)
    sock.sendall(_HANDSHAKE_HEAD.pack(size, env.getNumTeammates(), env.getNumOpponents(), env.getUnum()))
    sock.sendall(memoryview(reply)[_REPLY_HEAD.size :])
    request = bytearray(_REQUEST.size)
    view = memoryview(request)
    while True:
        got = 0
        while got < _REQUEST.size:
            count = sock.recv_into(view[got:], _REQUEST.size - got)
            if count == 0:  # the env went away
                return 0
            got += count
        code, param0, param1 = _REQUEST.unpack(request)
        if code == _QUIT:
            return 0
        params = HFO_ACTION_PARAMS.get(code)
        if params is None:
            env.act(HFO_NOOP)
        else:
            env.act(code, *(param0, param1)[:params])
        status = env.step()
        env.getState(state)
        on_ball = env.playerOnBall()
        _REPLY_HEAD.pack_into(reply, 0, status, on_ball.side, on_ball.unum)
        sock.sendall(reply)
        if status == HFO_SERVER_DOWN:
            return 1


# ---------------------------------------------------------------------------------------------------------------
# The still goalie's worker: ``python -m hfo2d.real --goalie FD HFO_DIR PORT``
# ---------------------------------------------------------------------------------------------------------------
def still_goalie_command(state: Sequence[float]) -> tuple[int, float]:
    """The still goalie's command from its own HFO master features: ``(HFO_TURN, moment)`` to face the field while
    its body is more than GOALIE_TURN_THRESHOLD_DEG off GOALIE_OWN_BODY_DEG, else ``(HFO_NOOP, 0.0)``.

    The moment is the body's error, in (-180, 180]: at rest librcsc's doTurn sends it as it is (its command moment
    is the angle times 1 + inertia_moment * speed, rounded to 0.001; librcsc action_effector.cpp
    ActionEffector::setTurn). Without a valid self (no fullstate, not yet localised) the goalie waits (NOOP).
    """
    if state[SELF_POS_VALID] <= 0.0:
        return HFO_NOOP, 0.0
    body = math.degrees(math.atan2(float(state[SELF_BODY_SIN]), float(state[SELF_BODY_COS])))
    error = (GOALIE_OWN_BODY_DEG - body + 180.0) % 360.0 - 180.0  # in [-180, 180)
    if abs(error) <= GOALIE_TURN_THRESHOLD_DEG:
        return HFO_NOOP, 0.0
    return HFO_TURN, 180.0 if error == -180.0 else error


def goalie_main(argv: Sequence[str]) -> int:
    """Connect to the HFO server on PORT as the defense goalie and play the still goalie until the env goes away.

    After the handshake (the offense worker's format) it plays :func:`still_goalie_command` every cycle, on its
    own: HFO's ``step()`` returns once the (sync-mode) server has played the cycle, which it does once the
    learning agent has sent its command too. It stops when the socket closes or says quit, or at SERVER_DOWN.
    Every turn is printed (the session's log).
    """
    import select

    # play_goalie: rcssserver's goalie, which HFO's referee places at (52.5, 0)
    sock, hfo, env = _connect_worker(argv, HFO_DEFENSE_TEAM_NAME, play_goalie=True)
    size = env.getStateSize()
    state = np.zeros(size, dtype=np.float32)
    env.getState(state)
    sock.sendall(_HANDSHAKE_HEAD.pack(size, env.getNumTeammates(), env.getNumOpponents(), env.getUnum()))
    sock.sendall(state.tobytes())
    episode = cycle = 0
    while True:
        if select.select([sock], [], [], 0.0)[0]:  # the env closed the socket or asked to quit
            data = sock.recv(_REQUEST.size)
            if not data or _REQUEST.unpack(data.ljust(_REQUEST.size, b"\0"))[0] == _QUIT:
                return 0
        code, moment = still_goalie_command(state)
        if code == HFO_TURN:
            body = math.degrees(math.atan2(float(state[SELF_BODY_SIN]), float(state[SELF_BODY_COS])))
            print(
                f"still goalie: episode {episode} cycle {cycle}: body {body:.3f} (own frame), turn {moment:.3f}"
            )
            env.act(HFO_TURN, moment)
        else:
            env.act(HFO_NOOP)
        status = env.step()
        cycle += 1
        env.getState(state)
        if status == HFO_SERVER_DOWN:
            return 1
        if status != 0:
            episode += 1
            cycle = 0


if __name__ == "__main__":
    if len(sys.argv) in (5, 8) and sys.argv[1] == "--worker":
        sys.exit(worker_main(sys.argv[2:]))
    if len(sys.argv) == 5 and sys.argv[1] == "--goalie":
        sys.exit(goalie_main(sys.argv[2:]))
    print(
        "usage: python -m hfo2d.real --worker|--goalie FD HFO_DIR PORT, or --worker FD HFO_DIR PORT TEAM"
        " FEATURE_SET PLAY_GOALIE (started by RealHFOEnv and hfo2d.real_teams)",
        file=sys.stderr,
    )
    sys.exit(2)
