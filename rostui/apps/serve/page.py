"""The page `rostui serve` hands a browser: textual-serve's xterm.js front end, and nothing from elsewhere.

textual-serve's own page links a font from a public CDN (an offline robot gets none, and every
browser that opens the app tells the CDN so).  This one names only this server: the Roboto Mono
font textual-serve ships (Apache 2.0) under ``/static/fonts``, the system's monospace after it,
and a Content-Security-Policy that makes the browser refuse anything else.  Its script finds the
websocket from the page's own address (so any name this server answers to works) and, when a
session ends, shows why the server ended it.
"""

from __future__ import annotations

from html import escape

#: Where :data:`STYLE` and :data:`SCRIPT` are served.
STYLE_PATH = "/page/rostui.css"
SCRIPT_PATH = "/page/rostui.js"

#: Headers of every answer: this server's files only, never framed by another page, no Referer.
SECURITY_HEADERS = {
    "Content-Security-Policy": ("default-src 'self'; connect-src 'self'; img-src 'self' data:; "
                                "style-src 'self' 'unsafe-inline'; script-src 'self'; font-src 'self'; "
                                "object-src 'none'; base-uri 'none'; form-action 'none'; frame-ancestors 'none'"),
    "X-Frame-Options": "DENY",
    "Referrer-Policy": "no-referrer",
    "X-Content-Type-Options": "nosniff",
    "Cache-Control": "no-store",
}

#: The page's look, and the font from this server.
STYLE = """\
@font-face {
  font-family: "Roboto Mono";
  src: url("../static/fonts/RobotoMono-VariableFont_wght.ttf") format("truetype");
  font-weight: 100 700;
  font-style: normal;
}
@font-face {
  font-family: "Roboto Mono";
  src: url("../static/fonts/RobotoMono-Italic-VariableFont_wght.ttf") format("truetype");
  font-weight: 100 700;
  font-style: italic;
}
html, body { margin: 0; height: 100%; background: #0c181f; }
body { font-family: "Roboto Mono", ui-monospace, "DejaVu Sans Mono", monospace; color: rgba(255, 255, 255, 0.95); }
#terminal { position: absolute; inset: 0; opacity: 0; transition: opacity 0.3s ease-out; }
body.-first-byte #terminal { opacity: 1; }
.card {
  position: absolute; inset: 0; display: flex; align-items: center; justify-content: center;
  flex-direction: column; gap: 16px; background: #0c181f; z-index: 10; text-align: center;
}
body.-first-byte #starting, #ended { display: none; }
body.-closed #ended { display: flex; }
#ended-reason { max-width: 48em; }
button {
  padding: 12px 28px; border: none; background: #5e0ba7; color: inherit; font: inherit; cursor: pointer;
}
button:hover { background: #ac5af4; }
"""

#: Runs before textual.js connects: the websocket from this page's address; the reason a session ended.
SCRIPT = """\
"use strict";
(function () {
  const terminal = document.getElementById("terminal");
  const scheme = window.location.protocol === "https:" ? "wss:" : "ws:";
  const here = window.location.pathname.replace(/[^/]*$/, "");
  terminal.dataset.sessionWebsocketUrl = scheme + "//" + window.location.host + here + "ws";
  const NativeWebSocket = window.WebSocket;
  window.WebSocket = class extends NativeWebSocket {
    constructor(url, protocols) {
      super(url, protocols);
      this.addEventListener("close", (event) => {
        if (event.reason) {
          document.getElementById("ended-reason").textContent = event.reason;
        }
      });
    }
  };
  document.getElementById("restart").addEventListener("click", () => window.location.reload());
})();
"""

_PAGE = """\
<!DOCTYPE html>
<html>
  <head>
    <meta charset="utf-8">
    <title>{title}</title>
    <link rel="icon" href="data:,">
    <link rel="preload" href="static/fonts/RobotoMono-VariableFont_wght.ttf" as="font" type="font/ttf" crossorigin>
    <link rel="stylesheet" href="static/css/xterm.css">
    <link rel="stylesheet" href="{style}">
    <script src="static/js/textual.js"></script>
    <script src="{script}" defer></script>
  </head>
  <body>
    <div class="card" id="starting"><div>{title}</div><div>starting…</div></div>
    <div class="card" id="ended">
      <div>Session ended.</div>
      <div id="ended-reason"></div>
      <button type="button" id="restart">Restart</button>
    </div>
    <div id="terminal" class="textual-terminal" data-font-size="{font_size}"></div>
  </body>
</html>
"""

#: The font sizes a page may ask for (``?fontsize=``).
FONT_SIZES = range(6, 65)


def page(title: str, font_size: int) -> str:
    """The HTML of the page for an app called ``title``, drawn at ``font_size`` px (clamped to :data:`FONT_SIZES`)."""
    size = min(max(font_size, FONT_SIZES.start), FONT_SIZES.stop - 1)
    return _PAGE.format(title=escape(title), font_size=size, style=STYLE_PATH.lstrip("/"),
                        script=SCRIPT_PATH.lstrip("/"))
