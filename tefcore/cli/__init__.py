"""The ``tefcore`` command.

Subcommands, each with its arguments in its own module: ``modes`` and
``fanplot`` (:mod:`tefcore.cli.blade`), ``stability``
(:mod:`tefcore.cli.stability`), ``sweep`` (:mod:`tefcore.cli.sweep`), ``map``
(:mod:`tefcore.cli.maps`), ``mechanism`` (:mod:`tefcore.cli.mechanism`),
``simulate`` and ``explore`` (:mod:`tefcore.cli.watch`), ``c81 check|example``
(:mod:`tefcore.cli.c81`), and from the paper layer
(:mod:`tefcore.paper.run.commands`) ``reproduce`` (executes the notebooks and
writes the claims report), ``batch`` and ``notebooks`` (lists them, copies them
for editing); ``tefcore --help`` lists them and ``tefcore SUBCOMMAND --help``
describes one.  Each command module has ``add_arguments(sub, add)``, which
adds its subcommands with :func:`add_command` (``add``: the house style and
the shared options), each set to run its function (``func(args) -> exit
status``); this module keeps the entry point, the shared options and the
dispatch.

Values given with ``--set`` (and ``sweep --values/--range``) follow the
units rules of :mod:`tefcore.config.text_input`: a dimensional field needs its
unit.  Output files are checked before anything is computed and written
atomically (:mod:`tefcore.safe_io`).  The command applies the process
settings of :func:`tefcore.runtime.apply_defaults` before it runs.  Exit
status: 0 success; 1 the command ran but its result is not clean (failed
sweep points, bad C81 decks, failing notebooks or claims); 2 an error,
printed as one line (:func:`tefcore.errors.run_command`); 130 interrupted; 141
output pipe closed.
"""

from __future__ import annotations

import argparse
import sys
import textwrap
import warnings

from .._version import __version__
from ..errors import run_command
from . import blade, c81, maps, mechanism, stability, sweep, watch

__all__ = ["COMMAND_MODULES", "OPENBLAS_X86_64_KERNELS", "add_command", "build_parser",
           "coretype_warning", "entry_point", "main"]

#: ``tefcore --help``: what the command is, and where the details are.
DESCRIPTION = """\
Floquet aeroelastic stability of helicopter rotor blades with trailing-edge
flaps: blade modes, trim and stability, sweeps and stability maps, the
mechanism of an instability, C81 airfoil decks, and the reproduction of the
paper's figures and claims."""

EPILOG = """\
examples:
  tefcore stability
  tefcore stability --set flap.cg_offset=0.2 --csv modes.csv
  tefcore sweep flap.overhang --range 0 0.4 9 --jobs 2
  tefcore c81 check my_deck.c81
  tefcore SUBCOMMAND --help

values given with --set need their unit when the field has one
('hub.pitch_link_stiffness=800 lb/in'); output files are checked before
anything is computed and written atomically.

exit status: 0 success; 1 ran, but the result is not clean (failed sweep
points, bad C81 decks, failing notebooks or claims); 2 an error (one line);
130 interrupted; 141 output pipe closed."""


#: The modules of the subcommands, in the order ``tefcore --help`` lists them
#: (the paper layer's follow, :func:`tefcore.paper.run.commands.add_commands`).
COMMAND_MODULES = (blade, stability, sweep, maps, mechanism, watch, c81)


def _common(p):
    """The options every computing subcommand shares: the configuration and its overrides."""
    p.add_argument("--config", default="mdart",
                   help="configuration TOML file or packaged name (default: mdart)")
    p.add_argument("-s", "--set", action="append", metavar="NAME=VALUE",
                   help="override a field by dotted name, "
                        "e.g. hub.pitch_link_stiffness='800 lb/in'")


