"""Tests of the real-HFO backend (hfo2d.real).

Always run (no HFO build needed): registration, the missing-build error, argument validation, bin/HFO's command
line, spaces and action mapping against HFOEnv, the state recovered from HFO master's features, and the env's
episode plumbing over a fake session that replays hfo2d's simulator as HFO would serve it.

The real HFO (a build in ``$HFO_DIR``, made by ``tools/real_hfo/build.sh``) is run only inside a loopback-only
network namespace (``HFO_DIR=... tools/real_hfo/loopback.sh python -m pytest tests/test_real_hfo.py``) or with
``HFO_TESTS=1``; otherwise those tests skip.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
import time
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

import hfo2d  # noqa: F401  (registers the ids)
from hfo2d import real
from hfo2d.features import hfo_feature_list
from hfo2d.heuristic import heuristic
from hfo2d.hfo_env import DASH, KICK, TURN, HFOEnv

STATUS_CODES = {name: code for code, name in enumerate(real.STATUS_NAMES)}


@pytest.fixture
def fake_build(tmp_path: Path) -> Path:
    """A directory that looks like an HFO build (the files find_hfo_dir checks), with nothing runnable in it."""
    for name in ("bin/HFO", "hfo/hfo.py", "hfo/libhfo_c.so"):
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text("")
    return tmp_path


# ---------------------------------------------------------------------------------------------------------------
# Import, registration, the build
# ---------------------------------------------------------------------------------------------------------------
def test_import_needs_neither_torch_nor_a_build() -> None:
    code = (
        "import sys, hfo2d, hfo2d.real\n"
        "assert 'torch' not in sys.modules, 'torch'\n"
        "assert 'hfo' not in sys.modules, 'hfo'\n"
        "assert not any('libhfo' in m for m in sys.modules)\n"
    )
    env = {k: v for k, v in os.environ.items() if k != real.HFO_DIR_ENV}
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=60)
    assert result.returncode == 0, result.stderr


def test_registered_lazily() -> None:
    ids = (
        ("HFO/RealEmptyGoal-v0", "empty_goal"),
        ("HFO/RealStaticKeeper-v0", "static_keeper"),
        ("HFO/RealKeeper-v0", "keeper"),
    )
    assert set(hfo2d.REAL_ENV_IDS.items()) == set(ids)
    for env_id, task in ids:
        spec = gym.spec(env_id)
        assert spec.entry_point == "hfo2d.real:RealHFOEnv"
        assert spec.kwargs == {"task": task}
        assert spec.max_episode_steps is None


def test_missing_build_says_how_to_build(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.delenv(real.HFO_DIR_ENV, raising=False)
    with pytest.raises(real.HFOBuildNotFound, match="HFO_DIR") as error:
        gym.make("HFO/RealKeeper-v0")
    message = str(error.value)
    for needle in ("build.sh", "LARG/HFO", "mhauskn/rcssserver", "mhauskn/librcsc", "hfo_dir"):
        assert needle in message
    monkeypatch.setenv(real.HFO_DIR_ENV, str(tmp_path))
    with pytest.raises(real.HFOBuildNotFound, match="bin/HFO, hfo/hfo.py, hfo/libhfo_c.so"):
        real.RealHFOEnv()
    (tmp_path / "bin").mkdir()
    (tmp_path / "bin" / "HFO").write_text("")
    with pytest.raises(FileNotFoundError, match=r"missing hfo/hfo.py, hfo/libhfo_c.so\)"):
        real.find_hfo_dir()


def test_build_from_env_var(monkeypatch: pytest.MonkeyPatch, fake_build: Path) -> None:
    monkeypatch.setenv(real.HFO_DIR_ENV, str(fake_build))
    env = gym.make("HFO/RealEmptyGoal-v0")
    assert env.unwrapped.hfo_dir == fake_build.resolve()
    assert env.unwrapped.session_port is None  # nothing started before reset
    env.close()


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"task": "penalty"}, "unknown task"),
        ({"action_format": "discrete"}, "unknown action_format"),
        ({"reward": "dense"}, "unknown reward"),
        ({"frames_per_trial": 0}, "frames_per_trial"),
        ({"untouched_time": 2.5}, "untouched_time"),
        ({"seed": -1}, "seed"),
        ({"seed": 2**31}, "seed"),
        ({"seed": True}, "seed"),
        ({"port": 80}, "port"),
        ({"port": 65534}, "port"),
        ({"noise": "yes"}, "noise"),
        ({"fullstate": 1}, "fullstate"),
        ({"render_mode": "human"}, "render"),
    ],
)
def test_argument_validation(fake_build: Path, kwargs: dict[str, Any], match: str) -> None:
    with pytest.raises(ValueError, match=match):
        real.RealHFOEnv(hfo_dir=fake_build, **kwargs)


def test_hfo_command_line(fake_build: Path) -> None:
    env = real.RealHFOEnv(task="keeper", hfo_dir=fake_build)
    args = env.hfo_args()
    assert args[:1] == ["--headless"]
    pairs = {args[i]: args[i + 1] for i in range(len(args) - 1) if not args[i + 1].startswith("--")}
    assert pairs["--offense-agents"] == "1"
    assert pairs["--defense-npcs"] == "1"
    assert pairs["--frames-per-trial"] == "500"
    assert pairs["--untouched-time"] == "100"
    assert int(pairs["--trials"]) >= 10**9
    assert "--fullstate" in args and "--no-logging" in args
    assert "--deterministic" not in args and "--seed" not in args
    env = real.RealHFOEnv(
        task="empty_goal",
        hfo_dir=fake_build,
        noise=False,
        fullstate=False,
        frames_per_trial=300,
        untouched_time=50,
        log_dir=fake_build / "logs",
    )
    args = env.hfo_args(seed=7)
    pairs = {args[i]: args[i + 1] for i in range(len(args) - 1) if not args[i + 1].startswith("--")}
    assert pairs["--defense-npcs"] == "0"
    assert pairs["--frames-per-trial"] == "300" and pairs["--untouched-time"] == "50"
    assert pairs["--seed"] == "7" and pairs["--log-dir"] == str(fake_build / "logs")
    assert "--deterministic" in args and "--fullstate" not in args and "--no-logging" not in args
    assert "--defense-agents" not in args and "--agent-play-goalie" not in args
    # the still goalie: no NPC, one defense agent playing goalie (unum 1, placed at (52.5, 0) by HFO's referee)
    args = real.RealHFOEnv(task="static_keeper", hfo_dir=fake_build).hfo_args()
    pairs = {args[i]: args[i + 1] for i in range(len(args) - 1) if not args[i + 1].startswith("--")}
    assert (
        pairs["--defense-npcs"] == "0" and pairs["--defense-agents"] == "1" and "--agent-play-goalie" in args
    )
    assert pairs["--offense-agents"] == "1" and "--fullstate" in args
    assert "--defense-agents" not in real.RealHFOEnv(task="keeper", hfo_dir=fake_build).hfo_args()


def test_bin_hfo_args_leaves_zero_counts_to_bin_hfo() -> None:
    # bin/HFO's parseArgs defaults every team count to 0: a zero --offense-npcs / --defense-agents is left out
    args = real.bin_hfo_args(offense_agents=2, defense_npcs=1, seed=None, log_dir=None)
    assert "--offense-npcs" not in args and "--defense-agents" not in args
    assert args[args.index("--defense-npcs") + 1] == "1" and args[args.index("--offense-agents") + 1] == "2"
    args = real.bin_hfo_args(offense_agents=0, offense_npcs=3, defense_agents=2, defense_npcs=0, seed=5)
    pairs = {args[i]: args[i + 1] for i in range(len(args) - 1) if not args[i + 1].startswith("--")}
    assert pairs["--offense-npcs"] == "3" and pairs["--defense-agents"] == "2" and pairs["--seed"] == "5"
    assert pairs["--trials"] == str(real.SESSION_TRIALS)


# ---------------------------------------------------------------------------------------------------------------
# Spaces and actions: hfo2d's
# ---------------------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("action_format", ["flat", "parameterized"])
@pytest.mark.parametrize(
    ("task", "hfo2d_task"),
    [("empty_goal", "empty_goal"), ("static_keeper", "static_keeper"), ("keeper", "keeper")],
)
def test_spaces_are_hfo2ds(fake_build: Path, action_format: str, task: str, hfo2d_task: str) -> None:
    env = real.RealHFOEnv(task=task, hfo_dir=fake_build, action_format=action_format)
    reference = HFOEnv(task=hfo2d_task, action_format=action_format)
    assert env.observation_space == reference.observation_space
    assert env.action_space == reference.action_space


def test_action_mapping_equals_hfoenvs(fake_build: Path) -> None:
    rng = np.random.default_rng(3)
    for action_format in ("flat", "parameterized"):
        env = real.RealHFOEnv(hfo_dir=fake_build, action_format=action_format)
        reference = HFOEnv(action_format=action_format)
        env.action_space.seed(5)
        kinds = set()
        for _ in range(300):
            action = env.action_space.sample()
            parsed = env._parse_action(action)
            assert parsed == reference._parse_action(action)
            kinds.add(parsed[0])
        assert kinds == {DASH, TURN, KICK}
        # invalid actions are refused the same way
        for bad in (np.full(8, 1.5, dtype=np.float32), (3, [0, 0], [0], [0, 0])):
            with pytest.raises(ValueError):
                reference._parse_action(bad)
            with pytest.raises(ValueError):
                env._parse_action(bad)
    flat = rng.random(8, dtype=np.float32)
    flat[:3] = (0.1, 0.2, 0.9)  # KICK
    kind, power, direction = real.RealHFOEnv(hfo_dir=fake_build)._parse_action(flat)
    assert (kind, power, direction) == (KICK, 100.0 * float(flat[6]), -180.0 + 360.0 * float(flat[7]))


def test_hfo_commands() -> None:
    # HFO's action codes: DASH 0 (power, direction), TURN 1 (direction), KICK 3 (power, direction)
    assert real.hfo_command(DASH, 40.0, -90.0) == (0, 40.0, -90.0)
    assert real.hfo_command(TURN, 0.0, 30.0) == (1, 30.0, 0.0)
    assert real.hfo_command(KICK, 100.0, 12.5) == (3, 100.0, 12.5)


# ---------------------------------------------------------------------------------------------------------------
# The still goalie
# ---------------------------------------------------------------------------------------------------------------
def _goalie_state(body_deg: float, valid: bool = True) -> list[float]:
    """The goalie's own HFO master vector (68 entries) with only the self-valid flag and the body angle set."""
    state = [0.0] * real.hfo_num_features(0, 1)
    state[0] = 1.0 if valid else -1.0
    state[5], state[6] = math.sin(math.radians(body_deg)), math.cos(math.radians(body_deg))
    return state


