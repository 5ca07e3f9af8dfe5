"""SkillPDQN: SkillDDPG's preset with the best recipe as defaults; the best configs built with it."""

from __future__ import annotations

import inspect
from pathlib import Path
from typing import Any

import pytest
import torch as th
import yaml

from sb3_hfo import SkillDDPG, SkillPDQN
from sb3_hfo.common.schedules import SCHEDULE_KEYS, parse_schedule
from sb3_hfo.common.toy_env import HybridTargetEnv
from sb3_hfo.skill_ddpg.acting import CriticChoice, KickMask
from sb3_hfo.skill_ddpg.skill_pdqn import PRESET_ALGORITHM_DEFAULTS, PRESET_POLICY_DEFAULTS

REPO = Path(__file__).resolve().parents[2]
BEST_CONFIGS = sorted(
    path for path in (REPO / "zoo_configs").glob("*.yml") if "--algo skill_pdqn " in path.read_text()
)


def test_the_best_recipe_configs_are_found() -> None:
    """The committed models' SkillPDQN configs (those of e1 to e4 and e6_keeper_v0)."""
    assert len(BEST_CONFIGS) == 5


#: Config keys rl-zoo3 handles itself (not constructor arguments).
ZOO_ONLY_KEYS = {"n_timesteps", "n_envs", "noise_type", "noise_std", "callback", "env_kwargs", "policy"}
ALGORITHM_ARGUMENTS = [
    name
    for name in inspect.signature(SkillDDPG.__init__).parameters
    if name
    not in ("self", "policy", "env", "policy_kwargs", "_init_setup_model", "seed", "device", "verbose")
]


def settings(model: SkillDDPG) -> dict[str, Any]:
    """What makes a model: its algorithm arguments, its policy's constructor arguments and its first weights."""
    policy_arguments = model.policy._get_constructor_parameters()
    policy_arguments.pop("lr_schedule")
    return {
        "algorithm": {name: repr(getattr(model, name, None)) for name in ALGORITHM_ARGUMENTS},
        "policy": {name: repr(value) for name, value in policy_arguments.items()},
        "weights": [value.clone() for value in model.policy.state_dict().values()],
    }


def assert_same_model(first: SkillDDPG, second: SkillDDPG) -> None:
    a, b = settings(first), settings(second)
    assert a["algorithm"] == b["algorithm"] and a["policy"] == b["policy"]
    assert all(th.equal(x, y) for x, y in zip(a["weights"], b["weights"], strict=True))


def test_the_preset_is_skill_ddpg_with_the_best_recipe_switched_on() -> None:
    preset = SkillPDQN("HFOPolicy", HybridTargetEnv(), seed=0)
    explicit = SkillDDPG(
        "HFOPolicy",
        HybridTargetEnv(),
        seed=0,
        policy_kwargs=dict(PRESET_POLICY_DEFAULTS),
        **PRESET_ALGORITHM_DEFAULTS,
    )
    assert_same_model(preset, explicit)
    paper = SkillDDPG("HFOPolicy", HybridTargetEnv(), seed=0)
    assert paper.discrete_target == "actor" and paper.mc_mixing == 0.0 and paper.policy.acting == ()
    assert preset.policy.parameter_masks is not None and preset.policy.acting == (CriticChoice(), KickMask())


def test_the_preset_defaults_are_its_signature_defaults() -> None:
    signature = inspect.signature(SkillPDQN.__init__).parameters
    assert {name: signature[name].default for name in PRESET_ALGORITHM_DEFAULTS} == PRESET_ALGORITHM_DEFAULTS


def test_policy_kwargs_override_the_preset_key_by_key() -> None:
    model = SkillPDQN("HFOPolicy", HybridTargetEnv(), seed=0, policy_kwargs=dict(acting="kick_mask"))
    assert model.policy.acting == (KickMask(),)  # the actor picks the discrete action again ...
    assert model.policy.parameter_masks is not None  # ... and the preset's other policy keys stay
    model = SkillPDQN("HFOPolicy", HybridTargetEnv(), seed=0, parameter_loss="chosen", mc_mixing=0.0)
    assert model.parameter_loss == "chosen" and model.mc_mixing == 0.0