class _Parser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line (:class:`~tefcore.errors.UsageError`).

    argparse prints the whole usage and exits; the command prints one line
    (``tefcore: error: map: the following arguments are required: Y_NUM (see
    'tefcore map --help')``) with status 2 (:func:`tefcore.errors.run_command`).
    Subcommands' parsers are of the same class (argparse's ``parser_class``).
    """

    def error(self, message: str):
        from ..errors import UsageError

        command = self.prog.removeprefix("tefcore").strip()
        where = f"{command}: " if command else ""
        raise UsageError(f"{where}{message} (see '{self.prog} --help')")


class _HelpFormatter(argparse.RawDescriptionHelpFormatter):
    """Descriptions and epilogs as written; each subcommand's help on its own line."""

    def __init__(self, prog: str) -> None:
        super().__init__(prog, max_help_position=32)

    def add_argument(self, action: argparse.Action) -> None:
        super().add_argument(action)
        if action.nargs == argparse.PARSER and action.help is not argparse.SUPPRESS:
            # argparse measures the subcommand names without the 4 columns of
            # indentation they are printed with, and wraps the longer ones
            for name in action.choices:
                self._action_max_length = max(self._action_max_length,
                                              len(name) + self._current_indent + 4)

    def _fill_text(self, text: str, width: int, indent: str) -> str:
        # paragraphs (blank-line separated) are filled; lines indented by two
        # spaces or more (examples) are kept as written
        out = []
        for para in text.split("\n\n"):
            if all(line.startswith("  ") or not line.strip() for line in para.splitlines()) \
                    or para.startswith(("examples:", "example:")):
                out.append("\n".join(indent + line for line in para.splitlines()))
            else:
                out.append(textwrap.fill(" ".join(para.split()), width, initial_indent=indent,
                                         subsequent_indent=indent))
        return "\n\n".join(out)


def _add(sub, name: str, help: str, description: str, func, *, common: bool = True,
         epilog: str | None = None):
    """One subcommand: a one-line ``help`` for ``tefcore --help``, a description."""
    p = sub.add_parser(name, help=help, description=description, epilog=epilog,
                       formatter_class=_HelpFormatter)
    if common:
        _common(p)
    p.set_defaults(func=func)
    return p


