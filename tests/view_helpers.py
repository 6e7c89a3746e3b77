"""Helpers for the view tests: the test-pattern camera as a real process, and the colours of drawn cells.

The camera is tests/view/image_pattern_pub.py, a plain rospy script run by
Debian's rospy (/usr/bin/python3) or unmodified by rostui's client
(`rostui python`).  The pattern (64x48): quadrants red (top left), green (top
right), blue (bottom left), white (bottom right) and a yellow marker square
in the middle of the top-left quadrant.
"""

from __future__ import annotations

import subprocess
from pathlib import Path
from typing import Any

import numpy as np
from PIL import Image as PILImage

from rostui.apps.view.halfblock import HalfBlock

from conftest import REPO, SYSTEM_PYTHON, rostui_cmd

SCRIPT = REPO / "tests" / "view" / "image_pattern_pub.py"
WIDTH, HEIGHT = 64, 48
RED, GREEN, BLUE, WHITE, YELLOW = (255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 255), (255, 255, 0)

#: Where to look (fractions of the picture's width and height) and the colour found there.
SAMPLES: tuple[tuple[float, float, tuple[int, int, int]], ...] = (
    (0.04, 0.05, RED), (0.25, 0.25, YELLOW), (0.75, 0.25, GREEN), (0.25, 0.75, BLUE), (0.75, 0.75, WHITE),
    (0.45, 0.45, RED), (0.55, 0.45, GREEN), (0.45, 0.55, BLUE), (0.55, 0.55, WHITE),
)
RAW = ("rgb8", "bgr8", "rgba8", "bgra8", "mono8", "mono16", "16UC1", "32FC1")
COMPRESSED = ("jpeg", "png")


def pattern() -> np.ndarray:
    """The test pattern as an RGB array (the script's own rule)."""
    rgb = np.zeros((HEIGHT, WIDTH, 3), dtype=np.uint8)
    rgb[: HEIGHT // 2, : WIDTH // 2] = RED
    rgb[: HEIGHT // 2, WIDTH // 2:] = GREEN
    rgb[HEIGHT // 2:, : WIDTH // 2] = BLUE
    rgb[HEIGHT // 2:, WIDTH // 2:] = WHITE
    rgb[HEIGHT // 8: HEIGHT * 3 // 8, WIDTH // 8: WIDTH * 3 // 8] = YELLOW
    return rgb


def grey(rgb: tuple[int, int, int]) -> tuple[int, int, int]:
    """A colour as the script's mono encodings carry it."""
    level = int(round(0.299 * rgb[0] + 0.587 * rgb[1] + 0.114 * rgb[2]))
    return level, level, level


def compressed_file(tmp_path: Path, fmt: str) -> Path:
    """The pattern written as a ``fmt`` (jpeg, png) file by Pillow."""
    path = tmp_path / f"pattern.{fmt}"
    PILImage.fromarray(pattern(), "RGB").save(path, "JPEG" if fmt == "jpeg" else "PNG", quality=95)
    return path


def start_camera(env: dict[str, str], tmp_path: Path, topic: str, encoding: str, *, rate: float = 10.0,
                 peer: str = "rostui") -> subprocess.Popen:
    """The pattern camera on ``topic`` as ``encoding``, by ``peer`` (``rospy`` or ``rostui``'s client)."""
    args = [str(SCRIPT), topic, encoding, f"{rate:g}"]
    if encoding in COMPRESSED:
        args.append(str(compressed_file(tmp_path, encoding)))
    argv = [SYSTEM_PYTHON, *args] if peer == "rospy" else rostui_cmd("python", *args)
    log = (tmp_path / f"camera{topic.replace('/', '_')}_{peer}.log").open("w")
    return subprocess.Popen(argv, env=env, stdout=log, stderr=subprocess.STDOUT)


def cell_colours(pixels: HalfBlock, fx: float, fy: float) -> tuple[tuple[int, int, int], tuple[int, int, int]]:
    """The (foreground, background) colours of the cell drawn at fraction (fx, fy) of ``pixels``'s picture."""
    width, height = pixels.size.width, pixels.size.height
    x, y = min(width - 1, int(fx * width)), min(height - 1, int(fy * height))
    strip = pixels.render_line(y)
    seen = 0
    for segment in strip:
        if seen + segment.cell_length > x:
            style: Any = segment.style
            assert segment.text[x - seen] == "▀", f"cell ({x}, {y}) is {segment.text[x - seen]!r}, not a half block"
            return tuple(style.color.triplet), tuple(style.bgcolor.triplet)  # type: ignore[return-value]
        seen += segment.cell_length
    raise AssertionError(f"no cell at ({x}, {y}) in a {width}x{height} picture")


def pixel_at(pixels: HalfBlock, fx: float, fy: float) -> tuple[int, int, int]:
    """The colour of the picture's pixel at fraction (fx, fy): the upper or lower half of its cell."""
    fg, bg = cell_colours(pixels, fx, fy)
    rows = pixels.size.height * 2
    return fg if int(fy * rows) % 2 == 0 else bg


def close(colour: tuple[int, int, int], expected: tuple[int, int, int], tolerance: int) -> bool:
    """Every channel of ``colour`` within ``tolerance`` of ``expected``."""
    return all(abs(int(a) - int(b)) <= tolerance for a, b in zip(colour, expected))
