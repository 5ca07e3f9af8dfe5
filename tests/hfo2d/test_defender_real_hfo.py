"""hfo2d's field defenders against real HFO's (benchmarks/defender_fidelity.py): a short real session with
client logs, then each real defender's commands replayed on its own inputs. Needs an HFO build ($HFO_DIR) and a
loopback-only network namespace (``HFO_DIR=... tools/real_hfo/loopback.sh python -m pytest
tests/hfo2d/test_defender_real_hfo.py``); skips otherwise."""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import pytest

from hfo2d import real


def _build() -> Path | None:
    candidate = os.environ.get(real.HFO_DIR_ENV)
    if not candidate:
        return None
    try:
        return real.find_hfo_dir(candidate)
    except FileNotFoundError:
        return None


BUILD = _build()
needs_real_hfo = pytest.mark.skipif(
    BUILD is None or not real.in_loopback_namespace(),
    reason="needs an HFO build ($HFO_DIR) and a loopback-only network namespace (tools/real_hfo/loopback.sh)",
)


@needs_real_hfo
def test_real_defenders_commands_are_reproduced(
    tmp_path: Path, benchmark_script: Callable[[str], ModuleType]
) -> None:
    fidelity = benchmark_script("defender_fidelity")
    fidelity.main(
        [
            "run",
            "--hfo-dir",
            str(BUILD),
            "--work-dir",
            str(tmp_path),
            "--defense-npcs",
            "3",
            "--trials",
            "6",
            "--seed",
            "3",
            "--port",
            "6950",
            "--deterministic",
            "--timeout",
            "300",
        ]
    )
    log_dir = tmp_path / "logs_d3_det_s3"
    parser = fidelity.build_parser()
    result = fidelity.cmd_replay(parser.parse_args(["replay", str(log_dir), "--show", "0"]))
    by_branch = result["summary"]["by_branch"]
    # positioning (BasicMove's go-to-point and turn to the ball) is the bulk of a field defender's cycles
    moved, moved_ok = (sum(by_branch.get(b, [0, 0])[i] for b in ("move", "turn_to_ball")) for i in (0, 1))
    assert moved > 300
    assert moved_ok / moved > 0.98
    off_ball = [r for r in result["mismatches"] if r["branch"] not in ("hold", "force_kick")]
    cycles = result["summary"]["cycles"]
    assert len(off_ball) / cycles < 0.02
