"""What decides a computed result, as fingerprints: input files and the model code.

A stored result (a point of a sweep file, :mod:`tefcore.sweeps.store`) may be
reused only while everything that decided it is unchanged.  The
configuration's field values are one part (:func:`tefcore.sweeps.store.config_hash`);
this module gives the others:

* :func:`input_files` / :func:`input_digests` -- the files a configuration
  refers to and that the computation reads (the C81 deck when
  ``model.aero_model = "c81"``), by the SHA-256 of their content: editing a
  deck in place changes its digest although its path does not change;
* :func:`numerical_environment` -- the versions of tefcore, numpy, scipy and
  the BLAS library with the kernels it runs: recorded beside a stored result,
  never a reason to refuse one (verdicts are decided with margins above the
  round-off these change; a resumed run says when they differ);
* :func:`model_stamp` -- a fingerprint of tefcore's numerical code: the
  SHA-256 of the source of every module of the package except those that
  only present or store results (:data:`PRESENTATION_MODULES`).  Any change
  to the numerical code, even to a comment, changes the stamp, so stored
  results are never reused across code changes (erring towards recomputing).
  A point function outside tefcore (``sweep(point=...)``) is not covered:
  only its name is recorded.

Examples
--------
>>> from tefcore.config.io import load_config
>>> input_digests(load_config("mdart"))   # thin-airfoil aerodynamics: no files read
{}
>>> len(model_stamp())
16
"""

from __future__ import annotations

import functools
import hashlib
from importlib import resources
from pathlib import Path

__all__ = [
    "PRESENTATION_MODULES",
    "describe_digest",
    "file_digest",
    "input_digests",
    "input_files",
    "model_stamp",
    "environment_note",
    "numerical_environment",
]

#: Modules of the solver that cannot change a computed point (command line,
#: errors, file handling, the boundary's reporting), as dotted names below
#: ``tefcore``; every other module of the solver counts.  The paper layer
#: (``tefcore.paper``: figures, claims, notebooks, reports) never does.
PRESENTATION_MODULES = frozenset({
    "__main__", "cli", "errors", "provenance", "safe_io", "sweeps.boundary",
})


def file_digest(path) -> str:
    """``"sha256:<hex>"`` of the content of `path`.

    Parameters
    ----------
    path : str or os.PathLike
        The file.

    Returns
    -------
    str

    Raises
    ------
    OSError
        If the file cannot be read.
    """
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return f"sha256:{h.hexdigest()}"


def input_files(cfg) -> dict[str, Path]:
    """Dotted field -> file that the computation for `cfg` reads.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The rotor configuration.

    Returns
    -------
    dict of str to pathlib.Path
        Empty when the computation reads no file (the thin-airfoil model).
    """
    if cfg.model.aero_model == "c81" and cfg.model.c81_deck:
        return {"model.c81_deck": Path(cfg.model.c81_deck)}
    return {}


def input_digests(cfg) -> dict[str, str]:
    """Dotted field -> :func:`file_digest` of each of :func:`input_files`.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The rotor configuration.

    Returns
    -------
    dict of str to str

    Raises
    ------
    ValueError
        If a file cannot be read (the message names the field and the path).
    """
    out = {}
    for dotted, path in input_files(cfg).items():
        try:
            out[dotted] = file_digest(path)
        except OSError as err:
            raise ValueError(f"{dotted} = {str(path)!r}: cannot read it "
                             f"({err.strerror or err})") from None
    return out


@functools.lru_cache(maxsize=1)
def model_stamp() -> str:
    """16 hex digits of SHA-256 over the numerical modules' source (module docstring)."""
    h = hashlib.sha256()
    for name, data in _solver_sources(resources.files("tefcore"), ""):
        dotted = name.removesuffix(".py").replace("/", ".").removesuffix(".__init__")
        if any(dotted == m or dotted.startswith(m + ".") for m in PRESENTATION_MODULES):
            continue                      # a presentation module, or one of its folder
        h.update(name.encode() + b"\0" + len(data).to_bytes(8, "little") + data)
    return h.hexdigest()[:16]


def _solver_sources(folder, prefix):
    """``(path below tefcore, bytes)`` of every solver module, sorted by path."""
    out = []
    for entry in folder.iterdir():
        name = prefix + entry.name
        if entry.is_dir() and entry.name != "paper" and entry.joinpath("__init__.py").is_file():
            out += _solver_sources(entry, name + "/")
        elif entry.name.endswith(".py"):
            out.append((name, entry.read_bytes()))
    return sorted(out)


def describe_digest(digest: str | None) -> str:
    """Short form of a digest for messages (``sha256 1a2b3c4d5e6f``).

    Parameters
    ----------
    digest : str or None
        ``"sha256:<hex>"`` (None: no file).

    Returns
    -------
    str
    """
    if not isinstance(digest, str):
        return repr(digest)
    algo, _, hexa = digest.partition(":")
    return f"{algo} {hexa[:12]}" if hexa else digest[:16]



def numerical_environment() -> dict[str, str]:
    """The numerical stack this process computes with: versions and BLAS kernels.

    Returns
    -------
    dict
        ``tefcore``, ``numpy``, ``scipy`` (versions) and ``blas`` (each BLAS
        library loaded: its implementation, version and the kernels it chose
        for this processor, e.g. ``"openblas 0.3.31 SkylakeX"``; the user's
        ``OPENBLAS_CORETYPE`` shows here when set).

    Examples
    --------
    >>> env = numerical_environment()
    >>> sorted(env), env["blas"] != ""
    (['blas', 'numpy', 'scipy', 'tefcore'], True)
    """
    import numpy
    import scipy
    import scipy.linalg  # noqa: F401  (loads scipy's BLAS, so that it is listed)
    from threadpoolctl import threadpool_info

    from ._version import __version__

    blas = sorted({" ".join(str(lib.get(k) or "") for k in ("internal_api", "version",
                                                            "architecture")).strip()
                   for lib in threadpool_info() if lib.get("user_api") == "blas"})
    return {"tefcore": __version__, "numpy": numpy.__version__, "scipy": scipy.__version__,
            "blas": "; ".join(blas) or "unknown"}


def environment_note(path, then, now) -> str | None:
    """What changed in the numerical stack since a stored result was computed, or None.

    Parameters
    ----------
    path : path-like
        The stored file (for the message).
    then, now : dict or None
        :func:`numerical_environment` recorded in its header, and this run's.

    Returns
    -------
    str or None
        One line naming each part that differs, then and now; None when the
        header recorded none (older files) or nothing differs.

    Examples
    --------
    >>> note = environment_note("s.jsonl", {"numpy": "2.3.0"}, {"numpy": "2.4.6"})
    >>> print(note)  # doctest: +NORMALIZE_WHITESPACE
    resuming s.jsonl: its points were computed with numpy 2.3.0 (now 2.4.6); the names and
    verdicts do not depend on it, values may differ in the last digits
    """
    if not isinstance(then, dict) or not then:
        return None
    changed = [f"{k} {then.get(k)} (now {now.get(k)})" for k in sorted(set(then) | set(now))
               if then.get(k) != now.get(k)]
    if not changed:
        return None
    return (f"resuming {path}: its points were computed with {', '.join(changed)}; "
            "the names and verdicts do not depend on it, values may differ in the last digits")
