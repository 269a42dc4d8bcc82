"""tefcore: aeroelastic stability of helicopter rotors with trailing-edge flaps.

An open replication of *Aeroelastic Stability of Trailing-Edge Flap Helicopter
Rotors*: a rotating finite-element blade with a trailing-edge flap and its
actuator, quasi-steady flap aerodynamics, trim and Floquet stability.

The matrices here are small (a few hundred dofs at most).  Importing tefcore
therefore limits BLAS to one thread and keeps freed heap memory in the
process (see :mod:`tefcore.runtime` for why, what it measured and the
environment variables that turn either off).
"""

import numpy  # noqa: F401  (load both BLAS builds before limiting them:
import scipy.linalg  # noqa: F401  threadpoolctl only sees libraries already loaded)

from .runtime import apply_defaults

__version__ = "0.1.0"

apply_defaults()
