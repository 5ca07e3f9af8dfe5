"""HFO's team game (hfo2d.team): bin/HFO's rosters and limits, HFORef's placements and referee for teams, defense
actions (TACKLE, CATCH), the defense's view and rewards, seeds, rendering, and the Gymnasium / PettingZoo faces."""

from __future__ import annotations

import math
import pickle
import subprocess
import sys
import warnings

import gymnasium as gym
import numpy as np
import pytest

import hfo2d
from hfo2d import features as features_module
from hfo2d.features import (
    BALL_PROXIMITY,
    SELF_BODY_COS,
    SELF_BODY_SIN,
    SELF_FROZEN,
    hfo_num_features,
    num_features,
)
from hfo2d.protocol import CAPTURED_BY_DEFENSE, GOAL, IN_GAME, OFFENSE_OFFSETS, OUT_OF_TIME
from hfo2d.strikers import make_striker
from hfo2d.team import (
    DEFENDER_FLAT_ACTION_LAYOUT,
    GOALIE_FLAT_ACTION_LAYOUT,
    HalfFieldOffenseEnv,
    TeamGame,
    _reversed_body_deg,
    team_roster,
)


def _flat(layout, name: str, **units: float) -> np.ndarray:
    """A flat action of ``layout`` that plays ``name`` with the given parameters (units in [0, 1], in order)."""
    action = np.full(layout.size, 0.5, dtype=np.float32)
    action[: layout.n_discrete] = 0.0
    action[layout.names.index(name)] = 1.0
    for offset, value in enumerate(units.values()):
        action[layout.parameter_slice(layout.names.index(name)).start + offset] = value
    return action


def _idle(game: TeamGame) -> dict[str, np.ndarray]:
    """Every agent dashes with power 0 (no effect on the world)."""
    actions = {}
    for agent in game.agents:
        actions[agent.name] = _flat(agent.layout, "DASH", power=0.0, direction=0.5)
    return actions


# --------------------------------------------------------------------------------------------------------------
# Rosters: bin/Trainer.py's uniform numbers and bin/HFO's limits


@pytest.mark.parametrize(
    ("sizes", "offense", "defense_agents", "defense_npcs"),
    [
        ((1, 0, 0), (11,), (), ()),
        ((2, 0, 1), (7, 11), (), (1,)),
        ((4, 0, 5), (7, 8, 9, 11), (), (1, 2, 3, 4, 5)),
        ((1, 1, 0), (11,), (1,), ()),  # no NPC: the defense agent is unum 1, the goalie
        ((2, 2, 1), (7, 11), (2, 3), (1,)),  # agents take the largest unums, the NPC goalie keeps 1
        ((1, 1, 8), (11,), (11,), (1, 2, 3, 4, 5, 6, 7, 8)),  # 9 defenders: unums 1-8 and 11 (defenseOrder)
        ((10, 0, 0), (2, 3, 4, 5, 6, 7, 8, 9, 10, 11), (), ()),
    ],
)
def test_rosters_follow_trainer(sizes, offense, defense_agents, defense_npcs) -> None:
    roster = team_roster(*sizes)
    assert roster.offense_agents == offense
    assert roster.defense_agents == defense_agents
    assert roster.defense_npcs == defense_npcs


def test_agent_play_goalie_gives_the_agents_the_smallest_unums() -> None:
    roster = team_roster(1, 2, 3, agent_play_goalie=True)
    assert roster.defense_agents == (1, 2) and roster.defense_npcs == (3, 4, 5) and roster.goalie_is_agent
    # scripted strikers take the offense's unums after the agents'
    assert team_roster(1, 0, 1, offense_npcs=2).offense_npcs == (7, 8)
    # hfo2d's scripted strikers stand in those places; agent2d's offense NPCs are not ported
    game = TeamGame(1, 0, 1, scripted_strikers=2)
    assert [player.unum for player, _ in game.scripted_strikers] == [7, 8]
    with pytest.raises(ValueError, match="scripted_strikers=N"):
        TeamGame(1, 0, 1, offense_npcs=1)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"offense_agents": 11}, r"offense_agents must lie in \[0, 10\]"),
        ({"offense_agents": 0}, "offense needs 1 to 10"),
        ({"offense_agents": 6, "scripted_strikers": 5}, "1 to 10 players"),
        ({"offense_agents": 1, "striker": "lob"}, "unknown striker"),
        ({"defense_agents": 12}, r"defense_agents must lie in \[0, 11\]"),
        ({"defense_agents": 6, "defense_npcs": 6}, "at most 11"),
        ({"offense_agents": True}, "must be an integer"),
        ({"defense_npcs": 1.0}, "must be an integer"),
        ({"agent_play_goalie": True}, "needs a defense agent"),
    ],
)
def test_bad_team_sizes_are_value_errors(kwargs, message) -> None:
    with pytest.raises(ValueError, match=message):
        TeamGame(**kwargs)


