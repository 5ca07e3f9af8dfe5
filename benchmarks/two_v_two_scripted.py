"""What a second striker adds against agent2d's goalie *and* one field defender: 1v2 against 2v2, scripted.

Against agent2d's goalie alone (``two_v_one_scripted.py``) no scripted pair beats one ``soft_dribble`` striker: the
goalie leaves a good striker only a few points to win. Here the defense is bin/HFO's ``--defense-npcs 2`` (agent2d's
goalie, unum 1, and one agent2d field defender), which takes the ball from a lone dribbler in most episodes
(``team_fidelity.py``: ``soft_dribble`` scores 22.8 % in hfo2d and 22.7 % in real HFO). Teams (``--teams``), all
built from ``soft_dribble`` (:mod:`hfo2d.strikers`):

* ``alone``: one striker, 1v2;
* ``both``: two strikers that both go for the ball (no roles), 2v2;
* ``split``: the striker nearer the ball plays ``soft_dribble``; the other runs to a support spot
  ``SUPPORT_DEPTH`` metres goalward of the ball and ``SUPPORT_WIDTH`` metres out on the other side of the pitch's
  axis from it, and faces the ball there;
* ``pass``: ``split``, and the ball player passes to the supporter when the field defender nearest the ball is
  within ``PRESS_RANGE`` of it, the supporter is at least ``OPEN_MARGIN`` metres farther from that defender than
  the ball is, and no defender (the goalie included) is within ``LANE_CLEARANCE`` of the passing lane. The pass is
  sent to the supporter's feet at ``PASS_BASE_SPEED + PASS_SPEED_PER_METRE * distance``; until the ball is
  nearly still or kickable the receiver chases it and the passer stands; then the nearer striker plays on.
* ``own_pass``: ``pass`` decided by each striker from its own view alone, with no team memory
  (:meth:`ScriptedPair.own_command`): a ball seen on its way to it is chased, one on its way to the teammate left
  alone; otherwise the striker the ball is no farther from than from its teammate plays the ball (and passes by
  ``pass``'s rule), the other supports. This is the rule a learned pair could be routed by.

Every striker reads HFO master's low-level vector (``feature_set="hfo"``, which both backends give): its own
position, the ball and the goalie through :func:`hfo2d.strikers.goalie_view_from_hfo` (what ``soft_dribble``
reads alone), and the teammate and the field defenders from their blocks, told apart by their uniform-number
entries (:func:`read_team_view`). So a team acts on the same numbers in hfo2d and in a real HFO build, and the
team's choice of ball player is the two strikers' own distance estimates, as a shared team memory would give.

    python benchmarks/two_v_two_scripted.py --episodes 1000 --seed 2 --out ~/runs/twovtwo/s2.json
    HOME=/root HFO_DIR=/root/real_hfo/HFO tools/real_hfo/loopback.sh python benchmarks/two_v_two_scripted.py \\
        --backend real --episodes 1000 --seed 2 --teams alone pass --out ~/runs/twovtwo/real_s2.json
    python benchmarks/two_v_two_scripted.py --episodes 2 --out /tmp/two_v_two.json     # seconds: the smoke run

How the figures are used: benchmarks/README.md, "A second striker against the goalie and a field defender".
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

import hfo2d
from hfo2d import strikers
from hfo2d.features import (
    FEATURES_PER_PLAYER,
    NUM_BASIC_FEATURES,
    hfo_num_features,
    landmark_position,
    paper_from_hfo,
)

TEAMS: tuple[str, ...] = ("alone", "both", "split", "pass", "own_pass")
DEFENSE_NPCS = 2  # bin/HFO --defense-npcs 2: agent2d's goalie (unum 1) and one agent2d field defender
PRESS_RANGE = (
    5.0  # m; the nearest field defender this close to the ball makes the ball player look for the pass
)
OPEN_MARGIN = 3.0  # m; the supporter must be this much farther from that defender than the ball is
LANE_CLEARANCE = 1.5  # m; no defender (goalie included) this close to the segment ball -> supporter
SUPPORT_DEPTH = 2.0  # m goalward of the ball
SUPPORT_WIDTH = 13.0  # m from the pitch's long axis, on the side away from the ball
SUPPORT_X_RANGE = (30.0, 46.0)  # m; the support spot's x is kept in the attacking part of HFO's half
SPOT_TOLERANCE = 1.0  # m; nearer than this to its spot the supporter turns to the ball instead of running
#: a pass's speed: enough to arrive (rcssserver's ball decay 0.94 takes 6 % a cycle), at most 2.7 m/cycle
PASS_SPEED_PER_METRE, PASS_BASE_SPEED, PASS_MAX_SPEED = 0.06, 0.8, 2.7
RECEIVED_BALL_SPEED = 0.2  # m/cycle; a pass slower than this is over, and the nearer striker plays it
#: ``own_pass``: a ball faster than this (m/cycle) whose heading is within PASS_SEEN_ANGLE degrees of the line to a
#: striker more than PASS_SEEN_MIN_DISTANCE m away is read as a pass to that striker (passes arrive at about
#: PASS_BASE_SPEED; soft_dribble's touches go goalward, not across to the supporter)
PASS_SEEN_SPEED, PASS_SEEN_ANGLE, PASS_SEEN_MIN_DISTANCE = 0.5, 25.0, 1.5
#: ``own_pass``'s roles (:func:`own_pass_role`): play the ball (``soft_dribble``), pass it, run onto a pass, let a
#: pass to the teammate go by, support
ROLES: tuple[str, ...] = ("play", "pass", "receive", "wait", "support")
PLAY, PASS, RECEIVE, WAIT, SUPPORT = range(len(ROLES))


@dataclass(frozen=True)
class TeamView:
    """What one striker reads: its :class:`hfo2d.strikers.Percept` and the listed teammates and field defenders
    (global positions, metres)."""

    percept: strikers.Percept
    teammates: tuple[tuple[float, float], ...]
    field_defenders: tuple[tuple[float, float], ...]


def read_team_view(features: Sequence[float], num_teammates: int, num_opponents: int) -> TeamView:
    """A striker's view from HFO master's vector: the player blocks' body-frame offsets rotated into the global
    frame and added to its own position; the goalie (unum 1) is left to the percept; unlisted slots are skipped."""
    percept = strikers.perceive(strikers.goalie_view_from_hfo(features, num_teammates, num_opponents))
    paper = paper_from_hfo(features, num_teammates, num_opponents)
    players = num_teammates + num_opponents
    first_unum = hfo_num_features(num_teammates, num_opponents) - 1 - players
    body = math.radians(percept.body_deg)
    teammates: list[tuple[float, float]] = []
    defenders: list[tuple[float, float]] = []
    for slot in range(players):
        first = NUM_BASIC_FEATURES + FEATURES_PER_PLAYER * slot
        if paper[first] == 0.0 and paper[first + 1] == 0.0:
            continue  # nobody listed in this slot
        ahead, right = landmark_position(paper, first, first + 1, first + 2)
        position = (
            percept.x + ahead * math.cos(body) - right * math.sin(body),
            percept.y + ahead * math.sin(body) + right * math.cos(body),
        )
        if slot < num_teammates:
            teammates.append(position)
        elif round(float(features[first_unum + slot]) * 100.0) != strikers.GOALIE_UNUM:
            defenders.append(position)
    return TeamView(percept, tuple(teammates), tuple(defenders))


def _ball_heading_to(percept: strikers.Percept, x: float, y: float) -> bool:
    """Whether the ball moves toward (x, y), more than ``PASS_SEEN_MIN_DISTANCE`` away, within ``PASS_SEEN_ANGLE``."""
    dx, dy = x - percept.ball_x, y - percept.ball_y
    if math.hypot(dx, dy) <= PASS_SEEN_MIN_DISTANCE:
        return False
    off = math.degrees(math.atan2(percept.ball_vy, percept.ball_vx) - math.atan2(dy, dx))
    return abs((off + 180.0) % 360.0 - 180.0) < PASS_SEEN_ANGLE


def support_spot(percept: strikers.Percept) -> tuple[float, float]:
    """Where the supporter waits: ``SUPPORT_DEPTH`` goalward of the ball, ``SUPPORT_WIDTH`` out on the far side."""
    side = -1.0 if percept.ball_y > 0.0 else 1.0
    low, high = SUPPORT_X_RANGE
    return min(max(percept.ball_x + SUPPORT_DEPTH, low), high), side * SUPPORT_WIDTH


def _support(
    supporter: strikers.Percept, spot: tuple[float, float], ball: tuple[float, float]
) -> strikers.Command:
    """Run to ``spot``; once there, face ``ball`` (the ball where the striker that decides sees it)."""
    if math.hypot(supporter.x - spot[0], supporter.y - spot[1]) > SPOT_TOLERANCE:
        return strikers.move_to(supporter, *spot)
    return strikers.turn_to(supporter, *ball)


class ScriptedPair:
    """One of :data:`TEAMS` for one game: :meth:`act` maps the strikers' HFO-master vectors to flat actions."""

    def __init__(self, team: str) -> None:
        if team not in TEAMS:
            raise ValueError(f"unknown team {team!r}; choose one of {TEAMS}")
        self.team = team
        self.striker = strikers.make_striker("soft_dribble")
        self.receiver: int | None = None  # the striker a pass in flight is meant for
        self.passes = 0
        self.passed_this_episode = False
        self.passed_now = False  # whether the last _pass_or passed

    @property
    def striker_count(self) -> int:
        return 1 if self.team == "alone" else 2

    def reset(self) -> None:
        self.receiver = None
        self.passed_this_episode = False

    def act(self, observations: Sequence[np.ndarray]) -> list[np.ndarray]:
        views = [read_team_view(obs, self.striker_count - 1, DEFENSE_NPCS) for obs in observations]
        if self.team in ("alone", "both"):
            return [strikers.flat_action(self.striker.decide(view.percept)) for view in views]
        if self.team == "own_pass":
            return [strikers.flat_action(self.own_command(view)) for view in views]
        return [strikers.flat_action(command) for command in self.commands(views)]

    def commands(self, views: Sequence[TeamView]) -> list[strikers.Command]:
        """The two strikers' commands (``split`` and ``pass``)."""
        percepts = [view.percept for view in views]
        ball_speed = math.hypot(percepts[0].ball_vx, percepts[0].ball_vy)
        if self.receiver is not None and ball_speed < RECEIVED_BALL_SPEED:
            self.receiver = None
        if self.receiver is None:
            distances = [math.hypot(p.ball_x - p.x, p.ball_y - p.y) for p in percepts]
            ball_player = 0 if distances[0] <= distances[1] else 1
        else:
            ball_player = self.receiver
        player, mate = percepts[ball_player], percepts[1 - ball_player]
        commands = [strikers.idle(), strikers.idle()]
        if self.receiver is not None and not player.kickable:
            commands[ball_player] = strikers.chase_ball(player, *strikers.GOAL_CENTRE)
            return commands  # the passer stands while the pass is on its way
        self.receiver = None
        command = self.striker.decide(player)
        if self.team == "pass" and player.kickable:
            command = self._pass_or(command, views[ball_player], (mate.x, mate.y))
            if self.passed_now:
                self.receiver = 1 - ball_player
        commands[ball_player] = command
        if self.receiver is None:
            commands[1 - ball_player] = _support(mate, support_spot(player), (player.ball_x, player.ball_y))
        return commands

    def own_command(self, view: TeamView) -> strikers.Command:
        """``own_pass``: one striker's command from its own view alone, no team memory: the command of its role
        (:func:`own_pass_role`)."""
        role = own_pass_role(view)
        player = view.percept
        if role == PLAY:
            return self.striker.decide(player)
        if role == PASS:
            self.passes += 1
            self.passed_this_episode = True
            return pass_to(player, view.teammates[0])
        if role == RECEIVE:
            return strikers.chase_ball(player, *strikers.GOAL_CENTRE)
        if role == WAIT:
            return strikers.idle()
        return _support(player, support_spot(player), (player.ball_x, player.ball_y))

    def _pass_or(
        self, command: strikers.Command, view: TeamView, mate: tuple[float, float]
    ) -> strikers.Command:
        """A pass to the supporter at ``mate`` when :func:`pass_is_on` (``passed_now`` says whether it passed)."""
        self.passed_now = pass_is_on(view, mate)
        if not self.passed_now:
            return command
        self.passes += 1
        self.passed_this_episode = True
        return pass_to(view.percept, mate)


