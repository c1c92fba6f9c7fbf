# gpfd.render, an import path users have (the drawing of gpfd's environments): the public names and
# the docstring of gpfd.environments.render, where the code is (scripts/check-python-imports).
from gpfd.environments import render as _code
from gpfd.environments.render import (
    ACROBOT_LINK_LENGTH,
    CARTPOLE_POLE_LENGTH,
    CARTPOLE_X_LIMIT,
    DRAWN,
    MODES,
    SWIMMER_SEGMENT_LENGTH,
    TETRIS_COLOURS,
    Canvas,
    Colour,
    Point,
    acrobot,
    cartpole,
    check_mode,
    frame,
    metadata,
    swimmer,
    tetris,
)

__doc__ = _code.__doc__
__all__ = [
    "ACROBOT_LINK_LENGTH",
    "CARTPOLE_POLE_LENGTH",
    "CARTPOLE_X_LIMIT",
    "Canvas",
    "Colour",
    "DRAWN",
    "MODES",
    "Point",
    "SWIMMER_SEGMENT_LENGTH",
    "TETRIS_COLOURS",
    "acrobot",
    "cartpole",
    "check_mode",
    "frame",
    "metadata",
    "swimmer",
    "tetris",
]
