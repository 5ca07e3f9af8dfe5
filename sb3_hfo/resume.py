"""Resumable training: checkpoint an SB3 off-policy run's whole state and continue it as if never stopped.

:func:`save_training_state` writes, in one file, everything a run's future depends on:

* the model as SB3's ``save`` stores it (weights, every optimizer's state, and its attributes: ``num_timesteps``,
  ``_episode_num``, ``_n_updates``, ``_total_timesteps``, ``_current_progress_remaining`` (the learning-rate and
  exploration schedules' progress), ``_last_obs`` / ``_last_episode_starts``, ``action_noise`` with its current
  ``sigma``, ``exploration_rate``, the episode statistics buffers);
* the replay buffer (with its write position and, for a Monte Carlo buffer, the episodes in progress);
* every random generator: Python's ``random``, numpy's global one, torch's (and CUDA's), the model's action and
  observation spaces';
* each environment of the (Dummy)VecEnv mid-episode, pickled whole with its wrappers (``hfo2d``'s envs pickle
  their pymunk world and ``np_random``); ``Monitor`` wrappers keep their counters, and their ``monitor.csv`` is cut
  back to its length at the checkpoint when the run resumes (so rows written after it are not repeated);
* the callbacks' counters (``n_calls``, ``StopTrainingOnMaxEpisodes.n_episodes``, ``EvalCallback``'s best reward,
  its evaluations and its evaluation env, ``ActionNoiseDecayCallback``'s start values, ...): each callback's
  attributes, less its links to the model, environments (snapshotted as above) and other callbacks;
* the logger's folder and outputs, so that TensorBoard continues in the same run folder at the right step.

The file is written atomically (a temporary file in the same folder, flushed to disk, then ``os.replace``): a
process killed at any moment leaves either the previous checkpoint or the new one, never a partial file.

:class:`TrainingCheckpointCallback` writes a checkpoint every ``save_freq`` environment steps (or ``save_minutes``
of wall-clock time), at the one point of
SB3's loop where the state is consistent (the start of a rollout: the last transition stored, the last update
done). To continue a run, build the model, environments and callbacks as the first run did, then::

    callbacks = [...]  # the run's own callbacks, built as before
    checkpoint = TrainingCheckpointCallback("run/checkpoint.pkl", save_freq=10_000, callbacks=callbacks)
    if checkpoint.path.exists():
        checkpoint.resume(model)  # restores everything into model, its envs and the callbacks
    model.learn(remaining_timesteps(model, total), callback=[*callbacks, checkpoint], reset_num_timesteps=False)

``learn``'s set-up resets the action noise, re-runs the callbacks' ``on_training_start`` (which would restart,
e.g., a noise-decay ramp) and, with ``reset_num_timesteps=True``, the counters and the envs; the callback restores
all of it again once ``learn`` has set up, so ``learn(total)`` as the first run called it (what rl-zoo3 does) works
as well. A run so resumed gives the same weights, replay buffer and counters as an unbroken one
(``tests/sb3_hfo/test_resume.py``).

Checkpoints are pickles (like SB3's replay buffers): load only files you trust. Only ``DummyVecEnv`` is supported
(a ``SubprocVecEnv``'s envs live in other processes). SB3's ``csv`` / ``json`` / ``log`` logger outputs restart
their file on resume (SB3 opens them for writing); ``stdout`` and ``tensorboard`` continue.
"""

from __future__ import annotations

import io
import os
import random
import sys
import time
from collections.abc import Iterable, Iterator, Sequence
from pathlib import Path
from typing import Any

import cloudpickle
import gymnasium as gym
import numpy as np
import torch as th
from stable_baselines3.common.base_class import BaseAlgorithm
from stable_baselines3.common.callbacks import BaseCallback, CallbackList, EventCallback
from stable_baselines3.common.logger import (
    CSVOutputFormat,
    HumanOutputFormat,
    JSONOutputFormat,
    Logger,
    TensorBoardOutputFormat,
    configure,
)
from stable_baselines3.common.monitor import Monitor
from stable_baselines3.common.save_util import load_from_zip_file
from stable_baselines3.common.utils import check_for_correct_spaces
from stable_baselines3.common.vec_env import DummyVecEnv, VecEnv

