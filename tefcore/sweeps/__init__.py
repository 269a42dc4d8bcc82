"""Sweeps of the stability over one or two parameters, resumable, in parallel.

Its modules, bottom up::

    store      the sweep file: format, header, resume
    evaluate   the point function, its checks, warm-start chains, worker pools
    table      the sweep's table: named roots, tracked, with their roles; refinement
    sweep      the sweep driver: serial, joblib or dask; warm starts; tracking
    boundary   where a tracked mode's damping crosses zero
    map_store  the boundary file of a stability map
    maps       two-parameter stability maps with the flutter boundary

Its public names (each loaded from its module on first use):

Sweeps
    :class:`~tefcore.sweeps.sweep.SweepResult`, :func:`~tefcore.sweeps.sweep.check_parameter`,
    :class:`~tefcore.sweeps.store.SweepFile`
Boundaries and maps
    :func:`~tefcore.sweeps.boundary.stability_boundary`
    (:class:`~tefcore.sweeps.boundary.BoundaryResult`),
    :func:`~tefcore.sweeps.maps.stability_map` (:class:`~tefcore.sweeps.maps.MapResult`)
The point function
    :func:`~tefcore.sweeps.evaluate.default_point`

The sweep itself is :func:`tefcore.sweep` (``tefcore.sweeps.sweep.sweep``): the
function has its module's name, so this face does not export it.

Examples
--------
The boundary of a point function whose one mode crosses zero at
``flap.cg_offset = 0.2`` (a stand-in for :func:`tefcore.stability`):

>>> import numpy as np, pandas as pd
>>> from types import SimpleNamespace
>>> from tefcore import config, sweeps
>>> def toy(cfg):
...     x = cfg.flap.cg_offset
...     return SimpleNamespace(
...         modes=pd.DataFrame({"mode_id": [0], "label": ["TEF"], "frequency_per_rev": [3.0],
...                             "real_part": [0.5 * (x - 0.2)],
...                             "damping_ratio": [-0.5 * (x - 0.2) / 3.0]}),
...         eigenvectors=np.ones((1, 1), complex), trim={"collective_deg": 8.0})
>>> found = sweeps.stability_boundary(config.load_config("mdart"), "flap.cg_offset",
...                                   (0.0, 1.0), point=toy)
>>> isinstance(found, sweeps.BoundaryResult), round(found.value, 9)
(True, 0.2)
"""

import sys

from ..faces import lazy_face

#: Public name -> the module that defines it (loaded on first use).
API = {
    "SweepResult": "tefcore.sweeps.sweep",
    "check_parameter": "tefcore.sweeps.sweep",
    "SweepFile": "tefcore.sweeps.store",
    "stability_boundary": "tefcore.sweeps.boundary",
    "BoundaryResult": "tefcore.sweeps.boundary",
    "stability_map": "tefcore.sweeps.maps",
    "MapResult": "tefcore.sweeps.maps",
    "default_point": "tefcore.sweeps.evaluate",
}

__all__ = list(API)
__getattr__, __dir__ = lazy_face(sys.modules[__name__], API)
