"""pygame renderer for the hfo2d half field (Gymnasium ``render_mode`` conventions, LunarLander style).

``"rgb_array"`` draws on an off-screen ``pygame.Surface`` (no display needed) and returns an (H, W, 3) uint8
frame; ``"human"`` opens a window and keeps ``render_fps`` frames per second. Screen y follows rcssserver's
+y (down), so world coordinates map to pixels without a flip.

Field geometry (metres) from rcssserver's constants via hfo_reference §1.
"""

from __future__ import annotations

import math
import os
import sys
from dataclasses import dataclass
from typing import Any

import numpy as np
from gymnasium import logger
from gymnasium.error import DependencyNotInstalled

from hfo2d.physics import (
    GOAL_HALF_WIDTH,
    GOAL_POST_RADIUS,
    GOAL_POSTS,
    PENALTY_AREA_HALF_WIDTH,
    PENALTY_AREA_X,
    PITCH_HALF_LENGTH,
    PITCH_HALF_WIDTH,
    ServerParams,
    World,
)

RENDER_FPS = 10  # one frame per 100 ms server cycle
PIXELS_PER_METRE = 10.0
# Visible window (metres): the HFO area x in [0, 52.5], |y| <= 34, plus a 3 m margin, which also shows a strip
# of the other half and the goal (2.44 m deep) behind the line.
VIEW_MARGIN = 3.0
VIEW_MIN_X = -VIEW_MARGIN
VIEW_MAX_X = PITCH_HALF_LENGTH + VIEW_MARGIN
VIEW_MIN_Y = -PITCH_HALF_WIDTH - VIEW_MARGIN
VIEW_MAX_Y = PITCH_HALF_WIDTH + VIEW_MARGIN
SCREEN_WIDTH = round((VIEW_MAX_X - VIEW_MIN_X) * PIXELS_PER_METRE)
SCREEN_HEIGHT = round((VIEW_MAX_Y - VIEW_MIN_Y) * PIXELS_PER_METRE)

GOAL_DEPTH = 2.44
GOAL_AREA_LENGTH = 5.5
GOAL_AREA_HALF_WIDTH = 9.16
CENTRE_CIRCLE_RADIUS = 9.15
PENALTY_SPOT_DIST = 11.0

# Players and the ball are drawn at true size but never smaller than these radii (pixels), so they stay visible:
# at 10 px/m the ball (0.085 m) would be under 1 px, so it is drawn 12 px across with a black rim.
MIN_PLAYER_RADIUS_PX = 6
MIN_BALL_RADIUS_PX = 6

COLOR_GRASS = (40, 130, 50)
COLOR_GRASS_STRIPE = (46, 140, 56)
COLOR_OUTSIDE = (30, 100, 40)
COLOR_LINE = (235, 235, 235)
COLOR_GOAL = (200, 200, 200)
COLOR_POST = (255, 255, 255)
COLOR_OFFENSE = (250, 210, 40)
COLOR_DEFENSE = (60, 120, 230)
COLOR_GOALIE = (220, 50, 180)
COLOR_KICKABLE = (255, 255, 255)
COLOR_BODY_DIR = (20, 20, 20)
COLOR_BALL = (255, 255, 255)
COLOR_BALL_EDGE = (0, 0, 0)
COLOR_TEXT = (255, 255, 255)
COLOR_OVERLAY = (0, 0, 0)
OVERLAY_ALPHA = 150  # of the dark strip behind the overlay text
COLOR_GOAL_STATUS = (90, 230, 90)
COLOR_OTHER_STATUS = (255, 120, 80)


@dataclass(frozen=True)
class Overlay:
    """What the env shows over the pitch (``HFOEnv`` fills it; every field is from the env's own counters).

    Args:
        episode: number of the current episode (1 for the first ``reset``).
        cycle: cycles played in it.
        goals: goals in the episodes ended so far.
        ended: episodes ended so far (terminated or truncated).
        status: the current episode's final status once it has ended (drawn large), else None.
        previous: (number, final status) of the last episode that ended before this one, or None.
    """

    episode: int
    cycle: int
    goals: int
    ended: int
    status: str | None = None
    previous: tuple[int, str] | None = None

    def lines(self) -> list[str]:
        """The overlay's small text lines, top to bottom."""
        lines = [
            f"episode {self.episode}   cycle {self.cycle}",
            f"goals {self.goals} / {self.ended} episodes",
        ]
        if self.status is None and self.previous is not None:
            lines.append(f"episode {self.previous[0]}: {self.previous[1]}")
        return lines


