"""Training callbacks for SkillDDPG (and any SB3 algorithm): the episode counter the paper's figures need, the
action-noise annealing and the keeper-skill curriculum. rl-zoo3 configs name them as
``sb3_hfo.callbacks.HFOEpisodeStatsCallback`` and so on (the ``callback:`` key).

:class:`HFOEpisodeStatsCallback` logs ``rollout/episodes`` (SB3 excludes ``time/episodes`` from TensorBoard, and
the paper's figures are plotted against episodes). The training goal rate is SB3's own ``rollout/success_rate``
(from HFO's ``info["is_success"]``), logged for any SB3 algorithm, e.g. a TD3 baseline.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from stable_baselines3.common.callbacks import BaseCallback


class HFOEpisodeStatsCallback(BaseCallback):
    """Log ``rollout/episodes``, the number of episodes finished so far, whenever one ends (written at SB3's next
    log dump): SB3 logs ``time/episodes`` to stdout only, and the paper's Figures 3 and 4 use episodes on the x axis.

    The goal rate is not logged here: SB3 logs it for every algorithm as ``rollout/success_rate`` (the last
    ``stats_window_size`` episodes' ``info["is_success"]``, which HFO sets at a GOAL), the one name it has.
    """

    def __init__(self, verbose: int = 0) -> None:
        super().__init__(verbose)
        self.episodes = 0

    def _on_step(self) -> bool:
        dones = np.asarray(self.locals.get("dones", []), dtype=bool)
        finished = int(dones.sum())
        if finished:
            self.episodes += finished
            self.logger.record("rollout/episodes", self.episodes)
        return True


def _ramp_progress(callback: BaseCallback, start_timesteps: int, ramp_fraction: float) -> float:
    """Progress in [0, 1] of a ramp over the first ``ramp_fraction`` of the current ``learn`` call's steps."""
    total = max(int(getattr(callback.model, "_total_timesteps", 0)) - start_timesteps, 1)
    return min((callback.num_timesteps - start_timesteps) / (ramp_fraction * total), 1.0)


class ActionNoiseDecayCallback(BaseCallback):
    """Anneal the standard deviation of the model's Gaussian (or Ornstein-Uhlenbeck) action noise linearly.

    SB3's ``action_noise`` keeps its ``sigma`` fixed, and rl-zoo3's ``noise_std`` sets it once. Wide noise early on
    shows the critic many kicks; late in training the same noise spoils aimed kicks, and the behaviour policy (whose
    returns ``mc_mixing`` mixes into the targets) stays far worse than the greedy one; annealing the noise and
    epsilon together helps (docs/findings.md, "Annealed exploration"). This callback moves every noise's ``sigma`` from its value at the start of
    each ``learn`` call to ``final_std`` over the first ``decay_fraction`` of that call (the schedule of SB3's
    epsilon), then holds it, and logs it as ``rollout/action_noise_std``.

    :param final_std: noise standard deviation at the end of the decay, on the policy's action scale ([-1, 1]
        in SB3's buffer; the same unit as rl-zoo3's ``noise_std``).
    :param decay_fraction: fraction of the ``learn`` call's ``total_timesteps`` over which to decay, in (0, 1].
    """

    def __init__(self, final_std: float, decay_fraction: float = 1.0, verbose: int = 0) -> None:
        super().__init__(verbose)
        if not np.isfinite(final_std) or final_std < 0:
            raise ValueError(f"final_std must be a finite number >= 0, got {final_std!r}")
        if not 0 < decay_fraction <= 1:
            raise ValueError(f"decay_fraction must be in (0, 1], got {decay_fraction!r}")
        self.final_std = float(final_std)
        self.decay_fraction = float(decay_fraction)
        self.initial_sigmas: list[np.ndarray] = []
        self._start_timesteps = 0

    def _noises(self) -> list[Any]:
        noise = getattr(self.model, "action_noise", None)
        if noise is None:
            return []
        return list(getattr(noise, "noises", [noise]))  # VectorizedActionNoise holds one noise per env

    def _init_callback(self) -> None:
        noises = self._noises()
        if not noises or not all(hasattr(noise, "_sigma") for noise in noises):
            raise ValueError(
                "ActionNoiseDecayCallback needs a model with a Gaussian or Ornstein-Uhlenbeck action_noise "
                f"(rl-zoo3: noise_type normal or ornstein-uhlenbeck); got {getattr(self.model, 'action_noise', None)!r}"
            )

    def _on_training_start(self) -> None:
        self.initial_sigmas = [
            np.array(noise._sigma, dtype=np.float64, copy=True) for noise in self._noises()
        ]
        self._start_timesteps = self.num_timesteps

    def _on_step(self) -> bool:
        progress = _ramp_progress(self, self._start_timesteps, self.decay_fraction)
        for noise, initial in zip(self._noises(), self.initial_sigmas, strict=True):
            noise._sigma = initial + progress * (self.final_std - initial)
        self.logger.record("rollout/action_noise_std", float(np.mean(self._noises()[0]._sigma)))
        return True


class KeeperSkillCurriculumCallback(BaseCallback):
    """Raise the scripted goalie's skill of the training envs from ``initial_skill`` to ``final_skill``.

    A curriculum for ``HFO/Keeper-v0`` (E6, which the paper could not solve): against the full keeper a random
    policy almost never scores, so the shaped reward's goal bonus is rarely seen. The skill moves linearly over the
    first ``ramp_fraction`` of each ``learn`` call in steps of ``skill_step`` (each change rebuilds the keeper at
    the envs' next reset), then holds; it is logged as ``rollout/keeper_skill``. Only the training envs are
    changed: rl-zoo3's evaluation env, and ``python -m sb3_hfo.evaluate``, keep the env's own ``keeper_skill``
    (1.0 for ``HFO/Keeper-v0``), so evaluations measure E6's task. SB3 resets the envs before callbacks start, so
    each env's first episode keeps the keeper it was made with.

    :param initial_skill: keeper skill at the start, in [0, 1] (0: a keeper that only turns to face the ball).
    :param final_skill: keeper skill at the end of the ramp, in [0, 1].
    :param ramp_fraction: fraction of the ``learn`` call's ``total_timesteps`` over which to ramp, in (0, 1].
    :param skill_step: the skill changes in steps of this size, in (0, 1].
    """

    def __init__(
        self,
        initial_skill: float = 0.0,
        final_skill: float = 1.0,
        ramp_fraction: float = 0.5,
        skill_step: float = 0.05,
        verbose: int = 0,
    ) -> None:
        super().__init__(verbose)
        for name, value in (("initial_skill", initial_skill), ("final_skill", final_skill)):
            if not 0.0 <= value <= 1.0:  # also rejects NaN
                raise ValueError(f"{name} must be in [0, 1], got {value!r}")
        if not 0 < ramp_fraction <= 1:
            raise ValueError(f"ramp_fraction must be in (0, 1], got {ramp_fraction!r}")
        if not 0 < skill_step <= 1:
            raise ValueError(f"skill_step must be in (0, 1], got {skill_step!r}")
        self.initial_skill = float(initial_skill)
        self.final_skill = float(final_skill)
        self.ramp_fraction = float(ramp_fraction)
        self.skill_step = float(skill_step)
        self.skill = self.initial_skill
        self._start_timesteps = 0

    def _init_callback(self) -> None:  # SB3 calls it at the start of every learn()
        try:
            self._set_skill(self.initial_skill)
        except (AttributeError, ValueError) as error:
            raise ValueError(
                f"KeeperSkillCurriculumCallback needs HFO/Keeper-v0 training envs (set_keeper_skill): {error}"
            ) from error

    def _on_training_start(self) -> None:
        self._start_timesteps = self.num_timesteps

    def _set_skill(self, skill: float) -> None:
        self.skill = skill
        self.training_env.env_method("set_keeper_skill", skill)

    def _on_step(self) -> bool:
        progress = _ramp_progress(self, self._start_timesteps, self.ramp_fraction)
        target = self.initial_skill + progress * (self.final_skill - self.initial_skill)
        # Rounded to the nearest skill_step, so that each env's keeper is rebuilt a few dozen times, not every step.
        quantised = self.final_skill if progress >= 1.0 else self.skill_step * round(target / self.skill_step)
        quantised = min(max(quantised, 0.0), 1.0)
        if quantised != self.skill:
            self._set_skill(quantised)
        self.logger.record("rollout/keeper_skill", self.skill)
        return True


class GoalRatePacedCurriculumCallback(BaseCallback):
    """A training env setting moved one step toward its final value whenever the agent scores often enough.

    :class:`KeeperSkillCurriculumCallback` moves the goalie's skill on a step schedule, whatever the agent does; in
    the E6 runs from reward (HybridPPO on ``HFO/Keeper-v1``, research/RESULTS.md) the training goal rate fell from
    48 % to 5 % while the skill rose: the task outgrew the policy. Here the pace is the agent's: the value starts
    at ``initial`` and moves by ``step`` toward ``final`` once at least ``window`` episodes were played at the
    current value and the goal rate over the last ``window`` of them is at least ``threshold``. It never moves
    back. An episode counts only if it started after the last change (an env applies the value at its next reset,
    so the episode running at a change was played partly at the old one).

    Each change calls ``env_method(name, value)`` on the training VecEnv. Goals are read from
    ``info["is_success"]`` at the end of each episode (HFO sets it on a GOAL). The value is logged as
    ``rollout/<logged_name>`` and the counted goal rate as ``rollout/curriculum_goal_rate``; :attr:`history` lists
    ``(timestep, value)`` at every change.

    :param env_method: the env method that takes the new value (e.g. ``"set_keeper_skill"``).
    :param initial: the value at the start.
    :param final: the last value; the value moves toward it from either side.
    :param step: the size of each move, > 0.
    :param threshold: the goal rate (in (0, 1]) that earns a move.
    :param window: the number of episodes, at least 1, over which the goal rate is measured.
    :param logged_name: the logger key's name under ``rollout/``.
    :param wait_for: another paced curriculum of the same run: this one moves only once that one has reached its
        final value (e.g. the goalie at full strength before the starts move away from the goal).
    """

    def __init__(
        self,
        env_method: str,
        initial: float,
        final: float,
        step: float,
        threshold: float = 0.7,
        window: int = 200,
        logged_name: str = "curriculum_value",
        verbose: int = 0,
        wait_for: GoalRatePacedCurriculumCallback | None = None,
    ) -> None:
        super().__init__(verbose)
        for name, value in (("initial", initial), ("final", final)):
            if not np.isfinite(value):
                raise ValueError(f"{name} must be a finite number, got {value!r}")
        if not (np.isfinite(step) and step > 0):
            raise ValueError(f"step must be a finite number > 0, got {step!r}")
        if not 0 < threshold <= 1:
            raise ValueError(f"threshold must be in (0, 1], got {threshold!r}")
        if isinstance(window, bool) or not isinstance(window, (int, np.integer)) or window < 1:
            raise ValueError(f"window must be an integer >= 1, got {window!r}")
        self.env_method_name = env_method
        self.initial = float(initial)
        self.final = float(final)
        self.step = float(step)
        self.threshold = float(threshold)
        self.window = int(window)
        self.logged_name = logged_name
        self.wait_for = wait_for
        self._wait_for_changes = 0  # changes of wait_for seen: each one restarts this curriculum's count
        self.value = self.initial
        self.history: list[tuple[int, float]] = []
        self._outcomes: list[bool] = []  # goals of the counted episodes since the last change
        self._fresh = np.zeros(0, dtype=bool)  # per game: its current episode started after the last change

    def _init_callback(self) -> None:
        try:
            self._set_value(self.initial)
        except (AttributeError, ValueError) as error:
            raise ValueError(
                f"{type(self).__name__} needs training envs with {self.env_method_name}: {error}"
            ) from error
        # SB3 reset the envs before this call, with the setting they were made with: their first episodes do not count
        self._fresh = np.zeros(self.training_env.num_envs, dtype=bool)

    def _set_value(self, value: float) -> None:
        self.value = value
        self.training_env.env_method(self.env_method_name, value)
        self.history.append((int(self.num_timesteps), value))
        self._outcomes = []

    def goal_rate(self) -> float | None:
        """The goal rate over the last ``window`` counted episodes at the current value (None before any)."""
        recent = self._outcomes[-self.window :]
        return float(np.mean(recent)) if recent else None

    @property
    def finished(self) -> bool:
        """Whether the value has reached ``final``."""
        return self.value == self.final

    def _next_value(self) -> float:
        if self.final >= self.value:
            return min(round(self.value + self.step, 6), self.final)
        return max(round(self.value - self.step, 6), self.final)

    def _on_step(self) -> bool:
        if self.wait_for is not None and len(self.wait_for.history) != self._wait_for_changes:
            # the other curriculum changed the task: the episodes counted so far, and those running, do not count
            self._wait_for_changes = len(self.wait_for.history)
            self._outcomes = []
            self._fresh[:] = False
        dones = np.asarray(self.locals["dones"], dtype=bool)
        infos = self.locals["infos"]
        for game in np.flatnonzero(dones):
            if self._fresh[game]:
                self._outcomes.append(bool(infos[game].get("is_success", False)))
            self._fresh[game] = True  # its next episode starts with the current value
        rate = self.goal_rate()
        waiting = self.wait_for is not None and not self.wait_for.finished
        if (
            not self.finished
            and not waiting
            and len(self._outcomes) >= self.window
            and rate >= self.threshold
        ):
            self._set_value(self._next_value())
            self._fresh[:] = False
            if self.verbose:
                print(
                    f"{self.logged_name} -> {self.value} at {self.num_timesteps} steps (goal rate {rate:.3f})",
                    flush=True,
                )
        self.logger.record(f"rollout/{self.logged_name}", self.value)
        if rate is not None:
            self.logger.record("rollout/curriculum_goal_rate", rate)
        return True


class GoalRateKeeperCurriculumCallback(GoalRatePacedCurriculumCallback):
    """The goalie's ``keeper_skill`` raised by ``skill_step`` from ``initial_skill`` to ``final_skill`` (both in
    [0, 1]) at the agent's pace: see :class:`GoalRatePacedCurriculumCallback`. :attr:`skill` is the current one."""

    def __init__(
        self,
        initial_skill: float = 0.0,
        final_skill: float = 1.0,
        skill_step: float = 0.1,
        threshold: float = 0.7,
        window: int = 200,
        verbose: int = 0,
    ) -> None:
        for name, value in (("initial_skill", initial_skill), ("final_skill", final_skill)):
            if not 0.0 <= value <= 1.0:  # also rejects NaN
                raise ValueError(f"{name} must be in [0, 1], got {value!r}")
        if final_skill < initial_skill:
            raise ValueError(f"final_skill ({final_skill}) must not be below initial_skill ({initial_skill})")
        if not 0 < skill_step <= 1:
            raise ValueError(f"skill_step must be in (0, 1], got {skill_step!r}")
        super().__init__(
            "set_keeper_skill",
            initial_skill,
            final_skill,
            skill_step,
            threshold,
            window,
            "keeper_skill",
            verbose,
        )

    @property
    def skill(self) -> float:
        """The training goalie's current skill."""
        return self.value


class GoalRateStartShiftCallback(GoalRatePacedCurriculumCallback):
    """A start-distance curriculum: hfo2d's ``start_shift`` (metres the ball's start range is moved toward the
    goal) lowered by ``shift_step`` from ``initial_shift`` to ``final_shift`` at the agent's pace (see
    :class:`GoalRatePacedCurriculumCallback`): the agent first learns to score from close, then from farther out,
    down to HFO's own starts at 0."""

    def __init__(
        self,
        initial_shift: float = 30.0,
        final_shift: float = 0.0,
        shift_step: float = 5.0,
        threshold: float = 0.7,
        window: int = 200,
        verbose: int = 0,
        wait_for: GoalRatePacedCurriculumCallback | None = None,
    ) -> None:
        if not 0.0 <= final_shift <= initial_shift:  # also rejects NaN
            raise ValueError(
                f"need 0 <= final_shift <= initial_shift, got {final_shift!r} and {initial_shift!r}"
            )
        super().__init__(
            "set_start_shift",
            initial_shift,
            final_shift,
            shift_step,
            threshold,
            window,
            "start_shift",
            verbose,
            wait_for,
        )
