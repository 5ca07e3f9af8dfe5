"""Watch a trained agent with rl-zoo3: ``python -m sb3_hfo.enjoy e1`` (a committed model's name, see
:mod:`sb3_hfo.models`; or a model ``.zip`` or rl-zoo3 run folder) or, in rl-zoo3's own way,
``python -m sb3_hfo.enjoy --env HFO/EmptyGoal-v0 -f logs/ --exp-id 1``.

The window needs the ``[render]`` extra (pygame). All rl-zoo3 ``enjoy.py`` options work (``--exp-id``, ``--load-best``, ``-n``, ``--no-render``, ...). SkillDDPG is
registered first (and loaded with a 1-transition replay buffer, which watching does not need); ``--algo`` defaults
to ``skill_ddpg``. Rendering opens a pygame window (``render_mode="human"``); use ``--no-render`` headless.
"""

from __future__ import annotations

import sys
import tempfile
from collections.abc import Sequence
from pathlib import Path

from sb3_hfo.cli.errors import (
    UserError,
    check_installed,
    check_playback_args,
    check_render_extra,
    fail,
    one_line_argparse_errors,
)
from sb3_hfo.cli.models import playback_argv
from sb3_hfo.cli.zoo import ALGO_NAME, run_rl_zoo_entry_point

PROG = "python -m sb3_hfo.enjoy"


def main(argv: Sequence[str] | None = None) -> None:
    """Run rl-zoo3's enjoy entry point with SkillDDPG registered; ``argv`` defaults to ``sys.argv[1:]``.

    User errors (no or unknown ``--env``, no ``-f``, no model there or a damaged one, bad ``--env-kwargs``, a
    negative ``--seed``, a bad option) exit with one line on stderr and code 2.
    """
    args = list(sys.argv[1:] if argv is None else argv)
    try:
        # rl_zoo3.enjoy imports its Hugging Face download helper, which needs `requests`.
        check_installed("zoo", ("rl_zoo3", "requests"), PROG)
    except UserError as error:
        fail(error)
    import rl_zoo3.enjoy

    with tempfile.TemporaryDirectory(prefix="sb3_hfo_enjoy_") as run_root:
        if not any(arg in ("-h", "--help") for arg in args):
            try:
                args = playback_argv(args, Path(run_root))
                check_playback_args(args, ALGO_NAME)
                if "--no-render" not in args:
                    check_render_extra()
            except UserError as error:
                fail(error)
        with one_line_argparse_errors(PROG):
            run_rl_zoo_entry_point(rl_zoo3.enjoy.enjoy, args, playback=True, single_thread=True)


if __name__ == "__main__":
    main()
