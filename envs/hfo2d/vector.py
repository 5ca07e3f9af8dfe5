"""Batched hfo2d: N games stepped in one process (:class:`HFOVectorEnv`) or sharded over worker processes
(:class:`ShardedHFOVectorEnv`), as Gymnasium 1.x ``VectorEnv`` s.

``gym.make_vec(id, num_envs=N, vectorization_mode="vector_entry_point")`` makes an :class:`HFOVectorEnv` for every
``HFO/*`` id of :mod:`hfo2d` (the simulator's ids, not the ``Real*`` ones), with ``gym.make``'s keyword rules.

Conventions (Gymnasium 1.x's, as its ``SyncVectorEnv`` follows them):

* **Seeds**: ``reset(seed=s)`` seeds game i with ``s + i`` (a list of seeds seeds each game with its own);
  ``reset()`` without a seed continues each game's own generator.
* **Bit for bit**: game i is an unwrapped :class:`hfo2d.HFOEnv` and plays exactly like ``gym.make(id)`` reset with
  game i's seed and given game i's actions, across episodes too (``tests/hfo2d/test_vector_env.py`` checks this
  against the golden rollouts and against ``SyncVectorEnv``).
* **Auto-reset**: ``AutoresetMode.SAME_STEP`` by default (``metadata["autoreset_mode"]``), the convention closest
  to SB3's: the step that ends a game's episode resets that game at once (without a seed, so Keeper-v1's goalie
  carries its state over as in real HFO, as an episode loop over ``gym.make(id)`` does); the observation returned
  is the new episode's, the info is the reset's info plus ``final_obs`` (the last observation) and
  ``final_info`` (the last step's info). ``autoreset_mode=AutoresetMode.NEXT_STEP`` (Gymnasium's default for
  ``SyncVectorEnv``) is also supported: the step after an episode's end resets the game, ignores its action and
  returns reward 0, not terminated, not truncated and the reset's info.
* **Infos**: Gymnasium's vector info dict: each key holds an array over the games and ``"_key"`` a boolean mask
  of the games that have it (the arrays, dtypes and key order of ``VectorEnv._add_info``). It is a
  :class:`VectorInfo`, a ``dict`` built on its first read: building it costs about as much as stepping a fast game,
  and training loops rarely read it. ``step_games`` (what ``sb3_hfo``'s adapter uses) returns the games' own info
  dicts instead.
* **Actions**: a batch of the single action space (flat: an array (N, 8); parameterized: a tuple of four arrays
  over the games). Every game's action is validated before any game moves: a bad one is a ValueError naming the
  game and the problem (the single env's message), and no game changes.

Speed: the games are the single env's ``step`` and ``reset`` unchanged; the batch's own work (the action check,
the buffers, the copies returned) is about 13 µs per step of 16 stand-in games that cost nothing. The figures
against the single env are in ``benchmarks/README.md`` (``benchmarks/vector_throughput.py``).

Only numpy and gymnasium (and hfo2d) are imported: no torch, no SB3 (their adapter is ``sb3_hfo.vec_env``).
"""

from __future__ import annotations

import contextlib
import multiprocessing
import multiprocessing.connection
import os
import pickle
import signal
import time
import traceback
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode
from gymnasium.vector.utils import batch_space

from hfo2d.hfo_env import HFOEnv

__all__ = ["HFOVectorEnv", "ShardedHFOVectorEnv", "VectorInfo", "split_games", "vector_info"]

AUTORESET_MODES: tuple[AutoresetMode, ...] = (AutoresetMode.SAME_STEP, AutoresetMode.NEXT_STEP)


def _autoreset_mode(mode: AutoresetMode | str) -> AutoresetMode:
    try:
        mode = AutoresetMode(mode)
    except ValueError:
        mode = None  # type: ignore[assignment]
    if mode not in AUTORESET_MODES:
        raise ValueError(f"autoreset_mode must be one of {[m.value for m in AUTORESET_MODES]}, got {mode!r}")
    return mode


def _check_num_envs(num_envs: Any) -> int:
    if isinstance(num_envs, bool) or not isinstance(num_envs, (int, np.integer)) or num_envs < 1:
        raise ValueError(f"num_envs must be a positive integer, got {num_envs!r}")
    return int(num_envs)


def _game_seeds(seed: int | Sequence[int | None] | None, num_envs: int) -> list[int | None]:
    """Gymnasium's convention: one seed s seeds game i with s + i; a sequence gives each game its own."""
    if seed is None:
        return [None] * num_envs
    if isinstance(seed, (int, np.integer)) and not isinstance(seed, bool):
        return [int(seed) + index for index in range(num_envs)]
    if isinstance(seed, Sequence) and not isinstance(seed, str) and len(seed) == num_envs:
        return list(seed)
    raise ValueError(f"seed must be None, an int or a sequence of {num_envs} seeds, got {seed!r}")


def _reset_mask(options: Mapping[str, Any] | None, num_envs: int) -> tuple[np.ndarray | None, dict | None]:
    """Gymnasium's ``options["reset_mask"]`` (the games to reset) split from the games' own reset options."""
    if options is None or "reset_mask" not in options:
        return None, None if options is None else dict(options)
    game_options = {key: value for key, value in options.items() if key != "reset_mask"}
    mask = np.asarray(options["reset_mask"])
    if mask.dtype != np.bool_ or mask.shape != (num_envs,):
        raise ValueError(
            f"reset_mask must be a bool array of shape ({num_envs},), got {options['reset_mask']!r}"
        )
    return mask, game_options or None


