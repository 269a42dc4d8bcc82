"""The sweep file of :func:`tefcore.sweeps.sweep.sweep` (``out=path``): format and store.

Also the two identities written to it: :func:`config_hash` of the base
configuration and the key of each swept value.

Format
------
UTF-8 JSON lines, one object per line, each line written by a single
``os.write`` on a file opened with ``O_APPEND`` and then ``fsync``-ed:

* line 1, the header::

    {"format": "tefcore.sweep", "version": 3, "parameter": "flap.cg_offset",
     "config_hash": "<16 hex>", "inputs": {"model.c81_deck": "sha256:<hex>"},
     "tefcore_version": "0.1.0", "model_stamp": "<16 hex>",
     "point": "tefcore.linear.stability:stability", "created": "<ISO time>"}

  It records everything that decides a point's result (:func:`sweep_header`):
  ``config_hash`` is :func:`config_hash` of the base configuration (after
  ``extra_overrides``) without the swept field; ``inputs`` the content
  digests of the files the configuration refers to
  (:func:`tefcore.provenance.input_digests`: the C81 deck, when used);
  ``tefcore_version`` and ``model_stamp`` (:func:`tefcore.provenance.model_stamp`,
  a fingerprint of the numerical code) the code.  Resuming when any of
  these differs raises :class:`~tefcore.errors.SweepFileError` (a
  ``ValueError``) naming what changed: the stored points would be stale.
  Another point function only warns (its name is recorded for
  information).  Files of version 1 (without ``inputs`` and
  ``model_stamp``) cannot be checked and are refused.
* one line per finished point::

    {"key": "0.25", "value": 0.25, "value_si": 0.25, "status": "ok",
     "error": null, "trim": {"collective_deg": 6.1, ...},
     "modes": {"mode_id": [0, 1], "label": ["blade flap 1", "TEF"],
               "frequency_per_rev": [...], "real_part": [...],
               "damping_ratio": [...]},
     "elapsed_s": 1.23}

  A point whose C81 table inputs were clipped also has ``"warning"`` (one
  line: the evaluations clipped and the extreme inputs) and ``"clipped"``
  (the same as data, :mod:`tefcore.aero.c81.range_summary`).

  ``key`` identifies the value: ``repr(float(v))`` for numbers, the
  whitespace-normalised string for ``"value unit"`` strings.  ``value`` is
  the value as given, ``value_si`` the validated field value in SI (null
  when the configuration rejected it).  Failed points have
  ``"status": "failed"``, ``"error": "<ExceptionType>: <message>"`` and
  ``"modes": null``.  Non-finite floats are written as ``NaN``/``Infinity``
  (Python's JSON dialect).  Eigenvectors are not stored.

On resume the file is read back; when a key occurs several times (a retried
failed point) the last record wins, and records for values not requested
are ignored (and kept).  A last line cut short by a crash is dropped and
the file truncated to its last complete line; any other line that is not a
record (not JSON, or without the fields above) raises
:class:`~tefcore.errors.SweepFileError` naming the line.

Writing (:mod:`tefcore.safe_io`): a new file is created atomically (its
header in a temporary file in the same folder, then ``os.replace``); a
sweep file that is a symbolic link is refused, and points are appended
without following links.  While a sweep writes the file it holds an
advisory lock on ``<file>.lock``: a second sweep of the same file fails at
once with :class:`~tefcore.errors.OutputError` (it does not wait).
"""

from __future__ import annotations

import hashlib
import json
import numbers
import os
import warnings
from collections.abc import Iterable, Mapping

import numpy as np

from ..config.configuration import SECTIONS, Config
from ..errors import SweepFileError
from ..provenance import (
    describe_digest,
    environment_note,
    input_digests,
    model_stamp,
    numerical_environment,
)
from ..safe_io import FileLock, atomic_write_text, check_output_file, open_append, write_error

__all__ = ["FORMAT", "FORMAT_VERSION", "RECORD_MODE_COLUMNS", "JsonLinesStore", "SweepFile",
           "check_provenance", "config_hash", "jsonable", "sweep_header", "value_key"]

FORMAT = "tefcore.sweep"
FORMAT_VERSION = 3
#: Columns every stored ``modes`` table has (the point function's required columns).
RECORD_MODE_COLUMNS = ("mode_id", "label", "frequency_per_rev", "real_part", "damping_ratio")


