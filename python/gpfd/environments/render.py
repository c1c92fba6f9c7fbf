"""Frames of gpfd's environments for ``render_mode="rgb_array"``: H x W x 3 uint8 images drawn with
NumPy alone, one small function per environment, from an instance's state variables (Tetris: its
board and piece, which the state variables do not determine).

The geometry is gpfd's (src/env/*.cpp and their dynamics headers): the cart-pole's pole of 1 m on
a track of +-2.4 m, Acrobot's two links of 1 m, the swimmer's segments of 1 m. Screen sizes and
colours follow Gymnasium's classic-control renderers (gymnasium/envs/classic_control/cartpole.py
and acrobot.py: 600 x 400 and 500 x 500), so that videos look alike; the drawing code is gpfd's.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    from gpfd._core import EnvBatch

MODES = ("rgb_array",)

Colour = tuple[int, int, int]
Point = tuple[float, float]

# Constants of gpfd's dynamics that the state variables do not carry.
CARTPOLE_POLE_LENGTH = 1.0  # 2 x kHalfLength, src/env/cartpole_dynamics.hpp
CARTPOLE_X_LIMIT = 2.4  # kXThreshold: the episode fails beyond it
ACROBOT_LINK_LENGTH = 1.0  # kL1 and the second link, src/env/acrobot_dynamics.hpp
SWIMMER_SEGMENT_LENGTH = 1.0  # Every segment, src/env/swimmer.cpp

# Tetris' pieces in gpfd's order (IOTSZLJ, src/env/tetromino.hpp), coloured as usual for them.
TETRIS_COLOURS: tuple[Colour, ...] = (
    (0, 190, 220),  # I
    (230, 200, 0),  # O
    (150, 60, 190),  # T
    (60, 180, 60),  # S
    (220, 50, 50),  # Z
    (240, 140, 0),  # L
    (40, 80, 220),  # J
)


class Canvas:
    """An image with y downwards, drawn on with filled convex shapes, each pixel taken when its
    centre lies inside. Shapes with non-finite coordinates are left out (a diverged state still
    gives a frame)."""

    def __init__(self, width: int, height: int, background: Colour = (255, 255, 255)):
        self.pixels = np.empty((height, width, 3), dtype=np.uint8)
        for c in range(3):  # A channel at a time: NumPy broadcasts a colour over 3 values slowly.
            self.pixels[..., c] = background[c]

    @property
    def height(self) -> int:
        return int(self.pixels.shape[0])

    @property
    def width(self) -> int:
        return int(self.pixels.shape[1])

    def _box(self, low_x: float, low_y: float, high_x: float, high_y: float):
        """The pixel centres of a bounding box, clipped to the image; None when empty."""
        if not np.isfinite([low_x, low_y, high_x, high_y]).all():
            return None
        x0, y0 = max(int(np.floor(low_x)), 0), max(int(np.floor(low_y)), 0)
        x1, y1 = min(int(np.ceil(high_x)), self.width), min(int(np.ceil(high_y)), self.height)
        if x0 >= x1 or y0 >= y1:
            return None
        ys, xs = np.mgrid[y0:y1, x0:x1]
        return (slice(y0, y1), slice(x0, x1)), xs + 0.5, ys + 0.5

    def _paint(self, where, inside: npt.ArrayLike, colour: Colour) -> None:
        region = self.pixels[where]
        mask = np.asarray(inside, dtype=bool)
        for c in range(3):
            region[..., c][mask] = colour[c]

    def polygon(self, points: list[Point], colour: Colour) -> None:
        """A convex polygon, its corners in either order around it."""
        p = np.asarray(points, dtype=np.float64)
        box = self._box(p[:, 0].min(), p[:, 1].min(), p[:, 0].max(), p[:, 1].max())
        if box is None:
            return
        where, xs, ys = box
        q = np.roll(p, -1, axis=0)
        # The side of each edge a pixel centre lies on; inside: the same side of every edge.
        sides = [
            (bx - ax) * (ys - ay) - (by - ay) * (xs - ax)
            for (ax, ay), (bx, by) in zip(p, q, strict=True)
        ]
        side = np.stack(sides)
        self._paint(where, (side >= 0).all(axis=0) | (side <= 0).all(axis=0), colour)

    def disc(self, centre: Point, radius: float, colour: Colour) -> None:
        cx, cy = centre
        box = self._box(cx - radius, cy - radius, cx + radius, cy + radius)
        if box is None:
            return
        where, xs, ys = box
        self._paint(where, (xs - cx) ** 2 + (ys - cy) ** 2 <= radius * radius, colour)

    def segment(self, a: Point, b: Point, width: float, colour: Colour) -> None:
        """A straight bar of `width` from a to b, with square ends."""
        (ax, ay), (bx, by) = a, b
        length = float(np.hypot(bx - ax, by - ay))
        if not length > 0:
            self.disc(a, width / 2, colour)
            return
        nx, ny = (ay - by) / length * width / 2, (bx - ax) / length * width / 2
        self.polygon(
            [(ax + nx, ay + ny), (bx + nx, by + ny), (bx - nx, by - ny), (ax - nx, ay - ny)], colour
        )

    def rect(self, x0: float, y0: float, x1: float, y1: float, colour: Colour) -> None:
        """An upright rectangle (x0 <= x1, y0 <= y1): the pixels whose centre it holds, as the
        polygon of its corners would take them, by slicing alone."""
        if not np.isfinite([x0, y0, x1, y1]).all():
            return
        c0, c1 = max(int(np.ceil(x0 - 0.5)), 0), min(int(np.floor(x1 - 0.5)) + 1, self.width)
        r0, r1 = max(int(np.ceil(y0 - 0.5)), 0), min(int(np.floor(y1 - 0.5)) + 1, self.height)
        if c0 < c1 and r0 < r1:
            for c in range(3):
                self.pixels[r0:r1, c0:c1, c] = colour[c]


def cartpole(state: np.ndarray) -> np.ndarray:
    """600 x 400: the cart on its track (ticks at the failure limits) and the pole; th = 0 is
    upright, positive th leans towards +x."""
    x, _, th, _ = (float(v) for v in state[:4])
    canvas = Canvas(600, 400)
    scale = canvas.width / (2 * CARTPOLE_X_LIMIT)  # Pixels per metre.
    track_y = canvas.height - 100.0
    centre_x = canvas.width / 2
    canvas.rect(0, track_y - 0.5, canvas.width, track_y + 0.5, (0, 0, 0))
    for limit in (-CARTPOLE_X_LIMIT, CARTPOLE_X_LIMIT):
        tick = centre_x + limit * scale
        canvas.rect(tick - 1, track_y, tick + 1, track_y + 12, (160, 160, 160))
    cart_x = centre_x + x * scale
    canvas.rect(cart_x - 25, track_y - 15, cart_x + 25, track_y + 15, (0, 0, 0))
    axle = (cart_x, track_y - 7.5)
    length = CARTPOLE_POLE_LENGTH * scale
    tip = (axle[0] + length * np.sin(th), axle[1] - length * np.cos(th))
    canvas.segment(axle, tip, 10.0, (202, 152, 101))
    canvas.disc(axle, 5.0, (129, 132, 203))
    return canvas.pixels


def acrobot(state: np.ndarray) -> np.ndarray:
    """500 x 500: the two links hanging from the bar (th1 = 0 hangs down, th2 relative to link 1)
    and the line the tip must pass (1 m above the bar)."""
    th1, th2 = float(state[0]), float(state[1])
    canvas = Canvas(500, 500)
    scale = canvas.width / (2 * (2 * ACROBOT_LINK_LENGTH + 0.2))
    centre = canvas.width / 2

    def pixel(px: float, py: float) -> Point:  # Metres, y up, from the bar.
        return centre + px * scale, centre - py * scale

    goal_y = pixel(0.0, 1.0)[1]
    canvas.rect(0, goal_y - 0.5, canvas.width, goal_y + 0.5, (0, 0, 0))
    elbow = (ACROBOT_LINK_LENGTH * np.sin(th1), -ACROBOT_LINK_LENGTH * np.cos(th1))
    tip = (
        elbow[0] + ACROBOT_LINK_LENGTH * np.sin(th1 + th2),
        elbow[1] - ACROBOT_LINK_LENGTH * np.cos(th1 + th2),
    )
    joints = [pixel(0.0, 0.0), pixel(*elbow), pixel(*tip)]
    for a, b in zip(joints[:-1], joints[1:], strict=True):
        canvas.segment(a, b, 0.2 * scale, (0, 204, 204))
    for joint in joints[:2]:
        canvas.disc(joint, 0.1 * scale, (204, 204, 0))
    return canvas.pixels


def swimmer(state: np.ndarray) -> np.ndarray:
    """500 x 500, centred on the centre of mass (the state has no position): the segments (the
    first one darker, its free end marked), the x axis it swims along, and the velocity of the
    centre of mass as a red bar (1 m/s = 1 segment length)."""
    values = np.asarray(state, dtype=np.float64)
    velocity = values[:2]
    angles = values[2::2]
    n = angles.size
    steps = SWIMMER_SEGMENT_LENGTH * np.stack([np.cos(angles), np.sin(angles)], axis=1)
    joints = np.vstack([np.zeros(2), np.cumsum(steps, axis=0)])  # Joint k ends segment k.
    centre = ((joints[:-1] + joints[1:]) / 2).mean(axis=0)  # Equal masses.
    canvas = Canvas(500, 500)
    scale = canvas.width / (n * SWIMMER_SEGMENT_LENGTH + 1.0)
    middle = canvas.width / 2

    def pixel(p: np.ndarray) -> Point:
        return middle + (p[0] - centre[0]) * scale, middle - (p[1] - centre[1]) * scale

    canvas.rect(0, middle - 0.5, canvas.width, middle + 0.5, (200, 200, 200))
    for i in range(n):
        colour = (30, 70, 160) if i == 0 else (70, 130, 200)
        canvas.segment(pixel(joints[i]), pixel(joints[i + 1]), 0.15 * scale, colour)
        if i > 0:
            canvas.disc(pixel(joints[i]), 0.075 * scale, colour)  # Round joints.
    canvas.disc(pixel(joints[0]), 0.1 * scale, (30, 70, 160))
    canvas.segment(pixel(centre), pixel(centre + velocity), 0.04 * scale, (220, 40, 40))
    canvas.disc(pixel(centre), 0.05 * scale, (0, 0, 0))
    return canvas.pixels


def tetris(board: Mapping[str, Any], cell: int = 24) -> np.ndarray:
    """The board (row 0 at the bottom) and, beside it, the piece to place in its colour; the
    filled cells turn red when the game is over."""
    cells = np.asarray(board["cells"], dtype=bool)
    rows, cols = cells.shape
    margin = cell // 2
    panel = 5 * cell
    canvas = Canvas(cols * cell + panel + 2 * margin, rows * cell + 2 * margin, (250, 250, 250))
    canvas.rect(margin, margin, margin + cols * cell, margin + rows * cell, (30, 30, 40))
    filled = (200, 60, 60) if board["game_over"] else (150, 160, 175)
    for r, c in zip(*np.nonzero(cells), strict=True):
        top = margin + (rows - 1 - int(r)) * cell
        left = margin + int(c) * cell
        canvas.rect(left + 1, top + 1, left + cell - 1, top + cell - 1, filled)
    colour = TETRIS_COLOURS[int(board["piece"])]
    origin_x, origin_y = 2 * margin + cols * cell + cell // 2, margin + 4 * cell
    for x, y in np.asarray(board["piece_cells"]):
        left, top = origin_x + int(x) * cell, origin_y - (int(y) + 1) * cell
        canvas.rect(left + 1, top + 1, left + cell - 1, top + cell - 1, colour)
    return canvas.pixels


_FROM_STATE: dict[str, Callable[[np.ndarray], np.ndarray]] = {
    "acrobot": acrobot,
    "cartpole": cartpole,
    "swimmer": swimmer,
}
DRAWN = (*sorted(_FROM_STATE), "tetris")  # The environments that render.


def check_mode(env_id: str, gpfd_env: str, render_mode: str | None) -> None:
    """ValueError unless `render_mode` is None or one this environment renders."""
    if render_mode is None:
        return
    if render_mode not in MODES:
        raise ValueError(
            f"{env_id} renders render_mode='rgb_array' only, got {render_mode!r} "
            "(gymnasium.make with render_mode='human' shows those frames in a window through "
            "Gymnasium's HumanRendering, which needs pygame)"
        )
    if gpfd_env not in DRAWN:
        raise ValueError(
            f"{env_id} cannot render (render_mode={render_mode!r}): gpfd draws "
            f"{', '.join(DRAWN)} only"
        )


def metadata(params: Mapping[str, Any]) -> dict[str, Any]:
    """Gymnasium's render metadata: the modes and the frame rate of real time (1 / dt; Tetris,
    without a time step, 4 pieces a second)."""
    fps = round(1.0 / float(params["dt"])) if "dt" in params else 4
    return {"render_modes": list(MODES), "render_fps": max(int(fps), 1)}


def frame(core: EnvBatch, index: int = 0) -> np.ndarray:
    """Instance `index` of a gpfd._core.EnvBatch drawn (one of DRAWN)."""
    if core.name == "tetris":
        return tetris(core.tetris_board(index))
    return _FROM_STATE[core.name](core.state(index))
