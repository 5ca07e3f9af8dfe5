"""Defects 4-9 of issue 35, each pinned by a test that failed before its fix.

4: ``-optimize`` drew ``noise_type: none`` for configs whose ``ActionNoiseDecayCallback`` rejects it;
5: ``enjoy`` drew every frame twice (half speed), ignored SIGTERM with its window open and said nothing headless;
6: a mistyped hyperparameter was a 50-line traceback and left an empty run folder;
7: ``record_video`` wrote yuv444p (H.264 High 4:4:4), which browsers and QuickTime do not play;
8: ``record_video -o`` to a folder it cannot create was a traceback;
9: README snippets and the ``.gitignore`` (the README's own tests are in this file too).
"""

from __future__ import annotations

import os
import subprocess
import sys
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

    from sb3_hfo.cli import zoo

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
    from sb3_hfo.cli.train import main

    logs = tmp_path / "logs"
    line = _one_line_error(capsys, main, _train_argv(logs, "--hyperparams", hyperparams))
    assert key in line and f"did you mean {suggestion}?" in line and "valid: " in line
    assert not logs.exists()


def test_train_config_key_typo_is_one_line(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    from sb3_hfo.cli.train import main

    text = (CONFIGS / "e1_empty_goal_fast.yml").read_text()
    assert "\n  tau: 0.001\n" in text
    config = tmp_path / "typo.yml"
    config.write_text(text.replace("\n  tau: 0.001\n", "\n  taau: 0.001\n"))
    logs = tmp_path / "logs"
    line = _one_line_error(capsys, main, _train_argv(logs, config=config))
    assert str(config) in line and "'taau'" in line and "did you mean 'tau'?" in line
    assert not logs.exists()


def test_train_failing_at_setup_leaves_no_run_folder(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    """A value the constructor rejects fails after rl-zoo3 made the run folder; the folder goes with the run, so
    the next run is still ``_1``, and the constructor's message is one line (it was a 40-line traceback)."""
    from sb3_hfo.cli.train import main

    logs = tmp_path / "logs"
    line = _one_line_error(capsys, main, _train_argv(logs, "--hyperparams", "mc_mixing:2.0"))
    assert "mc_mixing must lie in [0, 1], got 2.0" in line and "--hyperparams" in line
    assert not logs.exists()


def test_a_bad_hybrid_ppo_value_is_one_line(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    from sb3_hfo.cli.train import main

    config = CONFIGS / "hybrid_ppo_empty_goal.yml"
    argv = _train_argv(
        tmp_path / "logs", "--algo", "hybrid_ppo", "--hyperparams", "policy_kwargs:dict(skills=0)"
    )
    line = _one_line_error(capsys, main, [*argv[:3], str(config), *argv[4:]])
    assert "skills must be an integer >= 1, got 0" in line


def test_only_the_algorithms_own_checks_become_one_line() -> None:
    """A ValueError from elsewhere (rl-zoo3, an env, a bug) keeps its traceback."""
    from sb3_hfo.cli.zoo import raised_by_algorithm_checks
    from sb3_hfo.skill_ddpg import SkillDDPG

    with pytest.raises(ValueError) as from_algorithm:
        SkillDDPG("HFOPolicy", "HFO/EmptyGoal-v0", mc_mixing=2.0)
    assert raised_by_algorithm_checks(from_algorithm.value)
    with pytest.raises(ValueError) as from_elsewhere:
        int("not a number")
    assert not raised_by_algorithm_checks(from_elsewhere.value)


# --- 7, 8: record_video -------------------------------------------------------------------------------------------


def _video_stream(path: Path) -> tuple[str, str, int, int]:
    """Codec, pixel format, width and height of ``path``'s video stream, by ffprobe when installed, else from
    ``ffmpeg -i`` (imageio-ffmpeg, a moviepy dependency, ships an ffmpeg binary)."""
    import re
    import shutil
    import subprocess

    ffprobe = shutil.which("ffprobe")
    if ffprobe is not None:
        entries = "stream=codec_name,pix_fmt,width,height"
        command = [
            ffprobe,
            "-v",
            "error",
            "-select_streams",
            "v:0",
            "-show_entries",
            entries,
            "-of",
            "json",
            str(path),
        ]
        import json

        stream = json.loads(subprocess.run(command, capture_output=True, text=True, check=True).stdout)[
            "streams"
        ][0]
        return stream["codec_name"], stream["pix_fmt"], int(stream["width"]), int(stream["height"])
    imageio_ffmpeg = pytest.importorskip("imageio_ffmpeg")
    info = subprocess.run(
        [imageio_ffmpeg.get_ffmpeg_exe(), "-hide_banner", "-i", str(path)], capture_output=True, text=True
    )
    match = re.search(r"Video: (\w+).*?, (\w+)\(?[^,]*, (\d+)x(\d+)", info.stderr)
    assert match is not None, info.stderr
    return match[1], match[2], int(match[3]), int(match[4])


def test_even_frame_repeats_the_last_column_and_row() -> None:
    import numpy as np

    from sb3_hfo.cli.record_video import even_frame

    frame = np.arange(740 * 585 * 3, dtype=np.int64).reshape(740, 585, 3).astype(np.uint8)
    padded = even_frame(frame)
    assert padded.shape == (740, 586, 3)
    assert np.array_equal(padded[:, :585], frame) and np.array_equal(padded[:, 585], frame[:, 584])
    assert even_frame(frame[:739]).shape == (740, 586, 3)
    assert np.array_equal(even_frame(padded), padded)  # even sides are left as they are


@pytest.mark.xdist_group("playback")
def test_record_video_writes_h264_yuv420p_with_even_sides(tmp_path: Path) -> None:
    """yuv444p (H.264 High 4:4:4), moviepy's default for RGB frames, plays in neither browsers nor QuickTime."""
    pytest.importorskip("pygame")
    pytest.importorskip("moviepy")
    from sb3_hfo.cli.record_video import main

    main(["e1", "-n", "10", "-o", str(tmp_path / "videos")])
    (video,) = (tmp_path / "videos").glob("*.mp4")
    codec, pixel_format, width, height = _video_stream(video)
    assert (codec, pixel_format) == ("h264", "yuv420p")
    assert width % 2 == 0 and height % 2 == 0


def test_record_video_to_a_folder_it_cannot_create_is_one_line(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    from sb3_hfo.cli.record_video import main

    blocker = tmp_path / "a_file"
    blocker.write_text("not a folder\n")
    line = _one_line_error(capsys, main, ["e1", "-n", "10", "-o", str(blocker / "videos")])
    assert str(blocker / "videos") in line and f"{blocker} is a file" in line
    line = _one_line_error(capsys, main, ["e1", "-n", "10", "-o", str(blocker)])
    assert "it is a file" in line


def test_record_video_to_a_read_only_folder_is_one_line(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    import os

    from sb3_hfo.cli.record_video import main

    read_only = tmp_path / "read_only"
    read_only.mkdir(mode=0o555)
    if os.access(read_only, os.W_OK):
        pytest.skip("this user may write anywhere (root)")
    line = _one_line_error(capsys, main, ["e1", "-n", "10", "-o", str(read_only / "videos")])
    assert "not writable" in line and not (read_only / "videos").exists()


# --- 5: enjoy ---------------------------------------------------------------------------------------------------


@pytest.mark.xdist_group("playback")
def test_enjoy_draws_each_step_once_and_says_when_no_window_shows(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """Every reset and step draws one frame, held to 10 fps: rl-zoo3's extra ``render("human")`` drew each one
    twice (half speed). Headless, one ``note:`` line says that nothing is shown, and the run goes on."""
    pytest.importorskip("pygame")
    import hfo2d.rendering
    from hfo2d.hfo_env import HFOEnv
    from sb3_hfo.cli.enjoy import main

    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    monkeypatch.setattr(hfo2d.rendering, "RENDER_FPS", 10_000)  # the count matters here, not the clock
    counts = {"draws": 0, "steps and resets": 0}

    def counting(method: Callable[..., Any], key: str) -> Callable[..., Any]:
        def counted(*args: Any, **kwargs: Any) -> Any:
            counts[key] += 1
            return method(*args, **kwargs)

        return counted

    monkeypatch.setattr(
        hfo2d.rendering.HFORenderer, "render", counting(hfo2d.rendering.HFORenderer.render, "draws")
    )
    for name in ("step", "reset"):
        monkeypatch.setattr(HFOEnv, name, counting(getattr(HFOEnv, name), "steps and resets"))
    main(["e1", "-n", "30"])
    assert counts["steps and resets"] >= 31
    assert counts["draws"] == counts["steps and resets"]
    notes = [line for line in capsys.readouterr().err.splitlines() if line.startswith("note:")]
    assert len(notes) == 1 and "'dummy'" in notes[0] and "--no-render" in notes[0]


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="X11 / Wayland displays are Linux's")
def test_without_x11_or_wayland_enjoy_picks_the_offscreen_driver_without_sdl_s_error_line() -> None:
    """With neither DISPLAY nor WAYLAND_DISPLAY, SDL probed Wayland and printed libwayland's "error:
    XDG_RUNTIME_DIR is invalid or not set" before falling back to "offscreen", on a run that then played on; the
    driver is now chosen outright, so the note is the only line."""
    pytest.importorskip("pygame")
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER")}
    env.pop("XDG_RUNTIME_DIR", None)
    code = "from sb3_hfo.cli.enjoy import display_driver; print(display_driver())"
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip() == "offscreen"
    assert "error" not in done.stderr.lower(), done.stderr
    env["SDL_VIDEODRIVER"] = "dummy"  # a driver the user asked for is kept
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert done.stdout.strip() == "dummy"


# --- 9: the README --------------------------------------------------------------------------------------------------

README = (REPO / "README.md").read_text()


def _python_blocks() -> list[str]:
    import re

    return re.findall(r"```python\n(.*?)```", README, re.S)


def _undefined_names(code: str) -> set[str]:
    """Names that ``code`` reads as globals without importing, assigning or defining them (nor builtins)."""
    import builtins
    import symtable

    module = symtable.symtable(code, "<README>", "exec")
    defined = {
        s.get_name() for s in module.get_symbols() if s.is_assigned() or s.is_imported() or s.is_namespace()
    }
    undefined: set[str] = set()
    tables = [module]
    while tables:
        table = tables.pop()
        for symbol in table.get_symbols():
            reads_global = symbol.is_referenced() and (table is module or symbol.is_global())
            name = symbol.get_name()
            if reads_global and name not in defined and not hasattr(builtins, name):
                undefined.add(name)
        tables += table.get_children()
    return undefined


def test_readme_python_snippets_import_what_they_use() -> None:
    """Each snippet runs on its own: it imports every name it uses (clone_striker's lacked SkillDDPG), and its
    imports work."""
    import ast

    blocks = _python_blocks()
    assert len(blocks) >= 4 and any("clone_striker" in block for block in blocks)
    for block in blocks:
        assert _undefined_names(block) == set(), block
        imports = [node for node in ast.parse(block).body if isinstance(node, (ast.Import, ast.ImportFrom))]
        exec(compile(ast.Module(body=imports, type_ignores=[]), "<README>", "exec"), {})


def test_undefined_names_finds_a_missing_import() -> None:
    assert _undefined_names("import os\nmodel = SkillDDPG(os.sep)\ndef f():\n    return clone(model)\n") == {
        "SkillDDPG",
        "clone",
    }


def test_readme_names_the_goal_rate_tag_that_training_logs() -> None:
    """Every ``rollout/...`` tag the README names is one a short run with a fast config's callbacks logs."""
    import re

    import gymnasium as gym
    import numpy as np
    from stable_baselines3.common.logger import KVWriter, Logger
    from stable_baselines3.common.noise import NormalActionNoise

    from sb3_hfo import SkillDDPG
    from sb3_hfo.callbacks import ActionNoiseDecayCallback, HFOEpisodeStatsCallback

    class Keys(KVWriter):
        def __init__(self) -> None:
            self.keys: set[str] = set()

        def write(self, key_values: dict[str, Any], key_excluded: dict[str, Any], step: int = 0) -> None:
            excluded = {key for key, formats in key_excluded.items() if formats and "tensorboard" in formats}
            self.keys |= set(key_values) - excluded

    named = set(re.findall(r"`(rollout/\w+)`", README))
    assert "rollout/success_rate" in named
    keys = Keys()
    noise = NormalActionNoise(np.zeros(8), np.full(8, 0.2))
    model = SkillDDPG("HFOPolicy", gym.make(ENV), learning_starts=10**6, action_noise=noise, seed=0)
    model.set_logger(Logger(folder=None, output_formats=[keys]))
    callbacks = [HFOEpisodeStatsCallback(), ActionNoiseDecayCallback(final_std=0.05, decay_fraction=0.7)]
    model.learn(400, callback=callbacks, log_interval=1)
    assert named <= keys.keys, named - keys.keys


def test_readme_playback_examples_name_the_quick_starts_run() -> None:
    """The quick start trains one run, so the examples after it can only name its ``_1`` folders."""
    import re

    assert "-f logs/quickstart" in README and "--tensorboard-log runs/tb" in README
    runs = re.findall(
        r"(?:runs/tb/HFO-\w+-v\d/SkillDDPG|logs/quickstart/skill_ddpg/HFO-\w+-v\d)_(\d+)", README
    )
    assert runs and set(runs) == {"1"}


def test_what_the_readme_examples_write_is_git_ignored() -> None:
    import shutil
    import subprocess

    if shutil.which("git") is None or not (REPO / ".git").exists():
        pytest.skip("not a git checkout")
    written = ["figure3.png", "results/e1.json", "videos/x.mp4", "logs/quickstart/a", "runs/tb/b"]
    completed = subprocess.run(["git", "check-ignore", *written], cwd=REPO, capture_output=True, text=True)
    assert completed.stdout.split() == written