def test_still_goalie_faces_the_field_and_stays() -> None:
    noop = (real.HFO_NOOP, 0.0)
    assert real.GOALIE_OWN_BODY_DEG == 0.0 and real.GOALIE_BODY_DEG == 180.0
    for body in (0.0, 0.49, -0.49, 360.0):  # facing the field: NOOP
        assert real.still_goalie_command(_goalie_state(body)) == noop
    for body, moment in (
        (180.0, 180.0),
        (-180.0, 180.0),
        (90.0, -90.0),
        (-30.0, 30.0),
        (0.6, -0.6),
        (-179.0, 179.0),
    ):
        code, turn = real.still_goalie_command(_goalie_state(body))
        assert code == real.HFO_TURN and turn == pytest.approx(moment, abs=1e-6), body
    assert real.still_goalie_command(_goalie_state(90.0, valid=False)) == noop  # not localised: wait
    # rcssserver's turn at rest: body += (1 + U(-player_rand, player_rand)) * moment, player_rand 0.1
    rng = np.random.default_rng(0)
    worst = 0
    for start in np.linspace(-180.0, 180.0, 73):
        body = float(start)
        turns = 0
        while (command := real.still_goalie_command(_goalie_state(body)))[0] == real.HFO_TURN and turns < 10:
            body = (body + (1.0 + rng.uniform(-0.1, 0.1)) * command[1] + 180.0) % 360.0 - 180.0
            turns += 1
        assert abs(body) <= real.GOALIE_TURN_THRESHOLD_DEG
        worst = max(worst, turns)
    assert (
        worst == 3
    )  # from its initial body (facing its own goal) the goalie faces the field in three cycles


