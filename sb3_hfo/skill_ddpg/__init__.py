"""SkillDDPG: the seed paper's DDPG with skills, and its policy."""

from sb3_hfo.skill_ddpg.policies import HFOActor, HFOCritic, HFOPolicy
from sb3_hfo.skill_ddpg.skill_ddpg import SkillDDPG

__all__ = ["HFOActor", "HFOCritic", "HFOPolicy", "SkillDDPG"]
