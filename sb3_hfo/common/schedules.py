"""Learning-rate schedules that a saved model can hold without rl-zoo3 installed.

Models trained with rl-zoo3 configs (``learning_rate_critic: lin_0.001``) used to pickle
``rl_zoo3.utils.SimpleLinearSchedule``, so loading them needed rl-zoo3. :class:`LinearToZero` is the same schedule
(same attribute, same values) owned by this package, and :func:`rl_zoo3_free_custom_objects` reads an older model's
rl-zoo3 schedules as :class:`LinearToZero` when rl-zoo3 is not installed.
"""

from __future__ import annotations

import base64
import io
import json
import pickle
import zipfile
from pathlib import Path
from typing import IO, Any

#: Hyperparameters holding a learning rate that rl-zoo3 style strings (``"lin_1e-3"``) or floats may describe.
SCHEDULE_KEYS: tuple[str, ...] = ("learning_rate", "learning_rate_actor", "learning_rate_critic")


class LinearToZero:
    """``progress_remaining * initial_value``: linear from ``initial_value`` at the start of training to 0 at its end
    (rl-zoo3's ``lin_<x>``)."""

    def __init__(self, initial_value: float | str) -> None:
        self.initial_value = float(initial_value)

    def __call__(self, progress_remaining: float) -> float:
        return progress_remaining * self.initial_value

    def __repr__(self) -> str:
        return f"LinearToZero(initial_value={self.initial_value})"


class DecayToZero:
    """``initial_value`` falling linearly to 0 over the first ``fraction`` of training, then 0: e.g. the weight of
    a pull toward a reference policy that lets go part-way (``HybridPPO(reference_coef=DecayToZero(1.0, 0.5))``).
    Called with SB3's ``progress_remaining`` (1 at the start, 0 at the end)."""

    def __init__(self, initial_value: float, fraction: float) -> None:
        if not float(initial_value) >= 0.0:
            raise ValueError(f"DecayToZero: initial_value must be >= 0, got {initial_value!r}")
        if not 0.0 < float(fraction) <= 1.0:
            raise ValueError(f"DecayToZero: fraction must lie in (0, 1], got {fraction!r}")
        self.initial_value = float(initial_value)
        self.fraction = float(fraction)

    def __call__(self, progress_remaining: float) -> float:
        elapsed = 1.0 - progress_remaining
        return self.initial_value * max(0.0, 1.0 - elapsed / self.fraction)

    def __repr__(self) -> str:
        return f"DecayToZero(initial_value={self.initial_value}, fraction={self.fraction})"


#: rl-zoo3 classes an older saved model may hold, and this package's equivalents.
_RL_ZOO3_EQUIVALENTS = {("rl_zoo3.utils", "SimpleLinearSchedule"): LinearToZero}


class _RlZoo3FreeUnpickler(pickle.Unpickler):
    def find_class(self, module: str, name: str) -> Any:
        equivalent = _RL_ZOO3_EQUIVALENTS.get((module, name))
        if equivalent is not None:
            return equivalent
        if module.split(".")[0] == "rl_zoo3":
            raise pickle.UnpicklingError(f'{module}.{name} needs rl-zoo3: pip install -e ".[zoo]"')
        return super().find_class(module, name)


def rl_zoo3_free_custom_objects(model: str | Path | IO[bytes]) -> dict[str, Any]:
    """SB3 ``load(custom_objects=...)`` entries for every value of a saved model's ``data`` that pickles an rl-zoo3
    class, each unpickled with that class replaced by this package's equivalent."""
    with zipfile.ZipFile(model) as archive:
        data = json.loads(archive.read("data"))
    if not isinstance(model, (str, Path)):
        model.seek(0)
    custom_objects: dict[str, Any] = {}
    for key, value in data.items():
        if isinstance(value, dict) and ":serialized:" in value:
            raw = base64.b64decode(value[":serialized:"].encode())
            if b"rl_zoo3" in raw:
                custom_objects[key] = _RlZoo3FreeUnpickler(io.BytesIO(raw)).load()
    return custom_objects


def parse_schedule(value: Any) -> Any:
    """Convert an rl-zoo3 style learning-rate value into what SB3 algorithms accept.

    ``"lin_<x>"`` -> linear decay from ``x`` (start of training) to 0 (end of ``n_timesteps``), as rl-zoo3 does
    for ``learning_rate``; a number or ``"<x>"`` -> constant ``x`` (as a float); a callable is returned unchanged.
    """
    if callable(value):
        return value
    if isinstance(value, str):
        kind, _, number = value.partition("_")
        if kind == "lin" and number:
            return LinearToZero(float(number))
        if not number:
            return float(kind)
        raise ValueError(f"unknown schedule {value!r}: expected 'lin_<value>' or a number")
    if isinstance(value, (int, float)):
        return float(value)
    raise ValueError(f"invalid learning rate {value!r}")
