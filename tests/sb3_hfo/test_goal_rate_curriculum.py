"""GoalRateKeeperCurriculumCallback: the goalie's skill rises with the agent's training goal rate, not with time."""

from __future__ import annotations

import numpy as np
import pytest
from stable_baselines3.common.logger import configure

from sb3_hfo.callbacks import GoalRateKeeperCurriculumCallback, GoalRateStartShiftCallback
from sb3_hfo.hybrid_ppo import HybridPPO
from sb3_hfo.vec_env import make_hfo_vec_env


def _callback_on(
    env_id: str, kind: type = GoalRateKeeperCurriculumCallback, **kwargs: float
) -> tuple[GoalRateKeeperCurriculumCallback, HybridPPO]:
    env = make_hfo_vec_env(env_id, 2, seed=0, monitor=False)
    model = HybridPPO("MlpPolicy", env, n_steps=8, batch_size=16, seed=0)
    model.set_logger(configure(None, []))
    return kind(**kwargs), model


def _finish(callback: GoalRateKeeperCurriculumCallback, dones: list[bool], goals: list[bool]) -> None:
    """One vectorised step in which the games with ``dones`` end, scoring where ``goals``."""
    infos = [{"is_success": goal} for goal in goals]
    callback.update_locals({"dones": np.array(dones), "infos": infos})
    callback.on_step()


def test_skill_rises_when_counted_goal_rate_reaches_threshold() -> None:
    callback, model = _callback_on("HFO/Keeper-v1", skill_step=0.25, threshold=0.5, window=4)
    callback.init_callback(model)
    env = model.get_env()
    assert env.get_attr("keeper_skill") == [0.0, 0.0]
    # the games' first episodes started with the goalie the envs were made with: not counted
    _finish(callback, [True, True], [True, True])
    assert callback.goal_rate() is None and callback.skill == 0.0
    # 3 of 4 counted episodes scored (0.75 >= 0.5): one rise, once the window is full
    _finish(callback, [True, True], [True, False])
    assert callback.skill == 0.0
    _finish(callback, [True, True], [True, True])
    assert callback.skill == 0.25
    assert env.get_attr("keeper_skill") == [0.25, 0.25]
    assert callback.history == [(0, 0.0), (0, 0.25)]
    # the episodes running at the change do not count; then a window at 1 of 4 (0.25 < 0.5) holds the skill
    _finish(callback, [True, True], [True, True])
    assert callback.goal_rate() is None
    _finish(callback, [True, True], [False, False])
    _finish(callback, [True, True], [True, False])
    assert callback.goal_rate() == 0.25 and callback.skill == 0.25
    assert model.logger.name_to_value["rollout/keeper_skill"] == 0.25


def test_skill_stops_at_final_skill() -> None:
    callback, model = _callback_on(
        "HFO/Keeper-v1", initial_skill=0.9, final_skill=1.0, skill_step=0.25, threshold=1.0, window=1
    )
    callback.init_callback(model)
    for _ in range(6):
        _finish(callback, [True, True], [True, True])
    assert callback.skill == 1.0
    assert [skill for _, skill in callback.history] == [0.9, 1.0]


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"initial_skill": float("nan")}, "initial_skill"),
        ({"initial_skill": 0.5, "final_skill": 0.4}, "final_skill"),
        ({"skill_step": 0.0}, "skill_step"),
        ({"threshold": 1.5}, "threshold"),
        ({"window": 0}, "window"),
        ({"window": True}, "window"),
    ],
)
def test_invalid_settings_are_refused(kwargs: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        GoalRateKeeperCurriculumCallback(**kwargs)


def test_env_without_goalie_is_refused() -> None:
    callback, model = _callback_on("HFO/EmptyGoal-v0")
    with pytest.raises(ValueError, match="needs training envs with set_keeper_skill"):
        callback.init_callback(model)


def test_start_shift_falls_toward_hfo_starts() -> None:
    callback, model = _callback_on(
        "HFO/Keeper-v1",
        GoalRateStartShiftCallback,
        initial_shift=25.0,
        shift_step=10.0,
        threshold=0.5,
        window=2,
    )
    callback.init_callback(model)
    env = model.get_env()
    assert env.get_attr("start_shift") == [25.0, 25.0]
    _finish(callback, [True, True], [True, True])  # not counted (started before the callback)
    _finish(callback, [True, True], [True, False])  # 0.5 >= 0.5: 25 -> 15
    assert env.get_attr("start_shift") == [15.0, 15.0]
    for _ in range(4):  # two more moves, the last one stopped at 0
        _finish(callback, [True, True], [True, True])
    assert [shift for _, shift in callback.history] == [25.0, 15.0, 5.0, 0.0]
    assert model.logger.name_to_value["rollout/start_shift"] == 0.0
    with pytest.raises(ValueError, match="final_shift"):
        GoalRateStartShiftCallback(initial_shift=5.0, final_shift=10.0)


def test_start_shift_waits_for_the_goalie_at_full_strength() -> None:
    keeper, model = _callback_on("HFO/Keeper-v1", initial_skill=0.5, skill_step=0.5, threshold=0.5, window=2)
    shift = GoalRateStartShiftCallback(
        initial_shift=10.0, shift_step=10.0, threshold=0.5, window=2, wait_for=keeper
    )
    keeper.init_callback(model)
    shift.init_callback(model)

    def both(goals: list[bool]) -> None:
        for callback in (keeper, shift):
            _finish(callback, [True, True], goals)

    both([True, True])  # first episodes: not counted
    both([True, True])  # the goalie reaches 1.0; the starts waited for it
    assert keeper.skill == 1.0 and shift.value == 10.0
    both([True, True])  # episodes running at the change: not counted by the goalie's; counted by the starts'
    assert shift.value == 0.0
    assert model.get_env().get_attr("start_shift") == [0.0, 0.0]
