"""The committed models (sb3_hfo.models): stripped files act as the full ones, the manifest, names on the CLIs."""

from __future__ import annotations

import io
import json
import os
import subprocess
import sys
import zipfile
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
import torch

import hfo2d  # noqa: F401  (registers the HFO/* ids)
from sb3_hfo import SkillDDPG
from sb3_hfo.cli.errors import UsageExit, UserError
from sb3_hfo.cli.models import build_parser, playback_argv
from sb3_hfo.evaluation import evaluate, wilson_interval
from sb3_hfo.models import (
    MANIFEST_PATH,
    MAX_MODEL_BYTES,
    MODELS_DIR,
    POLICY_ENTRY,
    STRIPPED_ENTRY,
    full_model_buffer,
    is_stripped,
    load_model,
    read_manifest,
    strip_model,
)
from sb3_hfo.skill_ddpg.acting import CriticChoice, MirrorChoice, format_acting, parse_acting

REPO = Path(__file__).resolve().parents[2]


def _trained_model(tmp_path: Path, **policy_kwargs: object) -> Path:
    """A small two-skill SkillDDPG trained for a few hundred steps: its optimizers have state and its target
    networks differ from the online ones."""
    model = SkillDDPG(
        "HFOPolicy",
        gym.make("HFO/EmptyGoal-v0"),
        learning_starts=50,
        batch_size=16,
        tau=0.05,
        seed=0,
        policy_kwargs=dict(net_arch=[16, 8], n_skills=2, mask_unused_parameters=True, **policy_kwargs),
    )
    model.learn(150)
    model.policy.acting = (CriticChoice(),)  # acting strategies switched after construction travel too
    path = tmp_path / "full.zip"
    model.save(path)
    return path


def _observations(n: int) -> np.ndarray:
    space = gym.make("HFO/EmptyGoal-v0").observation_space
    space.seed(0)
    return np.stack([space.sample() for _ in range(n)])


def test_a_stripped_model_acts_exactly_as_the_full_one(tmp_path: Path) -> None:
    full_path = _trained_model(tmp_path)
    stripped_path = tmp_path / "stripped.zip"
    size = strip_model(full_path, stripped_path)
    assert size == stripped_path.stat().st_size < full_path.stat().st_size / 2
    assert is_stripped(stripped_path) and not is_stripped(full_path)
    full, stripped = SkillDDPG.load(full_path, device="cpu"), load_model(stripped_path, device="cpu")
    observations = _observations(300)
    full_actions, _ = full.predict(observations, deterministic=True)
    stripped_actions, _ = stripped.predict(observations, deterministic=True)
    np.testing.assert_array_equal(full_actions, stripped_actions)
    assert stripped.policy.acting == (CriticChoice(),) and stripped.policy.n_skills == 2
    # what was dropped: the target networks (rebuilt as the online ones) and the optimizers' moments
    for online, target in (
        (stripped.policy.actor, stripped.policy.actor_target),
        (stripped.policy.critic, stripped.policy.critic_target),
    ):
        for a, b in zip(online.parameters(), target.parameters(), strict=True):
            assert torch.equal(a, b)
    assert any(
        not torch.equal(a, b)
        for a, b in zip(full.policy.actor.parameters(), full.policy.actor_target.parameters(), strict=True)
    )
    # load_model reads a full zip as SkillDDPG.load does
    again, _ = load_model(full_path, device="cpu").predict(observations, deterministic=True)
    np.testing.assert_array_equal(again, full_actions)


def test_a_stripped_zip_holds_no_target_network_and_no_optimizer_state(tmp_path: Path) -> None:
    stripped_path = tmp_path / "stripped.zip"
    strip_model(_trained_model(tmp_path), stripped_path)
    with zipfile.ZipFile(stripped_path) as archive:
        names = archive.namelist()
        policy = torch.load(io.BytesIO(archive.read(POLICY_ENTRY)), weights_only=True)
        optimizers = [
            torch.load(io.BytesIO(archive.read(name)), weights_only=True)
            for name in names
            if name.endswith("optimizer.pth")
        ]
        recorded = json.loads(archive.read(STRIPPED_ENTRY))["targets"]
    assert not [key for key in policy if "_target" in key.split(".")[0]]
    assert recorded and all(source in policy for source in recorded.values())
    assert len(optimizers) == 3 and all(opt["state"] == {} and opt["param_groups"] for opt in optimizers)
    with zipfile.ZipFile(full_model_buffer(stripped_path)) as rebuilt:
        assert STRIPPED_ENTRY not in rebuilt.namelist()
    with pytest.raises(UserError, match="already stripped"):
        strip_model(stripped_path, tmp_path / "twice.zip")


