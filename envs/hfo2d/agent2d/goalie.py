"""HFO's goalie as a policy of the hfo2d simulator: world model, decision, client conversions.

Each cycle :meth:`Agent2dGoalie.decide` builds the goalie's world model from the true state (HFO's ``--fullstate``:
librcsc overwrites it with the server's exact values), runs the decision tree of :mod:`hfo2d.agent2d.decision`, and
:meth:`Agent2dGoalie.apply` sends the resulting body command through librcsc's client conversions to the server
commands of :class:`hfo2d.physics.World`.

Sources (facts, no code): librcsc d222758 ``rcsc/player/world_model.cpp`` (updateJustBeforeDecision: the
opponent-kickable test and the zeroing of the ball velocity; updateLastKicker), ``self_object.cpp``
(updateAfterSenseBody: the last catch time), ``action_effector.cpp``; HFO b8b2a1d ``src/sample_player.cpp``
(actionImpl: frozen players send nothing), ``src/role_goalie.cpp``.
"""

from __future__ import annotations

import dataclasses
import math
import struct
from collections.abc import Sequence
from operator import itemgetter

import numpy as np

from hfo2d import accel as _accel
from hfo2d.agent2d import common as _common
from hfo2d.agent2d.actions import send_command
from hfo2d.agent2d.common import (
    Command,
    Effector,
    GoalieView,
    angle_of,
    bind_server_params,
    canonical_params,
    norm_deg,
    register_binder,
)
from hfo2d.agent2d.decision import FreeKickState, decide
from hfo2d.agent2d.intercept import build_intercept_table
from hfo2d.physics import BallState, PlayerState, ServerParams, World
from hfo2d.protocol import AGENT2D_FIRST_BODY_DEGS

# librcsc world_model.cpp updatePlayerStateCache: an opponent counts as kickable within
# kickable_area + min(0.25, 0.02 * ball distance from self) + min(0.25, 0.02 * its distance from self).
KICKABLE_OPP_ERROR_MAX = 0.25
KICKABLE_OPP_ERROR_RATE = 0.02


def opponent_may_kick(opp_ball: float, opp_self: float, ball_from_self: float) -> bool:
    """librcsc's kickable-opponent test above: the opponent ``opp_ball`` from the ball and ``opp_self`` from this
    player, the ball ``ball_from_self`` from this player (KICKABLE_AREA as bound to the server parameters)."""
    return opp_ball < KICKABLE_AREA + min(
        KICKABLE_OPP_ERROR_MAX, ball_from_self * KICKABLE_OPP_ERROR_RATE
    ) + min(KICKABLE_OPP_ERROR_MAX, opp_self * KICKABLE_OPP_ERROR_RATE)


# librcsc world_model.cpp updateLastKicker: a player within 2 * ball_speed_max of the ball may have kicked it.
LAST_KICKER_DIST = 6.0
BALL_VEL_CHANGE_SPEED = 0.1
BALL_VEL_CHANGE_ANGLE = 20.0
NEVER_CAUGHT = -1000


