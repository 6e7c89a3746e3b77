"""`rostui view /camera/image_raw` drawing with kitty graphics and sixel, end to end on a pseudo-terminal.

The real command runs on a pty (not tmux, which strips these escapes) sized
80x24 cells of 8x16 pixels (TIOCSWINSZ carries the pixel size, as kitty and
xterm set it); the pattern camera (tests/view/image_pattern_pub.py, rostui's
client) publishes on a `rostui core` master.  The test keeps every byte the
app writes and reads the pictures out of them:

- kitty: the ``ESC _ G ... ESC \\`` commands carry a PNG (base64, in chunks);
  decoded with Pillow it has the pattern's colours in the right quadrants, at
  the camera's size (no larger than the cells it is placed on, which keep the
  aspect); each new frame frees the one before it, and quitting frees the last;
- sixel: the ``ESC P ... q`` picture's palette holds the pattern's colours,
  its raster size is its cells times the cell's pixels, and the pixels of
  each quadrant have the right colour register.

Either way is forced with ROSTUI_VIEW_GRAPHICS, or picked by the app from the
terminal's answers to textual-image's queries, which the test writes back to
the pty as a terminal would.
"""

from __future__ import annotations

import base64
import fcntl
import io
import os
import pty
import re
import signal
import struct
import subprocess
import sys
import termios
import threading
import time
from pathlib import Path
from typing import Any, Callable, Iterator

import pytest
from PIL import Image as PILImage

from conftest import stop_process, until
from view_helpers import start_camera

REPO = Path(__file__).resolve().parent.parent
COLS, ROWS, CELL_W, CELL_H = 80, 24, 8, 16
RED, GREEN, BLUE, WHITE, YELLOW = (255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 255), (255, 255, 0)
#: (fraction x, fraction y, colour) of the pattern (tests/view/image_pattern_pub.py).
SAMPLES = [(0.75, 0.25, GREEN), (0.25, 0.75, BLUE), (0.75, 0.75, WHITE), (0.25, 0.25, YELLOW), (0.05, 0.05, RED)]
KITTY = re.compile(rb"\x1b_G([^;\x1b]*)(?:;([^\x1b]*))?\x1b\\")
SIXEL = re.compile(rb"\x1bP[0-9;]*q\"1;1;(\d+);(\d+)(.*?)\x1b\\", re.S)