__all__ = [
    "CHECKPOINT_NAME",
    "TrainingCheckpointCallback",
    "TrainingState",
    "load_training_state",
    "remaining_timesteps",
    "save_training_state",
]

#: File name of a run's checkpoint inside its run folder (``python -m sb3_hfo.train --checkpoint-freq``).
CHECKPOINT_NAME = "training_checkpoint.pkl"
#: Version of the checkpoint's layout; a file of another version is refused.
FORMAT_VERSION = 1

# A DummyVecEnv's own state besides its envs: the seeds / options its next reset() applies, the last step's buffers.
_VEC_ENV_ATTRIBUTES = ("_seeds", "_options", "reset_infos", "buf_obs", "buf_dones", "buf_rews", "buf_infos")
# Model attributes that stay as built: the spaces keep their identity with the env's (their generators are
# restored), and the policy is rebuilt from policy_kwargs only by SB3's load, not here.
# start_time: fps counts from the resume.
_MODEL_KEYS_KEPT = ("observation_space", "action_space", "policy_class", "policy_kwargs", "start_time")
# Callback attributes that are links, not state: the model, SB3's step locals, the parent, a progress bar.
_CALLBACK_LINKS = ("model", "locals", "globals", "parent", "pbar")


# ----------------------------------------------------------------------------------------------------------------
# Saving and loading


def save_training_state(
    path: str | os.PathLike[str],
    model: BaseAlgorithm,
    callbacks: Sequence[BaseCallback] = (),
    run_info: dict[str, Any] | None = None,
) -> None:
    """Write ``model``'s whole training state, its environments', the random generators' and ``callbacks``' to
    ``path`` atomically (the previous file stays whole until the new one is complete).

    :param callbacks: the run's callbacks whose counters matter (nested ``CallbackList`` / ``EventCallback``
        children are included).
    :param run_info: what identifies the run (its command-line options, say), returned by
        :func:`load_training_state` so that a resume can check it continues the same run.
    :raises ValueError: a part of the state that cannot be checkpointed (a ``SubprocVecEnv``, an env or a
        callback attribute that does not pickle); nothing is written.
    """
    path = Path(path)
    model_zip = io.BytesIO()
    model.save(model_zip)
    state = {
        "version": FORMAT_VERSION,
        "algorithm": type(model).__qualname__,
        "model_zip": model_zip.getvalue(),
        "extra_tensors": _extra_tensors(model),
        "replay_buffer": getattr(model, "replay_buffer", None),
        "env": _vec_env_state(model.get_env()),
        "callbacks": [_callback_state(callback) for callback in _flatten(callbacks)],
        "logger": _logger_state(model),
        "rng": _rng_state(model),
        "run_info": dict(run_info or {}),
    }
    _atomic_write(path, state)


class TrainingState:
    """A checkpoint read by :func:`load_training_state`: its ``run_info``, and the means to restore it again, all
    but the weights, optimizers and replay buffer, once ``learn`` has set up (which resets counters, the action
    noise, the envs and the callbacks' ramps)."""

    def __init__(self, path: Path, state: dict[str, Any], model_data: bytes) -> None:
        self.path = path
        self._state = state
        self._model_data = (
            model_data  # pickled, so that every restore starts from the checkpoint's own values
        )

    @property
    def run_info(self) -> dict[str, Any]:
        """The ``run_info`` given to :func:`save_training_state`."""
        return dict(self._state["run_info"])

    @property
    def num_timesteps(self) -> int:
        """The checkpointed run's ``num_timesteps``."""
        return int(self._state["num_timesteps"])

    def restore(self, model: BaseAlgorithm, callbacks: Sequence[BaseCallback]) -> None:
        """Put back the model's attributes (counters, schedules' progress, last observation, action noise, episode
        buffers), its replay buffer, the environments, the callbacks' state and the random generators (last, so
        that nothing restored before draws from them)."""
        for key, value in cloudpickle.loads(self._model_data).items():
            setattr(model, key, value)
        # fps counts from here (SB3 logs (num_timesteps - _num_timesteps_at_start) / time since start_time).
        model._num_timesteps_at_start = model.num_timesteps
        model.start_time = time.time_ns()
        for name, tensor in self._state["extra_tensors"].items():
            _get_attribute(model, name).copy_(tensor)
        if self._state["replay_buffer"] is not None:
            model.replay_buffer = self._state["replay_buffer"]
        vec_env = model.get_env()
        assert vec_env is not None
        _restore_vec_env(vec_env, self._state["env"])
        _restore_callbacks(callbacks, self._state["callbacks"])
        _restore_rng(model, self._state["rng"])


