"""What a script sees of rosgraph and rospkg: the master's API, rosgraph's name functions, rospkg's packages.

tests/test_rosgraph_rospkg.py runs it under Debian's rosgraph and rospkg and under rostui's, against the same
master and ROS_PACKAGE_PATH (its first entry holds probe_pkg and probe_base), and compares what it prints.
"""

import os
import socket
import sys

import rosgraph
import rosgraph.masterapi
import rosgraph.names as names
import rospkg

master = rosgraph.Master("probe")
print("caller", master.caller_id, rosgraph.is_master_online(), rosgraph.is_master_online("http://127.0.0.1:1/"))
master.setParam("/probe_ns", {"a": 1, "b": {"c": "x"}})
print("params", master.getParam("/probe_ns"), master.hasParam("/probe_ns/b/c"), master.hasParam("/nope"),
      master.searchParam("probe_ns"), "/probe_ns/a" in master.getParamNames())
print("delete", master.deleteParam("/probe_ns/a"), master.getParam("/probe_ns"))
for call, args in (("getParam", ("/nope",)), ("lookupService", ("/nope",)), ("lookupNode", ("/nope",))):
    try:
        getattr(master, call)(*args)
    except rosgraph.MasterError as exc:
        print(call, type(exc).__name__, isinstance(exc, rosgraph.masterapi.Error), exc)
print("uri", master.getUri() == os.environ["ROS_MASTER_URI"].rstrip("/") + "/" or master.getUri(),
      isinstance(master.getPid(), int), master.lookupNode("/rosout").startswith("http://"))
print("state", sorted(t for t, _ in master.getSystemState()[0]), sorted(t for t, _ in master.getTopicTypes()),
      master.getPublishedTopics("/"))
offline = rosgraph.Master("/probe", master_uri="http://127.0.0.1:1/")
print("offline", offline.is_online())
try:
    offline.getPid()
except socket.error as exc:
    print("offline raises", type(exc).__name__)
for uri in (None, "foo", "http://:12/", "http://host/"):
    try:
        rosgraph.Master("/probe", master_uri=uri) if uri else rosgraph.masterapi.Master("/p")._reinit(None)
        print("uri ok", uri)
    except ValueError as exc:
        print("uri", uri, "ValueError", exc)
print("myargv", rosgraph.myargv(["run", "a:=b", "_p:=1", "x"]))
print("master uri", rosgraph.get_master_uri(env={"ROS_MASTER_URI": "http://e:1"}, argv=["x"]),
      rosgraph.get_master_uri(env={}, argv=["x", "__master:=http://a:2"]), rosgraph.get_master_uri(env={}, argv=[]))

NAMES = ["", "/", "~", "a", "a/b", "/a", "/a/", "//a//b/", "~a", "~a/b", "a//b", "1a", "a-b", "_a", "/a/b/c",
         "~/a", "a b", "foo:=bar"]
for name in NAMES:
    row = [repr(name), names.is_global(name), names.is_private(name), names.is_legal_name(name),
           names.is_legal_base_name(name), names.is_legal_remap(name), names.canonicalize_name(name),
           names.namespace(name)]
    for ns in ("", "/", "~", "/ns", "/ns/", "ns"):
        row.append(names.ns_join(ns, name))
    for node in ("/node", "/ns/node", "/"):
        try:
            row.append(names.resolve_name(name, node, {"/ns/a": "/remapped"}))
        except Exception as exc:
            row.append(type(exc).__name__)
    try:
        row.append(names.make_global_ns(name))
    except ValueError as exc:
        row.append(str(exc))
    except IndexError as exc:
        row.append("IndexError")
    row.append(names.script_resolve_name("probe", name))
    print("name", *row)
print("ns", names.get_ros_namespace(env={"ROS_NAMESPACE": "robot"}, argv=[]),
      names.get_ros_namespace(env={}, argv=["__ns:=/other"]), names.get_ros_namespace(env={}, argv=[]),
      names.make_caller_id("node"))
print("mappings", sorted(names.load_mappings(["a:=b", "_p:=1", "__name:=n", "/x:=/y", "bad", "c:=", "~d:=e"]).items()))
print("anon", names.anonymous_name("probe").startswith("probe_"))

pack = rospkg.RosPack()
root = os.environ["ROS_PACKAGE_PATH"].split(os.pathsep)[0]
print("path", pack.get_path("probe_pkg") == os.path.join(root, "probe_pkg"), "probe_pkg" in pack.list())
manifest = pack.get_manifest("probe_pkg")
print("manifest", manifest.description, manifest.license, manifest.version, manifest.is_catkin,
      manifest.get_export("probe_pkg", "plugin"), manifest.get_export("probe_pkg", "plugin", convert=False),
      manifest.get_export("nothing", "x"))
old = pack.get_manifest("probe_old")
print("rosbuild", old.description, old.license, [d.name for d in old.depends], old.get_export("cpp", "cflags"))
try:
    pack.get_path("no_such_package")
except rospkg.ResourceNotFound as exc:
    print("missing", type(exc).__name__, str(exc).splitlines()[0], isinstance(exc, rospkg.common.ResourceNotFound))
print("name of", rospkg.get_package_name(os.path.join(root, "probe_pkg", "src")), rospkg.get_package_name("/"))
env = {"ROS_HOME": "/h"}
print("dirs", rospkg.get_ros_home(env), rospkg.get_log_dir(env), rospkg.get_log_dir({"ROS_LOG_DIR": "/l", **env}),
      rospkg.get_ros_home({"HOME": "/x"}) == os.path.join(os.path.expanduser("~"), ".ros"))
sys.stdout.flush()
