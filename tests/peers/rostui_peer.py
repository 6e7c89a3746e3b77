"""rostui peer: a SetBool server or client written with rostui's sync client API.

Usage (project python):
    rostui_peer.py serve SERVICE [--fail TEXT] [ROS args]
        success=True, message "got true"/"got false"; with --fail the handler
        raises an exception carrying TEXT.  Prints "ready" once advertised.
    rostui_peer.py call SERVICE true|false [--no-wait] [ROS args]
        Prints "success=<True/False> message=<text>", or
        "ServiceException: <text>" and exits 1.
    rostui_peer.py latch TOPIC TEXT [ROS args]
        Publishes one latched std_msgs/String and spins.  Prints "ready".
    rostui_peer.py getparam NAME [ROS args]
        Prints "NAME = <the value as JSON, keys sorted>", or "KeyError: <name>" and exits 1.
    rostui_peer.py setparam NAME YAML [ROS args]
        Sets NAME to the YAML value, then prints "set NAME".
"""

import json
import sys

import yaml

from rostui import client as ros

SetBool = ros.srv("std_srvs/SetBool")


def serve(service: str, fail: str | None) -> int:
    def handle(req):
        print(f"request data={req.data}", flush=True)
        if fail is not None:
            raise RuntimeError(fail)
        return SetBool._response_class(success=True, message="got true" if req.data else "got false")

    ros.init_node("rostui_setbool_server", anonymous=True)
    ros.Service(service, SetBool, handle)
    print("ready", flush=True)
    ros.spin()
    return 0


def call(service: str, value: bool, wait: bool) -> int:
    ros.init_node("rostui_setbool_client", anonymous=True)
    if wait:
        ros.wait_for_service(service, timeout=20)
    proxy = ros.ServiceProxy(service, SetBool)
    try:
        resp = proxy(value)
    except ros.ServiceException as exc:
        print(f"ServiceException: {exc}", flush=True)
        return 1
    print(f"success={resp.success} message={resp.message}", flush=True)
    return 0


def latch(topic: str, text: str) -> int:
    ros.init_node("rostui_latcher", anonymous=True)
    pub = ros.Publisher(topic, ros.msg("std_msgs/String"), queue_size=1, latch=True)
    pub.publish(text)
    print("ready", flush=True)
    ros.spin()
    return 0


def getparam(name: str) -> int:
    ros.init_node("rostui_param_reader", anonymous=True)
    try:
        value = ros.get_param(name)
    except KeyError as exc:
        print(f"KeyError: {exc}", flush=True)
        return 1
    print(f"{name} = {json.dumps(value, sort_keys=True)}", flush=True)
    return 0


def setparam(name: str, text: str) -> int:
    ros.init_node("rostui_param_writer", anonymous=True)
    ros.set_param(name, yaml.safe_load(text))
    print(f"set {name}", flush=True)
    return 0


def main() -> int:
    args = ros.myargv()[1:]
    mode, target = args[0], args[1]
    if mode == "serve":
        return serve(target, args[args.index("--fail") + 1] if "--fail" in args else None)
    if mode == "call":
        return call(target, args[2].lower() == "true", "--no-wait" not in args)
    if mode == "latch":
        return latch(target, args[2])
    if mode == "getparam":
        return getparam(target)
    if mode == "setparam":
        return setparam(target, args[2])
    print(f"unknown mode {mode}", file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
