"""The repository's real-HFO tooling (tools/real_hfo): the files the messages name exist, the scripts parse and
explain themselves, the loopback runner isolates, and no file sends a user outside the repository."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from hfo2d import real

ROOT = Path(__file__).resolve().parents[2]
BUILD_SCRIPT = ROOT / "tools" / "real_hfo" / "build.sh"
LOOPBACK = ROOT / "tools" / "real_hfo" / "loopback.sh"


def test_the_build_hint_names_files_of_the_repository() -> None:
    named = set(re.findall(r"(?:tools|docs)/[\w./-]+\.(?:sh|md)", real.BUILD_HINT))
    assert {"tools/real_hfo/build.sh", "tools/real_hfo/loopback.sh", "docs/real_hfo.md"} <= named
    for path in named:
        assert (ROOT / path).is_file(), path
    for script in (BUILD_SCRIPT, LOOPBACK):
        assert os.access(script, os.X_OK), script


def test_the_build_script_parses_and_lists_its_sources_and_pins() -> None:
    subprocess.run(["bash", "-n", str(BUILD_SCRIPT)], check=True)
    shown = subprocess.run(
        ["bash", str(BUILD_SCRIPT), "--help"], capture_output=True, text=True, check=True
    ).stdout
    for default in (
        "https://github.com/LARG/HFO",
        "https://github.com/mhauskn/rcssserver",
        "https://github.com/mhauskn/librcsc",
        "b8b2a1d",
        "82212ee",
        "d222758",
        "--skip-apt",
    ):
        assert default in shown, default


def test_the_build_script_installs_flex_s_cxx_header_and_lists_what_it_installs() -> None:
    """rcssserver's coach-language lexer includes <FlexLexer.h>, which Debian ships in libfl-dev; ``flex`` only
    recommends that package, so ``apt-get --no-install-recommends flex`` left it out and the build failed on a fresh
    machine. The packages the script installs, its --help and docs/real_hfo.md must name the same list."""
    text = BUILD_SCRIPT.read_text()
    install = text.split("apt-get install -y -q --no-install-recommends", 1)[1].split("\nfi", 1)[0]
    installed = install.replace("\\", " ").split()
    assert "libfl-dev" in installed and "flex" in installed
    listed = text.split("installed with apt-get unless --skip-apt (root or sudo needed):", 1)[1]
    listed_packages = " ".join(
        line.lstrip("#").split("(the last two")[0] for line in listed.splitlines()[1:3]
    ).split()
    assert listed_packages == installed
    documented = (ROOT / "docs" / "real_hfo.md").read_text().replace("\n", " ")
    assert f"`{' '.join(installed)}`" in " ".join(documented.split())


@pytest.mark.parametrize(
    "args, message",
    [
        ([], "Usage"),
        (["--jobs", "0", "/tmp/x"], "--jobs must be a positive integer"),
        (["--bogus", "/tmp/x"], "unknown option --bogus"),
        (["/tmp/a", "/tmp/b"], "one DEST only"),
    ],
)
def test_the_build_script_refuses_bad_arguments_before_doing_anything(args: list[str], message: str) -> None:
    result = subprocess.run(["bash", str(BUILD_SCRIPT), *args], capture_output=True, text=True)
    assert result.returncode == 2
    assert message in result.stderr


def _can_unshare() -> bool:
    if shutil.which("unshare") is None or shutil.which("ip") is None:
        return False
    return subprocess.run(["bash", str(LOOPBACK), "true"], capture_output=True).returncode == 0


@pytest.mark.skipif(not _can_unshare(), reason="no unshare / ip here, or no right to make namespaces")
def test_the_loopback_runner_leaves_only_loopback_and_nothing_behind(tmp_path: Path) -> None:
    marker = tmp_path / "left_running"
    code = (
        "import socket, subprocess, sys\n"
        "print([name for _, name in socket.if_nameindex()])\n"
        # a child that would outlive a plain shell: it sleeps, then writes the marker
        f"subprocess.Popen(['sh', '-c', 'sleep 2; touch {marker}'], start_new_session=True)\n"
        "sys.exit(3)\n"
    )
    result = subprocess.run(
        ["bash", str(LOOPBACK), sys.executable, "-c", code], capture_output=True, text=True
    )
    assert result.returncode == 3  # the command's own exit status
    assert result.stdout.strip() == "['lo']"
    subprocess.run(["sleep", "3"], check=True)
    assert not marker.exists()  # the namespace's processes ended with the command


def test_the_real_hfo_benchmark_names_the_runner_outside_a_namespace() -> None:
    if real.in_loopback_namespace():
        pytest.skip("runs inside a loopback-only namespace, where the benchmark does not refuse")
    result = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "real_hfo.py"), "--hfo-dir", "/nonexistent"],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env={**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), str(ROOT / "envs")])},
    )
    assert result.returncode == 2
    assert "tools/real_hfo/loopback.sh" in result.stderr


def test_no_file_points_to_real_hfo_tools_outside_the_repository() -> None:
    """The real-HFO route once named a build script and a namespace script that lived beside the repository."""
    listed = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True)
    if listed.returncode != 0:
        pytest.skip("not a git checkout")
    outside = re.compile(r"shared/real_hfo|\.\./shared/|\bnetns\.sh\b")
    offenders = []
    for name in listed.stdout.splitlines():
        path = ROOT / name
        if (
            path.suffix not in {".py", ".md", ".sh", ".yml", ".yaml", ".toml", ".json", ".txt"}
            or not path.is_file()
        ):
            continue
        if path == Path(__file__).resolve():
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
            if outside.search(line):
                offenders.append(f"{name}:{number}")
    assert not offenders, offenders
