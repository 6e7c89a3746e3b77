"""Topics between rostui and rospy nodes, under both `rostui core` and a real roscore.

Every test starts real processes: the rostui examples (talker.py,
listener.py) and the rospy peers in tests/peers, and checks what a user
sees on their consoles.
"""

from __future__ import annotations

from interop_helpers import example, rospy_peer, run_tool, spawn, wait_for_node  # noqa: F401

COUNT = 5


def test_rostui_talker_to_rospy_listener(any_master, rospy_available, spawn, ros_env):
    listener = spawn(rospy_peer("rospy_listener.py", "/chatter", str(COUNT)), label="rospy listener")
    listener.wait_for(r"^subscribed$")
    talker = spawn(example("talker.py", "--count", str(COUNT)), label="rostui talker")
    assert listener.wait_exit() == 0, listener.describe()
    heard = [line for line in listener.lines if line.startswith("data: ")]
    assert heard == [f"data: hello world {n}" for n in range(COUNT)], listener.describe()
    assert talker.wait_exit() == 0, talker.describe()
    assert talker.count(r"^\[ INFO\] \[\d+\.\d+\]: hello world \d+$") == COUNT, talker.describe()


def test_rospy_talker_to_rostui_listener(any_master, rospy_available, spawn, ros_env):
    listener = spawn(example("listener.py", "__name:=ears"), label="rostui listener")
    wait_for_node(ros_env, "/ears")
    talker = spawn(rospy_peer("rospy_talker.py", "/chatter", str(COUNT), "20"), label="rospy talker")
    for n in range(COUNT):
        listener.wait_for(rf"^\[ INFO\] \[\d+\.\d+\]: I heard: hello {n}$")
    assert talker.wait_exit() == 0, talker.describe()
    assert listener.count(r"I heard: ") == COUNT, listener.describe()


def test_rostui_talker_to_rostui_listener(any_master, spawn, ros_env):
    listener = spawn(example("listener.py", "__name:=ears"), label="rostui listener")
    wait_for_node(ros_env, "/ears")
    talker = spawn(example("talker.py", "--count", str(COUNT)), label="rostui talker")
    assert talker.wait_exit() == 0, talker.describe()
    for n in range(COUNT):
        listener.wait_for(rf"I heard: hello world {n}$")


def test_remapping_on_the_command_line(any_master, rospy_available, spawn, ros_env):
    """`chatter:=other` moves both rostui examples to /other; a rospy node there hears it.

    The talker waits for both listeners: publishing once the faster one had
    connected cost the rospy listener its first message (a CI failure).
    """
    listener = spawn(rospy_peer("rospy_listener.py", "/other", str(COUNT)), label="rospy listener")
    listener.wait_for(r"^subscribed$")
    rostui_ears = spawn(example("listener.py", "chatter:=other", "__name:=ears"), label="rostui listener")
    wait_for_node(ros_env, "/ears")
    talker = spawn(example("talker.py", "--count", str(COUNT), "--subscribers", "2", "chatter:=other"),
                   label="rostui talker")
    assert listener.wait_exit() == 0, listener.describe()
    assert [l for l in listener.lines if l.startswith("data: ")] == [
        f"data: hello world {n}" for n in range(COUNT)], listener.describe()
    assert talker.wait_exit() == 0, talker.describe()
    rostui_ears.wait_for(rf"I heard: hello world {COUNT - 1}$")
    topics = run_tool(["rostopic", "list"], ros_env).stdout.split()
    assert "/other" in topics
    assert "/chatter" not in topics

