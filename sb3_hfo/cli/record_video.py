"""Record an mp4 of a trained agent with rl-zoo3's ``record_video`` (SB3 ``VecVideoRecorder``, moviepy).

``python -m sb3_hfo.record_video e1 -n 500`` (a committed model's name, see :mod:`sb3_hfo.models`, or a model
``.zip`` or rl-zoo3 run folder; the video goes to ``videos/`` unless ``-o`` says otherwise) or, in rl-zoo3's own
way, ``python -m sb3_hfo.record_video --env HFO/EmptyGoal-v0 -f logs/ --exp-id 1 -n 500 -o videos/``.
Needs the ``[render]`` extra (pygame, moviepy).

rl-zoo3 forces ``render_mode="rgb_array"``, so no window is needed; SDL is pointed at its dummy video driver
(unless ``SDL_VIDEODRIVER`` is already set) so that pygame also works on machines without a display.
The video lands in ``-o`` (default: ``<log folder>/videos``), named ``final-model-skill_ddpg-HFO-...-step-0-to-step-N.mp4``.
It is H.264 in yuv420p (frames padded to even sides), which browsers and QuickTime play; an ``-o`` that cannot
be made is one line, exit code 2.
rl-zoo3's record_video is a script (its code runs under ``if __name__ == "__main__"``), so it is run as a module.
"""

from __future__ import annotations

import os
import runpy
import sys
import tempfile
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import torch

from sb3_hfo.cli.errors import (
    UserError,
    check_installed,
    check_output_folder,
    check_playback_args,
    check_render_extra,
    fail,
    one_line_argparse_errors,
    option_value,
)
from sb3_hfo.cli.models import playback_argv
from sb3_hfo.cli.zoo import ALGO_NAME, run_rl_zoo_entry_point


def even_frame(frame: np.ndarray) -> np.ndarray:
    """``frame`` (H, W, 3) with its last row and/or column repeated to make H and W even: H.264 in yuv420p stores
    colour at half resolution in both directions, so it needs even sides (hfo2d's frames are 585 px wide)."""
    height, width = frame.shape[:2]
    return np.pad(frame, ((0, height % 2), (0, width % 2), (0, 0)), mode="edge")


def _browser_video_recorder() -> type:
    """SB3's VecVideoRecorder writing H.264 in yuv420p (moviepy's default for RGB frames is yuv444p, H.264 High
    4:4:4, which browsers and QuickTime do not play)."""
    from moviepy.video.io.ImageSequenceClip import ImageSequenceClip
    from stable_baselines3.common.vec_env import VecVideoRecorder

    class BrowserVideoRecorder(VecVideoRecorder):
        def _stop_recording(self) -> None:
            if self.recorded_frames:
                frames = [even_frame(frame) for frame in self.recorded_frames]
                clip = ImageSequenceClip(frames, fps=self.frames_per_sec)
                clip.write_videofile(self.video_path, codec="libx264", ffmpeg_params=["-pix_fmt", "yuv420p"])
                clip.close()
            else:
                super()._stop_recording()  # SB3's warning about zero frames
            self.recorded_frames = []
            self.recording = False

    return BrowserVideoRecorder


def _run_rl_zoo_record_video() -> None:
    import stable_baselines3.common.vec_env as vec_env

    # rl-zoo3's record_video takes VecVideoRecorder from this module when it runs
    original = vec_env.VecVideoRecorder
    vec_env.VecVideoRecorder = _browser_video_recorder()  # type: ignore[misc]
    try:
        runpy.run_module("rl_zoo3.record_video", run_name="__main__", alter_sys=True)
    finally:
        vec_env.VecVideoRecorder = original  # type: ignore[misc]


PROG = "python -m sb3_hfo.record_video"
#: Where a committed model's video goes unless ``-o`` says otherwise.
DEFAULT_VIDEO_FOLDER = "videos"


def main(argv: Sequence[str] | None = None) -> None:
    """Run rl-zoo3's record_video with SkillDDPG registered; ``argv`` defaults to ``sys.argv[1:]``.

    User errors (as for :mod:`sb3_hfo.enjoy`) exit with one line on stderr and code 2.
    """
    args = list(sys.argv[1:] if argv is None else argv)
    try:
        check_installed("zoo", ("rl_zoo3", "requests"), PROG)
    except UserError as error:
        fail(error)

    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    # rl-zoo3's record_video has no --num-threads; small networks run fastest on one torch thread.
    torch.set_num_threads(1)
    with tempfile.TemporaryDirectory(prefix="sb3_hfo_record_") as run_root:
        if not any(arg in ("-h", "--help") for arg in args):
            try:
                if (
                    args
                    and not args[0].startswith("-")
                    and option_value(args, "-o", "--output-folder") is None
                ):
                    # rl-zoo3 would write into the (temporary) run folder
                    args = [*args, "-o", DEFAULT_VIDEO_FOLDER]
                args = playback_argv(args, Path(run_root))
                check_playback_args(args, ALGO_NAME)
                output = option_value(args, "-o", "--output-folder")
                if output is not None:
                    check_output_folder(output, "-o")
                check_render_extra(video=True)
            except UserError as error:
                fail(error)
        with one_line_argparse_errors(PROG):
            run_rl_zoo_entry_point(_run_rl_zoo_record_video, args, playback=True)


if __name__ == "__main__":
    main()
