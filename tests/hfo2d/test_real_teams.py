"""Tests of the real HFO for teams (hfo2d.real_teams.RealTeamParallelEnv).

Always run (no HFO build): argument checks, spaces, bin/HFO's command line, the action decoding, and the whole
process plumbing (launcher, one worker per agent, lock-step cycles, episode ends, SERVER_DOWN and its recovery,
clean shutdown) over a stand-in build: a bin/HFO that prints bin/Trainer.py's waiting lines and an ``hfo`` binding in
pure Python. PettingZoo's ``parallel_api_test`` runs on the stand-in.

The real HFO (``$HFO_DIR``) runs only inside a loopback-only network namespace (``tools/real_hfo/loopback.sh``) or
with ``HFO_TESTS=1``; otherwise that test skips.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
import warnings
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from hfo2d import real
from hfo2d.action_layout import HybridActionBox, hfo_flat_action_space
from hfo2d.features import hfo_num_features, high_level_num_features, num_features
from hfo2d.real_teams import RealTeamParallelEnv, defense_action_space

FAKE_LAUNCHER = """\
import sys, time
args = sys.argv[1:]
open(sys.argv[0] + ".args", "w").write(" ".join(args))
def count(flag):
    return int(args[args.index(flag) + 1]) if flag in args else 0
goalie_agent = "--agent-play-goalie" in args or count("--defense-npcs") == 0
for k in range(count("--offense-agents")):
    print(f"Waiting for player-controlled agent base_left-{k}: config_dir=x, server_port=1, server_addr=localhost, "
          f"team_name=base_left, play_goalie=False", flush=True)
for k in range(count("--defense-agents")):
    print(f"Waiting for player-controlled agent base_right-{k}: config_dir=x, server_port=1, server_addr=localhost, "
          f"team_name=base_right, play_goalie={goalie_agent and k == 0}", flush=True)
time.sleep(600)
"""
# Every agent: its vector holds its cycle count / 1000 in entry 7 and the parameters of its last act in 55, 56
# (low-level); all agents end an episode with GOAL every 6th cycle (they run in lock-step, so they agree); a file
# HFO_DIR/down takes the server down (status SERVER_DOWN for everybody).
FAKE_BINDING = """\
import os

HERE = os.path.dirname(os.path.abspath(__file__))


class _OnBall:
    side = 1
    unum = 7


class HFOEnvironment:
    def connectToServer(self, feature_set, config_dir, port, host, team, goalie, record):
        args = open(os.path.join(HERE, "..", "bin", "HFO.args")).read().split()
        count = lambda flag: int(args[args.index(flag) + 1]) if flag in args else 0
        offense = count("--offense-agents") + count("--offense-npcs")
        defense = count("--defense-agents") + count("--defense-npcs")
        self.offense = team == "base_left"
        self.teammates, self.opponents = (offense - 1, defense) if self.offense else (defense - 1, offense)
        self.feature_set, self.goalie = feature_set, goalie
        self.count, self.params = 0, ()

    def getStateSize(self):
        t, o = self.teammates, self.opponents
        return 58 + 9 * (t + o) + 1 if self.feature_set == 0 else 10 + 6 * t + 3 * o + 2

    def getNumTeammates(self):
        return self.teammates

    def getNumOpponents(self):
        return self.opponents

    def getUnum(self):
        return (1 if self.goalie else 2) if not self.offense else 7

    def getState(self, out):
        out[:] = 0.0
        if self.feature_set == 0:
            out[0] = out[1] = out[6] = 1.0
            out[7] = self.count / 1000.0
            out[55] = self.params[0] / 100.0 if len(self.params) > 0 else 0.0
            out[56] = self.params[1] / 180.0 if len(self.params) > 1 else 0.0
            t, o = self.teammates, self.opponents
            out[58 + 8 * (t + o) : 58 + 9 * (t + o)] = -1.0  # nobody listed
        return out

    def act(self, code, *params):
        self.params = params

    def step(self):
        self.count += 1
        if os.path.exists(os.path.join(HERE, "..", "down")):
            return 5
        return 1 if self.count % 6 == 0 else 0

    def playerOnBall(self):
        return _OnBall()
