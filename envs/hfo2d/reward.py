"""Rewards for HFO: Hausknecht & Stone's shaped reward as DQNHFO computes it, and the sparse goal reward.

Shaped (Hausknecht & Stone, ICLR 2016; computation of mhauskn/dqn-hfo, 2016, via hfo_reference §6.1-§6.2)::

    r_t = Δ ball_proximity + I_kick + 3 · (−Δ ball_to_goal) + 5 · I_goal

All distances are taken from the feature vector, in normalised feature units (1 m = 2 / 62.55 = 0.032 units):

* ``ball_dist = 1 − f[53]`` and ``goal_dist = 1 − f[15]`` (features are proximities ``1 − 2·d/62.55``);
* ``ball_to_goal = sqrt(ball_dist² + goal_dist² − 2·ball_dist·goal_dist·cos α)`` (law of cosines) with α the
  angle between the ball bearing (f[51], f[52]) and the goal-centre bearing (f[13], f[14]);
* ``move_to_ball`` = rise of the ball proximity f[53] since the previous step;
* ``kick_bonus`` = 1 the first time in an episode that the kickable flag f[12] jumps from −1 to +1;
* ``ball_to_goal`` = 3 × the fall of ``ball_to_goal`` since the previous step;
* ``goal`` = 5 on the GOAL step.

The delta terms (and the kickable jump) are 0 on an episode's first step and zeroed on its last step (any status
other than IN_GAME, truncation included), so a goal step pays exactly +5.

Version choice: the 2016 DQNHFO computation is used. DQNHFO's later HEAD (2016-03 on) also conditions the terms on
the server's "player on ball"; with a single offense player this changes the reward only while the keeper is the
player on ball, and that ends the episode at once (CAPTURED_BY_DEFENSE), so the extra machinery would buy nothing.
The Oct-2015 quirk of computing deltas from the state before the action (lagging one step) is not reproduced.

Shaped toward the gap (``"shaped_gap"``; not HFO's, an option of this package): the shaped reward with
``ball_to_goal`` measured to the middle of the wider gap between the goalie and a goal post instead of to the goal
centre, i.e. 3.5 m beside a goalie standing at the centre, on the ball's side when the gaps are equal (within
``GAP_TIE_TOLERANCE``). Without a goalie (or with its slot empty) it equals ``"shaped"``. Why: the goal-centre term
pays for moving the ball straight at a goalie on the goal line, and agents trained with it against the static
keeper shoot at him from close range (research/RESULTS.md). The target is computed from the
features alone (goal centre, posts, ball and goalie landmarks, all in the agent's body frame).

Shaped toward the gap, lost shots refunded (``"shaped_gap_refund"``; not HFO's, an option of this package):
``"shaped_gap"``, except that when an episode ends without a goal (terminated: CAPTURED_BY_DEFENSE, OUT_OF_BOUNDS,
or OUT_OF_TIME after 100 untouched cycles) its last step takes back the ball-to-gap progress paid since the ball
was last kickable by the agent. Progress the agent carried the ball through (dribbling) stays paid; a kick's
progress is kept only when it ends in a goal or the agent reaches the ball again. Why: under ``"shaped_gap"`` a
long shot into the keeper's arms collects most of an episode's shaping early, which a discount below 1 favours
over dribbling closer (research/RESULTS.md).

Carry (``"carry"``; not HFO's, an option of this package, research/e6_from_reward.md Part D)::

    r_t = Δ ball_proximity + I_kick + 3 · carry_record_t − 0.002 + 5 · I_goal

``move_to_ball``, ``kick_bonus`` and ``goal`` are the shaped reward's; the ball-to-goal term is replaced by
``ball_to_goal`` = 3 × the ball's *new record* of closeness to the goal centre, counted only on in-game steps where
the ball is within ``POSSESSION_RADIUS`` (2 m) of the agent: the first such step sets the record, and a later one
pays how far the ball-to-goal distance then lies below the record (and lowers the record). ``cycle_cost`` takes
0.002 on every step. Why each part (the E6 runs of Part B):

* a kick pays nothing until the agent is back on the ball, so a long shot (24-34 m, power ~100) that the full
  goalie catches earns nothing, while carrying the ball to the goal earns the whole ball-to-goal term; the
  scripted ``soft_dribble`` (hfo2d.strikers), which scores 92.6 % against agent2d's goalie in real HFO by keeping
  the ball within a few metres, collects it on most of its cycles;
* records only: moving the ball back and forth (or kicking it away and dribbling it back) pays nothing twice, so
  the term sums to at most 3 × the ball's start distance (about 3 for HFO's starts) and cannot be farmed;
* the goal centre, not the goalie gap, as the target: it is fixed, so a record stays a record when the goalie moves;
  ``soft_dribble`` also dribbles at the goal centre and aims only its shot at the far post;
* the cycle cost: under ``shaped_gap_refund`` holding the ball was free and the agent held it for ~420 cycles
  without shooting; 0.002 a cycle (at most 0.2 discounted with γ = 0.99) makes waiting cost a little, well below
  what a carried metre pays (0.096), and there is no penalty for a lost ball, which would make a shot that may
  fail worse than holding on;
* the goal stays 5 (DQNHFO's), more than the whole carry term: the last metres are worth less than a shot that
  scores.

The terms are ``move_to_ball``, ``kick_bonus``, ``ball_to_goal`` (the carry record), ``goal`` and ``cycle_cost``.

Carry and shoot (``"carry_shot"``; not HFO's, an option of this package, research/e6_from_reward.md Part E)::

    r_t = carry's r_t + 1 · shot_record_t

``"carry"`` plus a ``shot`` term, its twin for the last kick: 1 per m/cycle of the ball's *new record* speed on a
step that follows one where the ball was kickable, when the kick was taken within ``SHOT_RANGE`` (12 m) of the
goal centre and the ball's path (a straight line from the ball along its velocity) crosses the goal line between
the posts. Why: under ``"carry"`` two seeds of three carried the ball to 5-6 m from the goal and lost it to the
goalie for millions of steps without ever shooting; their kick-power deviation (one per head, the same in every
state) had shrunk to ~3 power units for the dribbling touches, so a shot (power 50-100) was a 10-30-sigma draw and
nothing near the goal paid a harder kick. Here a slightly harder kick at the goal pays at once (about 0.03 per
power unit), whether or not it scores. Records only: it sums to at most the fastest shot's speed (~3 per episode,
below the goal's 5), and a kick fast toward the goal pays once; ``soft_dribble``'s touches near the goal pay their
speed (~0.6) once, and its shot from 10-11 m ~2.6. The goalie's block is not read: a saved shot pays like a scored one, and the goal's 5 tells
them apart.

The terms are ``"carry"``'s and ``shot``.

Sparse: 1 on GOAL, else 0 (gym-soccer's Soccer-v0, hfo_reference §6.3).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Protocol

from hfo2d.features import (
    BALL_ANGLE_COS,
    BALL_ANGLE_SIN,
    BALL_PROXIMITY,
    BALL_SPEED,
    BALL_SPEED_MAX,
    BALL_VEL_ANGLE_COS,
    BALL_VEL_ANGLE_SIN,
    GOAL_CENTER_COS,
    GOAL_CENTER_PROXIMITY,
    GOAL_CENTER_SIN,
    GOAL_HALF_WIDTH,
    GOAL_POST_BOTTOM_COS,
    GOAL_POST_BOTTOM_PROXIMITY,
    GOAL_POST_BOTTOM_SIN,
    GOAL_POST_TOP_COS,
    GOAL_POST_TOP_PROXIMITY,
    GOAL_POST_TOP_SIN,
    GOALIE_ANGLE_COS,
    GOALIE_ANGLE_SIN,
    GOALIE_PROXIMITY,
    KICKABLE,
    MAX_HFO_DIST,
    SELF_BODY_COS,
    SELF_BODY_SIN,
    landmark_position,
)

REWARD_NAMES: tuple[str, ...] = ("shaped", "shaped_gap", "shaped_gap_refund", "carry", "carry_shot", "sparse")
#: The rewards that read the goalie's block (:func:`gap_target`: features 58-65, where HFO/Keeper-v1's layout has the
#: goalie). A team's layout puts the nearest teammate there, so a team env gives these rewards the 1v1 view of the
#: same state (the 58 basic features, then the goalie's block alone).
GOALIE_READING_REWARDS: tuple[str, ...] = ("shaped_gap", "shaped_gap_refund")
STATUS_IN_GAME = "IN_GAME"
STATUS_GOAL = "GOAL"

GOAL_REWARD = 5.0  # DQNHFO's EOT reward for the agent's own goal
KICK_BONUS = 1.0  # first time kickable in an episode
BALL_TO_GOAL_WEIGHT = 3.0  # outweighs the negative move-to-ball term once the kicked ball runs away
KICKABLE_JUMP = 1.0  # DQNHFO awards the bonus when the kickable feature rises by at least this much
SPARSE_GOAL_REWARD = 1.0
# m; gaps whose widths differ by less than this count as equal, and the ball's side picks the target
GAP_TIE_TOLERANCE = 0.5

REWARD_TERM_NAMES: tuple[str, ...] = ("move_to_ball", "kick_bonus", "ball_to_goal", "goal")

# The carry reward (module docstring): the ball counts as the agent's within this many metres of it. The kickable
# range is 1.085 m; a soft dribble's touch (0.6 m/cycle) keeps the ball within about 2 m while a shot (up to
# 3 m/cycle) leaves it in one cycle.
POSSESSION_RADIUS = 2.0
CARRY_WEIGHT = BALL_TO_GOAL_WEIGHT  # per feature unit of the ball-to-goal record (0.096 per metre)
CYCLE_COST = 0.002  # taken every step
CARRY_TERM_NAMES: tuple[str, ...] = (*REWARD_TERM_NAMES, "cycle_cost")
# The carry-and-shoot reward (module docstring): a kick counts as a shot when taken with the ball within this many
# metres of the goal centre. The stalled carry runs lost the ball at 5-6 m; seed 0's scoring shots left from ~5-6 m;
# the scripted soft_dribble (hfo2d.strikers; 93.8 % against agent2d's goalie) shoots from 9.5-11.5 m.
SHOT_RANGE = 12.0
# per m/cycle of the record shot speed: a full-power kick (~2.7 m/cycle) pays ~2.7, the goal 5
SHOT_WEIGHT = 1.0
CARRY_SHOT_TERM_NAMES: tuple[str, ...] = (*CARRY_TERM_NAMES, "shot")


class RewardFunction(Protocol):
    """What the env needs from a reward: reset at episode start, then one call per step; ``term_names`` are the keys
    of the terms each call returns (an env reports them all as 0 on its reset step)."""

    term_names: tuple[str, ...]

    def reset(self, features: Sequence[float] | None = None) -> None: ...

    def __call__(
        self, features: Sequence[float], status: str, terminated: bool | None = None
    ) -> tuple[float, dict[str, float]]: ...


def ball_to_goal_distance(features: Sequence[float]) -> float:
    """Ball-to-goal-centre distance in normalised feature units (2 units = 62.55 m), from the features alone.

    Law of cosines on the agent-ball and agent-goal sides, as DQNHFO does.
    """
    ball_dist = 1.0 - features[BALL_PROXIMITY]
    goal_dist = 1.0 - features[GOAL_CENTER_PROXIMITY]
    # cos(ball_bearing - goal_bearing) from the (sin, cos) pairs directly
    cos_alpha = (
        features[BALL_ANGLE_COS] * features[GOAL_CENTER_COS]
        + features[BALL_ANGLE_SIN] * features[GOAL_CENTER_SIN]
    )
    squared = ball_dist * ball_dist + goal_dist * goal_dist - 2.0 * ball_dist * goal_dist * cos_alpha
    return math.sqrt(squared) if squared > 0.0 else 0.0


def gap_target(features: Sequence[float]) -> tuple[float, float]:
    """Middle of the wider gap between the goalie and a goal post, in metres in the agent's body frame.

    The goal centre when there is no goalie slot (58 features) or the slot is empty (goalie at x <= 0).
    The goalie's offset along the goal mouth is clipped to the posts; equal gaps (within GAP_TIE_TOLERANCE) go to
    the ball's side.
    """
    centre_x, centre_y = landmark_position(features, GOAL_CENTER_SIN, GOAL_CENTER_COS, GOAL_CENTER_PROXIMITY)
    if len(features) <= GOALIE_PROXIMITY:
        return centre_x, centre_y
    goalie_sin, goalie_cos = features[GOALIE_ANGLE_SIN], features[GOALIE_ANGLE_COS]
    if goalie_sin * goalie_sin + goalie_cos * goalie_cos < 0.5:  # empty slot: all zeros
        return centre_x, centre_y
    top_x, top_y = landmark_position(features, GOAL_POST_TOP_SIN, GOAL_POST_TOP_COS, GOAL_POST_TOP_PROXIMITY)
    bottom_x, bottom_y = landmark_position(
        features, GOAL_POST_BOTTOM_SIN, GOAL_POST_BOTTOM_COS, GOAL_POST_BOTTOM_PROXIMITY
    )
    mouth_length = math.hypot(bottom_x - top_x, bottom_y - top_y)
    if mouth_length == 0.0:
        return centre_x, centre_y
    # unit vector along the goal mouth, top post -> bottom post
    along_x, along_y = (bottom_x - top_x) / mouth_length, (bottom_y - top_y) / mouth_length
    goalie_x, goalie_y = landmark_position(features, GOALIE_ANGLE_SIN, GOALIE_ANGLE_COS, GOALIE_PROXIMITY)
    goalie_offset = (goalie_x - centre_x) * along_x + (goalie_y - centre_y) * along_y
    goalie_offset = min(max(goalie_offset, -GOAL_HALF_WIDTH), GOAL_HALF_WIDTH)
    top_gap = goalie_offset + GOAL_HALF_WIDTH
    bottom_gap = GOAL_HALF_WIDTH - goalie_offset
    if abs(top_gap - bottom_gap) < GAP_TIE_TOLERANCE:
        ball_x, ball_y = landmark_position(features, BALL_ANGLE_SIN, BALL_ANGLE_COS, BALL_PROXIMITY)
        ball_offset = (ball_x - centre_x) * along_x + (ball_y - centre_y) * along_y
        towards_bottom = ball_offset >= 0.0
    else:
        towards_bottom = bottom_gap > top_gap
    if towards_bottom:
        target_offset = 0.5 * (goalie_offset + GOAL_HALF_WIDTH)
    else:
        target_offset = 0.5 * (goalie_offset - GOAL_HALF_WIDTH)
    return centre_x + target_offset * along_x, centre_y + target_offset * along_y


def ball_to_gap_distance(features: Sequence[float]) -> float:
    """Ball-to-``gap_target`` distance in normalised feature units (2 units = 62.55 m)."""
    ball_x, ball_y = landmark_position(features, BALL_ANGLE_SIN, BALL_ANGLE_COS, BALL_PROXIMITY)
    target_x, target_y = gap_target(features)
    return 2.0 * math.hypot(ball_x - target_x, ball_y - target_y) / MAX_HFO_DIST


class ShapedReward:
    """Hausknecht & Stone's shaped reward, DQNHFO's 2016 computation (see the module docstring)."""

    term_names = REWARD_TERM_NAMES

    distance_to_target = staticmethod(ball_to_goal_distance)
    #: take back, on a terminal step without a goal, the progress paid since the ball was last kickable
    refund_lost_progress = False

    def __init__(self) -> None:
        self._progress_since_kickable = 0.0
        self._previous_ball_proximity = 0.0
        self._previous_kickable = -1.0
        self._previous_ball_to_goal = 0.0
        self._first_step = True
        self._kick_bonus_paid = False

    def reset(self, features: Sequence[float] | None = None) -> None:
        """Start a new episode: the next call is a first step and the kick bonus is available again.

        ``features`` (the reset observation) is unused: DQNHFO pays no deltas on an episode's first step.
        """
        self._first_step = True
        self._kick_bonus_paid = False
        self._progress_since_kickable = 0.0

    def __call__(
        self, features: Sequence[float], status: str, terminated: bool | None = None
    ) -> tuple[float, dict[str, float]]:
        """Reward of the step that produced ``features`` and ended with ``status``.

        Args:
            features: the step's feature vector (58 or 66 values, feature units).
            status: the step's HFO status ("IN_GAME", "GOAL", ...).
            terminated: whether the episode ended for good (None: any status but IN_GAME); only the refund of
                ``refund_lost_progress`` uses it (a truncated episode is not refunded). The deltas end with any
                status but IN_GAME, truncation included, as in DQNHFO.

        Returns:
            (reward, terms) where terms maps each of REWARD_TERM_NAMES to its (weighted) share; they sum to reward.
        """
        ball_proximity = float(features[BALL_PROXIMITY])
        kickable = float(features[KICKABLE])
        ball_to_goal = self.distance_to_target(features)

        move_to_ball = 0.0
        kick_bonus = 0.0
        ball_to_goal_term = 0.0
        if not self._first_step and status == STATUS_IN_GAME:
            move_to_ball = ball_proximity - self._previous_ball_proximity
            ball_to_goal_term = BALL_TO_GOAL_WEIGHT * (self._previous_ball_to_goal - ball_to_goal)
            # DQNHFO's kick bonus: the kickable feature jumped from -1 to +1 and the episode has not been paid it
            if not self._kick_bonus_paid and kickable - self._previous_kickable >= KICKABLE_JUMP:
                kick_bonus = KICK_BONUS
                self._kick_bonus_paid = True
        if self.refund_lost_progress:
            if terminated is None:
                terminated = status != STATUS_IN_GAME
            if terminated and status != STATUS_GOAL:
                ball_to_goal_term = -self._progress_since_kickable
            # kickable > 0: the agent has the ball, and the progress so far is its own
            self._progress_since_kickable = (
                0.0 if kickable > 0.0 else self._progress_since_kickable + ball_to_goal_term
            )

        self._first_step = False
        self._previous_ball_proximity = ball_proximity
        self._previous_kickable = kickable
        self._previous_ball_to_goal = ball_to_goal
        # the reward and its REWARD_TERM_NAMES shares, the goal's paid when ``status`` is GOAL
        goal = GOAL_REWARD if status == STATUS_GOAL else 0.0
        terms = {
            "move_to_ball": move_to_ball,
            "kick_bonus": kick_bonus,
            "ball_to_goal": ball_to_goal_term,
            "goal": goal,
        }
        return move_to_ball + kick_bonus + ball_to_goal_term + goal, terms


class GapShapedReward(ShapedReward):
    """The shaped reward with ball progress measured toward ``gap_target`` (see the module docstring)."""

    distance_to_target = staticmethod(ball_to_gap_distance)


class RefundedGapShapedReward(GapShapedReward):
    """``shaped_gap`` that takes back a lost ball's progress since the agent last had it (module docstring)."""

    refund_lost_progress = True


