"""``python -m tefcore`` is the ``tefcore`` command."""

from .cli import main

raise SystemExit(main())
