"""``python -m tefcore`` is the ``tefcore`` command."""

from .cli import entry_point

__all__: list[str] = []

raise SystemExit(entry_point())