def test_field_defender_npcs_need_the_defender_port(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "hfo2d.agent2d.defender", None)  # the port, absent
    with pytest.raises(ValueError, match=r"hfo2d\.agent2d\.defender\.Agent2dDefender"):
        TeamGame(1, 0, 2)
    with pytest.raises(
        ValueError, match="field defenders"
    ):  # with the agent as goalie, NPC unum 2 is a defender
        TeamGame(1, 1, 1, agent_play_goalie=True)
    TeamGame(1, 0, 1)  # the goalie alone needs no defender


# --------------------------------------------------------------------------------------------------------------
# Placement, referee, physics


def test_start_positions_follow_hforef() -> None:
    game = TeamGame(4, 4, 0, agent_play_goalie=True, seed=0)
    for seed in range(30):
        game.reset(seed=seed)
        ball = game.world.ball
        assert 0.0 <= ball.x <= 10.5 and abs(ball.y) <= 27.2
        for player in game.offense_players:
            # at rest, they have not moved since the placement (a rare overlap push is a few cm)
            assert -0.1 - 0.1 <= player.x <= 52.5 + 0.1 and abs(player.y) <= 27.2 + 0.1
        goalie = next(player for player in game.defense_players if player.goalie)
        assert (goalie.unum, goalie.x, goalie.y) == (1, 52.5, 0.0)
        for player in game.defense_players:
            if not player.goalie:
                assert 42.0 - 0.1 <= player.x <= 52.5 + 0.1 and abs(player.y) <= 27.2 + 0.1
        # each striker is at ball + 10.5 (U(0, 1) + offset) per axis, with HFO's ten offsets shuffled: the
        # unclamped ones reveal their offsets, all of them HFO's and no two the same
        offsets = []
        for player in game.offense_players:
            if -0.1 < player.x < 52.5 and abs(player.y) < 27.2:
                offsets.append(
                    (math.floor((player.x - ball.x) / 10.5), math.floor((player.y - ball.y) / 10.5))
                )
        assert set(offsets) <= set(OFFENSE_OFFSETS) and len(set(offsets)) == len(offsets), offsets


def test_server_order_offense_first_by_unum() -> None:
    game = TeamGame(3, 2, 1, seed=0)
    assert [(p.side, p.unum) for p in game.world.players] == [
        ("l", 7),
        ("l", 8),
        ("l", 11),
        ("r", 1),
        ("r", 2),
        ("r", 3),
    ]
    assert [(a.name, a.player.unum) for a in game.agents] == [
        ("offense_0", 7),
        ("offense_1", 8),
        ("offense_2", 11),
        ("defense_0", 2),
        ("defense_1", 3),
    ]


def test_a_field_defender_captures_after_two_cycles_and_the_goalie_at_once() -> None:
    game = TeamGame(1, 2, 0, seed=0)  # defense agents: unum 1 (goalie) and 2
    game.reset(seed=0)
    defender = game.agent("defense_1").player
    assert defender.unum == 2 and not defender.goalie
    game.world.place_ball(defender.x + 0.5, defender.y)
    statuses = []
    for _ in range(4):
        game.world.place_ball(defender.x + 0.5, defender.y)  # it keeps the ball by it
        *_, terminated, _, _ = game.step(_idle(game))
        statuses.append(game.status)
        if terminated:
            break
    # HFORef: take_time counts the cycles the defender is on the ball; >= 2 ends the episode the cycle after
    assert statuses == [IN_GAME, IN_GAME, CAPTURED_BY_DEFENSE]
    game.reset(seed=0)
    goalie = game.agent("defense_0").player
    game.world.place_ball(goalie.x - 0.6, goalie.y)
    game.step(_idle(game))
    assert game.status == CAPTURED_BY_DEFENSE


