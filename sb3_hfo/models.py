"""The committed models: one per task, shipped inside the package (``sb3_hfo/pretrained/``, listed in its
``manifest.json``) and stored without training state.

A committed model is a SkillDDPG ``.zip`` *stripped* of what only training needs (the optimizers' moment
estimates and the target networks): it holds the policy's online weights (actor and critics) and the model's
``data`` entry, which is what ``predict`` needs, in about a third of the full file. :func:`load_model` loads a
stripped zip, or a full one, through ``SkillDDPG.load``: the target networks are rebuilt as copies of the online
ones and the optimizers start afresh, so the loaded model acts exactly as the full one (:func:`check_same_actions`
checks it on every model the ``add`` command writes) and can be trained further like a freshly warm-started one.

The manifest names each model (``e1``, ``e6``, ...) and records how it was trained (its zoo config, or, for a
model a benchmark script made, ``"config": null`` with that ``script`` and its exact ``command``: :func:`trained_with`,
:func:`check_provenance`), its training seed, env id, the acting strategies it was saved with (their text form),
the JSON of its 1,000-episode evaluation (:mod:`sb3_hfo.evaluation`) and, where measured, its real-HFO figure. ``evaluate``, ``enjoy`` and ``record_video``
accept a manifest name wherever they accept a model. The command line that lists, adds and records models is
:mod:`sb3_hfo.cli.models` (``python -m sb3_hfo.cli.models list``).
"""

from __future__ import annotations

import copy
import io
import json
import zipfile
import zlib
from pathlib import Path
from typing import Any

import numpy as np
import torch
from stable_baselines3.common.noise import ActionNoise, VectorizedActionNoise

from sb3_hfo.common.schedules import rl_zoo3_free_custom_objects
from sb3_hfo.errors import UserError, module_missing, one_line
from sb3_hfo.skill_ddpg import SkillDDPG

#: The committed models and their manifest (package data: ``sb3_hfo/pretrained/``).
MODELS_DIR = Path(__file__).resolve().parent / "pretrained"
MANIFEST_PATH = MODELS_DIR / "manifest.json"
#: Upper bound on a committed model's size (bytes).
MAX_MODEL_BYTES = 1_000_000
#: Zip entry that marks a stripped model and says how to rebuild its target networks.
STRIPPED_ENTRY = "sb3_hfo_stripped.json"
STRIPPED_FORMAT = 1
POLICY_ENTRY = "policy.pth"
#: Episodes and first seed of a manifest evaluation (a Wilson 95 % interval of about +-1 point at 98 %).
EVALUATION_EPISODES = 1000
EVALUATION_SEED = 0
#: Observations on which ``add`` compares the stripped model's actions with the full model's.
CHECK_EPISODES = 10


# --------------------------------------------------------------------------------------------------------------
# Stripping and loading


def check_model_zip(path: str | Path) -> None:
    """UserError unless ``path`` is a readable zip that holds SB3's ``data`` entry (a saved model)."""
    path = Path(path)
    if not path.is_file():
        raise UserError(f"model file not found: {path}")
    if not zipfile.is_zipfile(path):
        raise UserError(f"{path} is not a model .zip: not a zip archive, or cut short")
    try:
        with zipfile.ZipFile(path) as archive:
            if "data" not in archive.namelist():
                raise UserError(f"{path} is not a saved SB3 model: the zip has no 'data' entry")
            damaged = archive.testzip()
    except (zipfile.BadZipFile, EOFError, OSError, zlib.error) as error:
        raise UserError(f"{path} is a damaged zip ({one_line(error)}): truncated or corrupted?") from None
    if damaged is not None:
        raise UserError(f"{path} is a damaged zip: its entry {damaged!r} fails the CRC check")


def _target_source(key: str) -> str | None:
    """The online parameter a target-network parameter copies (``actor_target.x`` -> ``actor.x``); None for a
    parameter that is not a target's."""
    module, sep, rest = key.partition(".")
    if module.endswith("_target"):
        return f"{module[: -len('_target')]}{sep}{rest}"
    return None


def _torch_bytes(obj: Any) -> bytes:
    buffer = io.BytesIO()
    torch.save(obj, buffer)
    return buffer.getvalue()


def _torch_object(raw: bytes) -> Any:
    return torch.load(io.BytesIO(raw), map_location="cpu", weights_only=True)


def is_stripped(path: str | Path) -> bool:
    """Whether ``path`` is a stripped model zip (written by :func:`strip_model`)."""
    with zipfile.ZipFile(path) as archive:
        return STRIPPED_ENTRY in archive.namelist()