"""


@pytest.fixture
def stand_in_build(make_stand_in_build: Callable[[str, str], Path]) -> Path:
    return make_stand_in_build(FAKE_LAUNCHER, FAKE_BINDING)


def _dash(space: HybridActionBox, power: float, direction: float) -> np.ndarray:
    """A flat DASH(power, direction) in ``space`` (an offense's or a defender's layout)."""
    action = np.zeros(space.shape, dtype=np.float32)
    action[0] = 1.0
    params = space.layout.parameter_slice(0)
    action[params.start] = power / 100.0
    action[params.start + 1] = (direction + 180.0) / 360.0
    return action


# ---------------------------------------------------------------------------------------------------------------
# Arguments, spaces, command line
# ---------------------------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"offense_agents": 0, "defense_agents": 0, "defense_npcs": 1}, "at least one learning agent"),
        ({"offense_agents": 11}, "1 to 10"),
        ({"offense_agents": 1, "defense_npcs": 12}, "at most 11"),
        ({"offense_agents": -1}, "integer >= 0"),
        ({"offense_agents": 1.5}, "integer >= 0"),
        ({"offense_agents": 1, "agent_play_goalie": True}, "needs a defense agent"),
        ({"feature_set": "pixels"}, "unknown feature_set"),
        ({"feature_set": "high_level"}, "reward='sparse'"),
        ({"reward": "nope"}, "unknown reward"),
        ({"defense_reward": "shaped"}, "only 'sparse'"),
        ({"action_format": "parameterized"}, "flat actions only"),
        ({"frames_per_trial": 0}, "positive integer"),
        ({"port": 80}, "port must be"),
        ({"seed": -1}, "seed must be"),
        ({"noise": "yes"}, "True or False"),
        ({"render_mode": "human"}, "does not render"),
    ],
)
def test_argument_validation(stand_in_build: Path, kwargs: dict, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        RealTeamParallelEnv(**{"hfo_dir": stand_in_build, **kwargs})


def test_missing_build(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(real.HFO_DIR_ENV, raising=False)
    with pytest.raises(real.HFOBuildNotFound, match="build.sh"):
        RealTeamParallelEnv(2, 0, 1)


def test_spaces_and_command_line(stand_in_build: Path) -> None:
    env = RealTeamParallelEnv(2, 2, 3, hfo_dir=stand_in_build, seed=4, noise=False, log_dir="/tmp/x")
    assert env.possible_agents == ["offense_0", "offense_1", "defense_0", "defense_1"]
    assert env.observation_space("offense_1").shape == (num_features(1, 5),)
    assert env.observation_space("defense_0").shape == (num_features(4, 2),)
    assert env.observation_space("offense_0") is env.observation_space("offense_0")
    assert env.action_space("offense_0").layout.names == ("DASH", "TURN", "KICK")
    assert env.action_space("defense_0").layout.names == ("DASH", "TURN", "TACKLE", "KICK")  # not the goalie
    args = env.hfo_args(4)
    for flag, value in (("--offense-agents", "2"), ("--defense-agents", "2"), ("--defense-npcs", "3")):
        assert args[args.index(flag) + 1] == value
    assert "--deterministic" in args and "--fullstate" in args and args[args.index("--seed") + 1] == "4"
    assert args[args.index("--log-dir") + 1] == "/tmp/x" and "--agent-play-goalie" not in args
    hfo = RealTeamParallelEnv(1, 1, 0, hfo_dir=stand_in_build, feature_set="hfo")
    assert hfo.observation_space("offense_0").shape == (hfo_num_features(0, 1),)
    assert hfo.action_space("defense_0").layout.names[-1] == "CATCH"  # a lone defender is HFO's goalie
    # without a defense NPC the agents hold unum 1: the first is the goalie (bin/Trainer.py)
    two = RealTeamParallelEnv(1, 2, 0, hfo_dir=stand_in_build)
    assert [two.action_space(a).layout.names[-1] for a in ("defense_0", "defense_1")] == ["CATCH", "KICK"]
    high = RealTeamParallelEnv(2, 0, 1, hfo_dir=stand_in_build, feature_set="high_level", reward="sparse")
    space = high.observation_space("offense_0")
    assert (
        space.shape == (high_level_num_features(1, 1),)
        and space.low.min() == -2.0
        and space.high.max() == 11.0
    )


def test_defense_action_space() -> None:
    goalie, field = defense_action_space(True), defense_action_space(False)
    assert goalie.shape == (11,) and field.shape == (10,)
    assert goalie.layout.parameter_sizes == (2, 1, 1, 2, 0) and goalie.layout.ball_action == 3
    assert goalie.layout.direction_indices == (6, 7, 8, 10) and field.layout.direction_indices == (5, 6, 7, 9)
    team = pytest.importorskip(
        "hfo2d.team", reason="hfo2d's own team game (another branch) is not merged yet"
    )
    # the same spaces as hfo2d's own team game
    assert (
        goalie.layout == team.GOALIE_FLAT_ACTION_LAYOUT and field.layout == team.DEFENDER_FLAT_ACTION_LAYOUT
    )


def test_action_decoding(stand_in_build: Path) -> None:
    env = RealTeamParallelEnv(1, 1, 0, hfo_dir=stand_in_build)
    assert env._decode("offense_0", _dash(hfo_flat_action_space(), 40.0, 90.0)) == (
        "DASH",
        (real.HFO_DASH, pytest.approx(40.0), 90.0),
    )
    tackle = np.zeros(11, dtype=np.float32)
    tackle[2], tackle[8] = 1.0, 0.25
    assert env._decode("defense_0", tackle) == ("TACKLE", (real.HFO_TACKLE, -90.0, 0.0))
    kick = np.zeros(11, dtype=np.float32)
    kick[3], kick[9], kick[10] = 1.0, 0.5, 1.0
    assert env._decode("defense_0", kick) == ("KICK", (real.HFO_KICK, 50.0, 180.0))
    catch = np.zeros(11, dtype=np.float32)
    catch[4] = 1.0
    assert env._decode("defense_0", catch) == ("CATCH", (real.HFO_CATCH, 0.0, 0.0))
    with pytest.raises(ValueError, match="shape"):
        env._decode("offense_0", np.zeros(11))
    with pytest.raises(ValueError, match=r"\[0, 1\]"):
        env._decode("offense_0", np.full(8, np.nan))


# ---------------------------------------------------------------------------------------------------------------
# Processes and wire over the stand-in build
# ---------------------------------------------------------------------------------------------------------------
def test_session_plumbing(stand_in_build: Path, group_gone: Callable[[int], bool]) -> None:
    env = RealTeamParallelEnv(2, 1, 1, hfo_dir=stand_in_build, feature_set="hfo", seed=5)
    with pytest.raises(RuntimeError, match="reset"):
        env.step({})
    obs, infos = env.reset()
    session = env._session
    assert session is not None and len(session.workers) == 3 and session.server is not None
    assert session.play_goalie == [False, False, False]  # one defense NPC: it is the goalie
    assert set(obs) == set(env.possible_agents) == set(env.agents)
    assert obs["offense_0"].shape == (hfo_num_features(1, 2),) and obs["defense_0"].shape == (
        hfo_num_features(1, 2),
    )
    assert obs["offense_1"][7] == pytest.approx(
        real.START_NOOPS / 1000.0
    )  # the three start NOOPs, every agent
    assert infos["defense_0"]["unum"] == 2 and infos["offense_0"]["unum"] == 7
    offense = hfo_flat_action_space()
    with pytest.raises(ValueError, match="missing"):
        env.step({"offense_0": _dash(offense, 0, 0)})
    actions = {
        "offense_0": _dash(offense, 40.0, 90.0),
        "offense_1": _dash(offense, 20.0, 0.0),
        "defense_0": _dash(env.action_space("defense_0"), 60.0, 0.0),
    }
    for _ in range(2):
        obs, rewards, terminated, truncated, infos = env.step(actions)
        assert obs["offense_0"][55] == pytest.approx(0.4) and obs["offense_0"][56] == pytest.approx(0.5)
        assert obs["defense_0"][55] == pytest.approx(0.6)  # each agent's own command reached its own worker
        assert not any(terminated.values()) and infos["offense_0"]["action"] == "DASH"
    obs, rewards, terminated, truncated, infos = env.step(actions)  # cycle 6 of the stand-in: GOAL
    assert all(terminated.values()) and not any(truncated.values()) and env.agents == []
    assert infos["offense_1"]["status"] == "GOAL" and rewards["defense_0"] == -1.0
    assert rewards["offense_0"] > 0.5  # hfo2d's shaped reward pays the goal
    assert infos["offense_0"]["stale_observation"] and obs["offense_0"][7] == pytest.approx(5 / 1000.0)
    obs, infos = env.reset()
    assert infos["offense_0"]["episode"] == 2 and obs["offense_0"][7] == pytest.approx(6 / 1000.0)
    # the server goes down: every agent's episode ends truncated, with a warning; the next reset starts anew
    server, workers = session.server, list(session.workers)
    (stand_in_build / "down").write_text("")
    with pytest.warns(RuntimeWarning, match="went down"):
        obs, rewards, terminated, truncated, infos = env.step(actions)
    assert all(truncated.values()) and infos["defense_0"]["status"] == "SERVER_DOWN" and env.agents == []
    assert all(group_gone(p.pid) for p in [server, *workers])
    (stand_in_build / "down").unlink()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        obs, infos = env.reset()
    assert infos["offense_0"]["session_restarts"] == 1 and len(obs) == 3
    server, workers = env._session.server, list(env._session.workers)
    env.close()
    assert all(p.poll() is not None and group_gone(p.pid) for p in [server, *workers])
    assert env.agents == []


def test_parallel_api_on_the_stand_in(stand_in_build: Path) -> None:
    pytest.importorskip("pettingzoo")
    from pettingzoo.test import parallel_api_test

    env = RealTeamParallelEnv(2, 1, 0, hfo_dir=stand_in_build, agent_play_goalie=True)
    try:
        parallel_api_test(env, num_cycles=20)
    finally:
        env.close()
    with pytest.raises(ValueError, match="places the players"):
        env.reset(options={"ball": (10.0, 0.0)})


# ---------------------------------------------------------------------------------------------------------------
# The real HFO (opt-in: inside a loopback-only network namespace, or HFO_TESTS=1)
# ---------------------------------------------------------------------------------------------------------------
def _session_processes(build: Path) -> list[str]:
    """Command lines of the running processes that belong to an HFO session (server, trainer, NPCs, workers)."""
    listing = subprocess.run(["ps", "-eo", "pid=,args="], capture_output=True, text=True, check=True).stdout
    own = str(os.getpid())
    return [
        line.strip()
        for line in listing.splitlines()
        if (str(build) in line or "hfo2d.real" in line or "rcssserver" in line or "sample_player" in line)
        and line.split()[0] != own
    ]


def test_real_two_agents_against_the_goalie(real_hfo_build: Path) -> None:
    # the process check is sound only in a namespace of this test's own (another session may run outside it)
    own_namespace = real.in_loopback_namespace()
    assert not own_namespace or _session_processes(real_hfo_build) == []
    env = RealTeamParallelEnv(2, 0, 1, hfo_dir=real_hfo_build, seed=3, frames_per_trial=60, untouched_time=20)
    rng = np.random.default_rng(0)
    statuses = []
    obs, infos = env.reset()
    unums = sorted(info["unum"] for info in infos.values())
    assert unums == [7, 11]  # bin/Trainer.py gives the agents agent2d's offense numbers, sorted
    # rcssserver, bin/HFO, agent2d's goalie and the two workers are seen (so that the check at the end can fail)
    assert not own_namespace or len(_session_processes(real_hfo_build)) >= 5
    while len(statuses) < 4:
        for agent, vector in obs.items():
            assert vector.shape == (num_features(1, 1),) and env.observation_space(agent).contains(vector)
        actions = {agent: env.action_space(agent).sample() for agent in env.agents}
        actions["offense_0"] = rng.random(8).astype(np.float32)
        obs, rewards, terminated, truncated, infos = env.step(actions)
        if env.agents == []:
            assert len({info["status"] for info in infos.values()}) == 1
            status = infos["offense_0"]["status"]
            assert status in ("GOAL", "CAPTURED_BY_DEFENSE", "OUT_OF_BOUNDS", "OUT_OF_TIME")
            assert all(terminated.values()) != all(truncated.values())
            statuses.append(status)
            obs, infos = env.reset()
    # a crash: the server dies, the episode ends truncated with a warning, the next reset starts a new session
    os.killpg(env._session.server.pid, 9)
    with pytest.warns(RuntimeWarning, match="went down"):
        for _ in range(50):
            obs, rewards, terminated, truncated, infos = env.step(
                {agent: env.action_space(agent).sample() for agent in env.agents}
            )
            if env.agents == []:
                break
    assert infos["offense_1"]["status"] == "SERVER_DOWN" and all(truncated.values())
    obs, infos = env.reset()
    assert infos["offense_0"]["session_restarts"] == 1
    pytest.importorskip("pettingzoo")
    from pettingzoo.test import parallel_api_test

    parallel_api_test(env, num_cycles=80)
    env.close()
    assert not own_namespace or _session_processes(real_hfo_build) == []


def test_real_gap_reward_reads_the_goalie_by_its_uniform_number(real_hfo_build: Path) -> None:
    """In real HFO's 2v2 the goalie (agent2d's, unum 1) is listed among the opponents with uniform-number entry
    0.01, not always first; a striker's gap reward reads that block (features.keeper_view_from_hfo)."""
    env = RealTeamParallelEnv(
        2,
        0,
        2,
        hfo_dir=real_hfo_build,
        seed=5,
        feature_set="hfo",
        reward="shaped_gap_refund",
        frames_per_trial=60,
        untouched_time=20,
    )
    basic = num_features(1, 2)  # where master's uniform numbers start
    obs, _ = env.reset()
    seen_slots = set()
    for _ in range(60):
        for name, vector in obs.items():
            opponent_unums = [round(value * 100) for value in vector[basic + 1 : basic + 3]]
            assert 1 in opponent_unums
            slot = opponent_unums.index(1)
            seen_slots.add(slot)
            view = env._reward_features(name)
            paper = env._paper[name]
            start = 58 + 8 * (1 + slot)
            assert view == paper[:58] + paper[start : start + 8]
        obs, _, _, _, _ = env.step({agent: env.action_space(agent).sample() for agent in env.agents})
        if not env.agents:
            obs, _ = env.reset()
    env.close()
    assert (
        1 in seen_slots
    )  # HFO lists opponents by distance: the goalie is often second (477 of 600 states, seed 5)


