"""The ROS computation graph as data: the master's registrations, rqt_graph's views and filters,
a layered left-to-right layout, live change marks and Graphviz DOT output.

Used by ``rostui graph`` (the Textual app draws what these modules compute)
and by ``rostui graph --dot``, which never loads Textual.
"""
