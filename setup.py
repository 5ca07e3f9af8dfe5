"""Builds hfo2d's optional C kernels (hfo2d._accel); everything else is in pyproject.toml.

The extension is optional: without a C compiler ``pip install`` still succeeds and hfo2d runs its pure-Python
code, which stays the reference (``HFO2D_PURE_PYTHON=1`` forces it even when the extension is built).
``-ffp-contract=off`` (no fused multiply-add) and no ``-ffast-math``: the kernels must do the same IEEE
operations as the Python they port, bit for bit.
"""

from setuptools import Extension, setup

setup(
    ext_modules=[
        Extension(
            "hfo2d._accel",
            sources=["envs/hfo2d/_accel.c"],
            extra_compile_args=["-O2", "-ffp-contract=off", "-fno-fast-math"],
            optional=True,
        )
    ]
)
