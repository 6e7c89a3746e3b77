"""``rostui graph``: rqt_graph for the terminal.

``canvas`` is plain Python (characters on a grid); ``app`` and ``widget``
hold the Textual parts and are imported only when the app opens.
"""
