"""How every command-line entry point ends: one clear line, never a traceback for our errors.

:func:`run_command` wraps the body of ``tefcore`` (:mod:`tefcore.cli`),
and ``python -m tefcore.paper.calibration``:

* tefcore's own errors (:data:`tefcore.errors.EXPECTED_ERRORS`: invalid
  input as ``ValueError``, :class:`~tefcore.errors.TefcoreError` such as a
  trim that does not converge, file-system ``OSError``) print
  ``<prog>: error: <message>`` on one line of stderr and exit with status 2;
* a closed output pipe (``tefcore modes | head -1``) ends quietly with
  status 141 (128 + SIGPIPE, what a shell reports for such a process);
* Ctrl-C prints ``<prog>: interrupted`` and exits with 130;
* anything else is a bug in tefcore and keeps its traceback.

Exit status 1 is left to the commands for "ran, but the result is not
clean" (failed sweep points, failing notebooks, claims worse than recorded).

Examples
--------
>>> def fail():
...     raise ValueError("flap.overhang = 1.2 is outside the allowed range [0, 1)")
>>> import sys, contextlib, io
>>> err = io.StringIO()
>>> with contextlib.redirect_stderr(err):
...     code = run_command(fail, prog="tefcore")
>>> code, err.getvalue()
(2, 'tefcore: error: flap.overhang = 1.2 is outside the allowed range [0, 1)\\n')
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable

from .errors import EXPECTED_ERRORS

__all__ = ["EXIT_BROKEN_PIPE", "EXIT_ERROR", "EXIT_INTERRUPTED", "error_line", "run_command"]

EXIT_ERROR = 2
EXIT_BROKEN_PIPE = 141
EXIT_INTERRUPTED = 130
#: Longest message printed (a longer one is cut, saying so).
MAX_MESSAGE = 600


def error_line(exc: BaseException, limit: int = MAX_MESSAGE) -> str:
    """One line describing `exc`: its message, whitespace collapsed, at most `limit` characters.

    An ``OSError`` with a file name reads ``<file>: <reason>``.

    Parameters
    ----------
    exc : BaseException
        The exception.
    limit : int, optional
        Longest line.

    Returns
    -------
    str

    Examples
    --------
    >>> error_line(FileNotFoundError(2, "No such file or directory", "cfg.toml"))
    'cfg.toml: No such file or directory'
    >>> error_line(ValueError("a\\n   b"))
    'a b'
    """
    if isinstance(exc, OSError) and exc.filename is not None and exc.strerror:
        text = f"{exc.filename}: {exc.strerror}"
    else:
        text = str(exc) or type(exc).__name__
    text = " ".join(text.split())
    if len(text) > limit:
        text = text[:limit] + f"... ({len(text) - limit} more characters)"
    return text


def _quiet_stdout() -> None:
    """Point stdout at /dev/null so that the interpreter's final flush cannot fail again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError, AttributeError):
        pass


def run_command(func: Callable[..., int], *args, prog: str = "tefcore") -> int:
    """Run a command body and turn its ending into an exit status (module docstring).

    Parameters
    ----------
    func : callable
        The command body; returns the exit status.
    *args
        Its arguments.
    prog : str, optional
        The program name for messages.

    Returns
    -------
    int
        ``func``'s status, or 2 (an expected error), 130 (interrupted), 141
        (output pipe closed).
    """
    try:
        code = func(*args)
        sys.stdout.flush()
        return code
    except BrokenPipeError:
        _quiet_stdout()
        return EXIT_BROKEN_PIPE
    except KeyboardInterrupt:
        print(f"{prog}: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except EXPECTED_ERRORS as exc:
        print(f"{prog}: error: {error_line(exc)}", file=sys.stderr)
        return EXIT_ERROR
