"""Acting strategies (sb3_hfo.skill_ddpg.acting): parsing, the policy's ``acting`` argument, the mirror side carried
through ``predict``'s ``state`` / ``episode_start``, and save / load."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import torch as th
from gymnasium import spaces

from hfo2d.action_layout import hfo_flat_action_space
from sb3_hfo import HFOPolicy, SkillDDPG
from sb3_hfo.common.toy_env import HybridTargetEnv
from sb3_hfo.skill_ddpg import CriticChoice, KickMask, MirrorChoice, parse_acting
from sb3_hfo.skill_ddpg.acting import format_acting
from sb3_hfo.skill_ddpg.legacy import LEGACY_POLICY_OPTIONS, translate_legacy_options

OBS_SPACE = spaces.Box(-1.0, 1.0, (66,), np.float32)  # HFO's features with a goalie
ACTION_SPACE = hfo_flat_action_space()


def make_policy(**kwargs: object) -> HFOPolicy:
    th.manual_seed(0)
    kwargs = {"domain": "hfo", **kwargs}
    return HFOPolicy(OBS_SPACE, ACTION_SPACE, lambda _: 1e-3, net_arch=[32, 16], **kwargs)  # type: ignore[arg-type]


def test_parse_and_format_round_trip_in_a_fixed_order() -> None:
    strategies = parse_acting(" mirror:0.1, critic ,kick_mask")
    assert strategies == (CriticChoice(), KickMask(), MirrorChoice(0.1))
    assert format_acting(strategies) == "critic,kick_mask,mirror:0.1"
    assert parse_acting(format_acting(strategies)) == strategies
    assert parse_acting([MirrorChoice(), CriticChoice()]) == (CriticChoice(), MirrorChoice())
    for empty in (None, "", "actor", ()):
        assert parse_acting(empty) == ()
    assert format_acting((MirrorChoice(float("inf")),)) == "mirror:inf"
    assert parse_acting("mirror:inf") == (MirrorChoice(float("inf")),)
    assert format_acting((MirrorChoice(1 / 3),)) == f"mirror:{1 / 3!r}"  # no digits lost on save


@pytest.mark.parametrize(
    ("spec", "named"),
    [
        ("critic,kickmask", "'kickmask'"),
        ("mirror:abc", "'mirror:abc'"),
        ("mirror:-1", "'mirror:-1'"),
        ("mirror:nan", "'mirror:nan'"),
        ("critic:2", "'critic:2'"),
        ("critic,critic", "critic more than once"),
    ],
)
def test_parse_errors_name_the_bad_token(spec: str, named: str) -> None:
    with pytest.raises(ValueError, match=named):
        parse_acting(spec)


def test_strategies_validate_themselves() -> None:
    for bad in (-0.5, float("nan"), "0.1", True):
        with pytest.raises(ValueError, match="MirrorChoice margin must be"):
            MirrorChoice(bad)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="got 'critic'"):
        parse_acting(["critic"])  # type: ignore[list-item]
    assert parse_acting(CriticChoice()) == (CriticChoice(),)  # one strategy on its own
    for bad in (True, 1, {"critic": True}):
        with pytest.raises(ValueError, match=f"got {bad!r}"):
            parse_acting(bad)  # type: ignore[arg-type]
    with pytest.raises(AttributeError):
        MirrorChoice(0.1).margin = 0.2  # type: ignore[misc]


def test_the_legacy_single_options_fold_into_acting_and_override_their_part() -> None:
    def folded(**kwargs: object) -> object:
        return translate_legacy_options(dict(net_arch=[8], **kwargs), warn=False)

    assert folded(
        discrete_choice="critic", kick_only_when_kickable=True, mirror_choice=True, mirror_margin=0.25
    ) == {
        "net_arch": [8],
        "acting": "critic,kick_mask,mirror:0.25",
    }
    # A preset's strategies and a config's single option compose, as they did side by side.
    assert folded(acting="critic,kick_mask", discrete_choice="actor", mirror_choice=True)["acting"] == (
        "kick_mask,mirror"
    )
    assert folded(acting="mirror:0.5", mirror_margin=0.1)["acting"] == "mirror:0.1"
    assert (
        folded(acting="critic", mirror_margin=0.1)["acting"] == "critic"
    )  # a margin alone switches nothing on
    assert folded(acting="critic,mirror", mirror_choice=False, mirror_margin=0.0)["acting"] == "critic"
    plain = dict(net_arch=[8], acting="critic")
    assert translate_legacy_options(plain, warn=False) is plain  # nothing to translate: unchanged
    for bad, named in (
        (dict(discrete_choice="crtic"), "discrete_choice"),
        (dict(kick_only_when_kickable="yes"), "kick_only_when_kickable"),
        (dict(mirror_choice=1), "mirror_choice"),
        (dict(mirror_choice=True, mirror_margin=-1.0), "margin"),
    ):
        with pytest.raises(ValueError, match=named):
            folded(**bad)


def test_the_policy_has_one_acting_argument_and_one_property() -> None:
    policy = make_policy(mask_unused_parameters=True, acting="critic,kick_mask")
    assert policy.acting == (CriticChoice(), KickMask())
    policy.acting = "mirror:inf"
    assert policy.acting == (MirrorChoice(float("inf")),)
    assert make_policy().acting == ()
    with pytest.raises(ValueError, match="'mirorr'"):
        make_policy(acting="mirorr")
    for legacy in ("discrete_choice", "kick_only_when_kickable", "mirror_choice", "mirror_margin"):
        assert not hasattr(policy, legacy)
        with pytest.raises(TypeError, match=legacy):
            make_policy(**{legacy: None})


def test_acting_changed_while_the_mirror_is_suspended_is_what_the_policy_acts_with() -> None:
    policy = make_policy(acting="mirror")
    with policy.mirror_choice_suspended():
        assert not policy.mirror_active
        policy.acting = "kick_mask"
    assert policy.acting == (KickMask(),) and not policy.mirror_active
    with policy.mirror_choice_suspended():
        policy.acting = "mirror:0.5"
        assert not policy.mirror_active
    assert policy.mirror_active


def test_a_refused_acting_value_changes_nothing() -> None:
    policy = make_policy(acting="kick_mask,mirror:0.5")  # no layout mask: the critic's choice still works
    box = HFOPolicy(
        spaces.Box(-1.0, 1.0, (4,), np.float32), spaces.Box(-1.0, 1.0, (2,), np.float32), lambda _: 1e-3
    )
    for target, spec, named in ((box, "critic", "CriticChoice"), (box, "kick_mask", "KickMask")):
        with pytest.raises(ValueError, match=named):
            target.acting = spec
        assert target.acting == ()
    assert policy.acting == (KickMask(), MirrorChoice(0.5))


def test_single_options_given_to_skill_ddpg_warn_and_act_as_acting() -> None:
    env = HybridTargetEnv()
    with pytest.warns(DeprecationWarning, match="discrete_choice"):
        old = SkillDDPG("HFOPolicy", env, seed=0, policy_kwargs=dict(net_arch=[16], discrete_choice="critic"))
    new = SkillDDPG("HFOPolicy", env, seed=0, policy_kwargs=dict(net_arch=[16], acting="critic"))
    assert old.policy.acting == new.policy.acting == (CriticChoice(),)
    assert not set(old.policy_kwargs) & set(LEGACY_POLICY_OPTIONS)
    obs = np.random.default_rng(1).uniform(-1, 1, (32, *env.observation_space.shape)).astype(np.float32)
    np.testing.assert_array_equal(old.predict(obs)[0], new.predict(obs)[0])


def mirror_policy() -> tuple[HFOPolicy, np.ndarray, np.ndarray]:
    """A policy with ``MirrorChoice(inf)`` (the side of an episode's first step is kept), 64 random states and
    the side each state picks afresh (1.0: mirrored), with both sides present."""
    policy = make_policy(mask_unused_parameters=True, acting="critic,mirror:inf")
    obs = np.random.default_rng(5).uniform(-1, 1, (64, 66)).astype(np.float32)
    _, (fresh,) = policy.predict(obs)  # state=None: every row starts an episode
    assert 0 < fresh.sum() < 64
    return policy, obs, fresh


def test_predict_returns_the_mirror_side_as_its_state_and_episode_start_resets_it() -> None:
    policy, obs, fresh = mirror_policy()
    # Mid-episode the kept side wins whatever the values (margin inf) ...
    flipped = (1.0 - fresh,)
    _, (kept,) = policy.predict(obs, state=flipped, episode_start=np.zeros(64, dtype=bool))
    np.testing.assert_array_equal(kept, flipped[0])
    # ... and a row that starts an episode decides afresh, the others keep theirs.
    starts = np.arange(64) % 2 == 0
    _, (sides,) = policy.predict(obs, state=flipped, episode_start=starts)
    np.testing.assert_array_equal(sides, np.where(starts, fresh, flipped[0]))


def test_two_parallel_envs_keep_separate_sides() -> None:
    policy, obs, fresh = mirror_policy()
    a, b = int(np.argmax(fresh == 1.0)), int(np.argmax(fresh == 0.0))  # one state of each side
    pair = obs[[a, b]]
    _, state = policy.predict(pair, episode_start=np.ones(2, dtype=bool))
    assert state[0].tolist() == [1.0, 0.0]
    # Both envs now see the other's state: each keeps its own side, which a fresh choice would not play there ...
    swapped = pair[::-1].copy()
    actions, state = policy.predict(swapped, state=state, episode_start=np.zeros(2, dtype=bool))
    assert state[0].tolist() == [1.0, 0.0]
    fresh_actions, _ = policy.predict(swapped)
    assert not np.allclose(actions, fresh_actions)
    # ... and each row plays what that env alone, with its own side, plays.
    for row, side in enumerate((1.0, 0.0)):
        alone, _ = policy.predict(
            swapped[row], state=(np.array([side]),), episode_start=np.zeros(1, dtype=bool)
        )
        np.testing.assert_allclose(actions[row], alone, atol=1e-6)
    # Only env 1 starts a new episode: env 0 keeps its side.
    _, state = policy.predict(swapped, state=state, episode_start=np.array([False, True]))
    assert state[0].tolist() == [1.0, 1.0]


def test_save_load_keeps_the_acting_strategies(tmp_path: Path) -> None:
    model = SkillDDPG(
        "HFOPolicy", HybridTargetEnv(), policy_kwargs=dict(net_arch=[16], acting="critic", domain="hfo")
    )
    model.policy.acting = "critic,mirror:0.25"  # switched after construction
    model.save(tmp_path / "m.zip")
    loaded = SkillDDPG.load(tmp_path / "m.zip")
    assert loaded.policy.acting == (CriticChoice(), MirrorChoice(0.25))
    # Saved as the one argument, in its text form, without the single options.
    assert loaded.policy_kwargs["acting"] == "critic,mirror:0.25"
    assert not set(loaded.policy_kwargs) & set(LEGACY_POLICY_OPTIONS)
    obs = np.random.default_rng(0).uniform(-1, 1, (8, *model.observation_space.shape)).astype(np.float32)
    np.testing.assert_array_equal(model.predict(obs)[0], loaded.predict(obs)[0])


def test_a_committed_model_saved_with_the_single_options_loads_with_the_same_strategies(
    tmp_path: Path,
) -> None:
    import warnings

    from sb3_hfo.models import MODELS_DIR, load_model

    with warnings.catch_warnings():
        warnings.simplefilter("error", DeprecationWarning)  # a saved model's options are translated silently
        model = load_model(MODELS_DIR / "e6_keeper_v0.zip", device="cpu", buffer_size=1)
    assert model.policy.acting == (CriticChoice(), KickMask())
    assert not set(model.policy_kwargs) & set(LEGACY_POLICY_OPTIONS)
    model.save(tmp_path / "again.zip")
    again = load_model(tmp_path / "again.zip", device="cpu", buffer_size=1)
    obs = np.random.default_rng(0).uniform(-1, 1, (16, *model.observation_space.shape)).astype(np.float32)
    np.testing.assert_array_equal(model.predict(obs)[0], again.predict(obs)[0])
