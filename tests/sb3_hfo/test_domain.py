"""Issue 33, item 6: the algorithms stay generic. HFO's facts reach them through one adapter, sb3_hfo.hfo.HFO_DOMAIN.

* no module of the algorithms, their policies or the shared helpers imports hfo2d (read with :mod:`ast`, imports
  inside functions included); the algorithms' modules do not import the HFO adapter either;
* the adapter's facts are hfo2d's (kickable column, self-x column, mirror maps, landmark bearings, flat action);
* a toy task that is not HFO trains with SkillDDPG and HybridPPO without any adapter (``domain=None``);
* models saved before the ``domain`` option load with HFO's, new ones keep theirs.
"""

from __future__ import annotations

import ast
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
import torch as th
from gymnasium import spaces

from sb3_hfo import HFO_DOMAIN, HybridPPO, SkillDDPG, SkillRouter
from sb3_hfo.common.action_layout import ActionLayout, space_layout
from sb3_hfo.common.domain import GENERIC_DOMAIN, DomainAdapter, resolve_domain
from sb3_hfo.common.mirror import make_mirror

PACKAGE = Path(__file__).resolve().parents[2] / "sb3_hfo"
#: Folders whose modules must not import hfo2d: the algorithms, their policies and the shared helpers.
GENERIC_FOLDERS = ("skill_ddpg", "hybrid_ppo", "common")
#: Folders whose modules must not import the HFO adapter either: agents know nothing of the domain.
ALGORITHM_FOLDERS = ("skill_ddpg", "hybrid_ppo")


def imported_names(path: Path) -> set[str]:
    """Every module an ``import`` / ``from ... import`` statement anywhere in ``path`` names (absolute imports)."""
    names: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(), filename=str(path))):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names.add(node.module)
            names.update(f"{node.module}.{alias.name}" for alias in node.names)
    return names


def offenders(folders: tuple[str, ...], forbidden: tuple[str, ...]) -> dict[str, list[str]]:
    found = {}
    for folder in folders:
        for path in sorted((PACKAGE / folder).rglob("*.py")):
            bad = sorted(
                name
                for name in imported_names(path)
                if any(name == f or name.startswith(f + ".") for f in forbidden)
            )
            if bad:
                found[str(path.relative_to(PACKAGE.parent))] = bad
    return found


def test_the_import_check_sees_function_level_imports(tmp_path: Path) -> None:
    module = tmp_path / "m.py"
    module.write_text("def f():\n    from hfo2d.features import SELF_X\n    import hfo2d\n")
    assert imported_names(module) >= {"hfo2d.features", "hfo2d"}


def test_no_algorithm_policy_or_shared_module_imports_hfo2d() -> None:
    assert all((PACKAGE / folder).is_dir() for folder in GENERIC_FOLDERS)
    assert offenders(GENERIC_FOLDERS, ("hfo2d",)) == {}


def test_the_algorithms_do_not_import_the_hfo_adapter() -> None:
    assert (
        offenders(ALGORITHM_FOLDERS, ("hfo2d", "sb3_hfo.hfo", "sb3_hfo.vec_env", "sb3_hfo.demonstrations"))
        == {}
    )


# ----------------------------------------------------------------------------------------------------------
# The adapter's facts are hfo2d's


def test_the_hfo_adapter_holds_hfo2ds_facts() -> None:
    from hfo2d import features
    from hfo2d.action_layout import HFO_FLAT_ACTION_LAYOUT, hfo_flat_action_space
    from hfo2d.symmetry import feature_mirror, flat_action_mirror_signs

    assert resolve_domain("hfo") is HFO_DOMAIN
    assert HFO_DOMAIN.kickable_column == features.KICKABLE
    assert HFO_DOMAIN.field_half_column == features.SELF_X and HFO_DOMAIN.field_half_threshold == 0.0
    assert HFO_DOMAIN.bearing_columns == {
        "goalie": (features.GOALIE_ANGLE_SIN, features.GOALIE_ANGLE_COS),
        "goal_center": (features.GOAL_CENTER_SIN, features.GOAL_CENTER_COS),
        "goal_post_top": (features.GOAL_POST_TOP_SIN, features.GOAL_POST_TOP_COS),
        "goal_post_bottom": (features.GOAL_POST_BOTTOM_SIN, features.GOAL_POST_BOTTOM_COS),
    }
    for n_features in (58, 66, 74):
        assert HFO_DOMAIN.observation_mirror is not None
        assert HFO_DOMAIN.observation_mirror(n_features) == feature_mirror(n_features)
    assert list(HFO_DOMAIN.action_mirror_signs or ()) == flat_action_mirror_signs()
    assert HFO_DOMAIN.mirror_parameter_sizes == HFO_FLAT_ACTION_LAYOUT.parameter_sizes
    assert HFO_DOMAIN.flat_action_space == hfo_flat_action_space()
    assert HFO_DOMAIN.flat_action_space.layout == HFO_FLAT_ACTION_LAYOUT  # type: ignore[union-attr]


