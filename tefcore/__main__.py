"""``python -m tefcore`` is the ``tefcore`` command."""

from .cli import main

__all__: list[str] = []

raise SystemExit(main())