# ------------------------------------------------------------------ identities


def jsonable(v):
    """A plain JSON-able Python value: numpy scalars and arrays converted, recursively.

    Parameters
    ----------
    v : object
        A value, mapping, list or tuple possibly holding numpy values.

    Returns
    -------
    object
        The same value with numpy arrays as lists, numpy scalars as Python
        scalars and mapping keys as strings.

    Examples
    --------
    >>> jsonable({"a": np.arange(2), 1: np.float64(0.5)})
    {'a': [0, 1], '1': 0.5}
    """
    if isinstance(v, np.ndarray):
        return v.tolist()
    if isinstance(v, np.generic):
        return v.item()
    if isinstance(v, Mapping):
        return {str(k): jsonable(x) for k, x in v.items()}
    if isinstance(v, list | tuple):
        return [jsonable(x) for x in v]
    return v


def value_key(v) -> str:
    """Canonical key of a sweep value (see the file format above).

    Parameters
    ----------
    v : float or str
        A number (keyed by ``repr(float(v))``) or a ``'value unit'`` string
        (keyed with its whitespace normalised).

    Returns
    -------
    str

    Raises
    ------
    ValueError
        For booleans, empty strings and anything else.

    Examples
    --------
    >>> value_key(2), value_key("  400  lb/in ")
    ('2.0', '400 lb/in')
    """
    if isinstance(v, bool | np.bool_):
        raise ValueError(f"sweep values must be numbers or 'value unit' strings, got {v!r}")
    if isinstance(v, numbers.Real):
        return repr(float(v))
    if isinstance(v, str):
        key = " ".join(v.split())
        if key:
            return key
    raise ValueError(f"sweep values must be numbers or 'value unit' strings, got {v!r}")