def strip_model(full_path: str | Path, out_path: str | Path) -> int:
    """Write ``full_path`` (a saved SkillDDPG zip) to ``out_path`` without the optimizers' state and the target
    networks; returns the new file's size in bytes.

    Each optimizer keeps its hyperparameters (``param_groups``) with an empty state, as a fresh one has; each
    target-network parameter whose online twin has the same shape is dropped and recorded, so that
    :func:`load_model` can rebuild it.
    """
    with zipfile.ZipFile(full_path) as archive:
        entries = {name: archive.read(name) for name in archive.namelist()}
    if POLICY_ENTRY not in entries or "data" not in entries:
        raise UserError(f"{full_path} is not a saved SB3 model (no {POLICY_ENTRY} or data entry)")
    if STRIPPED_ENTRY in entries:
        raise UserError(f"{full_path} is already stripped")
    state = _torch_object(entries[POLICY_ENTRY])
    targets: dict[str, str] = {}
    for key, value in state.items():
        source = _target_source(key)
        if source is not None and source in state and state[source].shape == value.shape:
            targets[key] = source
    entries[POLICY_ENTRY] = _torch_bytes({k: v for k, v in state.items() if k not in targets})
    for name in entries:
        if name.endswith("optimizer.pth"):
            optimizer = _torch_object(entries[name])
            entries[name] = _torch_bytes({"state": {}, "param_groups": optimizer["param_groups"]})
    entries[STRIPPED_ENTRY] = json.dumps({"format": STRIPPED_FORMAT, "targets": targets}, indent=1).encode()
    out_path = Path(out_path)
    out_path.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(out_path, "w", compression=zipfile.ZIP_DEFLATED) as archive:
        for name, raw in entries.items():
            archive.writestr(name, raw)
    return out_path.stat().st_size


def full_model_buffer(path: str | Path) -> io.BytesIO:
    """A stripped model rebuilt, in memory, as a full SB3 zip: target networks copied from the online ones."""
    with zipfile.ZipFile(path) as archive:
        entries = {name: archive.read(name) for name in archive.namelist()}
    info = json.loads(entries.pop(STRIPPED_ENTRY))
    if info.get("format") != STRIPPED_FORMAT:
        raise UserError(f"{path}: unknown stripped-model format {info.get('format')!r}")
    state = _torch_object(entries[POLICY_ENTRY])
    for target, source in info["targets"].items():
        state[target] = state[source].clone()
    entries[POLICY_ENTRY] = _torch_bytes(state)
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as archive:
        for name, raw in entries.items():
            archive.writestr(name, raw)
    buffer.seek(0)
    return buffer


#: Policy modules whose models load with another algorithm than SkillDDPG: module -> (algorithm module, class).
POLICY_ALGORITHMS: dict[str, tuple[str, str]] = {
    "sb3_hfo.hybrid_ppo.policies": ("sb3_hfo.hybrid_ppo", "HybridPPO")
}


def saved_algo_class(path: str | Path) -> type | None:
    """The algorithm a saved zip needs when its policy's module says so (:data:`POLICY_ALGORITHMS`: a HybridPPO
    zip), else ``None``. SB3 zips record the policy class, not the algorithm; its module is read from ``data``."""
    import importlib

    try:
        with zipfile.ZipFile(path) as archive:
            data = json.loads(archive.read("data"))
        module = data["policy_class"]["__module__"]
    except (KeyError, TypeError, ValueError, zipfile.BadZipFile, OSError):
        return None
    if module not in POLICY_ALGORITHMS:
        return None
    algo_module, name = POLICY_ALGORITHMS[module]
    return getattr(importlib.import_module(algo_module), name)


def load_model(path: str | Path, algo_class: type | None = None, **kwargs: Any) -> Any:
    """Load a SkillDDPG model from a full or a stripped zip, or a committed model by its manifest name (``"e1"``),
    with ``algo_class.load`` (default SkillDDPG). A zip that needs another algorithm (:func:`saved_algo_class`:
    a HybridPPO zip) loads with that one whatever ``algo_class`` says, without ``buffer_size``.

    ``kwargs`` go to ``load`` (e.g. ``device="cpu"``, ``buffer_size=1``, ``env=...``). The model continues training
    with ``model.learn`` on ``env``, whatever its number of envs: the saved action noise (one per training env) is
    fitted to it (:func:`fit_action_noise`). TensorBoard logs go where ``tensorboard_log`` says, and nowhere when it
    is not given (the saved value is the training run's folder, relative to wherever that ran).
    """
    if not Path(path).is_file() and looks_like_name(str(path)):
        entry = manifest_entry(str(path))
        if entry is None:
            raise UserError(unknown_name_message(str(path)))
        path = model_file(entry)
    algo_class = algo_class or SkillDDPG
    saved_class = saved_algo_class(path)
    if saved_class is not None and not issubclass(algo_class, saved_class):
        algo_class = saved_class
        kwargs.pop("buffer_size", None)  # an on-policy model has no replay buffer
    source: Any = full_model_buffer(path) if is_stripped(path) else str(path)
    if module_missing("rl_zoo3"):
        # Models trained through rl-zoo3 may pickle its schedules; without the [zoo] extra they load as equals.
        kwargs["custom_objects"] = {**rl_zoo3_free_custom_objects(source), **kwargs.get("custom_objects", {})}
    kwargs.setdefault("tensorboard_log", None)  # load() sets kwargs over the saved attributes
    model = algo_class.load(source, **kwargs)
    if model.get_env() is not None and hasattr(model, "action_noise"):  # on-policy models have none
        model.action_noise = fit_action_noise(model.action_noise, model.n_envs)
    return model


