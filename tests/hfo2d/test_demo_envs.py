"""``python -m hfo2d.demo --env`` offers every hfo2d task, HFO's own goalie (``HFO/Keeper-v1``) included (issue 35,
defect 9)."""

from __future__ import annotations

import pytest

import hfo2d
from hfo2d import demo


def test_demo_offers_every_hfo2d_env() -> None:
    assert "HFO/Keeper-v1" in hfo2d.ENV_IDS
    assert set(demo.ENV_IDS) == set(hfo2d.ENV_IDS)


def test_demo_plays_keeper_v1(capsys: pytest.CaptureFixture[str]) -> None:
    demo.main(["--env", "HFO/Keeper-v1", "--episodes", "1", "--render-mode", "none", "--seed", "0"])
    assert "HFO/Keeper-v1: scored" in capsys.readouterr().out
