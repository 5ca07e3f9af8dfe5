"""rl-zoo3 integration: configs, train / evaluate / plot / record_video command lines, error messages.

The expensive part is one subprocess (``trained_runs``) that trains every config in ``zoo_configs/`` in turn for
a few hundred steps with tiny networks, through the same ``sb3_hfo.train`` code path as the documented
commands; per-config tests then read its report. Everything else runs in-process or in short subprocesses.
Under pytest-xdist use ``--dist loadgroup`` so that the training runs once (the tests share an xdist group).
"""

from __future__ import annotations

import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest
import yaml

pytestmark = pytest.mark.xdist_group("zoo")

REPO = Path(__file__).resolve().parents[2]
CONFIG_DIR = REPO / "zoo_configs"
CONFIGS = sorted(CONFIG_DIR.glob("*.yml"))
CONFIG_NAMES = [path.stem for path in CONFIGS]
#: The ablation lineage behind the committed models: checked for validity here, not smoke-trained.
RESEARCH_CONFIGS = sorted((REPO / "research" / "zoo_configs").glob("*.yml"))
EXPERIMENTS = ("e1", "e2", "e3", "e4", "e5", "e6")

#: Smoke-run settings: a few hundred steps, tiny networks, a small buffer, log every episode.
SMOKE_STEPS = 250
SMOKE_NET_ARCH = [16, 16]


def _load_config(path: Path) -> tuple[str, dict[str, Any]]:
    with open(path) as f:
        content = yaml.safe_load(f)
    assert isinstance(content, dict) and content, f"{path.name}: expected an env id entry"
    # One experiment per file: a second env id (E6 on HFO/Keeper-v1 beside v0) must be an alias of the first.
    (env_id, hyperparams), *others = content.items()
    for other_id, other in others:
        assert other == hyperparams, f"{path.name}: {other_id} must repeat {env_id}'s settings (a YAML alias)"
    return env_id, hyperparams


def _algo(config: Path) -> str:
    """The ``--algo`` a config's header command names (SkillPDQN, the preset, for the best configs; HybridPPO's
    configs say ``hybrid_ppo``); ``skill_ddpg`` when it names none."""
    named = re.search(r"--algo (\w+) ", config.read_text())
    return named.group(1) if named else "skill_ddpg"


#: Configs of HybridPPO (on-policy): no replay buffer, SkillDDPG's keys do not apply.
HYBRID_PPO_CONFIGS = [config for config in CONFIGS if _algo(config) == "hybrid_ppo"]


def _env_dir(env_id: str) -> str:
    # rl-zoo3 (huggingface_sb3.EnvironmentName) replaces "/" by "-" in folder names.
    return env_id.replace("/", "-")


#: Smoke-run sizes of the callbacks that play a scripted striker before training.
SMOKE_CALLBACK_KWARGS = {
    "sb3_hfo.demonstrations.StrikerCloningCallback": {"rounds": 1, "episodes_per_round": 2, "epochs": 1},
    "sb3_hfo.demonstrations.DemonstrationPrefillCallback": {"episodes": 2},
}


def _smoke_callback(callback: str | dict[str, Any]) -> str | dict[str, Any]:
    if not isinstance(callback, dict):
        return callback
    ((name, kwargs),) = callback.items()
    return {name: {**(kwargs or {}), **SMOKE_CALLBACK_KWARGS.get(name, {})}}


def _smoke_argv(config: Path, root: Path) -> list[str]:
    env_id, hyperparams = _load_config(config)
    # --hyperparams replaces whole values, so the config's policy_kwargs are kept and only net_arch shrinks.
    policy_kwargs = {**(hyperparams.get("policy_kwargs") or {}), "net_arch": SMOKE_NET_ARCH}
    # Steps are counted over all environments: each of a config's n_envs gets SMOKE_STEPS, enough to end episodes.
    n_envs = int(hyperparams.get("n_envs", 1))
    argv = [
        "--algo",
        _algo(config),
        "--env",
        env_id,
        "--conf-file",
        str(config),
        "--seed",
        "0",
        "-n",
        str(SMOKE_STEPS * n_envs),
        "--log-interval",
        "1",
        "--tensorboard-log",
        str(root / "tb" / config.stem),
        "-f",
        str(root / "logs" / config.stem),
        "--num-threads",
        "1",
        "--hyperparams",
        *(
            ["n_steps:64", "batch_size:64"]
            if config in HYBRID_PPO_CONFIGS
            else ["learning_starts:100", "buffer_size:2000"]
        ),
        f"policy_kwargs:{policy_kwargs!r}",
    ]
    # A scripted striker's episodes before training cost minutes at a config's size: a few are enough here.
    callbacks = [_smoke_callback(callback) for callback in hyperparams.get("callback") or []]
    if callbacks != (hyperparams.get("callback") or []):
        argv.append(f"callback:{callbacks!r}")
    # One run exercises rl-zoo3's periodic evaluation callback too.
    argv += (
        ["--eval-freq", str(200 * n_envs), "--eval-episodes", "1"]
        if config.stem == "e1_empty_goal_fast"
        else ["--eval-freq", "-1"]
    )
    return argv


# Trains every config in one interpreter (imports of torch / SB3 / rl-zoo3 dominate a single run's cost) and
# records, per config, either "ok" or the traceback, so one broken config fails only its own test.
DRIVER = """
import json, sys, traceback
from sb3_hfo.cli.train import main
argvs, report_path = json.loads(sys.argv[1]), sys.argv[2]  # main() replaces sys.argv
report = {}
for name, argv in argvs.items():
    try:
        main(argv)
        report[name] = "ok"
    except BaseException:
        report[name] = traceback.format_exc()
with open(report_path, "w") as f:
    json.dump(report, f)
"""