def _per_game_options(
    per_game: Sequence[Mapping[str, Any] | None] | None, common: Mapping[str, Any] | None, num_envs: int
) -> list[Mapping[str, Any] | None]:
    if per_game is None:
        return [common] * num_envs
    if len(per_game) != num_envs:
        raise ValueError(
            f"per_game_options needs {num_envs} entries (a dict or None each), got {len(per_game)}"
        )
    return [options or None for options in per_game]


def _indices(indices: Sequence[int] | int | None, num_envs: int) -> list[int]:
    """SB3's ``indices``: None for every game, one index, or a sequence of them (each checked)."""
    if indices is None:
        return list(range(num_envs))
    chosen = [indices] if isinstance(indices, (int, np.integer)) else list(indices)
    for index in chosen:
        if isinstance(index, bool) or not isinstance(index, (int, np.integer)) or not 0 <= index < num_envs:
            raise ValueError(f"game index {index!r} is not one of 0 ... {num_envs - 1}")
    return [int(index) for index in chosen]


def _values_for(values: Any, count: int) -> list[Any]:
    """One value for every chosen game, or a list / tuple of exactly one per game."""
    if not isinstance(values, (list, tuple)):
        return [values] * count
    if len(values) != count:
        raise ValueError(f"set_attr needs one value or {count} values, got {len(values)}")
    return list(values)


# -----------------------------------------------------------------------------------------------------------------
# Gymnasium's vector info dict, built column by column
# -----------------------------------------------------------------------------------------------------------------
_PLAIN_NUMBERS = (int, float, bool)


def vector_info(infos: Sequence[Mapping[str, Any]], num_envs: int) -> dict[str, Any]:
    """The games' info dicts as Gymnasium's vector info: per key an array over the games and ``"_key"`` the mask
    of the games that have it. Same arrays, dtypes and masks as ``gymnasium.vector.VectorEnv._add_info`` applied
    game by game (its dtype is the type of the first value seen; nested dicts recurse; ``final_obs`` is an object
    array), built a key at a time instead of a game at a time."""
    first = infos[0].keys() if infos else {}.keys()
    if all(info.keys() == first for info in infos):
        keys: Any = first
        everywhere = True
    else:
        keys = dict.fromkeys(key for info in infos for key in info)
        everywhere = False
    result: dict[str, Any] = {}
    for key in keys:
        if everywhere:
            values = [info[key] for info in infos]
            mask = np.ones(num_envs, dtype=np.bool_)
        else:
            present = [key in info for info in infos]
            mask = np.array(present, dtype=np.bool_)
            values = [info.get(key) for info in infos]
        sample = next(value for value, has in zip(values, mask, strict=True) if has)
        if key == "final_obs":
            array: Any = _object_array(values, mask, num_envs)
        elif isinstance(sample, dict):
            array = vector_info(
                [value if has else {} for value, has in zip(values, mask, strict=True)], num_envs
            )
        elif type(sample) in _PLAIN_NUMBERS or isinstance(sample, np.number):
            if everywhere:
                array = np.array(values, dtype=type(sample))
            else:
                array = np.zeros(num_envs, dtype=type(sample))
                for index in np.flatnonzero(mask):
                    array[index] = values[index]
        elif isinstance(sample, np.ndarray):
            array = np.zeros((num_envs, *sample.shape), dtype=sample.dtype)
            for index in np.flatnonzero(mask):
                array[index] = values[index]
        else:
            array = _object_array(values, mask, num_envs)
        result[key] = array
        result[f"_{key}"] = mask
    return result


class VectorInfo(dict):
    """Gymnasium's vector info dict (:func:`vector_info`) built when it is first read.

    Building it costs about as much as a fast game's step (an array and a mask per key), and most training loops
    never read most keys, so :meth:`HFOVectorEnv.step` returns this dict, which holds the games' own info dicts
    until any read or write (``info["status"]``, ``in``, iteration, ``len``, ``dict(info)``, ``==``, pickling,
    ``copy.deepcopy``) builds the real contents once. It is a ``dict`` (``isinstance(info, dict)`` holds) and then
    behaves as one.
    """

    __slots__ = ("_games",)

    def __init__(
        self, games: Sequence[Mapping[str, Any]] | Callable[[], Sequence[Mapping[str, Any]]]
    ) -> None:
        """``games``: the games' info dicts, or a function that returns them (called once, on the first read)."""
        super().__init__()
        self._games: Any = games

    def _build(self) -> None:
        games = self._games
        if games is not None:
            self._games = None
            if callable(games):
                games = games()
            dict.update(self, vector_info(games, len(games)))

    def __reduce_ex__(self, protocol: Any) -> Any:  # pickle / deepcopy: a plain dict of the built contents
        self._build()
        return dict, (dict(self.items()),)


def _built_first(name: str) -> Callable[..., Any]:
    method = getattr(dict, name)

    def wrapper(self: VectorInfo, *args: Any, **kwargs: Any) -> Any:
        self._build()
        return method(self, *args, **kwargs)

    wrapper.__name__ = name
    wrapper.__doc__ = method.__doc__
    return wrapper


# every dict method that reads or writes the contents builds them first
for _name in (
    "__getitem__",
    "__setitem__",
    "__delitem__",
    "__contains__",
    "__iter__",
    "__reversed__",
    "__len__",
    "__eq__",
    "__ne__",
    "__or__",
    "__ror__",
    "__ior__",
    "__repr__",
    "keys",
    "values",
    "items",
    "get",
    "pop",
    "popitem",
    "setdefault",
    "update",
    "copy",
    "clear",
):
    setattr(VectorInfo, _name, _built_first(_name))
VectorInfo.__hash__ = None  # type: ignore[assignment]  (as dict's)


