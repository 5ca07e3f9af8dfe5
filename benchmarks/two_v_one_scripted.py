"""What a second striker can add in HFO's 2v1 against agent2d's goalie, with scripted strikers (issue 34 item 5).

The learned 2v1 of ``two_v_one.py`` has to beat one striker alone. This script asks, without any learning, whether
two strikers *can* do better than one here: each team below is built from the hand-written ``soft_dribble``
striker (:mod:`hfo2d.strikers`, 92.6 % alone in real HFO), plays ``--episodes`` hfo2d games from HFO's starts
(``hfo2d.team.TeamGame``, noise on, agent2d's goalie), and reports the goal rate with its 95 % Wilson interval and
the end statuses. Teams (``--teams``; in every two-striker team the striker nearer the ball plays ``soft_dribble``):

* ``alone``: one ``soft_dribble`` striker, the 1v1 game (``TeamGame(1, 0, 1)``);
* ``both``: two ``soft_dribble`` strikers that both go for the ball (no roles);
* ``support``: the other striker runs to a spot in front of the far post (``SUPPORT_SPOT``, on the side of the post
  ``soft_dribble`` aims at) and waits there facing the ball;
* ``tap_in``: ``support``, and while a shot is in flight toward a point outside the posts the supporter steps onto the
  ball's line and, once the ball is kickable, shoots it at the far post (the lone striker's misses are mostly such
  wide shots: see the module's findings in benchmarks/README.md);
* ``pass``: ``support``, and the ball player passes to the supporter when the goalie is within ``PASS_GOALIE_RANGE``
  of the ball, the passing lane is clear of it by ``PASS_LANE_CLEARANCE`` and the supporter is within
  ``PASS_RECEIVER_RANGE`` of the goal centre; the receiver, now nearer the ball, plays ``soft_dribble`` (a shot from
  there);
* ``screen``: the other striker screens the goalie: it runs to a point ``SCREEN_GAP`` from the goalie on the line
  toward the post the ball player aims at, then keeps dashing into the goalie, so that rcssserver's player-player
  collisions (both pushed apart, both velocities times -0.1) hold the goalie back from that post.

The strikers read their own paper features with the teammate's block removed (what ``soft_dribble`` reads alone);
the team picks the ball player from both strikers' estimates of their distance to the ball, as a shared team
memory would. How the figures are used: benchmarks/README.md, "Two strikers against agent2d's goalie".

    python benchmarks/two_v_one_scripted.py --episodes 1000 --out ~/runs/twovone3/scripted.json
    HOME=/root HFO_DIR=/root/real_hfo/HFO tools/real_hfo/loopback.sh \\
        python benchmarks/two_v_one_scripted.py --backend real --teams alone tap_in --out ~/runs/twovone3/real.json
    python benchmarks/two_v_one_scripted.py --episodes 3 --out /tmp/scripted.json   # seconds: what the test runs
    python benchmarks/two_v_one_scripted.py --teams pass --pass-goalie-range 4.5 --pass-lane-clearance 1.5 \\
        --support-spot 46 4 --out ~/runs/twovone6/pass_sweep/g4.5_l1.5_46_4.json       # one point of the pass sweep
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time
from collections import Counter
from pathlib import Path
from typing import Any

import numpy as np

from hfo2d import strikers
from hfo2d.features import FEATURES_PER_PLAYER, NUM_BASIC_FEATURES
from hfo2d.team import TeamGame

TEAMS: tuple[str, ...] = ("alone", "both", "support", "tap_in", "pass", "screen")
#: m; where the supporter waits: (x, |y|), y on the side of the post soft_dribble aims at (the far post from the
#: goalie); 2 m in front of the goal line and 1.5 m outside the post (HFO's goal half-width is 7.01 m)
SUPPORT_SPOT = (50.5, 8.5)
SPOT_TOLERANCE = 1.0  # m; closer than this to its spot the supporter turns to the ball instead of running
GOAL_LINE_X = 52.5  # m, rcssserver's pitch half-length
#: m; a ball heading for the goal line beyond this |y| is going wide (the post at 7.01 m, less a ball's margin)
WIDE_SHOT_Y = 6.7
SHOT_IN_FLIGHT_SPEED = (
    1.2  # m/cycle; a ball faster than this after the ball player's kick is a shot in flight
)
PASS_GOALIE_RANGE = 7.0  # m from the ball
PASS_LANE_CLEARANCE = 2.5  # m from the goalie to the ball-receiver segment
PASS_RECEIVER_RANGE = 16.0  # m from the goal centre
PASS_ZONE = 22.0  # m; passes only with the ball this close to the goal centre
#: a pass's speed: enough to arrive (rcssserver's ball decay 0.94 takes 6 % a cycle), at most 2.7 m/cycle
PASS_SPEED_PER_METRE, PASS_BASE_SPEED, PASS_MAX_SPEED = 0.06, 0.6, 2.7
#: m; where the screen stands: this far from the goalie toward the far post (two players' radii of 0.3 m plus a
#: little, so that its dash into the goalie collides at once)
SCREEN_GAP = 0.7
SCREEN_TOLERANCE = 0.4  # m; nearer than this to its point the screen dashes into the goalie
TEAMMATE_BLOCK = np.arange(NUM_BASIC_FEATURES, NUM_BASIC_FEATURES + FEATURES_PER_PLAYER)


class ScriptedTeam:
    """One of :data:`TEAMS` for one game: :meth:`act` maps the strikers' observations to their flat actions."""

    def __init__(
        self,
        team: str,
        pass_goalie_range: float = PASS_GOALIE_RANGE,
        pass_lane_clearance: float = PASS_LANE_CLEARANCE,
        support_spot: tuple[float, float] = SUPPORT_SPOT,
    ) -> None:
        if team not in TEAMS:
            raise ValueError(f"unknown team {team!r}; choose one of {TEAMS}")
        self.team = team
        self.pass_goalie_range, self.pass_lane_clearance = pass_goalie_range, pass_lane_clearance
        self.support_spot = support_spot
        self.striker = strikers.make_striker("soft_dribble")
        self.shooter: int | None = None  # the striker whose kick is in flight
        self.passes = 0
        self.taps = 0

    @property
    def striker_count(self) -> int:
        return 1 if self.team == "alone" else 2

    def reset(self) -> None:
        self.shooter = None

    def act(self, observations: list[np.ndarray]) -> list[np.ndarray]:
        percepts = [
            strikers.perceive(np.delete(obs, TEAMMATE_BLOCK) if len(observations) > 1 else obs)
            for obs in observations
        ]
        if self.team == "alone":
            return [strikers.flat_action(self.striker.decide(percepts[0]))]
        distances = [math.hypot(p.ball_x - p.x, p.ball_y - p.y) for p in percepts]
        ball_player = 0 if distances[0] <= distances[1] else 1
        return [strikers.flat_action(command) for command in self.commands(percepts, ball_player)]

    def commands(self, percepts: list[strikers.Percept], ball_player: int) -> list[strikers.Command]:
        """The two strikers' commands, ``ball_player`` being the one nearer the ball."""
        if self.team == "both":
            return [self.striker.decide(percept) for percept in percepts]
        player, mate = percepts[ball_player], percepts[1 - ball_player]
        spot = self._spot(player, self.support_spot)
        in_flight = math.hypot(player.ball_vx, player.ball_vy) > SHOT_IN_FLIGHT_SPEED
        if self.team == "tap_in":
            for index, percept in enumerate(percepts):
                if percept.kickable and in_flight and index == self._supporter():
                    self.taps += 1
                    self.shooter = index
                    shot = strikers.kick_to(percept, *strikers.far_post(percept, 1.0), strikers.SHOT_SPEED)
                    return [shot, strikers.idle()] if index == 0 else [strikers.idle(), shot]
            if in_flight and self.shooter is not None:
                supporter = 1 - self.shooter
                commands: list[strikers.Command] = [strikers.idle(), strikers.idle()]
                commands[supporter] = self._onto_wide_shot(percepts[supporter], spot)
                return commands
            self.shooter = ball_player if player.kickable else (self.shooter if in_flight else None)
        command = self.striker.decide(player)
        if self.team == "pass" and player.kickable:
            command = self._pass_or(command, player, mate)
        commands = [strikers.idle(), strikers.idle()]
        commands[ball_player] = command
        if self.team == "screen" and mate.goalie is not None:
            commands[1 - ball_player] = self._screen(player, mate)
        else:
            commands[1 - ball_player] = self._hold(mate, spot)
        return commands

    @staticmethod
    def _screen(player: strikers.Percept, mate: strikers.Percept) -> strikers.Command:
        """Stand ``SCREEN_GAP`` from the goalie toward the post the ball player aims at, then push into the goalie."""
        assert mate.goalie is not None
        goalie_x, goalie_y = mate.goalie
        post_x, post_y = strikers.far_post(player, 0.0)
        length = math.hypot(post_x - goalie_x, post_y - goalie_y) or 1.0
        point = (
            goalie_x + (post_x - goalie_x) / length * SCREEN_GAP,
            goalie_y + (post_y - goalie_y) / length * SCREEN_GAP,
        )
        if math.hypot(mate.x - point[0], mate.y - point[1]) > SCREEN_TOLERANCE:
            return strikers.move_to(mate, *point)
        return strikers.move_to(mate, goalie_x, goalie_y)

    def _supporter(self) -> int | None:
        return None if self.shooter is None else 1 - self.shooter

    @staticmethod
    def _spot(
        player: strikers.Percept, support_spot: tuple[float, float] = SUPPORT_SPOT
    ) -> tuple[float, float]:
        """The supporter's spot, on the side of the post the ball player aims at."""
        if player.goalie is not None:
            side = 1.0 if strikers.far_post(player, 0.0)[1] > 0.0 else -1.0
        else:
            side = -1.0 if player.ball_y > 0.0 else 1.0
        return support_spot[0], side * support_spot[1]

    @staticmethod
    def _hold(percept: strikers.Percept, spot: tuple[float, float]) -> strikers.Command:
        if math.hypot(percept.x - spot[0], percept.y - spot[1]) > SPOT_TOLERANCE:
            return strikers.move_to(percept, *spot)
        return strikers.turn_to(percept, percept.ball_x, percept.ball_y)

    def _onto_wide_shot(self, percept: strikers.Percept, spot: tuple[float, float]) -> strikers.Command:
        """Step onto the line of a shot that will miss the goal, ahead of the ball; else hold the spot."""
        vx, vy = percept.ball_vx, percept.ball_vy
        if vx > 0.1:
            crossing_y = percept.ball_y + vy * (GOAL_LINE_X - percept.ball_x) / vx
            if abs(crossing_y) > WIDE_SHOT_Y:
                ahead = ((percept.x - percept.ball_x) * vx + (percept.y - percept.ball_y) * vy) / (
                    vx * vx + vy * vy
                )
                ahead = max(ahead, 1.0)
                target = (percept.ball_x + vx * ahead, percept.ball_y + vy * ahead)
                if math.hypot(percept.x - target[0], percept.y - target[1]) > 0.5:
                    return strikers.move_to(percept, *target)
                return strikers.turn_to(percept, percept.ball_x, percept.ball_y)
        return self._hold(percept, spot)

    def _pass_or(
        self, command: strikers.Command, player: strikers.Percept, mate: strikers.Percept
    ) -> strikers.Command:
        """A pass to the supporter when the goalie closes on the ball and the lane is clear, else ``command``."""
        if player.goalie is None:
            return command
        goalie_x, goalie_y = player.goalie
        if (
            math.hypot(goalie_x - player.ball_x, goalie_y - player.ball_y) < self.pass_goalie_range
            and player.ball_goal_dist < PASS_ZONE
            and math.hypot(strikers.GOAL_CENTRE[0] - mate.x, strikers.GOAL_CENTRE[1] - mate.y)
            < PASS_RECEIVER_RANGE
            and strikers.segment_distance(goalie_x, goalie_y, player.ball_x, player.ball_y, mate.x, mate.y)
            > self.pass_lane_clearance
            and not strikers.kick_blocked(player, mate.x, mate.y)
        ):
            distance = math.hypot(mate.x - player.ball_x, mate.y - player.ball_y)
            self.passes += 1
            speed = min(PASS_MAX_SPEED, PASS_SPEED_PER_METRE * distance + PASS_BASE_SPEED)
            return strikers.kick_to(player, mate.x, mate.y, speed)
        return command


