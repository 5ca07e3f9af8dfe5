"""The committed models ship inside the package: an installed sb3_hfo finds them without a checkout (issue 35:
after a non-editable ``pip install .``, ``evaluate e1`` said "names: none")."""

from __future__ import annotations

import fnmatch
import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from sb3_hfo.models import MANIFEST_PATH, MODELS_DIR, model_file, read_manifest

REPO = Path(__file__).resolve().parents[2]
PACKAGE_DIR = REPO / "sb3_hfo"


def _package_data_globs() -> list[str]:
    tomllib = pytest.importorskip("tomllib")  # Python >= 3.11
    config = tomllib.loads((REPO / "pyproject.toml").read_text())
    return list(config["tool"]["setuptools"]["package-data"]["sb3_hfo"])


def _shipped(path: Path) -> bool:
    """Whether pyproject's package data for sb3_hfo takes ``path`` (a file inside the package) into a wheel."""
    relative = path.relative_to(PACKAGE_DIR).as_posix()
    return any(fnmatch.fnmatch(relative, pattern) for pattern in _package_data_globs())


def test_every_manifest_file_is_package_data() -> None:
    assert MODELS_DIR.resolve().parent == PACKAGE_DIR.resolve()
    assert _shipped(MANIFEST_PATH)
    manifest = read_manifest()
    assert manifest
    for name, entry in manifest.items():
        path = model_file(entry)
        assert path.is_file() and path.resolve().parent == MODELS_DIR.resolve(), name
        assert _shipped(path), f"{name}: {path} is not matched by pyproject's package-data"


def test_a_stray_file_is_not_package_data() -> None:
    assert not _shipped(PACKAGE_DIR / "pretrained" / "notes.txt")


def test_a_wheel_holds_the_models_and_finds_them_outside_a_checkout(tmp_path: Path) -> None:
    """Build a wheel (no dependencies, no network), unpack it and load a committed model by name from a folder
    where only the unpacked wheel is importable."""
    pytest.importorskip("setuptools")
    source = _mkdir(tmp_path / "source")  # a copy: the build's build/ and egg-info stay out of the checkout
    for name in ("pyproject.toml", "README.md", "LICENSE"):
        shutil.copy(REPO / name, source / name)
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc")
    shutil.copytree(PACKAGE_DIR, source / "sb3_hfo", ignore=ignore)
    shutil.copytree(REPO / "envs" / "hfo2d", source / "envs" / "hfo2d", ignore=ignore)
    wheels = tmp_path / "wheels"
    build = [sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "--no-index"]
    completed = subprocess.run(
        [*build, "-q", "-w", str(wheels), str(source)], capture_output=True, text=True, timeout=120
    )
    assert completed.returncode == 0, completed.stderr[-2000:]
    (wheel,) = wheels.glob("sb3_hfo-*.whl")
    with zipfile.ZipFile(wheel) as archive:
        names = set(archive.namelist())
        archive.extractall(tmp_path / "installed")
    expected = {f"sb3_hfo/pretrained/{entry['file']}" for entry in read_manifest().values()}
    assert {"sb3_hfo/pretrained/manifest.json", *expected} <= names
    elsewhere = _mkdir(tmp_path / "elsewhere")
    code = (
        "import sb3_hfo.models as m\n"
        "model = m.load_model('e1', device='cpu', buffer_size=1)\n"
        "print(m.__file__, type(model).__name__, sorted(m.read_manifest()))\n"
    )
    env = {key: value for key, value in os.environ.items() if key != "PYTHONPATH"}
    env["PYTHONPATH"] = str(tmp_path / "installed")
    completed = subprocess.run(
        [sys.executable, "-c", code], cwd=elsewhere, env=env, capture_output=True, text=True, timeout=120
    )
    assert completed.returncode == 0, completed.stderr[-2000:]
    module_file, algo, names_text = completed.stdout.split(" ", 2)
    assert Path(module_file).is_relative_to(tmp_path / "installed")
    assert algo == "HybridPPO" and "'e1'" in names_text


def _mkdir(path: Path) -> Path:
    path.mkdir(parents=True, exist_ok=True)
    return path
