"""The rules of `rostui serve` in process: who gets in (token, Host, Origin), what a page may send (sizes clamped),
and a page that names no other site.  The same rules over HTTP: tests/hostile/test_serve_sessions.py."""

from __future__ import annotations

import re
import socket

import pytest

from rostui.apps.serve.access import Access, host_and_port, machine_names, new_token
from rostui.apps.serve.messages import (
    MAX_COLUMNS,
    MAX_ROWS,
    BadMessage,
    Focus,
    Ping,
    Resize,
    Stdin,
    clamp_size,
    parse,
    size_from_query,
)
from rostui.apps.serve.page import SCRIPT, SECURITY_HEADERS, STYLE, page

from cli_helpers import rostui
from conftest import free_port

TOKEN = "t" * 32


def local(port: int = 8000, public: str = "http://localhost:8000") -> Access:
    """The rules of a server on 127.0.0.1:``port`` opened at ``public``."""
    return Access(TOKEN, port, machine_names("127.0.0.1"), public)


def test_tokens_are_long_random_and_new_on_each_start() -> None:
    tokens = {new_token() for _ in range(50)}
    assert len(tokens) == 50
    assert all(len(t) >= 32 and re.fullmatch(r"[A-Za-z0-9_-]+", t) for t in tokens)


def test_the_token_is_required_in_the_url_or_the_cookie() -> None:
    rules = local()
    assert rules.check("localhost:8000", None, TOKEN, None) is None
    assert rules.check("localhost:8000", None, None, TOKEN) is None
    for query, cookie in ((None, None), ("", None), (TOKEN[:-1], None), (None, TOKEN + "x"), (TOKEN.upper(), None)):
        refusal = rules.check("localhost:8000", None, query, cookie)
        assert refusal is not None and refusal.check == "token" and refusal.status == 403
        assert TOKEN not in refusal.reason
    assert rules.cookie == "rostui-serve-8000"  # cookies do not tell ports apart: one name a port


@pytest.mark.parametrize("host", ["localhost:8000", "127.0.0.1:8000", "[::1]:8000", "LOCALHOST:8000"])
def test_this_machine_s_names_with_the_served_port_are_accepted(host: str) -> None:
    assert local().check(host, f"http://{host}", TOKEN, None) is None


@pytest.mark.parametrize("host", [None, "", "attacker.example:8000", "attacker.example", "localhost:8001",
                                  "localhost", "localhost:notaport", "user@localhost:8000", "localhost:8000/x"])
def test_other_host_headers_are_refused(host: str | None) -> None:
    refusal = local().check(host, None, TOKEN, None)
    assert refusal is not None and refusal.check == "host", host


@pytest.mark.parametrize("origin", ["http://attacker.example", "http://localhost:8001", "http://localhost",
                                    "null", "file://", "ws://localhost:8000x", "chrome-extension://abc",
                                    "http://localhost:8000.attacker.example"])
def test_pages_of_other_origins_are_refused_even_with_the_token(origin: str) -> None:
    refusal = local().check("localhost:8000", origin, TOKEN, TOKEN)
    assert refusal is not None and refusal.check == "origin", origin
    assert refusal.reason.startswith("rostui serve: a page from ")


def test_a_tunnel_to_another_port_is_accepted_when_named_as_the_public_url() -> None:
    rules = local(public="http://localhost:9000")
    assert rules.check("localhost:9000", "http://localhost:9000", TOKEN, None) is None
    assert rules.check("localhost:8000", "http://localhost:8000", TOKEN, None) is None
    proxied = local(public="https://robot.example")
    assert proxied.check("robot.example", "https://robot.example", TOKEN, None) is None
    assert proxied.check("robot.example", "http://robot.example", TOKEN, None) is not None


def test_listening_everywhere_accepts_this_machine_s_names_only() -> None:
    rules = Access(TOKEN, 8000, machine_names("0.0.0.0"), "http://robot:8000")
    assert rules.check(f"{socket.gethostname()}:8000", None, TOKEN, None) is None
    assert rules.check("127.0.0.1:8000", None, TOKEN, None) is None
    assert rules.check("robot:8000", "http://robot:8000", TOKEN, None) is None
    assert rules.check("attacker.example:8000", None, TOKEN, None) is not None


def test_host_and_port() -> None:
    assert host_and_port("LocalHost:80") == ("localhost", 80)
    assert host_and_port("[::1]:8000") == ("::1", 8000)
    assert host_and_port("robot", "https") == ("robot", 443)
    for bad in ("", ":8000", "a:b", "a:99999", "x@y:1", "a/b"):
        assert host_and_port(bad) is None, bad


def test_sizes_are_clamped_and_only_numbers_are_sizes() -> None:
    assert clamp_size(100000, 100000) == (MAX_COLUMNS, MAX_ROWS)
    assert clamp_size(10 ** 30, -5) == (MAX_COLUMNS, 1)
    assert clamp_size(0, 0) == (1, 1)
    assert clamp_size(132, 43) == (132, 43)
    for width, height in (("80", 24), (80.0, 24), (True, 24), (None, 24), ([80], 24)):
        with pytest.raises(BadMessage):
            clamp_size(width, height)
    assert size_from_query("100000", "100000") == (MAX_COLUMNS, MAX_ROWS)
    assert size_from_query("x", "24") == (80, 24)
    assert size_from_query(None, None) == (80, 24)
    assert size_from_query("1e9", "24") == (80, 24)


def test_what_a_page_sends_is_read_strictly() -> None:
    assert parse('["stdin", "q"]') == Stdin("q")
    assert parse('["resize", {"width": 100000, "height": 40}]') == Resize(MAX_COLUMNS, 40)
    assert parse('["ping", "1700000000000"]') == Ping("1700000000000")
    assert parse('["focus"]') == Focus(True) and parse('["blur"]') == Focus(False)
    for text in ("", "q", "[]", "{}", "[1]", '["stdin"]', '["stdin", 5]', '["stdin", "a", "b"]', '["focus", 1]',
                 '["resize", [80, 24]]', '["resize", {"width": "80", "height": 24}]', '["open_url", "x"]',
                 "[" * 100000, '"stdin"'):
        with pytest.raises(BadMessage):
            parse(text)


def test_the_page_names_no_other_site() -> None:
    html = page('rostui bag view <script>alert(1)</script>.bag', 10 ** 6)
    everything = html + STYLE + SCRIPT
    assert not re.search(r"(https?:)?//(?!\" \+ window\.location\.host)[a-z]", everything.replace("ws:", "")), \
        re.findall(r"\S*//\S*", everything)
    assert "<script>alert" not in html and "&lt;script&gt;" in html
    assert 'data-font-size="64"' in html
    policy = SECURITY_HEADERS["Content-Security-Policy"]
    assert "default-src 'self'" in policy and "frame-ancestors 'none'" in policy and "https:" not in policy
    assert "Roboto Mono" in STYLE and "monospace" in STYLE


def test_serve_refuses_a_session_limit_below_one(ros_env: dict[str, str]) -> None:
    r = rostui(["serve", "--port", str(free_port()), "--max-sessions", "0", "graph"], ros_env)
    assert r.returncode == 1 and r.stdout == ""
    assert r.stderr == "rostui serve: --max-sessions must be 1 or more, not 0\n"