def test_static_keeper_state_is_hfo2ds_static_keeper() -> None:
    # the learning agent's view of hfo2d's still goalie, as HFO master sends it, recovers the goalie at (52.5, 0)
    # facing the field (global 180 degrees)
    sim = HFOEnv(task="static_keeper")
    sim.reset(seed=2)
    state = real.state_from_hfo_features(_hfo_vector(sim).tolist(), 1)
    keeper = state["keeper"]
    assert keeper is not None
    assert keeper[:2] == pytest.approx((52.5, 0.0), abs=2e-3)
    assert abs((keeper[4] - real.GOALIE_BODY_DEG + 180.0) % 360.0 - 180.0) < 1e-3


# ---------------------------------------------------------------------------------------------------------------
# The state behind HFO master's features
# ---------------------------------------------------------------------------------------------------------------
def _hfo_vector(sim: HFOEnv, success: bool = True) -> np.ndarray:
    vector = hfo_feature_list(sim.agent, sim.world.ball, sim._kickable_distance, (), sim._opponents, success)
    return np.asarray(vector, dtype=np.float32)  # HFO sends float32


def _max_error(a: Any, b: Any) -> float:
    return max(abs(x - y) for x, y in zip(a, b, strict=True))


@pytest.mark.parametrize("task", ["empty_goal", "keeper"])
def test_state_from_hfo_features(task: str) -> None:
    sim = HFOEnv(task=task)
    sim.reset(seed=11)
    rng = np.random.default_rng(11)
    checked = 0
    place = True
    position_error = velocity_error = 0.0
    for step in range(240):
        if place or step % 30 == 0:  # spread the states over the half, the ball moving
            place = False
            x, y = rng.uniform(-1, 52.5), rng.uniform(-34, 34)
            sim.reset(
                options={
                    "player": (x, y, rng.uniform(-180, 180), *rng.uniform(-0.3, 0.3, 2)),
                    "ball": (
                        min(x + rng.choice((-1, 1)) * rng.uniform(0.5, 3), 52.0),
                        y,
                        *rng.uniform(-2, 2, 2),
                    ),
                }
            )
        _, _, terminated, truncated, info = sim.step(rng.random(8, dtype=np.float32))
        if terminated or truncated:
            place = True
            continue
        state = real.state_from_hfo_features(_hfo_vector(sim).tolist(), 1 if task == "keeper" else 0)
        player, ball = state["player"], state["ball"]
        assert player is not None and ball is not None
        position_error = max(position_error, _max_error(player[:2], info["player"][:2]))
        position_error = max(position_error, _max_error(ball[:2], info["ball"][:2]))
        velocity_error = max(velocity_error, _max_error(ball[2:], info["ball"][2:]))
        assert abs((player[4] - info["player"][4] + 180.0) % 360.0 - 180.0) < 1e-3
        if math.hypot(*info["player"][2:4]) < 0.45:  # the feature caps the own speed at 0.46 m/cycle
            velocity_error = max(velocity_error, _max_error(player[2:4], info["player"][2:4]))
        if task == "keeper":
            keeper = state["keeper"]
            assert keeper is not None
            position_error = max(position_error, _max_error(keeper[:2], info["keeper"][:2]))
            if math.hypot(*info["keeper"][2:4]) < 0.74:  # capped at 0.75 m/cycle
                velocity_error = max(velocity_error, _max_error(keeper[2:4], info["keeper"][2:4]))
            assert abs((keeper[4] - info["keeper"][4] + 180.0) % 360.0 - 180.0) < 1e-3
        else:
            assert "keeper" not in state
        checked += 1
    assert checked > 150
    assert position_error < 2e-3 and velocity_error < 1e-4, (position_error, velocity_error)


