"""tefcore: aeroelastic stability of helicopter rotors with trailing-edge flaps.

An open replication of *Aeroelastic Stability of Trailing-Edge Flap Helicopter
Rotors*: a rotating finite-element blade with a trailing-edge flap and its
actuator, quasi-steady flap aerodynamics, trim and Floquet stability.

The matrices here are small (a few hundred dofs at most), for which a
multi-threaded BLAS is far slower than a single thread (seen: 320 ms against
3.6 ms for one 183-dof eigenproblem on two cores).  Importing tefcore therefore
limits BLAS to one thread unless ``TEFCORE_BLAS_THREADS`` says otherwise;
parallelism comes from sweeping points in separate processes instead.
"""

import os

import numpy  # noqa: F401  (load both BLAS builds before limiting them:
import scipy.linalg  # noqa: F401  threadpoolctl only sees libraries already loaded)
from threadpoolctl import threadpool_limits

__version__ = "0.1.0"

_blas_threads = os.environ.get("TEFCORE_BLAS_THREADS", "1")
if _blas_threads != "default":
    threadpool_limits(int(_blas_threads), user_api="blas")
