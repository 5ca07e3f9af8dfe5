"""sb3_hfo.multi_agent's frozen opponents: one side of HFO team games learns while a fixed policy plays the other
(TeamVecEnv(opponent=...), make_team_vec_env(opponent=...)), and play_matches between two fixed sides."""

from __future__ import annotations

import numpy as np
import pytest

from hfo2d.strikers import make_striker
from hfo2d.team import TeamGame
from sb3_hfo.hybrid_ppo import HybridPPO
from sb3_hfo.multi_agent import FrozenOpponent, TeamVecEnv, make_team_vec_env, play_matches

GOALIE_ACTION_SIZE = 11  # 5 preferences (DASH, TURN, TACKLE, KICK, CATCH), then 6 parameters


class _ScriptedBatch:
    """A batched opponent made of per-observation scripted strikers, recording the batches it was given."""

    def __init__(self) -> None:
        self.striker = make_striker("soft_dribble")
        self.batches: list[np.ndarray] = []

    def __call__(self, observations: np.ndarray) -> np.ndarray:
        self.batches.append(observations.copy())
        return np.stack([self.striker(observation) for observation in observations])


def _still_goalie(observations: np.ndarray) -> np.ndarray:
    actions = np.zeros((len(observations), GOALIE_ACTION_SIZE), dtype=np.float32)
    actions[:, 0] = 1.0  # DASH at power 0: the goalie stands
    return actions


def test_the_opponent_plays_the_other_side_in_one_call_per_step() -> None:
    opponent = _ScriptedBatch()
    env = make_team_vec_env(
        3, offense_agents=1, defense_agents=1, side="defense", opponent=opponent, seed=0, monitor=False
    )
    assert env.num_envs == 3 and env.slots == [(0, "defense_0"), (1, "defense_0"), (2, "defense_0")]
    assert env.opponent_slots == [(0, "offense_0"), (1, "offense_0"), (2, "offense_0")]
    assert env.action_space.shape == (GOALIE_ACTION_SIZE,)
    env.reset()
    for _ in range(5):
        env.step(_still_goalie(np.zeros((3, 1))))
    assert len(opponent.batches) == 5 and all(batch.shape == (3, 66) for batch in opponent.batches)


def test_a_frozen_striker_plays_as_it_would_in_the_game_itself() -> None:
    """The VecEnv's games follow exactly the moves of a TeamGame stepped by hand with the same policies."""
    env = make_team_vec_env(
        1,
        offense_agents=1,
        defense_agents=1,
        side="defense",
        opponent=_ScriptedBatch(),
        seed=5,
        monitor=False,
    )
    game = TeamGame(1, 1, 0)
    by_hand = make_striker("soft_dribble")
    observations, _ = game.reset(seed=5)
    vec_observation = env.reset()
    ended = False
    for _ in range(300):
        goalie_action = _still_goalie(vec_observation)
        np.testing.assert_array_equal(vec_observation[0], observations["defense_0"])
        vec_observation, rewards, dones, infos = env.step(goalie_action)
        observations, game_rewards, terminated, truncated, game_infos = game.step(
            {"offense_0": by_hand(observations["offense_0"]), "defense_0": goalie_action[0]}
        )
        assert rewards[0] == np.float32(game_rewards["defense_0"])
        if dones[0]:
            assert terminated or truncated
            assert infos[0]["status"] == game.status
            np.testing.assert_array_equal(infos[0]["terminal_observation"], observations["defense_0"])
            ended = True
            break
    assert ended and game.status == "GOAL"  # soft_dribble scores past a goalie that stands still


def test_seeds_repeat_and_the_opponent_matters() -> None:
    def trace(opponent: object) -> str:
        env = make_team_vec_env(
            2, offense_agents=1, defense_agents=1, side="defense", opponent=opponent, seed=1
        )
        env.action_space.seed(0)
        steps = [env.reset()]
        for _ in range(30):
            steps.append(env.step(np.stack([env.action_space.sample() for _ in range(2)]))[:3])
        return repr(steps)

    def idle(observations: np.ndarray) -> np.ndarray:
        actions = np.zeros((len(observations), 8), dtype=np.float32)
        actions[:, 0] = 1.0
        return actions

    assert trace(_ScriptedBatch()) == trace(_ScriptedBatch())
    assert trace(_ScriptedBatch()) != trace(idle)


def test_games_against_the_opponent_and_against_npcs_mix() -> None:
    opponent = _ScriptedBatch()
    games = [TeamGame(1, 1, 0, seed=0), TeamGame(1, 0, 1, seed=1)]  # a striker model against both goalies
    env = TeamVecEnv(games, side="offense", opponent=lambda observations: _still_goalie(observations))
    assert env.slots == [(0, "offense_0"), (1, "offense_0")] and env.opponent_slots == [(0, "defense_0")]
    observations = env.reset()
    for _ in range(3):
        observations, *_ = env.step(np.stack([opponent.striker(row) for row in observations]))
    assert env.get_attr("steps") == [3, 3]


