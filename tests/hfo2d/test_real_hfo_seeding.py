"""Seeds of the real HFO (hfo2d.real): whether a build repeats its noise, and, with a build, that it does.

Without a build (CI) only the detection runs, on stand-in builds. The real sessions need ``$HFO_DIR`` (a build made
by ``tools/real_hfo/build.sh``) and a loopback-only network namespace (``tools/real_hfo/loopback.sh python -m
pytest ...``) or ``HFO_TESTS=1``; otherwise they skip.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

from hfo2d import real
from hfo2d.heuristic import heuristic


def _stand_in_build(root: Path, server_bytes: bytes) -> Path:
    """A folder with the files find_hfo_dir checks, and a bin/rcssserver holding ``server_bytes``."""
    for name in ("bin/HFO", "hfo/hfo.py", "hfo/libhfo_c.so"):
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text("")
    (root / "bin" / "rcssserver").write_bytes(server_bytes)
    return root


def test_a_patched_server_is_detected(tmp_path: Path) -> None:
    build = _stand_in_build(
        tmp_path, b"\x7fELF...HFORef using seed: \x00" + real.SEEDED_NOISE_MARKER + b": \x00"
    )
    assert real.server_seeds_noise(build)
    assert real.RealHFOEnv(hfo_dir=build).noise_seeded


def test_a_stock_server_does_not_seed_its_noise(tmp_path: Path) -> None:
    build = _stand_in_build(tmp_path, b"\x7fELF...HFORef using seed: \x00Simulator Random Seed: \x00")
    assert not real.server_seeds_noise(build)
    assert not real.RealHFOEnv(hfo_dir=build).noise_seeded
    # without noise nothing random is left: a seed fixes the episodes on any server
    assert real.RealHFOEnv(hfo_dir=build, noise=False).noise_seeded
    # no server binary at all: nothing is promised
    (build / "bin" / "rcssserver").unlink()
    assert not real.server_seeds_noise(build)


def _real_build() -> Path | None:
    if not os.environ.get(real.HFO_DIR_ENV):
        return None
    try:
        return real.find_hfo_dir()
    except real.HFOBuildNotFound:
        return None


REAL_BUILD = _real_build()
needs_real_hfo = pytest.mark.skipif(
    REAL_BUILD is None or not (os.environ.get("HFO_TESTS") == "1" or real.in_loopback_namespace()),
    reason="needs an HFO build ($HFO_DIR, tools/real_hfo/build.sh) and a loopback-only network namespace "
    "(tools/real_hfo/loopback.sh) or HFO_TESTS=1",
)


def _episodes(seed: int, episodes: int) -> list[np.ndarray]:
    """Every observation of ``episodes`` episodes of the scripted striker against agent2d's goalie, noise on."""
    env = real.RealHFOEnv(task="keeper", hfo_dir=REAL_BUILD, seed=seed)
    played = []
    try:
        for _ in range(episodes):
            obs, _ = env.reset()
            trajectory = [obs]
            done = False
            while not done:
                obs, _, terminated, truncated, _ = env.step(heuristic(env, obs))
                trajectory.append(obs)
                done = terminated or truncated
            played.append(np.array(trajectory))
    finally:
        env.close()
    return played


@needs_real_hfo
def test_one_seed_repeats_its_episodes_with_noise_on() -> None:
    assert REAL_BUILD is not None
    if not real.server_seeds_noise(REAL_BUILD):
        pytest.skip(
            "a stock rcssserver repeats only the start positions of a seed (tools/real_hfo/build.sh patches)"
        )
    first, second = _episodes(seed=5, episodes=6), _episodes(seed=5, episodes=6)
    assert [len(e) for e in first] == [len(e) for e in second]
    for one, other in zip(first, second, strict=True):
        np.testing.assert_array_equal(one, other)
    # and the noise is on: another seed plays otherwise
    other_seed = _episodes(seed=6, episodes=1)
    assert other_seed[0].shape != first[0].shape or not np.array_equal(other_seed[0], first[0])
