"""KittyImage: a picture drawn with the kitty graphics protocol, its escapes written through Textual's own output.

textual-image's ``TGPImage`` draws with unicode placeholders (a virtual
placement, ``U=1``) and is kept for that; what it does not do well for a
camera is replaced here:

- it writes the image escapes to ``sys.__stdout__`` itself, from the main
  thread, while Textual writes its frames to ``sys.__stderr__`` from its
  writer thread: the two can interleave in the middle of an escape.  Here
  every escape goes through the app driver's ``write``, in order with the
  frame that shows the placeholders;
- it deletes the previous image with ``a=d,I=<id>`` (no ``d`` key: "every
  placement on screen", and no data freed), so a camera's frames pile up in
  the terminal's image store.  Here each new frame frees the one before it
  (``a=d,d=I,i=<id>``), and quitting frees the last one;
- it sends the image again on every repaint of the widget; here only when
  the picture or its size changed;
- it enlarges a small picture to the cells' pixels before encoding it;
  here the terminal does (kitty fits the image to the placement's cells).

This subclasses textual-image's renderable and widget internals, which is
why pyproject.toml pins textual-image to 0.12.
"""

from __future__ import annotations

import sys
from typing import Any, Callable

from textual.app import RenderResult as TextualRenderResult
from textual_image.renderable import tgp
from textual_image.widget._base import Image as BaseImage

__all__ = ["KittyImage", "KittyRenderable", "escape"]

_START, _END = "\x1b_G", "\x1b\\"


def escape(payload: str | None = None, **keys: int | str) -> str:
    """One kitty graphics command: ``ESC _ G key=value,... [;payload] ESC \\``."""
    body = ",".join(f"{k}={v}" for k, v in keys.items())
    return f"{_START}{body}{';' + payload if payload else ''}{_END}"


def _stdout(data: str) -> None:
    if sys.__stdout__ is not None:
        sys.__stdout__.write(data)
        sys.__stdout__.flush()


class KittyRenderable(tgp.Image):
    """textual-image's kitty renderable, writing through ``write`` and freeing images properly."""

    write: Callable[[str], None] = staticmethod(_stdout)

    def _send_image_to_terminal(self, width: int, height: int) -> None:
        self.terminal_image_id = next(tgp.Image._image_id_counter) % (2**32 - 1) + 1
        pixels = self._image_data
        if pixels.width > width or pixels.height > height:
            pixels = pixels.scaled(width, height)
        # a smaller picture is sent as it is: the terminal enlarges it to the placement's cells,
        # which costs neither PNG encoding nor bytes on the line
        data = pixels.to_base64()
        parts = []
        while data:
            chunk, data = data[:4096], data[4096:]
            parts.append(escape(chunk, i=self.terminal_image_id, m=1 if data else 0, f=100, q=2))
        self.write("".join(parts))

    def _create_virtual_placement(self, width: int, height: int) -> None:
        assert self.terminal_image_id
        self.write(escape(a="p", i=self.terminal_image_id, c=width, r=height, U=1, q=2))

    def cleanup(self) -> None:
        """Delete the image and free its data in the terminal (a no-op when it was never sent)."""
        if self.terminal_image_id:
            self.write(escape(a="d", d="I", i=self.terminal_image_id, q=2))
            self.terminal_image_id = None


class KittyImage(BaseImage, Renderable=KittyRenderable):
    """A Textual widget showing ``image`` with the kitty graphics protocol, through the app's own output."""

    def _write(self, data: str) -> None:
        driver = getattr(self.app, "_driver", None)
        if driver is not None and getattr(driver, "_writer_thread", True) is not None:
            driver.write(data)
        else:
            _stdout(data)

    def render(self) -> TextualRenderResult:
        """The placeholder cells; the image is sent again only when it or the widget's size changed."""
        if not self._image:
            return ""
        size = self._get_styled_size()
        current: Any = self._renderable
        if current is not None and getattr(current, "_for", None) == (id(self._image), size):
            return current
        if current is not None:
            current.cleanup()
        renderable = KittyRenderable(self._image, *size)
        renderable.write = self._write
        renderable._for = (id(self._image), size)  # type: ignore[attr-defined]
        self._renderable = renderable
        return renderable

    def on_unmount(self) -> None:
        """Free the last image in the terminal."""
        if self._renderable is not None:
            self._renderable.cleanup()
            self._renderable = None