def _run(args: list[str], cwd: Path, timeout: float = 120) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "SDL_VIDEODRIVER": "dummy", "MPLBACKEND": "Agg", "OMP_NUM_THREADS": "1"}
    return subprocess.run(
        [sys.executable, *args],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )


@pytest.fixture(scope="module")
def trained_runs(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict[str, str], str]:
    """Train every config briefly; returns (root folder, per-config report, combined output)."""
    root = tmp_path_factory.mktemp("zoo")
    argvs = {config.stem: _smoke_argv(config, root) for config in CONFIGS}
    report_file = root / "report.json"
    result = _run(["-c", DRIVER, json.dumps(argvs), str(report_file)], cwd=root, timeout=300)
    assert report_file.is_file(), (
        f"training driver crashed:\n{result.stdout[-3000:]}\n{result.stderr[-3000:]}"
    )
    return root, json.loads(report_file.read_text()), result.stdout + result.stderr


def _model_path(root: Path, config_name: str) -> Path:
    config = CONFIG_DIR / f"{config_name}.yml"
    env_id, _ = _load_config(config)
    return root / "logs" / config_name / _algo(config) / f"{_env_dir(env_id)}_1" / f"{_env_dir(env_id)}.zip"


# ------------------------------------------------------------------------------------------------------------------
# Configs (no training)


def test_every_experiment_has_a_paper_and_a_fast_config() -> None:
    for experiment in EXPERIMENTS:
        names = [name for name in CONFIG_NAMES if name.startswith(experiment + "_")]
        assert len([n for n in names if n.endswith("_fast")]) == 1, f"{experiment}: {names}"
        assert len([n for n in names if not n.endswith("_fast")]) == 1, f"{experiment}: {names}"


def test_zoo_configs_are_the_paper_s_and_one_per_committed_model() -> None:
    """zoo_configs/ holds the paper's experiments and the configs of the committed models (sb3_hfo/pretrained/manifest.json);
    the rest is in research/zoo_configs/."""
    from sb3_hfo.models import read_manifest

    # a model that a benchmark script made has no config ("config": null; tests/sb3_hfo/test_models.py)
    manifest_configs = {entry["config"] for entry in read_manifest().values() if entry["config"] is not None}
    for config in manifest_configs:
        assert (REPO / config).is_file(), config
    for config in CONFIGS:
        if (
            config.stem.startswith(EXPERIMENTS) or config in HYBRID_PPO_CONFIGS
        ):  # HybridPPO: no model committed yet
            continue
        assert f"zoo_configs/{config.name}" in manifest_configs, config.name
    assert RESEARCH_CONFIGS, "research/zoo_configs/ is empty"
    assert not {c.name for c in CONFIGS} & {c.name for c in RESEARCH_CONFIGS}


@pytest.mark.parametrize(
    "config",
    # HybridPPO's configs are new here, not renamed research configs: they have no research ancestor
    [c for c in CONFIGS if not c.stem.startswith(EXPERIMENTS) and c not in HYBRID_PPO_CONFIGS],
    ids=lambda c: c.stem,
)
def test_a_committed_model_s_config_is_named_by_task_with_its_lineage(config: Path) -> None:
    """Named by its task, not by the research diary's id; its header's lineage names the research config it was
    and the public config it descends from (one of the paper's, or a sibling's whose lineage goes on)."""
    import re

    assert not re.match(r"x\d+_", config.name), config.name
    _, found, rest = config.read_text().partition("\n# Lineage: ")
    assert found, f"{config.name}: no '# Lineage:' line in its header"
    lineage = rest.split("\n#\n", 1)[0]
    assert re.match(r"research config x\d+ \(this file was zoo_configs/x\d+_[a-z0-9_]+\.yml", lineage), (
        lineage
    )
    ancestors = set(re.findall(r"(?<![/\w])([a-z][a-z0-9_]*\.yml)", lineage)) - {config.name}
    assert ancestors and all((CONFIG_DIR / name).is_file() for name in ancestors), ancestors


@pytest.mark.parametrize(
    "config", CONFIGS + RESEARCH_CONFIGS, ids=[str(c.relative_to(REPO)) for c in CONFIGS + RESEARCH_CONFIGS]
)
def test_config_is_valid_and_documents_its_command(config: Path) -> None:
    import hfo2d

    env_id, hyperparams = _load_config(config)
    assert env_id in hfo2d.ENV_IDS
    if config in HYBRID_PPO_CONFIGS:
        for key in ("gamma", "batch_size", "n_steps", "n_epochs", "n_timesteps"):
            assert isinstance(hyperparams[key], (int, float)), f"{key} = {hyperparams[key]!r}"
        learning_rate = hyperparams["learning_rate"]
        assert isinstance(learning_rate, (int, float)) or re.fullmatch(r"lin_[0-9.]+", learning_rate)
        conf_file = config.relative_to(REPO).as_posix()
        assert (
            f"python -m sb3_hfo.train --algo hybrid_ppo --env {env_id} --conf-file {conf_file} --seed 0"
            in config.read_text()
        )
        return
    for key in ("tau", "gamma", "batch_size", "buffer_size", "n_timesteps"):
        # PyYAML reads "1e-4" (no dot) as a string; every number must really be a number.
        assert isinstance(hyperparams[key], (int, float)), f"{key} = {hyperparams[key]!r}"
    for key in ("learning_rate_actor", "learning_rate_critic"):
        learning_rate = hyperparams[key]
        assert isinstance(learning_rate, (int, float)) or re.fullmatch(r"lin_[0-9.]+", learning_rate), (
            f"{key} = {learning_rate!r}"
        )
    text = config.read_text()
    conf_file = config.relative_to(REPO).as_posix()
    command = (
        f"python -m sb3_hfo.train --algo {_algo(config)} --env {env_id} --conf-file {conf_file} --seed 0"
    )
    assert command in text, f"{conf_file} must document its own command line"
    skills = 2 if "skills" in config.stem else 1
    assert hyperparams["policy_kwargs"]["n_skills"] == skills
    assert hyperparams["policy_kwargs"].get("inverting_gradients", False) is ("inverting" in config.stem)


