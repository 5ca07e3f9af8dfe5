"""Watch a trained agent with rl-zoo3: ``python -m sb3_hfo.enjoy --algo skill_ddpg --env HFO/EmptyGoal-v0 -f logs/``.

All rl-zoo3 ``enjoy.py`` options work (``--exp-id``, ``--load-best``, ``-n``, ``--no-render``, ...). SkillDDPG is
registered first (and loaded with a 1-transition replay buffer, which watching does not need); ``--algo`` defaults
to ``skill_ddpg``. Rendering opens a pygame window (``render_mode="human"``); use ``--no-render`` headless.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence


def main(argv: Sequence[str] | None = None) -> None:
    """Run rl-zoo3's enjoy entry point with SkillDDPG registered; ``argv`` defaults to ``sys.argv[1:]``."""
    from sb3_hfo.zoo import run_rl_zoo_entry_point

    try:
        import rl_zoo3.enjoy
    except ModuleNotFoundError as error:
        # rl_zoo3.enjoy imports its Hugging Face download helper, which needs `requests`.
        sys.exit(f"error: rl_zoo3.enjoy needs the missing module {error.name!r}: pip install {error.name}")

    run_rl_zoo_entry_point(
        rl_zoo3.enjoy.enjoy, sys.argv[1:] if argv is None else argv, playback=True, single_thread=True
    )


if __name__ == "__main__":
    main()