def play(team_name: str, episodes: int, seed: int, backend: str = "hfo2d", **settings: Any) -> dict[str, Any]:
    """``episodes`` episodes of one scripted team from HFO's starts: in hfo2d (the game seeded once with ``seed``)
    or in a real HFO build (``backend="real"``: ``hfo2d.parallel_env``, HFO's ``--seed`` from ``seed``);
    ``settings`` go to :class:`ScriptedTeam` (the pass and the supporter's spot)."""
    from sb3_hfo.evaluation import goal_rate_summary  # as the other benchmarks report

    team = ScriptedTeam(team_name, **settings)
    if backend == "hfo2d":
        game: Any = TeamGame(team.striker_count, 0, 1, seed=seed)
    else:
        import hfo2d

        game = hfo2d.parallel_env(offense_agents=team.striker_count, defense_npcs=1, backend=backend)
    names = list(game.agent_names if backend == "hfo2d" else game.possible_agents)
    statuses: Counter[str] = Counter()
    cycles = wide_of_goal = 0
    started = time.time()
    observations, _ = game.reset(seed=seed)
    try:
        for _ in range(episodes):
            team.reset()
            while True:
                actions = dict(zip(names, team.act([observations[name] for name in names]), strict=True))
                observations, _, terminated, truncated, infos = game.step(actions)
                cycles += 1
                ended = (
                    (terminated or truncated)
                    if backend == "hfo2d"
                    else any(terminated.values()) or any(truncated.values())
                )
                if ended:
                    status = str(infos[names[0]]["status"])
                    statuses[status] += 1
                    ball = infos[names[0]].get("ball")  # hfo2d's true state; the real backend has none
                    if status == "OUT_OF_BOUNDS" and ball is not None and ball[0] > GOAL_LINE_X:
                        wide_of_goal += 1  # out over the goal line: a shot that missed
                    observations, _ = game.reset()
                    break
    finally:
        if backend != "hfo2d":
            game.close()
    return {
        "team": team_name,
        "backend": backend,
        **goal_rate_summary(statuses, episodes),
        "out_over_goal_line": wide_of_goal if backend == "hfo2d" else None,
        "passes": team.passes,
        "tap_ins_tried": team.taps,
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
    parser.add_argument(
        "--pass-goalie-range",
        type=float,
        default=PASS_GOALIE_RANGE,
        help="m; pass: the goalie this near the ball",
    )
    parser.add_argument(
        "--pass-lane-clearance",
        type=float,
        default=PASS_LANE_CLEARANCE,
        help="m; pass: the goalie this far from the lane",
    )
    parser.add_argument(
        "--support-spot",
        type=float,
        nargs=2,
        default=SUPPORT_SPOT,
        metavar=("X", "ABS_Y"),
        help="m; where the supporter waits (support, tap_in, pass)",
    )
    args = parser.parse_args(argv)
    if args.episodes < 1:
        parser.error(f"--episodes must be >= 1, got {args.episodes}")
    if args.pass_goalie_range <= 0 or args.pass_lane_clearance < 0:
        parser.error("--pass-goalie-range must be > 0 and --pass-lane-clearance >= 0")
    if not (0.0 < args.support_spot[0] <= GOAL_LINE_X and 0.0 <= args.support_spot[1] <= 34.0):
        parser.error(
            f"--support-spot X ABS_Y must lie in the offense half (0 < X <= 52.5, 0 <= ABS_Y <= 34), got {args.support_spot}"
        )
    settings = {
        "pass_goalie_range": args.pass_goalie_range,
        "pass_lane_clearance": args.pass_lane_clearance,
        "support_spot": (args.support_spot[0], args.support_spot[1]),
    }
    results = {}
    for name in args.teams:
        results[name] = play(name, args.episodes, args.seed, args.backend, **settings)
        print(json.dumps(results[name]), flush=True)
    record = {
        "episodes": args.episodes,
        "seed": args.seed,
        "backend": args.backend,
        "striker": "soft_dribble",
        **settings,
    }
    record["results"] = results
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(record, indent=1))
    return record


if __name__ == "__main__":
    main()