# Only the e-configs claim the paper's settings; x-configs (beyond the paper) may differ in anything.
PAPER_CONFIGS = [c for c in CONFIGS if c.stem.startswith(EXPERIMENTS) and not c.stem.endswith("_fast")]


@pytest.mark.parametrize("config", PAPER_CONFIGS, ids=lambda c: c.stem)
def test_paper_configs_use_the_paper_settings(config: Path) -> None:
    _, hyperparams = _load_config(config)
    assert hyperparams["batch_size"] == 32
    assert hyperparams["learning_rate_actor"] == pytest.approx(1e-4)
    assert hyperparams["learning_rate_critic"] == "lin_0.001"
    assert hyperparams["tau"] == pytest.approx(1e-4)
    assert hyperparams["train_freq"] == 1 and hyperparams["gradient_steps"] == 1
    assert hyperparams["n_timesteps"] == 50_000 * 500
    expected_arch = [1024, 512, 256, 128] if "inverting" in config.stem else [400, 300, 200]
    assert hyperparams["policy_kwargs"]["net_arch"] == expected_arch
    assert {
        "stable_baselines3.common.callbacks.StopTrainingOnMaxEpisodes": {"max_episodes": 50_000}
    } in hyperparams["callback"]


# ------------------------------------------------------------------------------------------------------------------
# Pure helpers


def test_wilson_interval_matches_reference_values() -> None:
    from sb3_hfo.evaluation import wilson_interval

    assert wilson_interval(0, 10) == pytest.approx((0.0, 0.2775), abs=1e-4)
    assert wilson_interval(5, 10) == pytest.approx((0.2366, 0.7634), abs=1e-4)
    assert wilson_interval(10, 10) == pytest.approx((0.7225, 1.0), abs=1e-4)
    assert wilson_interval(0, 0) == (0.0, 1.0)


def test_summarize_counts_goals_kicks_and_skills() -> None:
    from sb3_hfo.evaluation import EpisodeRecord, summarize

    records = [
        EpisodeRecord("GOAL", 80, 6.0, 3, [100.0, 50.0, 30.0], 10, [60, 20]),
        EpisodeRecord("GOAL", 120, 5.0, 1, [90.0], 0, [100, 20]),
        EpisodeRecord("OUT_OF_BOUNDS", 50, -1.0, 2, [10.0, 20.0], 5, [50, 0]),
    ]
    result = summarize(
        records, model="m.zip", env_id="HFO/EmptyGoal-v0", seed=0, deterministic=True, n_skills=2
    )
    assert result.goals == 2 and result.scoring_rate == pytest.approx(2 / 3)
    assert result.mean_steps_to_goal == pytest.approx(100.0)  # scoring episodes only
    assert result.kicks_per_goal == pytest.approx(2.0)  # (3 + 1) kicks / 2 goals
    assert result.mean_kick_power == pytest.approx(50.0)  # over all 6 executed kicks
    assert result.dribble_fraction == pytest.approx(15 / 250)
    assert result.skill_fractions == pytest.approx([210 / 250, 40 / 250])
    assert result.status_counts == {"GOAL": 2, "OUT_OF_BOUNDS": 1}
    assert result.mean_shot_distance is None  # no record says where its last kick was taken
    assert all(counts == {"episodes": 0, "goals": 0} for counts in result.shots_by_distance.values())


def test_summarize_bins_last_kicks_by_distance_to_goal() -> None:
    from sb3_hfo.evaluation import EpisodeRecord, shot_distance_label, summarize

    def record(status: str, shot_distance: float | None) -> EpisodeRecord:
        return EpisodeRecord(status, 10, 0.0, 1, [100.0], 0, [10], shot_distance=shot_distance)

    records = [
        record("GOAL", 12.0),
        record("GOAL", 25.0),
        record("CAPTURED_BY_DEFENSE", 28.0),
        record("OUT_OF_BOUNDS", 45.0),
        record("GOAL", 45.0),
        record("OUT_OF_TIME", None),  # never kicked: in no bin and not in the mean
    ]
    result = summarize(
        records, model="m", env_id="HFO/StaticKeeper-v0", seed=0, deterministic=True, n_skills=1
    )
    assert result.mean_shot_distance == pytest.approx((12 + 25 + 28 + 45 + 45) / 5)
    assert result.shots_by_distance == {
        "0-20 m": {"episodes": 1, "goals": 1},
        "20-30 m": {"episodes": 2, "goals": 1},
        "30-40 m": {"episodes": 0, "goals": 0},
        ">= 40 m": {"episodes": 2, "goals": 1},
    }
    assert shot_distance_label(20.0) == "20-30 m" and shot_distance_label(39.99) == "30-40 m"


