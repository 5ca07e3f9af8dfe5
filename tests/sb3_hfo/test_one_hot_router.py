"""OneHotRouter: the skill read back from one-hot columns that an observation wrapper appended."""

from __future__ import annotations

import pickle

import numpy as np
import pytest
import torch as th

from sb3_hfo.common.routers import OneHotRouter, make_router


def observations_with(skills: list[int], n_skills: int, features: int = 4) -> np.ndarray:
    rng = np.random.default_rng(0)
    rows = rng.uniform(-1.0, 1.0, size=(len(skills), features)).astype(np.float32)
    return np.concatenate([rows, np.eye(n_skills, dtype=np.float32)[skills]], axis=1)


def test_the_router_reads_each_rows_skill_from_its_columns_in_numpy_and_torch() -> None:
    skills = [2, 0, 4, 1, 3, 3]
    observations = observations_with(skills, 5)
    router = OneHotRouter(4, 5)
    routed = router(observations)
    assert routed.dtype == np.int64 and routed.tolist() == skills
    routed_t = router(th.as_tensor(observations))
    assert routed_t.dtype == th.long and routed_t.tolist() == skills
    assert make_router(router, 5) is router  # a hand-coded router the policies accept as it is


def test_columns_that_are_not_one_hot_or_missing_are_refused() -> None:
    router = OneHotRouter(4, 3)
    observations = observations_with([0, 1], 3)
    for broken in (observations[:, :6], observations * 0.5):  # too few columns; not a one-hot
        for batch in (broken, th.as_tensor(broken)):
            with pytest.raises(ValueError, match="OneHotRouter"):
                router(batch)
    two_set = observations.copy()
    two_set[0, 5] = 1.0  # two skills in one row
    with pytest.raises(ValueError, match="not one-hot"):
        router(two_set)


@pytest.mark.parametrize(("first_column", "n_skills"), [(-1, 3), (0, 1), (2.0, 3), (True, 3), (0, "3")])
def test_bad_arguments_name_the_problem(first_column: object, n_skills: object) -> None:
    with pytest.raises(ValueError, match="OneHotRouter: (first_column|n_skills)"):
        OneHotRouter(first_column, n_skills)  # type: ignore[arg-type]


def test_the_router_pickles_and_compares_by_its_settings() -> None:
    router = OneHotRouter(86, 5)
    copy = pickle.loads(pickle.dumps(router))
    assert copy == router and hash(copy) == hash(router) and copy != OneHotRouter(86, 4)