def test_goalie_agent_catches_and_a_field_defender_cannot() -> None:
    game = TeamGame(1, 2, 0, seed=0)
    game.reset(seed=0)
    goalie = game.agent("defense_0")
    assert (
        goalie.layout is GOALIE_FLAT_ACTION_LAYOUT
        and game.agent("defense_1").layout is DEFENDER_FLAT_ACTION_LAYOUT
    )
    # the ball 1.15 m in front of the goalie: outside kickable_area (1.085), inside the catch area (1.2 x 1)
    body = math.radians(goalie.player.body_deg)
    game.world.place_ball(goalie.player.x + 1.15 * math.cos(body), goalie.player.y + 1.15 * math.sin(body))
    actions = _idle(game)
    actions["defense_0"] = _flat(GOALIE_FLAT_ACTION_LAYOUT, "CATCH")
    _, rewards, terminated, _, infos = game.step(actions)
    assert infos["defense_0"]["action"] == "CATCH" and infos["defense_0"]["action_success"]
    assert (
        goalie.player.catch_ban == game.params.catch_ban_cycle - 1
    )  # the ban was set, one cycle counted down
    assert terminated and game.status == CAPTURED_BY_DEFENSE
    assert rewards["defense_0"] == rewards["defense_1"] == 1.0 and rewards["offense_0"] == 0.0
    with pytest.raises(
        ValueError, match=r"shape \(10,\)"
    ):  # no CATCH preference in a field defender's action
        game.reset(seed=0)
        game.step({**_idle(game), "defense_1": _flat(GOALIE_FLAT_ACTION_LAYOUT, "CATCH")})


def test_tackle_freezes_and_the_frozen_flag_shows_it() -> None:
    game = TeamGame(1, 1, 1, seed=0)  # defense_0 is a field defender (unum 2)
    game.reset(seed=0)
    agent = game.agent("defense_0")
    body = math.radians(agent.player.body_deg)
    game.world.place_ball(agent.player.x + 0.8 * math.cos(body), agent.player.y + 0.8 * math.sin(body))
    actions = _idle(game)
    actions["defense_0"] = _flat(DEFENDER_FLAT_ACTION_LAYOUT, "TACKLE", direction=0.5)
    observations, _, _, _, infos = game.step(actions)
    assert infos["defense_0"]["action"] == "TACKLE" and infos["defense_0"]["action_success"]
    assert agent.player.tackle_cycles == game.params.tackle_cycles - 1
    assert observations["defense_0"][SELF_FROZEN] == 1.0 and observations["offense_0"][SELF_FROZEN] == -1.0
    assert not game.episode_over
    # a frozen player's commands are refused: HFO's last action status is false, and the dash moves nothing
    actions["defense_0"] = _flat(DEFENDER_FLAT_ACTION_LAYOUT, "DASH", power=1.0, direction=0.5)
    x = agent.player.x
    _, _, _, _, infos = game.step(actions)
    assert not infos["defense_0"]["action_success"]
    assert abs(agent.player.x - x) < 0.05


def test_defense_agents_see_the_field_mirrored() -> None:
    game = TeamGame(1, 1, 0, seed=0)
    observations, _ = game.reset(seed=0)
    defender = game.agent("defense_0").player
    body = math.radians(defender.body_deg + 180.0)  # librcsc reverses a right-side player's body angle
    observation = observations["defense_0"]
    assert observation[SELF_BODY_SIN] == pytest.approx(math.sin(body), abs=1e-6)
    assert observation[SELF_BODY_COS] == pytest.approx(math.cos(body), abs=1e-6)
    # the ball's distance does not depend on the frame
    ball = game.world.ball
    distance = math.hypot(ball.x - defender.x, ball.y - defender.y)
    assert observation[BALL_PROXIMITY] == pytest.approx(1.0 - 2.0 * distance / 62.55, abs=1e-4)
    # HFO lists a player only at x > 0 in the observer's frame: in the defender's, the HFO half is x < 0
    assert not observation[num_features(0, 0) :].any()
    assert observations["offense_0"][num_features(0, 0) :].any()  # the striker sees the goalie


def test_a_defenders_body_angle_turns_round_as_librcsc_folds_it() -> None:
    # AngleDeg folds by 360 only beyond +-180: a body of 0 reads +180 (sin +1.2e-16, not -1.2e-16)
    assert [_reversed_body_deg(body) for body in (0.0, -180.0, 90.0, -90.0, 179.0)] == [
        180.0,
        0.0,
        -90.0,
        90.0,
        -1.0,
    ]


