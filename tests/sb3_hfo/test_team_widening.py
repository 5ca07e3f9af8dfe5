"""sb3_hfo.multi_agent: a 1v1 striker's policy widened for a teammate, and the evaluation of a shared-policy team."""

from __future__ import annotations

import numpy as np
import pytest
import torch as th
from torch import nn

import hfo2d
from hfo2d.features import KICKABLE_BUFFER, low_level_feature_list
from hfo2d.team import TeamGame
from sb3_hfo.evaluation import wilson_interval
from sb3_hfo.hybrid_ppo import HybridPPO
from sb3_hfo.multi_agent import (
    evaluate_team,
    evaluate_team_games,
    make_team_vec_env,
    teammate_block_insertion,
    widen_policy_inputs,
)

POLICY_KWARGS = {
    "net_arch": {"pi": [32, 16], "vf": [32]},
    "activation_fn": nn.LeakyReLU,
    "skills": 2,
    "router": "field_half",
    "domain": "hfo",
    "squash_mean": True,
}


def striker_model(strikers: int, seed: int) -> HybridPPO:
    env = make_team_vec_env(2, offense_agents=strikers, defense_npcs=1, seed=seed, monitor=False)
    return HybridPPO("MlpPolicy", env, seed=seed, n_steps=8, batch_size=8, policy_kwargs=POLICY_KWARGS)


def test_the_teammate_blocks_go_between_the_basic_features_and_the_opponents() -> None:
    assert teammate_block_insertion(0, 1) == (58, 8)
    assert teammate_block_insertion(1, 3) == (66, 16)
    assert teammate_block_insertion(2, 2) == (74, 0)
    # the 2v1 observation without that block is the 1v1 observation of the same state
    one = hfo2d.parallel_env(offense_agents=1, defense_npcs=1)
    two = hfo2d.parallel_env(offense_agents=2, defense_npcs=1)
    single, _ = one.reset(seed=5)
    pair, _ = two.reset(seed=5)
    position, count = teammate_block_insertion(0, 1)
    cut = np.delete(pair["offense_0"], np.s_[position : position + count])
    assert cut.shape == single["offense_0"].shape == (66,)
    # same features: the goalie's block stays where the 1v1 layout has it (HFO/Keeper-v1's goalie columns)
    goalie_block = two.game.defense_players[0]
    assert goalie_block.goalie
    player = two.game.offense_players[0]
    expected = low_level_feature_list(
        player, two.game.world.ball, two.game.params.kickable_area - KICKABLE_BUFFER, (), [goalie_block]
    )
    np.testing.assert_allclose(cut, np.asarray(expected, dtype=np.float32))
    with pytest.raises(ValueError, match="only adds"):
        teammate_block_insertion(2, 1)
    with pytest.raises(ValueError, match="teammates_before"):
        teammate_block_insertion(-1, 1)


def test_a_widened_policy_acts_and_values_as_the_1v1_policy_on_its_columns() -> None:
    source = striker_model(1, seed=0)
    # non-zero first-layer weights everywhere, so a wrong column order would change the outputs
    target = striker_model(2, seed=1)
    position, count = teammate_block_insertion(0, 1)
    widen_policy_inputs(source.policy, target.policy, position)
    rng = np.random.default_rng(0)
    observations = rng.uniform(-1, 1, size=(64, 74)).astype(np.float32)
    observations[::2, 4] = -observations[::2, 4]  # both routed skills (field_half reads a basic feature)
    narrow = np.delete(observations, np.s_[position : position + count], axis=1)
    wide_actions, _ = target.predict(observations, deterministic=True)
    narrow_actions, _ = source.predict(narrow, deterministic=True)
    np.testing.assert_array_equal(wide_actions, narrow_actions)
    with th.no_grad():
        wide_values = target.policy.predict_values(th.as_tensor(observations))
        narrow_values = source.policy.predict_values(th.as_tensor(narrow))
    th.testing.assert_close(wide_values, narrow_values)
    # the new columns start at zero and are still trainable weights of the first layers
    for trunk in (target.policy.actor_trunk, target.policy.critic_trunk):
        weight = trunk[0].weight
        assert weight.requires_grad and weight.shape[1] == 74
        assert th.count_nonzero(weight[:, position : position + count]) == 0
        assert th.count_nonzero(weight[:, :position]) > 0