def test_state_from_invalid_features() -> None:
    vector = [0.0] * 68
    vector[0] = -1.0  # self position not valid (no fullstate)
    assert real.state_from_hfo_features(vector, 1) == {"player": None, "ball": None, "keeper": None}
    vector = [0.0] * 68
    vector[0] = vector[6] = 1.0  # valid self, ball flag off, goalie unum -1
    vector[66] = -1.0
    state = real.state_from_hfo_features(vector, 1)
    assert state["player"] is not None and state["ball"] is None and state["keeper"] is None


# ---------------------------------------------------------------------------------------------------------------
# Episode plumbing over a fake session: hfo2d's simulator served as HFO serves its state
# ---------------------------------------------------------------------------------------------------------------
class FakeSession:
    """Stands in for hfo2d.real._Session: an hfo2d simulator answering HFO's act + step.

    As HFO does: the state at connection precedes the placement (zeros), the state is float32, and the step that
    ends an episode already returns the next episode's first state. HFO's clock is imitated too: the session's
    first episode is truncated one step earlier.
    """

    instances: list[FakeSession] = []

    def __init__(
        self,
        hfo_dir: Path,
        args: list[str],
        port: int | None,
        log_dir: Path | None,
        rng: Any,
        still_goalie: bool = False,
    ) -> None:
        value = {args[i]: args[i + 1] for i in range(len(args) - 1)}
        self.args = args
        self.still_goalie = still_goalie
        self.frames = int(value["--frames-per-trial"])
        defense_agents = int(value.get("--defense-agents", 0))
        assert still_goalie == (defense_agents == 1)
        self.num_opponents = int(value["--defense-npcs"]) + defense_agents
        self.num_teammates = 0
        self.unum = 11
        self.port = 40000 + len(FakeSession.instances)
        self.seed = int(value.get("--seed", 0))
        self.sim = HFOEnv(
            task="static_keeper" if still_goalie else "keeper" if self.num_opponents else "empty_goal",
            feature_set="hfo",
            action_format="parameterized",
            frames_per_trial=self.frames - 2,
            untouched_time=int(value["--untouched-time"]),
        )
        self.placed, _ = self.sim.reset(seed=self.seed)
        self.state_size = len(self.placed)
        self.state = np.zeros(self.state_size, dtype=np.float32)
        self.start_noops = 0
        self.fail_next = False
        self.closed = False
        self.records: list[dict[str, Any]] = []  # per simulated step: paper features, reward, status, ends
        self.resets: list[list[float]] = [self.sim._features()]  # the paper features of each episode's start
        FakeSession.instances.append(self)

    def step(self, code: int, param0: float, param1: float) -> tuple[int, int, int]:
        if self.fail_next:
            raise real.SessionDown("fake: the server went away")
        p0, p1 = float(np.float32(param0)), float(np.float32(param1))  # the wire carries float32
        if self.start_noops < real.START_NOOPS and code == real.HFO_NOOP:  # the start: the placement shows up
            self.start_noops += 1
            self.state[:] = self.placed
            return 0, 0, -1
        self.start_noops = real.START_NOOPS
        zeros2 = np.zeros(2, dtype=np.float32)
        if code == real.HFO_DASH:
            action = (0, np.array([p0, p1], dtype=np.float32), np.zeros(1, dtype=np.float32), zeros2)
        elif code == real.HFO_TURN:
            action = (1, zeros2, np.array([p0], dtype=np.float32), zeros2)
        elif code == real.HFO_KICK:
            action = (2, zeros2, np.zeros(1, dtype=np.float32), np.array([p0, p1], dtype=np.float32))
        else:  # NOOP: a zero dash
            action = (0, zeros2, np.zeros(1, dtype=np.float32), zeros2)
        obs, reward, terminated, truncated, info = self.sim.step(action)
        self.records.append(
            {
                "features": self.sim._features(),
                "reward": reward,
                "status": info["status"],
                "terminated": terminated,
                "truncated": truncated,
                "player": info["player"],
            }
        )
        if terminated or truncated:
            obs, _ = self.sim.reset()
            self.sim.frames_per_trial = self.frames - 1
            self.resets.append(self.sim._features())
        self.state[:] = obs
        return STATUS_CODES[info["status"]], 0, -1

    def log_tail(self, lines: int = 20) -> str:
        return "fake log"

    def close(self) -> None:
        self.closed = True