@pytest.mark.skipif(
    not hasattr(features_module, "high_level_feature_list"),
    reason="hfo2d.features has no high-level features",
)
def test_high_level_features_for_both_sides() -> None:
    game = TeamGame(2, 1, 1, feature_set="high_level", seed=0)
    observations, _ = game.reset(seed=0)
    for _ in range(3):
        for agent in game.agents:
            teammates, opponents = 1, 2  # 2v2: each agent has one teammate and two opponents
            assert agent.observation_space.shape == (
                features_module.high_level_num_features(teammates, opponents),
            )
            assert agent.observation_space.contains(observations[agent.name]), agent.name
        observations, *_ = game.step(_idle(game))
    # the defender's own x lies in the defense's (mirrored) range, the striker's in the offense's
    assert observations["defense_0"][0] < 0.0 < observations["offense_0"][0]


@pytest.mark.skipif(
    hasattr(features_module, "high_level_feature_list"), reason="hfo2d.features has the high-level features"
)
def test_high_level_features_need_their_port() -> None:
    with pytest.raises(ValueError, match="high_level_feature_list"):
        TeamGame(2, 0, 1, feature_set="high_level")


def test_collisions_between_defenders() -> None:
    game = TeamGame(1, 2, 0, seed=0)
    game.reset(seed=0)
    first, second = (agent.player for agent in game.agents[1:])
    game.world.place_player(first, 45.0, 10.0, 0.0)
    game.world.place_player(second, 45.3, 10.0, 180.0)
    game.step(_idle(game))
    assert first.collided_player and second.collided_player
    assert math.hypot(first.x - second.x, first.y - second.y) > 0.3


def test_one_striker_against_the_goalie_plays_as_keeper_v1() -> None:
    """From the same state, TeamGame(1, 0, 1) and HFO/Keeper-v1 play the same episode bit for bit."""
    for seed in (0, 1):
        game = TeamGame(1, 0, 1, noise=False, seed=seed)
        observations, _ = game.reset(seed=seed)
        env = gym.make("HFO/Keeper-v1", noise=False).unwrapped
        env.reset(seed=seed)
        env.world.place_ball(*(getattr(game.world.ball, name) for name in ("x", "y", "vx", "vy")))
        for source, target in zip(game.world.players, env.world.players, strict=True):
            env.world.place_player(target, source.x, source.y, source.body_deg, source.vx, source.vy)
        for npc_list, world, referee in (
            (env.defense_npcs, env.world, env.referee),
            (game.defense_npcs, game.world, game.referee),
        ):
            referee.reset(world)
            for _, npc in npc_list:
                npc.restart()
                npc.reset()
        striker = make_striker("soft_dribble")
        observation = observations["offense_0"]
        for _ in range(200):
            action = striker(observation)
            observations, rewards, terminated, truncated, _ = game.step({"offense_0": action})
            observation, reward, env_terminated, _, _ = env.step(action)
            np.testing.assert_array_equal(observations["offense_0"], observation)
            assert rewards["offense_0"] == reward and terminated == env_terminated
            if terminated or truncated:
                break
        assert game.status == env.status != IN_GAME


# --------------------------------------------------------------------------------------------------------------
# Seeds, rewards, spaces, errors


def _rollout(game: TeamGame, seed: int, steps: int = 60) -> list:
    observations, _ = game.reset(seed=seed)
    spaces_rng = {agent.name: agent.action_space for agent in game.agents}
    for offset, space in enumerate(spaces_rng.values()):
        space.seed(seed + offset)
    trace = [observations]
    for _ in range(steps):
        observations, rewards, terminated, truncated, _ = game.step(
            {name: space.sample() for name, space in spaces_rng.items()}
        )
        trace.append((observations, rewards, game.status))
        if terminated or truncated:
            break
    return trace


def test_reset_with_a_seed_repeats() -> None:
    game = TeamGame(2, 1, 1, seed=5)
    first = _rollout(game, 3)
    _rollout(game, 4)  # another episode in between: its carry-over must not leak into the seeded one
    again = _rollout(game, 3)
    fresh = _rollout(TeamGame(2, 1, 1, seed=99), 3)
    for run in (again, fresh):
        assert len(run) == len(first)
        for a, b in zip(first, run, strict=True):
            assert repr(a) == repr(b)
    assert repr(_rollout(game, 7)[0]) != repr(first[0])