class Terminal:
    """The real `rostui view` on a pty; keeps what it writes and answers queries through ``answer``."""

    def __init__(self, argv: list[str], env: dict[str, str], answer: Callable[[bytes], bytes] | None = None) -> None:
        master, slave = pty.openpty()
        fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", ROWS, COLS, COLS * CELL_W, ROWS * CELL_H))
        self.proc = subprocess.Popen(argv, env=env, cwd=REPO, stdin=slave, stdout=slave, stderr=slave,
                                     start_new_session=True, close_fds=True)
        os.close(slave)
        self.fd = master
        self.data = bytearray()
        self.lock = threading.Lock()
        self.answer = answer
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self) -> None:
        answered = 0
        while True:
            try:
                chunk = os.read(self.fd, 65536)
            except OSError:
                return
            if not chunk:
                return
            with self.lock:
                self.data += chunk
                seen = bytes(self.data)
            if self.answer is not None:
                reply = self.answer(seen[answered:])
                if reply:
                    answered = len(seen)
                    os.write(self.fd, reply)

    def output(self) -> bytes:
        """Everything written so far."""
        with self.lock:
            return bytes(self.data)

    def quit(self) -> int:
        """Press q; the exit status (the process's session is killed after 20 s)."""
        if self.fd < 0:
            return self.proc.returncode
        if self.proc.poll() is None:
            os.write(self.fd, b"q")
            try:
                self.proc.wait(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait()
        self.reader.join(timeout=5)
        os.close(self.fd)
        self.fd = -1
        return self.proc.returncode


@pytest.fixture
def camera(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> Iterator[subprocess.Popen]:
    """The pattern camera, 64x48 rgb8 at 10 Hz."""
    proc = start_camera(ros_env, tmp_path, "/camera/image_raw", "rgb8", rate=10)
    yield proc
    stop_process(proc)


def view(env: dict[str, str], graphics: str | None, answer: Callable[[bytes], bytes] | None = None) -> Terminal:
    """`rostui view /camera/image_raw` with ROSTUI_VIEW_GRAPHICS=``graphics`` (None: not set)."""
    env = {k: v for k, v in env.items() if k not in ("ROSTUI_VIEW_GRAPHICS", "COLUMNS", "LINES")}
    env.update(TERM="xterm-256color", COLORTERM="truecolor")
    if graphics is not None:
        env["ROSTUI_VIEW_GRAPHICS"] = graphics
    return Terminal([sys.executable, "-m", "rostui", "view", "/camera/image_raw"], env, answer)


def kitty_images(out: bytes) -> tuple[dict[int, PILImage.Image], list[dict[str, str]]]:
    """The images transmitted (id -> picture) and every other command (placements, deletions) in ``out``."""
    images: dict[int, PILImage.Image] = {}
    others: list[dict[str, str]] = []
    pending: dict[int, str] = {}
    for keys_raw, payload in KITTY.findall(out):
        keys = dict(kv.split("=", 1) for kv in keys_raw.decode().split(",") if "=" in kv)
        if "f" in keys and keys.get("a", "t") == "t":  # a PNG (f=100), in chunks: m=1 until the last
            assert keys["f"] == "100", keys
            image_id = int(keys["i"])
            pending[image_id] = pending.get(image_id, "") + payload.decode()
            if keys.get("m", "0") == "0":
                images[image_id] = PILImage.open(io.BytesIO(base64.b64decode(pending.pop(image_id)))).convert("RGB")
        else:
            others.append(keys)
    return images, others


def check_pattern(picture: PILImage.Image) -> None:
    """The pattern's colours are where the pattern has them (sampled away from the edges)."""
    for fx, fy, colour in SAMPLES:
        x, y = int(fx * picture.width), int(fy * picture.height)
        got = picture.getpixel((x, y))
        assert max(abs(a - b) for a, b in zip(got, colour)) <= 8, f"({fx}, {fy}) is {got}, not {colour}"


def wait_for(term: Terminal, test: Callable[[bytes], bool], what: str, timeout: float = 30.0) -> bytes:
    """The output once ``test`` holds for it; fails naming ``what`` and the exit status when it never does."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        out = term.output()
        if test(out):
            return out
        if term.proc.poll() is not None:
            break
        time.sleep(0.1)
    raise AssertionError(f"no {what}; exit status {term.proc.poll()}; last output {term.output()[-2000:]!r}")


def check_kitty(term: Terminal) -> None:
    """Three frames of the pattern come as kitty images, each freed by the next; quitting frees the last."""
    out = wait_for(term, lambda out: len(kitty_images(out)[0]) >= 3, "three kitty images")
    images, others = kitty_images(out)
    for picture in images.values():
        check_pattern(picture)
    placements = [keys for keys in others if keys.get("a") == "p"]
    assert placements and all(keys.get("U") == "1" for keys in placements)
    first = placements[0]
    cells = int(first["c"]), int(first["r"])
    picture = images[int(first["i"])]
    assert picture.size == (64, 48)  # sent at the camera's size: the terminal enlarges it to the cells
    assert cells[0] > 20 and abs(cells[0] * CELL_W / (cells[1] * CELL_H) - 64 / 48) < 0.1  # aspect kept
    assert re.search(rb"64x48 rgb8 .*kitty", out)
    assert term.quit() == 0
    out = term.output()
    # an escape cut in two by another one written beside it
    broken = re.search(rb"\x1b\[(?=([0-?]*))\1(?=([ -/]*))\2(?![@-~])", out)
    assert broken is None, out[max(0, broken.start() - 80):broken.start() + 80]
    images, others = kitty_images(out)
    freed = {int(keys["i"]) for keys in others if keys.get("a") == "d" and keys.get("d") == "I"}
    assert freed == set(images), "every image sent is freed in the terminal, the last one on quit"


def sixel_pictures(out: bytes) -> list[tuple[int, int, bytes]]:
    """(width, height, body) of every sixel picture in ``out``."""
    return [(int(w), int(h), body) for w, h, body in SIXEL.findall(out)]


def sixel_decode(body: bytes, width: int, height: int) -> PILImage.Image:
    """The picture a sixel body draws.

    Palette entries are ``#n;2;r;g;b`` in percent; ``$`` goes back to column 0, ``-`` to the next band.
    """
    picture = PILImage.new("RGB", (width, height))
    palette: dict[int, tuple[int, int, int]] = {}
    colour, x, band = (0, 0, 0), 0, 0
    for select, rgb, rle, char, control in re.findall(
            rb"#(\d+)(;2;\d+;\d+;\d+)?|!(\d+)([?-~])|([?-~$-])", body):
        if select:
            if rgb:
                palette[int(select)] = tuple(round(int(v) * 255 / 100) for v in rgb.split(b";")[2:])  # type: ignore
            colour = palette[int(select)]
            continue
        if control == b"$":
            x = 0
            continue
        if control == b"-":
            x, band = 0, band + 1
            continue
        run, bits = (int(rle), char[0] - 63) if rle else (1, control[0] - 63)
        for bit in range(6):
            y = band * 6 + bit
            if bits >> bit & 1 and y < height:
                for column in range(x, min(width, x + run)):
                    picture.putpixel((column, y), colour)
        x += run
    return picture


def check_sixel(term: Terminal) -> None:
    """The pattern comes as sixel pictures: its colours in the palette, in their quadrants, at the cells' size."""
    out = wait_for(term, lambda out: len(sixel_pictures(out)) >= 2, "two sixel pictures")
    width, height, body = sixel_pictures(out)[-1]
    palette = {tuple(round(int(v) * 255 / 100) for v in rgb) for rgb in re.findall(rb"#\d+;2;(\d+);(\d+);(\d+)", body)}
    assert {RED, GREEN, BLUE, WHITE, YELLOW} <= palette
    assert width % CELL_W == 0 and height % CELL_H == 0  # whole cells
    cells_w, cells_h = width // CELL_W, height // CELL_H
    assert cells_w > 20 and abs((width / height) - 64 / 48) < 0.1
    check_pattern(sixel_decode(body, width, height))
    assert re.search(rb"64x48 rgb8 .*sixel", out)
    assert cells_h <= ROWS - 3
    assert term.quit() == 0


def test_kitty_forced(camera: Any, ros_env: dict[str, str]) -> None:
    term = view(ros_env, "kitty")
    try:
        check_kitty(term)
    finally:
        term.quit()


def test_sixel_forced(camera: Any, ros_env: dict[str, str]) -> None:
    term = view(ros_env, "sixel")
    try:
        check_sixel(term)
    finally:
        term.quit()


def kitty_terminal(out: bytes) -> bytes:
    """A kitty-like terminal's answers: device attributes without sixel, OK to the graphics query."""
    reply = b""
    if b"\x1b[c" in out:
        reply += b"\x1b[?62;22c"
    query = re.search(rb"\x1b_Gi=(\d+),[^;]*a=q[^;]*;AAAA\x1b\\", out)
    if query:
        reply += b"\x1b_Gi=" + query.group(1) + b";OK\x1b\\"
    return reply


def sixel_terminal(out: bytes) -> bytes:
    """An xterm -ti vt340-like terminal's answer: device attributes with 4 (sixel)."""
    return b"\x1b[?63;1;2;4;6;9;15;22c" if b"\x1b[c" in out else b""


@pytest.mark.parametrize("answer, check", [(kitty_terminal, check_kitty), (sixel_terminal, check_sixel)],
                         ids=["kitty", "sixel"])
def test_picked_from_the_terminals_answer(camera: Any, ros_env: dict[str, str], answer: Any, check: Any) -> None:
    term = view(ros_env, None, answer)
    try:
        check(term)
    finally:
        term.quit()
