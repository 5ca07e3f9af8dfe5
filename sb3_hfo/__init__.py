"""sb3_hfo: Stable-Baselines3 plugin for RoboCup Half Field Offense.

Importing it registers the HFO Gymnasium environments (``HFO/EmptyGoal-v0``, ``HFO/StaticKeeper-v0``,
``HFO/Keeper-v0``, from :mod:`hfo2d`) and exports the SkillDDPG algorithm, its preset SkillPDQN, their policy, the skill routers
and HybridPPO (PPO over hybrid actions, :mod:`sb3_hfo.hybrid_ppo`).
"""

import hfo2d  # noqa: F401  (registers the HFO envs)
from sb3_hfo.common.routers import ROUTERS, FieldHalfRouter, SingleSkillRouter, SkillRouter, make_router
from sb3_hfo.hybrid_ppo import HybridPPO
from sb3_hfo.skill_ddpg import HFOActor, HFOCritic, HFOPolicy, SkillDDPG, SkillPDQN

__version__ = "0.1.0"

__all__ = [
    "ROUTERS",
    "FieldHalfRouter",
    "HFOActor",
    "HFOCritic",
    "HFOPolicy",
    "HybridPPO",
    "SingleSkillRouter",
    "SkillDDPG",
    "SkillPDQN",
    "SkillRouter",
    "__version__",
    "make_router",
]