@pytest.fixture
def fake_sessions(monkeypatch: pytest.MonkeyPatch) -> list[FakeSession]:
    FakeSession.instances = []
    monkeypatch.setattr(real, "_Session", FakeSession)
    return FakeSession.instances


def _play(env: real.RealHFOEnv, episodes: int, seed: int) -> list[dict[str, Any]]:
    """Random flat actions; per step the env's (obs, reward, terminated, truncated, info)."""
    rng = np.random.default_rng(seed)
    out: list[dict[str, Any]] = []
    obs, info = env.reset()
    out.append({"reset": obs, "info": info})
    done = 0
    while done < episodes:
        obs, reward, terminated, truncated, info = env.step(rng.random(8, dtype=np.float32))
        out.append(
            {"obs": obs, "reward": reward, "terminated": terminated, "truncated": truncated, "info": info}
        )
        if terminated or truncated:
            done += 1
            obs, info = env.reset()
            out.append({"reset": obs, "info": info})
    return out


@pytest.mark.parametrize(
    ("task", "frames", "untouched"),
    [("keeper", 500, 100), ("empty_goal", 500, 30), ("keeper", 30, 1000), ("static_keeper", 500, 100)],
)
def test_episodes_match_the_simulator_served(
    fake_build: Path, fake_sessions: list[FakeSession], task: str, frames: int, untouched: int
) -> None:
    env = real.RealHFOEnv(
        task=task, hfo_dir=fake_build, seed=4, frames_per_trial=frames, untouched_time=untouched
    )
    steps = _play(env, episodes=4, seed=1)
    (session,) = fake_sessions
    assert session.seed == 4 and session.still_goalie == (task == "static_keeper")
    assert env.observation_space.shape == ((58,) if task == "empty_goal" else (66,))
    records = iter(session.records)
    resets = iter(session.resets)
    previous_obs = None
    ends = []
    for entry in steps:
        if "reset" in entry:
            np.testing.assert_allclose(entry["reset"], next(resets), atol=2e-5)
            assert entry["info"]["status"] == "IN_GAME" and entry["info"]["episode"] == len(ends) + 1
            previous_obs = entry["reset"]
            continue
        record = next(records)
        info = entry["info"]
        assert info["status"] == record["status"]
        assert entry["terminated"] == record["terminated"] and entry["truncated"] == record["truncated"]
        assert entry["reward"] == pytest.approx(record["reward"], abs=1e-4)
        if record["terminated"] or record["truncated"]:
            # HFO's own last observation is lost: the env repeats the one the last action was taken from
            np.testing.assert_array_equal(entry["obs"], previous_obs)
            assert info["stale_observation"]
            ends.append((len(ends), record["status"], entry["truncated"]))
        else:
            np.testing.assert_allclose(entry["obs"], record["features"], atol=2e-5)
            np.testing.assert_allclose(info["player"][:2], record["player"][:2], atol=2e-3)
            assert not info["stale_observation"]
            if task == "static_keeper":  # the still goalie, as the striker's features show it
                assert info["keeper"][:2] == pytest.approx((52.5, 0.0), abs=2e-3)
                assert abs(abs(info["keeper"][4]) - real.GOALIE_BODY_DEG) < 1e-3
        previous_obs = entry["obs"]
    assert len(ends) == 4
    if frames == 30:  # HFO's clock: the first episode has 28 steps, later ones 29
        assert any(truncated for _, _, truncated in ends)
    env.close()
    assert session.closed


def test_frame_limit_steps(fake_build: Path, fake_sessions: list[FakeSession]) -> None:
    env = real.RealHFOEnv(task="keeper", hfo_dir=fake_build, frames_per_trial=20, untouched_time=1000)
    lengths = []
    env.reset()
    while len(lengths) < 3:
        _, _, terminated, truncated, info = env.step(
            np.array([1, 0, 0, 0, 0.5, 0.5, 0, 0.5], dtype=np.float32)
        )
        if terminated or truncated:  # a still agent: only the frame limit ends the episode
            assert truncated and not terminated and info["status"] == "OUT_OF_TIME"
            lengths.append(env.steps)
            env.reset()
    assert lengths == [18, 19, 19]


def test_reset_mid_episode_finishes_it(fake_build: Path, fake_sessions: list[FakeSession]) -> None:
    env = real.RealHFOEnv(task="empty_goal", hfo_dir=fake_build, untouched_time=10)
    env.reset()
    for _ in range(3):
        env.step(np.array([0, 1, 0, 0, 0, 0.5, 0, 0], dtype=np.float32))
    obs, info = env.reset()
    (session,) = fake_sessions
    assert session.records[-1]["status"] != "IN_GAME"  # NOOPs played until the simulator ended the episode
    np.testing.assert_allclose(obs, session.resets[-1], atol=2e-5)
    assert info["episode"] == 2
    with pytest.raises(ValueError, match="reset options"):
        env.reset(options={"ball": (1.0, 2.0)})


def test_step_before_reset_and_invalid_action(fake_build: Path, fake_sessions: list[FakeSession]) -> None:
    env = real.RealHFOEnv(hfo_dir=fake_build)
    with pytest.raises(RuntimeError, match="reset"):
        env.step(np.zeros(8, dtype=np.float32))
    env.reset()
    steps_before = len(fake_sessions[0].records)
    with pytest.raises(ValueError):
        env.step(np.full(8, np.nan, dtype=np.float32))
    assert len(fake_sessions[0].records) == steps_before  # nothing sent


