"""`rostui publish` and `rostui call` end to end in a real terminal (tmux, 80x24) on the module's `rostui core`:
a String typed into the form reaches Debian's rospy subscriber on ctrl+s; a SetBool request set to True
reaches Debian's rospy server and its answer shows; q on the fields returns to the shell with 0."""

from __future__ import annotations

from typing import Iterator

import pytest

from interop_helpers import peers, rospy_peer
from test_form_app import env, master, received  # noqa: F401  (fixtures)
from tmux_helpers import Pane, rostui_line, shell_pane

EXIT_MARK = "FORM_EXIT="


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 80x24 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("form", 80, 24) as pane:
        yield pane


def send_data(pane: Pane, expression: str) -> None:
    """Enter on the form's first field (``data``), its expression typed over, Enter, then ctrl+s."""
    pane.keys("Enter")
    pane.wait_until(lambda: pane.shows("Enter takes it"), "the expression editor")
    pane.keys("C-u")
    pane.type(expression)
    pane.wait_until(lambda: pane.shows(f"data = {expression}"), "the new expression")
    pane.keys("C-s")


def test_publish_in_tmux(pane: Pane, env: dict[str, str]) -> None:
    with peers(env) as spawn:
        listener = spawn(rospy_peer("rospy_typed_listener.py", "/tmux_words=std_msgs/String"), label="listener")
        listener.wait_for("subscribed")
        pane.type(rostui_line(env, EXIT_MARK, "publish", "/tmux_words", "std_msgs/String"))
        pane.wait_until(lambda: pane.shows("Fields · std_msgs/String", "nothing is published until ctrl+s"),
                        "the form")
        send_data(pane, "'hello from tmux'")
        pane.wait_until(lambda: pane.shows("published one std_msgs/String on /tmux_words"), "the message sent")
        pane.wait_until(lambda: [m.data for m in received(listener, "/tmux_words", "std_msgs/String")]
                        == ["hello from tmux"], "the String at rospy")
        pane.keys("q")
        pane.wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "the shell to report exit status 0 after q")


def test_call_in_tmux(pane: Pane, env: dict[str, str]) -> None:
    with peers(env) as spawn:
        server = spawn(rospy_peer("rospy_setbool_server.py", "/tmux_flag"), label="server")
        server.wait_for("ready")
        pane.type(rostui_line(env, EXIT_MARK, "call", "/tmux_flag"))
        pane.wait_until(lambda: pane.shows("/tmux_flag [std_srvs/SetBool]", "nothing is called until ctrl+s"),
                        "the request's form")
        send_data(pane, "True")
        pane.wait_until(lambda: pane.shows("success: True", 'message: "got true"'), "the response")
        server.wait_for("request data=True")
        pane.keys("q")
        pane.wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "the shell to report exit status 0 after q")
