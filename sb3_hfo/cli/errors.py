"""User errors of the command-line tools: one line ``error: <what is wrong>`` on stderr, exit code 2.

``train``, ``evaluate``, ``plot``, ``enjoy`` and ``record_video`` check what a user can get wrong (a missing or
damaged model, a missing ``--conf-file``, a missing ``--env``, bad env kwargs, a negative seed, a bad option)
before the work starts and report it with :func:`fail`. Tracebacks are left for bugs.

rl-zoo3's own parsers (``train``, ``enjoy``, ``record_video`` hand their command line to rl-zoo3) are checked by
:func:`check_train_args` and :func:`check_playback_args` first; :func:`one_line_argparse_errors` turns the
option errors that rl-zoo3's parser still finds into one line as well.
"""

from __future__ import annotations

import argparse
import contextlib
import difflib
import importlib.util
import inspect
import io
import os
import sys
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any, NoReturn

import gymnasium as gym

import hfo2d
from sb3_hfo.cli.configs import config_names, is_bare_name
from sb3_hfo.cli.zoo import ALGO_NAME, BATCH_CONFIG_KEYS, ConfigConflictError, algo_classes, batch_options

# The library's errors and checks, also offered here (`as` marks them re-exported) for the command-line tools.
from sb3_hfo.errors import UserError as UserError
from sb3_hfo.errors import module_missing as module_missing
from sb3_hfo.errors import one_line as one_line
from sb3_hfo.evaluation import hfo_env_ids
from sb3_hfo.models import check_model_zip as check_model_zip
from sb3_hfo.skill_ddpg.legacy import LEGACY_POLICY_OPTIONS

#: Exit status of a user error (argparse's).
USAGE_EXIT_CODE = 2


class UsageExit(SystemExit):
    """``SystemExit(2)`` whose ``str()`` is the one-line message (already written to stderr)."""

    def __init__(self, message: str) -> None:
        super().__init__(USAGE_EXIT_CODE)
        self.message = message

    def __str__(self) -> str:
        return self.message


def fail(message: object) -> NoReturn:
    """Write ``error: <message>`` (one line) to stderr and exit with code 2."""
    line = f"error: {one_line(message)}"
    print(line, file=sys.stderr)
    raise UsageExit(line)