def _object_array(values: list[Any], mask: np.ndarray, num_envs: int) -> np.ndarray:
    array = np.full(num_envs, None, dtype=object)
    for index in np.flatnonzero(mask):
        array[index] = values[index]  # one by one: a tuple must stay one element
    return array


def checked_actions(actions: Any, envs: Sequence[HFOEnv], flat_shape: tuple[int, ...] | None) -> Any:
    """Each game's action (an iterable over the games), every one validated as the single env validates it:
    a ValueError names the first bad game and the single env's message. ``flat_shape`` is the batch's flat action
    shape (N, 8), or None for the parameterized format."""
    num_envs = len(envs)
    if flat_shape is not None:
        if (
            type(actions) is np.ndarray
            and actions.shape == flat_shape
            and actions.dtype.kind == "f"
            and actions.min() >= 0.0  # (a NaN anywhere makes min() and max() NaN, which fails the comparison)
            and actions.max() <= 1.0
        ):
            return actions  # rows of a valid float array: what the single env's fast path takes
        if type(actions) is not np.ndarray or actions.ndim != 2:
            try:
                actions = list(actions)
            except TypeError:
                raise ValueError(
                    f"actions must be one per game: shape {flat_shape}, got {actions!r}"
                ) from None
        if len(actions) != num_envs:
            raise ValueError(f"actions must be one per game: shape {flat_shape}, got {len(actions)} actions")
        for index, (env, action) in enumerate(zip(envs, actions, strict=True)):
            _validate(index, env._parse_flat_action, action)
        return actions
    if not isinstance(actions, (tuple, list)) or len(actions) != 4:
        raise ValueError(
            "parameterized actions must be a tuple of 4 arrays over the games (kinds, dash parameters, turn "
            f"parameters, kick parameters), got {actions!r}"
        )
    for part in actions:
        if len(part) != num_envs:
            raise ValueError(f"parameterized actions need {num_envs} entries per part, got {len(part)}")
    rows = list(zip(*actions, strict=True))
    for index, (env, action) in enumerate(zip(envs, rows, strict=True)):
        _validate(index, env._parse_parameterized_action, action)
    return rows


def _validate(index: int, parse: Callable[[Any], Any], action: Any) -> None:
    try:
        parse(action)
    except ValueError as error:
        raise ValueError(f"game {index}: {error}") from None


# -----------------------------------------------------------------------------------------------------------------
# One process
# -----------------------------------------------------------------------------------------------------------------
class _AllGamesAccess:
    """Gymnasium's ``call`` / ``get_attr`` / ``set_attr`` over every game, through a batch's per-game methods
    (``call_games``, ``get_attr_games``, ``set_attr_games``: SB3's indices), shared by both batches."""

    def call(self, name: str, *args: Any, **kwargs: Any) -> tuple[Any, ...]:
        """Each game's attribute ``name``, called with the arguments if it is callable (SyncVectorEnv's call)."""
        return tuple(self.call_games(name, args, kwargs))  # type: ignore[attr-defined]

    def get_attr(self, name: str) -> tuple[Any, ...]:
        """Each game's attribute ``name``."""
        return tuple(self.get_attr_games(name))  # type: ignore[attr-defined]

    def set_attr(self, name: str, values: Any) -> None:
        """Set attribute ``name`` of every game: one value for all, or a list / tuple of one per game."""
        self.set_attr_games(name, values)  # type: ignore[attr-defined]


