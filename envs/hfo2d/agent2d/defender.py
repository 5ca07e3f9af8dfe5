"""HFO's field defenders (agent2d "base" team, every role but the goalie) as hfo2d NPCs.

HFO starts agent2d's ``sample_player`` for each defence NPC; unum 1 is the goalie (:mod:`hfo2d.agent2d.goalie`),
the others are field players whose roles (CenterBack, SideBack, ...) all decide alike and differ only in their
formation position. Each cycle :meth:`Agent2dDefender.decide` builds the player's world model from the true state
(HFO's ``--fullstate``), and decides:

1. frozen by its own tackle: no body command;
2. outside PlayOn (after its goalie caught the ball without ending the trial): Bhv_SetPlayFreeKick's move to its
   ``goalie-catch-our.conf`` position;
3. the ball kickable and an opponent able to kick too: the simultaneous kick (``doForceKick``,
   Body_KickOneStep toward the opponent goal at 3.0 m/cycle);
4. the ball kickable (and no teammate that can kick nearer to it): the on-ball play. agent2d runs its action-chain
   planner here (about 10,000 lines of pass, dribble and hold search); this port holds the ball instead
   (:func:`hold_ball_kick`), which keeps it within the player's reach, so that HFO's referee sees a second
   defence touch and ends the trial CAPTURED_BY_DEFENSE as it mostly does after agent2d's hold and short dribble;
5. otherwise Bhv_BasicMove: Bhv_BasicTackle(0.8, 80); the intercept test (Body_Intercept2009 when no teammate
   can kick and self_min <= 3, or self_min <= mate_min and self_min < opp_min + 3); else Body_GoToPoint to the
   formation position (:mod:`hfo2d.agent2d.formation`) with Strategy::get_normal_dash_power, or Body_TurnToBall
   when already there.

The goalie's modules do the shared work: librcsc's intercept table and self prediction with the goalie-only
rules off (:mod:`~hfo2d.agent2d.intercept`), Body_Intercept2009, Body_GoToPoint and the client conversions
(:mod:`~hfo2d.agent2d.actions`), the tackle (:mod:`~hfo2d.agent2d.tackle`). Every server value comes from the
world's :class:`~hfo2d.physics.ServerParams` through :func:`~hfo2d.agent2d.common.bind_server_params`.

Sources (facts and numbers, no code): HFO b8b2a1d ``src/sample_player.cpp`` (actionImpl, doPreprocess,
doForceKick), ``src/role_center_back.cpp`` and the other field roles (execute: kickable unless a nearer teammate
can kick), ``src/bhv_basic_move.cpp``, ``src/bhv_basic_tackle.cpp``, ``src/strategy.cpp`` (updatePosition: the
focus point ballAt(min(mate_min, opp_min, self_min)) and the offside clamp; get_normal_dash_power and its static
recover flag), ``src/bhv_set_play.cpp`` (get_set_play_dash_power), ``src/bhv_set_play_free_kick.cpp`` (doMove),
``bin/teams/base/config/formations-dt/*.conf``; librcsc d222758 ``rcsc/player/world_model.cpp``
(updateJustBeforeDecision: the kickable flags of the nearest teammate and opponent, the ball-velocity zeroing under a
kickable opponent, updateOurDefenseLine, the offside line), ``rcsc/player/self_object.cpp`` (the fullstate
kickable buffer, the forced kickable rule, the foul probability), ``rcsc/player/intercept_table.cpp``
(teammateReachCycle without the goalie), ``rcsc/action/body_kick_one_step.cpp``, ``rcsc/action/basic_actions.cpp``
(Body_TurnToBall), ``rcsc/player/action_effector.cpp`` (setKick: power rounded to 0.001).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from operator import itemgetter

import numpy as np

from hfo2d.accel import ACCEL as _ACCEL
from hfo2d.agent2d import common as _common
from hfo2d.agent2d import intercept as _intercept
from hfo2d.agent2d.actions import (
    body_go_to_point,
    body_intercept,
    body_turn_to_point,
    safety_dash_power,
    send_command,
)
from hfo2d.agent2d.common import (
    Command,
    Effector,
    GoalieView,
    InterceptTable,
    angle_of,
    ball_at,
    bind_server_params,
    canonical_params,
    norm_deg,
    register_binder,
)
from hfo2d.agent2d.formation import normal_formation
from hfo2d.agent2d.formation_data import GOALIE_CATCH_OUR
from hfo2d.agent2d.goalie import (
    _ACCEL_MIRRORED_SELF,
    _PACK_FOUR,
    _VIEW_FIELDS,
    fullstate_value,
    mirrored_players,
    opponent_may_kick,
)
from hfo2d.agent2d.intercept import build_intercept_table, fastest_reach, full_self_cache
from hfo2d.agent2d.tackle import basic_tackle
from hfo2d.physics import PlayerState, ServerParams, World

__all__ = ["Agent2dDefender", "DefenderView", "TeamInterceptTable", "hold_ball_kick"]

# (x, y, vx, vy, body, remaining tackle freeze) of another player, in the defender's frame (DF)
OtherPlayer = tuple[float, float, float, float, float, int]

# librcsc world_model.cpp / self_object.cpp constants (not server parameters)
FORCED_KICKABLE_SLACK = 0.001  # self_object.cpp: the forced kickable rule needs d_B < kickable_area - 0.001
FORCED_KICKABLE_SELF_MIN = 10  # ... and self_min >= 10, or an opponent 7 cycles faster than both sides
FORCED_KICKABLE_LEAD = 7
# sample_player.cpp doForceKick: the opponent goal (DF), first speed 3.0
FORCE_KICK_TARGET = (52.5, 0.0)
FORCE_KICK_SPEED = 3.0
# bhv_basic_move.cpp: Bhv_BasicTackle(0.8, 80); the intercept test's 3 cycles
BASIC_TACKLE_PROB = 0.8
BASIC_TACKLE_BODY_THR = 80.0
INTERCEPT_SURE_CYCLES = 3
# strategy.cpp get_normal_dash_power (fractions of stamina_max, multiples of stamina_inc_max * recovery)
RECOVER_ON_RATE = 0.5
RECOVER_OFF_RATE = 0.7
# bhv_set_play_free_kick.cpp doMove: dodge a near opponent when the stamina is above 0.9 * stamina_max
SET_PLAY_DODGE_STAMINA_RATE = 0.9
# hfo2d's hold (this port's stand-in for agent2d's on-ball chain): keep the ball this far in front of the body
HOLD_FRONT_DIST = 0.6


def _bind(sp: ServerParams) -> None:
    global KICKABLE_AREA, SELF_KICKABLE_DIST, BALL_DECAY, PLAYER_DECAY, STAMINA_MAX, STAMINA_INC_MAX
    global MAX_DASH_POWER, KICK_POWER_RATE, MAX_POWER, BALL_ACCEL_MAX, BALL_SPEED_MAX, PLAYER_SIZE, BALL_SIZE
    global KICKABLE_MARGIN
    KICKABLE_AREA = _common.KICKABLE_AREA  # 1.085
    SELF_KICKABLE_DIST = _common.SELF_KICKABLE_DIST  # 1.03
    BALL_DECAY = _common.BALL_DECAY  # 0.94
    PLAYER_DECAY = _common.PLAYER_DECAY  # 0.4
    STAMINA_MAX = _common.STAMINA_MAX  # 8000
    STAMINA_INC_MAX = _common.STAMINA_INC_MAX  # 45
    MAX_DASH_POWER = _common.MAX_DASH_POWER  # 100
    KICK_POWER_RATE = sp.kick_power_rate  # 0.027
    MAX_POWER = sp.maxpower  # 100
    BALL_ACCEL_MAX = sp.ball_accel_max  # 2.7
    BALL_SPEED_MAX = sp.ball_speed_max  # 3
    PLAYER_SIZE = sp.player_size  # 0.3
    BALL_SIZE = sp.ball_size  # 0.085
    KICKABLE_MARGIN = sp.kickable_margin  # 0.7


register_binder(_bind)


# --- world model ----------------------------------------------------------------------------------------------
@dataclass(slots=True)
class DefenderView(GoalieView):
    """What a field defender knows when it decides (fullstate), in DF (own goal at x = -52.5).

    The inherited opponent fields (``ox`` ... ``opp_tackle_count``) describe the opponent nearest to the ball (the
    one librcsc tests for ``kick_opp`` and blocks in Body_Intercept); ``opponents`` lists them all, nearest to the
    ball first; ``teammates`` the other field players (not the goalie), nearest to the ball first.
    ``lk_not_ours`` is always False: it switches off the goalie-only intercept rules, which need ``self.goalie()``.
    """

    unum: int = 2
    opponents: tuple[OtherPlayer, ...] = ()
    teammates: tuple[OtherPlayer, ...] = ()
    goalie_pos: tuple[float, float] | None = None
    mate_kick: bool = False  # librcsc existKickableTeammate (goalie included)
    mate_ball_dist: float = (
        math.inf
    )  # the distance to the ball of the teammate nearest to it (goalie included)
    opp_self_dist: float = math.inf  # getOpponentNearestToSelf's distance
    defense_line_x: float = 0.0  # WorldModel::ourDefenseLineX
    offside_line_x: float = 0.0  # WorldModel::offsideLineX


@dataclass(slots=True)
class TeamInterceptTable(InterceptTable):
    """librcsc's InterceptTable with the teammates' reach: ``mate_min`` is the fastest non-goalie teammate's (0 when
    a teammate, the goalie included, can kick; 1000 without one)."""

    mate_min: int = 1000
    #: the lazy table (build_intercept_table(view, full=False)) the fields were read from: its ball cache serves
    #: the full self cache when Body_Intercept needs it (intercept.full_self_cache)
    source: InterceptTable | None = None


# Agent2dDefender._view builds its DefenderView positionally, in this field order
_DEFENDER_VIEW_FIELDS = _VIEW_FIELDS + (  # GoalieView's fields (hfo2d.agent2d.goalie), then its own
    "unum",
    "opponents",
    "teammates",
    "goalie_pos",
    "mate_kick",
    "mate_ball_dist",
    "opp_self_dist",
    "defense_line_x",
    "offside_line_x",
)
if tuple(f.name for f in fields(DefenderView)) != _DEFENDER_VIEW_FIELDS:
    raise ImportError(
        "DefenderView's fields changed: update defender._DEFENDER_VIEW_FIELDS and Agent2dDefender._view"
    )


_first = itemgetter(0)  # a sort key (in C)


def _check_skill(skill: object) -> None:
    if isinstance(skill, bool) or not isinstance(skill, (int, float, np.number)) or not 0.0 <= skill <= 1.0:
        raise ValueError(f"defender skill must be a number in [0, 1], got {skill!r}")


def _check_unum(unum: object) -> int:
    if isinstance(unum, bool) or not isinstance(unum, (int, np.integer)) or not 2 <= int(unum) <= 11:
        raise ValueError(
            f"a field defender's unum must be an integer in 2..11 (1 is the goalie), got {unum!r}"
        )
    return int(unum)


_DECIDED = object()  # Agent2dDefender.apply's default command: the last decision's


class Agent2dDefender:
    """One of HFO's default defence field players (agent2d "base" team), defending the goal at x = +52.5.

    Args:
        params: server parameters of the world it plays in.
        rng: generator for the weakening draws (``skill < 1``); skill 1 draws nothing.
        skill: in [0, 1]. 1 is agent2d's defender. Below 1 it sends no command in a cycle with probability
            ``1 - skill`` (this project's weakening, as for :class:`~hfo2d.agent2d.goalie.Agent2dGoalie`).
        unum: its uniform number, 2..11; it picks the formation position (HFO gives unum u the role of the
            formation file's line u: 2, 3 CenterBack, 4, 5 SideBack, 6 DefensiveHalf, ...).

    ``last_command`` is the body command of the last decision, ``last_view`` its world model, ``last_table`` its
    intercept table and ``last_branch`` the behaviour that chose it ("frozen", "hesitate", "set_play_move",
    "force_kick", "hold", "tackle", "intercept", "move", "turn_to_ball"). It is a :class:`hfo2d.npc.DefenseNPC`
    whose client state (the defence line, the recover flag) carries over between episodes, as in real HFO.
    """

    carries_over = True

    def __init__(
        self, params: ServerParams, rng: np.random.Generator, skill: float = 1.0, unum: int = 2
    ) -> None:
        _check_skill(skill)
        self.unum = _check_unum(unum)
        self.params = params
        self._server_params = canonical_params(params)
        self.rng = rng
        self.skill = float(skill)
        self.restart()

    def __setstate__(self, state: dict[str, object]) -> None:
        self.__dict__.update(state)
        self._server_params = canonical_params(self._server_params)
        if "_ball_key" not in state:  # pickled before the conversions were kept
            self._forget_conversions()

    def restart(self) -> None:
        """Forget the client state, as a player made afresh (the params, generator, skill and unum stay)."""
        self.last_command: Command | None = None
        self.last_view: DefenderView | None = None
        self.last_table: TeamInterceptTable | None = None
        self.last_branch = ""
        self.last_home: tuple[float, float] | None = None
        # client state that outlives an episode in real HFO (one process per NPC)
        self._defense_line_x = 0.0  # WorldModel::M_our_defense_line_x, 0 at construction
        self._recover_mode = False  # Strategy::get_normal_dash_power's static s_recover_mode
        self._play_on = True
        self._set_play_count = 0  # WorldModel::setplayCount: cycles since the set play began
        self._effector = Effector()
        self._forget_conversions()

    def _forget_conversions(self) -> None:
        # _view's last conversions of the ball (x, y, vx, vy) and of its own (body, stamina, effort, recovery), by
        # the bytes of their server values (fullstate_value is a function of the bits)
        self._ball_key: bytes | None = None
        self._ball_numbers = (0.0, 0.0, 0.0, 0.0)
        self._body_key: bytes | None = None
        self._body_numbers = (0.0, 0.0, 0.0, 0.0)

    def set_skill(self, skill: float) -> None:
        """Play with quality ``skill`` in [0, 1] from now on."""
        _check_skill(skill)
        self.skill = float(skill)

    def start_body_deg(self, rng: np.random.Generator) -> float:
        """The body angle of a defender that no episode has moved yet: rcssserver starts every player at 0 and
        agent2d's before-kick-off scan turns it (Bhv_CustomBeforeKickOff), so real HFO's first episode starts
        facing either way, drawn from ``rng`` as for the goalie."""
        from hfo2d.protocol import AGENT2D_FIRST_BODY_DEGS

        return AGENT2D_FIRST_BODY_DEGS[int(rng.integers(len(AGENT2D_FIRST_BODY_DEGS)))]

    def reset(self) -> None:
        """A new episode: the referee's before_kick_off / play_on messages put the world model back in PlayOn."""
        self._play_on = True
        self._set_play_count = 0
        self.last_command = None

    def goalie_caught(self) -> None:
        """Its goalie caught the ball and the trial goes on (the referee's ``goalie_catch_ball_r``): GoalieCatch
        (our set play) until the next episode. The env calls it when the goalie's catch succeeds."""
        if self._play_on:
            self._play_on = False
            self._set_play_count = 0

    # -------------------------------------------------------------------------------------------------------------
    def act(self, world: World, player: PlayerState) -> None:
        """Decide and send this cycle's command."""
        self.apply(world, player, self.decide(world, player))

    def decide(self, world: World, player: PlayerState) -> Command | None:
        """The body command for the coming cycle, from the state after the last server step."""
        if self._server_params is not _common.BOUND_PARAMS:
            bind_server_params(self._server_params)
        view = self._view(world, player)
        self.last_view = view
        self.last_table = None
        self.last_home = None
        eff = self._effector
        eff.command = None
        if player.tackle_cycles > 0:
            self.last_branch = "frozen"  # SamplePlayer sends no body command while frozen
        elif self.skill < 1.0 and self.rng.random() >= self.skill:
            self.last_branch = "hesitate"
        else:
            table = self._table(view)
            self.last_table = table
            self._forced_kickable(view, table)
            self._decide(eff, view, table)
        if not self._play_on:
            self._set_play_count += 1
        self.last_command = eff.command
        return eff.command

    def apply(self, world: World, player: PlayerState, command: Command | None | object = _DECIDED) -> None:
        """Send ``command`` (by default the last :meth:`decide`'s) through librcsc's client conversions."""
        if command is _DECIDED:
            command = self.last_command
        if command is None:
            return
        if self._server_params is not _common.BOUND_PARAMS:
            bind_server_params(self._server_params)
        if not send_command(world, player, self.last_view, command) and command.kind == "kick":
            world.kick(player, *client_kick(command.a, command.b))

    # -------------------------------------------------------------------------------------------------------------
    def _view(self, world: World, me: PlayerState) -> DefenderView:
        """librcsc's world model just before the decision (updateJustBeforeDecision), in DF."""
        fs = fullstate_value
        ball = world.ball
        if _ACCEL_MIRRORED_SELF is not None:
            px, py, vx, vy, body, stamina, effort, recovery, bx, by, wx, wy = _ACCEL_MIRRORED_SELF(me, ball)
        else:
            # (the same numbers as last cycle for the same server values, as in Agent2dGoalie._view: a resting ball
            # and a defender that does not turn or tire repeat them)
            key = _PACK_FOUR(ball.x, ball.y, ball.vx, ball.vy)
            if key == self._ball_key:
                bx, by, wx, wy = self._ball_numbers
            else:
                bx, by, wx, wy = -fs(ball.x), -fs(ball.y), -fs(ball.vx), -fs(ball.vy)
                self._ball_key = key
                self._ball_numbers = (bx, by, wx, wy)
            px, py, vx, vy = -fs(me.x), -fs(me.y), -fs(me.vx), -fs(me.vy)
            key = _PACK_FOUR(me.body_deg, me.stamina, me.effort, me.recovery)
            if key == self._body_key:
                body, stamina, effort, recovery = self._body_numbers
            else:
                body = norm_deg(fs(me.body_deg) + 180.0)
                stamina, effort, recovery = fs(me.stamina), fs(me.effort), fs(me.recovery)
                self._body_key = key
                self._body_numbers = (body, stamina, effort, recovery)
        d_b = math.hypot(bx - px, by - py)
        # (distance from the ball, distance from self, numbers) of every opponent; (distance from the ball,
        # numbers) of every other field player of ours; each distance is computed once and reused by the sorts and
        # the tests below (the same expressions they used)
        ranked_opponents: list[tuple[float, float, OtherPlayer]] = []
        ranked_teammates: list[tuple[float, OtherPlayer]] = []
        goalie_pos: tuple[float, float] | None = None
        # (ball distance, tackle freeze) of every teammate, the goalie included
        mates: list[tuple[float, int]] = []
        our_xs = [px]
        side = me.side
        for ball_dist, self_dist, other, p in mirrored_players(world.players, me, bx, by, px, py):
            if p.side == side:
                our_xs.append(other[0])
                mates.append((ball_dist, other[5]))
                if p.goalie:
                    # our goalie: only its position and freeze are read (no reach is predicted for it)
                    goalie_pos = (other[0], other[1])
                else:
                    ranked_teammates.append((ball_dist, other))
            else:
                ranked_opponents.append((ball_dist, self_dist, other))
        # stable sorts by the ball distance alone: equal distances keep the server order
        ranked_opponents.sort(key=_first)
        ranked_teammates.sort(key=_first)
        mates.sort(key=_first)
        opponents = [o for _, _, o in ranked_opponents]
        # check_player_kickable: the first player of a side by distance to the ball that is not tackling is tested
        # (a teammate within kickable_area, an opponent within kickable_area plus the observation margins)
        mate_kick = False
        for dist, frozen in mates:
            if frozen <= 0:
                mate_kick = dist < KICKABLE_AREA
                break
        kick_opp = False
        for opp_ball, opp_self, o in ranked_opponents:
            if o[5] <= 0:
                kick_opp = opponent_may_kick(opp_ball, opp_self, d_b)
                break
        nearest = opponents[0] if opponents else None
        self_kick = d_b <= SELF_KICKABLE_DIST
        true_wx, true_wy = wx, wy
        if kick_opp and not self_kick:
            wx = wy = 0.0  # BallObject::setOpponentControlEffect
        opp_self_dist = math.inf
        for _, opp_self, _ in ranked_opponents:
            if opp_self < opp_self_dist:
                opp_self_dist = opp_self
        self._defense_line_x = self._update_defense_line(our_xs, goalie_pos is not None, bx)
        offside = self._offside_line(opponents, bx + wx)
        noise = world.noise
        params = world.params
        o = nearest if nearest is not None else (0.0, 0.0, 0.0, 0.0, 0.0, 0)
        # positional, in _DEFENDER_VIEW_FIELDS order (a keyword call of 37 fields costs about 1.5 us more)
        return DefenderView(
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
            true_wx,
            true_wy,
            nearest is not None,
            o[0],
            o[1],
            o[2],
            o[3],
            o[4],
            o[5],
            kick_opp,
            self_kick,
            False,
            self._play_on,
            params.ball_rand if noise else 0.0,
            params.player_rand if noise else 0.0,
            self.unum,
            tuple(opponents),
            tuple(t for _, t in ranked_teammates),
            goalie_pos,
            mate_kick,
            mates[0][0] if mates else math.inf,
            opp_self_dist,
            self._defense_line_x,
            offside,
        )

    def _update_defense_line(self, our_xs: list[float], goalie_known: bool, ball_x: float) -> float:
        """WorldModel::updateOurDefenseLine: the second-smallest x of our players (running minima from 0), the
        smallest without a known goalie beyond the penalty line, rate-limited against the last line (fewer than 11
        players), never above the ball."""
        first = second = 0.0
        for x in our_xs:
            if x < second:
                second = x
                if second < first:
                    first, second = second, first
        line = second
        if not goalie_known and first > _common.PENALTY_AREA_X:
            line = first
        prev = self._defense_line_x
        if len(our_xs) < 11:
            if line > prev + 13.0:
                pass
            elif line > prev + 5.0:
                line = prev + 1.0
        if ball_x < line:
            line = ball_x
        return line

    @staticmethod
    def _offside_line(opponents: list[OtherPlayer], ball_next_x: float) -> float:
        """WorldModel::offsideLineX for HFO: their defence line (second-largest opponent x, running maxima from
        0, never below 0; the offense has no goalie and plays at x <= 0 in DF), raised to the ball's next x."""
        first = second = 0.0
        for o in opponents:
            x = o[0]
            if x > second:
                second = x
                if second > first:
                    first, second = second, first
        return max(second, ball_next_x)

    def _table(self, view: DefenderView) -> TeamInterceptTable:
        """InterceptTable::update for a field player: self (the goalie-only rules off), the fastest non-goalie
        teammate, the fastest opponent."""
        # the fast table: self_min and the fastest entry are exact, the full self cache (which only Body_Intercept
        # reads) is built when the intercept branch is taken (_basic_move)
        base = build_intercept_table(view, full=False)
        ball = base.ball_part()
        # the fastest of each side (fastest_reach: predict_player_reach for each, on the ball part's frame)
        if _ACCEL is None:
            opp_min = 0 if view.kick_opp else fastest_reach(view, ball, view.opponents, False)
            mate_min = 0 if view.mate_kick else fastest_reach(view, ball, view.teammates, True)
        else:  # intercept.fastest_reach's kernel called here, without its Python frame
            cache, _, sin_a, cos_a = ball
            bx = view.bx
            by = view.by
            px = view.px
            py = view.py
            shortcut = view.wx == 0.0 and view.wy == 0.0 and _intercept._RESTING_SHORTCUTS
            kernel = _ACCEL.fastest_reach
            opp_min = (
                0
                if view.kick_opp
                else kernel(view.opponents, cache, bx, by, px, py, shortcut, sin_a, cos_a, False, 1000)
            )
            mate_min = (
                0
                if view.mate_kick
                else kernel(view.teammates, cache, bx, by, px, py, shortcut, sin_a, cos_a, True, 1000)
            )
        return TeamInterceptTable(ball[0], base.self_cache, base.self_min, opp_min, False, mate_min, base)

    @staticmethod
    def _forced_kickable(view: DefenderView, table: TeamInterceptTable) -> None:
        """SelfObject::updateKickableState's forced rule: a ball just beyond the fullstate buffer counts as
        kickable when nobody gets it sooner anyway, or when it is about to leave the pitch."""
        if view.self_kickable or view.ball_dist >= KICKABLE_AREA - FORCED_KICKABLE_SLACK:
            return
        s, m, o = table.self_min, table.mate_min, table.opp_min
        fx, fy = ball_at(view.bx, view.by, view.wx, view.wy, min(s, m, o))
        if (
            s >= FORCED_KICKABLE_SELF_MIN
            or (o < s - FORCED_KICKABLE_LEAD and o < m - FORCED_KICKABLE_LEAD)
            or abs(fx) > _common.PITCH_HALF_LENGTH
            or abs(fy) > _common.PITCH_HALF_WIDTH
        ):
            view.self_kickable = True

    # -------------------------------------------------------------------------------------------------------------
    def _decide(self, eff: Effector, view: DefenderView, table: TeamInterceptTable) -> None:
        if not view.play_on:
            self.last_branch = "set_play_move"
            self._set_play_move(eff, view)
            return
        if view.self_kickable and view.kick_opp:
            self.last_branch = "force_kick"
            kick_one_step(eff, view, FORCE_KICK_TARGET, FORCE_KICK_SPEED)
            return
        kickable = view.self_kickable and not (view.mate_kick and view.mate_ball_dist < view.ball_dist)
        if kickable:
            self.last_branch = "hold"
            hold_ball_kick(eff, view)
            return
        self._basic_move(eff, view, table)

    def _basic_move(self, eff: Effector, view: DefenderView, table: TeamInterceptTable) -> None:
        """Bhv_BasicMove: tackle, intercept, or keep the formation position."""
        if basic_tackle(eff, view, table, BASIC_TACKLE_PROB, BASIC_TACKLE_BODY_THR):
            self.last_branch = "tackle"
            return
        s, m, o = table.self_min, table.mate_min, table.opp_min
        if not view.mate_kick and (s <= INTERCEPT_SURE_CYCLES or (s <= m and s < o + INTERCEPT_SURE_CYCLES)):
            self.last_branch = "intercept"
            if not table.complete:
                if table.source is not None:
                    table.self_cache = full_self_cache(table.source)
                else:
                    table.self_cache = build_intercept_table(view).self_cache
                table.complete = True
            body_intercept(eff, view, table, True, view.ball_rand)
            return
        hx, hy = self.home_position(view, table)
        power = self._normal_dash_power(view, table)
        thr = max(1.0, 0.1 * view.ball_dist)
        self.last_branch = "move"
        if not body_go_to_point(eff, view, hx, hy, thr, power):
            self.last_branch = "turn_to_ball"
            turn_to_ball(eff, view)

    def home_position(self, view: DefenderView, table: TeamInterceptTable) -> tuple[float, float]:
        """Strategy::updatePosition for this unum: the formation at ballAt(min(mate, opp, self reach)), with x
        clamped below the offside line (raised to the teammates' trap point) less 1 m."""
        step = min(1000, table.mate_min, table.opp_min, table.self_min)
        fx, fy = ball_at(view.bx, view.by, view.wx, view.wy, step)
        hx, hy = normal_formation().position(self.unum, fx, fy)
        max_x = view.offside_line_x
        if table.mate_min < 50:
            trap_x, _ = ball_at(view.bx, view.by, view.wx, view.wy, table.mate_min)
            max_x = max(max_x, trap_x)
        max_x -= 1.0
        if hx > max_x:
            hx = max_x
        self.last_home = (hx, hy)
        return hx, hy

    def _normal_dash_power(self, view: DefenderView, table: TeamInterceptTable) -> float:
        """Strategy::get_normal_dash_power (the stamina capacity never runs out in an HFO episode)."""
        if view.stamina < STAMINA_MAX * RECOVER_ON_RATE:
            self._recover_mode = True
        elif view.stamina > STAMINA_MAX * RECOVER_OFF_RATE:
            self._recover_mode = False
        inc = STAMINA_INC_MAX * view.recovery
        if view.defense_line_x > view.px and view.bx < view.defense_line_x + 20.0:
            return MAX_DASH_POWER
        if self._recover_mode:
            return max(0.0, inc - 25.0)
        if view.mate_kick and view.ball_dist < 20.0:
            return min(inc * 1.1, MAX_DASH_POWER)
        if view.px > view.offside_line_x:
            return MAX_DASH_POWER
        s, m, o = table.self_min, table.mate_min, table.opp_min
        if view.bx > 25.0 and view.bx > view.px + 10.0 and s < o - 6 and m < o - 6:
            return min(max(MAX_DASH_POWER * 0.1, inc * 0.5), MAX_DASH_POWER)
        return min(inc * 1.7, MAX_DASH_POWER)

    def _set_play_move(self, eff: Effector, view: DefenderView) -> None:
        """Bhv_SetPlayFreeKick::doMove after our goalie's catch: to the goalie-catch-our.conf position (dodging a
        near opponent by 3 m every other 20 cycles), below the offside line, at the safety dash power."""
        tx, ty = GOALIE_CATCH_OUR[self.unum]
        if (
            self._set_play_count > 0
            and view.stamina > STAMINA_MAX * SET_PLAY_DODGE_STAMINA_RATE
            and view.opp_self_dist < 3.0
        ):
            ax, ay = view.bx - tx, view.by - ty
            length = math.hypot(ax, ay)
            if length > 0.0:
                ax, ay = ax * 3.0 / length, ay * 3.0 / length
            phase = view.cycle % 60
            if 20 <= phase < 40:
                tx, ty = tx - ay, ty + ax  # rotated +90 degrees
            elif phase >= 40:
                tx, ty = tx + ay, ty - ax  # rotated -90 degrees
            tx = min(max(tx, -_common.PITCH_HALF_LENGTH), _common.PITCH_HALF_LENGTH)
            ty = min(max(ty, -_common.PITCH_HALF_WIDTH), _common.PITCH_HALF_WIDTH)
        tx = min(tx, view.offside_line_x - 0.5)
        self.last_home = (tx, ty)
        thr = max(1.0, view.ball_dist * 0.07)
        if not body_go_to_point(eff, view, tx, ty, thr, safety_dash_power(view, MAX_DASH_POWER)):
            turn_to_ball(eff, view)


# --- on-ball actions ------------------------------------------------------------------------------------------
def turn_to_ball(eff: Effector, view: GoalieView) -> None:
    """Body_TurnToBall(1): turn toward ballAt(1) as seen from selfAt(1)."""
    bx, by = ball_at(view.bx, view.by, view.wx, view.wy, 1)
    body_turn_to_point(eff, view, bx, by, 1)


def kick_rate(view: GoalieView) -> float:
    """librcsc SelfObject::kickRate (rcssserver's kick effectiveness): kick_power_rate * (1 - 0.25 * the ball's
    angle off the body / 180 - 0.25 * its distance beyond touching / kickable_margin)."""
    dist = view.ball_dist
    dir_diff = abs(norm_deg(angle_of(view.bx - view.px, view.by - view.py) - view.body))
    gap = max(0.0, dist - PLAYER_SIZE - BALL_SIZE)
    return KICK_POWER_RATE * (1.0 - 0.25 * dir_diff / 180.0 - 0.25 * gap / KICKABLE_MARGIN)


def _kick_to_velocity(eff: Effector, view: GoalieView, vx: float, vy: float, rate: float) -> None:
    """Kick the ball from its velocity W to (vx, vy): power |v - W| / rate, direction relative to the body."""
    ax, ay = vx - view.wx, vy - view.wy
    power = math.hypot(ax, ay) / rate if rate > 0.0 else 0.0
    eff.command = Command("kick", power, norm_deg(angle_of(ax, ay) - view.body))


def kick_one_step(eff: Effector, view: GoalieView, target: tuple[float, float], first_speed: float) -> None:
    """Body_KickOneStep(target, first_speed): the fastest ball velocity toward ``target`` one kick can give
    (the circle of reachable velocities around W, radius min(maxpower * kick rate, ball_accel_max), met by the
    ray toward the target; capped at ``first_speed`` and ball_speed_max), else stop the ball."""
    rate = kick_rate(view)
    wx, wy = view.wx, view.wy  # the world model's (zeroed under a kickable opponent when not kickable itself)
    first_speed = min(first_speed, BALL_SPEED_MAX)
    max_accel = min(MAX_POWER * rate, BALL_ACCEL_MAX)
    angle = math.radians(angle_of(target[0] - view.bx, target[1] - view.by))
    ux, uy = math.cos(angle), math.sin(angle)
    # |t u - W| = r on the ray t >= 0: t^2 - 2 t (u.W) + |W|^2 - r^2 = 0
    b = ux * wx + uy * wy
    c = wx * wx + wy * wy - max_accel * max_accel
    disc = b * b - c
    roots = [] if disc < 0.0 else sorted({b - math.sqrt(disc), b + math.sqrt(disc)}, reverse=True)
    roots = [t for t in roots if t >= 0.0]
    if not roots:
        # no kick reaches the direction: stop the ball as far as one kick can
        ax, ay = -wx, -wy
        r = math.hypot(ax, ay)
        if r > max_accel:
            ax, ay = ax * max_accel / r, ay * max_accel / r
        vx, vy = wx + ax, wy + ay
    else:
        t = roots[0]
        if t > BALL_SPEED_MAX:
            inside = c <= 0.0  # the circle holds the zero velocity
            t = BALL_SPEED_MAX if (len(roots) == 2 and roots[1] <= BALL_SPEED_MAX) or inside else 0.0
        t = min(t, first_speed)
        vx, vy = ux * t, uy * t
    _kick_to_velocity(eff, view, vx, vy, rate)


def hold_ball_kick(eff: Effector, view: GoalieView) -> None:
    """This port's stand-in for agent2d's on-ball play (Bhv_ChainAction: hold, dribble, pass...): kick the ball
    to HOLD_FRONT_DIST in front of the player's next position, as far as one kick can move it, so that it stays
    within reach. agent2d mostly holds or dribbles short after winning the ball (the second defence touch then
    ends HFO's trial CAPTURED_BY_DEFENSE); its passes and long kicks are not reproduced."""
    rate = kick_rate(view)
    nx = view.px + view.vx * PLAYER_DECAY + HOLD_FRONT_DIST * math.cos(math.radians(view.body))
    ny = view.py + view.vy * PLAYER_DECAY + HOLD_FRONT_DIST * math.sin(math.radians(view.body))
    # the ball velocity that puts it there next cycle, reachable from W within one kick's acceleration
    vx, vy = nx - view.bx, ny - view.by
    ax, ay = vx - view.wx, vy - view.wy
    max_accel = min(MAX_POWER * rate, BALL_ACCEL_MAX)
    r = math.hypot(ax, ay)
    if r > max_accel:
        ax, ay = ax * max_accel / r, ay * max_accel / r
    _kick_to_velocity(eff, view, view.wx + ax, view.wy + ay, rate)


def client_kick(power: float, direction: float) -> tuple[float, float]:
    """The kick librcsc sends (ActionEffector::setKick): power clamped to [0, maxpower] and rounded to 0.001, the
    direction normalised, both written with a C++ stream's 6 significant digits."""
    p = min(max(power, 0.0), MAX_POWER)
    p = round(p * 1000.0) * 0.001
    return float(f"{p:.6g}"), float(f"{norm_deg(direction):.6g}")
