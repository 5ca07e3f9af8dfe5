"""Watch a trained agent with rl-zoo3: ``python -m sb3_hfo.enjoy e1`` (a committed model's name, see
:mod:`sb3_hfo.models`; or a model ``.zip`` or rl-zoo3 run folder) or, in rl-zoo3's own way,
``python -m sb3_hfo.enjoy --env HFO/EmptyGoal-v0 -f logs/ --exp-id 1``.

The window needs the ``[render]`` extra (pygame). All rl-zoo3 ``enjoy.py`` options work (``--exp-id``, ``--load-best``, ``-n``, ``--no-render``, ...). SkillDDPG is
registered first (and loaded with a 1-transition replay buffer, which watching does not need); ``--algo`` defaults
to ``skill_ddpg``. Rendering opens a pygame window (``render_mode="human"``) at 10 frames per second, one frame
per step; use ``--no-render`` headless. Without a display (pygame falls back to SDL's ``offscreen`` driver, or
``SDL_VIDEODRIVER=dummy`` asks for none) it still plays, drawing into no window, and says so in one line on stderr
(``note: ...``) rather than failing, so that scripts and CI can run it; when no video driver starts at all it is
one ``error:`` line, exit code 2. SIGTERM ends it while the window is open (see :mod:`hfo2d.rendering`).
"""

from __future__ import annotations

import os
import sys
import tempfile
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

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
#: SDL video drivers that show nothing: pygame falls back to "offscreen" without a display, "dummy" is asked for.
HEADLESS_VIDEO_DRIVERS = ("offscreen", "dummy")


def display_driver() -> str:
    """The SDL video driver that the window would use (the display is started and stopped again to ask).

    :raises UserError: when no video driver starts.
    """
    from hfo2d.rendering import choose_offscreen_without_display
    from sb3_hfo.errors import UserError, one_line

    os.environ.setdefault("SDL_NO_SIGNAL_HANDLERS", "1")  # as hfo2d's renderer: SIGTERM stays the default
    choose_offscreen_without_display()  # not SDL's own probing, which prints libwayland's error line
    import pygame

    try:
        pygame.display.init()
    except pygame.error as error:
        raise UserError(
            f"no display for the window ({one_line(error)}): pass --no-render, or record an mp4 with "
            "python -m sb3_hfo.record_video"
        ) from None
    try:
        return str(pygame.display.get_driver())
    finally:
        pygame.display.quit()


def _drawn_once_per_step(create_test_env: Callable[..., Any]) -> Callable[..., Any]:
    """Wrap rl-zoo3's ``create_test_env`` so that a "human" VecEnv ignores rl-zoo3's ``render("human")``.

    An hfo2d env in "human" mode draws itself on every reset and step (Gymnasium's convention), each frame held to
    the env's 10 frames per second; rl-zoo3's enjoy then calls ``render("human")`` after the step, which drew every
    frame a second time and waited a second time: the game ran at half speed.
    """
    from stable_baselines3.common.vec_env import VecEnvWrapper

    class DrawnOncePerStep(VecEnvWrapper):
        def reset(self) -> Any:
            return self.venv.reset()

        def step_wait(self) -> Any:
            return self.venv.step_wait()

        def render(self, mode: str | None = None) -> Any:
            if self.render_mode == "human":
                return None  # the envs drew this frame in their own step
            return self.venv.render(mode)

    def create(*args: Any, **kwargs: Any) -> Any:
        env = create_test_env(*args, **kwargs)
        return DrawnOncePerStep(env) if env.render_mode == "human" else env

    return create


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
                    driver = display_driver()
                    if driver in HEADLESS_VIDEO_DRIVERS:
                        print(
                            f"note: no display (SDL video driver {driver!r}): the game is drawn into no window; "
                            "--no-render skips drawing, python -m sb3_hfo.record_video makes an mp4",
                            file=sys.stderr,
                        )
            except UserError as error:
                fail(error)
        original_create_test_env = rl_zoo3.enjoy.create_test_env
        rl_zoo3.enjoy.create_test_env = _drawn_once_per_step(original_create_test_env)
        try:
            with one_line_argparse_errors(PROG):
                run_rl_zoo_entry_point(rl_zoo3.enjoy.enjoy, args, playback=True, single_thread=True)
        finally:
            rl_zoo3.enjoy.create_test_env = original_create_test_env


if __name__ == "__main__":
    main()
