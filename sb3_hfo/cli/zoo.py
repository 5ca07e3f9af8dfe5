"""Glue between sb3_hfo and rl-zoo3 (the experiment runner).

rl-zoo3 keeps its algorithms and Optuna samplers in module-level tables (``rl_zoo3.utils.ALGOS``,
``rl_zoo3.hyperparams_opt.HYPERPARAMS_SAMPLER`` / ``HYPERPARAMS_CONVERTER``) and builds the ``--algo`` choices
from ``ALGOS`` *before* it imports ``--gym-packages``. So ``python -m sb3_hfo.train`` (and ``enjoy``,
``record_video``) call :func:`register_with_rl_zoo` first and then hand over to rl-zoo3's own entry points.

Some rl-zoo3 behaviours need a nudge for sb3_hfo, done by :class:`HFOExperimentManager`:

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
* The algorithms know no task (:mod:`sb3_hfo.common.domain`): on an HFO env id a config's ``policy_kwargs`` get
  ``domain: hfo`` unless they name a domain, so that its ``skill_router: field_half``, ``acting: kick_mask`` and
  ``relative_to`` landmarks read HFO's columns.
* ``vec_env: batch`` (a config key of sb3_hfo's, with ``num_workers: N``): the training envs are hfo2d's batch
  (:func:`sb3_hfo.vec_env.make_hfo_vec_env`: the ``n_envs`` games stepped by one batch, in this process or
  sharded over ``N`` processes, wrapped in ``VecMonitor``) instead of rl-zoo3's ``DummyVecEnv`` of
  ``Monitor``-wrapped envs, which deep-copies every game's info dict every step. Seeds as rl-zoo3's (game i gets
  ``--seed`` + i), one ``monitor.csv`` in the run folder; the evaluation env is a batch as well. Resumable training
  (``--checkpoint-freq`` / ``--resume``) needs the ``DummyVecEnv`` and refuses a batch.
* rl-zoo3 (2.9) hands a config's ``env_kwargs`` (e.g. ``reward: shaped_gap``) to the training envs but builds the
  evaluation env with the command line's ``--env-kwargs`` only, so ``--eval-freq`` evaluations would report a
  different reward and pick ``best_model.zip`` by it. Unless ``--eval-env-kwargs`` is given, the evaluation env
  gets the same ``env_kwargs`` as the training envs, which is what rl-zoo3 documents as its default.

The training callbacks that configs name are library code: :mod:`sb3_hfo.callbacks`.
"""

from __future__ import annotations

import argparse
import contextlib
import numbers
import shutil
import sys
import tempfile
import traceback
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import hfo2d  # noqa: F401  (registers the HFO/* Gymnasium ids)
from hfo2d import ENV_IDS
from sb3_hfo.common.schedules import SCHEDULE_KEYS, parse_schedule
from sb3_hfo.errors import one_line
from sb3_hfo.hybrid_ppo import HybridPPO
from sb3_hfo.models import full_model_buffer, is_stripped
from sb3_hfo.skill_ddpg import SkillDDPG, SkillPDQN

#: Name under which SkillDDPG appears in rl-zoo3 (``--algo skill_ddpg``, log folder ``logs/skill_ddpg/``): the
#: default ``--algo`` of ``python -m sb3_hfo.train``, ``enjoy`` and ``record_video``.
ALGO_NAME = "skill_ddpg"
#: Name under which SkillPDQN, SkillDDPG's preset with the best recipe, appears in rl-zoo3 (``--algo skill_pdqn``).
PRESET_ALGO_NAME = "skill_pdqn"
#: Name under which HybridPPO (PPO over hybrid actions, :mod:`sb3_hfo.hybrid_ppo`) appears in rl-zoo3.
HYBRID_PPO_ALGO_NAME = "hybrid_ppo"


def algo_classes() -> dict[str, type]:
    """The algorithms registered with rl-zoo3, by ``--algo`` name."""
    return {ALGO_NAME: SkillDDPG, PRESET_ALGO_NAME: SkillPDQN, HYBRID_PPO_ALGO_NAME: HybridPPO}


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


class ConfigConflictError(ValueError):
    """A config's keys that cannot run together, or with the command line's options (reported in one line)."""


