"""A form for one message or service request: its fields as rows of expressions, evaluated into a message.

:mod:`.expression` evaluates what a row says (numbers, ``sin(t)``, ``i``, ``now``) without running Python;
:mod:`.rows` lays a type out as rows and builds a message from them; :mod:`.form_file` saves and loads a form.
"""
