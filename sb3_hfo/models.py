"""The committed models: one per task, listed in ``models/manifest.json`` and stored without training state.

A committed model is a SkillDDPG ``.zip`` *stripped* of what only training needs (the optimizers' moment
estimates and the target networks): it holds the policy's online weights (actor and critics) and the model's
``data`` entry, which is what ``predict`` needs, in about a third of the full file. :func:`load_model` loads a
stripped zip, or a full one, through ``SkillDDPG.load``: the target networks are rebuilt as copies of the online
ones and the optimizers start afresh, so the loaded model acts exactly as the full one (``add`` checks it on every
model it writes) and can be trained further like a freshly warm-started one.

The manifest names each model (``e1``, ``e6``, ...) and records its config, training seed, env id, the acting
strategies it was saved with (their text form), the JSON of its 1,000-episode evaluation (:mod:`sb3_hfo.evaluate`) and, where
measured, its real-HFO figure. ``evaluate``, ``enjoy`` and ``record_video`` accept a manifest name wherever they
accept a model. One command adds (or replaces) a model::

    python -m sb3_hfo.models add e1 logs/skill_ddpg/HFO-EmptyGoal-v0_1/best_model.zip \\
        --config zoo_configs/x5_empty_goal_max_target_kickable_fast.yml --seed 1 --env HFO/EmptyGoal-v0

It strips the model into ``models/<name>.zip``, checks that the stripped model's actions equal the full one's,
evaluates it over 1,000 episodes (``--episodes``, ``--eval-seed``) and writes the manifest entry. A real-HFO
evaluation of a committed model (``python -m sb3_hfo.evaluate NAME --env HFO/RealKeeper-v0 ... --json F``) is
recorded in its entry with ``python -m sb3_hfo.models real NAME F --source "..."``.
``python -m sb3_hfo.models list`` prints the manifest.
"""

from __future__ import annotations

import argparse
import hashlib
import io
import json
import sys
import tempfile
import zipfile
from collections.abc import Sequence
from dataclasses import asdict
from pathlib import Path
from typing import Any

from sb3_hfo.cli.errors import OneLineArgumentParser, UserError, fail, module_missing, non_negative_int

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


def _target_source(key: str) -> str | None:
    """The online parameter a target-network parameter copies (``actor_target.x`` -> ``actor.x``); None for a
    parameter that is not a target's."""
    module, sep, rest = key.partition(".")
    if module.endswith("_target"):
        return f"{module[: -len('_target')]}{sep}{rest}"
    return None


def _torch_bytes(obj: Any) -> bytes:
    import torch

    buffer = io.BytesIO()
    torch.save(obj, buffer)
    return buffer.getvalue()


