"""Sweeps of the stability over one or two parameters, resumable, in parallel.

Its modules (import each by name; the package itself exports nothing)::

    sweep     the sweep driver: serial, joblib or dask; warm starts; tracking
    store     the sweep file: format, header, resume
    boundary  where a tracked mode's damping crosses zero
    maps      two-parameter stability maps with the flutter boundary
"""

__all__: list[str] = []
