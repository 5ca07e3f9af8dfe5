"""Glue between sb3_hfo and rl-zoo3 (the experiment runner).

rl-zoo3 keeps its algorithms and Optuna samplers in module-level tables (``rl_zoo3.utils.ALGOS``,
``rl_zoo3.hyperparams_opt.HYPERPARAMS_SAMPLER`` / ``HYPERPARAMS_CONVERTER``) and builds the ``--algo`` choices
from ``ALGOS`` *before* it imports ``--gym-packages``. So ``python -m sb3_hfo.train`` (and ``enjoy``,
``record_video``) call :func:`register_with_rl_zoo` first and then hand over to rl-zoo3's own entry points.

Four rl-zoo3 behaviours need a nudge for SkillDDPG, done by :class:`HFOExperimentManager`:

* rl-zoo3 turns ``"lin_<x>"`` strings into linear schedules only for the key ``learning_rate``; SkillDDPG has
  two learning rates (``learning_rate_actor``, ``learning_rate_critic``), so the same conversion is applied to
  those keys (the paper decays the critic's learning rate during training).
* During ``-optimize`` rl-zoo3 replaces the config's ``policy_kwargs`` wholesale by the sampled one, which would
  drop the experiment-defining keys (``n_skills``, ``skill_router``, ``inverting_gradients``); the sampled
  ``policy_kwargs`` are merged on top of the config's instead.
* ``-i`` (warm start) loads a committed model, which is stored stripped (:mod:`sb3_hfo.models`), through its
  rebuilt full zip.
* ``--checkpoint-freq N`` / ``--resume RUN_DIR`` (options of ``python -m sb3_hfo.train``, not rl-zoo3's): a
  checkpoint of the whole training state (:mod:`sb3_hfo.resume`) every ``N`` steps in the run folder, and a run
  continued from its folder's checkpoint (same folder, budget and TensorBoard run; the hyperparameters must match).
* rl-zoo3 (2.9) hands a config's ``env_kwargs`` (e.g. ``reward: shaped_gap``) to the training envs but builds the
  evaluation env with the command line's ``--env-kwargs`` only, so ``--eval-freq`` evaluations would report a
  different reward and pick ``best_model.zip`` by it. Unless ``--eval-env-kwargs`` is given, the evaluation env
  gets the same ``env_kwargs`` as the training envs, which is what rl-zoo3 documents as its default.

:class:`HFOEpisodeStatsCallback` logs ``rollout/episodes`` (SB3 excludes ``time/episodes`` from TensorBoard, and
the paper's figures are plotted against episodes). The training goal rate is SB3's own ``rollout/success_rate``
(from HFO's ``info["is_success"]``), logged for any SB3 algorithm, e.g. a TD3 baseline.
"""

from __future__ import annotations

import argparse
import contextlib
import shutil
import sys
import tempfile
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from stable_baselines3.common.callbacks import BaseCallback

#: Name under which SkillDDPG appears in rl-zoo3 (``--algo skill_ddpg``, log folder ``logs/skill_ddpg/``): the
#: default ``--algo`` of ``python -m sb3_hfo.train``, ``enjoy`` and ``record_video``.
ALGO_NAME = "skill_ddpg"
#: Name under which SkillPDQN, SkillDDPG's preset with the best recipe, appears in rl-zoo3 (``--algo skill_pdqn``).
PRESET_ALGO_NAME = "skill_pdqn"
#: Name under which HybridPPO (PPO over hybrid actions, :mod:`sb3_hfo.hybrid_ppo`) appears in rl-zoo3.
HYBRID_PPO_ALGO_NAME = "hybrid_ppo"

#: Hyperparameters holding a learning rate that rl-zoo3 style strings (``"lin_1e-3"``) or floats may describe.
SCHEDULE_KEYS: tuple[str, ...] = ("learning_rate", "learning_rate_actor", "learning_rate_critic")


def hfo_env_ids() -> list[str]:
    """Registered Gymnasium ids of the HFO tasks (imports :mod:`hfo2d`, which registers them)."""
    import gymnasium as gym

    import hfo2d  # noqa: F401  (registers HFO/* ids)

    return sorted(env_id for env_id in gym.registry if env_id.startswith("HFO/"))