def test_seeds_start_sessions(fake_build: Path, fake_sessions: list[FakeSession]) -> None:
    env = real.RealHFOEnv(hfo_dir=fake_build)
    env.reset(seed=3)
    env.reset(seed=3)  # same seed: same session
    assert [s.seed for s in fake_sessions] == [3]
    env.reset(seed=5)  # another: a new session with that --seed
    assert [s.seed for s in fake_sessions] == [3, 5]
    assert fake_sessions[0].closed and not fake_sessions[1].closed
    env.reset()
    assert len(fake_sessions) == 2
    env.close()
    assert fake_sessions[1].closed


def test_server_down_restarts_with_a_warning(fake_build: Path, fake_sessions: list[FakeSession]) -> None:
    env = real.RealHFOEnv(task="keeper", hfo_dir=fake_build)
    obs, _ = env.reset()
    fake_sessions[0].fail_next = True
    with pytest.warns(RuntimeWarning, match="went down"):
        obs2, reward, terminated, truncated, info = env.step(np.zeros(8, dtype=np.float32))
    assert (terminated, truncated, reward, info["status"]) == (False, True, 0.0, "SERVER_DOWN")
    np.testing.assert_array_equal(obs2, obs)
    assert fake_sessions[0].closed
    with pytest.raises(RuntimeError, match="reset"):
        env.step(np.zeros(8, dtype=np.float32))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        obs, info = env.reset()
    assert len(fake_sessions) == 2 and info["session_restarts"] == 1 and info["episode"] == 2
    env.step(np.zeros(8, dtype=np.float32))


# ---------------------------------------------------------------------------------------------------------------
# Processes and wire over a stand-in build: a bin/HFO that only waits, an `hfo` binding in pure Python
# ---------------------------------------------------------------------------------------------------------------
FAKE_LAUNCHER = """\
import sys, time
open(sys.argv[0] + ".args", "w").write(" ".join(sys.argv[1:]))
print("Waiting for player-controlled agent base_left-0", flush=True)
if "--defense-agents" in sys.argv:
    print("Waiting for player-controlled agent base_right-0", flush=True)
time.sleep(600)
"""
FAKE_BINDING = """\
import math, os, time

LOW_LEVEL_FEATURE_SET = 0
DASH, TURN, KICK, NOOP = 0, 1, 3, 13
HERE = os.path.dirname(os.path.abspath(__file__))


class _OnBall:
    side = 1
    unum = 11


class HFOEnvironment:
    # The offense agent: 59 features (68 with the still goalie): the basic 58 (zeros, self valid), [the goalie's
    # block and unum,] the last-action flag. Each step writes the step count into feature 7, the action's params
    # into 55 and 56 and its code into the flag. A full-power KICK scores, a TURN to exactly -180 takes the server
    # down. The goalie (base_right, play_goalie): 68 features, valid self and its body (own frame, 180 at first:
    # facing its own goal), which a TURN turns exactly; each cycle takes 5 ms and its first 8 commands are
    # written to HFO_DIR/goalie_commands.
    def __init__(self):
        self.count = 0
        self.code, self.params = NOOP, (0.0, 0.0)
        self.goalie = False
        self.body = 180.0

    def connectToServer(self, feature_set, config_dir, port, host, team, goalie, record):
        assert feature_set == 0 and config_dir.endswith("formations-dt")
        assert (team, goalie) in (("base_left", False), ("base_right", True))
        self.goalie = goalie
        args = open(os.path.join(HERE, "..", "bin", "HFO.args")).read().split()
        self.opponents = 1 if goalie or "--defense-agents" in args else 0

    def getStateSize(self):
        return 58 + 9 * self.opponents + 1

    def getNumTeammates(self):
        return 0

    def getNumOpponents(self):
        return self.opponents

    def getUnum(self):
        return 1 if self.goalie else 11

    def getState(self, out):
        out[:] = 0.0
        out[0] = out[1] = out[6] = 1.0
        if self.goalie:
            out[5], out[6] = math.sin(math.radians(self.body)), math.cos(math.radians(self.body))
            return out
        out[7] = self.count / 1000.0
        out[55] = self.params[0] / 100.0 if len(self.params) > 0 else 0.0
        out[56] = self.params[1] / 180.0 if len(self.params) > 1 else 0.0
        out[-1] = -1.0 if self.code == KICK else 1.0
        return out

    def act(self, code, *params):
        self.code, self.params = code, params

    def step(self):
        self.count += 1
        if self.goalie:
            if self.count <= 8:
                with open(os.path.join(HERE, "..", "goalie_commands"), "a") as f:
                    f.write(" ".join(str(v) for v in (self.code, *self.params)) + "\\n")
            if self.code == TURN:
                self.body = (self.body + self.params[0] + 180.0) % 360.0 - 180.0
            time.sleep(0.005)
            return 0
        if self.code == TURN and self.params[0] == -180.0:
            return 5
        if self.code == KICK and self.params[0] == 100.0:
            return 1
        return 0

    def playerOnBall(self):
        return _OnBall()
"""


