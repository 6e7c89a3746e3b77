"""`rostui serve`: the terminal apps in a web browser, through textual-serve (the optional extra ``rostui[web]``).

Only `rostui serve` imports this package, after checking that the extra is there:

- :mod:`~rostui.apps.serve.access`: the token, and the Host and Origin a page may come from;
- :mod:`~rostui.apps.serve.messages`: what a page may send, terminal sizes clamped;
- :mod:`~rostui.apps.serve.page`: the page, with nothing from another site;
- :mod:`~rostui.apps.serve.processes`: app processes in groups of their own, ended for sure;
- :mod:`~rostui.apps.serve.server`: the web server that ties them together.
"""
