"""Record an mp4 of a trained agent with rl-zoo3's ``record_video`` (SB3 ``VecVideoRecorder``, moviepy).

``python -m sb3_hfo.record_video --algo skill_ddpg --env HFO/EmptyGoal-v0 -f logs/ -n 500 -o videos/``

rl-zoo3 forces ``render_mode="rgb_array"``, so no window is needed; SDL is pointed at its dummy video driver
(unless ``SDL_VIDEODRIVER`` is already set) so that pygame also works on machines without a display.
The video lands in ``-o`` (default: ``<log folder>/videos``), named ``final-model-skill_ddpg-HFO-...-step-0-to-step-N.mp4``.
rl-zoo3's record_video is a script (its code runs under ``if __name__ == "__main__"``), so it is run as a module.
"""

from __future__ import annotations

import os
import runpy
import sys
from collections.abc import Sequence


def _run_rl_zoo_record_video() -> None:
    runpy.run_module("rl_zoo3.record_video", run_name="__main__", alter_sys=True)


PROG = "python -m sb3_hfo.record_video"


def main(argv: Sequence[str] | None = None) -> None:
    """Run rl-zoo3's record_video with SkillDDPG registered; ``argv`` defaults to ``sys.argv[1:]``.

    User errors (as for :mod:`sb3_hfo.enjoy`) exit with one line on stderr and code 2.
    """
    import torch

    from sb3_hfo.cli_errors import UserError, check_playback_args, fail, one_line_argparse_errors
    from sb3_hfo.zoo import ALGO_NAME, run_rl_zoo_entry_point

    args = list(sys.argv[1:] if argv is None else argv)
    if not any(arg in ("-h", "--help") for arg in args):
        try:
            check_playback_args(args, ALGO_NAME)
        except UserError as error:
            fail(error)
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    # rl-zoo3's record_video has no --num-threads; small networks run fastest on one torch thread.
    torch.set_num_threads(1)
    with one_line_argparse_errors(PROG):
        run_rl_zoo_entry_point(_run_rl_zoo_record_video, args, playback=True)


if __name__ == "__main__":
    main()