def fullstate_value_python(x: float) -> float:
    """A number as the client reads it from a fullstate message: rcssserver 15 (fullstatesender.cpp, protocol
    >= 8; serializerplayerstdv1.cpp serializeFSBegin sets ``precision(6)``) prints positions, velocities, body
    angles (degrees), stamina, effort and recovery unquantised with 6 significant digits (``%g``), and librcsc
    fullstate_sensor.cpp parses them with strtod.

    This is ``float(f"{x:.6g}")`` (formatting rounds the exact value half to even, parsing returns the nearest
    double), computed faster, for the goalie's world model reads 17 numbers a cycle:

    * results are memoised by input (:data:`_FULLSTATE_MEMO`): a resting ball, the stamina model and a goalie
      standing still repeat their numbers from cycle to cycle. Zeros print as themselves ("0", "-0") and are not
      stored, since a dict does not tell 0.0 from -0.0; neither is NaN;
    * for 1e-16 <= |x| < 10000 without strings: with the scale s = 10**(5 - e) of x's decade e (an exact double),
      p = |x| * s lies within 2**-34 of the exact product P. If 100000.001 <= p < 999999, the decade was right
      and no carry to the next one can happen; if moreover p's fraction is more than 1e-6 away from one half,
      P rounds (half to even or not) to the same whole number m as p does. The printed number is m / s, and one
      IEEE division of the exact m by the exact s gives the double nearest to it, as the parser does. Anything
      else (a decade picked wrong at its boundary, a near tie) takes the string route;
    * for 0 < |x| < 1e-16 (the velocity of a goalie standing still decays by 0.4 a cycle through these) the same
      test, with s = 10**(5 - e) > 10**22 no longer a double: p is |x| times the double nearest to s (or, past
      10**308, times 1e22 and the double nearest to s / 10**22), at most three roundings of relative error
      2**-53 each, so p still lies within 2**-30 of P, far inside both margins. The printed number
      m / 10**(5 - e) is then divided in Python integers, which CPython rounds correctly (to the nearest double,
      subnormals included), as the parser does.
    """
    y = _FULLSTATE_MEMO.get(x)
    if y is not None:
        return y
    if x == 0.0:
        return float(x)  # keeps the sign of a zero
    a = -x if x < 0.0 else x
    y = None
    if 1.0e-16 <= a < 10000.0:
        if a >= 1.0:
            s = 100000.0 if a < 10.0 else (10000.0 if a < 100.0 else (1000.0 if a < 1000.0 else 100.0))
        elif a >= 0.001:
            s = 1000000.0 if a >= 0.1 else (10000000.0 if a >= 0.01 else 100000000.0)
        else:
            s = _POW10[5 - math.floor(math.log10(a))]  # 10**9 .. 10**22
        p = a * s
        f = p % 1.0
        if 100000.001 <= p < 999999.0 and not 0.499999 < f < 0.500001:
            y = ((p - f) + 1.0 if f > 0.5 else p - f) / s
            if x < 0.0:
                y = -y
    elif a < 1.0e-16:  # 5e-324 <= a: x is neither zero nor NaN here
        digits = 5 - math.floor(math.log10(a))  # 22 < digits <= 329
        # (10.0**308 is the largest power of ten below the double range)
        p = a * _POW10_NEAREST[digits] if digits <= 308 else a * 1.0e22 * _POW10_NEAREST[digits - 22]
        f = p % 1.0
        if 100000.001 <= p < 999999.0 and not 0.499999 < f < 0.500001:
            m = int(p)  # p - f: p is positive
            y = (m + 1 if f > 0.5 else m) / _POW10_INT[digits]
            # (not memoised: these numbers decay from cycle to cycle and do not come back)
            return -y if x < 0.0 else y
    if y is None:
        y = float(f"{x:.6g}")
    if x == x:
        if len(_FULLSTATE_MEMO) >= _FULLSTATE_MEMO_SIZE:
            _FULLSTATE_MEMO.clear()
        _FULLSTATE_MEMO[x] = y
    return y


_first = itemgetter(0)  # a sort key (in C)

# The bytes of four doubles: Agent2dGoalie._view's key for a group of numbers that repeats from cycle to cycle
# (bitwise, so that -0.0 and 0.0 differ)
_PACK_FOUR = struct.Struct("<4d").pack

_POW10 = tuple(float(10**k) for k in range(23))  # exact doubles
_POW10_INT = tuple(10**k for k in range(330))  # the scales of the numbers below 1e-16, down to 5e-324
_POW10_NEAREST = tuple(float(10**k) for k in range(309))  # the doubles nearest to them (exact up to 10**22)
_FULLSTATE_MEMO: dict[float, float] = {}
_FULLSTATE_MEMO_SIZE = 4096

#: :func:`fullstate_value_python`, computed by hfo2d._accel's kernel when it is in use (the same floats, no memo:
#: the C computes a number faster than the dict finds it; see :mod:`hfo2d.accel`)
fullstate_value = fullstate_value_python if _accel.ACCEL is None else _accel.ACCEL.fullstate_value


