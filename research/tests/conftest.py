"""Shared settings of the research tests (as tests/conftest.py)."""

from __future__ import annotations

from collections.abc import Iterator

import pytest


@pytest.fixture(autouse=True)
def one_torch_thread() -> Iterator[None]:
    """Batch-32 networks run fastest (and reproducibly) on one thread, especially on a shared 2-core machine.

    torch is imported only when installed tests need it: hfo2d's own tests must run without it.
    """
    import torch as th

    previous = th.get_num_threads()
    th.set_num_threads(1)
    yield
    th.set_num_threads(previous)
