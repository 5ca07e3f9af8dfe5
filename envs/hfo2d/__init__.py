"""hfo2d: a fast 2D RoboCup Half Field Offense simulator with Gymnasium environments.

Importing the package registers these environments (no TimeLimit wrapper; episodes end by HFO's own rules); the
simulator's four also batch N games in one process with ``gym.make_vec(id, N,
vectorization_mode="vector_entry_point")`` (:mod:`hfo2d.vector`, which also shards a batch over processes):

* ``HFO/EmptyGoal-v0``: one striker, empty goal (58 features);
* ``HFO/StaticKeeper-v0``: a goalie that stands on the goal line (66 features);
* ``HFO/Keeper-v0``: hfo2d's own scripted goalie (66 features; ``keeper_skill`` in [0, 1]);
* ``HFO/Keeper-v1``: HFO's own goalie, agent2d's, as HFO runs it (66 features; ``keeper_skill`` in [0, 1]);
* ``HFO/RealEmptyGoal-v0``, ``HFO/RealKeeper-v0``: the same tasks in the real HFO (agent2d's goalie), through a
  local HFO build (``hfo2d.real.RealHFOEnv``; ``hfo_dir`` or ``$HFO_DIR``; nothing of it is imported until made).
* ``HFO/RealStaticKeeper-v0``: the real HFO against a goalie that stands still on the goal line facing the field
  (a defense agent of ``hfo2d.real``, as ``HFO/StaticKeeper-v0``'s keeper).
* ``HFO/HalfFieldOffense-v0``: bin/HFO's team sizes (``offense_agents``, ``defense_agents``, ``defense_npcs``
  keywords), one learning agent (:class:`hfo2d.team.HalfFieldOffenseEnv`); :func:`parallel_env` makes every agent
  of such a game a PettingZoo ParallelEnv (PettingZoo is imported only then).

Only numpy, gymnasium and pymunk are imported here; pygame is imported when rendering starts. The optional C
extension ``hfo2d._accel`` (built at ``pip install`` where a C compiler is found) runs the hottest code with the
same floats; without it, or with ``HFO2D_PURE_PYTHON=1``, the pure-Python reference runs (:mod:`hfo2d.accel`).
"""

from __future__ import annotations

from typing import Any

import gymnasium

from hfo2d.heuristic import heuristic
from hfo2d.hfo_env import HFOEnv
from hfo2d.physics import ServerParams, World

__all__ = [
    "ENV_IDS",
    "HFOEnv",
    "RegisteredEnvCreator",
    "RegisteredVectorEnvCreator",
    "ServerParams",
    "World",
    "heuristic",
    "parallel_env",
]

ENV_IDS: dict[str, str] = {
    "HFO/EmptyGoal-v0": "empty_goal",
    "HFO/StaticKeeper-v0": "static_keeper",
    "HFO/Keeper-v0": "keeper",
    "HFO/Keeper-v1": "keeper",
}

#: Keyword arguments of each registered id beyond its task.
ENV_EXTRA_KWARGS: dict[str, dict[str, str]] = {"HFO/Keeper-v1": {"goalie": "agent2d"}}


def _defining_kwargs(env_id: str) -> dict[str, str]:
    """The kwargs that make ``env_id`` what it is: its task and, for task "keeper", its goalie."""
    return _defining(ENV_IDS[env_id], ENV_EXTRA_KWARGS.get(env_id, {}).get("goalie", "hfo2d"))


def _defining(task: Any, goalie: Any) -> dict[str, Any]:
    return {"task": task, "goalie": goalie} if task == "keeper" else {"task": task}


class RegisteredEnvCreator:
    """What ``gym.make`` calls for a registered HFO id: an :class:`HFOEnv` with the id's own task (and goalie).

    A kwarg that would turn the id into another environment (``gym.make("HFO/EmptyGoal-v0", task="keeper")``)
    is a ValueError naming the id to use instead; every other kwarg goes to :class:`HFOEnv` as given.
    """

    metadata = HFOEnv.metadata  # gym.make checks render_mode against it

    def __init__(self, env_id: str) -> None:
        self.env_id = env_id
        self.fixed = _defining_kwargs(env_id)

    def __call__(self, **kwargs: Any) -> HFOEnv:
        return HFOEnv(**self.game_kwargs(**kwargs))

    def game_kwargs(self, **kwargs: Any) -> dict[str, Any]:
        """:class:`HFOEnv`'s kwargs for this id: ``kwargs`` with the id's own (task, goalie); a kwarg that would
        make another environment is a ValueError."""
        for key, value in self.fixed.items():
            given = kwargs.get(key, value)
            if given != value:
                wanted = _defining(kwargs.get("task", self.fixed["task"]), kwargs.get("goalie", "hfo2d"))
                others = [other for other in ENV_IDS if _defining_kwargs(other) == wanted]
                instead = f"make {others[0]}" if others else f"use hfo2d.HFOEnv({key}={given!r}, ...)"
                raise ValueError(
                    f"{self.env_id} is {key}={value!r}; {key}={given!r} would make another environment: {instead}"
                )
        return {**kwargs, **self.fixed}

    def __repr__(self) -> str:
        return f"hfo2d.RegisteredEnvCreator({self.env_id!r})"

    def __reduce__(self) -> tuple[type, tuple[str]]:
        # Pickled by the module's current class, so that an env made before importlib.reload(hfo2d) (whose registry
        # entry keeps this older instance) still pickles: a reload re-runs the module in the same globals.
        return RegisteredEnvCreator, (self.env_id,)


