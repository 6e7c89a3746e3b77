"""``rostui launch --tui``: a launch with a live table of its nodes and the output of one of them.

``rows`` turns the supervisor's processes into table text (no Textual);
``app`` holds the Textual parts and is imported only when the monitor opens.
"""