#: sb3_hfo's own config keys, read by :class:`HFOExperimentManager` and not passed to the algorithm:
#: ``vec_env`` (``dummy``: rl-zoo3's ``DummyVecEnv``, the default; ``batch``: hfo2d's batch) and ``num_workers``
#: (processes that step the batch; only with ``vec_env: batch``).
BATCH_CONFIG_KEYS: tuple[str, ...] = ("vec_env", "num_workers")
VEC_ENV_KINDS: tuple[str, ...] = ("dummy", "batch")


@dataclass(frozen=True)
class BatchOptions:
    """A config's ``vec_env`` / ``num_workers``: whether the training envs are hfo2d's batch, and its processes."""

    batch: bool = False
    num_workers: int = 1


def batch_options(hyperparams: dict[str, Any], partial: bool = False) -> BatchOptions:
    """The ``vec_env`` / ``num_workers`` keys of a run's hyperparameters.

    :param partial: ``hyperparams`` is one source of them (the config section, or ``--hyperparams``, which rl-zoo3
        merges over it): ``num_workers`` is not checked against a ``vec_env`` the other source may set.
    :raises ConfigConflictError: an unknown ``vec_env``, a ``num_workers`` that is not a positive integer, or
        ``num_workers`` without ``vec_env: batch``.
    """
    kind = hyperparams.get("vec_env", "dummy")
    if kind not in VEC_ENV_KINDS:
        raise ConfigConflictError(f"vec_env must be one of {', '.join(VEC_ENV_KINDS)}, got {kind!r}")
    workers = hyperparams.get("num_workers", 1)
    if isinstance(workers, bool) or not isinstance(workers, numbers.Integral) or workers < 1:
        raise ConfigConflictError(f"num_workers must be a positive integer, got {workers!r}")
    if "num_workers" in hyperparams and kind != "batch" and not (partial and "vec_env" not in hyperparams):
        raise ConfigConflictError("num_workers applies to vec_env: batch only (hfo2d's batch of games)")
    return BatchOptions(kind == "batch", int(workers))


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


#: The folders of the algorithms whose constructors check their own arguments (ValueError naming the argument).
_ALGORITHM_FOLDERS: tuple[Path, ...] = tuple(
    Path(module.__file__).resolve().parent
    for module in (sys.modules[SkillDDPG.__module__], sys.modules[HybridPPO.__module__])
)