class CarryReward:
    """Pays the ball's progress to the goal only as new records set while the agent has the ball (docstring)."""

    term_names = CARRY_TERM_NAMES

    def __init__(self) -> None:
        # supplies move_to_ball, kick_bonus and goal; its ball_to_goal is unused
        self._shaped = ShapedReward()
        self._record: float | None = None  # least ball-to-goal distance seen with the ball in possession

    def reset(self, features: Sequence[float] | None = None) -> None:
        """Start a new episode: no record yet, the kick bonus available again."""
        self._shaped.reset(features)
        self._record = None

    def __call__(
        self, features: Sequence[float], status: str, terminated: bool | None = None
    ) -> tuple[float, dict[str, float]]:
        """Reward of the step that produced ``features`` and ended with ``status`` (``terminated`` is unused: no
        term depends on how an episode without a goal ended).

        Returns:
            (reward, terms) with the terms of CARRY_TERM_NAMES; they sum to reward.
        """
        _, shaped_terms = self._shaped(features, status, terminated)
        carry = 0.0
        ball_distance_m = (1.0 - float(features[BALL_PROXIMITY])) * 0.5 * MAX_HFO_DIST
        if status == STATUS_IN_GAME and ball_distance_m <= POSSESSION_RADIUS:
            ball_to_goal = ball_to_goal_distance(features)
            if self._record is None:
                self._record = ball_to_goal  # the first touch sets the baseline and pays nothing
            elif ball_to_goal < self._record:
                carry = CARRY_WEIGHT * (self._record - ball_to_goal)
                self._record = ball_to_goal
        terms = {
            "move_to_ball": shaped_terms["move_to_ball"],
            "kick_bonus": shaped_terms["kick_bonus"],
            "ball_to_goal": carry,
            "goal": shaped_terms["goal"],
            "cycle_cost": -CYCLE_COST,
        }
        return sum(terms.values()), terms