def test_evaluation_measures_the_shot_from_where_the_ball_was_kicked() -> None:
    import gymnasium as gym

    from sb3_hfo.evaluation import run_episodes, summarize

    class PlacedStart(gym.Wrapper):  # facing the goal centre, ball 0.5 m ahead: 22 m out
        def reset(self, *, seed: int | None = None, options: dict | None = None) -> tuple:
            return self.env.reset(seed=seed, options={"player": (30.0, 0.0, 0.0), "ball": (30.5, 0.0)})

    class KickStraightAhead:
        def predict(self, obs: np.ndarray, state=None, episode_start=None, deterministic=False) -> tuple:
            return np.array([0, 0, 1, 0, 0.5, 0.5, 1.0, 0.5], dtype=np.float32), None

    env = PlacedStart(gym.make("HFO/EmptyGoal-v0"))
    records = run_episodes(KickStraightAhead(), env, episodes=3, seed=0, deterministic=True, n_skills=1)
    assert [r.kicks for r in records] == [1, 1, 1]  # later KICKs miss the ball that has left
    assert [r.shot_distance for r in records] == pytest.approx([22.0] * 3)
    result = summarize(records, model="m", env_id="HFO/EmptyGoal-v0", seed=0, deterministic=True, n_skills=1)
    assert result.shots_by_distance["20-30 m"]["episodes"] == 3
    assert result.shots_by_distance["20-30 m"]["goals"] == result.goals


@pytest.mark.parametrize(
    ("player", "ball", "line"),
    [
        ((50.0, 20.0, 0.0), (50.5, 20.0), "goal_line"),  # a shot wide of the post
        ((20.0, 33.0, 90.0), (20.0, 33.5), "side_line"),
        ((1.0, 0.0, 180.0), (0.5, 0.0), "halfway_line"),
    ],
)
def test_evaluation_names_the_line_an_out_of_bounds_ball_crossed(
    player: tuple[float, float, float], ball: tuple[float, float], line: str
) -> None:
    import gymnasium as gym

    from sb3_hfo.evaluation import run_episodes, summarize

    class PlacedStart(gym.Wrapper):
        def reset(self, *, seed: int | None = None, options: dict | None = None) -> tuple:
            return self.env.reset(seed=seed, options={"player": player, "ball": ball})

    class KickStraightAhead:  # full power along the body
        def predict(self, obs: np.ndarray, state=None, episode_start=None, deterministic=False) -> tuple:
            return np.array([0, 0, 1, 0, 0.5, 0.5, 1.0, 0.5], dtype=np.float32), None

    env = PlacedStart(gym.make("HFO/EmptyGoal-v0"))
    records = run_episodes(KickStraightAhead(), env, episodes=2, seed=0, deterministic=True, n_skills=1)
    assert [(r.status, r.exit) for r in records] == [("OUT_OF_BOUNDS", line)] * 2
    for record in records:  # the recorded end position is past the line it names, and there is no keeper
        x, y = record.end_ball  # type: ignore[misc]
        assert {"goal_line": x > 52.5, "side_line": abs(y) > 34.0, "halfway_line": x < 0.0}[line]
        assert record.end_keeper is None
    result = summarize(records, model="m", env_id="HFO/EmptyGoal-v0", seed=0, deterministic=True, n_skills=1)
    assert result.out_of_bounds_exits == {
        name: 2 * (name == line) for name in ("goal_line", "side_line", "halfway_line")
    }


def test_evaluation_records_where_the_keeper_caught_the_ball() -> None:
    import gymnasium as gym

    from sb3_hfo.evaluation import run_episodes

    class PlacedStart(gym.Wrapper):  # 12 m out, facing the static keeper on the goal centre
        def reset(self, *, seed: int | None = None, options: dict | None = None) -> tuple:
            return self.env.reset(seed=seed, options={"player": (40.0, 0.0, 0.0), "ball": (40.5, 0.0)})

    class KickSoftlyAhead:  # power 60 along the body, straight at the keeper
        def predict(self, obs: np.ndarray, state=None, episode_start=None, deterministic=False) -> tuple:
            return np.array([0, 0, 1, 0, 0.5, 0.5, 0.6, 0.5], dtype=np.float32), None

    env = PlacedStart(gym.make("HFO/StaticKeeper-v0"))
    records = run_episodes(KickSoftlyAhead(), env, episodes=2, seed=0, deterministic=True, n_skills=1)
    for record in records:
        assert record.status == "CAPTURED_BY_DEFENSE"
        keeper_x, keeper_y = record.end_keeper  # type: ignore[misc]
        ball_x, ball_y = record.end_ball  # type: ignore[misc]
        assert math.dist((keeper_x, keeper_y), (ball_x, ball_y)) < 2.0  # caught within the keeper's reach
        assert 40.5 < ball_x < 52.5


def test_evaluation_loop_counts_goals_and_kicks_of_a_scoring_policy() -> None:
    import gymnasium as gym

    import hfo2d
    from sb3_hfo.evaluation import run_episodes, summarize

    env = gym.make("HFO/EmptyGoal-v0")

    class ScriptedStriker:  # the model interface run_episodes needs: predict(obs) -> (action, state)
        def predict(self, obs: np.ndarray, state=None, episode_start=None, deterministic=False) -> tuple:
            return hfo2d.heuristic(env, obs), None

    records = run_episodes(ScriptedStriker(), env, episodes=5, seed=0, deterministic=True, n_skills=1)
    result = summarize(
        records, model="heuristic", env_id="HFO/EmptyGoal-v0", seed=0, deterministic=True, n_skills=1
    )
    assert result.episodes == 5 and sum(result.status_counts.values()) == 5
    assert result.goals >= 3  # the scripted striker scores nearly always against an empty goal
    assert (
        result.kicks_per_goal is not None and result.kicks_per_goal >= 1.0
    )  # a goal needs at least one kick
    assert result.mean_kick_power is not None and 0.0 < result.mean_kick_power <= 100.0
    assert result.mean_steps_to_goal is not None and 0 < result.mean_steps_to_goal < 500
    assert 0.0 < result.dribble_fraction < 1.0  # it runs onto the ball before kicking


