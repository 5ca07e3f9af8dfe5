"""SkillPDQN: SkillDDPG with the measured best recipe as its defaults (a preset subclass, as SB3's ``DDPG`` is one
of ``TD3``).

:class:`~sb3_hfo.skill_ddpg.SkillDDPG` keeps the seed paper's method and defaults. Every committed model's config
switched on the same options by hand, all borrowed from P-DQN / MP-DQN (Xiong et al. 2018; Bester et al. 2019) and
from Hausknecht & Stone (2016); ``SkillPDQN`` has them on by default:

* the critic sees only the chosen discrete action's parameters (``mask_unused_parameters``);
* the critic picks the discrete action when acting (:class:`~sb3_hfo.skill_ddpg.acting.CriticChoice`) and its TD target takes the best
  discrete action (``discrete_target="max"``);
* the actor trains every discrete action's parameters by that action's value (``parameter_loss="each_action"``);
* no KICK while the ball is out of reach (:class:`~sb3_hfo.skill_ddpg.acting.KickMask`), where the policy's
  ``domain`` names the kickable column (HFO's: ``domain="hfo"``);
* a penalty on the actor's pre-``tanh`` outputs (``preactivation_penalty=1e-3``);
* Monte-Carlo mixing of the critic target (``mc_mixing=0.2``);
* epsilon-greedy exploration that keeps the actor's parameters (``exploration_keep_parameters``).

It needs an action space with a hybrid layout (:mod:`sb3_hfo.common.action_layout`; the HFO envs have one). Every default
can be overridden; the results behind them are on the results page (``docs/results.md``).
"""

from __future__ import annotations

from typing import Any, ClassVar, TypeVar

from stable_baselines3.common.type_aliases import GymEnv, MaybeCallback

from sb3_hfo.common.domain import resolve_domain
from sb3_hfo.skill_ddpg.acting import CriticChoice, KickMask
from sb3_hfo.skill_ddpg.policies import HFOPolicy
from sb3_hfo.skill_ddpg.skill_ddpg import SkillDDPG

__all__ = ["PRESET_ALGORITHM_DEFAULTS", "PRESET_POLICY_DEFAULTS", "SkillPDQN"]

SelfSkillPDQN = TypeVar("SelfSkillPDQN", bound="SkillPDQN")

#: SkillPDQN's defaults that differ from SkillDDPG's, as constructor arguments.
PRESET_ALGORITHM_DEFAULTS: dict[str, Any] = {
    "exploration_keep_parameters": True,
    "mc_mixing": 0.2,
    "preactivation_penalty": 1e-3,
    "discrete_target": "max",
    "parameter_loss": "each_action",
}
#: SkillPDQN's ``policy_kwargs`` defaults (:class:`~sb3_hfo.skill_ddpg.policies.HFOPolicy` arguments); the
#: ``policy_kwargs`` given override them key by key.
PRESET_POLICY_DEFAULTS: dict[str, Any] = {
    "mask_unused_parameters": True,
    "acting": (CriticChoice(), KickMask()),
}


def preset_policy_kwargs(policy_kwargs: dict[str, Any] | None) -> dict[str, Any]:
    """``policy_kwargs`` over :data:`PRESET_POLICY_DEFAULTS`; the default acting drops the kick mask when the
    ``domain`` names no kickable column (the mask reads it; a task without one has nothing to mask by)."""
    merged = {**PRESET_POLICY_DEFAULTS, **(policy_kwargs or {})}
    if "acting" not in (policy_kwargs or {}) and resolve_domain(merged.get("domain")).kickable_column is None:
        merged["acting"] = tuple(s for s in PRESET_POLICY_DEFAULTS["acting"] if not isinstance(s, KickMask))
    return merged


class SkillPDQN(SkillDDPG):
    """SkillDDPG with P-DQN's discrete-action handling and the other measured improvements on by default (see the
    module docstring). The arguments are SkillDDPG's; only these defaults differ.

    :param exploration_keep_parameters: default ``True``.
    :param mc_mixing: default ``0.2`` (Hausknecht & Stone's value on HFO).
    :param preactivation_penalty: default ``1e-3``.
    :param discrete_target: default ``"max"``.
    :param parameter_loss: default ``"each_action"``.
    :param policy_kwargs: merged over :data:`PRESET_POLICY_DEFAULTS` (``mask_unused_parameters=True``,
        ``acting=(CriticChoice(), KickMask())``; without ``KickMask`` where the ``domain`` names no kickable column).
    :param kwargs: any other :class:`~sb3_hfo.skill_ddpg.SkillDDPG` argument.
    """

    policy_aliases: ClassVar[dict[str, type[HFOPolicy]]] = SkillDDPG.policy_aliases  # type: ignore[assignment]

    def __init__(
        self,
        policy: str | type[HFOPolicy],
        env: GymEnv | str,
        exploration_keep_parameters: bool = True,
        mc_mixing: float = 0.2,
        preactivation_penalty: float = 1e-3,
        discrete_target: str = "max",
        parameter_loss: str = "each_action",
        policy_kwargs: dict[str, Any] | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(
            policy,
            env,
            exploration_keep_parameters=exploration_keep_parameters,
            mc_mixing=mc_mixing,
            preactivation_penalty=preactivation_penalty,
            discrete_target=discrete_target,
            parameter_loss=parameter_loss,
            policy_kwargs=preset_policy_kwargs(policy_kwargs),
            **kwargs,
        )

    def learn(
        self: SelfSkillPDQN,
        total_timesteps: int,
        callback: MaybeCallback = None,
        log_interval: int = 4,
        tb_log_name: str = "SkillPDQN",
        reset_num_timesteps: bool = True,
        progress_bar: bool = False,
    ) -> SelfSkillPDQN:
        """SkillDDPG's ``learn``; TensorBoard runs are named ``SkillPDQN_<n>`` by default."""
        return super().learn(
            total_timesteps, callback, log_interval, tb_log_name, reset_num_timesteps, progress_bar
        )
