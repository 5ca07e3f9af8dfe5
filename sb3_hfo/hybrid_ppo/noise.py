"""A schedule for HybridPPO's parameter noise: the log standard deviations set from outside, not learned.

HybridPPO learns its parameters' log std with the rest of the policy; with no entropy bonus and a policy started
from a clone they hardly move (rl_from_clone.py's runs: -3.5 at the start, -3.40 to -3.52 after 2M steps). The
noise is then the policy's exploration *and* part of what PPO optimises: the stochastic policy, not the greedy one
that is evaluated. :class:`LogStdSchedule` moves every skill head's log std linearly from ``start`` to ``end`` over
training (the policy's and, when one is set, the pull reference's alike), so the sampled policy can be brought
close to the greedy one by the end of a run.
"""

from __future__ import annotations

import math

import torch as th
from stable_baselines3.common.callbacks import BaseCallback

__all__ = ["LogStdSchedule"]


class LogStdSchedule(BaseCallback):
    """Sets every parameter log std of a :class:`~sb3_hfo.hybrid_ppo.HybridPPO` policy (all skill heads) to
    ``start + (end - start) * elapsed`` before each rollout, ``elapsed`` being the share of the training steps done
    (``1 - progress_remaining``), and stops their gradient, so PPO neither learns nor drifts them.

    The frozen pull reference (:meth:`~sb3_hfo.hybrid_ppo.HybridPPO.set_reference`), if any, gets the same log std:
    then the Gaussian part of the pull ``KL(reference || pi)`` compares only the means, as it did when both started
    equal. ``start`` should be the policy's own initial log std (``log_std_init``), or the first rollout jumps.

    :param start: log std at the start of training (normalised parameter scale: ``[-1, 1]`` spans the env's bounds).
    :param end: log std at the end of training.
    :raises ValueError: a bound that is not a finite number.
    """

    def __init__(self, start: float, end: float, verbose: int = 0) -> None:
        super().__init__(verbose)
        for name, value in (("start", start), ("end", end)):
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
                raise ValueError(f"LogStdSchedule: {name} must be a finite number, got {value!r}")
        self.start = float(start)
        self.end = float(end)

    def value(self, progress_remaining: float) -> float:
        """The log std at ``progress_remaining`` (SB3's: 1 at the start of training, 0 at its end)."""
        elapsed = min(1.0, max(0.0, 1.0 - progress_remaining))
        return self.start + (self.end - self.start) * elapsed

    def _heads_log_std(self) -> list[th.nn.Parameter]:
        policies = [self.model.policy]
        reference = getattr(self.model, "reference_policy", None)
        if reference is not None:
            policies.append(reference)
        return [head.log_std for policy in policies for head in policy.heads]

    def _on_training_start(self) -> None:
        if not hasattr(self.model.policy, "heads"):
            raise ValueError(
                f"LogStdSchedule needs a HybridPPO policy with skill heads, got {type(self.model.policy).__name__}"
            )
        for log_std in self._heads_log_std():
            log_std.requires_grad_(False)  # Adam skips a parameter without a gradient
        self._apply()

    def _on_rollout_start(self) -> None:
        self._apply()

    def _apply(self) -> None:
        value = self.value(self.model._current_progress_remaining)
        with th.no_grad():
            for log_std in self._heads_log_std():
                log_std.fill_(value)
        self.logger.record("train/log_std_scheduled", value)

    def _on_step(self) -> bool:
        return True
