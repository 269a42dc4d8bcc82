"""pytest configuration of the repository root.

The notebooks' jupytext sources (``tefcore/paper/notebooks/NN_*.py``) are
notebooks, not modules: ``--doctest-modules`` must not import (and so run)
them.  nbval checks the ``.ipynb`` beside them.

Hypothesis runs **derandomized** by default (profile ``fixed``): the examples
of each property test are the same in every run, so the test command -- and CI
on a clean checkout -- is reproducible, and a failure it shows is a failure of
the code, not of the draw.  ``python -m pytest --hypothesis-profile=explore``
draws fresh random examples (more of them) to look for new edge cases; a case
found that way is fixed and kept as a test (as ``flexbeam.mass = 5e-324`` in
``tests/structure/test_hub.py``).
"""

from hypothesis import settings

collect_ignore_glob = ["tefcore/paper/notebooks/*.py"]

settings.register_profile("fixed", derandomize=True)
settings.register_profile("explore", derandomize=False, max_examples=500)
settings.load_profile("fixed")