def fit_action_noise(noise: ActionNoise | None, n_envs: int) -> ActionNoise | None:
    """``noise`` (as saved: one noise, or SB3's VectorizedActionNoise of one per training env) for ``n_envs`` envs.

    SB3 wraps a single noise for several envs itself but keeps a vectorised one as it is, whose samples then have
    the training run's env count (a reshape or broadcast error). A vectorised noise of another count is rebuilt
    from its first env's noise, which keeps its kind and current scale (sigma, as ActionNoiseDecayCallback left
    it), reset; a single env gets that noise alone.
    """
    if not isinstance(noise, VectorizedActionNoise) or noise.n_envs == n_envs:
        return noise
    template = copy.deepcopy(noise.noises[0])
    template.reset()
    return template if n_envs == 1 else VectorizedActionNoise(template, n_envs)


# --------------------------------------------------------------------------------------------------------------
# The manifest


def read_manifest(path: Path = MANIFEST_PATH) -> dict[str, dict[str, Any]]:
    """The manifest's entries by name (empty when there is no manifest)."""
    if not path.is_file():
        return {}
    return dict(json.loads(path.read_text())["models"])


def write_manifest(models: dict[str, dict[str, Any]], path: Path = MANIFEST_PATH) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps({"models": models}, indent=2) + "\n")


def manifest_entry(name: str, path: Path = MANIFEST_PATH) -> dict[str, Any] | None:
    """The manifest entry called ``name``, or None."""
    return read_manifest(path).get(name)


def trained_with(entry: dict[str, Any]) -> str:
    """The file a manifest entry's model was trained with, from the repository's root: its zoo config, or the
    benchmark script that made it when it has no config (``"config": null``)."""
    return str(entry["config"] if entry.get("config") is not None else entry.get("script"))


def check_provenance(entry: dict[str, Any], root: Path) -> None:
    """ValueError unless ``entry`` says how its model was trained: a ``config`` file under ``root``, or
    ``"config": null`` with a ``script`` file under ``root`` and the ``command`` that ran it (naming the script)."""
    config = entry.get("config", "missing")
    if config is not None:
        if not isinstance(config, str) or not (root / config).is_file():
            raise ValueError(
                f"config {config!r}: no such file under {root} (null for a benchmark script's model)"
            )
        return
    script, command = entry.get("script"), entry.get("command")
    if not isinstance(script, str) or not (root / script).is_file():
        raise ValueError(f"a model without a config needs its script, a file under {root}; got {script!r}")
    if not isinstance(command, str) or Path(script).name not in command:
        raise ValueError(f"a model made by {script} needs the command that ran it; got {command!r}")


def model_file(entry: dict[str, Any], manifest_path: Path = MANIFEST_PATH) -> Path:
    """The model file of a manifest entry."""
    return manifest_path.parent / entry["file"]


def unknown_name_message(name: str, manifest_path: Path = MANIFEST_PATH) -> str:
    """The error for a model that is neither a file nor a manifest name."""
    names = ", ".join(read_manifest(manifest_path)) or "none"
    return f"{name!r} is neither a model file or folder nor a committed model name (names: {names})"


def looks_like_name(text: str) -> bool:
    """Whether ``text`` could be a manifest name rather than a path (no separator, no ``.zip``)."""
    return "/" not in text and "\\" not in text and not text.endswith(".zip") and text not in (".", "..")


# --------------------------------------------------------------------------------------------------------------
# Checking a stripped model


def check_same_actions(
    full: Any, stripped: Any, env: Any, episodes: int = CHECK_EPISODES, seed: int = 0
) -> int:
    """Play ``episodes`` with ``full`` and compare ``stripped``'s ``predict`` (state and episode starts
    included) at every step; returns the number of steps compared. Raises UserError at the first difference."""
    steps = 0
    obs, _ = env.reset(seed=seed)
    for _ in range(episodes):
        state_full = state_stripped = None
        start = np.ones(1, dtype=bool)
        done = False
        while not done:
            action, state_full = full.predict(obs, state=state_full, episode_start=start, deterministic=True)
            other, state_stripped = stripped.predict(
                obs, state=state_stripped, episode_start=start, deterministic=True
            )
            if not np.array_equal(action, other):
                raise UserError(f"the stripped model acts differently at step {steps}: {action} != {other}")
            start = np.zeros(1, dtype=bool)
            obs, _, terminated, truncated, _ = env.step(action)
            done = bool(terminated or truncated)
            steps += 1
        obs, _ = env.reset()
    return steps


if __name__ == "__main__":
    # ``python -m sb3_hfo.models list`` would otherwise run this library module and do nothing. The command line
    # lives in sb3_hfo.cli.models, which imports this module, so it is named here rather than imported.
    import sys

    print(
        "error: sb3_hfo.models is the library; its command line is python -m sb3_hfo.cli.models "
        "(list, add NAME MODEL ..., real NAME ...)",
        file=sys.stderr,
    )
    raise SystemExit(2)  # a user error, as the command-line tools exit on one
