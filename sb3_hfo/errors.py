"""The library's user errors: a mistake in what was asked for (a missing model, an unknown env id, bad env
kwargs), reported by the command-line tools (:mod:`sb3_hfo.cli.errors`) as one line and exit code 2."""

from __future__ import annotations

import importlib.util


class UserError(Exception):
    """A mistake in what the user asked for; the message names it in one line."""


def one_line(message: object) -> str:
    """``message`` with its whitespace (newlines included) collapsed to single spaces."""
    return " ".join(str(message).split())


def module_missing(module: str) -> bool:
    """Whether the top-level module ``module`` cannot be imported (looked up without importing it)."""
    try:
        return importlib.util.find_spec(module) is None
    except (ImportError, ValueError):  # a broken install, or sys.modules[module] set to a non-module
        return True