@pytest.fixture
def stand_in_build(make_stand_in_build: Callable[[str, str], Path]) -> Path:
    return make_stand_in_build(FAKE_LAUNCHER, FAKE_BINDING)


def _flat(kind: int, power: float, direction: float) -> np.ndarray:
    action = np.zeros(8, dtype=np.float32)
    action[kind] = 1.0
    slots = {DASH: (3, 4), TURN: (None, 5), KICK: (6, 7)}[kind]
    if slots[0] is not None:
        action[slots[0]] = power / 100.0
    action[slots[1]] = (direction + 180.0) / 360.0
    return action


def test_session_processes_and_wire(stand_in_build: Path, group_gone: Callable[[int], bool]) -> None:
    env = real.RealHFOEnv(hfo_dir=stand_in_build, seed=9)
    obs, info = env.reset()
    session = env._session
    assert session is not None and session.server.poll() is None and session.worker.poll() is None
    args = (stand_in_build / "bin" / "HFO.args").read_text().split()
    assert args[args.index("--port") + 1] == str(env.session_port)
    assert real.PORT_RANGE[0] <= env.session_port < real.PORT_RANGE[1]
    assert args[args.index("--seed") + 1] == "9"
    assert obs[7] == pytest.approx(real.START_NOOPS / 1000.0)  # the three start NOOPs were played
    obs, reward, terminated, truncated, info = env.step(_flat(DASH, 40.0, 90.0))
    assert not (terminated or truncated) and info["status"] == "IN_GAME"
    assert obs[7] == pytest.approx((real.START_NOOPS + 1) / 1000.0)
    assert obs[55] == pytest.approx(0.4) and obs[56] == pytest.approx(
        0.5
    )  # DASH's power and direction arrived
    assert info["action_success"] and info["player_on_ball"] == ("L", 11)
    obs, reward, terminated, truncated, info = env.step(_flat(TURN, 0.0, 45.0))
    assert obs[55] == pytest.approx(0.45) and obs[56] == 0.0  # TURN: the direction only
    obs, reward, terminated, truncated, info = env.step(_flat(KICK, 50.0, -90.0))
    assert not info["action_success"] and info["kick_power"] == 0.0  # HFO's flag: the kick failed
    before = obs
    obs, reward, terminated, truncated, info = env.step(_flat(KICK, 100.0, 0.0))
    assert terminated and not truncated and info["status"] == "GOAL" and info["is_success"]
    np.testing.assert_array_equal(obs, before)
    obs, info = env.reset()
    assert obs[7] == pytest.approx((real.START_NOOPS + 4) / 1000.0) and info["episode"] == 2
    server, worker = session.server, session.worker
    with pytest.warns(RuntimeWarning, match="went down"):
        *_, truncated, info = env.step(_flat(TURN, 0.0, -180.0))
    assert truncated and info["status"] == "SERVER_DOWN"
    assert server.poll() is not None and worker.poll() is not None
    assert group_gone(server.pid) and group_gone(worker.pid)
    obs, info = env.reset()
    assert info["session_restarts"] == 1
    server, worker = env._session.server, env._session.worker
    env.close()
    assert server.poll() is not None and worker.poll() is not None
    assert group_gone(server.pid) and group_gone(worker.pid)


def test_still_goalie_worker(stand_in_build: Path, group_gone: Callable[[int], bool]) -> None:
    env = real.RealHFOEnv(task="static_keeper", hfo_dir=stand_in_build, seed=9)
    obs, info = env.reset()
    assert obs.shape == (66,)
    session = env._session
    assert session is not None and session.goalie is not None and session.goalie.poll() is None
    args = (stand_in_build / "bin" / "HFO.args").read_text().split()
    assert args[args.index("--defense-npcs") + 1] == "0" and args[args.index("--defense-agents") + 1] == "1"
    assert "--agent-play-goalie" in args
    obs, *_ = env.step(_flat(DASH, 40.0, 90.0))
    assert obs[55] == pytest.approx(0.4)  # the learning agent's worker serves the env as before
    commands_file = stand_in_build / "goalie_commands"
    deadline = time.monotonic() + 20.0
    while (
        time.monotonic() < deadline
        and len(commands_file.read_text().splitlines() if commands_file.exists() else []) < 8
    ):
        time.sleep(0.05)
    commands = [line.split() for line in commands_file.read_text().splitlines()]
    # one turn to face the field (its features: 180 degrees, facing its own goal), then NOOP every cycle
    assert commands[0] == [str(real.HFO_TURN), "180.0"]
    assert commands[1:] == [[str(real.HFO_NOOP)]] * 7
    goalie, server, worker = session.goalie, session.server, session.worker
    env.close()
    assert goalie.returncode == 0  # it quit when asked, on its own
    assert group_gone(goalie.pid) and group_gone(server.pid) and group_gone(worker.pid)
    # a dead goalie takes the session down at the next step (rcssserver may play on without it)
    env.reset()
    goalie = env._session.goalie
    os.killpg(goalie.pid, 9)
    goalie.wait(timeout=10)
    with pytest.warns(RuntimeWarning, match="still goalie's worker exited"):
        *_, truncated, info = env.step(_flat(DASH, 40.0, 90.0))
    assert truncated and info["status"] == "SERVER_DOWN"
    env.close()


