"""HFO's own goalie (agent2d's "base" team goalie, as HFO runs it) written for the hfo2d simulator.

:class:`~hfo2d.agent2d.goalie.Agent2dGoalie` is the goalie of ``HFO/Keeper-v1``. The modules follow the programs
they reproduce: :mod:`~hfo2d.agent2d.decision` (HFO's goalie behaviours), :mod:`~hfo2d.agent2d.intercept`
(librcsc's intercept table), :mod:`~hfo2d.agent2d.actions` (librcsc's body actions and client conversions),
:mod:`~hfo2d.agent2d.tackle` (agent2d's tackle), over the vocabulary of :mod:`~hfo2d.agent2d.common`.
"""
