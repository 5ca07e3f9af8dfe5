"""Builds hfo2d's optional C kernels (hfo2d._accel, envs/hfo2d/_accel.c) and copies the zoo configs into the built
package (``_BuildPy``); everything else is in pyproject.toml.

The extension is optional: without a C compiler (or when it fails to build) ``pip install`` still succeeds and
hfo2d runs its pure-Python code, which stays the reference (``HFO2D_PURE_PYTHON=1`` forces it even when the
extension is built). The kernels must do the same IEEE operations as the Python they port, bit for bit, so GCC and
Clang compile them with ``-ffp-contract=off`` (no fused multiply-add; Clang contracts by default) and never with
``-ffast-math``; MSVC's default ``/fp:precise`` does not contract.

In a checkout: ``python setup.py build_ext --inplace`` puts the built module next to envs/hfo2d/accel.py.
"""

import shutil
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext
from setuptools.command.build_py import build_py

# GCC and Clang (the "unix" compiler of setuptools): exact IEEE arithmetic, see above
_UNIX_FLAGS = ["-O2", "-ffp-contract=off", "-fno-fast-math"]


class _BuildExt(build_ext):
    """build_ext with the exact-arithmetic flags for the compiler at hand."""

    def build_extensions(self) -> None:
        if self.compiler.compiler_type == "unix":
            for extension in self.extensions:
                extension.extra_compile_args = [*extension.extra_compile_args, *_UNIX_FLAGS]
        super().build_extensions()


class _BuildPy(build_py):
    """build_py that also puts the repository's zoo_configs/*.yml into the built package as sb3_hfo/zoo_configs/,
    so that ``--conf-file NAME`` works after a (non-editable) ``pip install .`` from any folder
    (sb3_hfo.cli.configs; an editable install reads zoo_configs/ itself)."""

    def run(self) -> None:
        super().run()
        source = Path(__file__).resolve().parent / "zoo_configs"
        if not source.is_dir():  # e.g. an sdist built without them: the package still installs
            return
        target = Path(self.build_lib) / "sb3_hfo" / "zoo_configs"
        target.mkdir(parents=True, exist_ok=True)
        for config in sorted(source.glob("*.yml")):
            shutil.copyfile(config, target / config.name)


setup(
    ext_modules=[Extension("hfo2d._accel", sources=["envs/hfo2d/_accel.c"], optional=True)],
    cmdclass={"build_ext": _BuildExt, "build_py": _BuildPy},
)
