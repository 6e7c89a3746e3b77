"""A real browser for end-to-end tests of `rostui serve`: Debian's chromium, headless, driven by selenium.

textual-serve's page draws the app with xterm.js on a canvas (its WebGL or canvas
renderer), so the screen's text is not in the DOM.  The page keeps its xterm.js
``Terminal`` in a closure; :meth:`XtermPage.terminal_found` finds it through
the DevTools protocol (``Runtime.queryObjects`` lists the page's live objects)
by the shape of xterm.js's public API, and :meth:`XtermPage.screen` reads the
visible rows with that API (``buffer.active.getLine(y).translateToString()``).
"""

from __future__ import annotations

import shutil
import tempfile
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Iterator

from conftest import need_command, wait_until

DEADLINE = 30.0
"""Seconds a wait for the page may take (generous: CI machines are slow)."""

#: Run on the array of the page's objects: keep the one xterm.js Terminal (public API) as window.__rostuiXterm.
FIND_TERMINAL = """function () {
    const isTerminal = (o) => {
        try {
            return typeof o.loadAddon === "function" && typeof o.onData === "function"
                && typeof o.buffer.active.getLine === "function";
        } catch (e) {
            return false;
        }
    };
    window.__rostuiXterm = this.find(isTerminal) || null;
    return window.__rostuiXterm !== null;
}"""

#: The visible rows of the terminal, one string a row (trailing blanks dropped).
READ_ROWS = """const term = window.__rostuiXterm;
const buffer = term.buffer.active;
const rows = [];
for (let y = 0; y < term.rows; y++) {
    const line = buffer.getLine(buffer.viewportY + y);
    rows.push(line ? line.translateToString(true) : "");
}
return rows.join("\\n");"""


@contextmanager
def headless_chromium(width: int = 1200, height: int = 800) -> Iterator[Any]:
    """A selenium WebDriver on Debian's headless chromium (chromium-driver), quit on leaving.

    Each browser has a profile of its own in a new temporary folder (removed on leaving), so browsers of
    tests running side by side share no cookies, cache or lock file.
    """
    need_command("chromium")
    need_command("chromedriver")
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    profile = tempfile.mkdtemp(prefix="rostui-chromium-")
    options = webdriver.ChromeOptions()
    options.binary_location = str(shutil.which("chromium"))
    for flag in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--disable-gpu",
                 f"--window-size={width},{height}", "--no-first-run", "--disable-extensions",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync",
                 f"--user-data-dir={profile}"):
        options.add_argument(flag)
    try:
        driver = webdriver.Chrome(service=Service(executable_path=str(shutil.which("chromedriver"))),
                                  options=options)
        try:
            yield driver
        finally:
            driver.quit()
    finally:
        shutil.rmtree(profile, ignore_errors=True)


@dataclass
class XtermPage:
    """textual-serve's page in a selenium-driven browser."""

    driver: Any

    def open(self, url: str) -> None:
        """Load ``url`` (the page connects its websocket at once) and wait until the app has drawn."""
        self.driver.get(url)
        wait_until(lambda: "-first-byte" in self.driver.execute_script("return document.body.className"),
                   f"the first bytes of the app at {url}", timeout=DEADLINE)
        wait_until(self.terminal_found, "xterm.js's Terminal in the page", timeout=DEADLINE)

    def terminal_found(self) -> bool:
        """Find the page's xterm.js Terminal among its live objects; True once it is kept."""
        cdp = self.driver.execute_cdp_cmd
        prototype = cdp("Runtime.evaluate", {"expression": "Object.prototype"})["result"]["objectId"]
        objects = cdp("Runtime.queryObjects", {"prototypeObjectId": prototype})["objects"]["objectId"]
        found = cdp("Runtime.callFunctionOn", {"objectId": objects, "functionDeclaration": FIND_TERMINAL,
                                               "returnByValue": True})
        return bool(found["result"].get("value"))

    def screen(self) -> str:
        """The terminal's visible text, as the page shows it."""
        return str(self.driver.execute_script(READ_ROWS))

    def shows(self, text: str) -> bool:
        """True when ``text`` is on the screen."""
        return text in self.screen()

    def wait_for(self, text: str) -> None:
        """Wait until ``text`` is on the screen."""
        try:
            wait_until(lambda: self.shows(text), f"{text!r} in the browser", timeout=DEADLINE)
        except AssertionError as exc:
            raise AssertionError(f"{exc}; the screen is:\n{self.screen()}") from None

    def press(self, *keys: str) -> None:
        """Type ``keys`` (selenium Keys values or text) into the terminal, as a person at the page would."""
        from selenium.webdriver.common.by import By

        self.driver.find_element(By.CSS_SELECTOR, ".xterm-helper-textarea").send_keys(*keys)

    def screenshot(self, path: Path) -> Path:
        """Save a PNG of the page; returns ``path``."""
        assert self.driver.save_screenshot(str(path)), f"chromium saved no screenshot at {path}"
        return path

    def close_tab(self) -> None:
        """Close the page's tab as a person would (its websocket closes); go on in a new blank tab."""
        page = self.driver.current_window_handle
        self.driver.switch_to.new_window("tab")
        blank = self.driver.current_window_handle
        self.driver.switch_to.window(page)
        self.driver.close()
        self.driver.switch_to.window(blank)

    def closed(self) -> bool:
        """True once the page says the session ended (its websocket closed)."""
        return "-closed" in str(self.driver.execute_script("return document.body.className"))