class OneLineArgumentParser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are one line (no usage block), exit code 2."""

    def error(self, message: str) -> NoReturn:
        fail(f"{message} (see {self.prog} --help)")


@contextlib.contextmanager
def one_line_argparse_errors(prog: str) -> Iterator[None]:
    """While active, every ArgumentParser (rl-zoo3's included) reports an error in one line naming ``prog``."""
    original = argparse.ArgumentParser.error

    def error(parser: argparse.ArgumentParser, message: str) -> NoReturn:
        fail(f"{message} (see {prog} --help)")

    argparse.ArgumentParser.error = error  # type: ignore[method-assign]
    try:
        yield
    finally:
        argparse.ArgumentParser.error = original  # type: ignore[method-assign]


def non_negative_int(text: str) -> int:
    """argparse type of a seed: an integer >= 0."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be an integer, got {text!r}") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be >= 0, got {value}")
    return value


# --------------------------------------------------------------------------------------------------------------
# Models, env kwargs


def check_env_kwargs(env_id: str, env_kwargs: dict[str, Any], what: str = "--env-kwargs") -> None:
    """UserError when an hfo2d env ``env_id`` cannot be made with ``env_kwargs`` (other ids are not checked:
    making a real-HFO env would start a server)."""
    if env_id not in hfo2d.ENV_IDS:
        return
    try:
        env = gym.make(env_id, **env_kwargs)
    except (TypeError, ValueError) as error:
        raise UserError(f"bad {what} for {env_id} {env_kwargs}: {one_line(error)}") from None
    env.close()


def parse_zoo_dict(items: Sequence[str], option: str) -> dict[str, Any]:
    """``KEY:VALUE`` items as rl-zoo3's ``StoreDict`` reads them (VALUE evaluated as Python); UserError naming
    the item that fails."""
    from rl_zoo3.utils import StoreDict

    action = StoreDict(option_strings=[option], dest="parsed", nargs="+")
    parsed: dict[str, Any] = {}
    for item in items:
        namespace = argparse.Namespace()
        if ":" not in item:
            raise UserError(f"{option} expects KEY:VALUE items, got {item!r}")
        try:
            action(argparse.ArgumentParser(), namespace, [item])
        except Exception as error:  # StoreDict evaluates the value: any error is the item's
            raise UserError(
                f"{option} {item!r}: the value is not a Python literal ({one_line(error)})"
            ) from None
        parsed.update(namespace.parsed)
    return parsed


# --------------------------------------------------------------------------------------------------------------
# rl-zoo3 command lines


def option_value(args: Sequence[str], *names: str) -> str | None:
    """Value of the last ``--name value`` / ``--name=value`` among ``args`` (None when absent)."""
    value = None
    for index, arg in enumerate(args):
        name, sep, inline = arg.partition("=")
        if name in names:
            value = inline if sep else (args[index + 1] if index + 1 < len(args) else None)
    return value


def option_values(args: Sequence[str], *names: str) -> list[str] | None:
    """The items after the last ``--name`` (``nargs="+"``: up to the next option); None when absent."""
    values = None
    for index, arg in enumerate(args):
        if arg in names:
            values = []
            for item in args[index + 1 :]:
                if item.startswith("-"):
                    break
                values.append(item)
    return values


def _known_ids() -> str:
    return ", ".join(hfo_env_ids())


def check_env_option(args: Sequence[str], example: str) -> str:
    """The ``--env`` of an rl-zoo3 command line: UserError when it is missing (rl-zoo3 would fall back to
    CartPole-v1) or not registered."""
    env_id = option_value(args, "--env")
    if env_id is None:
        raise UserError(
            f"--env is required (rl-zoo3 would fall back to CartPole-v1), e.g. {example}; "
            f"registered HFO ids: {_known_ids()}"
        )
    if env_id not in gym.registry:
        raise UserError(f"unknown env id {env_id!r}; registered HFO ids: {_known_ids()}")
    return env_id


def check_seed_option(args: Sequence[str], hint: str = "") -> None:
    """UserError for a negative ``--seed`` (a non-integer one is left to the parser)."""
    seed = option_value(args, "--seed")
    try:
        negative = seed is not None and int(seed) < 0
    except ValueError:
        return
    if negative:
        raise UserError(f"--seed must be >= 0, got {seed}{hint}")


def _load_yaml(path: Path) -> Any:
    import yaml

    try:
        with open(path) as f:
            return yaml.safe_load(f)
    except yaml.YAMLError as error:
        raise UserError(f"--conf-file {path} is not valid YAML: {one_line(error)}") from None


def _config_names() -> str:
    return ", ".join(config_names()) or "none found"


def check_train_args(args: Sequence[str]) -> None:
    """The user errors of a ``train`` command line, before rl-zoo3 starts (see the module docstring)."""
    conf = option_value(args, "-conf", "--conf-file")
    if conf is None:
        # rl-zoo3 would otherwise look for hyperparams/skill_ddpg.yml inside its own package.
        raise UserError(
            "--conf-file is required: a YAML file, or the name of one that comes with sb3-hfo "
            f"({_config_names()}), e.g. --conf-file e1_empty_goal_fast"
        )
    is_path = not is_bare_name(conf)
    if is_path and not Path(conf).is_file():
        raise UserError(f"--conf-file {conf}: no such file")
    if not is_path:
        try:
            found = importlib.util.find_spec(conf) is not None
        except (ImportError, ValueError):
            found = False
        if not found:
            close = difflib.get_close_matches(conf, config_names(), n=1)
            raise UserError(
                f"--conf-file {conf}: no such file, config of sb3-hfo, nor importable Python module; "
                + (f"did you mean {close[0]}?" if close else f"the configs: {_config_names()}")
            )
    env_id = check_env_option(args, "--env HFO/EmptyGoal-v0")
    check_seed_option(args, " (leave --seed out for a random one)")
    zoo_dicts = {}
    for option in ("--env-kwargs", "--eval-env-kwargs", "-params", "--hyperparams"):
        items = option_values(args, option)
        if items is not None:
            zoo_dicts[option] = parse_zoo_dict(items, option)
    config_kwargs: dict[str, Any] = {}
    if conf.endswith((".yml", ".yaml")):
        config = _load_yaml(Path(conf))
        if not isinstance(config, dict):
            raise UserError(f"--conf-file {conf}: expected a mapping of env ids to hyperparameters")
        section = config.get(env_id, config.get("default"))
        if not isinstance(section, dict):
            raise UserError(
                f"--conf-file {conf} has no hyperparameters for {env_id} (it has: {', '.join(map(str, config))})"
            )
        config_kwargs = dict(section.get("env_kwargs") or {})
        check_hyperparameter_keys(section, f"--conf-file {conf}", option_value(args, "--algo"))
    if "--hyperparams" in zoo_dicts or "-params" in zoo_dicts:
        cli_hyperparams = {**zoo_dicts.get("-params", {}), **zoo_dicts.get("--hyperparams", {})}
        check_hyperparameter_keys(cli_hyperparams, "--hyperparams", option_value(args, "--algo"))
    if "--env-kwargs" in zoo_dicts:
        # rl-zoo3: the command line's env_kwargs replace the config's
        check_env_kwargs(env_id, zoo_dicts["--env-kwargs"])
    else:
        check_env_kwargs(env_id, config_kwargs, what=f"env_kwargs in {conf}")
    if "--eval-env-kwargs" in zoo_dicts:
        check_env_kwargs(env_id, zoo_dicts["--eval-env-kwargs"], what="--eval-env-kwargs")


#: Config keys that rl-zoo3 (2.x, ``ExperimentManager._preprocess_hyperparams`` and ``_preprocess_action_noise``)
#: reads itself instead of passing them to the algorithm.
ZOO_CONFIG_KEYS: tuple[str, ...] = (
    "n_timesteps",
    "n_envs",
    "normalize",
    "monitor_kwargs",
    "env_kwargs",
    "frame_stack",
    "env_wrapper",
    "vec_env_wrapper",
    "callback",
    "noise_type",
    "noise_std",
)
#: Constructor arguments that rl-zoo3 sets from its own options (a config that sets them too makes the constructor
#: fail with "got multiple values").
ZOO_OPTION_ARGS: dict[str, str] = {
    "env": "--env",
    "seed": "--seed",
    "verbose": "--verbose",
    "device": "--device",
    "tensorboard_log": "--tensorboard-log",
}


def constructor_arguments(cls: type) -> list[str]:
    """The keyword arguments of ``cls(...)``, following ``**kwargs`` up the base classes (SkillPDQN passes its
    own to SkillDDPG); private ones (``_init_setup_model``) left out."""
    names: list[str] = []
    for klass in cls.__mro__:
        if "__init__" not in vars(klass):
            continue
        parameters = list(inspect.signature(klass.__init__).parameters.values())[1:]
        names += [p.name for p in parameters if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)]
        if not any(p.kind == p.VAR_KEYWORD for p in parameters):
            break
    return sorted({name for name in names if not name.startswith("_")})


def _check_names(given: Sequence[str], valid: Sequence[str], what: str, where: str) -> None:
    for name in given:
        if name in valid:
            continue
        close = difflib.get_close_matches(str(name), valid, n=1)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        raise UserError(f"{where}: unknown {what} {name!r}{hint}; valid: {', '.join(valid)}")


def check_hyperparameter_keys(hyperparams: dict[str, Any], where: str, algo: str | None) -> None:
    """UserError naming a key of ``hyperparams`` (a config section or ``--hyperparams``) that neither rl-zoo3 nor
    the algorithm's constructor takes, with the closest valid key; the same for the keys of a ``policy_kwargs``
    dict when the policy is the algorithm's own. Algorithms other than sb3_hfo's are not checked."""
    algo_class = algo_classes().get(algo or ALGO_NAME)
    if algo_class is None:
        return
    for name, option in ZOO_OPTION_ARGS.items():
        if name in hyperparams:
            raise UserError(f"{where}: {name!r} is set by rl-zoo3's {option} option, not as a hyperparameter")
    arguments = [name for name in constructor_arguments(algo_class) if name not in ZOO_OPTION_ARGS]
    label = algo or ALGO_NAME
    valid_keys = sorted({*arguments, *ZOO_CONFIG_KEYS, *BATCH_CONFIG_KEYS})
    _check_names(list(hyperparams), valid_keys, f"{label} hyperparameter", where)
    try:
        batch_options(hyperparams, partial=True)
    except ConfigConflictError as error:
        raise UserError(f"{where}: {error}") from None
    policy_kwargs = hyperparams.get("policy_kwargs")
    policy_class = algo_class.policy_aliases.get(hyperparams.get("policy", "MlpPolicy"))
    if isinstance(policy_kwargs, dict) and policy_class is not None:
        # observation_space, action_space and lr_schedule are the algorithm's to pass
        policy_arguments = [
            name
            for name in constructor_arguments(policy_class)
            if name not in ("observation_space", "action_space", "lr_schedule")
        ]
        valid = sorted({*policy_arguments, *LEGACY_POLICY_OPTIONS})
        _check_names(list(policy_kwargs), valid, f"{policy_class.__name__} policy_kwargs key", where)


#: The modules each extra of pyproject.toml brings (top-level import names) and what needs them.
EXTRA_MODULES: dict[str, tuple[str, ...]] = {
    "zoo": ("rl_zoo3", "optuna", "pandas", "matplotlib", "requests"),
    "render": ("pygame", "moviepy"),
}


def check_installed(extra: str, modules: Sequence[str], needed_by: str) -> None:
    """UserError naming ``pip install -e ".[extra]"`` when one of ``modules`` (of that extra) is missing.

    ``pip install -e .`` installs the Python API only; the command-line tools' dependencies are the ``[zoo]``
    and ``[render]`` extras, so a missing one is a user's install, not a bug: one line instead of a traceback.
    """
    unknown = set(modules) - set(EXTRA_MODULES[extra])
    if unknown:
        raise ValueError(f"{sorted(unknown)} are not modules of the [{extra}] extra")
    missing = [name for name in modules if module_missing(name)]
    if missing:
        raise UserError(
            f"{needed_by} needs {' and '.join(missing)}, from the [{extra}] extra: "
            f'pip install -e ".[{extra}]" (in the sb3-hfo folder)'
        )


def check_render_extra(video: bool = False) -> None:
    """UserError naming the ``[render]`` extra when pygame (a window, every frame) or, for a video, moviepy is
    missing."""
    modules = ("pygame", "moviepy") if video else ("pygame",)
    check_installed("render", modules, "recording a video" if video else "a window (or pass --no-render)")


def check_output_folder(folder: str | Path, option: str) -> None:
    """UserError unless ``folder`` is a writable folder or one that can be made: its nearest existing ancestor is
    a writable folder. Nothing is created."""
    target = Path(folder).absolute()
    existing = target
    try:
        while not existing.exists():
            existing = existing.parent
    except OSError as error:  # e.g. a parent that may not be searched
        raise UserError(f"{option} {folder}: cannot create it ({one_line(error)})") from None
    if not existing.is_dir():
        where = "it is a file" if existing == target else f"{existing} is a file"
        raise UserError(f"{option} {folder}: cannot make a folder there, {where}")
    if not os.access(existing, os.W_OK | os.X_OK):
        where = "it is" if existing == target else f"{existing} is"
        raise UserError(f"{option} {folder}: cannot write there, {where} not writable")


def check_playback_args(args: Sequence[str], algo: str) -> Path:
    """The user errors of an ``enjoy`` / ``record_video`` command line; returns the model rl-zoo3 will load."""
    from huggingface_sb3 import EnvironmentName
    from rl_zoo3.utils import get_model_path

    env_id = check_env_option(args, "--env HFO/EmptyGoal-v0")
    check_seed_option(args)
    items = option_values(args, "--env-kwargs")
    if items is not None:
        check_env_kwargs(env_id, parse_zoo_dict(items, "--env-kwargs"))
    folder = option_value(args, "-f", "--folder")
    if folder is None:
        raise UserError(
            "-f/--folder is required: the rl-zoo3 log folder of the run, e.g. -f logs/ (the folder train's -f wrote)"
        )
    try:
        exp_id = int(option_value(args, "--exp-id") or 0)
        checkpoint = option_value(args, "--load-checkpoint")
    except ValueError:
        return Path(folder)  # rl-zoo3's parser names the bad --exp-id
    try:
        with contextlib.redirect_stdout(io.StringIO()):  # it prints "Loading latest experiment"
            _, model_path, _ = get_model_path(
                exp_id,
                folder,
                option_value(args, "--algo") or algo,
                EnvironmentName(env_id),
                "--load-best" in args,
                checkpoint,
                "--load-last-checkpoint" in args,
            )
    except (AssertionError, ValueError) as error:
        raise UserError(one_line(error)) from None
    check_model_zip(model_path)
    return Path(model_path)
