"""The training callbacks' earlier home: the research diary's configs (``research/zoo_configs/``) and rl-zoo3 run
folders made before the CLI moved to :mod:`sb3_hfo.cli` name ``sb3_hfo.zoo.HFOEpisodeStatsCallback`` and so on.

The callbacks are :mod:`sb3_hfo.callbacks`; the rl-zoo3 glue is :mod:`sb3_hfo.cli.zoo`.
"""

from sb3_hfo.callbacks import ActionNoiseDecayCallback, HFOEpisodeStatsCallback, KeeperSkillCurriculumCallback

__all__ = ["ActionNoiseDecayCallback", "HFOEpisodeStatsCallback", "KeeperSkillCurriculumCallback"]