def test_a_model_is_played_greedily_and_swapped_between_rounds() -> None:
    striker_env = make_team_vec_env(1, offense_agents=1, defense_npcs=1, seed=0, monitor=False)
    striker = HybridPPO("MlpPolicy", striker_env, n_steps=8, batch_size=8, seed=0)
    env = make_team_vec_env(2, offense_agents=1, defense_agents=1, side="defense", opponent=striker, seed=0)
    goalie = HybridPPO("MlpPolicy", env, n_steps=16, batch_size=32, n_epochs=1, seed=0)
    # HybridPPO reads the goalie's layout from the env: CATCH has no parameter
    assert goalie.policy.adapter.names == ("DASH", "TURN", "TACKLE", "KICK", "CATCH")
    assert goalie.policy.adapter.parameter_mask.sum(axis=1).tolist() == [2, 1, 1, 2, 0]
    before = [p.detach().clone() for p in goalie.policy.parameters()]
    frozen = [p.detach().clone() for p in striker.policy.parameters()]
    goalie.learn(64)
    assert goalie.num_timesteps == 64
    assert any(
        not np.array_equal(a, b.detach()) for a, b in zip(before, goalie.policy.parameters(), strict=True)
    )
    assert all(
        np.array_equal(a, b.detach()) for a, b in zip(frozen, striker.policy.parameters(), strict=True)
    )
    observations = np.random.default_rng(0).uniform(-1, 1, size=(4, 66)).astype(np.float32)
    opponent = env.venv.opponent  # under the VecMonitor
    np.testing.assert_array_equal(
        opponent(observations), striker.predict(observations, deterministic=True)[0]
    )
    env.venv.set_opponent(_ScriptedBatch())
    assert env.venv.opponent.name == "_ScriptedBatch"
    with pytest.raises(ValueError, match="made for the action space"):
        env.venv.set_opponent(goalie)  # a goalie model cannot play the strikers
    assert env.venv.opponent.name == "_ScriptedBatch"  # unchanged


def test_errors_name_the_problem() -> None:
    with pytest.raises(ValueError, match="name the learning side"):
        make_team_vec_env(1, offense_agents=1, defense_agents=1, opponent=_still_goalie)
    with pytest.raises(ValueError, match="no game has an agent outside side"):
        TeamVecEnv([TeamGame(1, 0, 1)], opponent=_still_goalie)
    with pytest.raises(ValueError, match="SB3 model .* or a function"):
        TeamVecEnv([TeamGame(1, 1, 0)], opponent=42)
    with pytest.raises(ValueError, match="outside side 'offense'"):
        TeamVecEnv([TeamGame(1, 1, 0)])
    env = TeamVecEnv([TeamGame(1, 1, 0)], side="defense", opponent=lambda observations: np.zeros((0, 8)))
    env.reset()
    with pytest.raises(ValueError, match="returned 0 actions for 1 observations"):
        env.step(_still_goalie(np.zeros((1, 1))))
    with pytest.raises(ValueError, match="already a FrozenOpponent"):
        FrozenOpponent(FrozenOpponent(_still_goalie))


def test_play_matches_repeats_and_counts_every_episode() -> None:
    kwargs = dict(offense_agents=1, defense_agents=1, seed=2, untouched_time=40)
    first = play_matches(3, 7, offense=_ScriptedBatch(), defense=_still_goalie, **kwargs)
    second = play_matches(3, 7, offense=_ScriptedBatch(), defense=_still_goalie, **kwargs)
    assert first == second and first.episodes == 7
    assert sum(first.counts().values()) == 7 and first.goal_rate == first.goals / 7
    # a goalie that stands still lets soft_dribble score every time; agent2d's goalie stops long shots
    assert first.goal_rate == 1.0
    against_agent2d = play_matches(
        3, 12, seed=2, offense_agents=0, defense_npcs=1, scripted_strikers=1, striker="long_shot"
    )
    assert against_agent2d.episodes == 12 and against_agent2d.goal_rate < 0.5


def test_play_matches_errors() -> None:
    with pytest.raises(ValueError, match="give a policy for them"):
        play_matches(1, 1, offense_agents=1, defense_agents=1, defense=_still_goalie)
    with pytest.raises(ValueError, match="no defense agent"):
        play_matches(1, 1, offense=_ScriptedBatch(), defense=_still_goalie, offense_agents=1, defense_npcs=1)
    with pytest.raises(ValueError, match="episodes must be a positive integer"):
        play_matches(1, 0, offense=_ScriptedBatch(), offense_agents=1, defense_npcs=1)