def test_a_pickled_game_plays_on_the_same() -> None:
    game = TeamGame(2, 1, 1, scripted_strikers=1, seed=0)
    game.reset(seed=0)
    actions = {agent.name: np.full(agent.layout.size, 0.3, np.float32) for agent in game.agents}
    for _ in range(5):
        game.step(actions)
    copy = pickle.loads(pickle.dumps(game))
    for _ in range(30):
        ours, theirs = game.step(actions), copy.step(actions)
        assert repr(ours) == repr(theirs)
        if ours[2] or ours[3]:
            break


def test_spaces_and_feature_sets() -> None:
    game = TeamGame(2, 2, 1, feature_set="hfo", seed=0)
    observations, _ = game.reset(seed=0)
    for agent in game.agents:
        assert agent.observation_space.shape == (
            hfo_num_features(agent.offense and 1 or 2, agent.offense and 3 or 2),
        )
        assert agent.observation_space.contains(observations[agent.name])
    game = TeamGame(2, 1, 0, action_format="parameterized", seed=0)
    assert (
        len(game.agent("defense_0").action_space) == 5
    )  # Discrete(5), DASH, TURN, TACKLE, KICK boxes; CATCH none
    observations, _ = game.reset(seed=0)
    actions = {agent.name: agent.action_space.sample() for agent in game.agents}
    game.step(actions)
    with pytest.raises(ValueError, match="outside"):
        game.step(
            {**actions, "offense_0": (0, np.array([150.0, 0.0]), np.array([0.0]), np.array([0.0, 0.0]))}
        )


def test_step_errors_change_nothing() -> None:
    game = TeamGame(2, 0, 1, seed=0)
    with pytest.raises(RuntimeError, match="reset"):
        game.step({})
    game.reset(seed=0)
    state = repr(game.world.players)
    for actions, message in (
        ({"offense_0": np.zeros(8, np.float32)}, "missing"),
        ({**_idle(game), "defense_0": np.zeros(10)}, "unknown"),
        ({**_idle(game), "offense_1": np.full(8, np.nan)}, "not finite"),
        ({**_idle(game), "offense_1": np.zeros(7)}, r"shape \(8,\)"),
        ([], "dict"),
    ):
        with pytest.raises(ValueError, match=message):
            game.step(actions)
    assert repr(game.world.players) == state and game.steps == 0


def test_rewards_of_both_sides_on_a_goal() -> None:
    game = TeamGame(1, 1, 0, agent_play_goalie=True, reward="sparse", defense_reward="shaped", seed=0)
    game.reset(seed=0)
    game.world.place_ball(52.0, 20.0, 0.0, 0.0)
    game.world.place_player(game.agent("defense_0").player, 52.5, -20.0, 0.0)  # the goalie far from it
    game.world.place_ball(51.5, 0.0, 2.0, 0.0)  # rolling into the goal
    _, rewards, terminated, _, infos = game.step(_idle(game))
    assert terminated and game.status == GOAL
    assert rewards == {"offense_0": 1.0, "defense_0": -1.0}
    assert infos["offense_0"]["is_success"] and not infos["defense_0"]["is_success"]


def test_out_of_time_pays_the_defense() -> None:
    game = TeamGame(1, 1, 0, untouched_time=5, seed=0)
    game.reset(seed=0)
    game.world.place_ball(5.0, 0.0)
    for agent in game.agents:
        game.world.place_player(agent.player, 20.0 + 10.0 * (agent.name == "defense_0"), 20.0, 0.0)
    for _ in range(10):
        _, rewards, terminated, truncated, _ = game.step(_idle(game))
        if terminated or truncated:
            break
    assert game.status == OUT_OF_TIME and rewards["defense_0"] == 1.0 and rewards["offense_0"] == 0.0


# --------------------------------------------------------------------------------------------------------------
# Rendering, the Gymnasium env, the ParallelEnv


