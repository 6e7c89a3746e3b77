"""The rostui runtime: ROS 1 names, messages, XML-RPC, master, TCPROS and nodes.

Nothing under ``rostui.core`` imports Textual, Typer or Rich, nor any other part of rostui
(``tests/test_layers.py`` checks it).
"""
