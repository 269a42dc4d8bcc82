"""tefcore's named errors: what the library raises on purpose.

Every error tefcore raises on purpose is one of

* ``ValueError`` -- invalid input: a configuration field (the message names
  the dotted field, its value and the allowed range), a unit, a sweep
  argument.  The named subclasses are :class:`tefcore.aero.c81.C81FormatError`
  (a malformed C81 deck, with file, line and column),
  :class:`tefcore.aero.c81.C81RangeError` (inputs outside a C81 table),
  :class:`tefcore.paper.claims.files.ReferenceDataError` (the paper's reference
  data) and :class:`SweepFileError` (a sweep file that cannot be resumed);
* :class:`TefcoreError` subclasses that are not input errors:
  :class:`tefcore.trimming.trim.TrimError` (the trim did not converge),
  :class:`tefcore.floquet.FloquetAccuracyError` (the Floquet exponents
  could not be computed to the requested accuracy; its subclass
  ``FloquetOverflowError`` is also a ``ValueError``) and
  :class:`OutputError` (an output destination is unusable or locked);
* :class:`UsageError` (a ``ValueError``) -- the command line's arguments do not
  parse (a missing or extra argument), with the subcommand and its help;
* ``OSError`` from the file system (a missing configuration file, a full
  disk), with the file name.

The command line (:func:`run_command`, below) turns each of these into one
line on stderr and exit status 2; anything else is a bug and keeps its
traceback.  The fuzz tests (``tests/*/test_fuzz_*.py``, ``tests/test_fuzz_units.py``)
check that parsers and validators raise nothing else.

How every command-line entry point ends
---------------------------------------
``run_command`` wraps the body of ``tefcore`` (:mod:`tefcore.cli`),
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
>>> issubclass(SweepFileError, ValueError), issubclass(OutputError, OSError)
(True, True)
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

__all__ = ["EXIT_BROKEN_PIPE", "EXIT_ERROR", "EXIT_INTERRUPTED", "EXPECTED_ERRORS",
           "OutputError", "SweepFileError", "TefcoreError", "UsageError", "error_line",
           "error_text", "run_command"]

#: Longest error message stored with a failed result (a longer one is cut, saying so).
MAX_ERROR_TEXT = 500


class TefcoreError(Exception):
    """Base of tefcore's own named errors (mixed with a built-in type)."""


class SweepFileError(TefcoreError, ValueError):
    """A sweep file that is damaged, of another format, or stale for this sweep."""


class OutputError(TefcoreError, OSError):
    """An output destination that cannot be written safely (checked before computing)."""


class UsageError(TefcoreError, ValueError):
    """Command-line arguments that do not parse: missing, extra or malformed."""


#: The exception types a caller of tefcore's parsers and validators should expect.
EXPECTED_ERRORS = (TefcoreError, ValueError, OSError)


def error_text(err: BaseException, limit: int = MAX_ERROR_TEXT) -> str:
    """``"<Type>: <message>"`` on one line, at most `limit` characters of message.

    For failed results stored in tables and files: whitespace (line breaks
    of an array printout, say) is collapsed and an overlong message is cut.

    Parameters
    ----------
    err : BaseException
        The exception.
    limit : int, optional
        Longest message kept.

    Returns
    -------
    str

    Examples
    --------
    >>> error_text(ValueError("x = 2\\n is outside [0, 1]"))
    'ValueError: x = 2 is outside [0, 1]'
    >>> error_text(ValueError("a" * 600), limit=10)
    'ValueError: aaaaaaaaaa... (590 more characters)'
    """
    text = " ".join(str(err).split())
    if len(text) > limit:
        text = text[:limit] + f"... ({len(text) - limit} more characters)"
    return f"{type(err).__name__}: {text}" if text else type(err).__name__

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
