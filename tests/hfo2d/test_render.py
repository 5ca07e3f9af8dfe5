"""pygame rendering (hfo2d.rendering): rgb_array frames, human mode on SDL's dummy driver, missing pygame."""

from __future__ import annotations

import os
import subprocess
import sys

# Headless: SDL reads these when pygame's display/audio start, so they must be set before any rendering.
os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.error import DependencyNotInstalled

import hfo2d  # noqa: F401  (registers the environments)
from hfo2d.hfo_env import HFOEnv
from hfo2d.physics import ServerParams, World
from hfo2d.rendering import (
    COLOR_BALL,
    COLOR_BALL_EDGE,
    COLOR_GOAL_STATUS,
    COLOR_GOALIE,
    COLOR_OFFENSE,
    SCREEN_HEIGHT,
    SCREEN_WIDTH,
    HFORenderer,
    Overlay,
    to_screen,
)

pytest.importorskip("pygame")

ENV_IDS = ("HFO/EmptyGoal-v0", "HFO/StaticKeeper-v0", "HFO/Keeper-v0")


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_rgb_array_frames(env_id: str) -> None:
    env = gym.make(env_id, render_mode="rgb_array")
    env.reset(seed=0)
    for _ in range(3):
        env.step(env.action_space.sample())
    frame = env.render()
    env.close()
    assert isinstance(frame, np.ndarray)
    assert frame.shape == (SCREEN_HEIGHT, SCREEN_WIDTH, 3)
    assert frame.dtype == np.uint8
    colours = np.unique(frame.reshape(-1, 3), axis=0)
    assert len(colours) > 5
    has_goalie = bool(np.all(frame == COLOR_GOALIE, axis=-1).any())
    assert has_goalie == (env_id != "HFO/EmptyGoal-v0")


def test_objects_are_drawn_where_they_are() -> None:
    params = ServerParams()
    world = World(params, np.random.default_rng(0))
    striker = world.add_player("l", 11)
    keeper = world.add_player("r", 1, goalie=True)
    world.place_player(striker, 20.0, -10.0, 0.0)
    world.place_player(keeper, 50.0, 3.0, 180.0)
    world.place_ball(30.0, 12.0)
    renderer = HFORenderer("rgb_array", params)
    frame = renderer.render(world)
    renderer.close()
    assert frame is not None

    def pixel(x: float, y: float) -> tuple[int, ...]:
        column, row = to_screen(x, y)
        return tuple(int(value) for value in frame[row, column])

    assert pixel(30.0, 12.0) == COLOR_BALL
    # the player discs (their centre carries the body-direction line, so look just beside it)
    assert pixel(20.0, -10.0 - 0.3) == COLOR_OFFENSE
    assert pixel(50.0, 3.0 + 0.3) == COLOR_GOALIE
    # screen y grows with world y (rcssserver's +y is down): the ball (y = 12) is below the striker (y = -10)
    assert to_screen(30.0, 12.0)[1] > to_screen(20.0, -10.0)[1]


def test_human_mode_with_dummy_driver() -> None:
    env = gym.make("HFO/Keeper-v0", render_mode="human")
    env.reset(seed=1)
    for _ in range(3):
        env.step(env.action_space.sample())
    assert env.render() is None
    env.close()
    env.close()  # closing twice is harmless


def test_unknown_render_mode_is_rejected() -> None:
    with pytest.raises(ValueError):
        HFORenderer("ansi", ServerParams())


def test_missing_pygame_raises_dependency_not_installed(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "pygame", None)  # makes `import pygame` raise ImportError
    with pytest.raises(DependencyNotInstalled, match=r"sb3-hfo\[render\]"):
        HFORenderer("rgb_array", ServerParams())


def test_ball_is_clearly_visible_at_the_default_size() -> None:
    params = ServerParams()
    world = World(params, np.random.default_rng(0))
    world.place_ball(30.0, 12.0)
    renderer = HFORenderer("rgb_array", params)
    frame = renderer.render(world)
    assert frame is not None
    column, row = to_screen(30.0, 12.0)
    patch = frame[row - 8 : row + 9, column - 8 : column + 9].reshape(-1, 3)
    ball_pixels = np.all(patch == COLOR_BALL, axis=-1) | np.all(patch == COLOR_BALL_EDGE, axis=-1)
    assert ball_pixels.sum() >= 90  # a disc about 12 px across (the true 0.085 m would be under 1 px)