MirroredPlayer = tuple[float, float, tuple[float, float, float, float, float, int], PlayerState]


def mirrored_players_python(
    players: Sequence[PlayerState], skip: PlayerState | None, bx: float, by: float, px: float, py: float
) -> list[MirroredPlayer]:
    """Every player but ``skip`` as a right-side client reads it from the fullstate (:func:`fullstate_value`,
    mirrored as librcsc's FullstateSensor::reverse does), in server order: (distance from the ball (bx, by),
    distance from the deciding player (px, py), (x, y, vx, vy, body, remaining tackle freeze), the player). The
    reference of hfo2d._accel's kernel, which :func:`mirrored_players` runs when it is in use."""
    fs = fullstate_value
    hypot = math.hypot
    out: list[MirroredPlayer] = []
    for p in players:
        if p is skip:
            continue
        x = -fs(p.x)
        y = -fs(p.y)
        other = (x, y, -fs(p.vx), -fs(p.vy), norm_deg(fs(p.body_deg) + 180.0), int(p.tackle_cycles))
        out.append((hypot(x - bx, y - by), hypot(x - px, y - py), other, p))
    return out


#: :func:`mirrored_players_python`, computed by hfo2d._accel's kernel when it is in use (the same numbers)
mirrored_players = mirrored_players_python if _accel.ACCEL is None else _accel.ACCEL.mirrored_players


def mirrored_self_python(me: PlayerState, ball: BallState) -> tuple[float, ...]:
    """(px, py, vx, vy, body, stamina, effort, recovery, bx, by, wx, wy): a right-side NPC's own numbers and the
    ball's as its client reads them from the fullstate (mirrored: positions and velocities negated, body
    normalize(body + 180)). The reference of hfo2d._accel's mirrored_self; without the extension the views keep
    their last conversions by the numbers' bits instead (the same numbers)."""
    fs = fullstate_value
    return (
        -fs(me.x),
        -fs(me.y),
        -fs(me.vx),
        -fs(me.vy),
        norm_deg(fs(me.body_deg) + 180.0),
        fs(me.stamina),
        fs(me.effort),
        fs(me.recovery),
        -fs(ball.x),
        -fs(ball.y),
        -fs(ball.vx),
        -fs(ball.vy),
    )


#: hfo2d._accel's mirrored_self and fullstate_value, or None for the pure-Python code
_ACCEL_MIRRORED_SELF = None if _accel.ACCEL is None else _accel.ACCEL.mirrored_self
_ACCEL_FULLSTATE_VALUE = None if _accel.ACCEL is None else _accel.ACCEL.fullstate_value

# Agent2dGoalie._view builds its GoalieView positionally, in this field order
_VIEW_FIELDS = (
    "cycle",
    "px",
    "py",
    "vx",
    "vy",
    "body",
    "stamina",
    "effort",
    "recovery",
    "bx",
    "by",
    "wx",
    "wy",
    "true_wx",
    "true_wy",
    "has_opp",
    "ox",
    "oy",
    "ux",
    "uy",
    "obody",
    "opp_tackle_count",
    "kick_opp",
    "self_kickable",
    "lk_not_ours",
    "play_on",
    "ball_rand",
    "player_rand",
)
if tuple(f.name for f in dataclasses.fields(GoalieView)) != _VIEW_FIELDS:
    raise ImportError("GoalieView's fields changed: update goalie._VIEW_FIELDS and Agent2dGoalie._view")


# The kickable-opponent test (opponent-ball distance < 1.085 + 0.25 + 0.25 at most) is False for sure when the
# attacker's unrounded position is farther than this from the ball: the fullstate's 6 significant digits move a
# coordinate below 1000 m by at most 5e-3
# (set by _bind, with the server parameters below)