def skill_ddpg_class() -> type:
    """The SkillDDPG class (imported lazily so that ``--help`` stays fast)."""
    from sb3_hfo.skill_ddpg import SkillDDPG

    return SkillDDPG


def algo_classes() -> dict[str, type]:
    """The algorithms registered with rl-zoo3, by ``--algo`` name (imported lazily)."""
    from sb3_hfo.hybrid_ppo import HybridPPO
    from sb3_hfo.skill_ddpg import SkillDDPG, SkillPDQN

    return {ALGO_NAME: SkillDDPG, PRESET_ALGO_NAME: SkillPDQN, HYBRID_PPO_ALGO_NAME: HybridPPO}


def parse_schedule(value: Any) -> Any:
    """Convert an rl-zoo3 style learning-rate value into what SB3 algorithms accept.

    ``"lin_<x>"`` -> linear decay from ``x`` (start of training) to 0 (end of ``n_timesteps``), as rl-zoo3 does
    for ``learning_rate``; a number or ``"<x>"`` -> constant ``x`` (as a float); a callable is returned unchanged.
    """
    from sb3_hfo.common.schedules import LinearToZero

    if callable(value):
        return value
    if isinstance(value, str):
        kind, _, number = value.partition("_")
        if kind == "lin" and number:
            return LinearToZero(float(number))
        if not number:
            return float(kind)
        raise ValueError(f"unknown schedule {value!r}: expected 'lin_<value>' or a number")
    if isinstance(value, (int, float)):
        return float(value)
    raise ValueError(f"invalid learning rate {value!r}")


@dataclass(frozen=True)
class CheckpointOptions:
    """``python -m sb3_hfo.train``'s own options: ``--checkpoint-freq`` (environment steps, or minutes of wall-clock
    time, between checkpoints) and ``--resume`` (the run folder to continue)."""

    freq: int | None = None
    resume: Path | None = None
    minutes: float | None = None

    @property
    def checkpointing(self) -> bool:
        """Whether ``--checkpoint-freq`` was given."""
        return self.freq is not None or self.minutes is not None


class ResumeError(ValueError):
    """``--resume`` cannot continue that run folder (its checkpoint is of other hyperparameters)."""


def split_checkpoint_options(argv: Sequence[str]) -> tuple[list[str], CheckpointOptions]:
    """Take ``--checkpoint-freq N`` and ``--resume RUN_DIR`` out of ``argv`` (the rest goes to rl-zoo3).

    :raises ValueError: a frequency that is not a positive integer, a run folder without a checkpoint, or
        ``--resume`` with ``-optimize``.
    """
    from sb3_hfo.resume import CHECKPOINT_NAME

    parser = argparse.ArgumentParser(add_help=False, allow_abbrev=False)
    parser.add_argument("--checkpoint-freq", type=str, default=None)
    parser.add_argument("--resume", type=str, default=None)
    known, rest = parser.parse_known_args(list(argv))
    freq, minutes = None, None
    value = known.checkpoint_freq
    if value is not None:
        if value.isdigit() and int(value) > 0:
            freq = int(value)
        elif value.endswith("min") and value[:-3].replace(".", "", 1).isdigit() and float(value[:-3]) > 0:
            minutes = float(value[:-3])
        else:
            raise ValueError(
                f"--checkpoint-freq must be a positive number of steps (50000) or of minutes (10min), got {value!r}"
            )
    resume = None
    if known.resume is not None:
        resume = Path(known.resume)
        if not (resume / CHECKPOINT_NAME).is_file():
            raise ValueError(
                f"--resume {resume}: no {CHECKPOINT_NAME} in that folder (a run of --checkpoint-freq)"
            )
        if _has_option(rest, "-optimize", "--optimize-hyperparameters"):
            raise ValueError("--resume continues a training run; it does not apply to -optimize")
    return rest, CheckpointOptions(freq, resume, minutes)