def test_the_layout_read_from_hfos_space_is_hfo2ds() -> None:
    from hfo2d.action_layout import HFO_FLAT_ACTION_LAYOUT, hfo_flat_action_space

    layout = space_layout(hfo_flat_action_space())
    assert layout is not None
    declared = HFO_FLAT_ACTION_LAYOUT
    assert (layout.names, layout.parameter_sizes, layout.direction_indices, layout.ball_action) == (
        declared.names,
        declared.parameter_sizes,
        declared.direction_indices,
        declared.ball_action,
    )
    for action in range(declared.n_discrete):
        assert layout.parameter_slice(action) == declared.parameter_slice(action)
        assert layout.action_direction(action) == declared.action_direction(action)
    np.testing.assert_array_equal(layout.parameter_masks(), declared.parameter_masks())
    assert space_layout(spaces.Box(0.0, 1.0, (8,), np.float32)) is None


def test_the_mirror_built_from_the_adapter_is_hfo2ds() -> None:
    from hfo2d.action_layout import hfo_flat_action_space
    from hfo2d.symmetry import mirror_features, mirror_flat_action

    mirror = make_mirror((66,), space_layout(hfo_flat_action_space()), "test", HFO_DOMAIN)
    rng = np.random.default_rng(0)
    obs = rng.uniform(-1, 1, (5, 66)).astype(np.float32)
    np.testing.assert_array_equal(mirror.observations(th.as_tensor(obs)).numpy(), mirror_features(obs))
    action = rng.uniform(0, 1, (5, 8))  # the env's [0, 1] scale; the mirror works on SB3's [-1, 1]
    mirrored = mirror.actions(th.as_tensor(2.0 * action - 1.0)).numpy()
    np.testing.assert_allclose((mirrored + 1.0) / 2.0, mirror_flat_action(action), atol=1e-12)


def test_domains_resolve_by_name_and_refuse_what_they_do_not_know() -> None:
    assert resolve_domain(None) is GENERIC_DOMAIN
    assert resolve_domain(HFO_DOMAIN) is HFO_DOMAIN
    with pytest.raises(ValueError, match=r"unknown domain 'soccer'; known domains: \['hfo'\]"):
        resolve_domain("soccer")
    with pytest.raises(ValueError, match="domain must be a DomainAdapter"):
        resolve_domain(3)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="kickable_column must be a column index"):
        DomainAdapter(kickable_column=-1)
    with pytest.raises(ValueError, match="both observation_mirror and action_mirror_signs"):
        DomainAdapter(action_mirror_signs=(1.0,))


# ----------------------------------------------------------------------------------------------------------
# A task that is not HFO, without any adapter


class _Layout:
    """A layout declared by an env of its own (duck typing: no hfo2d class)."""

    names = ("LEFT", "RIGHT")
    parameter_sizes = (1, 1)
    direction_indices = ()
    ball_action = None


class _LayoutBox(spaces.Box):
    def __init__(self) -> None:
        super().__init__(-1.0, 1.0, (4,), np.float32)
        self.layout = _Layout()


class SideBandit(gym.Env[np.ndarray, Any]):
    """One step: ``obs[0] = r``; the right action is LEFT for r > 0, RIGHT otherwise, with its parameter at ``r / 2``.
    Reward ``1 - |p - r / 2|`` for the right action, -1 otherwise. ``hybrid=True``: the flat Box with a declared
    layout; ``False``: ``Tuple(Discrete(2), Box(2))``."""

    def __init__(self, hybrid: bool = True) -> None:
        self.observation_space = spaces.Box(-1.0, 1.0, (3,), np.float32)
        self.action_space: spaces.Space = (
            _LayoutBox()
            if hybrid
            else spaces.Tuple((spaces.Discrete(2), spaces.Box(-1.0, 1.0, (2,), np.float32)))
        )
        self._obs = np.zeros(3, np.float32)

    def reset(self, *, seed: int | None = None, options: dict | None = None) -> tuple[np.ndarray, dict]:
        super().reset(seed=seed)
        self._obs = self.np_random.uniform(-1.0, 1.0, 3).astype(np.float32)
        return self._obs.copy(), {}

    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict]:
        if isinstance(self.action_space, spaces.Tuple):
            chosen, parameters = int(action[0]), np.asarray(action[1])
        else:
            flat = np.asarray(action).reshape(4)
            chosen, parameters = int(flat[:2].argmax()), flat[2:]
        right = 0 if self._obs[0] > 0 else 1
        reward = 1.0 - abs(float(parameters[chosen]) - self._obs[0] / 2) if chosen == right else -1.0
        return self._obs.copy(), reward, True, False, {}


class SignRouter(SkillRouter):
    """Skill 0 where ``obs[0] > 0``: a router of the task's own, no domain needed."""

    n_skills = 2

    def __call__(self, obs: Any) -> Any:
        if isinstance(obs, th.Tensor):
            return (obs[:, 0] <= 0).long()
        return (np.asarray(obs)[:, 0] <= 0).astype(np.int64)


