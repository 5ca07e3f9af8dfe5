"""Settings of the command-line tests (rl-zoo3, torch)."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
import torch as th


@pytest.fixture(autouse=True)
def one_torch_thread() -> Iterator[None]:
    """Batch-32 networks run fastest (and reproducibly) on one thread, especially on a shared 2-core machine.

    Here and in tests/sb3_hfo/conftest.py, not in a conftest above tests/hfo2d/: hfo2d's tests must run without torch.
    """
    previous = th.get_num_threads()
    th.set_num_threads(1)
    yield
    th.set_num_threads(previous)