def _experiment_manager_class(checkpointing: CheckpointOptions | None = None) -> type:
    """Build :class:`HFOExperimentManager` lazily (rl_zoo3.exp_manager imports optuna, torch, ...)."""
    from rl_zoo3.exp_manager import ExperimentManager
    from rl_zoo3.hyperparams_opt import HYPERPARAMS_SAMPLER

    options = checkpointing or CheckpointOptions()

    class HFOExperimentManager(ExperimentManager):
        """rl-zoo3's ExperimentManager with SkillDDPG's two learning rates, policy_kwargs merging, eval env_kwargs
        and resumable runs."""

        def __init__(self, *args: Any, **kwargs: Any) -> None:
            super().__init__(*args, **kwargs)
            self._run_info: dict[str, Any] = {}
            if options.resume is not None:  # continue that run folder instead of numbering a new one
                self.save_path = str(options.resume)
                self.params_path = f"{self.save_path}/{self.env_name}"

        def create_envs(self, n_envs: int, eval_env: bool = False, no_log: bool = False) -> Any:
            if options.resume is not None and not eval_env:  # append to the run's monitor.csv (cut at resume)
                self.monitor_kwargs = {**self.monitor_kwargs, "override_existing": False}
            return super().create_envs(n_envs, eval_env=eval_env, no_log=no_log)

        def _save_config(self, saved_hyperparams: dict[str, Any]) -> None:
            # What a resume must match (the seed only built what the checkpoint replaces).
            self._run_info = {
                "algo": self.algo,
                "env": str(self.env_name),
                "n_envs": self.n_envs,
                "n_timesteps": self.n_timesteps,
                "hyperparams": dict(saved_hyperparams),
            }
            if options.resume is None:  # a resumed run keeps its first command line and config files
                super()._save_config(saved_hyperparams)

        def learn(self, model: Any) -> None:
            if not options.checkpointing and options.resume is None:
                return super().learn(model)
            from sb3_hfo.resume import CHECKPOINT_NAME, TrainingCheckpointCallback

            path = Path(self.save_path) / CHECKPOINT_NAME
            # Without --checkpoint-freq a resumed run keeps its own interval (set below).
            freq, minutes = (options.freq, options.minutes) if options.checkpointing else (None, 10.0)
            saver = TrainingCheckpointCallback(
                path, freq, list(self.callbacks), verbose=self.verbose, save_minutes=minutes
            )
            if options.resume is not None:
                saved = saver.resume(model).run_info
                differs = sorted(key for key in self._run_info if saved.get(key) != self._run_info[key])
                if differs:
                    raise ResumeError(f"--resume {options.resume}: its run had other {', '.join(differs)}")
                if not options.checkpointing:
                    saver.save_freq, saver.save_minutes = saved["checkpoint_interval"]
                print(f"Resuming {self.save_path} at {model.num_timesteps} steps")
            saver.run_info = {**self._run_info, "checkpoint_interval": (saver.save_freq, saver.save_minutes)}
            self.callbacks.append(saver)
            return super().learn(model)

        def setup_experiment(self) -> Any:
            # A run that fails while it is set up (a bad value in the config, an env that cannot be made) leaves
            # no folder behind: rl-zoo3 numbers a run after the folders present, so an empty HFO-...-v0_1 would
            # turn the next run into _2.
            # The folders this run would create: the run's own and the missing ones above it (-f, its algo folder).
            created = []
            folder = Path(self.save_path).absolute()
            while not folder.exists():
                created.append(folder)
                folder = folder.parent
            try:
                return super().setup_experiment()
            except BaseException:
                if created:
                    shutil.rmtree(created[0], ignore_errors=True)
                    for parent in created[1:]:
                        with contextlib.suppress(OSError):  # not empty: something else wrote there meanwhile
                            parent.rmdir()
                raise

        def _preprocess_hyperparams(self, hyperparams: dict[str, Any]) -> Any:
            processed = super()._preprocess_hyperparams(hyperparams)
            if self._eval_env_kwargs_args is None:
                self.eval_env_kwargs = dict(self.env_kwargs)
            return processed

        @staticmethod
        def _preprocess_schedules(hyperparams: dict[str, Any]) -> dict[str, Any]:
            for key in SCHEDULE_KEYS:
                if key in hyperparams:
                    hyperparams[key] = parse_schedule(hyperparams[key])
            return hyperparams

        def _load_pretrained_agent(self, hyperparams: dict[str, Any], env: Any) -> Any:
            # -i with a committed (stripped) model: rl-zoo3 loads it with SkillDDPG.load, which needs the full zip.
            from sb3_hfo.models import full_model_buffer, is_stripped

            if not is_stripped(self.trained_agent):
                return super()._load_pretrained_agent(hyperparams, env)
            original = self.trained_agent
            with tempfile.TemporaryDirectory(prefix="sb3_hfo_warm_start_") as folder:
                full = Path(folder) / Path(original).name
                full.write_bytes(full_model_buffer(original).getvalue())
                self.trained_agent = str(full)
                try:
                    return super()._load_pretrained_agent(hyperparams, env)
                finally:
                    self.trained_agent = original

        def hyperparameters_optimization(self) -> None:
            original_sampler = HYPERPARAMS_SAMPLER[self.algo]
            base_policy_kwargs = dict(self._hyperparams.get("policy_kwargs") or {})
            sampler = merge_policy_kwargs(original_sampler, base_policy_kwargs)
            if callbacks_need_action_noise(self.specified_callbacks):
                sampler = require_action_noise(sampler)
            HYPERPARAMS_SAMPLER[self.algo] = sampler
            try:
                super().hyperparameters_optimization()
            finally:
                HYPERPARAMS_SAMPLER[self.algo] = original_sampler

    return HFOExperimentManager