def load_training_state(
    path: str | os.PathLike[str], model: BaseAlgorithm, callbacks: Sequence[BaseCallback] = ()
) -> TrainingState:
    """Restore a checkpoint of :func:`save_training_state` into ``model`` (built as the checkpointed one was, with
    its environment), its environments and ``callbacks`` (the same callbacks, in the same order).

    :raises FileNotFoundError: no file at ``path``.
    :raises ValueError: the file is not such a checkpoint, or it is of another algorithm, environment spaces,
        number of environments or set of callbacks; the model is left unchanged.
    """
    path = Path(path)
    with path.open("rb") as file:
        try:
            state = cloudpickle.load(file)
        except Exception as error:  # a truncated or foreign file: pickle raises many kinds
            raise ValueError(f"{path} is not a readable training checkpoint: {error}") from error
    if not isinstance(state, dict) or state.get("version") != FORMAT_VERSION:
        raise ValueError(f"{path} is not a training checkpoint of format {FORMAT_VERSION}")
    if state["algorithm"] != type(model).__qualname__:
        raise ValueError(
            f"{path} is a checkpoint of {state['algorithm']}, the model is a {type(model).__qualname__}"
        )
    vec_env = model.get_env()
    if vec_env is None:
        raise ValueError("the model has no environment to restore the checkpoint's into")
    data, params, torch_variables = load_from_zip_file(io.BytesIO(state["model_zip"]), device=model.device)
    check_for_correct_spaces(vec_env, data["observation_space"], data["action_space"])
    if data.get("n_envs") != vec_env.num_envs:
        raise ValueError(
            f"{path} was saved with {data.get('n_envs')} env(s), the model has {vec_env.num_envs}"
        )
    _check_env_snapshot(vec_env, state["env"], path)
    _check_callbacks(callbacks, state["callbacks"], path)

    model.set_parameters(params, exact_match=True, device=model.device)
    for name, tensor in (torch_variables or {}).items():
        _get_attribute(model, name).data.copy_(tensor.data)
    state["num_timesteps"] = data["num_timesteps"]
    model_data = {key: value for key, value in data.items() if key not in _MODEL_KEYS_KEPT}
    loaded = TrainingState(path, state, cloudpickle.dumps(model_data, protocol=5))
    loaded.restore(model, callbacks)
    _restore_logger(model, state["logger"])
    return loaded


def remaining_timesteps(model: BaseAlgorithm, total_timesteps: int) -> int:
    """The ``total_timesteps`` to give ``learn(..., reset_num_timesteps=False)`` so that a resumed run ends where
    the unbroken one would (SB3 adds ``num_timesteps`` to it) and its schedules keep their length."""
    return max(int(total_timesteps) - int(model.num_timesteps), 0)