class RegisteredVectorEnvCreator:
    """What ``gym.make_vec(id, num_envs, vectorization_mode="vector_entry_point")`` calls for a registered HFO id:
    an :class:`hfo2d.vector.HFOVectorEnv` of ``num_envs`` games of the id, with :class:`RegisteredEnvCreator`'s
    keyword rules; ``autoreset_mode`` (``AutoresetMode.SAME_STEP``, the default, or ``NEXT_STEP``) goes to the
    batch, every other kwarg to each game's :class:`HFOEnv`.
    """

    def __init__(self, env_id: str) -> None:
        self.env_id = env_id
        self.game_creator = RegisteredEnvCreator(env_id)

    def __call__(self, num_envs: int = 1, autoreset_mode: Any = None, **kwargs: Any) -> Any:
        from hfo2d.vector import HFOVectorEnv

        batch_kwargs = {} if autoreset_mode is None else {"autoreset_mode": autoreset_mode}
        game_kwargs = self.game_creator.game_kwargs(**kwargs)
        return HFOVectorEnv(num_envs, env_id=self.env_id, **batch_kwargs, **game_kwargs)

    def __repr__(self) -> str:
        return f"hfo2d.RegisteredVectorEnvCreator({self.env_id!r})"

    def __reduce__(self) -> tuple[type, tuple[str]]:
        return RegisteredVectorEnvCreator, (self.env_id,)  # as RegisteredEnvCreator.__reduce__


# A re-import (importlib.reload, a second interpreter path) must not warn about re-registration.
for _env_id, _task in ENV_IDS.items():
    if _env_id not in gymnasium.registry:
        gymnasium.register(
            id=_env_id,
            entry_point=RegisteredEnvCreator(_env_id),
            vector_entry_point=RegisteredVectorEnvCreator(_env_id),
            kwargs={"task": _task, **ENV_EXTRA_KWARGS.get(_env_id, {})},
        )

#: The real-HFO backend's ids (hfo2d.real, imported only when one is made; needs a local HFO build).
REAL_ENV_ENTRY_POINT = "hfo2d.real:RealHFOEnv"
REAL_ENV_IDS: dict[str, str] = {
    "HFO/RealEmptyGoal-v0": "empty_goal",
    "HFO/RealStaticKeeper-v0": "static_keeper",
    "HFO/RealKeeper-v0": "keeper",
}
for _env_id, _task in REAL_ENV_IDS.items():
    if _env_id not in gymnasium.registry:
        gymnasium.register(id=_env_id, entry_point=REAL_ENV_ENTRY_POINT, kwargs={"task": _task})

#: HFO's team game, one learning agent (hfo2d.team, imported when made).
TEAM_ENV_ID = "HFO/HalfFieldOffense-v0"
if TEAM_ENV_ID not in gymnasium.registry:
    gymnasium.register(id=TEAM_ENV_ID, entry_point="hfo2d.team:HalfFieldOffenseEnv")

#: The backends of :func:`parallel_env`.
PARALLEL_BACKENDS: tuple[str, ...] = ("hfo2d", "real")


def parallel_env(
    offense_agents: int = 1,
    defense_agents: int = 0,
    defense_npcs: int = 0,
    backend: str = "hfo2d",
    **kwargs: Any,
) -> Any:
    """Every learning agent of an HFO team game as a PettingZoo ``ParallelEnv``, with bin/HFO's team sizes.

    Agents ``"offense_0"``, ..., ``"defense_0"``, ...; spaces, rules and rewards: :mod:`hfo2d.team`.

    Args:
        offense_agents, defense_agents, defense_npcs: bin/HFO's ``--offense-agents``, ``--defense-agents``,
            ``--defense-npcs``.
        backend: ``"hfo2d"`` (this simulator, :class:`hfo2d.team_parallel.HFOTeamParallelEnv`) or ``"real"`` (a
            real HFO build, ``hfo2d.real_teams.RealTeamParallelEnv``; ``hfo_dir`` or ``$HFO_DIR``).
        **kwargs: the backend's other arguments (e.g. ``render_mode``, ``feature_set``, ``agent_play_goalie``).

    Raises:
        ValueError: an unknown backend, or team sizes bin/HFO rejects.
        ImportError: PettingZoo is not installed (the ``[teams]`` extra: ``pip install -e ".[teams]"``), or the backend's module is
            missing.
    """
    if backend == "hfo2d":
        from hfo2d.team_parallel import HFOTeamParallelEnv

        return HFOTeamParallelEnv(offense_agents, defense_agents, defense_npcs, **kwargs)
    if backend == "real":
        try:
            from hfo2d.real_teams import RealTeamParallelEnv
        except ModuleNotFoundError as error:
            if error.name != "hfo2d.real_teams":
                raise
            raise ImportError(
                "backend='real' needs hfo2d.real_teams, which this hfo2d does not have yet"
            ) from None
        return RealTeamParallelEnv(
            offense_agents=offense_agents, defense_agents=defense_agents, defense_npcs=defense_npcs, **kwargs
        )
    raise ValueError(f"unknown backend {backend!r}; choose one of {PARALLEL_BACKENDS}")
