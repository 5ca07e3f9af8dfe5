"""HybridPPO: PPO over parameterised (discrete + continuous) actions, with the seed paper's skills as an option."""

from sb3_hfo.hybrid_ppo.distributions import HybridDistribution
from sb3_hfo.hybrid_ppo.hybrid_ppo import HybridPPO
from sb3_hfo.hybrid_ppo.layout import ActionAdapter
from sb3_hfo.hybrid_ppo.policies import HybridActorCriticPolicy

__all__ = ["ActionAdapter", "HybridActorCriticPolicy", "HybridDistribution", "HybridPPO"]