def add_command(sub, name: str, help: str, description: str, func, *, common: bool = True,
                epilog: str | None = None) -> argparse.ArgumentParser:
    """One subcommand in the house style: its line in ``tefcore --help``, its description.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subcommands it joins.
    name : str
        The subcommand.
    help : str
        Its one line in ``tefcore --help``.
    description : str
        Its ``--help`` text.
    func : callable or None
        What runs it (``func(args) -> exit status``); None for a group of subcommands.
    common : bool, optional
        Add the shared options (``--config``, ``--set``).
    epilog : str, optional
        Examples after the options.

    Returns
    -------
    argparse.ArgumentParser
        The subcommand's parser, for its own arguments.
    """
    p = sub.add_parser(name, help=help, description=description, epilog=epilog,
                       formatter_class=_HelpFormatter)
    if common:
        _common(p)
    p.set_defaults(func=func)
    return p


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``tefcore`` command.

    Returns
    -------
    argparse.ArgumentParser
        With one subparser per subcommand; each sets ``func``, the function
        that runs it (``func(args) -> exit status``).
    """
    parser = _Parser(prog="tefcore", description=DESCRIPTION, epilog=EPILOG,
                     formatter_class=_HelpFormatter)
    parser.add_argument("--version", action="version", version=f"tefcore {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="SUBCOMMAND",
                                title="subcommands")
    for module in COMMAND_MODULES:
        module.add_arguments(sub, add_command)
    from ..paper.run.commands import add_commands  # reproduce, batch, notebooks: the paper layer

    add_commands(sub, formatter_class=_HelpFormatter)
    return parser


#: The kernels OpenBLAS can be told to load on x86-64 (``OPENBLAS_CORETYPE``; the
#: ``corename`` list of its ``driver/others/dynamic.c``), read without case as it reads them.
OPENBLAS_X86_64_KERNELS = (
    "Katmai", "Coppermine", "Northwood", "Prescott", "Banias", "Atom", "Core2", "Penryn",
    "Dunnington", "Nehalem", "Athlon", "Opteron", "Opteron_SSE3", "Barcelona", "Nano",
    "Sandybridge", "Bobcat", "Bulldozer", "Piledriver", "Haswell", "Steamroller", "Excavator",
    "Zen", "SkylakeX", "Cooperlake", "SapphireRapids")


def coretype_warning(environ=None, machine: str | None = None) -> str | None:
    """The line to print when ``OPENBLAS_CORETYPE`` names no kernel OpenBLAS knows.

    OpenBLAS then says nothing (unless ``OPENBLAS_VERBOSE=2``) and picks its
    kernels by the processor, as if the variable were not set.  Checked on
    x86-64 only, where the names are known (:data:`OPENBLAS_X86_64_KERNELS`).

    Parameters
    ----------
    environ : mapping, optional
        The environment (default: ``os.environ``).
    machine : str, optional
        The processor family (default: ``platform.machine()``).

    Returns
    -------
    str or None

    Examples
    --------
    >>> coretype_warning({"OPENBLAS_CORETYPE": "haswell"}, "x86_64") is None
    True
    >>> print(coretype_warning({"OPENBLAS_CORETYPE": "Haswel"}, "x86_64"))
    ... # doctest: +NORMALIZE_WHITESPACE
    tefcore: warning: OPENBLAS_CORETYPE = 'Haswel' is not a kernel OpenBLAS knows (did you
    mean Haswell?); OpenBLAS ignores it and picks its kernels by the processor
    """
    import os
    import platform

    value = (os.environ if environ is None else environ).get("OPENBLAS_CORETYPE")
    if not value or (machine or platform.machine()).lower() not in ("x86_64", "amd64"):
        return None
    if value.strip().lower() in {k.lower() for k in OPENBLAS_X86_64_KERNELS}:
        return None
    import difflib

    close = difflib.get_close_matches(value, OPENBLAS_X86_64_KERNELS, n=1, cutoff=0.6)
    hint = f" (did you mean {close[0]}?)" if close else " (e.g. Haswell, SkylakeX, Zen)"
    return (f"tefcore: warning: OPENBLAS_CORETYPE = {value!r} is not a kernel OpenBLAS "
            f"knows{hint}; OpenBLAS ignores it and picks its kernels by the processor")


def main(argv: list[str] | None = None) -> int:
    """Run the ``tefcore`` command.

    Parameters
    ----------
    argv : list of str, optional
        The arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit status; errors are one line on stderr with status 2
        (:func:`tefcore.errors.run_command`).
    """
    def body():
        args = build_parser().parse_args(argv)
        from ..runtime import apply_defaults

        if (line := coretype_warning()) is not None:
            print(line, file=sys.stderr)
        apply_defaults()  # the command owns its process (tefcore.runtime)
        with warnings.catch_warnings():
            warnings.showwarning = _show_warning
            return args.func(args)

    return run_command(body, prog="tefcore")


def entry_point() -> int:
    """The ``tefcore`` program: :func:`main`, then an exit without the final garbage collection.

    A process that has imported numpy, scipy and pandas spends 0.1-0.2 s
    when it exits in the interpreter's last collections, which walk every
    object those modules made, although the memory goes back with the process
    (measured: ``python -c "import tefcore.sweeps.sweep"`` 0.79 s, 0.61 s with
    ``gc.freeze()`` at its end; ``tefcore stability`` 0.81 times the wall time,
    interleaved medians of 11).  Once the command has returned -- its output
    files written and closed (:mod:`tefcore.safe_io`), its worker pools and
    kernels shut down -- this flushes the standard streams and moves every
    object out of the collector's reach (``gc.freeze``).  The exit handlers
    still run (loky's pool, temporary folders, coverage); objects left in
    reference cycles are not finalized, as the interpreter does not promise
    at exit anyway.  :func:`main` itself, which tests and programs call in
    their own process, leaves the collector alone.

    Returns
    -------
    int
        The exit status of :func:`main`.
    """
    import gc

    status = main()
    for stream in (sys.stdout, sys.stderr):
        if stream is None:                # pythonw and some launchers: no stream at all
            continue
        try:
            stream.flush()
        except (OSError, ValueError):     # closed or gone: nothing left to flush
            pass
    gc.freeze()
    return status


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """A warning as one line, ``tefcore: warning: <Category>: <message>``."""
    text = " ".join(str(message).split())
    print(f"tefcore: warning: {category.__name__}: {text}", file=file or sys.stderr)


if __name__ == "__main__":
    raise SystemExit(entry_point())
