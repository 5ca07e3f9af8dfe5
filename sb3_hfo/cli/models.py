"""The committed models' command line: ``python -m sb3_hfo.cli.models list | add | real``.

One command adds (or replaces) a model::

    python -m sb3_hfo.cli.models add e1 logs/skill_ddpg/HFO-EmptyGoal-v0_1/best_model.zip \\
        --config zoo_configs/empty_goal_skill_pdqn_fast.yml --seed 1 --env HFO/EmptyGoal-v0

It strips the model into ``sb3_hfo/pretrained/<name>.zip``, checks that the stripped model's actions equal the
full one's, evaluates it over 1,000 episodes (``--episodes``, ``--eval-seed``) and writes the manifest entry. A
model that a benchmark script made, not a zoo config, gives ``--script benchmarks/X.py --command "python
benchmarks/X.py ..."`` instead of ``--config`` (the entry then holds ``"config": null``). ``--evaluation-json F``
takes that evaluation from an ``evaluate --json`` run of SOURCE itself (checked: the same file by sha256, env,
episodes, seed and acting) instead of playing the episodes again. A
real-HFO evaluation of a committed model (``python -m sb3_hfo.evaluate NAME --env HFO/RealKeeper-v0 ... --json F``)
is recorded in its entry with ``python -m sb3_hfo.cli.models real NAME F --source "..."``.
``python -m sb3_hfo.cli.models list`` prints the manifest. The models themselves, stripping and loading are
:mod:`sb3_hfo.models`; :func:`playback_argv` lets ``enjoy`` and ``record_video`` take a model by name.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import platform
import sys
import tempfile
from collections.abc import Sequence
from dataclasses import asdict
from pathlib import Path
from typing import Any

import gymnasium as gym
import torch

from sb3_hfo.cli.errors import (
    OneLineArgumentParser,
    UserError,
    check_model_zip,
    fail,
    non_negative_int,
    option_value,
    option_values,
)
from sb3_hfo.cli.evaluate import add_acting_argument
from sb3_hfo.cli.zoo import ALGO_NAME, HYBRID_PPO_ALGO_NAME
from sb3_hfo.evaluation import REMOVED_ENV_KWARGS, check_env_id, evaluate, resolve_model, wilson_interval
from sb3_hfo.hybrid_ppo import HybridPPO
from sb3_hfo.models import (
    EVALUATION_EPISODES,
    EVALUATION_SEED,
    MANIFEST_PATH,
    MAX_MODEL_BYTES,
    MODELS_DIR,
    check_provenance,
    check_same_actions,
    load_model,
    looks_like_name,
    model_file,
    read_manifest,
    saved_algo_class,
    strip_model,
    trained_with,
    unknown_name_message,
    write_manifest,
)
from sb3_hfo.skill_ddpg.acting import format_acting

# --------------------------------------------------------------------------------------------------------------
# enjoy / record_video


def playback_argv(args: Sequence[str], run_root: Path) -> list[str]:
    """An ``enjoy`` / ``record_video`` command line whose first argument is a MODEL (a manifest name, a ``.zip`` or
    an rl-zoo3 run folder), rewritten for rl-zoo3, which loads models only from its log-folder layout.

    The model is linked into ``run_root`` as run 1 of that layout (``-f run_root --exp-id 1``); ``--env`` and
    ``--env-kwargs`` default to the manifest's (or the run folder's). A command line without a MODEL is returned
    unchanged. Raises UserError for an unknown name or a MODEL given together with ``-f``.
    """
    # rl-zoo3's dependency (the [zoo] extra), which enjoy and record_video check for first
    from huggingface_sb3 import EnvironmentName

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
    algo = option_value(rest, "--algo")
    extra: list[str] = []
    if algo is None:
        # The algorithm that saved the zip (SB3 zips record only the policy class): a HybridPPO model plays under
        # rl-zoo3's name "hybrid_ppo", anything else under SkillDDPG's.
        saved = saved_algo_class(resolved.path)
        algo = HYBRID_PPO_ALGO_NAME if saved is not None and issubclass(saved, HybridPPO) else ALGO_NAME
        extra += ["--algo", algo]
    run = run_root / algo / f"{env_name}_1"
    run.mkdir(parents=True, exist_ok=True)
    (run / f"{env_name}.zip").symlink_to(resolved.path.resolve())
    extra += ["--env", env_id] if option_value(rest, "--env") is None else []
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
    cpu = platform.processor() or platform.machine()
    cpuinfo = Path("/proc/cpuinfo")
    if cpuinfo.is_file():
        for line in cpuinfo.read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.partition(":")[2].strip()
                break
    return f"{cpu}, {os.cpu_count()} cores"


def _recorded_path(path: Path) -> str:
    """``path`` as the manifest records it: from the repository's root for a model in the package, else from its
    folder's name (``models/tiny.zip``)."""
    try:
        return path.resolve().relative_to(MODELS_DIR.parent.parent).as_posix()
    except ValueError:
        return f"{path.parent.name}/{path.name}"