def merge_policy_kwargs(
    sampler: Callable[..., dict[str, Any]], base: dict[str, Any]
) -> Callable[..., dict[str, Any]]:
    """Wrap an Optuna sampler so its ``policy_kwargs`` extend ``base`` (the config's) instead of replacing it."""

    def merged_sampler(*args: Any, **kwargs: Any) -> dict[str, Any]:
        sampled = sampler(*args, **kwargs)
        sampled["policy_kwargs"] = {**base, **sampled.get("policy_kwargs", {})}
        return sampled

    return merged_sampler


def callbacks_need_action_noise(callbacks: Any) -> bool:
    """Whether a config's ``callback:`` entry (a name, a ``{name: kwargs}`` dict or a list of them) lists
    :class:`ActionNoiseDecayCallback`, which needs the model to have an action noise."""
    entries = callbacks if isinstance(callbacks, list) else [callbacks]
    names = [name for entry in entries for name in (entry if isinstance(entry, dict) else [entry])]
    return any(
        isinstance(name, str) and name.rsplit(".", 1)[-1] == "ActionNoiseDecayCallback" for name in names
    )


def require_action_noise(sampler: Callable[..., dict[str, Any]]) -> Callable[..., dict[str, Any]]:
    """Wrap an Optuna sampler of :mod:`sb3_hfo.hyperparams_opt` so that it never draws ``noise_type: none``."""
    from sb3_hfo.cli.hyperparams_opt import NOISE_REQUIRED_ARG

    def noisy_sampler(
        trial: Any, n_actions: int, n_envs: int, additional_args: dict[str, Any]
    ) -> dict[str, Any]:
        return sampler(trial, n_actions, n_envs, {**additional_args, NOISE_REQUIRED_ARG: True})

    return noisy_sampler


def _playback_class(algo_class: type) -> type:
    """A subclass whose ``load`` defaults to a 1-transition replay buffer and also reads stripped models
    (:mod:`sb3_hfo.models`).

    rl-zoo3's enjoy/record_video shrink the replay buffer only for algorithms in a hard-coded local list of
    off-policy names, which cannot be extended; watching a trained agent needs no buffer.
    """

    class PlaybackModel(algo_class):  # type: ignore[valid-type, misc]
        @classmethod
        def load(cls, path: Any, *args: Any, **kwargs: Any) -> Any:  # type: ignore[override]
            from sb3_hfo.models import full_model_buffer, is_stripped

            kwargs.setdefault("buffer_size", 1)
            if isinstance(path, (str, Path)) and Path(path).is_file() and is_stripped(path):
                path = full_model_buffer(path)
            return algo_class.load(path, *args, **kwargs)

    PlaybackModel.__name__ = algo_class.__name__
    PlaybackModel.__qualname__ = algo_class.__qualname__
    return PlaybackModel


