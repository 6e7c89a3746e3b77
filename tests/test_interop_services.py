"""Services between rostui and rospy, under both `rostui core` and a real roscore.

Both directions, a handler that raises (its text must reach the caller), and
a call to a service nobody offers (one clear ServiceException).
"""

from __future__ import annotations

import asyncio

import pytest

from interop_helpers import example, rospy_peer, rostui_peer, run_tool, spawn  # noqa: F401
from rostui import client as ros
from rostui.core.node import AsyncNode

SetBool = ros.srv("std_srvs/SetBool")


def test_rospy_client_to_rostui_server(any_master, rospy_available, spawn):
    server = spawn(example("toggle_server.py"), label="rostui toggle_server")
    for value, expect in (("true", "got true"), ("false", "got false")):
        client = spawn(rospy_peer("rospy_setbool_client.py", "/toggle", value), label="rospy client")
        assert client.wait_exit() == 0, client.describe() + "\n" + server.describe()
        assert client.lines[-1] == f"success=True message={expect}", client.describe()
    server.wait_for(r"toggle: now off$")


def test_rostui_client_to_rospy_server(any_master, rospy_available, spawn):
    server = spawn(rospy_peer("rospy_setbool_server.py", "/toggle"), label="rospy server")
    server.wait_for(r"^ready$")
    for value, expect in (("true", "got true"), ("false", "got false")):
        client = spawn(example("toggle_client.py", value), label="rostui toggle_client")
        assert client.wait_exit() == 0, client.describe() + "\n" + server.describe()
        assert client.lines[-1] == f"success=True message={expect}", client.describe()
    server.wait_for(r"^request data=False$")


def test_rostui_handler_error_reaches_rospy_client(any_master, rospy_available, spawn):
    server = spawn(rostui_peer("serve", "/toggle", "--fail", "the flux capacitor is offline"),
                   label="rostui failing server")
    server.wait_for(r"^ready$")
    client = spawn(rospy_peer("rospy_setbool_client.py", "/toggle", "true"), label="rospy client")
    assert client.wait_exit() == 1, client.describe()
    assert client.lines[-1].startswith("ServiceException: "), client.describe()
    assert "the flux capacitor is offline" in client.lines[-1], client.describe()
    # the server survives a failing handler and keeps answering
    again = spawn(rospy_peer("rospy_setbool_client.py", "/toggle", "false"), label="rospy client 2")
    assert again.wait_exit() == 1, again.describe()
    assert server.count(r"^request data=") == 2, server.describe()


def test_rospy_handler_error_reaches_rostui_client(any_master, rospy_available, spawn):
    server = spawn(rospy_peer("rospy_setbool_server.py", "/toggle", "--fail", "the flux capacitor is offline"),
                   label="rospy failing server")
    server.wait_for(r"^ready$")
    client = spawn(rostui_peer("call", "/toggle", "true"), label="rostui client")
    assert client.wait_exit() == 1, client.describe()
    assert client.lines[-1].startswith("ServiceException: "), client.describe()
    assert "the flux capacitor is offline" in client.lines[-1], client.describe()


def test_rostui_client_to_rostui_server(any_master, spawn):
    server = spawn(rostui_peer("serve", "/toggle"), label="rostui server")
    server.wait_for(r"^ready$")
    client = spawn(rostui_peer("call", "/toggle", "false"), label="rostui client")
    assert client.wait_exit() == 0, client.describe()
    assert client.lines[-1] == "success=True message=got false", client.describe()


def test_calling_a_missing_service_from_a_script(any_master, spawn):
    client = spawn(rostui_peer("call", "/no_such_service", "true", "--no-wait"), label="rostui client")
    assert client.wait_exit() == 1, client.describe()
    errors = [line for line in client.lines if "ServiceException" in line]
    assert errors == [client.lines[-1]], client.describe()
    assert "/no_such_service" in errors[0], client.describe()
    assert "Traceback" not in client.output, client.describe()


def test_calling_a_missing_service_async(any_master, ros_env):
    """The async face raises one ServiceException that names the service."""

    async def scenario() -> str:
        node = AsyncNode("missing_service_caller")
        await node.start()
        try:
            with pytest.raises(ros.ServiceException) as info:
                await node.service_proxy("/no_such_service", SetBool).call(SetBool._request_class(data=True))
            return str(info.value)
        finally:
            await node.shutdown()

    text = asyncio.run(asyncio.wait_for(scenario(), 30))
    assert "/no_such_service" in text
    assert "\n" not in text


def test_rosservice_call_on_rospy_server_from_rostui_master(rostui_core, rospy_available, spawn, ros_env):
    """A rospy server registered with `rostui core` answers a real `rosservice call`."""
    server = spawn(rospy_peer("rospy_setbool_server.py", "/toggle"), label="rospy server")
    server.wait_for(r"^ready$")
    out = run_tool(["rosservice", "call", "/toggle", "data: false"], ros_env).stdout
    assert out.splitlines() == ["success: True", 'message: "got false"']