def shot_speed_at_goal(features: Sequence[float]) -> float:
    """The ball's speed (m/cycle) when its straight path crosses the goal line between the posts, else 0.

    From the features alone: the ball's body-frame position (features 51-53), its speed (55) and global heading
    (56, 57) turned into the body frame by the global body angle (5, 6), and the posts (16-21).
    """
    scaled_speed = float(features[BALL_SPEED])
    speed = BALL_SPEED_MAX if scaled_speed >= 1.0 else (scaled_speed + 1.0) * 0.5 * BALL_SPEED_MAX
    if speed <= 0.0:
        return 0.0
    ball_x, ball_y = landmark_position(features, BALL_ANGLE_SIN, BALL_ANGLE_COS, BALL_PROXIMITY)
    # heading relative to the body: sin/cos of (velocity heading - body angle)
    vel_sin, vel_cos = float(features[BALL_VEL_ANGLE_SIN]), float(features[BALL_VEL_ANGLE_COS])
    body_sin, body_cos = float(features[SELF_BODY_SIN]), float(features[SELF_BODY_COS])
    direction_x = vel_cos * body_cos + vel_sin * body_sin
    direction_y = vel_sin * body_cos - vel_cos * body_sin
    top_x, top_y = landmark_position(features, GOAL_POST_TOP_SIN, GOAL_POST_TOP_COS, GOAL_POST_TOP_PROXIMITY)
    bottom_x, bottom_y = landmark_position(
        features, GOAL_POST_BOTTOM_SIN, GOAL_POST_BOTTOM_COS, GOAL_POST_BOTTOM_PROXIMITY
    )
    # ball + t * direction = top + s * (bottom - top), solved for t (ahead: t > 0) and s (between the posts)
    post_x, post_y = bottom_x - top_x, bottom_y - top_y
    determinant = direction_x * (-post_y) + direction_y * post_x
    if abs(determinant) < 1e-9:  # parallel to the goal line
        return 0.0
    offset_x, offset_y = top_x - ball_x, top_y - ball_y
    ahead = (offset_x * (-post_y) + offset_y * post_x) / determinant
    along = (direction_x * offset_y - direction_y * offset_x) / determinant
    return speed if ahead > 0.0 and 0.0 <= along <= 1.0 else 0.0


