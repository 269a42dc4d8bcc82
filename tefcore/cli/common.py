"""What the ``tefcore`` subcommands share: the configuration a command's options name,
and the table a command writes with ``--csv``."""

from __future__ import annotations

from ..safe_io import atomic_output

__all__ = ["load", "write_csv"]


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