def test_parse_schedule_handles_rl_zoo_strings() -> None:
    from sb3_hfo.common.schedules import parse_schedule

    schedule = parse_schedule("lin_0.001")
    assert schedule(1.0) == pytest.approx(1e-3) and schedule(0.5) == pytest.approx(5e-4)
    assert parse_schedule(0.0003) == pytest.approx(3e-4)
    assert parse_schedule("0.0003") == pytest.approx(3e-4)
    with pytest.raises(ValueError, match="unknown schedule"):
        parse_schedule("exp_0.1")


def test_optuna_sampler_returns_constructor_arguments() -> None:
    import optuna

    from sb3_hfo.cli.hyperparams_opt import NET_ARCHS, convert_skill_ddpg_params, sample_skill_ddpg_params

    study = optuna.create_study(sampler=optuna.samplers.RandomSampler(seed=0))
    trial = study.ask()
    sampled = sample_skill_ddpg_params(trial, n_actions=8, n_envs=1, additional_args={})
    assert 0.95 <= sampled["gamma"] < 1.0
    assert sampled["gradient_steps"] == sampled["train_freq"]
    assert sampled["policy_kwargs"]["net_arch"] in NET_ARCHS.values()
    assert callable(sampled["learning_rate_critic"]) or isinstance(sampled["learning_rate_critic"], float)
    assert "noise_type" not in sampled and "action_noise" in sampled
    # --trial-id path: raw Optuna values -> config-file values.
    converted = convert_skill_ddpg_params(trial.params)
    assert converted["batch_size"] == 2 ** trial.params["batch_size_pow"]


def test_wrapper_defaults_algo_and_threads_but_keeps_explicit_values() -> None:
    from sb3_hfo.cli.zoo import default_algo_argv

    assert default_algo_argv(["--env", "X"], single_thread=True) == [
        "--algo",
        "skill_ddpg",
        "--env",
        "X",
        "--num-threads",
        "1",
    ]
    assert default_algo_argv(["--algo=td3", "--num-threads", "4"], single_thread=True) == [
        "--algo=td3",
        "--num-threads",
        "4",
    ]


def test_train_reports_unknown_env_and_missing_config_in_one_line() -> None:
    from sb3_hfo.cli.train import main

    with pytest.raises(
        SystemExit, match=r"unknown env id 'HFO/NoSuchTask-v0'; registered HFO ids: .*HFO/Keeper-v0"
    ):
        main(["--env", "HFO/NoSuchTask-v0", "--conf-file", "zoo_configs/e1_empty_goal_fast.yml"])
    with pytest.raises(SystemExit, match="--conf-file is required"):
        main(["--env", "HFO/EmptyGoal-v0"])


@pytest.mark.parametrize(
    ("cli_env_kwargs", "cli_eval_env_kwargs", "expected_train", "expected_eval"),
    [
        (None, None, "shaped_gap", "shaped_gap"),
        ({"reward": "sparse"}, None, "sparse", "sparse"),
        (None, {"reward": "shaped"}, "shaped_gap", "shaped"),
    ],
)
def test_evaluation_env_gets_the_configs_env_kwargs(
    tmp_path: Path,
    cli_env_kwargs: dict[str, str] | None,
    cli_eval_env_kwargs: dict[str, str] | None,
    expected_train: str,
    expected_eval: str,
) -> None:
    from sb3_hfo.cli.zoo import _experiment_manager_class, register_with_rl_zoo

    register_with_rl_zoo()
    config = tmp_path / "gap.yml"
    config.write_text(
        "HFO/StaticKeeper-v0:\n  env_kwargs:\n    reward: shaped_gap\n  n_timesteps: 100\n  policy: MlpPolicy\n"
    )
    manager = _experiment_manager_class()(
        SimpleNamespace(),
        "skill_ddpg",
        "HFO/StaticKeeper-v0",
        str(tmp_path),
        env_kwargs=cli_env_kwargs,
        eval_env_kwargs=cli_eval_env_kwargs,
        config=str(config),
        verbose=0,
    )
    hyperparams, _ = manager.read_hyperparameters()
    manager._preprocess_hyperparams(hyperparams)
    assert manager.env_kwargs == {"reward": expected_train}
    assert manager.eval_env_kwargs == {"reward": expected_eval}


def test_merge_policy_kwargs_keeps_the_experiment_keys() -> None:
    from sb3_hfo.cli.zoo import merge_policy_kwargs

    def sampler(*_: Any) -> dict[str, Any]:
        return {"policy_kwargs": {"net_arch": [8]}}

    merged = merge_policy_kwargs(sampler, {"n_skills": 2, "net_arch": [400]})()
    assert merged["policy_kwargs"] == {"n_skills": 2, "net_arch": [8]}


def test_moving_average_and_episode_estimate() -> None:
    from sb3_hfo.cli.plot import Run, moving_average

    assert moving_average(np.array([1.0, 3.0, 5.0, 7.0]), 2) == pytest.approx([1.0, 2.0, 4.0, 6.0])
    run = Run("r", {"rollout/ep_len_mean": (np.array([100.0, 300.0]), np.array([100.0, 50.0]))})
    episodes, name = run.episodes_at(np.array([100.0, 300.0]))
    assert name == "episodes (estimated)" and episodes == pytest.approx([1.0, 5.0])