class CarryShotReward(CarryReward):
    """``carry`` plus a record of the shot speed at the goal mouth, for kicks taken near the goal (docstring)."""

    term_names = CARRY_SHOT_TERM_NAMES

    def __init__(self) -> None:
        super().__init__()
        self._shot_record = 0.0  # fastest qualifying shot of the episode, m/cycle
        self._previous_kickable = False
        self._previous_ball_to_goal_m = math.inf

    def reset(self, features: Sequence[float] | None = None) -> None:
        """Start a new episode: no carry or shot record, the kick bonus available again."""
        super().reset(features)
        self._shot_record = 0.0
        self._previous_kickable = features is not None and float(features[KICKABLE]) > 0.0
        self._previous_ball_to_goal_m = (
            math.inf if features is None else ball_to_goal_distance(features) * 0.5 * MAX_HFO_DIST
        )

    def __call__(
        self, features: Sequence[float], status: str, terminated: bool | None = None
    ) -> tuple[float, dict[str, float]]:
        """Reward of the step that produced ``features`` and ended with ``status``.

        Returns:
            (reward, terms) with the terms of CARRY_SHOT_TERM_NAMES; they sum to reward.
        """
        _, terms = super().__call__(features, status, terminated)
        shot = 0.0
        # a kick of the last step: the ball was kickable before it, and close enough to the goal to be a shot
        if (
            status == STATUS_IN_GAME
            and self._previous_kickable
            and self._previous_ball_to_goal_m <= SHOT_RANGE
        ):
            speed = shot_speed_at_goal(features)
            if speed > self._shot_record:
                shot = SHOT_WEIGHT * (speed - self._shot_record)
                self._shot_record = speed
        self._previous_kickable = float(features[KICKABLE]) > 0.0
        self._previous_ball_to_goal_m = ball_to_goal_distance(features) * 0.5 * MAX_HFO_DIST
        terms["shot"] = shot
        return sum(terms.values()), terms


