"""The zoo configs that come with sb3-hfo, by name: ``python -m sb3_hfo.train --conf-file e1_empty_goal_fast``.

The configs live in the repository's ``zoo_configs/`` folder. A wheel (``pip install .``, not editable) carries a
copy inside the package, ``sb3_hfo/zoo_configs/`` (setup.py's ``build_py`` puts it there), so that training works
from any folder, as ``evaluate e1`` does for the committed models; a checkout or an editable install reads the
folder itself. ``--conf-file`` still takes a path or a Python module, as rl-zoo3's does: a bare name (no ``/``, no
``.yml``/``.yaml``/``.py`` suffix) is looked up here first.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

CONFIG_SUFFIX = ".yml"
#: where a wheel carries the configs (setup.py copies zoo_configs/*.yml here at build time)
PACKAGED_CONFIGS = Path(__file__).resolve().parents[1] / "zoo_configs"
#: the repository's own folder, for a checkout and an editable install
CHECKOUT_CONFIGS = Path(__file__).resolve().parents[2] / "zoo_configs"


def config_dirs() -> list[Path]:
    """The folders that hold configs here, the packaged copy first."""
    return [folder for folder in (PACKAGED_CONFIGS, CHECKOUT_CONFIGS) if folder.is_dir()]


def config_names() -> list[str]:
    """Every config name that ``--conf-file NAME`` accepts, sorted."""
    return sorted({path.stem for folder in config_dirs() for path in folder.glob(f"*{CONFIG_SUFFIX}")})


def is_bare_name(conf: str) -> bool:
    """A ``--conf-file`` value that names no file: no folder, no YAML or Python suffix."""
    return "/" not in conf and "\\" not in conf and not conf.endswith((".yml", ".yaml", ".py"))


def find_config(name: str) -> Path | None:
    """The file of config ``name``, or None."""
    for folder in config_dirs():
        path = folder / f"{name}{CONFIG_SUFFIX}"
        if path.is_file():
            return path
    return None


def with_named_config(args: Sequence[str]) -> list[str]:
    """``args`` with a ``--conf-file`` (``-conf``) that names a shipped config replaced by the config's path."""
    resolved = list(args)
    for index, arg in enumerate(resolved):
        option, equals, value = arg.partition("=")
        if option not in ("--conf-file", "-conf"):
            continue
        if equals:
            path = find_config(value) if is_bare_name(value) else None
            if path is not None:
                resolved[index] = f"{option}={path}"
        elif index + 1 < len(resolved) and is_bare_name(resolved[index + 1]):
            path = find_config(resolved[index + 1])
            if path is not None:
                resolved[index + 1] = str(path)
    return resolved