def test_add_strips_checks_evaluates_and_writes_the_manifest_entry(tmp_path: Path) -> None:
    from sb3_hfo.cli.models import add

    full_path = _trained_model(tmp_path)
    manifest = tmp_path / "models" / "manifest.json"
    args = build_parser().parse_args(
        ["add", "tiny", str(full_path), "--config", "zoo_configs/e1_empty_goal_fast.yml", "--seed", "3"]
        + ["--env", "HFO/EmptyGoal-v0", "--episodes", "3", "--acting", "critic,mirror"]
        + ["--real-hfo", "2/4", "--real-hfo-env", "HFO/RealEmptyGoal-v0", "--real-hfo-source", "a test"]
    )
    entry = add(args, manifest_path=manifest)
    assert read_manifest(manifest) == {"tiny": entry}
    model = manifest.parent / "tiny.zip"
    assert entry["file"] == "tiny.zip" and entry["bytes"] == model.stat().st_size and is_stripped(model)
    assert entry["env_id"] == "HFO/EmptyGoal-v0" and entry["seed"] == 3
    assert entry["acting"] == "critic,mirror" and "acting_options" not in entry
    # the strategies are saved in the committed file
    assert load_model(model).policy.acting == (CriticChoice(), MirrorChoice())
    evaluation = entry["evaluation"]
    assert evaluation["episodes"] == 3 and evaluation["model"] == "models/tiny.zip"
    assert evaluation["acting"] == "critic,mirror"  # evaluated as it is committed
    again = evaluate(str(model), env_id="HFO/EmptyGoal-v0", episodes=3, seed=0)
    assert evaluation["goals"] == again.goals and evaluation["status_counts"] == again.status_counts
    real = entry["real_hfo"]
    assert real["goals"] == 2 and real["scoring_rate_ci95"] == list(wilson_interval(2, 4))

    # a real-HFO evaluate --json of that file replaces the figure, with its end counts; other files are refused
    from sb3_hfo.cli.models import record_real_hfo

    measured = {"model": str(model), "env_id": "HFO/RealEmptyGoal-v0", "goals": 3, "episodes": 5}
    measured["status_counts"] = {"GOAL": 3, "OUT_OF_TIME": 2}
    real_json = tmp_path / "real.json"
    real_json.write_text(json.dumps(measured))
    real_args = build_parser().parse_args(["real", "tiny", str(real_json), "--source", "a test run"])
    recorded = record_real_hfo(real_args, manifest_path=manifest)["real_hfo"]
    assert read_manifest(manifest)["tiny"]["real_hfo"] == recorded
    assert recorded["goals"] == 3 and recorded["status_counts"] == measured["status_counts"]
    assert recorded["source"] == "a test run" and recorded["scoring_rate_ci95"] == list(wilson_interval(3, 5))
    refusals = [
        ({**measured, "model": str(full_path)}, "not the committed tiny.zip"),
        ({**measured, "env_id": "HFO/EmptyGoal-v0"}, "not a real-HFO env"),
        ({"goals": 1}, "no episodes, env_id"),
    ]
    for bad, message in refusals:
        real_json.write_text(json.dumps(bad))
        with pytest.raises(UserError, match=message):
            record_real_hfo(real_args, manifest_path=manifest)
    assert read_manifest(manifest)["tiny"]["real_hfo"] == recorded


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (
            ["add", "no/slash", "m.zip", "--config", "zoo_configs/e1_empty_goal_fast.yml", "--seed", "0"],
            "name",
        ),
        (
            ["add", "x", "nowhere.zip", "--config", "zoo_configs/e1_empty_goal_fast.yml", "--seed", "0"],
            "not found",
        ),
        (["add", "x", "e1", "--config", "nowhere.yml", "--seed", "0"], "--config nowhere.yml: no such file"),
        (["add", "x", "e1", "--config", "zoo_configs/e1_empty_goal_fast.yml", "--seed", "-1"], "--seed"),
    ],
)
def test_add_names_a_bad_input_in_one_line(
    argv: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    from sb3_hfo.cli.models import main

    with pytest.raises(UsageExit) as raised:
        main(argv)
    assert raised.value.code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err, err


# --- the committed models ---------------------------------------------------------------------------------------

MANIFEST = read_manifest()


def test_models_holds_only_the_manifest_and_its_models() -> None:
    files = {path.name for path in MODELS_DIR.iterdir()}
    assert files == {MANIFEST_PATH.name, *(entry["file"] for entry in MANIFEST.values())}
    assert 1 <= len(MANIFEST) <= 6


@pytest.mark.parametrize("name", sorted(MANIFEST))
def test_a_committed_model_is_small_stripped_and_matches_its_manifest_entry(name: str) -> None:
    import hashlib

    entry = MANIFEST[name]
    path = MODELS_DIR / entry["file"]
    assert path.stat().st_size == entry["bytes"] <= MAX_MODEL_BYTES
    assert hashlib.sha256(path.read_bytes()).hexdigest() == entry["sha256"]
    assert is_stripped(path) and (REPO / entry["config"]).is_file()
    evaluation = entry["evaluation"]
    assert evaluation["episodes"] == 1000 and evaluation["env_id"] == entry["env_id"]
    assert evaluation["scoring_rate"] == evaluation["goals"] / evaluation["episodes"]
    assert tuple(evaluation["scoring_rate_ci95"]) == wilson_interval(
        evaluation["goals"], evaluation["episodes"]
    )
    assert sum(evaluation["status_counts"].values()) == evaluation["episodes"]
    model = load_model(path, device="cpu", buffer_size=1)
    env = gym.make(entry["env_id"], **entry["env_kwargs"])
    assert model.observation_space.shape == env.observation_space.shape
    env.close()
    assert model.policy.acting == parse_acting(entry["acting"])
    assert format_acting(model.policy.acting) == entry["acting"] == evaluation["acting"]  # the text form
    real = entry["real_hfo"]
    if real:
        assert real["env_id"].startswith("HFO/Real") and real["source"]
        assert tuple(real["scoring_rate_ci95"]) == wilson_interval(real["goals"], real["episodes"])


# --- continuing to train a committed model ------------------------------------------------------------------


@pytest.mark.parametrize("n_envs", [1, 2])
def test_a_committed_model_continues_training_with_any_number_of_envs(
    n_envs: int, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """e1 was trained with 4 envs: its saved action noise is for 4 (issue 35, defect 1: a reshape error on 1)."""
    from stable_baselines3.common.env_util import make_vec_env
    from stable_baselines3.common.noise import VectorizedActionNoise

    monkeypatch.chdir(tmp_path)
    saved = load_model("e1", device="cpu", buffer_size=1).action_noise
    assert isinstance(saved, VectorizedActionNoise) and saved.n_envs == 4  # the premise
    env = gym.make("HFO/EmptyGoal-v0") if n_envs == 1 else make_vec_env("HFO/EmptyGoal-v0", n_envs=n_envs)
    model = load_model("e1", env=env, device="cpu", buffer_size=500, learning_starts=0, batch_size=8)
    model.learn(40)
    noises = getattr(model.action_noise, "noises", [model.action_noise])
    assert len(noises) == n_envs
    for noise in noises:  # the saved noise's kind and scale, for each env
        assert type(noise) is type(saved.noises[0])
        np.testing.assert_array_equal(noise._sigma, saved.noises[0]._sigma)
    assert model.num_timesteps >= 40


def test_a_loaded_model_logs_to_tensorboard_only_where_told(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The saved tensorboard_log (the training run's, e.g. tbX5S1/) is not where a user's run should write."""
    monkeypatch.chdir(tmp_path)
    model = load_model("e1", env=gym.make("HFO/EmptyGoal-v0"), device="cpu", buffer_size=500)
    assert model.tensorboard_log is None
    model.learn(5)
    assert list(tmp_path.iterdir()) == []  # no stray log folder in the working directory
    logs = tmp_path / "my_logs"
    told = load_model("e1", env=gym.make("HFO/EmptyGoal-v0"), buffer_size=500, tensorboard_log=str(logs))
    assert told.tensorboard_log == str(logs)
    told.learn(5)
    assert [path.name for path in tmp_path.iterdir()] == ["my_logs"] and any(logs.rglob("events.out.*"))


# --- names on the command lines ---------------------------------------------------------------------------------


def test_load_model_takes_a_manifest_name() -> None:
    name, entry = next(iter(MANIFEST.items()))
    model = load_model(name, device="cpu", buffer_size=1)
    assert model.observation_space.shape == gym.make(entry["env_id"]).observation_space.shape
    with pytest.raises(UserError, match="names: "):
        load_model("no_such_model")


def test_evaluate_takes_a_manifest_name_with_its_env() -> None:
    name, entry = next(iter(MANIFEST.items()))
    result = evaluate(name, episodes=1, seed=0)
    assert result.env_id == entry["env_id"] and result.env_kwargs == entry["env_kwargs"]
    assert Path(result.model) == MODELS_DIR / entry["file"]


@pytest.mark.parametrize("tool", ["evaluate", "enjoy", "record_video"])
def test_an_unknown_name_is_one_line_listing_the_names(tool: str, capsys: pytest.CaptureFixture[str]) -> None:
    import importlib

    main = importlib.import_module(f"sb3_hfo.{tool}").main
    try:
        code = main(["no_such_model", "-n", "5"] if tool != "evaluate" else ["no_such_model"])
    except SystemExit as exit:
        code = exit.code
    assert code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "'no_such_model'" in err
    assert all(name in err for name in MANIFEST)


def test_playback_argv_lays_a_model_out_as_an_rl_zoo3_run(tmp_path: Path) -> None:
    name, entry = next(iter(MANIFEST.items()))
    argv = playback_argv([name, "-n", "5"], tmp_path)
    assert argv[:2] == ["-n", "5"] and argv[argv.index("--env") + 1] == entry["env_id"]
    assert argv[-4:] == ["-f", str(tmp_path), "--exp-id", "1"]
    env_name = entry["env_id"].replace("/", "-")
    linked = tmp_path / "skill_ddpg" / f"{env_name}_1" / f"{env_name}.zip"
    assert linked.resolve() == (MODELS_DIR / entry["file"]).resolve()
    assert playback_argv(["--env", "HFO/EmptyGoal-v0", "-f", "logs"], tmp_path) == [
        "--env",
        "HFO/EmptyGoal-v0",
        "-f",
        "logs",
    ]
    with pytest.raises(UserError, match="either a MODEL"):
        playback_argv([name, "-f", "logs"], tmp_path / "other")


def _run_tool(args: list[str], cwd: Path) -> subprocess.CompletedProcess[str]:
    env = {
        **os.environ,
        "SDL_VIDEODRIVER": "dummy",
        "PYTHONPATH": os.pathsep.join([str(REPO), str(REPO / "envs")]),
    }
    return subprocess.run(
        [sys.executable, "-m", *args], capture_output=True, text=True, timeout=300, cwd=cwd, env=env
    )


@pytest.mark.xdist_group("playback")
def test_enjoy_and_record_video_play_a_committed_model_by_name(tmp_path: Path) -> None:
    pytest.importorskip("pygame")
    pytest.importorskip("moviepy")
    watched = _run_tool(["sb3_hfo.enjoy", "e1", "-n", "30", "--no-render"], tmp_path)
    assert watched.returncode == 0, watched.stderr[-2000:]
    recorded = _run_tool(["sb3_hfo.record_video", "e1", "-n", "20"], tmp_path)
    assert recorded.returncode == 0, recorded.stderr[-2000:]
    videos = list((tmp_path / "videos").glob("*.mp4"))  # the default -o of a committed model
    assert len(videos) == 1 and videos[0].stat().st_size > 1000


def test_train_warm_starts_from_a_committed_model(tmp_path: Path) -> None:
    config = REPO / "zoo_configs" / "empty_goal_skill_pdqn_fast.yml"
    command = ["sb3_hfo.train", "--env", "HFO/EmptyGoal-v0", "--conf-file", str(config), "-n", "64"]
    command += ["--seed", "0", "-f", "logs", "--eval-freq", "-1", "-i", str(MODELS_DIR / "e1.zip")]
    completed = _run_tool(command, tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    assert "Loading pretrained agent" in completed.stdout
    assert (tmp_path / "logs" / "skill_ddpg" / "HFO-EmptyGoal-v0_1" / "HFO-EmptyGoal-v0.zip").is_file()


@pytest.mark.parametrize(("video", "missing"), [(False, "pygame"), (True, "moviepy")])
def test_playback_names_the_render_extra_when_its_modules_are_missing(
    video: bool, missing: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    import importlib.util

    from sb3_hfo.cli.errors import check_render_extra

    real_find_spec = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == missing else real_find_spec(name, *a)
    )
    with pytest.raises(
        UserError, match=rf'needs {missing}, from the \[render\] extra: pip install -e "\.\[render\]"'
    ):
        check_render_extra(video=video)
