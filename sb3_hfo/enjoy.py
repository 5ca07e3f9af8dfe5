"""Watch a trained agent with rl-zoo3: ``python -m sb3_hfo.enjoy --algo skill_ddpg --env HFO/EmptyGoal-v0 -f logs/``.

All rl-zoo3 ``enjoy.py`` options work (``--exp-id``, ``--load-best``, ``-n``, ``--no-render``, ...). SkillDDPG is
registered first (and loaded with a 1-transition replay buffer, which watching does not need); ``--algo`` defaults
to ``skill_ddpg``. Rendering opens a pygame window (``render_mode="human"``); use ``--no-render`` headless.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence

PROG = "python -m sb3_hfo.enjoy"


def main(argv: Sequence[str] | None = None) -> None:
    """Run rl-zoo3's enjoy entry point with SkillDDPG registered; ``argv`` defaults to ``sys.argv[1:]``.

    User errors (no or unknown ``--env``, no ``-f``, no model there or a damaged one, bad ``--env-kwargs``, a
    negative ``--seed``, a bad option) exit with one line on stderr and code 2.
    """
    from sb3_hfo.cli_errors import UserError, check_playback_args, fail, one_line_argparse_errors
    from sb3_hfo.zoo import ALGO_NAME, run_rl_zoo_entry_point

    args = list(sys.argv[1:] if argv is None else argv)
    try:
        import rl_zoo3.enjoy
    except ModuleNotFoundError as error:
        # rl_zoo3.enjoy imports its Hugging Face download helper, which needs `requests`.
        fail(f"rl_zoo3.enjoy needs the missing module {error.name!r}: pip install {error.name}")
    if not any(arg in ("-h", "--help") for arg in args):
        try:
            check_playback_args(args, ALGO_NAME)
        except UserError as error:
            fail(error)

    with one_line_argparse_errors(PROG):
        run_rl_zoo_entry_point(rl_zoo3.enjoy.enjoy, args, playback=True, single_thread=True)


if __name__ == "__main__":
    main()
