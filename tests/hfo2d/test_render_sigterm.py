"""A human-mode window leaves SIGTERM alone (issue 35, defect 5): SDL used to take the default handler over and
turn the signal into a QUIT event that nobody reads, so ``kill`` left ``enjoy`` and ``hfo2d.demo`` running."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]

# Opens the window (on SDL's dummy driver), then sends itself SIGTERM; it prints only if it survives.
SCRIPT = """
import os, signal, time
import gymnasium as gym
import hfo2d
env = gym.make("HFO/EmptyGoal-v0", render_mode="human")
env.reset(seed=0)
env.step(env.action_space.sample())
os.kill(os.getpid(), signal.SIGTERM)
time.sleep(5)
print("survived SIGTERM")
"""


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_sigterm_ends_a_process_with_an_open_window() -> None:
    pytest.importorskip("pygame")
    env = {**os.environ, "SDL_VIDEODRIVER": "dummy", "PYTHONPATH": str(REPO / "envs")}
    env.pop("SDL_NO_SIGNAL_HANDLERS", None)
    completed = subprocess.run(
        [sys.executable, "-c", SCRIPT], capture_output=True, text=True, timeout=60, env=env, cwd=REPO
    )
    assert "survived" not in completed.stdout
    assert completed.returncode == -signal.SIGTERM, completed.stderr[-2000:]