def pass_is_on(view: TeamView, mate: tuple[float, float]) -> bool:
    """``pass``'s rule for a ball player with the ball kickable: the nearest field defender presses (within
    ``PRESS_RANGE`` of the ball), the supporter at ``mate`` is ``OPEN_MARGIN`` farther from it, no defender (the
    goalie included) is within ``LANE_CLEARANCE`` of the lane, and nothing blocks the kick."""
    player = view.percept
    if not view.field_defenders:
        return False
    defender = min(view.field_defenders, key=lambda d: math.hypot(d[0] - player.ball_x, d[1] - player.ball_y))
    pressing = math.hypot(defender[0] - player.ball_x, defender[1] - player.ball_y)
    open_by = math.hypot(defender[0] - mate[0], defender[1] - mate[1]) - pressing
    blockers = list(view.field_defenders) + ([player.goalie] if player.goalie is not None else [])
    lane_clear = all(
        strikers.segment_distance(bx, by, player.ball_x, player.ball_y, *mate) > LANE_CLEARANCE
        for bx, by in blockers
    )
    return (
        pressing < PRESS_RANGE
        and open_by > OPEN_MARGIN
        and lane_clear
        and not strikers.kick_blocked(player, *mate)
    )


def pass_to(player: strikers.Percept, mate: tuple[float, float]) -> strikers.Command:
    """The pass to ``mate``'s feet, at a speed that grows with the distance."""
    distance = math.hypot(mate[0] - player.ball_x, mate[1] - player.ball_y)
    return strikers.kick_to(
        player, *mate, min(PASS_MAX_SPEED, PASS_BASE_SPEED + PASS_SPEED_PER_METRE * distance)
    )


