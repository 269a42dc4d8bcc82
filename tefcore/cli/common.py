"""What the ``tefcore`` subcommands share: the configuration a command's options name."""

from __future__ import annotations

__all__ = ["load"]


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