CRASHING_SCRIPT = """
import os, signal
from hfo2d.real_teams import RealTeamParallelEnv
env = RealTeamParallelEnv(2, 0, 1, seed=3)
env.reset()
env.step({agent: env.action_space(agent).sample() for agent in env.agents})
print(env._session.server.pid, *(worker.pid for worker in env._session.workers), flush=True)
os.kill(os.getpid(), signal.SIGKILL)
"""


def test_real_session_dies_with_a_crashed_process(real_hfo_build: Path) -> None:
    if not real.in_loopback_namespace():
        pytest.skip("the process check needs a namespace of this test's own (tools/real_hfo/loopback.sh)")
    done = subprocess.run(
        [sys.executable, "-c", CRASHING_SCRIPT],
        capture_output=True,
        text=True,
        env={**os.environ, real.HFO_DIR_ENV: str(real_hfo_build)},
        timeout=300,
    )
    assert done.returncode == -9 and len(done.stdout.split()) == 3, done.stderr[-2000:]
    # the launcher and the workers get SIGTERM when their parent dies (prctl PR_SET_PDEATHSIG); bin/HFO then stops
    # rcssserver and agent2d
    deadline = time.monotonic() + 30.0
    while _session_processes(real_hfo_build) and time.monotonic() < deadline:
        time.sleep(0.5)
    assert _session_processes(real_hfo_build) == []
