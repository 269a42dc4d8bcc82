"""Output files written safely: checked first, written atomically, never through a link.

Every file tefcore writes (sweep files, CSV tables, reports, figures,
configurations, C81 decks) goes through this module:

* :func:`check_output_file` -- checked *before* any computing: the
  destination is not a symbolic link, a folder or a device, and its folder
  exists and is writable.  Problems raise
  :class:`~tefcore.errors.OutputError` naming the path.
* :func:`atomic_output` / :func:`atomic_write_text` -- the content goes to
  a temporary file created exclusively (``O_CREAT | O_EXCL | O_NOFOLLOW``,
  :func:`tempfile.mkstemp`) in the destination's own folder, is
  ``fsync``-ed, and replaces the destination with :func:`os.replace` (one
  atomic rename, which replaces a link rather than following it); the
  folder is ``fsync``-ed after.  Readers see the old file or the new one,
  never a part; a crash leaves at most a stray ``.<name>.*.tmp`` file.
  The temporary name is unique, so simultaneous writers never collide.
* :class:`FileLock` -- an advisory lock (``fcntl.flock``) on
  ``<path>.lock`` for files that are appended to over a long run (sweep
  files): a second writer fails at once with an
  :class:`~tefcore.errors.OutputError` naming the process that holds the
  lock (it does not wait).  The lock file is left in place (removing it
  would let two writers lock two different files); it is empty apart from
  the holder's process id.  ``flock`` locks are not reliable on some network
  file systems, and do nothing where ``fcntl`` is missing (Windows).
* :func:`open_append` -- appending without following a link.
* :func:`check_outputs` -- a command's outputs checked together before it
  computes: each as above, none the same file (after links are resolved, or
  a hard link) as an input, a store the command appends to, or another
  output; none an existing store (a file with a :class:`FileLock` lock file
  beside it); and a binary output replaces only a file of its own kind
  (:data:`FILE_SIGNATURES`), never, say, a text file named ``a.gif``.

Examples
--------
>>> import tempfile, pathlib
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> atomic_write_text(folder / "a.txt", "hello\\n").read_text()
'hello\\n'
>>> (folder / "link.txt").symlink_to(folder / "a.txt")
>>> atomic_write_text(folder / "link.txt", "x")  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
tefcore.errors.OutputError: output file .../link.txt is a symbolic link; ...
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import IO

from .errors import OutputError

try:  # POSIX only
    import fcntl
except ImportError:  # pragma: no cover - Windows
    fcntl = None

__all__ = [
    "FILE_SIGNATURES",
    "FileLock",
    "atomic_output",
    "atomic_write_bytes",
    "atomic_write_text",
    "check_output_file",
    "check_output_folder",
    "check_outputs",
    "check_replaceable",
    "open_append",
    "same_file",
    "write_error",
]

#: How a binary output of each kind starts: ``(offset, bytes)`` alternatives.  An
#: existing file that starts otherwise is not a previous output of that kind
#: (:func:`check_replaceable`); kinds not listed (CSV, JSON, text) are not checked.
FILE_SIGNATURES: dict[str, tuple[tuple[int, bytes], ...]] = {
    "png": ((0, b"\x89PNG\r\n\x1a\n"),),
    "gif": ((0, b"GIF87a"), (0, b"GIF89a")),
    "mp4": ((4, b"ftyp"),),
    "pdf": ((0, b"%PDF-"),),
    "svg": ((0, b"<?xml"), (0, b"<svg")),
    "jpg": ((0, b"\xff\xd8\xff"),),
    "jpeg": ((0, b"\xff\xd8\xff"),),
    "tif": ((0, b"II*\x00"), (0, b"MM\x00*")),
    "tiff": ((0, b"II*\x00"), (0, b"MM\x00*")),
    "webp": ((8, b"WEBP"),),
    "eps": ((0, b"%!PS"), (0, b"\xc5\xd0\xd3\xc6")),
    "ps": ((0, b"%!PS"),),
    # netCDF3 (classic, 64-bit offsets) and netCDF4 (HDF5)
    "netcdf": ((0, b"CDF\x01"), (0, b"CDF\x02"), (0, b"\x89HDF\r\n\x1a\n")),
}


def check_output_folder(folder, what: str = "output folder", *, create: bool = False) -> Path:
    """Check that `folder` is (or, with `create`, can be made) a writable folder.

    Parameters
    ----------
    folder : str or os.PathLike
        The folder.
    what : str, optional
        What it is, for messages (e.g. ``"--out"``).
    create : bool, optional
        Create it (with its parents) when missing.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    OutputError
        Naming the folder and the problem.
    """
    folder = Path(folder)
    if create and not folder.exists() and not folder.is_symlink():
        try:
            folder.mkdir(parents=True, exist_ok=True)
        except OSError as err:
            raise OutputError(f"{what} {folder}: cannot create it ({err.strerror})") from None
    if not folder.exists():
        raise OutputError(f"{what} {folder} does not exist")
    if not folder.is_dir():
        raise OutputError(f"{what} {folder} is not a folder")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise OutputError(f"{what} {folder} is not writable")
    return folder


def check_output_file(path, what: str = "output file", *, create_folder: bool = False) -> Path:
    """Check an output destination before computing anything for it.

    Parameters
    ----------
    path : path-like
        The file to be written.
    what : str
        How to name it in messages (e.g. ``"--csv"``).
    create_folder : bool
        Create the missing parent folders instead of refusing.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    OutputError
        The path is a symbolic link, a folder or not a regular file, or its
        folder is missing or not writable.
    """
    path = Path(path)
    if path.is_symlink():
        raise OutputError(f"{what} {path} is a symbolic link; tefcore does not write through "
                          "or replace links (remove it, or choose another path)")
    if path.exists():
        mode = path.stat().st_mode
        if stat.S_ISDIR(mode):
            raise OutputError(f"{what} {path} is a folder, not a file")
        if not stat.S_ISREG(mode):
            raise OutputError(f"{what} {path} exists and is not a regular file")
    folder = path.parent
    try:
        check_output_folder(folder, "folder", create=create_folder)
    except OutputError as err:
        raise OutputError(f"{what} {path}: {err}") from None
    return path


def _identity(path) -> tuple:
    """What makes two paths one file: the resolved path, and the inode where it exists."""
    try:
        st = os.stat(path)
        inode = (st.st_dev, st.st_ino)
    except OSError:                  # not there (yet): its resolved path alone
        inode = None
    return Path(os.path.abspath(path)).resolve(), inode


def _same(a: tuple, b: tuple) -> bool:
    return a[0] == b[0] or (a[1] is not None and a[1] == b[1])


def same_file(a, b) -> bool:
    """Whether two paths name the same file: after links and ``..`` are resolved, or as
    the same inode (a hard link, another spelling on a case-insensitive disk).

    Parameters
    ----------
    a, b : path-like
        The paths; neither need exist.

    Returns
    -------
    bool

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> same_file(folder / "a.csv", folder / "sub" / ".." / "a.csv")
    True
    >>> (folder / "link").symlink_to(folder)
    >>> same_file(folder / "a.csv", folder / "link" / "a.csv")
    True
    >>> same_file(folder / "a.csv", folder / "b.csv")
    False
    """
    return _same(_identity(a), _identity(b))


def check_replaceable(path, what: str, kind: str | None) -> None:
    """Refuse to replace an existing file that is not a previous output of `kind`.

    Parameters
    ----------
    path : path-like
        The output file.
    what : str
        How to name it in messages (``"--gif"``).
    kind : str or None
        A key of :data:`FILE_SIGNATURES` (``"gif"``); another kind, or None, is
        not checked.

    Raises
    ------
    OutputError
        The file exists, is not empty, and does not start as a `kind` file does.
    """
    signatures = FILE_SIGNATURES.get((kind or "").lower())
    path = Path(path)
    if not signatures or path.is_symlink() or not path.is_file():
        return
    try:
        with open(path, "rb") as f:
            head = f.read(16)
    except OSError as err:
        raise OutputError(f"{what} {path}: cannot read it to check what it is "
                          f"({err.strerror})") from None
    if head and not any(head[o:o + len(b)] == b for o, b in signatures):
        name = kind.upper() if kind != "netcdf" else "netCDF"
        raise OutputError(f"{what} {path} exists and is not a {name} file; tefcore replaces "
                          f"only a previous {name} output (remove it, or choose another path)")


def _entries(items):
    """``(Path, what, kind)`` of ``(path, what)`` or ``(path, what, kind)``, None paths left out."""
    for item in items:
        if item[0] is not None:
            yield Path(item[0]), item[1], (item[2] if len(item) > 2 else None)


def check_outputs(outputs, *, inputs=(), stores=()) -> list[Path]:
    """Check a command's output files together, before it computes anything.

    Each output is checked by :func:`check_output_file` and, when its kind is
    given, :func:`check_replaceable`; then no output may be the same file
    (:func:`same_file`) as an input, a store or another output, nor an
    existing store of another run (a file whose :class:`FileLock` lock file is
    beside it): writing it would destroy what is there while the command
    reads or appends to it.

    Parameters
    ----------
    outputs : iterable of tuple
        ``(path, what)`` or ``(path, what, kind)`` (kind: a key of
        :data:`FILE_SIGNATURES`); a None path is no output.
    inputs : iterable of tuple, optional
        ``(path, what)`` of the files the command reads (its configuration,
        the C81 decks the configuration names).
    stores : iterable of tuple, optional
        ``(path, what)`` of the files it appends to and resumes (sweep files),
        checked by the command itself; their lock files count as stores too.

    Returns
    -------
    list of pathlib.Path
        The outputs.

    Raises
    ------
    OutputError
        Naming the output and what it would destroy.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> check_outputs([(folder / "s.csv", "--csv"), (folder / "s.json", "--json")])
    ... # doctest: +ELLIPSIS
    [PosixPath('.../s.csv'), PosixPath('.../s.json')]
    >>> check_outputs([(folder / "s.csv", "--csv")], stores=[(folder / "s.csv", "--out")])
    ... # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    tefcore.errors.OutputError: --csv .../s.csv is the same file as --out .../s.csv, ...
    """
    outs = list(_entries(outputs))
    stores = list(_entries(stores))
    stores += [(p.with_name(p.name + ".lock"), f"the lock file of {w} {p}", None)
               for p, w, _ in stores]
    others = [(p, w, "an input") for p, w, _ in _entries(inputs)] + \
             [(p, w, "a file it appends to") for p, w, _ in stores]
    known = [_identity(p) for p, _, _ in others]
    n_inputs = len(others) - len(stores)
    for (store, store_what, _), key in zip(others[n_inputs:], known[n_inputs:], strict=True):
        for (other, other_what, _), in_key in zip(others[:n_inputs], known, strict=False):
            if _same(key, in_key):
                raise OutputError(f"{store_what} {store} is the same file as {other_what} "
                                  f"{other}, an input: appending to it would spoil that file "
                                  "(choose another path)")
    seen = []
    for i, (path, what, _) in enumerate(outs):
        this = _identity(path)
        for (other, other_what, role), key in zip(others, known, strict=True):
            if _same(this, key):
                raise OutputError(f"{what} {path} is the same file as {other_what} {other}, "
                                  f"{role}: writing it would destroy that file "
                                  "(choose another path)")
        for (other, other_what, _), key in zip(outs[:i], seen, strict=True):
            if _same(this, key):
                raise OutputError(f"{what} {path} and {other_what} {other} are the same file: "
                                  "one output would replace the other (choose different paths)")
        seen.append(this)
    for path, what, kind in outs:
        check_output_file(path, what)
        lock = path.with_name(path.name + ".lock")
        if path.is_file() and lock.exists():
            raise OutputError(f"{what} {path} is a file tefcore appends to and resumes (its lock "
                              f"file {lock} is beside it): writing over it would lose its "
                              "records (choose another path)")
        check_replaceable(path, what, kind)
    return [p for p, _, _ in outs]


def write_error(err: OSError, what: str, path, doing: str) -> OutputError:
    """An :class:`~tefcore.errors.OutputError` naming the file and what failed.

    For the OS errors of writing that carry no file name (a full disk,
    ``[Errno 28] No space left on device``, a quota, a file size limit).

    Parameters
    ----------
    err : OSError
        The error.
    what : str
        What the file is (e.g. ``"--csv"``, ``"sweep file"``).
    path : path-like
        The file.
    doing : str
        What was being done (``"cannot write it"``).

    Returns
    -------
    OutputError

    Examples
    --------
    >>> import errno
    >>> print(write_error(OSError(errno.ENOSPC, "No space left on device"), "--csv", "t.csv",
    ...                   "cannot write it"))
    --csv t.csv: cannot write it (No space left on device); the file as it was before is unchanged
    """
    reason = err.strerror or str(err) or type(err).__name__
    kept = ("the records written before are kept" if "append" in doing
            else "the file as it was before is unchanged")
    return OutputError(f"{what} {path}: {doing} ({reason}); {kept}")


def _file_mode(path: Path) -> int:
    """Permissions for the new file: those of the file replaced, else 0o666 & ~umask."""
    try:
        return stat.S_IMODE(os.lstat(path).st_mode)
    except OSError:
        mask = os.umask(0o022)
        os.umask(mask)
        return 0o666 & ~mask


def _fsync_folder(folder: Path) -> None:
    try:
        fd = os.open(folder, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:  # some file systems cannot sync a folder
        pass
    finally:
        os.close(fd)


@contextlib.contextmanager
def atomic_output(path, mode: str = "w", *, encoding: str | None = "utf-8",
                  newline: str | None = None, what: str = "output file") -> Iterator[IO]:
    """Context manager: a file object whose content replaces `path` atomically on success.

    On an exception inside the block the temporary file is removed and
    `path` is untouched.

    Parameters
    ----------
    path : str or os.PathLike
        The destination.
    mode : {"w", "wb"}, optional
        Text or binary.
    encoding : str or None, optional
        Text encoding (text mode).
    newline : str or None, optional
        As for :func:`open` (``""`` for CSV).
    what : str, optional
        What the file is, for messages (e.g. ``"--csv"``).

    Yields
    ------
    file object
        Write to it inside the ``with`` block.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "t.csv"
    >>> with atomic_output(p, newline="") as f:
    ...     _ = f.write("a,b\\n1,2\\n")
    >>> p.read_text()
    'a,b\\n1,2\\n'
    """
    path = check_output_file(path, what)
    binary = "b" in mode
    try:
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    except OSError as err:
        raise write_error(err, what, path, "cannot create a temporary file beside it") \
            from None
    try:
        with os.fdopen(fd, mode, encoding=None if binary else encoding,
                       newline=None if binary else newline) as f:
            yield f
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, _file_mode(path))
        os.replace(tmp, path)
    except BaseException as err:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        if isinstance(err, OSError) and not isinstance(err, OutputError) \
                and err.filename is None:
            # a full disk (ENOSPC), a quota, a file size limit: errors without a path
            raise write_error(err, what, path, "cannot write it") from None
        raise
    _fsync_folder(path.parent)


def atomic_write_bytes(path, data: bytes, *, what: str = "output file") -> Path:
    """Write `data` to `path` atomically (see :func:`atomic_output`); return the path.

    Parameters
    ----------
    path : str or os.PathLike
        The destination.
    data : bytes
        The content.
    what : str, optional
        What the file is, for messages (e.g. ``"--csv"``).

    Returns
    -------
    pathlib.Path
    """
    with atomic_output(path, "wb", what=what) as f:
        f.write(data)
    return Path(path)


def atomic_write_text(path, text: str, *, encoding: str = "utf-8",
                      what: str = "output file") -> Path:
    """Write `text` to `path` atomically (see :func:`atomic_output`); return the path.

    Parameters
    ----------
    path : str or os.PathLike
        The destination.
    text : str
        The content.
    encoding : str, optional
        Text encoding.
    what : str, optional
        What the file is, for messages (e.g. ``"--csv"``).

    Returns
    -------
    pathlib.Path
    """
    return atomic_write_bytes(path, text.encode(encoding), what=what)


def open_append(path, what: str = "output file") -> int:
    """File descriptor for appending to an existing `path`, refusing a symbolic link.

    Parameters
    ----------
    path : str or os.PathLike
        An existing file.
    what : str, optional
        What the file is, for messages (e.g. ``"--csv"``).

    Returns
    -------
    int
        A file descriptor opened for appending (close it with :func:`os.close`).

    Raises
    ------
    OutputError
        For a symbolic link or a file that cannot be opened.
    """
    flags = os.O_WRONLY | os.O_APPEND | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        return os.open(path, flags)
    except OSError as err:
        if err.errno == errno.ELOOP:
            raise OutputError(f"{what} {path} is a symbolic link; tefcore does not write "
                              "through links") from None
        raise


class FileLock:
    """Exclusive advisory lock held on ``<path>.lock`` while a file is being written.

    Parameters
    ----------
    path : path-like
        The file being protected (the lock file is beside it).
    what : str
        How to name `path` in messages.

    Raises
    ------
    OutputError
        From :meth:`acquire` (and ``with``): another process holds the lock,
        or the lock file is a link or cannot be created.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "s.jsonl"
    >>> with FileLock(p):
    ...     FileLock(p).acquire()  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    tefcore.errors.OutputError: .../s.jsonl is being written by another process (...
    """

    def __init__(self, path, what: str = ""):
        self.path = Path(path)
        self.lock_path = self.path.with_name(self.path.name + ".lock")
        self.what = f"{what} " if what else ""
        self.fd: int | None = None

    def acquire(self) -> FileLock:
        """Take the lock, or raise :class:`~tefcore.errors.OutputError` at once."""
        if fcntl is None:  # pragma: no cover - no advisory locks here
            return self
        flags = (os.O_RDWR | os.O_CREAT | getattr(os, "O_NOFOLLOW", 0)
                 | getattr(os, "O_CLOEXEC", 0))
        try:
            fd = os.open(self.lock_path, flags, 0o666)
        except OSError as err:
            why = "it is a symbolic link" if err.errno == errno.ELOOP else err.strerror
            raise OutputError(f"cannot use the lock file {self.lock_path} of {self.what}"
                              f"{self.path}: {why}") from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as err:
            holder = ""
            with contextlib.suppress(OSError, ValueError):
                pid = int(os.pread(fd, 32, 0).split()[0])
                holder = f", process {pid}"
            os.close(fd)
            if err.errno in (errno.EWOULDBLOCK, errno.EAGAIN, errno.EACCES):
                raise OutputError(f"{self.what}{self.path} is being written by another process "
                                  f"(lock {self.lock_path}{holder}); wait until it has "
                                  "finished, or write to another file") from None
            raise OutputError(f"cannot lock {self.lock_path}: {err.strerror}") from None
        with contextlib.suppress(OSError):
            os.ftruncate(fd, 0)
            os.pwrite(fd, f"{os.getpid()}\n".encode(), 0)
        self.fd = fd
        return self

    def release(self) -> None:
        """Release the lock (the lock file stays)."""
        if self.fd is not None:
            os.close(self.fd)
            self.fd = None

    def __enter__(self) -> FileLock:
        return self.acquire()

    def __exit__(self, *exc) -> None:
        self.release()
