"""The exit status a command chose stands under ``python -m rostui`` too, after a Ctrl-C it handled.

CPython notes a KeyboardInterrupt that leaves text run by ``exec`` or ``eval``
of a string (``namedtuple``, ``dataclasses``, a ``bag filter`` expression that
calls ``exec``) even when the program then catches it; a ``python -m`` run
that ends with that note still set kills itself with SIGINT (status -2, 130 in
a shell), whatever status the program chose. A Ctrl-C landing in such text
made ``python -m rostui bag filter`` print its one line and still die by
SIGINT. Running any string clears the note, so an empty one at the end does.
"""


def forget_handled_interrupts() -> None:
    """Clear CPython's note of a KeyboardInterrupt raised in text run from a string (see the module's docstring).

    An interrupt still on its way out is noted again by the interpreter after this, so it still ends the
    process by SIGINT, as it should.
    """
    exec("pass")  # noqa: S102 - a constant: running a string is what clears the note