def test_time_to_targets_reads_the_first_evaluation_at_each_rate() -> None:
    from sb3_hfo.cli.plot import EVAL_SUCCESS_TAG, Run, time_to_targets

    steps = np.array([10_000.0, 20_000.0, 30_000.0, 40_000.0])
    run = Run("r", {EVAL_SUCCESS_TAG: (steps, np.array([0.5, 0.96, 0.9, 0.99]))})
    run.wall_clock[EVAL_SUCCESS_TAG] = np.array([60.0, 120.0, 180.0, 240.0])
    summary = time_to_targets(run, [0.95, 0.98, 1.0])
    assert summary["first_0.95"] == (20_000, 120.0)
    assert summary["first_0.98"] == (40_000, 240.0)
    assert summary["first_1"] is None
    assert summary["last"] == pytest.approx(0.99) and summary["best"] == pytest.approx(0.99)
    assert time_to_targets(Run("no eval"), [0.95])["first_0.95"] is None
    # TensorBoard keeps float32: an evaluation of exactly 45 / 50 comes back as 0.89999998 and still counts as 90 %
    stored = Run("tb", {EVAL_SUCCESS_TAG: (steps[:2], np.array([0.5, 0.9], dtype=np.float32).astype(float))})
    stored.wall_clock[EVAL_SUCCESS_TAG] = np.array([60.0, 120.0])
    assert time_to_targets(stored, [0.9])["first_0.9"] == (20_000, 120.0)


def test_episode_stats_callback_logs_episodes_and_leaves_the_goal_rate_to_sb3() -> None:
    from sb3_hfo.callbacks import HFOEpisodeStatsCallback

    class Recorder:
        def __init__(self) -> None:
            self.values: dict[str, float] = {}

        def record(self, key: str, value: float) -> None:
            self.values[key] = value

    callback = HFOEpisodeStatsCallback()
    recorder = Recorder()
    callback.model = SimpleNamespace(logger=recorder)  # type: ignore[assignment]  (BaseCallback.logger reads it)
    for dones in ([True], [False], [True, True]):
        callback.locals = {
            "dones": np.array(dones),
            "infos": [{"status": "GOAL", "is_success": True}] * len(dones),
        }
        callback._on_step()
    assert recorder.values == {"rollout/episodes": 3}


def test_plot_reads_the_goal_rate_of_older_runs(tmp_path: Path) -> None:
    from stable_baselines3.common.logger import configure

    from sb3_hfo.cli.plot import GOAL_RATE_TAG, load_run

    assert GOAL_RATE_TAG == "rollout/success_rate"
    for name, tag, value in (("old", "rollout/goal_rate", 0.25), ("new", GOAL_RATE_TAG, 0.75)):
        logger = configure(str(tmp_path / name), ["tensorboard"])
        logger.record(tag, value)
        logger.dump(step=100)
        logger.close()
        run = load_run(tmp_path / name, name)
        steps, values = run.scalars[GOAL_RATE_TAG]
        assert steps.tolist() == [100.0] and values.tolist() == [value]


def test_keeper_skill_curriculum_ramps_the_training_envs_only() -> None:
    from stable_baselines3.common.callbacks import BaseCallback
    from stable_baselines3.common.env_util import make_vec_env

    from sb3_hfo import SkillDDPG
    from sb3_hfo.callbacks import KeeperSkillCurriculumCallback

    class SkillRecorder(BaseCallback):
        def __init__(self) -> None:
            super().__init__()
            self.skills: list[list[float]] = []

        def _on_step(self) -> bool:
            self.skills.append(self.training_env.get_attr("keeper_skill"))
            return True

    env = make_vec_env("HFO/Keeper-v0", n_envs=2, seed=0)
    # learning_starts beyond the budget: only the rollout runs, no gradient step.
    model = SkillDDPG("HFOPolicy", env, learning_starts=10_000, seed=0)
    curriculum = KeeperSkillCurriculumCallback(
        initial_skill=0.0, final_skill=1.0, ramp_fraction=0.5, skill_step=0.25
    )
    recorder = SkillRecorder()
    model.learn(400, callback=[curriculum, recorder])  # 200 calls of 2 envs; the ramp spans the first 100
    per_call = [skills[0] for skills in recorder.skills]
    assert all(skills[0] == skills[1] for skills in recorder.skills)
    assert per_call[0] == 0.0
    assert per_call == sorted(per_call)
    assert set(per_call) == {0.0, 0.25, 0.5, 0.75, 1.0}
    # rounded to the nearest step: 1.0 from 87.5 % of the ramp (176 of its 200 steps), held to the end
    assert per_call.index(1.0) == 87
    assert per_call.index(0.25) == 12
    with pytest.raises(ValueError, match="needs HFO/Keeper-v0 training envs"):
        SkillDDPG("HFOPolicy", "HFO/EmptyGoal-v0", learning_starts=10_000).learn(
            2, callback=curriculum.__class__()
        )
    with pytest.raises(ValueError, match="ramp_fraction"):
        KeeperSkillCurriculumCallback(ramp_fraction=0.0)
    with pytest.raises(ValueError, match="initial_skill"):
        KeeperSkillCurriculumCallback(initial_skill=float("nan"))


