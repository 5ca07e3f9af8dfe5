"""hfo2d: a fast 2D RoboCup Half Field Offense simulator with Gymnasium environments.

Importing the package registers these environments (no TimeLimit wrapper; episodes end by HFO's own rules):

* ``HFO/EmptyGoal-v0``: one striker, empty goal (58 features);
* ``HFO/StaticKeeper-v0``: a goalie that stands on the goal line (66 features);
* ``HFO/Keeper-v0``: hfo2d's own scripted goalie (66 features; ``keeper_skill`` in [0, 1]);
* ``HFO/Keeper-v1``: HFO's own goalie, agent2d's, as HFO runs it (66 features; ``keeper_skill`` in [0, 1]);
* ``HFO/RealEmptyGoal-v0``, ``HFO/RealKeeper-v0``: the same tasks in the real HFO (agent2d's goalie), through a
  local HFO build (``hfo2d.real.RealHFOEnv``; ``hfo_dir`` or ``$HFO_DIR``; nothing of it is imported until made).

Only numpy, gymnasium and pymunk are imported here; pygame is imported when rendering starts.
"""

from __future__ import annotations

import gymnasium

from hfo2d.heuristic import heuristic
from hfo2d.hfo_env import HFOEnv
from hfo2d.physics import ServerParams, World

__all__ = ["ENV_IDS", "HFOEnv", "ServerParams", "World", "heuristic"]

ENV_ENTRY_POINT = "hfo2d.hfo_env:HFOEnv"
ENV_IDS: dict[str, str] = {
    "HFO/EmptyGoal-v0": "empty_goal",
    "HFO/StaticKeeper-v0": "static_keeper",
    "HFO/Keeper-v0": "keeper",
    "HFO/Keeper-v1": "keeper",
}

# A re-import (importlib.reload, a second interpreter path) must not warn about re-registration.
#: Keyword arguments of each registered id beyond its task.
ENV_EXTRA_KWARGS: dict[str, dict[str, str]] = {"HFO/Keeper-v1": {"goalie": "agent2d"}}

for _env_id, _task in ENV_IDS.items():
    if _env_id not in gymnasium.registry:
        gymnasium.register(
            id=_env_id, entry_point=ENV_ENTRY_POINT, kwargs={"task": _task, **ENV_EXTRA_KWARGS.get(_env_id, {})}
        )

#: The real-HFO backend's ids (hfo2d.real, imported only when one is made; needs a local HFO build).
REAL_ENV_ENTRY_POINT = "hfo2d.real:RealHFOEnv"
REAL_ENV_IDS: dict[str, str] = {"HFO/RealEmptyGoal-v0": "empty_goal", "HFO/RealKeeper-v0": "keeper"}
for _env_id, _task in REAL_ENV_IDS.items():
    if _env_id not in gymnasium.registry:
        gymnasium.register(id=_env_id, entry_point=REAL_ENV_ENTRY_POINT, kwargs={"task": _task})