def _bind(sp: ServerParams) -> None:
    global KICKABLE_AREA, SELF_KICKABLE_DIST, BALL_DECAY, _KICK_OPP_SURE_FAR
    KICKABLE_AREA = _common.KICKABLE_AREA  # 1.085
    SELF_KICKABLE_DIST = _common.SELF_KICKABLE_DIST  # 1.03
    BALL_DECAY = _common.BALL_DECAY  # 0.94
    _KICK_OPP_SURE_FAR = KICKABLE_AREA + 2.0 * KICKABLE_OPP_ERROR_MAX + 0.1


register_binder(_bind)


class _FullstateView(GoalieView):
    """The goalie's world model as :meth:`Agent2dGoalie._view` builds it: a :class:`GoalieView` whose attacker
    numbers (``ox``, ``oy``, ``ux``, ``uy``, ``obody``) are read from the fullstate (:func:`fullstate_value`)
    when first needed, as most decisions need none of them. A field left None at construction is lazy; the raw
    server values are in ``_opp_raw``."""

    # With several opponents (team games) ``other_opponents`` holds every opponent but the nearest to the ball as
    # (x, y, vx, vy, body, tackle freeze) in GF, and ``opp_self_dist`` the distance of the one nearest to the
    # goalie; with one attacker both stay unset (readers use getattr), so HFO 1v1 takes its old path unchanged.
    __slots__ = ("_opp_raw", "_ox", "_oy", "_ux", "_uy", "_obody", "other_opponents", "opp_self_dist")

    def __init__(
        self,
        cycle: int,
        px: float,
        py: float,
        vx: float,
        vy: float,
        body: float,
        stamina: float,
        effort: float,
        recovery: float,
        bx: float,
        by: float,
        wx: float,
        wy: float,
        true_wx: float,
        true_wy: float,
        has_opp: bool,
        ox: float | None,
        oy: float | None,
        ux: float | None,
        uy: float | None,
        obody: float | None,
        opp_tackle_count: int,
        kick_opp: bool,
        self_kickable: bool,
        lk_not_ours: bool,
        play_on: bool,
        ball_rand: float,
        player_rand: float,
    ) -> None:
        # GoalieView's fields in _VIEW_FIELDS order; the lazy ones straight into their slots
        self.cycle = cycle
        self.px = px
        self.py = py
        self.vx = vx
        self.vy = vy
        self.body = body
        self.stamina = stamina
        self.effort = effort
        self.recovery = recovery
        self.bx = bx
        self.by = by
        self.wx = wx
        self.wy = wy
        self.true_wx = true_wx
        self.true_wy = true_wy
        self.has_opp = has_opp
        self._ox = ox
        self._oy = oy
        self._ux = ux
        self._uy = uy
        self._obody = obody
        self.opp_tackle_count = opp_tackle_count
        self.kick_opp = kick_opp
        self.self_kickable = self_kickable
        self.lk_not_ours = lk_not_ours
        self.play_on = play_on
        self.ball_rand = ball_rand
        self.player_rand = player_rand

    @property  # type: ignore[override]
    def ox(self) -> float:
        v = self._ox
        if v is None:
            v = self._ox = -fullstate_value(self._opp_raw[0])
        return v

    @ox.setter
    def ox(self, value: float) -> None:
        self._ox = value

    @property  # type: ignore[override]
    def oy(self) -> float:
        v = self._oy
        if v is None:
            v = self._oy = -fullstate_value(self._opp_raw[1])
        return v

    @oy.setter
    def oy(self, value: float) -> None:
        self._oy = value

    @property  # type: ignore[override]
    def ux(self) -> float:
        v = self._ux
        if v is None:
            v = self._ux = -fullstate_value(self._opp_raw[2])
        return v

    @ux.setter
    def ux(self, value: float) -> None:
        self._ux = value

    @property  # type: ignore[override]
    def uy(self) -> float:
        v = self._uy
        if v is None:
            v = self._uy = -fullstate_value(self._opp_raw[3])
        return v

    @uy.setter
    def uy(self, value: float) -> None:
        self._uy = value

    @property  # type: ignore[override]
    def obody(self) -> float:
        v = self._obody
        if v is None:
            v = self._obody = norm_deg(fullstate_value(self._opp_raw[4]) + 180.0)
        return v

    @obody.setter
    def obody(self, value: float) -> None:
        self._obody = value