# ---------------------------------------------------------------------------------------------------------------
# The real HFO (opt-in: inside a loopback-only network namespace, or HFO_TESTS=1)
# ---------------------------------------------------------------------------------------------------------------
def test_real_empty_goal_session(real_hfo_build: Path) -> None:
    env = gym.make("HFO/RealEmptyGoal-v0", hfo_dir=real_hfo_build, noise=False, seed=2, frames_per_trial=200)
    unwrapped = env.unwrapped
    obs, info = env.reset()
    assert obs.shape == (58,) and obs.dtype == np.float32 and np.all(np.abs(obs) <= 1.0)
    assert info["player"] is not None and 0.0 <= info["ball"][0] <= 10.5 and abs(info["ball"][1]) <= 27.2
    statuses = []
    lengths = []
    while len(statuses) < 3:  # the scripted striker against the empty goal
        obs, reward, terminated, truncated, info = env.step(heuristic(env, obs))
        assert obs.shape == (58,) and np.all(np.abs(obs) <= 1.0)
        if terminated or truncated:
            statuses.append(info["status"])
            lengths.append(unwrapped.steps)
            assert truncated == (info["status"] == "OUT_OF_TIME" and unwrapped.steps >= 198)
            obs, info = env.reset()
    assert "GOAL" in statuses, (statuses, lengths)
    # a reset in the middle of an episode
    env.step(np.zeros(8, dtype=np.float32))
    obs, info = env.reset()
    assert info["episode"] == 5
    server, worker = unwrapped._session.server, unwrapped._session.worker
    # the server dies: SERVER_DOWN, a warning, and a new session at the next reset
    os.killpg(server.pid, 9)
    with pytest.warns(RuntimeWarning, match="went down"):
        for _ in range(5):
            *_, truncated, info = env.step(np.zeros(8, dtype=np.float32))
            if truncated:
                break
    assert info["status"] == "SERVER_DOWN"
    obs, info = env.reset()
    assert info["session_restarts"] == 1 and obs.shape == (58,)
    server, worker = unwrapped._session.server, unwrapped._session.worker
    env.close()
    assert server.poll() is not None and worker.poll() is not None


def test_real_keeper_session(real_hfo_build: Path) -> None:
    env = real.RealHFOEnv(task="keeper", hfo_dir=real_hfo_build, untouched_time=30)
    obs, info = env.reset(seed=1)
    assert obs.shape == (66,) and np.all(np.abs(obs) <= 1.0)
    keeper = info["keeper"]
    assert keeper is not None and math.hypot(keeper[0] - 52.5, keeper[1]) < 1.0  # two cycles after placement
    rng = np.random.default_rng(0)
    ends = 0
    while ends < 2:
        obs, reward, terminated, truncated, info = env.step(rng.random(8, dtype=np.float32))
        assert obs.shape == (66,) and info["status"] in real.STATUS_NAMES[:5]
        ends += terminated or truncated
        if terminated or truncated:
            obs, info = env.reset()
    assert info["episode"] == 3 and info["session_restarts"] == 0
    env.close()


def test_real_static_keeper_session(real_hfo_build: Path) -> None:
    env = gym.make("HFO/RealStaticKeeper-v0", hfo_dir=real_hfo_build, untouched_time=20)
    unwrapped = env.unwrapped
    obs, info = env.reset(seed=1)
    assert obs.shape == (66,) and np.all(np.abs(obs) <= 1.0)
    keepers = [info["keeper"]]
    rng = np.random.default_rng(0)
    ends = 0
    while ends < 2:
        obs, reward, terminated, truncated, info = env.step(rng.random(8, dtype=np.float32))
        assert obs.shape == (66,) and info["status"] in real.STATUS_NAMES[:5]
        if not info["stale_observation"]:
            keepers.append(info["keeper"])
        if terminated or truncated:
            ends += 1
            obs, info = env.reset()
            keepers.append(info["keeper"])
    # the goalie stands on the goal line facing the field from the first observation on
    for keeper in keepers:
        assert keeper is not None and math.hypot(keeper[0] - 52.5, keeper[1]) < 1e-3
        assert keeper[2:4] == (0.0, 0.0)
        assert abs(abs(keeper[4]) - real.GOALIE_BODY_DEG) <= real.GOALIE_TURN_THRESHOLD_DEG
    session = unwrapped._session
    turns = [line for line in session._log_text().splitlines() if line.startswith("still goalie:")]
    assert 1 <= len(turns) <= 3 and "episode 0 cycle 0: body 180.000" in turns[0]  # HFO's initial body
    # a dead goalie takes the session down (the env checks it every step)
    os.killpg(session.goalie.pid, 9)
    with pytest.warns(RuntimeWarning, match="still goalie's worker exited"):
        for _ in range(100):
            *_, truncated, info = env.step(np.zeros(8, dtype=np.float32))
            if truncated:
                break
    assert info["status"] == "SERVER_DOWN"
    server, worker = session.server, session.worker
    env.close()
    assert server.poll() is not None and worker.poll() is not None