def _play_to_a_goal(env: HFOEnv) -> dict:
    env.reset(seed=0, options={"player": (48.0, 0.0, 0.0), "ball": (48.6, 0.0)})
    kick = np.array([0, 0, 1, 0, 0.5, 0.5, 1.0, 0.5], dtype=np.float32)
    turn = np.array([0, 1, 0, 0, 0.5, 0.5, 0, 0.5], dtype=np.float32)
    _, _, terminated, _, info = env.step(kick)
    while not terminated:
        _, _, terminated, _, info = env.step(turn)
    return info


def test_overlay_counts_episodes_cycles_goals_and_shows_the_end(monkeypatch: pytest.MonkeyPatch) -> None:
    overlays: list[Overlay | None] = []
    original = HFORenderer.render

    def spy(self: HFORenderer, world: World, overlay: Overlay | None = None) -> np.ndarray | None:
        overlays.append(overlay)
        return original(self, world, overlay)

    monkeypatch.setattr(HFORenderer, "render", spy)
    env = HFOEnv(noise=False, render_mode="rgb_array")
    env.reset(seed=0)
    env.render()
    assert overlays[-1] == Overlay(episode=1, cycle=0, goals=0, ended=0)
    assert _play_to_a_goal(env)["status"] == "GOAL"  # a reset in mid-episode: episode 2, not an ended one
    cycles = env.steps
    end_frame = env.render()
    assert overlays[-1] == Overlay(episode=2, cycle=cycles, goals=1, ended=1, status="GOAL")
    env.reset(seed=3)
    for _ in range(3):
        env.step(env.action_space.sample())
    frame = env.render()
    assert env.world.cycle > 3  # the world's clock runs on; the overlay's cycle is the episode's
    assert overlays[-1] == Overlay(episode=3, cycle=3, goals=1, ended=1, previous=(2, "GOAL"))
    assert overlays[-1].lines() == ["episode 3   cycle 3", "goals 1 / 1 episodes", "episode 2: GOAL"]
    # the end status is drawn large, in the goal colour, only once the episode has ended
    assert end_frame is not None and frame is not None
    assert np.all(end_frame == COLOR_GOAL_STATUS, axis=-1).sum() > 50
    assert not np.all(frame == COLOR_GOAL_STATUS, axis=-1).any()
    # the overlay sits on a dark strip in the top-left corner
    assert frame[2, 2].tolist() != frame[SCREEN_HEIGHT // 2, 2].tolist()
    env.close()


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="X11 / Wayland displays are Linux's")
def test_human_mode_without_a_display_warns_once_and_prints_no_sdl_error() -> None:
    """With neither DISPLAY nor WAYLAND_DISPLAY, SDL probed Wayland and printed libwayland's "error:
    XDG_RUNTIME_DIR is invalid or not set" before drawing into no window; hfo2d now picks SDL's offscreen driver
    itself and says so in one warning. A driver the user chose is left alone."""
    code = (
        "import gymnasium as gym, hfo2d\n"
        "env = gym.make('HFO/EmptyGoal-v0', render_mode='human')\n"
        "env.reset(seed=0)\n"
        "for _ in range(3): env.step(env.action_space.sample())\n"
        "import os; print(os.environ['SDL_VIDEODRIVER'])\n"
    )
    removed = ("DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER", "XDG_RUNTIME_DIR")
    env = {key: value for key, value in os.environ.items() if key not in removed}
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip() == "offscreen"
    assert "XDG_RUNTIME_DIR" not in done.stderr
    assert done.stderr.count("hfo2d: no display") == 1, done.stderr
    env["SDL_VIDEODRIVER"] = "dummy"
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert done.stdout.strip() == "dummy" and "hfo2d: no display" not in done.stderr
