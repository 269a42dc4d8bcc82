"""tefcore's named errors: what the library raises on purpose.

Every error tefcore raises on purpose is one of

* ``ValueError`` -- invalid input: a configuration field (the message names
  the dotted field, its value and the allowed range), a unit, a sweep
  argument.  The named subclasses are :class:`tefcore.aero.c81.C81FormatError`
  (a malformed C81 deck, with file, line and column),
  :class:`tefcore.aero.c81.C81RangeError` (inputs outside a C81 table),
  :class:`tefcore.paper.reference_files.ReferenceDataError` (the paper's reference
  data) and :class:`SweepFileError` (a sweep file that cannot be resumed);
* :class:`TefcoreError` subclasses that are not input errors:
  :class:`tefcore.trimming.trim.TrimError` (the trim did not converge),
  :class:`tefcore.floquet.FloquetAccuracyError` (the Floquet exponents
  could not be computed to the requested accuracy; its subclass
  ``FloquetOverflowError`` is also a ``ValueError``) and
  :class:`OutputError` (an output destination is unusable or locked);
* ``OSError`` from the file system (a missing configuration file, a full
  disk), with the file name.

The command line (:mod:`tefcore.cli_errors`) turns each of these into one
line on stderr and exit status 2; anything else is a bug and keeps its
traceback.  The fuzz tests (``tests/*/test_fuzz_*.py``, ``tests/test_fuzz_units.py``)
check that parsers and validators raise nothing else.

Examples
--------
>>> issubclass(SweepFileError, ValueError), issubclass(OutputError, OSError)
(True, True)
"""

from __future__ import annotations

__all__ = ["EXPECTED_ERRORS", "OutputError", "SweepFileError", "TefcoreError", "error_text"]

#: Longest error message stored with a failed result (a longer one is cut, saying so).
MAX_ERROR_TEXT = 500


class TefcoreError(Exception):
    """Base of tefcore's own named errors (mixed with a built-in type)."""


class SweepFileError(TefcoreError, ValueError):
    """A sweep file that is damaged, of another format, or stale for this sweep."""


class OutputError(TefcoreError, OSError):
    """An output destination that cannot be written safely (checked before computing)."""


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