def test_skill_ddpg_trains_on_a_task_that_is_not_hfo_without_an_adapter(tmp_path: Path) -> None:
    model = SkillDDPG(
        "MlpPolicy",
        SideBandit(),
        learning_starts=32,
        batch_size=16,
        seed=0,
        policy_kwargs=dict(
            net_arch=[16], n_skills=2, skill_router=SignRouter(), mask_unused_parameters=True, acting="critic"
        ),
    )
    policy = model.policy
    assert policy.domain is GENERIC_DOMAIN
    assert policy.action_layout == ActionLayout(("LEFT", "RIGHT"), (1, 1))  # read from the space
    before = [p.clone() for p in policy.actor.parameters()]
    model.learn(96)
    assert any(not th.equal(a, b) for a, b in zip(before, policy.actor.parameters(), strict=True))
    model.save(tmp_path / "m.zip")
    loaded = SkillDDPG.load(tmp_path / "m.zip", env=SideBandit())
    assert loaded.policy.domain is GENERIC_DOMAIN and loaded.policy_kwargs["domain"] is None
    obs = np.random.default_rng(1).uniform(-1, 1, (6, 3)).astype(np.float32)
    np.testing.assert_array_equal(
        model.predict(obs, deterministic=True)[0], loaded.predict(obs, deterministic=True)[0]
    )
    # What only a domain can say is refused by name, not guessed.
    with pytest.raises(ValueError, match="KickMask needs an action layout with a ball action"):
        policy.acting = "kick_mask"
    with pytest.raises(ValueError, match="'field_half' skill router needs a domain"):
        SkillDDPG("MlpPolicy", SideBandit(), policy_kwargs=dict(n_skills=2, skill_router="field_half"))


@pytest.mark.parametrize("hybrid", [True, False], ids=["layout_box", "tuple"])
def test_hybrid_ppo_trains_on_a_task_that_is_not_hfo_without_an_adapter(hybrid: bool) -> None:
    model = HybridPPO(
        "MlpPolicy",
        SideBandit(hybrid),
        n_steps=64,
        batch_size=32,
        n_epochs=2,
        seed=0,
        policy_kwargs=dict(net_arch=[16], skills=2, router=SignRouter()),
    )
    before = [p.clone() for p in model.policy.parameters()]
    model.learn(128)
    assert model.num_timesteps == 128
    assert any(not th.equal(a, b) for a, b in zip(before, model.policy.parameters(), strict=True))
    with pytest.raises(ValueError, match="'field_half' skill router needs a domain"):
        HybridPPO("MlpPolicy", SideBandit(hybrid), policy_kwargs=dict(skills=2, router="field_half"))


# ----------------------------------------------------------------------------------------------------------
# Saved models


def test_a_model_saved_before_the_domain_option_loads_with_hfos(tmp_path: Path) -> None:
    from sb3_hfo.common.toy_env import HybridTargetEnv

    model = SkillDDPG(
        "MlpPolicy",
        HybridTargetEnv(),
        seed=0,
        policy_kwargs=dict(net_arch=[8], acting="kick_mask", domain="hfo"),
    )
    model.policy_kwargs = {
        key: value for key, value in model.policy_kwargs.items() if key != "domain"
    }  # as before
    model.save(tmp_path / "old.zip")
    loaded = SkillDDPG.load(tmp_path / "old.zip")
    assert loaded.policy.domain is HFO_DOMAIN and loaded.policy_kwargs["domain"] == "hfo"


def test_a_hybrid_ppo_model_saved_before_the_domain_option_loads_with_hfos(tmp_path: Path) -> None:
    from sb3_hfo.common.toy_env import HybridTargetEnv

    kwargs = dict(net_arch=[8], skills=2, router="field_half")
    model = HybridPPO(
        "MlpPolicy",
        HybridTargetEnv(),
        n_steps=8,
        batch_size=8,
        seed=0,
        policy_kwargs=dict(kwargs, domain="hfo"),
    )
    assert model.policy_kwargs["domain"] == "hfo"
    model.policy_kwargs = kwargs  # as saved before
    model.save(tmp_path / "old.zip")
    loaded = HybridPPO.load(tmp_path / "old.zip")
    assert loaded.policy_kwargs["domain"] == "hfo" and loaded.policy.skill_router == model.policy.skill_router
    assert HybridPPO("MlpPolicy", SideBandit(False), n_steps=8, batch_size=8).policy_kwargs["domain"] is None


def test_the_committed_models_act_with_hfos_domain() -> None:
    from sb3_hfo.models import load_model

    assert (
        resolve_domain(load_model("e1").policy.domain) is HFO_DOMAIN
    )  # HybridPPO's (keeps the name it was given)
    assert load_model("e1_skill_pdqn").policy.domain is HFO_DOMAIN  # SkillDDPG's