def config_hash(cfg: Config, exclude: Iterable[str] = ()) -> str:
    """Hash (16 hex digits) of the field values of `cfg`, without `exclude`.

    Only the physical fields count (not ``name``, ``description``,
    ``sources`` or ``reference``), so two configurations with equal fields
    hash alike.  Floats enter by their exact ``repr``.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The configuration.
    exclude : iterable of str, optional
        Dotted fields left out (the swept parameter).

    Returns
    -------
    str

    Examples
    --------
    >>> from tefcore.config.io import load_config
    >>> cfg = load_config("mdart")
    >>> config_hash(cfg) == config_hash(cfg.with_overrides({"name": "other"}))
    True
    >>> other = cfg.with_overrides({"flap.cg_offset": 0.1})
    >>> config_hash(cfg) == config_hash(other)
    False
    >>> config_hash(cfg, ["flap.cg_offset"]) == config_hash(other, ["flap.cg_offset"])
    True
    """
    skip = set(exclude)
    data = {
        f"{s}.{p.name}": jsonable(getattr(getattr(cfg, s), p.name))
        for s, cls in SECTIONS.items()
        for p in cls.PARAMS
        if f"{s}.{p.name}" not in skip
    }
    text = json.dumps(data, sort_keys=True, allow_nan=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


# ------------------------------------------------------------------ the file


def sweep_header(cfg: Config, parameter: str, chash: str, point_name: str) -> dict:
    """Header of a new sweep file: what decides every point (module docstring).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The rotor configuration.
    parameter : str
        The swept dotted field.
    chash : str
        :func:`config_hash` of ``cfg`` without ``parameter``.
    point_name : str
        ``module:qualname`` of the point function.

    Returns
    -------
    dict
        The first line of the file: format and version, parameter,
        configuration hash, input file digests, tefcore version, model stamp
        and point function, with the creation time.

    Raises
    ------
    ValueError
        If a file the configuration refers to cannot be read.

    Examples
    --------
    >>> from tefcore.config.io import load_config
    >>> cfg = load_config("mdart")
    >>> head = sweep_header(cfg, "flap.cg_offset", config_hash(cfg), "m:f")
    >>> head["version"] == FORMAT_VERSION, head["inputs"], len(head["model_stamp"])
    (True, {}, 16)
    """
    import datetime

    from .._version import __version__

    return {"format": FORMAT, "version": FORMAT_VERSION, "parameter": parameter,
            "config_hash": chash, "inputs": input_digests(cfg),
            "tefcore_version": __version__, "model_stamp": model_stamp(),
            "environment": numerical_environment(), "point": point_name,
            "created": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")}


_RESTART = ("use another out path, or resume=False to overwrite it (command line: delete "
            "the file or choose another --out)")


def check_provenance(path, head: dict, header: dict, restart: str) -> None:
    """Refuse a stored file whose input files or code differ from this run's.

    Parameters
    ----------
    path : path-like
        The file (for messages).
    head : dict
        Its header.
    header : dict
        This run's header (``inputs``, ``tefcore_version``, ``model_stamp``).
    restart : str
        What the user can do, appended to the message.

    Raises
    ------
    SweepFileError
        Naming the input file, the tefcore version or the model code that
        changed, with its value then and now.
    """
    then, now = head.get("inputs"), header["inputs"]
    if not isinstance(then, dict):
        raise SweepFileError(f"{path}: the header's 'inputs' is not a table; the file is "
                             "damaged")
    for dotted in sorted(set(then) | set(now)):
        if then.get(dotted) != now.get(dotted):
            raise SweepFileError(
                f"cannot resume {path}: the file {dotted} has changed since its points were "
                f"computed ({describe_digest(then.get(dotted))} then, "
                f"{describe_digest(now.get(dotted))} now), so they would be stale; {restart}")
    for what, name in (("tefcore_version", "tefcore version"),
                       ("model_stamp", "model code (model_stamp)")):
        if head.get(what) != header[what]:
            raise SweepFileError(
                f"cannot resume {path}: its points were computed by another {name} "
                f"({head.get(what)!r} then, {header[what]!r} now) and may be stale; "
                f"{restart}")
    # the numerical stack (numpy, scipy, BLAS kernels) is recorded, never refused:
    # no name or verdict depends on its round-off
    note = environment_note(path, head.get("environment"), header.get("environment", {}))
    if note:
        warnings.warn(note, UserWarning, stacklevel=4)


def _check_header(path, head, header: dict) -> None:
    """Refuse to resume `path` (header `head`) for a sweep with `header`."""
    if not isinstance(head, dict) or head.get("format") != FORMAT:
        raise SweepFileError(f"{path} is not a tefcore sweep file (line 1 is not its "
                             "header); use another out path")
    if head.get("version") == 1:
        raise SweepFileError(f"cannot resume {path}: it was written by an older tefcore "
                             "(sweep file version 1) that did not record the input files and "
                             f"the model code, so its points cannot be checked; {_RESTART}")
    if head.get("version") != FORMAT_VERSION:
        raise SweepFileError(f"{path}: unsupported sweep file version {head.get('version')!r} "
                             f"(this tefcore reads version {FORMAT_VERSION})")
    for what in ("parameter", "config_hash"):
        if head.get(what) != header[what]:
            raise SweepFileError(
                f"cannot resume {path}: it holds a sweep of {head.get('parameter')!r} "
                f"on configuration {head.get('config_hash')}, not of "
                f"{header['parameter']!r} on configuration {header['config_hash']} "
                f"({what} differs); {_RESTART}")
    check_provenance(path, head, header, _RESTART)
    if head.get("point") != header["point"]:
        warnings.warn(f"resuming {path}, written by point function {head.get('point')}, "
                      f"with {header['point']}", UserWarning, stacklevel=5)


def _is_real(x) -> bool:
    return isinstance(x, numbers.Real) and not isinstance(x, bool)


def _record_problem(rec) -> str | None:
    """Why `rec` (a decoded line) is not a point record, or None.

    Its fields (:func:`_fields_problem`), then, for a point with status
    ``ok``, its modes table (:func:`_modes_problem`) and its tracking fields
    (:func:`_tracking_problem`); a failed point has no modes.
    """
    problem = _fields_problem(rec)
    if problem is not None:
        return problem
    modes = rec["modes"]
    if rec["status"] == "failed":
        return None if modes is None else "a failed point must have 'modes': null"
    problem = _modes_problem(modes)
    if problem is not None:
        return problem
    return _tracking_problem(rec, len(modes["mode_id"]))


def _fields_problem(rec) -> str | None:
    """Why the fields of `rec` (all but the modes table) are malformed, or None."""
    if not isinstance(rec, dict):
        return f"a JSON {type(rec).__name__}, not a record"
    missing = [k for k in ("key", "status", "value_si", "error", "trim", "modes")
               if k not in rec]
    if missing:
        return f"a record without {', '.join(map(repr, missing))}"
    if not isinstance(rec["key"], str) or not rec["key"]:
        return f"'key' must be a non-empty string, got {rec['key']!r:.40}"
    if rec["status"] not in ("ok", "failed"):
        return f"'status' must be 'ok' or 'failed', got {rec['status']!r:.40}"
    if rec["error"] is not None and not isinstance(rec["error"], str):
        return "'error' must be a string or null"
    if not (rec["value_si"] is None or _is_real(rec["value_si"])
            or isinstance(rec["value_si"], str)):
        return "'value_si' must be a number, a string or null"
    if not isinstance(rec["trim"], dict):
        return "'trim' must be a table"
    if not isinstance(rec.get("warning", ""), str):
        return "'warning' must be a string"
    if not isinstance(rec.get("clipped", {}), dict):
        return "'clipped' must be a table"
    return None


def _modes_problem(modes) -> str | None:
    """Why the modes table of an ok point is malformed, or None: a table of the
    :data:`RECORD_MODE_COLUMNS`, non-empty lists of one length, numbers and labels."""
    if not isinstance(modes, dict):
        return "'modes' of a point with status 'ok' must be a table of columns"
    lacking = [c for c in RECORD_MODE_COLUMNS if c not in modes]
    if lacking:
        return f"'modes' lacks the column(s) {', '.join(map(repr, lacking))}"
    lengths = {len(v) if isinstance(v, list) else -1 for v in modes.values()}
    if len(lengths) != 1 or lengths == {-1} or lengths == {0}:
        return "the 'modes' columns must be non-empty lists of one length"
    for col in ("frequency_per_rev", "real_part", "damping_ratio", "mode_id"):
        if not all(_is_real(x) for x in modes[col]):
            return f"'modes'.{col!r} must hold numbers"
    if not all(isinstance(x, str) for x in modes["label"]):
        return "'modes'.'label' must hold strings"
    return None


def _tracking_problem(rec, n_modes: int) -> str | None:
    """Why the tracking fields of an ok record are malformed, or None."""
    vec = rec.get("vectors")
    if vec is not None:
        if not (isinstance(vec, dict) and set(vec) == {"re", "im"}):
            return "'vectors' must be a table with 're' and 'im'"
        for part in ("re", "im"):
            rows = vec[part]
            if not (isinstance(rows, list) and rows and all(
                    isinstance(r, list) and len(r) == n_modes and all(_is_real(x) for x in r)
                    for r in rows)):
                return f"'vectors'.{part!r} must be rows of {n_modes} numbers (one per mode)"
        if len(vec["re"]) != len(vec["im"]):
            return "'vectors' 're' and 'im' differ in size"
    if not isinstance(rec.get("periodic", False), bool):
        return "'periodic' must be true or false"
    depth = rec.get("refinement", 0)
    if isinstance(depth, bool) or not isinstance(depth, int) or depth < 0:
        return "'refinement' must be a count >= 0"
    return None


def _decode(line: bytes):
    """One JSON line, or raise ``ValueError`` (any decoding failure)."""
    try:
        return json.loads(line.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError, RecursionError) as err:
        raise ValueError(str(err)) from None


class JsonLinesStore:
    """Append-only JSON-lines file: a header line, then one record per line.

    The store of sweep points (:class:`SweepFile`) and of a map's boundary
    crossings (:class:`tefcore.sweeps.map_store.BoundaryFile`).  Opening takes
    the file's lock (:class:`tefcore.safe_io.FileLock`) until :meth:`close`;
    with ``resume`` an existing file is checked against ``header`` (a stale
    file is refused) and its records loaded into :attr:`records` (key ->
    record, the last of a key wins), an incomplete last line (an interrupted
    write) dropped with a warning and the file truncated to its last complete
    line; any other bad line is a :class:`~tefcore.errors.SweepFileError`
    naming the file and the line.  Subclasses say what the file is
    (:attr:`what`), how its header is checked (:meth:`check_header`) and what
    a record is (:meth:`record_problem`).

    Parameters
    ----------
    path : str or os.PathLike
        The JSON-lines file (its folder is created).
    header : dict
        First line of the file.
    resume : bool
        Keep and load an existing file; otherwise start it anew.
    """

    #: What the file is, for messages.
    what = "JSON-lines file"

    def __init__(self, path, header: dict, resume: bool):
        self.path = check_output_file(path, self.what, create_folder=True)
        self.records: dict[str, dict] = {}
        self.lock = FileLock(self.path, self.what).acquire()
        try:
            if resume and self.path.exists() and self.path.stat().st_size > 0:
                self._load(header)
            else:
                atomic_write_text(self.path, json.dumps(header) + "\n", what=self.what)
            self.fd = open_append(self.path, self.what)
        except BaseException:
            self.lock.release()
            raise

    def check_header(self, head, header: dict) -> None:
        """Raise :class:`~tefcore.errors.SweepFileError` if `head` does not match `header`.

        Parameters
        ----------
        head : object
            The decoded first line of the file (None when it is not JSON).
        header : dict
            This run's header.
        """
        raise NotImplementedError

    def record_problem(self, rec) -> str | None:
        """Why `rec` (a decoded line) is not a record of this file, or None.

        Parameters
        ----------
        rec : object
            A decoded line.

        Returns
        -------
        str or None
        """
        raise NotImplementedError

    def _load(self, header: dict) -> None:
        raw = self.path.read_bytes()
        lines = raw.split(b"\n")
        try:
            head = _decode(lines[0])
        except ValueError:
            head = None
        self.check_header(head, header)
        good = len(lines[0]) + 1
        body = lines[1:]
        for n, line in enumerate(body, start=2):
            last = n == len(lines)
            if last and not line:
                break
            try:
                if last:  # no newline after it: cut short by a crash
                    raise ValueError("unterminated line")
                rec = _decode(line)
            except ValueError:
                if not last:
                    raise SweepFileError(f"{self.path}, line {n}: not a JSON record; the file "
                                         "is damaged (remove the line or the file)") from None
                warnings.warn(f"{self.path}: dropping an incomplete last line (interrupted "
                              "write)", UserWarning, stacklevel=4)
                os.truncate(self.path, good)
                break
            if (problem := self.record_problem(rec)) is not None:
                raise SweepFileError(f"{self.path}, line {n}: {problem}; the file is damaged "
                                     "(remove the line or the file)")
            self.records[rec["key"]] = rec
            good += len(line) + 1

    def append(self, rec: dict) -> None:
        """Append one record as a JSON line and flush it to disk (``fsync``).

        Parameters
        ----------
        rec : dict
            One point's record (JSON-able: :func:`jsonable`).
        """
        data = (json.dumps(rec, separators=(",", ":"), allow_nan=True) + "\n").encode()
        view = memoryview(data)
        try:
            while view:
                view = view[os.write(self.fd, view):]
            os.fsync(self.fd)
        except OSError as err:   # a full disk: name the file (a cut-short line is dropped
            # when the file is resumed)
            raise write_error(err, self.what, self.path, "cannot append a record") from None

    def close(self) -> None:
        """Close the file and release its lock."""
        os.close(self.fd)
        self.lock.release()


class SweepFile(JsonLinesStore):
    """Append-only JSON-lines store of finished sweep points (format above).

    Opening takes the file's lock until :meth:`close`; with ``resume`` an
    existing file is checked against ``header`` (a stale file is refused)
    and its records loaded into :attr:`records`, an incomplete last line (an
    interrupted write) dropped (:class:`JsonLinesStore`).

    Parameters
    ----------
    path : str or os.PathLike
        The JSON-lines file (its folder is created).
    header : dict
        First line of the file (:func:`sweep_header`).
    resume : bool
        Keep and load an existing file; otherwise start it anew.
    """

    what = "sweep file"

    def check_header(self, head, header: dict) -> None:
        """Refuse a file of another format, version, parameter, configuration or code.

        Parameters
        ----------
        head : object
            The decoded first line of the file.
        header : dict
            This sweep's header (:func:`sweep_header`).
        """
        _check_header(self.path, head, header)

    def record_problem(self, rec) -> str | None:
        """Why `rec` is not a point record (module docstring), or None.

        Parameters
        ----------
        rec : object
            A decoded line.

        Returns
        -------
        str or None
        """
        return _record_problem(rec)
