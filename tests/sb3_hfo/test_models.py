"""The committed models (sb3_hfo.models): stripped files act as the full ones, the manifest, loading by name,
continuing to train (their command line: tests/cli/test_models_cli.py)."""

from __future__ import annotations

import io
import json
import zipfile
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
import torch

import hfo2d  # noqa: F401  (registers the HFO/* ids)
from sb3_hfo import SkillDDPG
from sb3_hfo.errors import UserError
from sb3_hfo.evaluation import evaluate, wilson_interval
from sb3_hfo.models import (
    MANIFEST_PATH,
    MAX_MODEL_BYTES,
    MODELS_DIR,
    POLICY_ENTRY,
    STRIPPED_ENTRY,
    check_provenance,
    full_model_buffer,
    is_stripped,
    load_model,
    read_manifest,
    strip_model,
    trained_with,
)
from sb3_hfo.skill_ddpg.acting import CriticChoice, format_acting, parse_acting

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
        policy_kwargs=dict(
            net_arch=[16, 8], n_skills=2, mask_unused_parameters=True, domain="hfo", **policy_kwargs
        ),
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


# --- the committed models ---------------------------------------------------------------------------------------

MANIFEST = read_manifest()


def test_models_holds_only_the_manifest_and_its_models() -> None:
    files = {path.name for path in MODELS_DIR.iterdir()}
    assert files == {MANIFEST_PATH.name, *(entry["file"] for entry in MANIFEST.values())}
    assert 1 <= len(MANIFEST) <= 10  # a handful of small files, not a model zoo


@pytest.mark.parametrize("name", sorted(MANIFEST))
def test_a_committed_model_is_small_stripped_and_matches_its_manifest_entry(name: str) -> None:
    import hashlib

    entry = MANIFEST[name]
    path = MODELS_DIR / entry["file"]
    assert path.stat().st_size == entry["bytes"] <= MAX_MODEL_BYTES
    assert hashlib.sha256(path.read_bytes()).hexdigest() == entry["sha256"]
    assert is_stripped(path)
    check_provenance(entry, REPO)  # a zoo config, or the benchmark script and the command that made it
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
    if hasattr(model.policy, "acting"):  # SkillDDPG's acting strategies; HybridPPO acts by its distribution
        assert model.policy.acting == parse_acting(entry["acting"])
        assert format_acting(model.policy.acting) == entry["acting"] == evaluation["acting"]  # the text form
    else:
        assert entry["acting"] is None
    real = entry["real_hfo"]
    if real:
        assert real["env_id"].startswith("HFO/Real") and real["source"]
        assert tuple(real["scoring_rate_ci95"]) == wilson_interval(real["goals"], real["episodes"])


def test_a_benchmark_script_s_model_names_its_script_and_command() -> None:
    """A model without a zoo config ("config": null) must name an existing script and the command that ran it."""
    script = "benchmarks/rl_from_clone.py"
    entry = {"config": None, "script": script, "command": f"python {script} --seed 1 --out DIR"}
    check_provenance(entry, REPO)
    assert trained_with(entry) == script
    assert (
        trained_with({"config": "zoo_configs/e1_empty_goal_fast.yml"}) == "zoo_configs/e1_empty_goal_fast.yml"
    )
    refused = [
        ({"config": "zoo_configs/nowhere.yml"}, "no such file"),
        (
            {"config": None, "script": "benchmarks/nowhere.py", "command": "python benchmarks/nowhere.py"},
            "needs its script",
        ),
        ({"config": None, "script": script}, "needs the command"),
        ({"config": None, "script": script, "command": "python benchmarks/other.py"}, "needs the command"),
        ({}, "no such file"),  # neither
    ]
    for bad, message in refused:
        with pytest.raises(ValueError, match=message):
            check_provenance(bad, REPO)


# --- continuing to train a committed model ------------------------------------------------------------------

#: The committed HybridPPO models, each with the env it was trained on (its manifest entry's).
HYBRID_PPO_MODELS = ("e1", "e6", "e6_from_clone", "e6_from_clone_shot")


@pytest.mark.parametrize("n_envs", [1, 3])
@pytest.mark.parametrize("name", HYBRID_PPO_MODELS)
def test_a_hybrid_ppo_model_continues_training_with_any_number_of_envs(
    name: str, n_envs: int, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """HybridPPO's committed models (trained on 16 games) load with ``env=`` and continue training with another
    number of envs, from their saved weights, and write no stray logs."""
    from stable_baselines3.common.env_util import make_vec_env

    from sb3_hfo.hybrid_ppo import HybridPPO

    monkeypatch.chdir(tmp_path)
    entry = MANIFEST[name]
    env = make_vec_env(entry["env_id"], n_envs=n_envs, seed=0, env_kwargs=entry["env_kwargs"])
    model = load_model(name, env=env, device="cpu", n_steps=16, batch_size=16, n_epochs=1)
    assert isinstance(model, HybridPPO) and model.n_envs == n_envs
    saved = {key: value.clone() for key, value in load_model(name, device="cpu").policy.state_dict().items()}
    loaded = model.policy.state_dict()
    assert all(
        torch.equal(loaded[key], value) for key, value in saved.items()
    )  # starts from the saved weights
    before = model.num_timesteps
    model.learn(32 * n_envs, reset_num_timesteps=False)
    assert model.num_timesteps >= before + 32 * n_envs
    assert any(not torch.equal(model.policy.state_dict()[key], value) for key, value in saved.items())
    assert list(tmp_path.iterdir()) == []  # no TensorBoard folder unless asked


@pytest.mark.parametrize("n_envs", [1, 2])
def test_a_committed_model_continues_training_with_any_number_of_envs(
    n_envs: int, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """e1_skill_pdqn was trained with 4 envs: its saved action noise is for 4 (issue 35, defect 1: a reshape error on 1)."""
    from stable_baselines3.common.env_util import make_vec_env
    from stable_baselines3.common.noise import VectorizedActionNoise

    monkeypatch.chdir(tmp_path)
    saved = load_model("e1_skill_pdqn", device="cpu", buffer_size=1).action_noise
    assert isinstance(saved, VectorizedActionNoise) and saved.n_envs == 4  # the premise
    env = gym.make("HFO/EmptyGoal-v0") if n_envs == 1 else make_vec_env("HFO/EmptyGoal-v0", n_envs=n_envs)
    model = load_model(
        "e1_skill_pdqn", env=env, device="cpu", buffer_size=500, learning_starts=0, batch_size=8
    )
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
    model = load_model("e1_skill_pdqn", env=gym.make("HFO/EmptyGoal-v0"), device="cpu", buffer_size=500)
    assert model.tensorboard_log is None
    model.learn(5)
    assert list(tmp_path.iterdir()) == []  # no stray log folder in the working directory
    logs = tmp_path / "my_logs"
    told = load_model(
        "e1_skill_pdqn", env=gym.make("HFO/EmptyGoal-v0"), buffer_size=500, tensorboard_log=str(logs)
    )
    assert told.tensorboard_log == str(logs)
    told.learn(5)
    assert [path.name for path in tmp_path.iterdir()] == ["my_logs"] and any(logs.rglob("events.out.*"))


# --- names ---------------------------------------------------------------------------------------------------------


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