class TrainingCheckpointCallback(BaseCallback):
    """Write the training state (:func:`save_training_state`) to ``path`` every ``save_freq`` environment steps
    (``num_timesteps``, all envs' steps) or every ``save_minutes`` of wall-clock time, and when ``learn`` ends its
    budget, atomically; resume from it with :meth:`resume`.

    Writing a checkpoint changes nothing in the run, so a wall-clock interval keeps runs reproducible too (it
    only decides where a resumed run restarts from).

    :param path: the checkpoint file (one file, replaced at each save).
    :param save_freq: environment steps between checkpoints (> 0), or ``None``.
    :param save_minutes: minutes of wall-clock time between checkpoints (> 0), or ``None``; at least one of the
        two.
    :param callbacks: the run's other callbacks whose state the checkpoint keeps (give them in the same order on
        resume).
    :param run_info: what identifies the run (see :func:`save_training_state`).
    """

    def __init__(
        self,
        path: str | os.PathLike[str],
        save_freq: int | None = None,
        callbacks: Sequence[BaseCallback] = (),
        run_info: dict[str, Any] | None = None,
        verbose: int = 0,
        save_minutes: float | None = None,
    ) -> None:
        super().__init__(verbose)
        if save_freq is not None and (
            isinstance(save_freq, bool) or not isinstance(save_freq, (int, np.integer)) or save_freq < 1
        ):
            raise ValueError(f"save_freq must be a positive integer (environment steps), got {save_freq!r}")
        if save_minutes is not None and not (
            isinstance(save_minutes, (int, float)) and 0 < save_minutes < np.inf
        ):
            raise ValueError(f"save_minutes must be a positive number, got {save_minutes!r}")
        if save_freq is None and save_minutes is None:
            raise ValueError(
                "give save_freq (environment steps) or save_minutes (wall-clock) between checkpoints"
            )
        self.path = Path(path)
        self.save_freq = None if save_freq is None else int(save_freq)
        self.save_minutes = None if save_minutes is None else float(save_minutes)
        self.tracked_callbacks = list(callbacks)
        self.run_info = dict(run_info or {})
        self._resumed: TrainingState | None = None
        self._next_save = 0
        self._last_saved = -1
        self._last_save_time = time.monotonic()

    def resume(self, model: BaseAlgorithm) -> TrainingState:
        """Restore the checkpoint at :attr:`path` into ``model``, its envs and the tracked callbacks (see
        :func:`load_training_state`); all but the weights are restored again when ``learn`` starts (after its
        set-up, which resets them) and when its first rollout starts. So ``learn`` may be called either as
        ``learn(remaining_timesteps(model, total), reset_num_timesteps=False)`` or as the first run called it,
        ``learn(total)`` (what rl-zoo3 does); this callback must be in its callbacks."""
        self._resumed = load_training_state(self.path, model, self.tracked_callbacks)
        return self._resumed

    def save(self) -> None:
        """Write a checkpoint of the current state now."""
        save_training_state(self.path, self.model, self.tracked_callbacks, self.run_info)
        self._last_saved = self.model.num_timesteps
        self._last_save_time = time.monotonic()
        if self.verbose >= 1:
            print(f"Training checkpoint at {self.model.num_timesteps} steps: {self.path}")

    def _on_training_start(self) -> None:
        if self._resumed is not None:  # learn's set-up has reset what resume() restored
            self._resumed.restore(self.model, self.tracked_callbacks)
        self._schedule_next_save()
        self._last_save_time = time.monotonic()

    def _schedule_next_save(self) -> None:
        if self.save_freq is not None:
            self._next_save = (self.model.num_timesteps // self.save_freq + 1) * self.save_freq

    def _save_due(self) -> bool:
        if self.save_freq is not None and self.model.num_timesteps >= self._next_save:
            return True
        return (
            self.save_minutes is not None
            and time.monotonic() - self._last_save_time >= 60 * self.save_minutes
        )

    def _on_rollout_start(self) -> None:
        # Here SB3's loop is between two iterations: the last transition stored, the last update done.
        if self._resumed is not None:  # once more: callbacks after this one in the list started after it
            self._resumed.restore(self.model, self.tracked_callbacks)
            self._resumed = None
        if self._save_due():
            self.save()
            self._schedule_next_save()

    def _on_step(self) -> bool:
        return True

    def _on_training_end(self) -> None:
        # After the last update of the budget the state is consistent too; a run stopped by a callback (which
        # returns before SB3 stores the step's transition) keeps its last checkpoint instead.
        if (
            self.model.num_timesteps >= self.model._total_timesteps
            and self.model.num_timesteps > self._last_saved
        ):
            self.save()


# ----------------------------------------------------------------------------------------------------------------
# The file


def _atomic_write(path: Path, state: dict[str, Any]) -> None:
    """Pickle ``state`` to a temporary file beside ``path``, flush it to disk, then rename it over ``path``."""
    path.parent.mkdir(parents=True, exist_ok=True)
    for stale in path.parent.glob(f".{path.name}.*.tmp"):  # left by a process killed while writing
        stale.unlink(missing_ok=True)
    temporary = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        with temporary.open("wb") as file:
            cloudpickle.dump(state, file, protocol=5)
            file.flush()
            os.fsync(file.fileno())
        os.replace(temporary, path)
    except BaseException as error:
        temporary.unlink(missing_ok=True)
        if isinstance(error, (cloudpickle.pickle.PicklingError, TypeError, AttributeError)):
            raise ValueError(f"the training state cannot be checkpointed: {error}") from error
        raise
    directory = os.open(path.parent, os.O_RDONLY)
    try:  # the rename itself reaches the disk
        os.fsync(directory)
    finally:
        os.close(directory)


# ----------------------------------------------------------------------------------------------------------------
# Model pieces SB3's save leaves out


def _extra_tensors(model: BaseAlgorithm) -> dict[str, th.Tensor]:
    """Tensors outside SB3's zip that training statistics accumulate in between log dumps (SkillDDPG's)."""
    stats = getattr(model, "_stat_sums", None)
    return {"_stat_sums": stats.detach().clone()} if isinstance(stats, th.Tensor) else {}


def _get_attribute(obj: Any, dotted: str) -> Any:
    for name in dotted.split("."):
        obj = getattr(obj, name)
    return obj


# ----------------------------------------------------------------------------------------------------------------
# Random generators


def _space_generator_state(space: gym.Space | None) -> dict[str, Any] | None:
    generator = getattr(
        space, "_np_random", None
    )  # None until first used or seeded (``np_random`` would seed it)
    return None if generator is None else generator.bit_generator.state


def _rng_state(model: BaseAlgorithm) -> dict[str, Any]:
    return {
        "python": random.getstate(),
        "numpy": np.random.get_state(),
        "torch": th.get_rng_state(),
        "cuda": th.cuda.get_rng_state_all() if th.cuda.is_available() else None,
        "action_space": _space_generator_state(model.action_space),
        "observation_space": _space_generator_state(model.observation_space),
    }


def _restore_rng(model: BaseAlgorithm, saved: dict[str, Any]) -> None:
    random.setstate(saved["python"])
    np.random.set_state(saved["numpy"])
    th.set_rng_state(saved["torch"])
    if saved["cuda"] is not None and th.cuda.is_available():
        th.cuda.set_rng_state_all(saved["cuda"])
    for name in ("action_space", "observation_space"):
        space = getattr(model, name)
        if saved[name] is None:
            space._np_random = None
        else:
            space.np_random.bit_generator.state = saved[name]


# ----------------------------------------------------------------------------------------------------------------
# Environments


def _wrapper_chain(env: gym.Env) -> Iterator[gym.Env]:
    while True:
        yield env
        if not isinstance(env, gym.Wrapper):
            return
        env = env.env


def _monitors(env: gym.Env) -> list[Monitor]:
    return [wrapper for wrapper in _wrapper_chain(env) if isinstance(wrapper, Monitor)]


def _monitor_file(monitor: Monitor) -> tuple[str, int] | None:
    """The monitor's csv file and its length now (the writer flushes every row)."""
    writer = monitor.results_writer
    if writer is None:
        return None
    writer.file_handler.flush()
    name = writer.file_handler.name
    return name, os.path.getsize(name)


def _vec_env_state(vec_env: VecEnv | None) -> dict[str, Any]:
    if not isinstance(vec_env, DummyVecEnv):
        raise ValueError(
            f"resumable training needs a DummyVecEnv (its envs live in this process), got {type(vec_env).__name__}"
        )
    envs = []
    for index, env in enumerate(vec_env.envs):
        monitors = _monitors(env)
        writers = [monitor.results_writer for monitor in monitors]
        files = [_monitor_file(monitor) for monitor in monitors]
        try:
            for monitor in monitors:  # an open file does not pickle; the resumed env keeps its own writer
                monitor.results_writer = None
            pickled = cloudpickle.dumps(env, protocol=5)
        except Exception as error:
            raise ValueError(
                f"env {index} ({env}) cannot be checkpointed: it does not pickle ({error})"
            ) from error
        finally:
            for monitor, writer in zip(monitors, writers, strict=True):
                monitor.results_writer = writer
        envs.append({"env": pickled, "chain": _chain_names(env), "monitor_files": files})
    attributes = {name: getattr(vec_env, name) for name in _VEC_ENV_ATTRIBUTES if hasattr(vec_env, name)}
    return {"envs": envs, "attributes": cloudpickle.dumps(attributes, protocol=5)}


def _chain_names(env: gym.Env) -> list[str]:
    return [type(wrapper).__name__ for wrapper in _wrapper_chain(env)]


def _check_env_snapshot(vec_env: VecEnv, saved: dict[str, Any], path: Path) -> None:
    if not isinstance(vec_env, DummyVecEnv):
        raise ValueError(f"resumable training needs a DummyVecEnv, got {type(vec_env).__name__}")
    if len(saved["envs"]) != len(vec_env.envs):
        raise ValueError(f"{path} holds {len(saved['envs'])} env(s), the VecEnv has {len(vec_env.envs)}")
    for index, (env, snapshot) in enumerate(zip(vec_env.envs, saved["envs"], strict=True)):
        if _chain_names(env) != snapshot["chain"]:
            raise ValueError(
                f"{path}: env {index} was {' < '.join(snapshot['chain'])}, now {' < '.join(_chain_names(env))}"
            )


def _restore_vec_env(vec_env: VecEnv, saved: dict[str, Any]) -> None:
    assert isinstance(vec_env, DummyVecEnv)
    for index, snapshot in enumerate(saved["envs"]):
        current = vec_env.envs[index]
        restored = cloudpickle.loads(snapshot["env"])
        for old, new, file in zip(
            _monitors(current), _monitors(restored), snapshot["monitor_files"], strict=True
        ):
            new.results_writer = old.results_writer
            if file is not None and new.results_writer is not None:
                _cut_monitor_file(new, *file)
        if restored is not current:
            vec_env.envs[index] = restored
    for name, value in cloudpickle.loads(saved["attributes"]).items():
        setattr(vec_env, name, value)


def _cut_monitor_file(monitor: Monitor, saved_name: str, saved_size: int) -> None:
    """Cut the monitor's csv back to its length at the checkpoint: rows of episodes after it are played again."""
    writer = monitor.results_writer
    assert writer is not None
    writer.file_handler.flush()
    name = writer.file_handler.name
    size = os.path.getsize(name)
    if size < saved_size:
        raise ValueError(
            f"the monitor file {name} ({size} bytes) is shorter than the checkpoint's {saved_name} ({saved_size} "
            "bytes): "
            "a resumed run's Monitor must append to its file (Monitor(..., override_existing=False))"
        )
    if size > saved_size:
        os.truncate(name, saved_size)
        writer.file_handler.seek(0, io.SEEK_END)


# ----------------------------------------------------------------------------------------------------------------
# Callbacks


def _flatten(callbacks: Iterable[BaseCallback]) -> Iterator[BaseCallback]:
    """Every callback, then its children (CallbackList's, EventCallback's), depth first."""
    for callback in callbacks:
        yield callback
        if isinstance(callback, CallbackList):
            yield from _flatten(callback.callbacks)
        if isinstance(callback, EventCallback) and callback.callback is not None:
            yield from _flatten([callback.callback])
        after_eval = getattr(callback, "callback_after_eval", None)
        if isinstance(after_eval, BaseCallback):
            yield from _flatten([after_eval])


def _callback_state(callback: BaseCallback) -> dict[str, Any]:
    """A callback's attributes less its links; its VecEnvs (an EvalCallback's eval_env) as env snapshots."""
    attributes: dict[str, Any] = {}
    envs: dict[str, Any] = {}
    for name, value in vars(callback).items():
        if name in _CALLBACK_LINKS or isinstance(value, (BaseAlgorithm, BaseCallback, Logger)):
            continue
        if (
            isinstance(value, (list, tuple))
            and value
            and all(isinstance(item, BaseCallback) for item in value)
        ):
            continue  # CallbackList.callbacks: flattened separately
        if isinstance(value, VecEnv):
            envs[name] = _vec_env_state(value)
            continue
        try:
            cloudpickle.dumps(value, protocol=5)
        except Exception as error:
            raise ValueError(
                f"{type(callback).__name__}.{name} cannot be checkpointed: it does not pickle ({error})"
            ) from error
        attributes[name] = value
    return {"class": type(callback).__qualname__, "attributes": cloudpickle.dumps(attributes), "envs": envs}


def _check_callbacks(callbacks: Sequence[BaseCallback], saved: list[dict[str, Any]], path: Path) -> None:
    current = [type(callback).__qualname__ for callback in _flatten(callbacks)]
    checkpointed = [entry["class"] for entry in saved]
    if current != checkpointed:
        raise ValueError(f"{path} was saved with the callbacks {checkpointed}, the run has {current}")


def _restore_callbacks(callbacks: Sequence[BaseCallback], saved: list[dict[str, Any]]) -> None:
    for callback, entry in zip(_flatten(callbacks), saved, strict=True):
        for name, value in cloudpickle.loads(entry["attributes"]).items():
            setattr(callback, name, value)
        for name, env_state in entry["envs"].items():
            _restore_vec_env(getattr(callback, name), env_state)


# ----------------------------------------------------------------------------------------------------------------
# Logger


def _format_name(output: Any) -> str | None:
    if isinstance(output, HumanOutputFormat):
        return "stdout" if output.file is sys.stdout else "log"
    # isinstance, not type(): a resumed run logs through _ResumedTensorBoardOutput, and a checkpoint written by it
    # must name TensorBoard too (an exact-type lookup dropped it, so a run resumed twice logged no more curves)
    names = {CSVOutputFormat: "csv", JSONOutputFormat: "json", TensorBoardOutputFormat: "tensorboard"}
    return next((name for kind, name in names.items() if isinstance(output, kind)), None)


def _logger_state(model: BaseAlgorithm) -> dict[str, Any] | None:
    logger = getattr(model, "_logger", None)
    if logger is None:
        return None
    formats = [name for name in map(_format_name, logger.output_formats) if name is not None]
    folder = logger.get_dir()
    return {
        # absolute: a resumed process may start in another working directory
        "folder": None if folder is None else os.path.abspath(folder),
        "formats": formats,
        "custom": bool(getattr(model, "_custom_logger", False)),
    }


class _ResumedTensorBoardOutput(TensorBoardOutputFormat):
    """SB3's TensorBoard output, writing to a run folder again from ``purge_step`` on: TensorBoard discards the
    events at steps >= ``purge_step`` from the folder's earlier event files (those logged after the checkpoint by
    the process that was stopped), so the curves show each step once."""

    def __init__(
        self, folder: str, purge_step: int
    ) -> None:  # not SB3's __init__: one writer, with purge_step
        from torch.utils.tensorboard import SummaryWriter

        self.writer = SummaryWriter(log_dir=folder, purge_step=purge_step)
        self._is_closed = False


def _restore_logger(model: BaseAlgorithm, saved: dict[str, Any] | None) -> None:
    """Log to the checkpointed run's folder and outputs again, TensorBoard from the step after the checkpoint.

    Without this, SB3's ``learn(reset_num_timesteps=False)`` would pick the newest ``<tb_log_name>_<n>`` folder of
    ``tensorboard_log``, which is another run's when two runs share it.
    """
    if saved is None or saved["folder"] is None:
        return
    logger = configure(saved["folder"], [name for name in saved["formats"] if name != "tensorboard"])
    if "tensorboard" in saved["formats"]:
        logger.output_formats.append(_ResumedTensorBoardOutput(saved["folder"], int(model.num_timesteps) + 1))
    model.set_logger(logger)