class HFOVectorEnv(_AllGamesAccess, gym.vector.VectorEnv):
    """N hfo2d games stepped in one process, each an unwrapped :class:`hfo2d.HFOEnv` (see the module docstring
    for the seeding, auto-reset and info conventions).

    Args:
        num_envs: the number of games.
        autoreset_mode: ``AutoresetMode.SAME_STEP`` (default) or ``AutoresetMode.NEXT_STEP`` (or their values).
        env_id: the registered id this batch stands for (for ``spec``-like reporting only; ``gym.make_vec``
            passes it); the games are made from ``env_kwargs``.
        **env_kwargs: :class:`hfo2d.HFOEnv`'s arguments, the same for every game (``task``, ``goalie``,
            ``action_format``, ``reward``, ``render_mode``, ...).

    Attributes:
        envs: the games (unwrapped ``HFOEnv`` s), game i at index i.
    """

    def __init__(
        self,
        num_envs: int,
        autoreset_mode: AutoresetMode | str = AutoresetMode.SAME_STEP,
        env_id: str | None = None,
        **env_kwargs: Any,
    ) -> None:
        self.num_envs = _check_num_envs(num_envs)
        self.autoreset_mode = _autoreset_mode(autoreset_mode)
        self.env_id = env_id
        self.env_kwargs = dict(env_kwargs)
        self.envs: tuple[HFOEnv, ...] = tuple(HFOEnv(**env_kwargs) for _ in range(self.num_envs))
        first = self.envs[0]
        self.render_mode = first.render_mode
        self.metadata = {**HFOEnv.metadata, "autoreset_mode": self.autoreset_mode}
        self.single_observation_space = first.observation_space
        self.single_action_space = first.action_space
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self._flat = first.action_format == "flat"
        self._action_shape = (self.num_envs, *self.single_action_space.shape) if self._flat else None
        n = self.num_envs
        self._observations = np.zeros((n, *self.single_observation_space.shape), dtype=np.float32)
        self._flat_observations = self._observations.reshape(-1)  # a view: the games' rows end to end
        self._rewards = np.zeros(n, dtype=np.float64)
        self._terminations = np.zeros(n, dtype=np.bool_)
        self._truncations = np.zeros(n, dtype=np.bool_)
        # NEXT_STEP: the games whose episode ended on the last step (reset on this one)
        self._ended = np.zeros(n, dtype=np.bool_)
        self._game_steps = tuple(env.step for env in self.envs)
        self._game_resets = tuple(env.reset for env in self.envs)
        self._needs_reset = True
        self.closed = False

    # --- Gymnasium API ---------------------------------------------------------------------------------------
    def reset(
        self, *, seed: int | Sequence[int | None] | None = None, options: Mapping[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        """Reset every game (or those of ``options["reset_mask"]``): game i with ``seed + i``; ``options`` (other
        than ``reset_mask``) go to every reset game (``HFOEnv.reset``'s hand placements)."""
        infos = self.reset_games(seed=seed, options=options)
        return self._observations.copy(), VectorInfo(infos)

    def step(self, actions: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]:
        """Step every game once with its row of ``actions``; see the module docstring for auto-reset."""
        infos = self.step_games(actions)
        return (
            self._observations.copy(),
            self._rewards.copy(),
            self._terminations.copy(),
            self._truncations.copy(),
            VectorInfo(infos),
        )

    def render(self) -> tuple[np.ndarray | None, ...] | None:
        """Each game's ``render()`` (a tuple over the games); None without a render mode."""
        if self.render_mode is None:
            gym.logger.warn("render() needs a render_mode, e.g. gym.make_vec(id, 2, render_mode='rgb_array')")
            return None
        return tuple(env.render() for env in self.envs)

    def close_extras(self, **kwargs: Any) -> None:
        for env in self.envs:
            env.close()

    # --- the same for some games (SB3's indices) -------------------------------------------------------------
    def call_games(
        self,
        name: str,
        args: Sequence[Any] = (),
        kwargs: Mapping[str, Any] | None = None,
        indices: Sequence[int] | None = None,
    ) -> list[Any]:
        """Attribute ``name`` of the games ``indices`` (default: all), called with the arguments if callable."""
        results = []
        for index in _indices(indices, self.num_envs):
            attribute = getattr(self.envs[index], name)
            results.append(attribute(*args, **(kwargs or {})) if callable(attribute) else attribute)
        return results

    def get_attr_games(self, name: str, indices: Sequence[int] | None = None) -> list[Any]:
        return [getattr(self.envs[index], name) for index in _indices(indices, self.num_envs)]

    def set_attr_games(self, name: str, values: Any, indices: Sequence[int] | None = None) -> None:
        """Set ``name`` on the games ``indices``: one value for all of them, or a list / tuple of one per game."""
        chosen = _indices(indices, self.num_envs)
        for index, value in zip(chosen, _values_for(values, len(chosen)), strict=True):
            setattr(self.envs[index], name, value)

    # --- the batch's core (shared with the workers of ShardedHFOVectorEnv and with sb3_hfo's adapter) -----------
    def reset_games(
        self,
        *,
        seed: int | Sequence[int | None] | None = None,
        options: Mapping[str, Any] | None = None,
        per_game_options: Sequence[Mapping[str, Any] | None] | None = None,
    ) -> list[dict[str, Any]]:
        """Reset the games into the observation buffer; returns each game's reset info ({} for a masked-out one).
        ``per_game_options`` (one reset options dict or None per game, SB3's ``set_options``) replaces
        ``options``' placements."""
        seeds = _game_seeds(seed, self.num_envs)
        mask, game_options = _reset_mask(options, self.num_envs)
        every_options = _per_game_options(per_game_options, game_options, self.num_envs)
        for checked in every_options:
            if checked is not None:  # a bad option fails before any game resets
                self.envs[0]._parse_reset_options(checked)
        if mask is not None and self._needs_reset and not mask.all():
            raise RuntimeError("the first reset() must reset every game (no reset_mask, or one of all True)")
        infos: list[dict[str, Any]] = []
        observations = self._observations
        for index, reset in enumerate(self._game_resets):
            if mask is not None and not mask[index]:
                infos.append({})
                continue
            observations[index], info = reset(seed=seeds[index], options=every_options[index])
            self._ended[index] = False
            infos.append(info)
        self._rewards[:] = 0.0
        self._terminations[:] = False
        self._truncations[:] = False
        self._needs_reset = False
        return infos

    def step_games(self, actions: Any) -> list[dict[str, Any]]:
        """Validate every game's action, then step the games into the buffers (observations, rewards,
        terminations, truncations); returns each game's info (for SAME_STEP an ended game's info is its reset
        info with ``final_obs`` and ``final_info``)."""
        if self._needs_reset:
            raise RuntimeError("call reset() before step()")
        rows = self._game_actions(actions)
        # The hot loop gathers plain Python lists and fills the numpy buffers once per batch (cheaper than an item
        # assignment per game); the rare episode ends take the branch.
        same_step = self.autoreset_mode is AutoresetMode.SAME_STEP
        ended = self._ended
        resets = self._game_resets
        any_ended = ended.any()
        observation_list: list[np.ndarray] = []
        rewards: list[float] = []
        ends: list[tuple[int, bool, bool]] = []
        infos: list[dict[str, Any]] = []
        for index, (step, action) in enumerate(zip(self._game_steps, rows, strict=False)):
            if any_ended and ended[index]:  # NEXT_STEP: this step resets the game; its action is ignored
                observation, info = resets[index]()
                reward, terminated, truncated = 0.0, False, False
                ended[index] = False
            else:
                observation, reward, terminated, truncated, info = step(action)
                if terminated or truncated:
                    if same_step:
                        final_observation = observation
                        observation, reset_info = resets[index]()
                        # (SyncVectorEnv's order of the keys, which the vector info's key order follows)
                        info = {"final_obs": final_observation, "final_info": info, **reset_info}
                    else:
                        ended[index] = True
            observation_list.append(observation)
            rewards.append(reward)
            if terminated or truncated:  # (rare: the flags are cleared below and these set afterwards)
                ends.append((index, terminated, truncated))
            infos.append(info)
        np.concatenate(observation_list, out=self._flat_observations)
        self._rewards[:] = rewards
        self._terminations.fill(False)
        self._truncations.fill(False)
        for index, terminated, truncated in ends:
            self._terminations[index] = terminated
            self._truncations[index] = truncated
        return infos

    def _game_actions(self, actions: Any) -> Any:
        return checked_actions(actions, self.envs, self._action_shape)

    def __repr__(self) -> str:
        return f"HFOVectorEnv({self.env_id or self.env_kwargs!r}, num_envs={self.num_envs})"


# -----------------------------------------------------------------------------------------------------------------
# Sharded over worker processes
# -----------------------------------------------------------------------------------------------------------------
def split_games(num_envs: int, num_workers: int) -> list[range]:
    """The games of each worker: contiguous blocks, the first ``num_envs % num_workers`` one game larger."""
    base, extra = divmod(num_envs, num_workers)
    blocks: list[range] = []
    start = 0
    for worker in range(num_workers):
        size = base + (worker < extra)
        blocks.append(range(start, start + size))
        start += size
    return blocks


def _shared_array(context: Any, shape: tuple[int, ...], dtype: Any) -> tuple[Any, np.ndarray]:
    raw = context.RawArray("b", max(1, int(np.prod(shape)) * np.dtype(dtype).itemsize))
    return raw, np.frombuffer(raw, dtype=dtype, count=int(np.prod(shape))).reshape(shape)


def _unpickled(answer: Any) -> Any:
    """A shard's answer: a worker's is pickled (a memoryview), the parent's own shard's is not."""
    return pickle.loads(answer) if isinstance(answer, memoryview) else answer


def _handle(batch: HFOVectorEnv, actions: np.ndarray | None, command: str, data: Any) -> Any:
    """One command of the parent to a shard (a worker's batch, or the parent's own shard)."""
    if command == "step":
        return batch.step_games(actions if data is None else data)
    if command == "reset":
        return batch.reset_games(**data)
    if command == "call":
        return batch.call_games(*data)
    if command == "get_attr":
        return batch.get_attr_games(*data)
    if command == "set_attr":
        return batch.set_attr_games(*data)
    if command == "render":
        return tuple(env.render() for env in batch.envs)
    raise ValueError(f"unknown command {command!r}")


def _shard_views(
    buffers: Mapping[str, tuple[Any, tuple[int, ...], str]], start: int, stop: int
) -> dict[str, np.ndarray]:
    """Rows ``start:stop`` of each shared array."""
    return {
        name: np.frombuffer(raw, dtype=dtype, count=int(np.prod(shape))).reshape(shape)[start:stop]
        for name, (raw, shape, dtype) in buffers.items()
    }


def _shard_batch(
    block: tuple[int, int], autoreset_mode: str, env_kwargs: Mapping[str, Any], buffers: Mapping[str, Any]
) -> tuple[HFOVectorEnv, np.ndarray | None]:
    """The batch of games ``block`` whose buffers are its rows of the shared arrays, and its rows of the actions."""
    start, stop = block
    batch = HFOVectorEnv(stop - start, autoreset_mode=autoreset_mode, **env_kwargs)
    views = _shard_views({name: buffers[name] for name in buffers if name not in _COUNTERS}, start, stop)
    batch._observations = views["observations"]
    batch._flat_observations = batch._observations.reshape(-1)  # (a view of the contiguous rows)
    batch._rewards = views["rewards"]
    batch._terminations = views["terminations"]
    batch._truncations = views["truncations"]
    return batch, views.get("actions")


# A worker's answer: one byte saying whether the command succeeded, then the pickled result (or exception), so that
# the parent can check every answer at once and unpickle a step's infos only when they are read.
_ANSWERED, _RAISED = b"a", b"r"


#: The shared counters of the hand-over (not game rows).
_COUNTERS = ("sent", "answered")
#: How long a side spins on a counter before it blocks on the pipe: longer than a policy's forward pass between two
#: steps, short enough that an idle worker (e.g. during a PPO update) soon stops burning its core.
_SPIN_SECONDS = 0.002


def _available_cpus() -> int:
    """The CPUs this process may run on (its affinity where the OS tells, else the machine's count)."""
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        return os.cpu_count() or 1


def _spin_until_changed(counter: np.ndarray, index: int, seen: int, seconds: float) -> bool:
    """Whether ``counter[index]`` moved away from ``seen`` within ``seconds`` of spinning."""
    if counter[index] != seen:
        return True
    deadline = time.perf_counter() + seconds
    while time.perf_counter() < deadline:
        if counter[index] != seen:
            return True
    return False


def _worker(
    connection: multiprocessing.connection.Connection,
    block: tuple[int, int],
    autoreset_mode: str,
    env_kwargs: dict[str, Any],
    buffers: dict[str, tuple[Any, tuple[int, ...], str]],
    shard: int = 0,
    spin_seconds: float = 0.0,
) -> None:
    """One worker: a :class:`HFOVectorEnv` of games ``block`` (start, stop) whose buffers are its rows of the
    shared arrays.

    It leaves when the parent says "close", when the parent process dies (multiprocessing's parent sentinel) or
    when the pipe breaks (nobody else holds the parent's end: the workers are started by spawn / forkserver, not
    fork)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the parent's to handle; it then closes us
    parent = multiprocessing.parent_process()
    try:
        batch, actions = _shard_batch(block, autoreset_mode, env_kwargs, buffers)
        connection.send(("ready", None))
    except Exception:
        connection.send(("error", traceback.format_exc()))
        return
    sent, answered = (
        np.frombuffer(buffers[name][0], dtype=np.int64, count=int(np.prod(buffers[name][1])))
        for name in _COUNTERS
    )
    seen = 0
    while True:
        # a command: announced by the parent's "sent" count (spinning a moment), else the pipe itself or the
        # parent's death: its sentinel (spawn / forkserver children have one) becomes ready
        if (
            not _spin_until_changed(sent, shard, seen, spin_seconds)
            and parent is not None
            and connection not in multiprocessing.connection.wait([connection, parent.sentinel])
        ):
            return
        try:
            command, data = connection.recv()
        except (EOFError, OSError):
            return
        seen += 1
        try:
            if command == "close":
                batch.close()
                connection.send_bytes(_ANSWERED + pickle.dumps(None))
                answered[shard] = seen
                return
            result = _handle(batch, actions, command, data)
            connection.send_bytes(_ANSWERED + pickle.dumps(result, protocol=pickle.HIGHEST_PROTOCOL))
        except Exception as error:  # sent to the parent, which raises it (the worker stays usable)
            connection.send_bytes(_RAISED + pickle.dumps(error, protocol=pickle.HIGHEST_PROTOCOL))
        answered[shard] = seen  # after the answer is in the pipe


class ShardedHFOVectorEnv(_AllGamesAccess, gym.vector.VectorEnv):
    """The games of :class:`HFOVectorEnv` in ``num_workers`` shards stepped in parallel, one batch per process (one
    per core): by default this process steps the first shard and ``num_workers - 1`` worker processes the others.

    Game i is the same game whatever the sharding: ``reset(seed=s)`` seeds it with ``s + i``, it plays bit for bit
    as in an unsharded batch (and as ``gym.make(id)``), with the same auto-reset and info conventions.
    Observations, rewards, flags and flat actions travel through shared memory; commands and infos through a pipe
    per worker. ``close()`` stops the workers; a worker also stops on its own when its parent process dies.

    Args:
        env_id: an hfo2d id (``"HFO/Keeper-v1"``, ...); the keyword rules of ``gym.make`` apply to ``env_kwargs``.
        num_envs: the number of games.
        num_workers: shards, each a contiguous block of games stepped by one process (at most ``num_envs``).
        autoreset_mode: as for :class:`HFOVectorEnv`.
        start_method: multiprocessing start method, "forkserver" (default where available) or "spawn". Not
            "fork": a forked worker would inherit its siblings' pipe ends and outlive a dead parent.
        in_process_shard: True (default): this process steps the first shard itself while the others step
            theirs (``num_workers - 1`` worker processes; its core would otherwise wait idle, and each step saves a
            round trip); False: every shard in its own worker process (``num_workers`` processes).
        **env_kwargs: :class:`hfo2d.HFOEnv`'s arguments beyond the id's own.
    """

    def __init__(
        self,
        env_id: str,
        num_envs: int,
        num_workers: int = 2,
        autoreset_mode: AutoresetMode | str = AutoresetMode.SAME_STEP,
        start_method: str | None = None,
        in_process_shard: bool = True,
        **env_kwargs: Any,
    ) -> None:
        from hfo2d import ENV_IDS, RegisteredEnvCreator

        if env_id not in ENV_IDS:
            raise ValueError(f"unknown hfo2d id {env_id!r}; choose one of {tuple(ENV_IDS)}")
        self.num_envs = _check_num_envs(num_envs)
        if isinstance(num_workers, bool) or not isinstance(num_workers, (int, np.integer)) or num_workers < 1:
            raise ValueError(f"num_workers must be a positive integer, got {num_workers!r}")
        if num_workers > self.num_envs:
            raise ValueError(f"num_workers ({num_workers}) must not exceed num_envs ({self.num_envs})")
        if start_method is None:
            start_method = (
                "forkserver" if "forkserver" in multiprocessing.get_all_start_methods() else "spawn"
            )
        if start_method not in ("forkserver", "spawn"):
            raise ValueError(f"start_method must be 'forkserver' or 'spawn', got {start_method!r}")
        self.autoreset_mode = _autoreset_mode(autoreset_mode)
        self.env_id = env_id
        creator = RegisteredEnvCreator(env_id)
        self.env_kwargs = creator.game_kwargs(**env_kwargs)  # the id's own kwargs, checked as gym.make does
        # spaces, argument errors and the parent's checks of actions and reset options, before any process starts
        probe = self._probe = HFOEnv(**self.env_kwargs)
        self.render_mode = probe.render_mode
        self.metadata = {**HFOEnv.metadata, "autoreset_mode": self.autoreset_mode}
        self.single_observation_space = probe.observation_space
        self.single_action_space = probe.action_space
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self._flat = probe.action_format == "flat"
        self._action_shape = (self.num_envs, *self.single_action_space.shape) if self._flat else None
        # the parent's action check parses with the probe (parsing reads only the action format)
        self._checker_envs = (probe,) * self.num_envs
        self.num_workers = int(num_workers)
        self.blocks = split_games(self.num_envs, self.num_workers)
        self.closed = False
        self._processes: list[Any] = []
        # one per shard (block); None for the shard this process steps itself
        self._connections: list[multiprocessing.connection.Connection | None] = []
        self._local: HFOVectorEnv | None = None
        self._local_actions: np.ndarray | None = None

        n = self.num_envs
        context = multiprocessing.get_context(start_method)
        shapes: dict[str, tuple[tuple[int, ...], Any]] = {
            "observations": ((n, *self.single_observation_space.shape), np.float32),
            "rewards": ((n,), np.float64),
            "terminations": ((n,), np.bool_),
            "truncations": ((n,), np.bool_),
        }
        if self._flat:
            shapes["actions"] = ((n, *self.single_action_space.shape), np.float32)
        # Per shard: how many commands the parent has sent and how many the shard has answered. A worker that sees
        # its "sent" count move reads the command from its pipe at once, and the parent that sees the "answered"
        # count move reads the answer: the data is already in the pipe, so neither side sleeps in a system call
        # that another CPU must wake it from (on this project's Firecracker VM such a wake-up cost ~400 µs per
        # step, most of a 16-game batch step). Each side spins only briefly, then blocks on the pipe as before.
        shapes["sent"] = ((self.num_workers,), np.int64)
        shapes["answered"] = ((self.num_workers,), np.int64)
        raws = {name: _shared_array(context, shape, dtype) for name, (shape, dtype) in shapes.items()}
        self._sent = raws["sent"][1]
        self._answered = raws["answered"][1]
        # Spinning pays only while every process that steps games has a core of its own; with more processes than
        # cores a spinning one would hold a core that another needs, so then both sides block on the pipes.
        processes = self.num_workers + (0 if in_process_shard else 1)
        self._spin_seconds = _SPIN_SECONDS if processes <= _available_cpus() else 0.0
        self._observations = raws["observations"][1]
        self._rewards = raws["rewards"][1]
        self._terminations = raws["terminations"][1]
        self._truncations = raws["truncations"][1]
        self._actions = raws["actions"][1] if self._flat else None
        try:
            buffers = {
                name: (raws[name][0], shape, np.dtype(dtype).str) for name, (shape, dtype) in shapes.items()
            }
            for shard, block in enumerate(self.blocks):
                if shard == 0 and in_process_shard:
                    self._local, self._local_actions = _shard_batch(
                        (block.start, block.stop), self.autoreset_mode.value, self.env_kwargs, buffers
                    )
                    self._connections.append(None)
                    continue
                parent_end, child_end = context.Pipe()
                process = context.Process(
                    target=_worker,
                    args=(
                        child_end,
                        (block.start, block.stop),
                        self.autoreset_mode.value,
                        self.env_kwargs,
                        buffers,
                        shard,
                        self._spin_seconds,
                    ),
                    daemon=True,
                    name=f"hfo2d-vector-{block.start}-{block.stop - 1}",
                )
                process.start()
                child_end.close()
                self._processes.append(process)
                self._connections.append(parent_end)
            for connection in self._connections:
                if connection is None:
                    continue
                try:
                    status, message = connection.recv()
                except EOFError:
                    status, message = "error", "it exited while starting (its traceback is on stderr)"
                if status != "ready":
                    raise RuntimeError(f"an hfo2d worker failed to start:\n{message}")
        except BaseException:
            self.close()
            raise
        self._needs_reset = True

    # --- Gymnasium API ---------------------------------------------------------------------------------------
    def reset(
        self, *, seed: int | Sequence[int | None] | None = None, options: Mapping[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        """As :meth:`HFOVectorEnv.reset` (game i seeded with ``seed + i`` whatever worker holds it)."""
        infos = self.reset_games(seed=seed, options=options)
        return self._observations.copy(), VectorInfo(infos)

    def step(self, actions: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]:
        """As :meth:`HFOVectorEnv.step`; the workers' infos are unpickled only when the info dict is read."""
        answers = self.step_games(actions, pickled=True)
        return (
            self._observations.copy(),
            self._rewards.copy(),
            self._terminations.copy(),
            self._truncations.copy(),
            VectorInfo(lambda: [info for answer in answers for info in _unpickled(answer)]),
        )

    def render(self) -> tuple[np.ndarray | None, ...] | None:
        if self.render_mode is None:
            gym.logger.warn(
                "render() needs a render_mode, e.g. ShardedHFOVectorEnv(id, 2, render_mode='rgb_array')"
            )
            return None
        return tuple(frame for part in self._broadcast("render", None) for frame in part)

    def call_games(
        self,
        name: str,
        args: Sequence[Any] = (),
        kwargs: Mapping[str, Any] | None = None,
        indices: Sequence[int] | None = None,
    ) -> list[Any]:
        """As :meth:`HFOVectorEnv.call_games` (the results must pickle: they come back through the pipes)."""
        return self._per_block(
            indices, lambda local, _: ("call", (name, tuple(args), dict(kwargs or {}), local))
        )

    def get_attr_games(self, name: str, indices: Sequence[int] | None = None) -> list[Any]:
        return self._per_block(indices, lambda local, _: ("get_attr", (name, local)))

    def set_attr_games(self, name: str, values: Any, indices: Sequence[int] | None = None) -> None:
        chosen = _indices(indices, self.num_envs)
        by_game = dict(zip(chosen, _values_for(values, len(chosen)), strict=True))
        self._per_block(
            chosen,
            lambda local, block: ("set_attr", (name, [by_game[block.start + i] for i in local], local)),
        )

    def _per_block(
        self, indices: Sequence[int] | None, message: Callable[[list[int], range], tuple]
    ) -> list[Any]:
        """Send each worker holding some of the games ``indices`` its command (made by ``message`` from the games'
        indices within the worker); returns the results in the order of ``indices``."""
        chosen = _indices(indices, self.num_envs)
        workers, payloads, locals_ = [], [], []
        for worker, block in enumerate(self.blocks):
            local = [index - block.start for index in chosen if index in block]
            if local:
                workers.append(worker)
                locals_.append((block, local))
                payloads.append(message(local, block))
        parts = self._exchange(workers, payloads)
        by_game = {}
        for (block, local), part in zip(locals_, parts, strict=True):
            if part is not None:
                by_game.update({block.start + i: value for i, value in zip(local, part, strict=True)})
        return [by_game.get(index) for index in chosen]

    def close_extras(self, **kwargs: Any) -> None:
        if self._local is not None:
            self._local.close()
        remote = [connection for connection in self._connections if connection is not None]
        for connection in remote:
            with contextlib.suppress(BrokenPipeError, OSError):
                connection.send(("close", None))
        for process, connection in zip(self._processes, remote, strict=False):
            with contextlib.suppress(EOFError, OSError):
                if connection.poll(5.0):
                    connection.recv_bytes()
            process.join(timeout=5.0)
            if process.is_alive():
                process.terminate()
                process.join(timeout=5.0)
            connection.close()
        self._processes = []
        self._connections = []

    def __del__(self) -> None:
        if not getattr(self, "closed", True):
            with contextlib.suppress(Exception):
                self.close()

    # --- the batch's core --------------------------------------------------------------------------------------
    def reset_games(
        self,
        *,
        seed: int | Sequence[int | None] | None = None,
        options: Mapping[str, Any] | None = None,
        per_game_options: Sequence[Mapping[str, Any] | None] | None = None,
    ) -> list[dict[str, Any]]:
        """As :meth:`HFOVectorEnv.reset_games`."""
        seeds = _game_seeds(seed, self.num_envs)
        mask, game_options = _reset_mask(options, self.num_envs)
        every_options = _per_game_options(per_game_options, game_options, self.num_envs)
        for checked in every_options:
            if checked is not None:  # a bad option fails before any game resets
                self._probe._parse_reset_options(checked)
        if mask is not None and self._needs_reset and not mask.all():
            raise RuntimeError("the first reset() must reset every game (no reset_mask, or one of all True)")
        payloads = []
        for block in self.blocks:
            block_options = game_options
            if mask is not None:
                block_options = {**(game_options or {}), "reset_mask": mask[block.start : block.stop]}
            payloads.append(
                {
                    "seed": seeds[block.start : block.stop],
                    "options": block_options,
                    "per_game_options": None
                    if per_game_options is None
                    else every_options[block.start : block.stop],
                }
            )
        infos = [info for part in self._scatter("reset", payloads) for info in part]
        self._needs_reset = False
        return infos

    def step_games(self, actions: Any, pickled: bool = False) -> list[Any]:
        """As :meth:`HFOVectorEnv.step_games`; with ``pickled`` the infos come as each worker's pickled list."""
        if self._needs_reset:
            raise RuntimeError("call reset() before step()")
        # every game's action is checked here, before any worker moves (the workers check their own rows again)
        rows = checked_actions(actions, self._checker_envs, self._action_shape)
        if rows is actions and type(actions) is np.ndarray and actions.dtype == np.float32:
            self._actions[:] = actions  # the workers read their rows from the shared memory
            payloads: list[Any] = [None] * self.num_workers
        elif self._flat:  # other dtypes, lists: each game's row exactly as given, through the pipes
            rows = list(rows)
            payloads = [rows[block.start : block.stop] for block in self.blocks]
        else:  # parameterized: each worker's slice of the four parts
            payloads = [tuple(part[block.start : block.stop] for part in actions) for block in self.blocks]
        answers = self._scatter("step", payloads, pickled=pickled)
        return answers if pickled else [info for part in answers for info in part]

    def _scatter(self, command: str, payloads: Sequence[Any], pickled: bool = False) -> list[Any]:
        """``command`` to every worker, each with its payload; the workers' results in order."""
        return self._exchange(range(self.num_workers), [(command, payload) for payload in payloads], pickled)

    def _exchange(
        self, shards: Sequence[int], messages: Sequence[tuple[str, Any]], pickled: bool = False
    ) -> list[Any]:
        """Send each of ``shards`` its (command, payload) (the workers first, so that they work while this process
        runs its own shard), then collect the results (a worker's still pickled, as a memoryview, with
        ``pickled``); an exception is raised here once every shard has answered (so that the pipes stay in step)."""
        if self.closed:
            raise RuntimeError("the ShardedHFOVectorEnv is closed")
        connections = self._connections
        for shard, message in zip(shards, messages, strict=True):
            if connections[shard] is not None:
                connections[shard].send(message)
                self._sent[shard] += (
                    1  # after the message is in the pipe (the worker reads it on seeing this)
                )
        answers: list[Any] = []
        error: BaseException | None = None
        for shard, message in zip(shards, messages, strict=True):
            connection = connections[shard]
            if connection is None:
                try:
                    answers.append(_handle(self._local, self._local_actions, *message))
                except Exception as raised:
                    error = error or raised
                    answers.append(None)
                continue
            try:
                # its answer is in the pipe once "answered" reaches "sent" (spinning a moment), else block on it
                _spin_until_changed(self._answered, shard, self._sent[shard] - 1, self._spin_seconds)
                answer = connection.recv_bytes()
            except (EOFError, OSError) as broken:
                raise RuntimeError("an hfo2d worker died; close() this env and make a new one") from broken
            if answer[:1] == _RAISED:
                error = error or pickle.loads(memoryview(answer)[1:])
            answers.append(memoryview(answer)[1:])
        if error is not None:
            raise error
        if pickled:
            return answers
        return [pickle.loads(answer) if isinstance(answer, memoryview) else answer for answer in answers]

    def _broadcast(self, command: str, payload: Any) -> list[Any]:
        return self._scatter(command, [payload] * self.num_workers)

    def __repr__(self) -> str:
        return (
            f"ShardedHFOVectorEnv({self.env_id!r}, num_envs={self.num_envs}, num_workers={self.num_workers})"
        )