def test_action_noise_decay_callback_anneals_sigma_per_env() -> None:
    from stable_baselines3 import TD3
    from stable_baselines3.common.callbacks import BaseCallback
    from stable_baselines3.common.env_util import make_vec_env
    from stable_baselines3.common.noise import NormalActionNoise

    from sb3_hfo.callbacks import ActionNoiseDecayCallback

    class SigmaRecorder(BaseCallback):
        def __init__(self) -> None:
            super().__init__()
            self.sigmas: list[float] = []

        def _on_step(self) -> bool:
            self.sigmas.append(float(self.model.action_noise.noises[1]._sigma[0]))
            return True

    env = make_vec_env("Pendulum-v1", n_envs=2, seed=0)
    noise = NormalActionNoise(mean=np.zeros(1), sigma=np.full(1, 0.4))
    # learning_starts beyond the budget: only the rollout (and its noise) runs, no gradient step.
    model = TD3("MlpPolicy", env, action_noise=noise, learning_starts=1_000, seed=0)
    recorder = SigmaRecorder()
    model.learn(80, callback=[ActionNoiseDecayCallback(final_std=0.1, decay_fraction=0.5), recorder])
    # 2 envs: 40 callback calls, 2 timesteps each; the decay ends at timestep 40 (half of 80).
    assert recorder.sigmas[9] == pytest.approx(0.4 - 0.3 * 20 / 40)
    assert recorder.sigmas[19:] == pytest.approx([0.1] * 21)
    assert model.logger.name_to_value["rollout/action_noise_std"] == pytest.approx(0.1)

    with pytest.raises(ValueError, match="final_std"):
        ActionNoiseDecayCallback(final_std=float("nan"))
    with pytest.raises(ValueError, match="decay_fraction"):
        ActionNoiseDecayCallback(final_std=0.1, decay_fraction=0.0)
    with pytest.raises(ValueError, match="action_noise"):
        TD3("MlpPolicy", env, learning_starts=1_000).learn(
            4, callback=ActionNoiseDecayCallback(final_std=0.1)
        )


# ------------------------------------------------------------------------------------------------------------------
# End to end (one training subprocess for all configs)


@pytest.mark.parametrize("config_name", CONFIG_NAMES)
def test_config_trains_and_saves_a_model(
    trained_runs: tuple[Path, dict[str, str], str], config_name: str
) -> None:
    root, report, output = trained_runs
    assert report.get(config_name) == "ok", report.get(config_name, output[-3000:])
    assert _model_path(root, config_name).is_file()


def test_evaluate_reports_json_for_an_rl_zoo_run_folder(
    trained_runs: tuple[Path, dict[str, str], str],
) -> None:
    root, _, _ = trained_runs
    run_folder = _model_path(root, "e2_empty_goal_skills_fast").parent
    out = root / "eval.json"
    result = _run(
        ["-m", "sb3_hfo.evaluate", str(run_folder), "--episodes", "3", "--seed", "1", "--json", str(out)],
        cwd=root,
    )
    assert result.returncode == 0, result.stderr[-3000:]
    assert "scoring rate" in result.stdout
    report = json.loads(out.read_text())
    assert report["env_id"] == "HFO/EmptyGoal-v0"  # read from the run folder's args.yml
    assert report["episodes"] == 3 and sum(report["status_counts"].values()) == 3
    assert report["n_skills"] == 2 and len(report["skill_fractions"]) == 2
    assert sum(report["skill_fractions"]) == pytest.approx(1.0)
    for key in (
        "scoring_rate",
        "scoring_rate_ci95",
        "mean_steps_to_goal",
        "kicks_per_goal",
        "mean_kick_power",
    ):
        assert key in report
    assert report["dribble_fraction"] >= 0.0
    assert report["deterministic"] is True  # greedy unless --stochastic


def test_evaluation_leaves_out_env_kwargs_the_env_no_longer_takes(tmp_path: Path) -> None:
    import gymnasium as gym
    import yaml

    import hfo2d  # noqa: F401  (registers the envs)
    from sb3_hfo import SkillDDPG
    from sb3_hfo.evaluation import load_for_evaluation

    run = tmp_path / "HFO-EmptyGoal-v0_1"
    (run / "HFO-EmptyGoal-v0").mkdir(parents=True)
    (run / "HFO-EmptyGoal-v0" / "args.yml").write_text(yaml.dump({"env": "HFO/EmptyGoal-v0"}))
    config = {"env_kwargs": {"random_start_fraction": 0.5, "noise": False}}
    (run / "HFO-EmptyGoal-v0" / "config.yml").write_text(yaml.dump(config))
    model = SkillDDPG("HFOPolicy", gym.make("HFO/EmptyGoal-v0"), policy_kwargs={"net_arch": [8]}, seed=0)
    model.save(run / "HFO-EmptyGoal-v0.zip")

    _, env, env_id, kwargs, _ = load_for_evaluation(str(run))
    assert env_id == "HFO/EmptyGoal-v0" and kwargs == {"noise": False}  # the task's settings stay
    assert not hasattr(env.unwrapped, "random_start_fraction") and env.unwrapped.noise is False
    env.close()


def test_evaluate_can_switch_on_the_mirror_choice() -> None:
    from sb3_hfo.cli.evaluate import build_parser
    from sb3_hfo.evaluation import evaluate

    model = "e6_keeper_v0"
    result = evaluate(str(model), episodes=2, seed=0, acting="critic,mirror")
    assert result.acting == "critic,mirror" and result.episodes == 2
    assert evaluate(str(model), episodes=1, seed=0).acting == "critic,kick_mask"  # the model's own setting
    # acting replaces the whole set: the model's own strategies plus the mirror choice are written out
    assert (
        evaluate(str(model), episodes=1, seed=0, acting="critic,kick_mask,mirror").acting
        == "critic,kick_mask,mirror"
    )
    assert (
        build_parser().parse_args(["m.zip", "--acting", "critic,kick_mask,mirror"]).acting
        == "critic,kick_mask,mirror"
    )
    # the single-option forms are gone, from the function and from the command line
    with pytest.raises(TypeError, match="mirror_choice"):
        evaluate(str(model), episodes=1, seed=0, mirror_choice=True)  # type: ignore[call-arg]
    with pytest.raises(SystemExit):
        build_parser().parse_args(["m.zip", "--mirror-choice", "on"])


