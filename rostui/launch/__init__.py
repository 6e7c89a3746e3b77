"""rostui launch: roslaunch XML files read into a launch model and run by a process supervisor.

``files`` turns command-line words into launch files and args, ``loader``
reads the XML (lxml) into a :class:`~rostui.launch.model.LaunchConfig`,
``inspect`` answers --nodes/--args/--dump-params/--files/--ros-args, and
``supervisor`` starts a master when none answers, sets the params and runs,
respawns and stops the nodes (``process``: one node's process tree and
state).  For ``rostui launch --tui`` the supervisor also captures each node's
output (``output``) and starts, stops and restarts single nodes; ``usage``
measures their CPU and memory.  Nothing here imports Textual.
"""
