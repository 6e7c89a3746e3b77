"""dynamic_reconfigure from outside a server: configurations and their messages (:mod:`.encoding`), typed
values (:mod:`.values`), and live servers found, followed and changed (:mod:`.live`). ``rostui dynparam``,
the reconfigure app and the ``dynamic_reconfigure`` module scripts import share them."""
