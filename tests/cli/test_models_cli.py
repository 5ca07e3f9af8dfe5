"""The committed models' command line (sb3_hfo.cli.models: add, real) and their names on enjoy, record_video,
evaluate and train."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from sb3_hfo.cli.errors import UsageExit, UserError
from sb3_hfo.cli.models import build_parser, playback_argv
from sb3_hfo.evaluation import evaluate, wilson_interval
from sb3_hfo.models import MODELS_DIR, is_stripped, load_model, read_manifest
from sb3_hfo.skill_ddpg.acting import CriticChoice, MirrorChoice

REPO = Path(__file__).resolve().parents[2]
MANIFEST = read_manifest()


def test_add_strips_checks_evaluates_and_writes_the_manifest_entry(tmp_path: Path) -> None:
    from sb3_hfo.cli.models import add

    full_path = tmp_path / "full.zip"
    load_model("e1_skill_pdqn", device="cpu", buffer_size=1).save(
        full_path
    )  # a full zip (target networks, optimizers)
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


# --- names on the command lines ---------------------------------------------------------------------------------


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


@pytest.mark.parametrize(("name", "algo"), [("e1", "hybrid_ppo"), ("e1_skill_pdqn", "skill_ddpg")])
def test_playback_argv_lays_a_model_out_as_an_rl_zoo3_run(name: str, algo: str, tmp_path: Path) -> None:
    """The run layout is the saved model's algorithm's (a HybridPPO zip under "hybrid_ppo", else "skill_ddpg")."""
    entry = MANIFEST[name]
    argv = playback_argv([name, "-n", "5"], tmp_path)
    assert argv[:2] == ["-n", "5"] and argv[argv.index("--env") + 1] == entry["env_id"]
    assert argv[argv.index("--algo") + 1] == algo
    assert argv[-4:] == ["-f", str(tmp_path), "--exp-id", "1"]
    env_name = entry["env_id"].replace("/", "-")
    linked = tmp_path / algo / f"{env_name}_1" / f"{env_name}.zip"
    assert linked.resolve() == (MODELS_DIR / entry["file"]).resolve()
    given = playback_argv([name, "--algo", "skill_ddpg", "-n", "5"], tmp_path / "given")
    assert given.count("--algo") == 1  # an explicit --algo is the user's
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
    command += ["--seed", "0", "-f", "logs", "--eval-freq", "-1", "-i", str(MODELS_DIR / "e1_skill_pdqn.zip")]
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


def test_add_takes_a_hybrid_ppo_model(tmp_path: Path) -> None:
    """A HybridPPO zip is stripped, checked, evaluated and recorded like a SkillDDPG one (no acting strategies)."""
    from sb3_hfo.cli.models import add
    from sb3_hfo.hybrid_ppo import HybridPPO

    full_path = tmp_path / "hybrid.zip"
    HybridPPO("MlpPolicy", "HFO/EmptyGoal-v0", n_steps=32, batch_size=32, seed=0).save(full_path)
    manifest = tmp_path / "models" / "manifest.json"
    command = [
        "add",
        "hybrid",
        str(full_path),
        "--config",
        "zoo_configs/hybrid_ppo_empty_goal.yml",
        "--seed",
        "0",
    ]
    command += ["--env", "HFO/EmptyGoal-v0", "--episodes", "2"]
    entry = add(build_parser().parse_args(command), manifest_path=manifest)
    assert entry["acting"] is None and entry["evaluation"]["episodes"] == 2
    assert isinstance(load_model(manifest.parent / "hybrid.zip"), HybridPPO)
    with pytest.raises(UserError, match="no acting strategies"):
        add(build_parser().parse_args([*command, "--acting", "critic"]), manifest_path=manifest)


def test_add_records_a_benchmark_script_s_model_with_the_evaluation_of_its_source(tmp_path: Path) -> None:
    """--script/--command give a model without a zoo config ("config": null); --evaluation-json takes the
    evaluation of SOURCE itself, and refuses one of another file or of other settings."""
    from dataclasses import asdict

    from sb3_hfo.cli.models import add
    from sb3_hfo.hybrid_ppo import HybridPPO

    full_path = tmp_path / "final.zip"
    HybridPPO("MlpPolicy", "HFO/EmptyGoal-v0", n_steps=32, batch_size=32, seed=0).save(full_path)
    result = asdict(evaluate(str(full_path), env_id="HFO/EmptyGoal-v0", episodes=3, seed=0))
    evaluation_json = tmp_path / "eval.json"
    evaluation_json.write_text(json.dumps(result))  # as evaluate --json writes it
    manifest = tmp_path / "models" / "manifest.json"
    script = "benchmarks/rl_from_clone.py"
    command = [
        "add",
        "scripted",
        str(full_path),
        "--seed",
        "2",
        "--env",
        "HFO/EmptyGoal-v0",
        "--episodes",
        "3",
    ]
    provenance = ["--script", script, "--command", f"python {script} --seed 2 --out DIR"]
    entry = add(
        build_parser().parse_args([*command, *provenance, "--evaluation-json", str(evaluation_json)]),
        manifest_path=manifest,
    )
    assert (
        entry["config"] is None
        and entry["script"] == script
        and entry["command"].startswith("python " + script)
    )
    evaluation = entry["evaluation"]
    assert evaluation["goals"] == result["goals"] and evaluation["status_counts"] == result["status_counts"]
    assert evaluation["model"] == "models/scripted.zip"  # the committed copy, which acts as SOURCE does
    import hashlib

    assert entry["evaluated_file"] == {
        "file": "final.zip",
        "sha256": hashlib.sha256(full_path.read_bytes()).hexdigest(),
    }
    again = evaluate(str(manifest.parent / "scripted.zip"), env_id="HFO/EmptyGoal-v0", episodes=3, seed=0)
    assert again.goals == evaluation["goals"] and again.status_counts == evaluation["status_counts"]

    other = tmp_path / "other.zip"
    HybridPPO("MlpPolicy", "HFO/EmptyGoal-v0", n_steps=32, batch_size=32, seed=1).save(other)
    refusals = [
        ([*command, *provenance, "--evaluation-json", str(tmp_path / "none.json")], "no such file"),
        ([*command, "--config", "zoo_configs/hybrid_ppo_empty_goal.yml", *provenance], "not both"),
        ([*command, "--script", script], "--script FILE with --command LINE"),
        ([*command, "--script", script, "--command", "python other.py"], "needs the command"),
    ]
    for argv, message in refusals:
        with pytest.raises(UserError, match=message):
            add(build_parser().parse_args(argv), manifest_path=manifest)
    for changed, message in (({"model": str(other)}, "sha256 differs"), ({"seed": 5}, "seed 5")):
        evaluation_json.write_text(json.dumps({**result, **changed}))
        with pytest.raises(UserError, match=message):
            add(
                build_parser().parse_args([*command, *provenance, "--evaluation-json", str(evaluation_json)]),
                manifest_path=manifest,
            )
    committed = manifest.parent / "scripted.zip"
    assert read_manifest(manifest) == {"scripted": entry}  # the refusals changed nothing
    assert hashlib.sha256(committed.read_bytes()).hexdigest() == entry["sha256"]


def test_running_the_library_module_names_the_command_line() -> None:
    """``python -m sb3_hfo.models list`` ran the library module and printed nothing, exit 0."""
    done = subprocess.run(
        [sys.executable, "-m", "sb3_hfo.models", "list"], capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.strip().splitlines() == [
        "error: sb3_hfo.models is the library; its command line is python -m sb3_hfo.cli.models "
        "(list, add NAME MODEL ..., real NAME ...)"
    ]
