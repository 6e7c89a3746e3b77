"""ImageView: sensor_msgs/Image and CompressedImage drawn in the terminal with textual-image.

The pixels come from :func:`rostui.models.sensors.images.decode_image`,
already shrunk to the panel's size (aspect kept), so textual-image only
draws.  It draws with the kitty graphics protocol or sixel when the terminal
said it has them (asked once, before Textual starts: :func:`detect_graphics`),
else with half-block characters (two pixels a cell).  ``ROSTUI_VIEW_GRAPHICS``
(``auto``, ``kitty``, ``sixel``, ``halfblock``) overrides the choice.  Above
the picture one line gives the size, the encoding, the frame rates
(received, drawn) and the latency (header stamp to arrival; in a bag, to recording).
"""

from __future__ import annotations

import os
import sys
import time
from dataclasses import dataclass
from typing import Any, Callable

from PIL import Image as PILImage
from textual.app import ComposeResult
from textual.containers import Center
from textual.markup import escape
from textual.widget import Widget
from textual.widgets import Static

from rostui.apps.view.feed import Rate
from rostui.apps.view.halfblock import HalfBlock
from rostui.apps.view.registry import TopicView
from rostui.models.sensors.images import ImageDecodeError, Picture, decode_image, fit, raw_pixels_read

__all__ = ["ImageView", "detect_graphics", "graphics", "GRAPHICS_ENV"]

#: Environment variable that picks how images are drawn: auto, kitty, sixel or halfblock.
GRAPHICS_ENV = "ROSTUI_VIEW_GRAPHICS"
#: Seconds between repaints of the information line.
INFO_EVERY = 0.5
#: Most pixels of a raw frame read to draw it on the event loop rather than a worker thread: about 0.3 ms for
#: rgb8 and 2 ms for a coloured 32FC1 depth image here, less than a trip to a thread and back takes on a busy
#: machine (while it lasts, a newer frame may replace the one waiting: a frame dropped).
ON_LOOP_PIXELS = 1 << 16

_detected: str | None = None


def detect_graphics() -> str:
    """Ask the terminal (once, before Textual owns it) what it draws: ``kitty``, ``sixel`` or ``halfblock``.

    textual-image asks on import; without a terminal on stdout it asks
    nothing and the answer is ``halfblock``.
    """
    global _detected
    if _detected is None:
        _detected = "halfblock"
        if sys.__stdout__ is not None and sys.__stdout__.isatty() and sys.__stdin__ is not None \
                and sys.__stdin__.isatty():
            import textual_image.renderable as renderable
            import textual_image.widget  # noqa: F401  (asks the cell size while it still can)

            if renderable.Image is renderable.SixelImage:
                _detected = "sixel"
            elif renderable.Image is renderable.TGPImage:
                _detected = "kitty"
    return _detected


def graphics() -> str:
    """How images are drawn here: :data:`GRAPHICS_ENV` when set (not ``auto``), else what the terminal said."""
    chosen = os.environ.get(GRAPHICS_ENV, "auto").strip().lower()
    if chosen in ("kitty", "sixel", "halfblock"):
        return chosen
    return _detected or "halfblock"


def _image_widget(kind: str) -> Widget:
    if kind == "halfblock":
        return HalfBlock()
    if kind == "kitty":
        from rostui.apps.view.kitty import KittyImage

        return KittyImage()
    from textual_image import widget

    return widget.SixelImage()


def _cell_pixels() -> tuple[int, int]:
    from textual_image._terminal import get_cell_size

    size = get_cell_size()
    return max(1, size.width), max(1, size.height)


@dataclass(frozen=True)
class _Layout:
    """Where a picture goes: ``cols`` x ``rows`` cells of ``cell_w`` x ``cell_h`` pixels, decoded to ``box``."""

    cols: int
    rows: int
    cell_w: int
    cell_h: int
    box: tuple[int, int]


@dataclass(frozen=True)
class _Decoded:
    """A message decoded off the loop for ``layout``: its picture, or why there is none."""

    msg: Any
    layout: _Layout
    picture: Picture | None
    error: str


def _decode(msg: Any, box: tuple[int, int]) -> tuple[Picture | None, str]:
    """``msg`` decoded to fit ``box``, or None and the one line saying why not (safe on any thread)."""
    try:
        return decode_image(msg, box), ""
    except ImageDecodeError as exc:
        return None, str(exc)