class SparseReward:
    """1 on GOAL, 0 otherwise."""

    term_names = REWARD_TERM_NAMES

    def reset(self, features: Sequence[float] | None = None) -> None:
        """Nothing to forget between episodes."""

    def __call__(
        self, features: Sequence[float], status: str, terminated: bool | None = None
    ) -> tuple[float, dict[str, float]]:
        """Reward of a step: ``(1.0 if status == "GOAL" else 0.0, terms)``; ``features`` is unused."""
        goal = SPARSE_GOAL_REWARD if status == STATUS_GOAL else 0.0
        return goal, {"move_to_ball": 0.0, "kick_bonus": 0.0, "ball_to_goal": 0.0, "goal": goal}


def make_reward(name: str) -> RewardFunction:
    """The reward called ``name`` (one of REWARD_NAMES); ValueError naming the choices otherwise."""
    if name == "shaped":
        return ShapedReward()
    if name == "shaped_gap":
        return GapShapedReward()
    if name == "shaped_gap_refund":
        return RefundedGapShapedReward()
    if name == "carry":
        return CarryReward()
    if name == "carry_shot":
        return CarryShotReward()
    if name == "sparse":
        return SparseReward()
    raise ValueError(f"unknown reward {name!r}; choose one of {REWARD_NAMES}")
