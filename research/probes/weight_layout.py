"""Micro-benchmark: does storing a linear layer's weight transposed speed up the three products of an update?

For each layer shape of the paper's networks (batch 32, one torch thread) it times the forward product
``F.linear(x, W, b)``, the weight gradient ``dZ.T @ x`` and the input gradient ``dZ @ W`` with ``W`` stored as
``(out, in)`` (PyTorch's layout, what SkillDDPG uses) and as a transposed view of an ``(in, out)`` tensor, and
prints the sums. Session 6 (2-core Intel Xeon VM, its training runs paused): the transposed layout made the
forward products 4-36 % faster and the input-gradient products 23-51 % slower, 2 % slower over all three
(530 against 520 us), so SkillDDPG keeps PyTorch's layout (benchmarks/README.md, "Tried and dropped"):

    python research/probes/weight_layout.py
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable, Sequence

import torch as th
from torch.nn import functional as F

BATCH = 32
#: (in, out) of every product in an update with the paper's 400-300-200 nets on HFO's 58 features
#: (the critic's second layer takes the 8 action entries too).
SHAPES = ((58, 400), (400, 300), (300, 200), (200, 8), (408, 300), (200, 1))


def microseconds(operation: Callable[[], object], calls: int = 2000, rounds: int = 5) -> float:
    """Best over ``rounds`` of the mean time per call, in microseconds."""
    for _ in range(50):
        operation()
    best = float("inf")
    for _ in range(rounds):
        start = time.perf_counter()
        for _ in range(calls):
            operation()
        best = min(best, (time.perf_counter() - start) / calls)
    return best * 1e6


def layer_times(
    x: th.Tensor, grad_z: th.Tensor, bias: th.Tensor, weight: th.Tensor, calls: int
) -> tuple[float, float, float]:
    """Microseconds of the forward, weight-gradient and input-gradient products of one layer."""
    grad_weight = th.empty_like(weight)  # keeps the weight's strides
    forward = microseconds(lambda: F.linear(x, weight, bias), calls)
    weight_grad = microseconds(lambda: th.mm(grad_z.t(), x, out=grad_weight), calls)
    input_grad = microseconds(lambda: th.mm(grad_z, weight), calls)
    return forward, weight_grad, input_grad


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--calls", type=int, default=2000, help="calls per timing round (5 rounds, best kept)"
    )
    args = parser.parse_args(argv)
    th.set_num_threads(1)
    totals = {"(out, in)": 0.0, "transposed": 0.0}
    for n_in, n_out in SHAPES:
        x, grad_z, bias = th.randn(BATCH, n_in), th.randn(BATCH, n_out), th.randn(n_out)
        weight = th.randn(n_out, n_in)
        layouts = {"(out, in)": weight, "transposed": weight.t().contiguous().t()}
        row = []
        for name, stored in layouts.items():
            forward, weight_grad, input_grad = layer_times(x, grad_z, bias, stored, args.calls)
            totals[name] += forward + weight_grad + input_grad
            row.append(f"{name}: forward {forward:6.1f}  dW {weight_grad:6.1f}  dX {input_grad:6.1f} us")
        print(f"{n_in:>4} -> {n_out:<4} " + " | ".join(row))
    print(
        "sum of the three products over all shapes: "
        + ", ".join(f"{k} {v:.0f} us" for k, v in totals.items())
    )


if __name__ == "__main__":
    main()