class ImageView(TopicView):
    """The newest image of ``topic``, as large as the panel allows with its aspect kept, and a line of figures."""

    DEFAULT_CSS = """
    ImageView { height: 1fr; width: 1fr; }
    ImageView > .image-info { height: 1; width: 1fr; }
    ImageView > Center { height: 1fr; width: 1fr; }
    ImageView .image-pixels { width: auto; height: auto; }
    """

    def __init__(self, topic: str, *, id: str | None = None, classes: str | None = None,
                 kind: str | None = None) -> None:
        super().__init__(topic, id=id, classes=classes)
        self.kind = kind or graphics()
        self.info = Static(classes="image-info")
        self.pixels = _image_widget(self.kind)
        self.pixels.add_class("image-pixels")
        self.drawn = Rate()
        self.received = Rate()
        self.picture: Picture | None = None
        self.latency: float | None = None
        self.error = ""
        self.cells = (0, 0)
        self._last: tuple[Any, float] | None = None
        #: The area (cells) the last picture was fitted to.
        self.drawn_for = (0, 0)

    def compose(self) -> ComposeResult:
        """The information line over the picture."""
        yield self.info
        with Center():
            yield self.pixels

    def on_mount(self) -> None:
        """Repaint the figures twice a second (rates fall to 0 when frames stop)."""
        self.set_interval(INFO_EVERY, self.paint_info)
        self.paint_info()

    def area(self) -> tuple[int, int]:
        """Cells the picture may use: the view's size less the information line."""
        size = self.content_size
        return max(1, size.width), max(1, size.height - 1)

    def show_message(self, msg: Any, received: float) -> None:
        """Decode ``msg`` at the size it is drawn and draw it."""
        self.received.add(received)
        self._last = (msg, received)
        if self.laid_out() and self.draw(msg, received):
            self.drawn.add(time.time())

    def laid_out(self) -> bool:
        """True once the view has a size (before, :meth:`on_resize` draws what came)."""
        return self.content_size.width > 0 and self.content_size.height > 1

    def on_resize(self) -> None:
        """Draw the last image again at the new size (a latched camera sends no other)."""
        if self._last is not None and self.laid_out():
            if self.draw(*self._last) and self.drawn.count == 0:
                self.drawn.add(time.time())
            self.paint_info()

    def off_loop(self, msg: Any, received: float) -> Callable[[], Any] | None:
        """Decoding, for a worker thread: ``msg`` fitted to the view's size now (None before it has one, or when
        it is a raw frame cheap enough to decode here: see :data:`ON_LOOP_PIXELS`)."""
        if not self.laid_out():
            return None
        layout = self._layout(msg)
        read = raw_pixels_read(msg, layout.box)
        if read is not None and read <= ON_LOOP_PIXELS:
            return None
        return lambda: _Decoded(msg, layout, *_decode(msg, layout.box))

    def show_prepared(self, prepared: Any, received: float) -> None:
        """Draw a frame decoded off the loop (again, here, if the view changed size meanwhile)."""
        assert isinstance(prepared, _Decoded)
        self.received.add(received)
        self._last = (prepared.msg, received)
        if not self.laid_out():
            return
        layout = self._layout(prepared.msg)
        drawn = (self._present(prepared.msg, received, layout, prepared.picture, prepared.error)
                 if layout == prepared.layout else self.draw(prepared.msg, received))
        if drawn:
            self.drawn.add(time.time())

    def _layout(self, msg: Any) -> _Layout:
        """Where ``msg`` is drawn: the cells it may use and the pixels it is decoded to."""
        cols, rows = self.area()
        if self.kind == "halfblock":
            cell_w, cell_h = 1, 2
        else:
            cell_w, cell_h = _cell_pixels()
        box = (cols * cell_w, rows * cell_h)
        source = (int(getattr(msg, "width", 0) or 0), int(getattr(msg, "height", 0) or 0))
        if self.kind == "kitty" and min(source) > 0:
            box = (min(box[0], source[0]), min(box[1], source[1]))  # the terminal enlarges it
        return _Layout(cols, rows, cell_w, cell_h, box)

    def draw(self, msg: Any, received: float) -> bool:
        """Draw ``msg`` to fit the view; False (and the reason on the figures line) when it cannot be decoded."""
        layout = self._layout(msg)
        return self._present(msg, received, layout, *_decode(msg, layout.box))

    def _present(self, msg: Any, received: float, layout: _Layout, picture: Picture | None, error: str) -> bool:
        """Show a decoded ``picture`` (or why there is none) in ``layout``."""
        self.drawn_for = (layout.cols, layout.rows)
        if picture is None:
            self.error = error
            self.paint_info()
            return False
        first = self.picture is None or bool(self.error)
        self.error = ""
        self.picture = picture
        stamp = getattr(getattr(msg, "header", None), "stamp", None)
        seconds = stamp.to_sec() if stamp is not None and hasattr(stamp, "to_sec") else 0.0
        self.latency = received - seconds if seconds > 0 else None
        cell_w, cell_h = layout.cell_w, layout.cell_h
        height, width = picture.rgb.shape[:2]
        shown_w, shown_h = fit(width, height, layout.cols * cell_w, layout.rows * cell_h)
        self.cells = (max(1, round(shown_w / cell_w)), max(1, round(shown_h / cell_h)))
        if isinstance(self.pixels, HalfBlock):
            self.pixels.set_pixels(picture.rgb)
        else:
            self.pixels.styles.width, self.pixels.styles.height = self.cells
            self.pixels.image = PILImage.fromarray(picture.rgb, "RGB")  # type: ignore[attr-defined]
        if first:
            self.paint_info()
        return True

    def paint_info(self) -> None:
        """The line of figures: size, encoding, rates, latency (or why the last frame was not drawn)."""
        now = time.time()
        if self.error:
            self.info.update(f"[b red]{escape(self.error)}[/]")
            return
        picture = self.picture
        if picture is None:
            self.info.update("waiting for the first image")
            return
        parts = [f"{picture.width}x{picture.height} {picture.encoding}"]
        received = self.arrivals or self.received
        if received.count < 2:
            parts.append(f"{received.count} frame")
        else:
            parts.append(f"{received.per_second(now):.1f} fps ({self.drawn.per_second(now):.1f} drawn)")
        if self.latency is not None:
            parts.append(f"latency {self.latency * 1000:.0f} ms")
        if picture.depth_range is not None:
            parts.append(f"depth {picture.depth_range[0]:.2f}–{picture.depth_range[1]:.2f} m")
        parts.append(self.kind)
        self.info.update(escape("  ".join(parts)))