_DECIDED = object()  # Agent2dGoalie.apply's default command: the last decision's


def _check_skill(skill: object) -> None:
    if isinstance(skill, bool) or not isinstance(skill, (int, float, np.number)) or not 0.0 <= skill <= 1.0:
        raise ValueError(f"keeper skill must be a number in [0, 1], got {skill!r}")


class Agent2dGoalie:
    """HFO's default defence goalie (agent2d "base" team, role Goalie), defending the goal at x = +52.5.

    Args:
        params: server parameters of the world it plays in.
        rng: generator for the weakening draws (``skill < 1``); skill 1 draws nothing.
        skill: in [0, 1]. 1 is exactly agent2d's goalie. Below 1 the goalie sends no command at all in a cycle with
            probability ``1 - skill`` (it hesitates: no turn, dash, catch or tackle), so skill 0 is a goalie that
            stands where it is. This weakening is this project's design, for curricula; HFO has no such knob.

    ``last_command`` is the body command of the last decision (None: nothing sent), ``last_view`` its world model.
    It is a :class:`hfo2d.npc.DefenseNPC` whose client state carries over between episodes, as in real HFO.
    """

    carries_over = True

    def __init__(self, params: ServerParams, rng: np.random.Generator, skill: float = 1.0) -> None:
        _check_skill(skill)
        self.params = params
        # the object bind_server_params knows these params by (goalies of equal params share it)
        self._server_params = canonical_params(params)
        self.rng = rng
        self.skill = float(skill)
        self.restart()

    def __setstate__(self, state: dict[str, object]) -> None:
        """Unpickled: the params object becomes the canonical one again, so that goalies of equal params still
        share one binding (:func:`~hfo2d.agent2d.common.canonical_params`)."""
        self.__dict__.update(state)
        self._server_params = canonical_params(self._server_params)

    def restart(self) -> None:
        """Forget the client state, as a goalie made afresh (the params, generator and skill stay)."""
        self.last_command: Command | None = None
        self.last_view: GoalieView | None = None
        # client state that outlives an episode in real HFO (the trainer resets only the server's objects)
        # librcsc SelfObject::catchTime as a cycle number; NEVER_CAUGHT: no catch yet (real HFO's first episode
        # starts long after cycle 0, so the ban test of the client never bites before a first catch)
        self._last_catch_cycle = NEVER_CAUGHT
        self._last_body_kind: str | None = None  # ActionEffector::lastBodyCommandType
        self._catch_command_cycle = 0  # ActionEffector::getCatchTime: the cycle of the last catch command
        self._free_kick = FreeKickState()  # Bhv_GoalieFreeKick's static flags
        self._last_kicker_ours = False  # WorldModel::M_last_kicker_side == our side (neutral at the start)
        self._prev_ball_vel: tuple[float, float] | None = None
        self._play_on = True
        self._catch_pending = False
        self._effector = Effector()  # decide()'s, emptied for every decision
        # _view's last conversions of the ball (x, y, vx, vy) and of the goalie's (body, stamina, effort, recovery),
        # by the bytes of their server values: a resting ball and a goalie that does not turn repeat them
        self._ball_key: bytes | None = None
        self._ball_numbers: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)
        self._body_key: bytes | None = None
        self._body_numbers: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)

    def set_skill(self, skill: float) -> None:
        """Play with quality ``skill`` in [0, 1] from now on; the client state (catch time...) stays."""
        _check_skill(skill)
        self.skill = float(skill)

    def start_body_deg(self, rng: np.random.Generator) -> float:
        """The body angle of a goalie that no episode has moved yet: rcssserver starts it at 0 (facing its own
        goal) and agent2d's before-kick-off scan turns it by 180 degrees every few cycles, so real HFO's first
        episode starts facing either way (drawn from ``rng``; agent2d goalie spec §2.5)."""
        return AGENT2D_FIRST_BODY_DEGS[int(rng.integers(len(AGENT2D_FIRST_BODY_DEGS)))]

    def reset(self) -> None:
        """A new episode: the referee's before_kick_off / play_on messages put the world model back in PlayOn."""
        self._play_on = True
        self._catch_pending = False
        self._prev_ball_vel = None
        self._last_kicker_ours = False
        self.last_command = None

    # -------------------------------------------------------------------------------------------------------------
    def act(self, world: World, keeper: PlayerState) -> None:
        """Decide and send this cycle's command (use :meth:`decide` + :meth:`apply` to split the two)."""
        self.apply(world, keeper, self.decide(world, keeper))

    def decide(self, world: World, keeper: PlayerState) -> Command | None:
        """The goalie's body command for the coming cycle, from the state after the last server step."""
        if self._server_params is not _common.BOUND_PARAMS:  # another world's parameters: the goalie's own
            bind_server_params(self._server_params)
        cycle = world.cycle
        # SelfObject::updateAfterSenseBody: the sense body after a catch command marks the catch time.
        if self._last_body_kind == "catch":
            self._last_catch_cycle = cycle
        elif self._last_catch_cycle == cycle:
            self._last_catch_cycle = NEVER_CAUGHT
        view = self._view(world, keeper)
        self.last_view = view
        command: Command | None = None
        if keeper.tackle_cycles > 0:
            command = None  # frozen by its own tackle: SamplePlayer sends no body command
        elif self.skill < 1.0 and self.rng.random() >= self.skill:
            command = None  # the weakening: hesitate this cycle
        else:
            table = build_intercept_table(view, None, None, False)  # the fast (and lazy) table
            table.complete = False
            eff = self._effector
            eff.command = None  # a fresh Effector's state
            decide(eff, view, table, self._last_catch_cycle, self._catch_command_cycle, self._free_kick)
            command = eff.command
            if command is not None and command.kind == "catch":
                if view.play_on:
                    self._catch_command_cycle = cycle  # ActionEffector::setCatch
                else:
                    command = None  # the client refuses a catch outside PlayOn
        self.last_command = command
        return command

    def apply(self, world: World, keeper: PlayerState, command: Command | None | object = _DECIDED) -> None:
        """Send ``command`` (by default the last :meth:`decide`'s) through librcsc's conversions
        (:func:`client_turn_moment`, :func:`client_dash`)."""
        if command is _DECIDED:
            command = self.last_command
        if command is None:
            return
        if self._server_params is not _common.BOUND_PARAMS:
            bind_server_params(self._server_params)
        kind = command.kind
        if kind == "catch":
            # PlayerCatchCommand: the direction is written with a C++ stream's default 6 significant digits
            if world.catch(keeper, float(f"{norm_deg(command.a):.6g}")):
                self._catch_pending = True
        elif kind in ("turn", "dash", "tackle"):
            send_command(world, keeper, self.last_view, command)
        # kind "move" (Bhv_GoalieFreeKick): rcssserver player.cpp Player::move ignores it in PlayOn, the only
        # server play mode of an HFO episode
        self._last_body_kind = kind

    # -------------------------------------------------------------------------------------------------------------
    def _view(self, world: World, keeper: PlayerState) -> GoalieView:
        """librcsc's world model just before the decision, converted to GF.

        Every number is what the client parses from rcssserver's fullstate message: printed with a C++ stream's
        default 6 significant digits (:func:`fullstate_value`), then mirrored for the right side as librcsc's
        FullstateSensor::reverse does (positions and velocities negated, body angle normalize(body + 180))."""
        ball = world.ball
        fs = fullstate_value
        # (the kernel converts as the extension's fullstate_value does: not when a test replaced the function)
        if _ACCEL_MIRRORED_SELF is not None and fs is _ACCEL_FULLSTATE_VALUE:
            px, py, vx, vy, body, stamina, effort, recovery, bx, by, wx, wy = _ACCEL_MIRRORED_SELF(
                keeper, ball
            )
        else:
            px, py, vx, vy = -fs(keeper.x), -fs(keeper.y), -fs(keeper.vx), -fs(keeper.vy)
            # (the same numbers as last cycle for the same server values: fullstate_value is a function of the
            # bits)
            key = _PACK_FOUR(ball.x, ball.y, ball.vx, ball.vy)
            if key == self._ball_key:
                bx, by, wx, wy = self._ball_numbers
            else:
                bx, by, wx, wy = -fs(ball.x), -fs(ball.y), -fs(ball.vx), -fs(ball.vy)
                self._ball_key = key
                self._ball_numbers = (bx, by, wx, wy)
            key = _PACK_FOUR(keeper.body_deg, keeper.stamina, keeper.effort, keeper.recovery)
            if key == self._body_key:
                body, stamina, effort, recovery = self._body_numbers
            else:
                body = norm_deg(fs(keeper.body_deg) + 180.0)
                stamina = fs(keeper.stamina)
                effort = fs(keeper.effort)
                recovery = fs(keeper.recovery)
                self._body_key = key
                self._body_numbers = (body, stamina, effort, recovery)
        d_b = math.hypot(bx - px, by - py)
        side = keeper.side
        opponents = [player for player in world.players if player.side != side]
        attacker = opponents[0] if opponents else None
        ox = oy = ux = uy = obody = 0.0
        frozen = 0
        kick_opp = False
        others: tuple[tuple[float, float, float, float, float, int], ...] | None = None
        if len(opponents) > 1:
            attacker, (ox, oy), kick_opp, others, opp_self_dist = self._several_opponents(
                opponents, bx, by, px, py, d_b
            )
            frozen = attacker.tackle_cycles
            opp_raw = (attacker.x, attacker.y, attacker.vx, attacker.vy, attacker.body_deg)
            ux = uy = obody = None  # converted when first read, as with one attacker
        elif attacker is not None:
            # the attacker's numbers are converted when the decision first reads them (_FullstateView); the
            # kickable test needs its position unless the raw position is surely too far from the ball
            ox = oy = ux = uy = obody = None
            opp_raw = (attacker.x, attacker.y, attacker.vx, attacker.vy, attacker.body_deg)
            frozen = attacker.tackle_cycles
            if frozen <= 0:
                rox = -opp_raw[0]
                roy = -opp_raw[1]
                if not (
                    -1000.0 < rox < 1000.0
                    and -1000.0 < roy < 1000.0
                    and math.hypot(rox - bx, roy - by) > _KICK_OPP_SURE_FAR
                ):
                    ox = -fs(opp_raw[0])
                    oy = -fs(opp_raw[1])
                    opp_ball = math.hypot(ox - bx, oy - by)
                    opp_self = math.hypot(ox - px, oy - py)
                    kick_opp = opponent_may_kick(opp_ball, opp_self, d_b)
        if self._catch_pending:
            # the referee's goalie_catch_ball message: GoalieCatch mode until the next episode. The ball velocity
            # stays the fullstate's: librcsc ball_object.cpp BallObject::update zeroes it only in the set plays
            # other than GoalieCatch, and updateByFullstate overwrites it anyway (measured: real HFO's goalie
            # decided on the unzeroed velocity in the cycle its catch was announced)
            self._catch_pending = False
            self._play_on = False
        noise = world.noise
        params = world.params
        # positional, in _VIEW_FIELDS order (a keyword call costs more than the rest of the view)
        view = _FullstateView(
            world.cycle,
            px,
            py,
            vx,
            vy,
            body,
            stamina,
            effort,
            recovery,
            bx,
            by,
            wx,
            wy,
            wx,
            wy,
            attacker is not None,
            ox,
            oy,
            ux,
            uy,
            obody,
            frozen,
            kick_opp,
            d_b <= SELF_KICKABLE_DIST,
            True,  # lk_not_ours, set below
            self._play_on,
            params.ball_rand if noise else 0.0,
            params.player_rand if noise else 0.0,
        )
        if attacker is not None:
            view._opp_raw = opp_raw
        if others is not None:
            view.other_opponents = others
            view.opp_self_dist = opp_self_dist
        if self._last_kicker_ours or not self._play_on or self._last_body_kind == "tackle":
            self._update_last_kicker(view, attacker is not None)
            view.lk_not_ours = not self._last_kicker_ours
        else:
            # _update_last_kicker's usual cycle (the last kicker is theirs and stays so): it only records the
            # velocity, and lk_not_ours stays True
            self._prev_ball_vel = (wx, wy)
        if kick_opp and not view.self_kickable:
            view.wx = view.wy = 0.0  # BallObject::setOpponentControlEffect
        return view

    @staticmethod
    def _several_opponents(
        opponents: list[PlayerState], bx: float, by: float, px: float, py: float, d_b: float
    ) -> tuple[
        PlayerState,
        tuple[float, float],
        bool,
        tuple[tuple[float, float, float, float, float, int], ...],
        float,
    ]:
        """librcsc's world model with several opponents (HFO team games), from their fullstate numbers in GF.

        Returns the opponent nearest to the ball (WorldModel::opponentsFromBall's first: the player the decision
        reads as "the attacker", as the field defender's view does) and its position, ``kick_opp``
        (updatePlayerStateCache's test on the first opponent from the ball that is not frozen by a tackle), every
        other opponent as (x, y, vx, vy, body, tackle freeze) for the intercept table's opponent reach and the
        nearest-opponent distances, and the distance of the opponent nearest to the goalie
        (getOpponentNearestToSelf)."""
        # (distance from the ball, distance from the goalie, (x, y, vx, vy, body, freeze), player), each distance
        # computed once for the sort and the tests below
        convert = mirrored_players if fullstate_value is _ACCEL_FULLSTATE_VALUE else mirrored_players_python
        ranked = convert(opponents, None, bx, by, px, py)
        # stable: equal distances keep the server order, as librcsc's sort of its opponent list does
        ranked.sort(key=_first)
        kick_opp = False
        for opp_ball, opp_self, other, _ in ranked:
            if other[5] <= 0:
                kick_opp = opponent_may_kick(opp_ball, opp_self, d_b)
                break
        others = tuple(other for _, _, other, _ in ranked[1:])
        opp_self_dist = math.inf
        for _, opp_self, _, _ in ranked:
            if opp_self < opp_self_dist:
                opp_self_dist = opp_self
        _, _, other, first = ranked[0]
        return first, (other[0], other[1]), kick_opp, others, opp_self_dist

    def _update_last_kicker(self, view: GoalieView, has_attacker: bool) -> None:
        """WorldModel::updateLastKicker, reduced to HFO 1v1: ours after the goalie's own tackle (or kick), theirs
        again once the ball's velocity changes with the attacker near it."""
        prev = self._prev_ball_vel
        self._prev_ball_vel = (view.true_wx, view.true_wy)
        if not view.play_on:
            self._last_kicker_ours = True  # GoalieCatch is our set play
            return
        if self._last_body_kind == "tackle":  # SelfObject::kicked(): the last body command sent was a tackle
            self._last_kicker_ours = True
            return
        if not self._last_kicker_ours or prev is None or not has_attacker:
            return
        cur_speed = math.hypot(view.true_wx, view.true_wy)
        prev_speed = math.hypot(*prev)
        angle_diff = abs(norm_deg(angle_of(view.true_wx, view.true_wy) - angle_of(*prev)))
        changed = (
            cur_speed > prev_speed + BALL_VEL_CHANGE_SPEED
            or cur_speed < prev_speed * BALL_DECAY * 0.5
            or (prev_speed > 0.5 and angle_diff > BALL_VEL_CHANGE_ANGLE)
        )
        if changed and math.hypot(view.ox - view.bx, view.oy - view.by) < LAST_KICKER_DIST:
            self._last_kicker_ours = False