def test_evaluate_acting_flag_parses_and_names_a_bad_token(capsys: pytest.CaptureFixture[str]) -> None:
    from sb3_hfo.cli.evaluate import build_parser, main

    parser = build_parser()
    assert parser.parse_args(["m.zip", "--acting", "critic,mirror:0.1"]).acting == "critic,mirror:0.1"
    assert parser.parse_args(["m.zip"]).acting is None  # the model's own
    with pytest.raises(SystemExit):
        main(["e6_keeper_v0", "--acting", "critic,mirorr"])
    assert "'mirorr'" in capsys.readouterr().err
    assert "--acting" in parser.format_help() and "--mirror-margin" not in parser.format_help()


def test_evaluate_sets_the_mirror_margin_and_threads_predicts_state_through_each_episode() -> None:
    import gymnasium as gym

    from sb3_hfo.cli.evaluate import build_parser
    from sb3_hfo.evaluation import EvaluationError, evaluate, run_episodes

    model = "e6_keeper_v0"
    result = evaluate(str(model), episodes=1, seed=0, acting="critic,mirror:inf")
    assert result.acting == "critic,mirror:inf"
    assert build_parser().parse_args(["m.zip", "--acting", "critic,kick_mask,mirror:0.2"]).acting == (
        "critic,kick_mask,mirror:0.2"
    )
    with pytest.raises(EvaluationError, match="MirrorChoice margin must be a number >= 0"):
        evaluate(str(model), episodes=1, seed=0, acting="critic,kick_mask,mirror:-1.0")
    with pytest.raises(EvaluationError, match="'mirror:-1'"):
        evaluate(str(model), episodes=1, seed=0, acting="mirror:-1")

    class CountingStriker:  # returns as its state the number of steps since its last episode start
        def __init__(self) -> None:
            self.calls: list[tuple[object, bool]] = []

        def predict(self, obs: np.ndarray, state=None, episode_start=None, deterministic=False) -> tuple:
            self.calls.append((state, bool(episode_start[0])))
            steps = 1 if episode_start[0] else state + 1
            return np.array([0, 0, 1, 0, 0.5, 0.5, 1.0, 0.5], dtype=np.float32), steps

    striker = CountingStriker()
    records = run_episodes(
        striker, gym.make("HFO/EmptyGoal-v0"), episodes=3, seed=0, deterministic=True, n_skills=1
    )
    starts = [i for i, (_, start) in enumerate(striker.calls) if start]
    assert starts == [0, records[0].steps, records[0].steps + records[1].steps]
    assert striker.calls[0][0] is None  # no state before the first step
    assert [state for state, start in striker.calls[1 : records[0].steps]] == list(range(1, records[0].steps))


def test_evaluate_is_greedy_unless_stochastic() -> None:
    from sb3_hfo.cli.evaluate import build_parser

    parser = build_parser()
    assert parser.parse_args(["m.zip"]).deterministic is True
    assert parser.parse_args(["m.zip", "--deterministic"]).deterministic is True
    assert parser.parse_args(["m.zip", "--stochastic"]).deterministic is False


def test_evaluate_unknown_env_id_lists_hfo_ids(trained_runs: tuple[Path, dict[str, str], str]) -> None:
    root, _, _ = trained_runs
    model = _model_path(root, "e1_empty_goal_fast")
    result = _run(
        ["-m", "sb3_hfo.evaluate", str(model), "--env", "HFO/NoSuchTask-v0", "--episodes", "1"], cwd=root
    )
    assert result.returncode == 2
    assert "unknown env id 'HFO/NoSuchTask-v0'" in result.stderr
    assert "HFO/EmptyGoal-v0" in result.stderr and "HFO/Keeper-v0" in result.stderr
    assert "Traceback" not in result.stderr


def test_evaluate_missing_model_is_a_clear_error(tmp_path: Path) -> None:
    result = _run(
        ["-m", "sb3_hfo.evaluate", str(tmp_path / "nope.zip"), "--env", "HFO/EmptyGoal-v0"], cwd=tmp_path
    )
    assert result.returncode == 2
    assert "model file not found" in result.stderr and "Traceback" not in result.stderr


def test_plot_writes_a_png_with_the_runs(trained_runs: tuple[Path, dict[str, str], str]) -> None:
    from sb3_hfo.cli.plot import collect_runs

    root, _, _ = trained_runs
    logdirs = [str(root / "tb" / "e1_empty_goal_fast"), str(root / "tb" / "e2_empty_goal_skills_fast")]
    runs = collect_runs(logdirs, ["no skills", "skills"])
    assert [run.label for run in runs] == ["no skills", "skills"]
    for run in runs:
        for tag in ("train/critic_loss", "rollout/ep_rew_mean", "rollout/success_rate", "rollout/episodes"):
            assert tag in run.scalars, f"{run.label}: {tag} not logged ({sorted(run.scalars)})"
    out = root / "figure.png"
    result = _run(
        ["-m", "sb3_hfo.plot", *logdirs, "--labels", "no skills", "skills", "--out", str(out)], cwd=root
    )
    assert result.returncode == 0, result.stderr[-3000:]
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size > 10_000


def test_record_video_writes_an_mp4_headless(trained_runs: tuple[Path, dict[str, str], str]) -> None:
    root, _, _ = trained_runs
    folder = root / "logs" / "e1_empty_goal_fast"
    videos = root / "videos"
    args = [
        "-m",
        "sb3_hfo.record_video",
        "--env",
        "HFO/EmptyGoal-v0",
        "-f",
        str(folder),
        "-n",
        "20",
        "-o",
        str(videos),
    ]
    result = _run(args, cwd=root)
    assert result.returncode == 0, result.stderr[-3000:]
    mp4s = list(videos.glob("*.mp4"))
    assert len(mp4s) == 1 and mp4s[0].stat().st_size > 1000