def choose_offscreen_without_display() -> bool:
    """On Linux with neither an X11 (``DISPLAY``) nor a Wayland (``WAYLAND_DISPLAY``) display and no
    ``SDL_VIDEODRIVER`` of the user's, set SDL's ``offscreen`` driver and return True (else change nothing, False).

    SDL would fall back to that driver by itself, but only after probing Wayland, whose library prints
    ``error: XDG_RUNTIME_DIR is invalid or not set in the environment.`` on a run that then goes on fine. Call it
    before ``pygame.display.init()``.
    """
    if (
        sys.platform.startswith("linux")
        and not os.environ.get("DISPLAY")
        and not os.environ.get("WAYLAND_DISPLAY")
        and not os.environ.get("SDL_VIDEODRIVER")
    ):
        os.environ["SDL_VIDEODRIVER"] = "offscreen"
        return True
    return False


def _import_pygame() -> Any:
    try:
        import pygame
    except ImportError as error:
        raise DependencyNotInstalled(
            'pygame is not installed, run `pip install "sb3-hfo[render]"` to render hfo2d environments'
        ) from error
    return pygame


def to_screen(x: float, y: float) -> tuple[int, int]:
    """World position (m, rcssserver frame) to pixel coordinates (column, row)."""
    return round((x - VIEW_MIN_X) * PIXELS_PER_METRE), round((y - VIEW_MIN_Y) * PIXELS_PER_METRE)


