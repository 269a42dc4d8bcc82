"""Floquet stability of linear periodic systems ``x' = A(psi) x`` (docs/theory.md section 5).

General tools, independent of the rotor model: any real or complex system
whose matrix is periodic in the azimuth ``psi`` with period ``period``
(default ``2 pi``, so rates and frequencies come out per rev).

* :func:`step_propagators`, :func:`transition_matrices`, :func:`monodromy` --
  the state transition matrix, all columns at once, by classical RK4 written
  as a matrix polynomial (or a fourth-order Magnus exponential), grouped into
  ``n_sub`` sub-interval matrices ``Phi_k``.
* :func:`characteristic_multipliers` -- eigenvalues of the product
  ``Phi_K ... Phi_1`` *without forming it*, by lifting to a block-cyclic
  matrix, so heavily damped modes are not lost.
* :func:`floquet_modes` -- characteristic exponents with the frequency
  ambiguity (integer multiples of ``2 pi / period``) resolved from the
  dominant harmonic of the periodic mode shape; :class:`FloquetResult`.
* :func:`floquet_motions` -- the exponents (principal branch) and each
  root's motion over the period on one grid, without error control or
  harmonic analysis: what continuation compares at each step.
* :func:`constant_coefficient_modes` -- the same result for a constant
  ``A`` (hover) by direct eigenanalysis.

Default grid: ``n_steps = 144`` RK4 steps per period (2.5 deg) in
``n_sub = 8`` sub-intervals of 45 deg, raised up to :data:`MAX_SUB` for
heavily damped roots (:data:`MIN_ROOT`); see :data:`DEFAULT_N_STEPS`,
:data:`DEFAULT_N_SUB` and the theory notes for why.  :func:`floquet_modes`
controls its own accuracy: a step-doubling error estimate per exponent, and
the steps doubled until every exponent meets ``atol + rtol |sigma|`` in its
damping rate and ``atol + rtol |eta|`` in its frequency
(:data:`DEFAULT_ATOL`, :data:`DEFAULT_RTOL`);
if it cannot, :class:`FloquetAccuracyWarning` or :class:`FloquetAccuracyError`
(docs/theory.md section 5.6a).

Its modules, one job each; this package is the public face of the private ones::

    _propagators  step propagators, transition matrices, input checks and errors
    _multipliers  characteristic multipliers by lifting the sub-interval factors
    _result       the result, damping ratio, constant coefficients (hover)
    _accuracy     error estimates by step doubling
    _analysis     :func:`floquet_modes`: exponents, shapes, participation
    second_order  the linearised rotor as a periodic system ``M, C, K`` and its modes

Examples
--------
A damped oscillator (frequency 0.7/rev, damping rate -0.05/rev) seen through
the periodic change of variables ``x = (1 + 0.3 sin psi) z``:

>>> import numpy as np
>>> from tefcore.floquet import floquet_modes
>>> B = np.array([[0.0, 1.0], [-(0.05**2 + 0.7**2), -0.1]])
>>> def A(psi):
...     s = 1 + 0.3 * np.sin(psi)
...     return B + (0.3 * np.cos(psi) / s)[:, None, None] * np.eye(2)
>>> res = floquet_modes(A).positive_frequency()
>>> np.round(res.frequencies, 6), np.round(res.damping_rates, 6)
(array([0.7]), array([-0.05]))
"""

from __future__ import annotations

from ._accuracy import DEFAULT_ATOL, DEFAULT_RTOL, MAX_DOUBLINGS
from ._analysis import (
    LIFT_RTOL,
    MAX_SUB,
    MIN_ROOT,
    ROOT_RTOL,
    STATE_ROOT_RTOL,
    floquet_modes,
    floquet_motions,
)
from ._multipliers import characteristic_multipliers
from ._propagators import (
    DEFAULT_N_STEPS,
    DEFAULT_N_SUB,
    FloquetAccuracyError,
    FloquetAccuracyWarning,
    FloquetOverflowError,
    monodromy,
    step_propagators,
    transition_matrices,
)
from ._result import FloquetResult, constant_coefficient_modes, damping_ratio

__all__ = [
    "DEFAULT_ATOL",
    "DEFAULT_N_STEPS",
    "DEFAULT_N_SUB",
    "DEFAULT_RTOL",
    "LIFT_RTOL",
    "MAX_DOUBLINGS",
    "MAX_SUB",
    "MIN_ROOT",
    "ROOT_RTOL",
    "STATE_ROOT_RTOL",
    "FloquetAccuracyError",
    "FloquetAccuracyWarning",
    "FloquetOverflowError",
    "FloquetResult",
    "characteristic_multipliers",
    "constant_coefficient_modes",
    "damping_ratio",
    "floquet_modes",
    "floquet_motions",
    "monodromy",
    "step_propagators",
    "transition_matrices",
]