def _sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _real_hfo_entry(args: argparse.Namespace) -> dict[str, Any] | None:
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


def _provenance(args: argparse.Namespace) -> dict[str, Any]:
    """The entry's ``config`` (a zoo config) or ``config: null`` with the ``script`` and ``command`` that made it."""
    if args.config is not None and (args.script is not None or args.command_line is not None):
        raise UserError(
            "give --config (a zoo config) or --script with --command (a benchmark script), not both"
        )
    if args.config is not None:
        if not Path(args.config).is_file():
            raise UserError(f"--config {args.config}: no such file")
        return {"config": args.config}
    if args.script is None or args.command_line is None:
        raise UserError("say how the model was trained: --config FILE, or --script FILE with --command LINE")
    fields = {"config": None, "script": args.script, "command": args.command_line}
    try:
        check_provenance(fields, Path.cwd())
    except ValueError as error:
        raise UserError(f"--script/--command: {error}") from None
    return fields


def _source_evaluation(
    args: argparse.Namespace, source: Path, env_id: str, env_kwargs: dict[str, Any], acting: str
) -> dict[str, Any]:
    """The ``evaluate --json`` result in ``args.evaluation_json``, checked to be SOURCE's evaluation as ``add``
    would run it (the same file by sha256, env id and kwargs, episodes, first seed, greedy, acting)."""
    path = args.evaluation_json
    try:
        result = json.loads(Path(path).read_text())
    except FileNotFoundError:
        raise UserError(f"--evaluation-json {path}: no such file") from None
    except (OSError, ValueError) as error:
        raise UserError(f"--evaluation-json {path}: not an evaluate --json file ({error})") from None
    if not isinstance(result, dict) or "model" not in result or "goals" not in result:
        raise UserError(f"--evaluation-json {path}: not an evaluate --json file (no model or goals)")
    evaluated = Path(str(result["model"]))
    if not evaluated.is_file() or _sha256(evaluated) != _sha256(source):
        raise UserError(
            f"--evaluation-json {path} evaluated {evaluated}, not {source} (missing, or sha256 differs)"
        )
    wanted = {
        "env_id": env_id,
        "env_kwargs": env_kwargs,
        "episodes": args.episodes,
        "seed": args.eval_seed,
        "deterministic": True,
        "acting": acting,
    }
    differing = [
        f"{key} {result.get(key)!r} (wanted {value!r})"
        for key, value in wanted.items()
        if result.get(key) != value
    ]
    if differing:
        raise UserError(f"--evaluation-json {path}: another evaluation: " + ", ".join(differing))
    return result