class HFORenderer:
    """Draws a ``World`` on the HFO half field.

    Args:
        render_mode: ``"human"`` (window, returns None) or ``"rgb_array"`` (returns an (H, W, 3) uint8 array,
            H = ``SCREEN_HEIGHT``, W = ``SCREEN_WIDTH``).
        params: server parameters (player/ball sizes and the kickable area drawn around players).
    """

    metadata = {"render_modes": ["human", "rgb_array"], "render_fps": RENDER_FPS}

    def __init__(self, render_mode: str, params: ServerParams) -> None:
        if render_mode not in self.metadata["render_modes"]:
            raise ValueError(
                f"render_mode must be one of {self.metadata['render_modes']}, got {render_mode!r}"
            )
        self.render_mode = render_mode
        self.params = params
        self._pygame = _import_pygame()
        self._screen: Any = None
        self._clock: Any = None
        self._field: Any = None  # static background, drawn once
        self._font: Any = None
        self._big_font: Any = None
        self._font_failed = False

    # ---------------------------------------------------------------------------------------------------------
    def render(self, world: World, overlay: Overlay | None = None) -> np.ndarray | None:
        """Draw the current state; an (H, W, 3) uint8 frame in ``"rgb_array"`` mode, None in ``"human"``.

        ``overlay``: episode, cycle, goals and status to show in the top-left corner (without it, only the
        world's own cycle counter is shown).
        """
        pygame = self._pygame
        if self.render_mode == "human" and self._screen is None:
            # SDL would otherwise take over SIGTERM (it has the default handler) and turn it into a QUIT event,
            # which a window that only pumps events ignores: `kill` would leave the program running.
            os.environ.setdefault("SDL_NO_SIGNAL_HANDLERS", "1")
            if choose_offscreen_without_display():
                logger.warn(
                    "hfo2d: no display (neither DISPLAY nor WAYLAND_DISPLAY is set): render_mode='human' draws into "
                    "no window; render_mode='rgb_array' returns the frames"
                )
            pygame.display.init()  # display only: pygame.init() would also open an audio device
            pygame.display.set_caption("hfo2d: Half Field Offense")
            self._screen = pygame.display.set_mode((SCREEN_WIDTH, SCREEN_HEIGHT))
        if self.render_mode == "human" and self._clock is None:
            self._clock = pygame.time.Clock()
        if self._field is None:
            self._field = self._draw_field()

        canvas = self._field.copy()
        self._draw_objects(canvas, world)
        self._draw_overlay(canvas, world, overlay)

        if self.render_mode == "human":
            assert self._screen is not None and self._clock is not None
            self._screen.blit(canvas, (0, 0))
            pygame.event.pump()
            self._clock.tick(RENDER_FPS)
            pygame.display.flip()
            return None
        return np.transpose(np.array(pygame.surfarray.pixels3d(canvas)), axes=(1, 0, 2))

    def close(self) -> None:
        """Close the window (human mode); safe to call more than once."""
        if self._screen is not None:
            pygame = self._pygame
            pygame.display.quit()
            self._screen = None
            self._clock = None

    # ---------------------------------------------------------------------------------------------------------
    def _draw_field(self) -> Any:
        pygame = self._pygame
        surface = pygame.Surface((SCREEN_WIDTH, SCREEN_HEIGHT))
        surface.fill(COLOR_OUTSIDE)
        scale = PIXELS_PER_METRE

        def rect(x0: float, y0: float, x1: float, y1: float) -> Any:
            left, top = to_screen(x0, y0)
            right, bottom = to_screen(x1, y1)
            return pygame.Rect(left, top, right - left, bottom - top)

        # Grass with 5 m mowing stripes, over the visible part of the pitch.
        pygame.draw.rect(
            surface, COLOR_GRASS, rect(VIEW_MIN_X, -PITCH_HALF_WIDTH, PITCH_HALF_LENGTH, PITCH_HALF_WIDTH)
        )
        stripe_x = VIEW_MIN_X
        while stripe_x < PITCH_HALF_LENGTH:
            if round(stripe_x / 5.0) % 2 == 0:
                stripe_end = min(stripe_x + 5.0, PITCH_HALF_LENGTH)
                pygame.draw.rect(
                    surface,
                    COLOR_GRASS_STRIPE,
                    rect(stripe_x, -PITCH_HALF_WIDTH, stripe_end, PITCH_HALF_WIDTH),
                )
            stripe_x += 5.0

        # Touch lines, goal line and the centre line (the left edge of the HFO area).
        width = 2
        pygame.draw.line(
            surface,
            COLOR_LINE,
            to_screen(VIEW_MIN_X, -PITCH_HALF_WIDTH),
            to_screen(PITCH_HALF_LENGTH, -PITCH_HALF_WIDTH),
            width,
        )
        pygame.draw.line(
            surface,
            COLOR_LINE,
            to_screen(VIEW_MIN_X, PITCH_HALF_WIDTH),
            to_screen(PITCH_HALF_LENGTH, PITCH_HALF_WIDTH),
            width,
        )
        pygame.draw.line(
            surface,
            COLOR_LINE,
            to_screen(PITCH_HALF_LENGTH, -PITCH_HALF_WIDTH),
            to_screen(PITCH_HALF_LENGTH, PITCH_HALF_WIDTH),
            width,
        )
        pygame.draw.line(
            surface, COLOR_LINE, to_screen(0.0, -PITCH_HALF_WIDTH), to_screen(0.0, PITCH_HALF_WIDTH), width
        )

        # Centre circle and centre spot.
        centre = to_screen(0.0, 0.0)
        pygame.draw.circle(surface, COLOR_LINE, centre, round(CENTRE_CIRCLE_RADIUS * scale), width)
        pygame.draw.circle(surface, COLOR_LINE, centre, 3)

        # Penalty area, goal area, penalty spot and the arc outside the penalty area.
        pygame.draw.rect(
            surface,
            COLOR_LINE,
            rect(PENALTY_AREA_X, -PENALTY_AREA_HALF_WIDTH, PITCH_HALF_LENGTH, PENALTY_AREA_HALF_WIDTH),
            width,
        )
        goal_area_x = PITCH_HALF_LENGTH - GOAL_AREA_LENGTH
        pygame.draw.rect(
            surface,
            COLOR_LINE,
            rect(goal_area_x, -GOAL_AREA_HALF_WIDTH, PITCH_HALF_LENGTH, GOAL_AREA_HALF_WIDTH),
            width,
        )
        spot_x = PITCH_HALF_LENGTH - PENALTY_SPOT_DIST
        pygame.draw.circle(surface, COLOR_LINE, to_screen(spot_x, 0.0), 2)
        # Arc of radius 9.15 around the spot, the part with x < 36 (outside the box).
        half_angle = math.acos((spot_x - PENALTY_AREA_X) / CENTRE_CIRCLE_RADIUS)
        arc_rect = rect(
            spot_x - CENTRE_CIRCLE_RADIUS,
            -CENTRE_CIRCLE_RADIUS,
            spot_x + CENTRE_CIRCLE_RADIUS,
            CENTRE_CIRCLE_RADIUS,
        )
        # pygame arcs are counter-clockwise in screen space starting from +x; the arc faces -x.
        pygame.draw.arc(surface, COLOR_LINE, arc_rect, math.pi - half_angle, math.pi + half_angle, width)

        # Goal mouth (net area behind the line) and both posts.
        pygame.draw.rect(
            surface,
            COLOR_GOAL,
            rect(PITCH_HALF_LENGTH, -GOAL_HALF_WIDTH, PITCH_HALF_LENGTH + GOAL_DEPTH, GOAL_HALF_WIDTH),
            width,
        )
        post_radius_px = max(3, round(GOAL_POST_RADIUS * scale))
        for post_x, post_y in GOAL_POSTS:
            pygame.draw.circle(surface, COLOR_POST, to_screen(post_x, post_y), post_radius_px)
        return surface

    def _draw_objects(self, canvas: Any, world: World) -> None:
        pygame = self._pygame
        scale = PIXELS_PER_METRE
        params = self.params
        kickable_px = max(MIN_PLAYER_RADIUS_PX + 2, round(params.kickable_area * scale))
        player_px = max(MIN_PLAYER_RADIUS_PX, round(params.player_size * scale))
        for player in world.players:
            centre = to_screen(player.x, player.y)
            if player.goalie:
                color = COLOR_GOALIE
            elif player.side == "l":
                color = COLOR_OFFENSE
            else:
                color = COLOR_DEFENSE
            pygame.draw.circle(canvas, COLOR_KICKABLE, centre, kickable_px, 1)
            pygame.draw.circle(canvas, color, centre, player_px)
            body = math.radians(player.body_deg)
            tip = (
                round(centre[0] + math.cos(body) * kickable_px),
                round(centre[1] + math.sin(body) * kickable_px),
            )
            pygame.draw.line(canvas, COLOR_BODY_DIR, centre, tip, 2)

        ball = world.ball
        ball_centre = to_screen(ball.x, ball.y)
        ball_px = max(MIN_BALL_RADIUS_PX, round(params.ball_size * scale))
        pygame.draw.circle(canvas, COLOR_BALL, ball_centre, ball_px)
        pygame.draw.circle(canvas, COLOR_BALL_EDGE, ball_centre, ball_px, 2)

    def _draw_overlay(self, canvas: Any, world: World, overlay: Overlay | None) -> None:
        """The text lines on a translucent strip in the top-left corner, and a finished episode's status."""
        pygame = self._pygame
        lines = [f"cycle {world.cycle}"] if overlay is None else overlay.lines()
        texts = [self._text(line) for line in lines]
        if any(text is None for text in texts):
            return
        width = max(text.get_width() for text in texts) + 12
        height = sum(text.get_height() + 2 for text in texts) + 6
        strip = pygame.Surface((width, height), pygame.SRCALPHA)
        strip.fill((*COLOR_OVERLAY, OVERLAY_ALPHA))
        canvas.blit(strip, (0, 0))
        row = 4
        for text in texts:
            canvas.blit(text, (6, row))
            row += text.get_height() + 2
        if overlay is not None and overlay.status is not None:
            color = COLOR_GOAL_STATUS if overlay.status == "GOAL" else COLOR_OTHER_STATUS
            banner = self._text(overlay.status.replace("_", " "), big=True, color=color)
            if banner is not None:
                back = pygame.Surface((banner.get_width() + 20, banner.get_height() + 8), pygame.SRCALPHA)
                back.fill((*COLOR_OVERLAY, OVERLAY_ALPHA))
                left = (SCREEN_WIDTH - back.get_width()) // 2
                canvas.blit(back, (left, height + 6))
                canvas.blit(banner, (left + 10, height + 10))

    def _text(self, message: str, big: bool = False, color: tuple[int, int, int] = COLOR_TEXT) -> Any:
        """Render a short label, or None where pygame's font module is unavailable."""
        if self._font_failed:
            return None
        pygame = self._pygame
        if self._font is None:
            try:
                pygame.font.init()
                self._font = pygame.font.Font(None, 22)
                self._big_font = pygame.font.Font(None, 44)
            except Exception:  # pygame built without SDL_ttf: draw without the label
                self._font_failed = True
                return None
        return (self._big_font if big else self._font).render(message, True, color)