def own_pass_role(view: TeamView) -> int:
    """``own_pass``'s role of one striker (one of :data:`ROLES`), from its own view alone: a ball seen on its way
    to it is chased (``RECEIVE``), one on its way to the teammate left alone (``WAIT``); otherwise the striker
    that the ball is no farther from than from its teammate plays the ball (``PASS`` when it is kickable and
    :func:`pass_is_on`, else ``PLAY``: ``soft_dribble``), the other supports (``SUPPORT``). A striker whose
    teammate HFO does not list (behind the halfway line) plays alone."""
    player = view.percept
    if not view.teammates:
        return PLAY
    mate = view.teammates[0]
    if not player.kickable and math.hypot(player.ball_vx, player.ball_vy) > PASS_SEEN_SPEED:
        if _ball_heading_to(player, player.x, player.y):
            return RECEIVE
        if _ball_heading_to(player, *mate):
            return WAIT
    mine = math.hypot(player.ball_x - player.x, player.ball_y - player.y)
    theirs = math.hypot(player.ball_x - mate[0], player.ball_y - mate[1])
    if mine <= theirs:
        return PASS if player.kickable and pass_is_on(view, mate) else PLAY
    return SUPPORT


def play(team_name: str, episodes: int, seed: int, backend: str = "hfo2d") -> dict[str, Any]:
    """``episodes`` episodes of one team from HFO's starts through ``hfo2d.parallel_env`` (hfo2d, or a real HFO
    build: ``HFO_DIR``, HFO's ``--seed`` from ``seed``, its first episode dropped as in ``team_fidelity.py``)."""
    from sb3_hfo.evaluation import goal_rate_summary  # as the other benchmarks report

    team = ScriptedPair(team_name)
    env = hfo2d.parallel_env(
        offense_agents=team.striker_count,
        defense_npcs=DEFENSE_NPCS,
        backend=backend,
        feature_set="hfo",
        reward="sparse",
    )
    dropped = 1 if backend == "real" else 0
    statuses: Counter[str] = Counter()
    after_a_pass: Counter[str] = Counter()
    cycles = 0
    started = time.time()
    try:
        for episode in range(episodes + dropped):
            observations, _ = env.reset(seed=seed if episode == 0 else None)
            team.reset()
            names = list(env.possible_agents)
            status = ""
            while env.agents:
                actions = dict(zip(names, team.act([observations[name] for name in names]), strict=True))
                observations, _, _, _, infos = env.step(actions)
                status = str(infos[names[0]]["status"])
                cycles += 1
            if episode >= dropped:
                statuses[status] += 1
                if team.passed_this_episode:
                    after_a_pass[status] += 1
    finally:
        env.close()
    return {
        "team": team_name,
        "backend": backend,
        **goal_rate_summary(statuses, episodes),
        "passes": team.passes,
        "episodes_with_a_pass": dict(after_a_pass),
        "cycles": cycles,
        "seconds": round(time.time() - started, 1),
        "load1": round(os.getloadavg()[0], 2),
    }


def main(argv: list[str] | None = None) -> dict[str, Any]:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--episodes", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--teams", nargs="+", default=list(TEAMS), choices=TEAMS)
    parser.add_argument(
        "--backend", default="hfo2d", choices=("hfo2d", "real"), help="real: HFO_DIR's HFO build"
    )
    parser.add_argument("--out", type=Path, required=True, help="the JSON file to write")
    args = parser.parse_args(argv)
    if args.episodes < 1:
        parser.error(f"--episodes must be >= 1, got {args.episodes}")
    record: dict[str, Any] = {
        "episodes": args.episodes,
        "seed": args.seed,
        "backend": args.backend,
        "striker": "soft_dribble",
        "defense_npcs": DEFENSE_NPCS,
        "results": {},
    }
    for name in args.teams:
        record["results"][name] = play(name, args.episodes, args.seed, args.backend)
        print(json.dumps(record["results"][name]), flush=True)
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(json.dumps(record, indent=1))
    return record


if __name__ == "__main__":
    main()
