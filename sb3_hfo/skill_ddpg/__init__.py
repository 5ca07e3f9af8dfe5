"""SkillDDPG: the seed paper's DDPG with skills, its policy, and SkillPDQN, its preset with the best recipe."""

from sb3_hfo.skill_ddpg.acting import CriticChoice, KickMask, MirrorChoice, parse_acting
from sb3_hfo.skill_ddpg.encoding import ActionEncoder, DirectionFeatures
from sb3_hfo.skill_ddpg.policies import HFOActor, HFOCritic, HFOPolicy
from sb3_hfo.skill_ddpg.skill_ddpg import SkillDDPG
from sb3_hfo.skill_ddpg.skill_pdqn import SkillPDQN

__all__ = [
    "ActionEncoder",
    "CriticChoice",
    "DirectionFeatures",
    "HFOActor",
    "HFOCritic",
    "HFOPolicy",
    "KickMask",
    "MirrorChoice",
    "SkillDDPG",
    "SkillPDQN",
    "parse_acting",
]