def test_the_preset_saves_and_loads_with_either_class(tmp_path: Path) -> None:
    model = SkillPDQN("HFOPolicy", HybridTargetEnv(), seed=0, learning_starts=20, batch_size=8)
    model.learn(40)
    model.save(tmp_path / "model.zip")
    obs = HybridTargetEnv().observation_space.sample()[None]
    expected = model.predict(obs, deterministic=True)[0]
    for algo_class in (SkillPDQN, SkillDDPG):
        loaded = algo_class.load(tmp_path / "model.zip", env=HybridTargetEnv())
        assert loaded.parameter_loss == "each_action" and CriticChoice() in loaded.policy.acting
        assert (loaded.predict(obs, deterministic=True)[0] == expected).all()


@pytest.mark.parametrize("config", BEST_CONFIGS, ids=lambda path: path.stem)
def test_a_best_config_builds_the_model_it_built_with_every_switch_spelt_out(config: Path) -> None:
    """Each best config, now a few lines on top of the preset, makes the same model as SkillDDPG with the preset's
    switches written into it (what the config held before)."""
    import gymnasium as gym

    ((env_id, hyperparams),) = yaml.safe_load(config.read_text()).items()
    kwargs = {key: value for key, value in hyperparams.items() if key not in ZOO_ONLY_KEYS}
    kwargs["buffer_size"] = 1000  # the model, not the memory
    for key in SCHEDULE_KEYS:
        if key in kwargs:
            kwargs[key] = parse_schedule(kwargs[key])
    policy_kwargs = kwargs.pop("policy_kwargs")
    env_kwargs = hyperparams.get("env_kwargs", {})
    preset = SkillPDQN(
        "MlpPolicy", gym.make(env_id, **env_kwargs), seed=0, policy_kwargs=policy_kwargs, **kwargs
    )
    spelt_out = SkillDDPG(
        "MlpPolicy",
        gym.make(env_id, **env_kwargs),
        seed=0,
        policy_kwargs={**PRESET_POLICY_DEFAULTS, **policy_kwargs},
        **{**PRESET_ALGORITHM_DEFAULTS, **kwargs},
    )
    assert_same_model(preset, spelt_out)
    assert len(policy_kwargs) <= 6, "the preset leaves a few lines of policy_kwargs"


def test_rl_zoo_knows_both_algorithms() -> None:
    pytest.importorskip("rl_zoo3")
    import rl_zoo3.hyperparams_opt
    import rl_zoo3.utils

    from sb3_hfo.cli.hyperparams_opt import sample_skill_pdqn_params
    from sb3_hfo.cli.zoo import register_with_rl_zoo

    register_with_rl_zoo()
    assert rl_zoo3.utils.ALGOS["skill_ddpg"] is SkillDDPG and rl_zoo3.utils.ALGOS["skill_pdqn"] is SkillPDQN
    assert rl_zoo3.hyperparams_opt.HYPERPARAMS_SAMPLER["skill_pdqn"] is sample_skill_pdqn_params
    assert "skill_pdqn" in rl_zoo3.hyperparams_opt.HYPERPARAMS_CONVERTER


def test_the_preset_sampler_adds_its_numeric_defaults() -> None:
    optuna = pytest.importorskip("optuna")
    from sb3_hfo.cli.hyperparams_opt import sample_skill_pdqn_params

    trial = optuna.create_study().ask()
    hyperparams = sample_skill_pdqn_params(trial, 8, 1, {})
    assert 0.0 <= hyperparams["mc_mixing"] <= 0.5 and 1e-4 <= hyperparams["preactivation_penalty"] <= 1e-2