def _torch_object(raw: bytes) -> Any:
    import torch

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

    ``kwargs`` go to ``load`` (e.g. ``device="cpu"``, ``buffer_size=1``, ``env=...``).
    """
    from sb3_hfo.cli.zoo import skill_ddpg_class

    if not Path(path).is_file() and looks_like_name(str(path)):
        entry = manifest_entry(str(path))
        if entry is None:
            raise UserError(unknown_name_message(str(path)))
        path = model_file(entry)
    algo_class = algo_class or skill_ddpg_class()
    saved_class = saved_algo_class(path)
    if saved_class is not None and not issubclass(algo_class, saved_class):
        algo_class = saved_class
        kwargs.pop("buffer_size", None)  # an on-policy model has no replay buffer
    source: Any = full_model_buffer(path) if is_stripped(path) else str(path)
    if module_missing("rl_zoo3"):
        # Models trained through rl-zoo3 may pickle its schedules; without the [zoo] extra they load as equals.
        from sb3_hfo.common.schedules import rl_zoo3_free_custom_objects

        kwargs["custom_objects"] = {**rl_zoo3_free_custom_objects(source), **kwargs.get("custom_objects", {})}
    return algo_class.load(source, **kwargs)


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
# enjoy / record_video


def playback_argv(args: Sequence[str], run_root: Path) -> list[str]:
    """An ``enjoy`` / ``record_video`` command line whose first argument is a MODEL (a manifest name, a ``.zip`` or
    an rl-zoo3 run folder), rewritten for rl-zoo3, which loads models only from its log-folder layout.

    The model is linked into ``run_root`` as run 1 of that layout (``-f run_root --exp-id 1``); ``--env`` and
    ``--env-kwargs`` default to the manifest's (or the run folder's). A command line without a MODEL is returned
    unchanged. Raises UserError for an unknown name or a MODEL given together with ``-f``.
    """
    from huggingface_sb3 import EnvironmentName

    from sb3_hfo.cli.errors import option_value, option_values
    from sb3_hfo.cli.evaluate import REMOVED_ENV_KWARGS, resolve_model
    from sb3_hfo.cli.zoo import ALGO_NAME

    args = list(args)
    if not args or args[0].startswith("-"):
        return args
    model, rest = args[0], args[1:]
    if option_value(rest, "-f", "--folder") is not None:
        raise UserError(f"give either a MODEL ({model}) or -f/--folder, not both")
    resolved = resolve_model(model)
    env_id = option_value(rest, "--env") or resolved.env_id
    if env_id is None:
        raise UserError(
            f"--env is required for {model} (it is not a committed model nor inside an rl-zoo3 run)"
        )
    env_name = EnvironmentName(env_id)
    algo = option_value(rest, "--algo") or ALGO_NAME
    run = run_root / algo / f"{env_name}_1"
    run.mkdir(parents=True, exist_ok=True)
    (run / f"{env_name}.zip").symlink_to(resolved.path.resolve())
    extra = ["--env", env_id] if option_value(rest, "--env") is None else []
    if option_values(rest, "--env-kwargs") is None:
        kwargs = {k: v for k, v in resolved.env_kwargs.items() if k not in REMOVED_ENV_KWARGS}
        if kwargs:
            extra += ["--env-kwargs", *(f"{key}:{value!r}" for key, value in kwargs.items())]
    return [*rest, *extra, "-f", str(run_root), "--exp-id", "1"]


# --------------------------------------------------------------------------------------------------------------
# add


def machine_description() -> str:
    """The CPU model and core count of this machine, e.g. ``"AMD EPYC, 2 cores"`` (where evaluation figures
    were measured: other CPUs can draw other episodes from the same seed)."""
    import os
    import platform

    cpu = platform.processor() or platform.machine()
    cpuinfo = Path("/proc/cpuinfo")
    if cpuinfo.is_file():
        for line in cpuinfo.read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.partition(":")[2].strip()
                break
    return f"{cpu}, {os.cpu_count()} cores"


def _sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def check_same_actions(
    full: Any, stripped: Any, env: Any, episodes: int = CHECK_EPISODES, seed: int = 0
) -> int:
    """Play ``episodes`` with ``full`` and compare ``stripped``'s ``predict`` (state and episode starts
    included) at every step; returns the number of steps compared. Raises UserError at the first difference."""
    import numpy as np

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


def _real_hfo_entry(args: argparse.Namespace) -> dict[str, Any] | None:
    from sb3_hfo.cli.evaluate import wilson_interval

    status_counts: dict[str, int] | None = None
    if args.real_hfo_json:
        result = _read_real_hfo_json(args.real_hfo_json)
        goals, episodes, env_id = int(result["goals"]), int(result["episodes"]), result["env_id"]
        status_counts = result.get("status_counts")
    elif args.real_hfo:
        goals_text, _, episodes_text = args.real_hfo.partition("/")
        try:
            goals, episodes = int(goals_text), int(episodes_text)
        except ValueError:
            raise UserError(
                f"--real-hfo expects GOALS/EPISODES, e.g. 348/1000, got {args.real_hfo!r}"
            ) from None
        if not 0 <= goals <= episodes or episodes < 1:
            raise UserError(f"--real-hfo {args.real_hfo}: need 0 <= goals <= episodes, episodes >= 1")
        env_id = args.real_hfo_env
        if not env_id:
            raise UserError("--real-hfo needs --real-hfo-env (the real-HFO env id it was measured on)")
    else:
        return None
    low, high = wilson_interval(goals, episodes)
    entry: dict[str, Any] = {
        "env_id": env_id,
        "goals": goals,
        "episodes": episodes,
        "scoring_rate": goals / episodes,
        "scoring_rate_ci95": [low, high],
        "source": args.real_hfo_source or "",
    }
    if status_counts is not None:
        entry["status_counts"] = status_counts
    return entry


def _read_real_hfo_json(path: str) -> dict[str, Any]:
    """An ``evaluate --json`` result of a real-HFO env; UserError naming the file if it is not one."""
    try:
        result = json.loads(Path(path).read_text())
    except FileNotFoundError:
        raise UserError(f"{path}: no such file") from None
    except (OSError, ValueError) as error:
        raise UserError(f"{path}: not an evaluate --json file ({error})") from None
    missing = [
        key for key in ("goals", "episodes", "env_id") if not isinstance(result, dict) or key not in result
    ]
    if missing:
        raise UserError(f"{path}: not an evaluate --json file (no {', '.join(missing)})")
    if not str(result["env_id"]).startswith("HFO/Real"):
        raise UserError(f"{path}: measured on {result['env_id']}, not a real-HFO env (HFO/Real...)")
    return result


def record_real_hfo(args: argparse.Namespace, manifest_path: Path = MANIFEST_PATH) -> dict[str, Any]:
    """Record a real-HFO evaluation of committed model ``args.name`` in its manifest entry; returns the entry.

    The JSON must be of that very file: its ``model`` path, if it names a file, must hash to the entry's sha256.
    """
    models = read_manifest(manifest_path)
    if args.name not in models:
        raise UserError(unknown_name_message(args.name, manifest_path))
    if not args.source.strip():
        raise UserError("--source must say how and where the real-HFO figure was measured")
    result = _read_real_hfo_json(args.json)
    entry = models[args.name]
    measured = Path(str(result.get("model", "")))
    if measured.is_file() and _sha256(measured) != entry["sha256"]:
        raise UserError(
            f"{args.json} evaluated {measured}, not the committed {entry['file']} (sha256 differs)"
        )
    real = _real_hfo_entry(argparse.Namespace(real_hfo_json=args.json, real_hfo_source=args.source))
    entry["real_hfo"] = json.loads(json.dumps(real))
    write_manifest(models, manifest_path)
    return entry


def add(args: argparse.Namespace, manifest_path: Path = MANIFEST_PATH) -> dict[str, Any]:
    """Strip, check, evaluate and record one model (see the module docstring); returns its manifest entry."""
    import torch

    from sb3_hfo.cli.errors import check_model_zip
    from sb3_hfo.cli.evaluate import (
        REMOVED_ENV_KWARGS,
        check_env_id,
        evaluate,
        resolve_model,
    )
    from sb3_hfo.skill_ddpg.acting import format_acting

    if not looks_like_name(args.name) or not args.name.replace("_", "").replace("-", "").isalnum():
        raise UserError(f"model name {args.name!r}: use letters, digits, '_' and '-' only")
    resolved = resolve_model(args.source)
    check_model_zip(resolved.path)
    env_id = args.env or resolved.env_id
    if env_id is None:
        raise UserError("--env is required (the source is not inside an rl-zoo3 run folder)")
    check_env_id(env_id)
    if not Path(args.config).is_file():
        raise UserError(f"--config {args.config}: no such file")
    real_hfo = _real_hfo_entry(args)
    env_kwargs = {k: v for k, v in resolved.env_kwargs.items() if k not in REMOVED_ENV_KWARGS}

    import gymnasium as gym

    torch.set_num_threads(1)
    full = load_model(resolved.path, device="cpu", buffer_size=1)
    try:
        if args.acting is not None:
            full.policy.acting = args.acting
    except ValueError as error:
        raise UserError(str(error)) from error
    out = model_file({"file": f"{args.name}.zip"}, manifest_path)
    with tempfile.TemporaryDirectory() as tmp:
        full_with_options = Path(tmp) / "full.zip"
        full.save(full_with_options)
        size = strip_model(full_with_options, out)
    if size > MAX_MODEL_BYTES:
        out.unlink()
        raise UserError(f"the stripped model is {size:,} bytes, more than {MAX_MODEL_BYTES:,}")
    stripped = load_model(out, device="cpu", buffer_size=1)
    env = gym.make(env_id, **env_kwargs)
    try:
        compared = check_same_actions(full, stripped, env)
    except UserError:
        out.unlink()
        raise
    finally:
        env.close()
    print(f"{out}: {size:,} bytes; the same actions as {resolved.path} in {compared} steps")
    result = evaluate(
        str(out), env_id=env_id, episodes=args.episodes, seed=args.eval_seed, env_kwargs=env_kwargs
    )
    evaluation = asdict(result)
    evaluation["model"] = f"models/{out.name}"
    low, high = result.scoring_rate_ci95
    print(f"{args.name}: {result.scoring_rate:.1%} [{low:.1%}, {high:.1%}] over {result.episodes} episodes")
    entry = {
        "file": out.name,
        "bytes": size,
        "sha256": _sha256(out),
        "env_id": env_id,
        "env_kwargs": env_kwargs,
        "config": args.config,
        "seed": args.seed,
        "source": args.source_note or str(args.source),
        "acting": format_acting(stripped.policy.acting),
        "evaluation_command": f"python -m sb3_hfo.evaluate {args.name} --episodes {args.episodes} "
        f"--seed {args.eval_seed} --json {args.name}.json",
        "evaluation": evaluation,
        "evaluation_machine": machine_description(),
        "real_hfo": real_hfo,
        "note": args.note or "",
    }
    if args.method:
        entry["method"] = args.method
    entry = json.loads(json.dumps(entry))  # as the manifest holds it (tuples become lists)
    models = read_manifest(manifest_path)
    models[args.name] = entry
    write_manifest(dict(sorted(models.items())), manifest_path)
    return entry


# --------------------------------------------------------------------------------------------------------------
# Command line


def build_parser() -> argparse.ArgumentParser:
    from sb3_hfo.cli.evaluate import add_acting_argument

    parser = OneLineArgumentParser(prog="python -m sb3_hfo.models", description=__doc__.split("\n")[0])
    commands = parser.add_subparsers(dest="command", required=True, parser_class=OneLineArgumentParser)
    commands.add_parser("list", help="print the manifest's models")
    add_parser = commands.add_parser("add", help="strip, check, evaluate and record a model")
    add_parser.add_argument("name", help="manifest name, e.g. e1")
    add_parser.add_argument("source", help="a SkillDDPG .zip or rl-zoo3 run folder")
    add_parser.add_argument("--config", required=True, help="the zoo_configs/ file it was trained with")
    add_parser.add_argument("--seed", type=non_negative_int, required=True, help="its training seed")
    add_parser.add_argument("--env", default=None, help="env id (default: the run folder's)")
    add_parser.add_argument("--source-note", default=None, help="where the model came from (default: SOURCE)")
    add_parser.add_argument("--episodes", type=non_negative_int, default=EVALUATION_EPISODES)
    add_parser.add_argument("--eval-seed", type=non_negative_int, default=EVALUATION_SEED)
    add_acting_argument(add_parser)
    add_parser.add_argument("--real-hfo", default=None, metavar="GOALS/EPISODES", help="a real-HFO result")
    add_parser.add_argument("--real-hfo-env", default=None, help="the real-HFO env id of --real-hfo")
    add_parser.add_argument("--note", default=None, help="a remark for the results page")
    add_parser.add_argument(
        "--method",
        default=None,
        help="how it was obtained, where not by the config's RL alone (the table shows it)",
    )
    add_parser.add_argument("--real-hfo-json", default=None, help="an evaluate --json file of a real-HFO run")
    add_parser.add_argument(
        "--real-hfo-source", default=None, help="how and when the real-HFO figure was measured"
    )
    real_parser = commands.add_parser("real", help="record a real-HFO evaluation of a committed model")
    real_parser.add_argument("name", help="manifest name, e.g. e6")
    real_parser.add_argument("json", help="the evaluate --json file of its run on a HFO/Real... env")
    real_parser.add_argument("--source", required=True, help="how, when and where it was measured")
    return parser


def print_manifest(manifest_path: Path = MANIFEST_PATH) -> None:
    for name, entry in read_manifest(manifest_path).items():
        evaluation = entry["evaluation"]
        low, high = evaluation["scoring_rate_ci95"]
        print(
            f"{name}: {entry['env_id']} {evaluation['scoring_rate']:.1%} [{low:.1%}, {high:.1%}] "
            f"({evaluation['episodes']} episodes), {entry['file']} {entry['bytes']:,} bytes, "
            f"{entry['config']} seed {entry['seed']}"
        )


def main(argv: Sequence[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        if args.command == "add":
            if args.episodes < 1:
                raise UserError("--episodes must be at least 1")
            add(args)
        elif args.command == "real":
            record_real_hfo(args)
        else:
            print_manifest()
    except UserError as error:
        fail(error)
    return 0


if __name__ == "__main__":
    sys.exit(main())
