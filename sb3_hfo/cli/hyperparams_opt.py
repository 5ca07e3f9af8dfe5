"""Optuna search space for SkillDDPG, in rl-zoo3's sampler format (``-optimize``).

rl-zoo3 calls ``HYPERPARAMS_SAMPLER[algo](trial, n_actions, n_envs, additional_args)`` for every trial and passes
the returned dict straight to the algorithm's constructor (on top of the config file's values); with
``--trial-id`` it rebuilds the hyperparameters of a stored trial through ``HYPERPARAMS_CONVERTER[algo](params)``,
where ``params`` are the raw Optuna values. So the sampler suggests raw values and the converter maps them onto
constructor arguments. :func:`sb3_hfo.cli.zoo.register_with_rl_zoo` installs them under ``"skill_ddpg"`` and, with
:func:`sample_skill_pdqn_params`, under ``"skill_pdqn"``.

The experiment-defining policy keys (``n_skills``, ``skill_router``, ``inverting_gradients``) come from the
config file and are never sampled; only ``net_arch`` is (see ``sb3_hfo.cli.zoo.merge_policy_kwargs``).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import optuna
from stable_baselines3.common.noise import NormalActionNoise, OrnsteinUhlenbeckActionNoise

from sb3_hfo.common.schedules import parse_schedule

#: Hidden layer sizes an Optuna trial may choose; "paper" is the seed paper's 400-300-200 (Method section).
NET_ARCHS: dict[str, list[int]] = {
    "tiny": [64, 64],
    "small": [256, 128, 64],
    "medium": [256, 256, 128],
    "paper": [400, 300, 200],
}

#: The action noises an Optuna trial may choose ("none": epsilon-greedy exploration only, as in the paper).
NOISE_TYPES: tuple[str, ...] = ("none", "normal", "ornstein-uhlenbeck")
#: Key of rl-zoo3's ``additional_args`` under which :class:`sb3_hfo.cli.zoo.HFOExperimentManager` says that the
#: config's callbacks need an action noise (``ActionNoiseDecayCallback`` rejects a model without one, so a trial
#: that drew "none" would be pruned before its first step).
NOISE_REQUIRED_ARG = "action_noise_required"


def convert_skill_ddpg_params(sampled_params: dict[str, Any]) -> dict[str, Any]:
    """Map raw Optuna values onto SkillDDPG constructor arguments (YAML-friendly: numbers and strings).

    :param sampled_params: ``trial.params`` of one trial (keys as suggested in :func:`sample_skill_ddpg_params`).
    :return: hyperparameters as a config file would hold them, e.g. ``learning_rate_critic: "lin_0.001"``.
    """
    params = dict(sampled_params)
    hyperparams: dict[str, Any] = {}
    hyperparams["gamma"] = 1.0 - params.pop("one_minus_gamma")
    hyperparams["batch_size"] = 2 ** params.pop("batch_size_pow")
    hyperparams["learning_rate_actor"] = params.pop("learning_rate_actor")
    critic_lr = params.pop("learning_rate_critic")
    # The paper decays the critic's learning rate; whether that helps is left to the search.
    hyperparams["learning_rate_critic"] = f"lin_{critic_lr}" if params.pop("critic_lr_decay") else critic_lr
    hyperparams["tau"] = params.pop("tau")
    train_freq = params.pop("train_freq")
    hyperparams["train_freq"] = train_freq
    # One gradient step per environment step, as in the paper ("on each frame we performed a learning iteration").
    hyperparams["gradient_steps"] = train_freq
    hyperparams["exploration_final_eps"] = params.pop("exploration_final_eps")
    hyperparams["exploration_fraction"] = params.pop("exploration_fraction")
    hyperparams["policy_kwargs"] = {"net_arch": list(NET_ARCHS[params.pop("net_arch")])}
    # rl-zoo3 turns noise_type / noise_std of a config into an action-noise object (it knows n_actions).
    noise_type = params.pop("noise_type", "none")
    noise_std = params.pop("noise_std", 0.0)
    if noise_type != "none":
        hyperparams["noise_type"] = noise_type
        hyperparams["noise_std"] = noise_std
    hyperparams.update(params)
    return hyperparams


def sample_skill_ddpg_params(
    trial: optuna.Trial, n_actions: int, n_envs: int, additional_args: dict[str, Any]
) -> dict[str, Any]:
    """Suggest SkillDDPG hyperparameters for one Optuna trial.

    :param trial: the Optuna trial.
    :param n_actions: size of the flat action vector (8 for HFO: 3 action preferences + 5 parameters).
    :param n_envs: number of training environments (unused: the update-to-data ratio is kept at 1 per step).
    :param additional_args: rl-zoo3's extra arguments (its HER settings are unused here); with
        ``additional_args[NOISE_REQUIRED_ARG]`` true, ``noise_type`` is drawn without "none".
    :return: constructor keyword arguments; learning rates as floats or schedules, action noise as an object.
    """
    noise_required = bool(additional_args.get(NOISE_REQUIRED_ARG, False))
    noise_types = [kind for kind in NOISE_TYPES if not (noise_required and kind == "none")]
    sampled = {
        "one_minus_gamma": trial.suggest_float("one_minus_gamma", 1e-3, 5e-2, log=True),
        "batch_size_pow": trial.suggest_int("batch_size_pow", 5, 8),  # 32 (paper) .. 256
        "learning_rate_actor": trial.suggest_float("learning_rate_actor", 1e-5, 1e-3, log=True),
        "learning_rate_critic": trial.suggest_float("learning_rate_critic", 1e-4, 3e-3, log=True),
        "critic_lr_decay": trial.suggest_categorical("critic_lr_decay", [True, False]),
        "tau": trial.suggest_float("tau", 1e-4, 2e-2, log=True),
        "train_freq": trial.suggest_int("train_freq", 1, 4),
        "exploration_final_eps": trial.suggest_float("exploration_final_eps", 0.0, 0.2),
        "exploration_fraction": trial.suggest_float("exploration_fraction", 0.01, 0.5, log=True),
        "net_arch": trial.suggest_categorical("net_arch", list(NET_ARCHS)),
        "noise_type": trial.suggest_categorical("noise_type", noise_types),
    }
    if sampled["noise_type"] != "none":
        sampled["noise_std"] = trial.suggest_float("noise_std", 0.01, 0.3, log=True)

    trial.set_user_attr("gamma", 1.0 - sampled["one_minus_gamma"])
    trial.set_user_attr("batch_size", 2 ** sampled["batch_size_pow"])

    hyperparams = convert_skill_ddpg_params(sampled)
    for key in ("learning_rate_actor", "learning_rate_critic"):
        hyperparams[key] = parse_schedule(hyperparams[key])
    # The sampled values go straight to the constructor, so the noise object is built here.
    noise_type = hyperparams.pop("noise_type", "none")
    noise_std = hyperparams.pop("noise_std", 0.0)
    # "none" must override a config's action noise too, so the key is always set.
    hyperparams["action_noise"] = None
    if noise_type == "normal":
        hyperparams["action_noise"] = NormalActionNoise(np.zeros(n_actions), noise_std * np.ones(n_actions))
    elif noise_type == "ornstein-uhlenbeck":
        hyperparams["action_noise"] = OrnsteinUhlenbeckActionNoise(
            np.zeros(n_actions), noise_std * np.ones(n_actions)
        )
    return hyperparams


def sample_skill_pdqn_params(
    trial: optuna.Trial, n_actions: int, n_envs: int, additional_args: dict[str, Any]
) -> dict[str, Any]:
    """Suggest SkillPDQN hyperparameters: SkillDDPG's search space (:func:`sample_skill_ddpg_params`) and the
    preset's two numeric defaults around their values, ``mc_mixing`` (0.2) and ``preactivation_penalty`` (1e-3).
    The preset's switches stay on (they define it)."""
    hyperparams = sample_skill_ddpg_params(trial, n_actions, n_envs, additional_args)
    hyperparams["mc_mixing"] = trial.suggest_float("mc_mixing", 0.0, 0.5)
    hyperparams["preactivation_penalty"] = trial.suggest_float("preactivation_penalty", 1e-4, 1e-2, log=True)
    return hyperparams