def test_widening_refuses_other_networks_and_changes_nothing() -> None:
    source = striker_model(1, seed=0)
    env = make_team_vec_env(1, offense_agents=2, defense_npcs=1, monitor=False)
    other = HybridPPO(
        "MlpPolicy",
        env,
        n_steps=8,
        batch_size=8,
        policy_kwargs={**POLICY_KWARGS, "skills": 3, "router": "learned"},
    )
    before = {key: value.clone() for key, value in other.policy.state_dict().items()}
    with pytest.raises(ValueError, match="networks differ"):
        widen_policy_inputs(source.policy, other.policy, 58)
    wider = striker_model(2, seed=1)
    with pytest.raises(ValueError, match="position"):
        widen_policy_inputs(source.policy, wider.policy, 70)
    with pytest.raises(ValueError, match="smaller"):
        widen_policy_inputs(wider.policy, source.policy, 58)
    after = other.policy.state_dict()
    assert all(th.equal(before[key], after[key]) for key in before)


def test_evaluate_team_counts_every_episode_and_repeats_with_its_seed() -> None:
    model = striker_model(2, seed=0)
    env = hfo2d.parallel_env(offense_agents=2, defense_npcs=1, untouched_time=20)
    ends: list[tuple[int, str]] = []
    first = evaluate_team(
        model, env, episodes=6, seed=3, on_episode=lambda played, status: ends.append((played, status))
    )
    second = evaluate_team(model, env, episodes=6, seed=3)
    env.close()
    assert first == second
    assert [played for played, _ in ends] == [1, 2, 3, 4, 5, 6]
    assert sorted(status for _, status in ends) == sorted(
        k for k, v in first["status"].items() for _ in range(v)
    )
    assert sum(first["status"].values()) == 6 == sum(first["ball_holders"].values())
    assert first["rate"] == first["goals"] / 6
    assert tuple(first["ci95"]) == wilson_interval(first["goals"], 6)
    assert first["agents"] == ["offense_0", "offense_1"]
    assert first["mean_cycles"] > 0
    with pytest.raises(ValueError, match="episodes"):
        evaluate_team(model, env, episodes=0, seed=0)


def test_evaluate_team_reports_who_had_the_ball() -> None:
    class Chaser:  # dash at the ball's bearing: an agent that reaches the ball, with no learning involved
        def predict(self, observations: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
            actions = np.zeros((len(observations), 8), dtype=np.float32)
            actions[:, 0] = 1.0  # DASH
            actions[:, 3] = 1.0  # full power
            bearing = np.degrees(np.arctan2(observations[:, 51], observations[:, 52]))
            actions[:, 4] = (bearing + 180.0) / 360.0  # direction relative to the body, [0, 1] scale
            return actions, None

    env = hfo2d.parallel_env(offense_agents=2, defense_npcs=1)
    result = evaluate_team(Chaser(), env, episodes=10, seed=0)
    env.close()
    assert sum(int(k) * v for k, v in result["ball_holders"].items()) > 0


def test_evaluate_team_games_plays_one_game_as_evaluate_team_and_counts_every_started_episode() -> None:
    model = striker_model(2, seed=0)
    env = hfo2d.parallel_env(offense_agents=2, defense_npcs=1, untouched_time=20)
    single = evaluate_team(model, env, episodes=5, seed=7)
    env.close()
    one_game = evaluate_team_games(model, [TeamGame(2, 0, 1, untouched_time=20)], episodes=5, seed=7)
    assert one_game == single
    games = [TeamGame(2, 0, 1, untouched_time=20) for _ in range(3)]
    several = evaluate_team_games(model, games, episodes=7, seed=7)
    assert sum(several["status"].values()) == 7 == sum(several["ball_holders"].values())
    assert tuple(several["ci95"]) == wilson_interval(several["goals"], 7)
    assert evaluate_team_games(model, games, episodes=7, seed=7) == several
    with pytest.raises(ValueError, match="same agents"):
        evaluate_team_games(model, [TeamGame(2, 0, 1), TeamGame(1, 0, 1)], episodes=2, seed=0)
