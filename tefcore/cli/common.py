"""What the ``tefcore`` subcommands share: the configuration a command's options name, the
files it reads, the table it writes with ``--csv``, and the checks of numbers typed."""

from __future__ import annotations

import argparse
import math
import os

from ..safe_io import atomic_output

__all__ = ["config_file", "inputs", "jobs", "load", "load_for_csv", "number", "write_csv"]


def load(args):
    """The configuration of a command: ``--config`` with its ``-s NAME=VALUE`` overrides.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options: ``config`` (a TOML file or packaged name) and
        ``set`` (``NAME=VALUE`` strings or None).

    Returns
    -------
    tefcore.config.configuration.Config
    """
    from ..config.io import load_config
    from ..config.text_input import parse_overrides

    cfg = load_config(args.config)
    if args.set:
        cfg = cfg.with_overrides(parse_overrides(args.set))
    return cfg


def write_csv(table, path, what: str = "--csv", **kwargs) -> None:
    """Write a table atomically (the destination was checked before computing).

    Parameters
    ----------
    table : pandas.DataFrame
        The table (written without its index).
    path : path-like
        The destination.
    what : str, optional
        The option that named it, for messages.
    **kwargs
        Further options of :meth:`pandas.DataFrame.to_csv` (``float_format``).
    """
    with atomic_output(path, newline="", what=what) as f:
        table.to_csv(f, index=False, **kwargs)


def config_file(config: str) -> str | None:
    """The file ``--config`` names, or None for a packaged configuration (``mdart``).

    :func:`tefcore.config.io.load_config` reads a name ending in ``.toml`` or
    with a folder in it as a file, anything else as a packaged name.

    Parameters
    ----------
    config : str
        The ``--config`` value.

    Returns
    -------
    str or None

    Examples
    --------
    >>> config_file("mdart"), config_file("rotor.toml"), config_file("runs/rotor")
    (None, 'rotor.toml', 'runs/rotor')
    """
    return config if config.endswith(".toml") or os.sep in config or "/" in config else None


def load_for_csv(args):
    """:func:`load`, then refuse a ``--csv`` that is one of the files it reads.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options (``config``, ``set``, ``csv``).

    Returns
    -------
    tefcore.config.configuration.Config
    """
    from ..safe_io import check_outputs

    cfg = load(args)
    check_outputs([(args.csv, "--csv")], inputs=inputs(args, cfg))
    return cfg


def inputs(args, cfg) -> list[tuple[str, str]]:
    """The files a command reads: its ``--config`` file and those the configuration names.

    For :func:`tefcore.safe_io.check_outputs` (no output may be one of them).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options (``config``).
    cfg : tefcore.config.configuration.Config
        The configuration they loaded.

    Returns
    -------
    list of tuple
        ``(path, what)``.
    """
    from ..provenance import input_files

    out = [(config_file(args.config), "--config")]
    out += [(str(path), field) for field, path in input_files(cfg).items()]
    return [(p, w) for p, w in out if p is not None]


def number(option: str, low: float | None = None, high: float | None = None, *,
           low_open: bool = False, integer: bool = False, unit: str = ""):
    """An argparse ``type``: a finite number in a range, else one line naming the option.

    Parameters
    ----------
    option : str
        The option (argparse names it in the message).
    low, high : float, optional
        The range's ends (None: unbounded on that side).
    low_open : bool, optional
        Exclude `low` (``(0, 100]``).
    integer : bool, optional
        A whole number.
    unit : str, optional
        Said after the range (``"revolutions"``).

    Returns
    -------
    callable
        ``text -> float`` (or int), raising :class:`argparse.ArgumentTypeError`.

    Examples
    --------
    >>> revs = number("--revs", 0, 100, low_open=True)
    >>> revs("6")
    6.0
    >>> revs("inf")
    Traceback (most recent call last):
    ...
    argparse.ArgumentTypeError: must be a number in (0, 100], got 'inf'

    The command prints it as ``tefcore: error: simulate: argument --revs: must
    be a number in (0, 100], got 'inf' (see 'tefcore simulate --help')``.
    """
    lo = "(-inf" if low is None else f"{'(' if low_open else '['}{low:g}"
    hi = "inf)" if high is None else f"{high:g}]"
    wanted = f"{'a whole number' if integer else 'a number'} in {lo}, {hi}" + \
        (f" {unit}" if unit else "")

    def parse(text: str):
        try:
            value = int(text) if integer else float(text)
        except ValueError:
            value = math.nan
        if not math.isfinite(value) or (low is not None and (value < low or (
                low_open and value == low))) or (high is not None and value > high):
            raise argparse.ArgumentTypeError(f"must be {wanted}, got {text!r}")
        return value

    parse.__name__ = option.lstrip("-")
    return parse


def jobs(text: str) -> int:
    """The argparse ``type`` of ``--jobs``: a whole number of processes other than 0.

    Negative asks for all the cores (as joblib reads it); any count is capped
    by the cores and the work when the command starts
    (:func:`tefcore.runtime.process_cap`).

    Parameters
    ----------
    text : str
        The value typed.

    Returns
    -------
    int

    Examples
    --------
    >>> jobs("4"), jobs("-1")
    (4, -1)
    >>> jobs("0")
    Traceback (most recent call last):
    ...
    argparse.ArgumentTypeError: must be a whole number of processes other than 0 (negative: \
all the cores), got '0'
    """
    try:
        n = int(text)
    except ValueError:
        n = 0
    if n == 0:
        raise argparse.ArgumentTypeError("must be a whole number of processes other than 0 "
                                         f"(negative: all the cores), got {text!r}")
    return n