def add(args: argparse.Namespace, manifest_path: Path = MANIFEST_PATH) -> dict[str, Any]:
    """Strip, check, evaluate and record one model (see the module docstring); returns its manifest entry."""
    if not looks_like_name(args.name) or not args.name.replace("_", "").replace("-", "").isalnum():
        raise UserError(f"model name {args.name!r}: use letters, digits, '_' and '-' only")
    resolved = resolve_model(args.source)
    check_model_zip(resolved.path)
    env_id = args.env or resolved.env_id
    if env_id is None:
        raise UserError("--env is required (the source is not inside an rl-zoo3 run folder)")
    check_env_id(env_id)
    provenance = _provenance(args)
    real_hfo = _real_hfo_entry(args)
    env_kwargs = {k: v for k, v in resolved.env_kwargs.items() if k not in REMOVED_ENV_KWARGS}

    torch.set_num_threads(1)
    full = load_model(resolved.path, device="cpu", buffer_size=1)
    if args.acting is not None and not hasattr(full.policy, "acting"):
        raise UserError(
            f"--acting: {type(full.policy).__name__} has no acting strategies (SkillDDPG's option)"
        )
    try:
        if args.acting is not None:
            full.policy.acting = args.acting
    except ValueError as error:
        raise UserError(str(error)) from error
    # HybridPPO's policy acts by its own distribution: no acting strategies to record
    acting = format_acting(full.policy.acting) if hasattr(full.policy, "acting") else None
    source_evaluation = (  # checked before anything is written
        _source_evaluation(args, Path(resolved.path), env_id, env_kwargs, acting or "")
        if args.evaluation_json
        else None
    )
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
    evaluated_file: dict[str, str] | None = None
    if source_evaluation is not None:
        evaluation = source_evaluation
        evaluated_file = {"file": Path(resolved.path).name, "sha256": _sha256(Path(resolved.path))}
    else:
        result = evaluate(
            str(out), env_id=env_id, episodes=args.episodes, seed=args.eval_seed, env_kwargs=env_kwargs
        )
        evaluation = asdict(result)
    evaluation["model"] = _recorded_path(out)
    low, high = evaluation["scoring_rate_ci95"]
    rate, episodes = evaluation["scoring_rate"], evaluation["episodes"]
    print(f"{args.name}: {rate:.1%} [{low:.1%}, {high:.1%}] over {episodes} episodes")
    entry = {
        "file": out.name,
        "bytes": size,
        "sha256": _sha256(out),
        "env_id": env_id,
        "env_kwargs": env_kwargs,
        **provenance,
        "seed": args.seed,
        "source": args.source_note or str(args.source),
        "acting": acting,
        "evaluation_command": f"python -m sb3_hfo.evaluate {args.name} --episodes {args.episodes} "
        f"--seed {args.eval_seed} --json {args.name}.json",
        "evaluation": evaluation,
        "evaluation_machine": machine_description(),
        "real_hfo": real_hfo,
        "note": args.note or "",
    }
    if args.method:
        entry["method"] = args.method
    if evaluated_file:
        # the episodes were played by the unstripped SOURCE, whose stripped copy acts the same (checked above)
        entry["evaluated_file"] = evaluated_file
    entry = json.loads(json.dumps(entry))  # as the manifest holds it (tuples become lists)
    models = read_manifest(manifest_path)
    models[args.name] = entry
    write_manifest(dict(sorted(models.items())), manifest_path)
    return entry


# --------------------------------------------------------------------------------------------------------------
# Command line


def build_parser() -> argparse.ArgumentParser:
    parser = OneLineArgumentParser(prog="python -m sb3_hfo.cli.models", description=__doc__.split("\n")[0])
    commands = parser.add_subparsers(dest="command", required=True, parser_class=OneLineArgumentParser)
    commands.add_parser("list", help="print the manifest's models")
    add_parser = commands.add_parser("add", help="strip, check, evaluate and record a model")
    add_parser.add_argument("name", help="manifest name, e.g. e1")
    add_parser.add_argument("source", help="a SkillDDPG .zip or rl-zoo3 run folder")
    add_parser.add_argument("--config", default=None, help="the zoo_configs/ file it was trained with")
    add_parser.add_argument("--script", default=None, help="instead of --config: the script that made it")
    add_parser.add_argument(
        "--command",
        dest="command_line",
        default=None,
        help="with --script: the exact command line that ran it",
    )
    add_parser.add_argument(
        "--evaluation-json",
        default=None,
        help="an evaluate --json file of SOURCE (instead of evaluating again)",
    )
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
            f"{trained_with(entry)} seed {entry['seed']}"
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