def register_with_rl_zoo(playback: bool = False, checkpointing: CheckpointOptions | None = None) -> None:
    """Make rl-zoo3 know SkillDDPG, SkillPDQN and the HFO environments. Idempotent.

    :param playback: register a variant whose ``load`` uses a 1-transition replay buffer (enjoy, record_video).
    :param checkpointing: ``train``'s checkpoint / resume options.
    """
    import rl_zoo3.exp_manager
    import rl_zoo3.hyperparams_opt
    import rl_zoo3.train
    import rl_zoo3.utils

    import hfo2d  # noqa: F401  (registers the HFO/* Gymnasium ids)
    from sb3_hfo.cli.hyperparams_opt import (
        convert_skill_ddpg_params,
        sample_skill_ddpg_params,
        sample_skill_pdqn_params,
    )

    samplers = {ALGO_NAME: sample_skill_ddpg_params, PRESET_ALGO_NAME: sample_skill_pdqn_params}
    for name, algo_class in algo_classes().items():
        if name == HYBRID_PPO_ALGO_NAME:  # on-policy: no replay buffer to shrink; rl-zoo3's PPO search space
            rl_zoo3.utils.ALGOS[name] = algo_class
            for table in (
                rl_zoo3.hyperparams_opt.HYPERPARAMS_SAMPLER,
                rl_zoo3.hyperparams_opt.HYPERPARAMS_CONVERTER,
            ):
                table[name] = table["ppo"]
            continue
        # rl_zoo3.ALGOS, rl_zoo3.utils.ALGOS and the names imported by train/enjoy/record_video are one dict object.
        rl_zoo3.utils.ALGOS[name] = _playback_class(algo_class) if playback else algo_class
        rl_zoo3.hyperparams_opt.HYPERPARAMS_SAMPLER[name] = samplers[name]
        # The sampler's raw values map onto constructor arguments the same way for both.
        rl_zoo3.hyperparams_opt.HYPERPARAMS_CONVERTER[name] = convert_skill_ddpg_params
    # train() looks ExperimentManager up in its module namespace at call time.
    rl_zoo3.train.ExperimentManager = _experiment_manager_class(checkpointing)  # type: ignore[misc]


def _has_option(argv: Sequence[str], *names: str) -> bool:
    return any(arg in names or arg.split("=", 1)[0] in names for arg in argv)


def default_algo_argv(argv: Sequence[str], single_thread: bool = False) -> list[str]:
    """Command-line arguments with ``--algo skill_ddpg`` (and ``--num-threads 1``) added unless given.

    :param single_thread: add ``--num-threads 1`` (train.py and enjoy.py have the option). SkillDDPG's networks
        are small: one torch thread is fastest, and torch's default (one thread per core) slowed a training run
        more than tenfold on a 2-core machine shared with other processes (290 -> 20 steps/s).
    """
    argv = list(argv)
    if not _has_option(argv, "--algo"):
        argv = ["--algo", ALGO_NAME, *argv]
    if single_thread and not _has_option(argv, "--num-threads"):
        argv = [*argv, "--num-threads", "1"]
    return argv


def run_rl_zoo_entry_point(
    entry_point: Callable[[], None],
    argv: Sequence[str],
    playback: bool,
    single_thread: bool = False,
    checkpointing: CheckpointOptions | None = None,
) -> None:
    """Register SkillDDPG, default ``--algo`` to it (see :func:`default_algo_argv`) and run an rl-zoo3 entry
    point with ``argv``."""
    register_with_rl_zoo(playback=playback, checkpointing=checkpointing)
    sys.argv = [sys.argv[0], *default_algo_argv(argv, single_thread=single_thread)]
    entry_point()


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
    epsilon together helps (research/RESULTS.md). This callback moves every noise's ``sigma`` from its value at the start of
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
