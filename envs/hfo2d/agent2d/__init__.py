"""HFO's own defence NPCs (agent2d's "base" team, as HFO runs it) written for the hfo2d simulator.

:class:`~hfo2d.agent2d.goalie.Agent2dGoalie` is the goalie of ``HFO/Keeper-v1``;
:class:`~hfo2d.agent2d.defender.Agent2dDefender` is one of the field defenders HFO adds after the goalie
(``--defense-npcs 2`` and more). The modules follow the programs they reproduce: :mod:`~hfo2d.agent2d.decision`
(HFO's goalie behaviours), :mod:`~hfo2d.agent2d.defender` (the field players' behaviours),
:mod:`~hfo2d.agent2d.formation` (librcsc's Delaunay-triangulation formation over HFO's formation data,
:mod:`~hfo2d.agent2d.formation_data`), :mod:`~hfo2d.agent2d.intercept` (librcsc's intercept table),
:mod:`~hfo2d.agent2d.actions` (librcsc's body actions and client conversions), :mod:`~hfo2d.agent2d.tackle`
(agent2d's tackle), over the vocabulary of :mod:`~hfo2d.agent2d.common`.

The server's parameters reach every module as librcsc's ``server_param`` message reaches the client: the modules
read them from module constants, which :func:`~hfo2d.agent2d.common.bind_server_params` sets from the
:class:`~hfo2d.physics.ServerParams` of the world the players play in (each player binds its own before each
decision; rcssserver 15.2.2's defaults at import).
"""
