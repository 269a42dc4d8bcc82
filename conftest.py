"""pytest configuration of the repository root.

The notebooks' jupytext sources (``tefcore/paper/notebooks/NN_*.py``) are
notebooks, not modules: ``--doctest-modules`` must not import (and so run)
them.  nbval checks the ``.ipynb`` beside them.
"""

collect_ignore_glob = ["tefcore/paper/notebooks/*.py"]