def test_render_draws_every_player() -> None:
    pytest.importorskip("pygame")
    from hfo2d.rendering import COLOR_DEFENSE, COLOR_GOALIE, COLOR_OFFENSE

    game = TeamGame(3, 2, 1, seed=0)
    game.reset(seed=0)
    frame = game.render("rgb_array")
    counts = [
        int(np.all(frame == np.array(color, np.uint8), axis=-1).sum())
        for color in (COLOR_OFFENSE, COLOR_DEFENSE, COLOR_GOALIE)
    ]
    assert all(count > 0 for count in counts), counts
    game.world.place_player(
        game.agent("offense_2").player, -30.0, 0.0, 0.0
    )  # off the drawn half: fewer pixels
    fewer = int(np.all(game.render("rgb_array") == np.array(COLOR_OFFENSE, np.uint8), axis=-1).sum())
    assert fewer < counts[0]
    game.close()


def test_gym_make_half_field_offense() -> None:
    env = gym.make("HFO/HalfFieldOffense-v0", offense_agents=1, defense_npcs=1)
    observation, info = env.reset(seed=0)
    assert observation.shape == (66,) and info["status"] == IN_GAME
    assert env.action_space.shape == (8,)
    assert (
        "## Version History" in HalfFieldOffenseEnv.__doc__
        and "## Episode End" in HalfFieldOffenseEnv.__doc__
    )
    goalie_env = gym.make("HFO/HalfFieldOffense-v0", offense_agents=0, defense_agents=1, scripted_strikers=1)
    observation, _ = goalie_env.reset(seed=0)
    assert goalie_env.action_space.shape == (11,) and observation.shape == (66,)
    with pytest.raises(ValueError, match="one learning agent"):
        gym.make("HFO/HalfFieldOffense-v0", offense_agents=2)
    with pytest.raises(ValueError, match="takes no options"):
        env.reset(options={"ball": (1.0, 2.0)})


def test_gym_env_seeds_repeat() -> None:
    env = gym.make("HFO/HalfFieldOffense-v0", offense_agents=1, defense_npcs=1)
    runs = []
    for _ in range(2):
        observation, _ = env.reset(seed=11)
        env.action_space.seed(0)
        trace = [observation]
        for _ in range(30):
            observation, reward, terminated, truncated, _ = env.step(env.action_space.sample())
            trace.append((observation, reward))
            if terminated or truncated:
                break
        runs.append(repr(trace))
    assert runs[0] == runs[1]


def test_parallel_env_passes_pettingzoo_api_test() -> None:
    pytest.importorskip("pettingzoo")
    from pettingzoo.test import parallel_api_test

    for kwargs in (
        {"offense_agents": 2, "defense_npcs": 1},
        {"offense_agents": 1, "defense_agents": 2, "feature_set": "hfo"},
    ):
        env = hfo2d.parallel_env(**kwargs, untouched_time=20)
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # the test's own complaints are warnings
            parallel_api_test(env, num_cycles=100)
    env = hfo2d.parallel_env(2, 1, 1)
    assert env.possible_agents == ["offense_0", "offense_1", "defense_0"]
    assert env.state().shape == (4 + 5 * 4,)
    with pytest.raises(ValueError, match="unknown backend"):
        hfo2d.parallel_env(backend="rcssserver")


def test_hfo2d_imports_without_pettingzoo() -> None:
    code = (
        "import sys; sys.modules['pettingzoo'] = None\n"
        "import gymnasium as gym, hfo2d\n"
        "gym.make('HFO/HalfFieldOffense-v0', defense_npcs=1).reset(seed=0)\n"
        "try:\n    hfo2d.parallel_env(2)\nexcept ImportError as error:\n    print(error)\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True
    )
    assert 'pip install -e ".[teams]"' in result.stdout


def test_a_game_of_npcs_alone_plays_to_the_end() -> None:
    """No learning agent: scripted strikers against agent2d's goalie, or an empty goal (scripted evaluations)."""
    statuses = []
    goalie_travel = 0.0
    for defense_npcs in (0, 1):
        game = TeamGame(0, 0, defense_npcs, scripted_strikers=1, seed=0)
        observations, infos = game.reset(seed=0)
        assert observations == {} and infos == {}
        for _ in range(10):
            for _ in range(500):
                _, rewards, terminated, truncated, _ = game.step({})
                for player, _npc in game.defense_npcs:
                    goalie_travel = max(goalie_travel, math.hypot(player.x - 52.5, player.y))
                if terminated or truncated:
                    break
            assert rewards == {} and game.status != IN_GAME
            statuses.append(game.status)
            game.reset()
    assert statuses[:10].count(GOAL) >= 9  # the dribbling striker hardly misses an empty goal
    assert goalie_travel > 1.0  # agent2d's goalie came out to meet it
