"""hfo2d: a fast 2D RoboCup Half Field Offense simulator with Gymnasium environments.

Importing the package registers three environments (no TimeLimit wrapper; episodes end by HFO's own rules):

* ``HFO/EmptyGoal-v0``: one striker, empty goal (58 features);
* ``HFO/StaticKeeper-v0``: a goalie that stands on the goal line (66 features);
* ``HFO/Keeper-v0``: a scripted goalie (66 features; ``keeper_skill`` in [0, 1]).

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
}

# A re-import (importlib.reload, a second interpreter path) must not warn about re-registration.
for _env_id, _task in ENV_IDS.items():
    if _env_id not in gymnasium.registry:
        gymnasium.register(id=_env_id, entry_point=ENV_ENTRY_POINT, kwargs={"task": _task})