def raised_by_algorithm_checks(error: BaseException) -> bool:
    """Whether ``error`` was raised inside sb3_hfo's algorithms (their constructors' argument checks) rather than
    by rl-zoo3, an env or a bug elsewhere: its innermost frame lies in an algorithm's package."""
    frames = traceback.extract_tb(error.__traceback__)
    if not frames:
        return False
    innermost = Path(frames[-1].filename).resolve()
    return any(innermost.is_relative_to(folder) for folder in _ALGORITHM_FOLDERS)


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
            self._batch = BatchOptions()
            if options.resume is not None:  # continue that run folder instead of numbering a new one
                self.save_path = str(options.resume)
                self.params_path = f"{self.save_path}/{self.env_name}"

        def create_envs(self, n_envs: int, eval_env: bool = False, no_log: bool = False) -> Any:
            if self._batch.batch:
                return self._create_batch(n_envs, eval_env, no_log)
            if options.resume is not None and not eval_env:  # append to the run's monitor.csv (cut at resume)
                self.monitor_kwargs = {**self.monitor_kwargs, "override_existing": False}
            return super().create_envs(n_envs, eval_env=eval_env, no_log=no_log)

        def _create_batch(self, n_envs: int, eval_env: bool, no_log: bool) -> Any:
            """The envs as hfo2d's batch, wrapped as rl-zoo3 wraps its ``DummyVecEnv`` (after its ``Monitor`` s:
            ``vec_env_wrapper``, ``VecNormalize``, frame stacking).

            The evaluation env is a batch too: SB3's ``EvalCallback`` copies ``VecNormalize``'s statistics by
            walking the training and evaluation envs' wrappers side by side, so both need the same chain."""
            from stable_baselines3.common.vec_env import VecFrameStack, VecMonitor

            from sb3_hfo.vec_env import make_hfo_vec_env

            env = make_hfo_vec_env(
                self.env_name.gym_id,
                n_envs,
                seed=self.seed,
                # the evaluation's few games (rl-zoo3's --n-eval-envs) are not worth a worker process
                num_workers=1 if eval_env else min(self._batch.num_workers, n_envs),
                monitor=False,
                **(self.eval_env_kwargs if eval_env else self.env_kwargs),
            )
            # One monitor.csv for all games (rl-zoo3's Monitors write one per env); rows in order of episode end.
            # Like rl-zoo3, no file for the evaluation env.
            env = VecMonitor(
                env,
                filename=None if no_log or eval_env else self.save_path,
                info_keywords=tuple(self.monitor_kwargs.get("info_keywords", ())),
            )
            if self.vec_env_wrapper is not None:
                env = self.vec_env_wrapper(env)
            env = self._maybe_normalize(env, eval_env)
            if self.frame_stack is not None:
                env = VecFrameStack(env, self.frame_stack)
            return env

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
            except BaseException as error:
                if created:
                    shutil.rmtree(created[0], ignore_errors=True)
                    for parent in created[1:]:
                        with contextlib.suppress(OSError):  # not empty: something else wrote there meanwhile
                            parent.rmdir()
                if isinstance(error, ValueError) and raised_by_algorithm_checks(error):
                    raise ConfigConflictError(
                        f"a hyperparameter of --conf-file / --hyperparams: {one_line(error)}"
                    ) from None
                raise

        def _preprocess_hyperparams(self, hyperparams: dict[str, Any]) -> Any:
            self._batch = batch_options(hyperparams)
            for key in BATCH_CONFIG_KEYS:
                hyperparams.pop(key, None)
            processed = super()._preprocess_hyperparams(hyperparams)
            if self._eval_env_kwargs_args is None:
                self.eval_env_kwargs = dict(self.env_kwargs)
            if self.algo in algo_classes():
                processed[0]["policy_kwargs"] = with_hfo_domain(
                    processed[0].get("policy_kwargs"), self.env_name.gym_id
                )
            if self._batch.batch:
                self._check_batch(env_wrapper=processed[1])
            return processed

        def _check_batch(self, env_wrapper: Any) -> None:
            """Refuse what ``vec_env: batch`` cannot do, before any folder or env is made."""
            from stable_baselines3.common.vec_env import DummyVecEnv

            if options.checkpointing or options.resume is not None:
                raise ConfigConflictError(
                    "--checkpoint-freq / --resume need rl-zoo3's DummyVecEnv; this config trains on hfo2d's batch "
                    "(vec_env: batch): add --hyperparams \"vec_env:'dummy'\" to checkpoint it"
                )
            if self.vec_env_class is not DummyVecEnv:
                raise ConfigConflictError(
                    f"--vec-env {self.vec_env_class.__name__} and vec_env: batch (the config's) exclude each other; "
                    "num_workers: 2 steps the batch on two processes"
                )
            if self.env_name.gym_id not in ENV_IDS:
                raise ConfigConflictError(
                    f"vec_env: batch needs an hfo2d id ({', '.join(ENV_IDS)}), got {self.env_name.gym_id}"
                )
            if env_wrapper is not None:
                raise ConfigConflictError(
                    "env_wrapper wraps each env, and vec_env: batch has no per-game wrappers: use vec_env_wrapper"
                )
            unsupported = sorted(set(self.monitor_kwargs) - {"info_keywords"})
            if unsupported:
                raise ConfigConflictError(
                    f"monitor_kwargs {unsupported} do not apply to vec_env: batch (VecMonitor takes info_keywords)"
                )

        @staticmethod
        def _preprocess_schedules(hyperparams: dict[str, Any]) -> dict[str, Any]:
            for key in SCHEDULE_KEYS:
                if key in hyperparams:
                    hyperparams[key] = parse_schedule(hyperparams[key])
            return hyperparams

        def _load_pretrained_agent(self, hyperparams: dict[str, Any], env: Any) -> Any:
            # -i with a committed (stripped) model: rl-zoo3 loads it with SkillDDPG.load, which needs the full zip.
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


#: The domain adapter the HFO env ids get (:data:`sb3_hfo.hfo.HFO_DOMAIN`).
HFO_DOMAIN_NAME = "hfo"


def with_hfo_domain(policy_kwargs: dict[str, Any] | None, env_id: str) -> dict[str, Any] | None:
    """``policy_kwargs`` with ``domain="hfo"`` added for an HFO env id (a config's own ``domain`` is kept)."""
    if env_id not in ENV_IDS:
        return policy_kwargs
    return {"domain": HFO_DOMAIN_NAME, **(policy_kwargs or {})}


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
    """Wrap an Optuna sampler of :mod:`sb3_hfo.cli.hyperparams_opt` so that it never draws ``noise_type: none``."""
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

    # Optuna (the [zoo] extra) is imported only when rl-zoo3 is about to run.
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
