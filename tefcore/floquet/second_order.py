"""The linearised rotor as a second-order periodic system, and its Floquet modes.

The paper's eq. (5), ``M(psi) q** + C(psi) q* + K(psi) q = 0``, sampled on
the trim's equally spaced azimuths (one sample: constant coefficients, as in
hover).  :class:`SecondOrderSystem` interpolates ``M, C, K`` by trigonometric
series (docs/theory.md section 8), forms the first-order state matrix
``A = [[0, I], [-M^-1 K, -M^-1 C]]`` at any azimuth, and returns the Floquet
modes -- the same system for the stability analysis
(:mod:`tefcore.linear.stability`), the mechanism diagnostics (:mod:`tefcore.linear.mechanism`)
and the homotopies that name the flap mode.

Examples
--------
A constant single-dof oscillator ``q** + 0.2 q* + 4 q = 0``:

>>> import numpy as np
>>> sys = SecondOrderSystem(np.ones((1, 1, 1)), 0.2 * np.ones((1, 1, 1)), 4 * np.ones((1, 1, 1)))
>>> res = sys.modes()
>>> np.round(res.exponents, 6)
array([-0.1-1.997498j, -0.1+1.997498j])
"""

from __future__ import annotations

import contextlib
import functools
from dataclasses import dataclass

import numpy as np

from ._accuracy import DEFAULT_ATOL
from ._analysis import floquet_modes, floquet_motions
from ._result import constant_coefficient_modes

__all__ = ["STATE_MIN_RATE", "SecondOrderSystem", "augmented_state_matrix", "combine",
           "periodic_modes", "state_matrix"]


#: With first-order (aerodynamic) states, roots damped faster than this
#: (per radian of azimuth) need not be resolved by the Floquet lifting
#: (``min_rate`` of :func:`tefcore.floquet.floquet_modes`): the fastest shed-wake
#: states of a blade decay at -30 /rev and would drive the lifting to 16
#: sub-intervals; -8 /rev keeps 8 or fewer (measured at MDART mu = 0.3 with the
#: wake: every root above -12 /rev within 1.4e-6 of the 16-interval result, 0.3 s
#: instead of 1.6 s per lift; 4 at zero coupling since the adjoints' bound is
#: taken at this rate too, :func:`tefcore.floquet.floquet_modes`), below every
#: blade or flap root of the figures.
STATE_MIN_RATE = -8.0


@dataclass(frozen=True)
class SecondOrderSystem:
    """``M(psi) q** + C(psi) q* + K(psi) q = 0`` from equally spaced samples.

    With ``n_first > 0`` the last ``n_first`` of the coordinates ``y = [q, z]``
    are first-order states ``z`` (the aerodynamic states, docs/theory.md 6.2):
    the matrices are ``(n + r) x (n + r)`` with zero ``z`` columns in ``M``,
    and the state is ``x = [q, q*, z]`` with the descriptor form
    ``E x* + F x = 0``,

    ``E = [[I, 0, 0], [0, M_qq, C_qz], [0, M_zq, C_zz]]``,
    ``F = [[0, -I, 0], [K_qq, C_qq, K_qz], [K_zq, C_zq, K_zz]]``,

    ``A = -E^-1 F``.  The second-order users (shapes ``[q; q*]`` first,
    :attr:`n_dof` coordinates) are unchanged.

    Attributes
    ----------
    m, c, k : ndarray, shape (N, n + r, n + r)
        Samples at ``psi_j = 2 pi j / N`` (``N = 1``: constant coefficients).
    n_first : int
        ``r``, the first-order states among the coordinates (last rows and columns).
    """

    m: np.ndarray
    c: np.ndarray
    k: np.ndarray
    n_first: int = 0

    @property
    def n_dof(self) -> int:
        """Second-order coordinates ``n``."""
        return self.m.shape[-1] - self.n_first

    @property
    def n_states(self) -> int:
        """Length of the state ``[q, q*, z]``: ``2 n + r``."""
        return 2 * self.n_dof + self.n_first

    @property
    def periodic(self) -> bool:
        """True when the coefficients vary with azimuth (more than one sample)."""
        return self.m.shape[0] > 1

    def matrices(self, psi, derivative: int = 0):
        """``M, C, K`` (or their psi-derivatives) at azimuths ``psi``, each (len(psi), n, n).

        Periodic coefficients are evaluated from their real Fourier
        coefficients, computed on the first call and kept on the system
        (within :meth:`transient_coefficients`, until the block ends).
        """
        if not self.periodic:
            psi = np.atleast_1d(psi)
            if derivative:
                return tuple(np.zeros((psi.size,) + a.shape[1:]) for a in (self.m, self.c, self.k))
            return tuple(np.broadcast_to(a, (psi.size,) + a.shape[1:]) for a in
                         (self.m, self.c, self.k))
        # the three stacked: one product with the cached real Fourier coefficients
        psi = np.atleast_1d(np.asarray(psi, float))
        cos_c, sin_c, k = self._fourier
        kp = np.outer(psi, k)
        # d^d/dpsi^d of a cos(k psi) + b sin(k psi), as cos and sin terms again
        c_part, s_part = ((cos_c, sin_c), (sin_c * k[:, None], -cos_c * k[:, None]),
                          (-cos_c * k[:, None]**2, -sin_c * k[:, None]**2))[derivative % 3] \
            if derivative < 3 else _derivative_coefficients(cos_c, sin_c, k, derivative)
        out = np.cos(kp) @ c_part
        out += np.sin(kp) @ s_part          # in place: one (n_psi, 3 n^2) array less
        out = out.reshape((psi.size, 3) + self.m.shape[1:])
        return out[:, 0], out[:, 1], out[:, 2]

    @contextlib.contextmanager
    def transient_coefficients(self):
        """A block after which the system does not keep the Fourier coefficients it computed.

        For a system evaluated once among many, e.g. the terms of an energy
        balance (:func:`tefcore.linear.mechanism.energy_decomposition`): 20
        terms of 82 coordinates and shed-wake states kept 80 MiB of
        coefficients, the largest process of the reproduction (measured).
        Within the block the coefficients are computed once and
        used by every evaluation; coefficients the system had before are
        kept.  The values are those of :meth:`matrices` outside a block.

        Yields
        ------
        SecondOrderSystem
            The system itself.

        Examples
        --------
        >>> psi = 2 * np.pi * np.arange(4) / 4
        >>> m = np.eye(1) + 0.1 * np.cos(psi)[:, None, None]
        >>> system = SecondOrderSystem(m, 0.0 * m, m)
        >>> with system.transient_coefficients():
        ...     mats, rates = system.matrices([0.3]), system.matrices([0.3], 1)
        >>> "_fourier" in vars(system)
        False
        """
        had = "_fourier" in self.__dict__
        try:
            yield self
        finally:
            if not had:
                self.__dict__.pop("_fourier", None)

    @functools.cached_property
    def _fourier(self):
        """:meth:`_fourier_coefficients`, computed once."""
        return self._fourier_coefficients()

    def _fourier_coefficients(self):
        """Real Fourier coefficients of the stacked ``M, C, K``: ``(a_k, b_k, k)`` with
        ``f(psi) = sum_k a_k cos(k psi) + b_k sin(k psi)`` (the Nyquist term a cosine,
        as :func:`tefcore.fourier.trig_interpolate`)."""
        s = np.stack([self.m, self.c, self.k], axis=1)
        n = s.shape[0]
        c = np.fft.rfft(s, axis=0) / n
        k = np.arange(c.shape[0])
        weight = np.where((k == 0) | ((n % 2 == 0) & (k == n // 2)), 1.0, 2.0)
        c = (c * weight.reshape((-1,) + (1,) * (s.ndim - 1))).reshape(c.shape[0], -1)
        return np.ascontiguousarray(c.real), np.ascontiguousarray(-c.imag), k.astype(float)

    def state_matrix(self, psi) -> np.ndarray:
        """``A(psi) = [[0, I], [-M^-1 K, -M^-1 C]]``, shape (len(psi), 2n, 2n);
        with first-order states ``-E^-1 F`` (2n + r square)."""
        m, c, k = self.matrices(psi)
        if self.n_first:
            return augmented_state_matrix(m, c, k, self.n_dof)
        return state_matrix(m, c, k)

    def rate_function(self):
        """``f(psi, x) = A(psi) x`` for one azimuth at a time (a time march's right-hand side).

        The same ``A`` as :meth:`state_matrix`, without building it: ``M, C,
        K`` from their Fourier coefficients by two vector products, then
        ``q** = -M^-1 (K q + C q*)`` by one solve (with first-order states, the
        descriptor rows of :meth:`state_matrix` at that azimuth).  A fifth of
        the cost of ``state_matrix([psi])[0] @ x`` (measured with
        MDART's 10 coordinates: 0.02 against 0.1 ms a call), equal to it to
        round-off (tested).

        Returns
        -------
        callable
            ``f(psi, x) -> x*`` for a float ``psi`` and a state ``x`` of
            length :attr:`n_states`.
        """
        n, size = self.n_dof, self.m.shape[-1]
        if not self.periodic or self.n_first:
            if not self.periodic:
                a = self.state_matrix(np.zeros(1))[0]
                return lambda psi, x: a @ x
            return lambda psi, x: self.state_matrix(np.array([psi]))[0] @ x
        cos_c, sin_c, k = self._fourier

        def f(psi, x):
            mck = (np.cos(k * psi) @ cos_c + np.sin(k * psi) @ sin_c).reshape(3, size, size)
            acc = np.linalg.solve(mck[0], -(mck[2] @ x[:n] + mck[1] @ x[n:]))
            return np.concatenate([x[n:], acc])
        return f

    def modes(self, n_steps: int = 72, n_sub: int = 4, shapes: bool = False,
              on_inaccurate: str = "warn", participation: bool | None = None,
              atol: float | None = DEFAULT_ATOL):
        """Floquet modes of the system (direct eigenanalysis if constant).

        Forward flight: fourth-order Magnus steps (doubled until the
        exponents' error estimates meet the tolerance), lifted sub-intervals
        and the integer frequency shift decided by the displacements
        (:func:`tefcore.floquet.floquet_modes`; ``on_inaccurate`` as there).
        With first-order states, roots below :data:`STATE_MIN_RATE` need not
        be resolved.  ``participation`` (default: with first-order states):
        the participation factors come with the result, from the adjoint
        solutions (:func:`tefcore.floquet.floquet_modes`).  ``atol=None``
        switches the accuracy control off (one grid of ``n_steps``: roots
        to be told apart, not converged).
        Returns a :class:`tefcore.floquet.FloquetResult` with both members
        of each conjugate pair.
        """
        if not self.periodic:
            return constant_coefficient_modes(self.state_matrix([0.0])[0])
        return periodic_modes(self.state_matrix, self.n_dof, self.n_first, n_steps=n_steps,
                              n_sub=n_sub, shapes=shapes, on_inaccurate=on_inaccurate,
                              participation=participation, atol=atol)

    def motions(self, n_steps: int = 72, n_sub: int = 4):
        """Exponents and motions on one grid of Magnus steps (forward flight).

        :func:`tefcore.floquet.floquet_motions` of :meth:`state_matrix`: the
        exponents on the principal branch, one of each conjugate pair, and
        each root's solution without its decay, ``(n_steps, n_states, m)``.
        For a periodic system without first-order states (``ValueError``
        otherwise: a constant system has :meth:`modes`).
        """
        if not self.periodic or self.n_first:
            raise ValueError("motions: for a periodic second-order system without "
                             "first-order states")
        return floquet_motions(self.state_matrix, n_steps=n_steps, n_sub=n_sub,
                               method="magnus")


def periodic_modes(a, n_dof: int, n_first: int = 0, *, n_steps: int = 72, n_sub: int = 4,
                   shapes: bool = False, on_inaccurate: str = "warn",
                   participation: bool | None = None, atol: float | None = DEFAULT_ATOL):
    """Floquet modes of a periodic second-order system from its ``A(psi)``.

    What :meth:`SecondOrderSystem.modes` does in forward flight, for an
    ``A`` given directly -- the system's :meth:`~SecondOrderSystem.state_matrix`,
    or samples of it on the step grid computed another way (the coupling
    homotopy's, :class:`tefcore.modes.continuation.HomotopySamples`).

    Parameters
    ----------
    a : callable or numpy.ndarray
        ``A(psi)`` (vectorised), or its ``2 n_steps`` samples at the step ends
        and midpoints (:func:`tefcore.floquet.floquet_modes`).
    n_dof : int
        Second-order coordinates ``n`` (the displacements decide the integer
        frequency shift).
    n_first : int, optional
        First-order states after ``[q, q*]``: with them, roots below
        :data:`STATE_MIN_RATE` need not be resolved, and the participation
        factors come by default.
    n_steps, n_sub, shapes, on_inaccurate, participation, atol
        As :meth:`SecondOrderSystem.modes`.

    Returns
    -------
    tefcore.floquet.FloquetResult
    """
    # floquet_modes chooses K before the lift: for first-order states down to
    # STATE_MIN_RATE, and for the adjoints of the participation factors with
    # the fastest state in view (8 with the shed wake's -31 /rev states)
    return floquet_modes(a, n_steps=n_steps, n_sub=n_sub, method="magnus", shapes=shapes,
                         shift_states=slice(0, n_dof), on_inaccurate=on_inaccurate, atol=atol,
                         min_rate=STATE_MIN_RATE if n_first else None,
                         participation=bool(n_first) if participation is None else participation)


def _derivative_coefficients(cos_c, sin_c, k, derivative):
    """Cosine and sine coefficients of the ``derivative``-th derivative of
    ``sum_k a_k cos(k psi) + b_k sin(k psi)``."""
    a, b = cos_c, sin_c
    for _ in range(derivative):
        a, b = b * k[:, None], -a * k[:, None]
    return a, b


def combine(parts, scales=None) -> SecondOrderSystem:
    """The system ``sum_t s_t (M_t, C_t, K_t)`` of named parts.

    Parameters
    ----------
    parts : dict of str to SecondOrderSystem
        Parts sampled on one grid.
    scales : dict of str to float, optional
        Factor of each part (absent names: 1).

    Examples
    --------
    >>> one = SecondOrderSystem(np.ones((1, 1, 1)), np.zeros((1, 1, 1)), np.ones((1, 1, 1)))
    >>> float(combine({"a": one, "b": one}, {"b": 0.5}).k[0, 0, 0])
    1.5
    """
    scales = scales or {}
    m = sum(scales.get(t, 1.0) * p.m for t, p in parts.items())
    c = sum(scales.get(t, 1.0) * p.c for t, p in parts.items())
    k = sum(scales.get(t, 1.0) * p.k for t, p in parts.items())
    first = {p.n_first for p in parts.values()}
    if len(first) != 1:
        raise ValueError(f"parts with different first-order states: {sorted(first)}")
    return SecondOrderSystem(np.asarray(m), np.asarray(c), np.asarray(k), first.pop())


def augmented_state_matrix(m, c, k, n):
    """``A = -E^-1 F`` of a system with first-order states after ``n`` coordinates
    (:class:`SecondOrderSystem`), stacked over the first axis.

    Parameters
    ----------
    m, c, k : numpy.ndarray
        Mass, damping and stiffness, ``(..., n + r, n + r)``: the first ``n``
        rows and columns second-order coordinates, the last ``r`` first-order
        states (their mass columns zero, their ``c`` block invertible).
    n : int
        Number of second-order coordinates.

    Returns
    -------
    numpy.ndarray
        ``(..., 2 n + r, 2 n + r)`` state matrix of ``[q, q*, z]``.

    Examples
    --------
    ``q** + 4 q = z``, ``z* + 2 z = 0``: the oscillator and the state's own root.

    >>> m = np.array([[[1.0, 0.0], [0.0, 0.0]]])
    >>> c = np.array([[[0.0, 0.0], [0.0, 1.0]]])
    >>> k = np.array([[[4.0, -1.0], [0.0, 2.0]]])
    >>> ev = np.sort_complex(np.linalg.eigvals(augmented_state_matrix(m, c, k, 1)[0]))
    >>> [(round(float(e.real), 12) + 0.0, round(float(e.imag), 12)) for e in ev]
    [(-2.0, 0.0), (0.0, -2.0), (0.0, 2.0)]
    """
    size = m.shape[-1]
    r = size - n
    # rows of [q**; z*]: G [q**; z*] = -(K_y y + C_q q*), G = [[M_qq, C_qz], [M_zq, C_zz]]
    g = np.concatenate([m[..., :, :n], c[..., :, n:]], axis=-1)
    rhs = np.concatenate([k[..., :, :n], c[..., :, :n], k[..., :, n:]], axis=-1)
    lower = -np.linalg.solve(g, rhs)                       # (..., n + r, 2n + r)
    top = np.zeros(m.shape[:-2] + (n, 2 * n + r))
    top[..., :, n:2 * n] = np.eye(n)
    a = np.concatenate([top, lower], axis=-2)
    return a


def state_matrix(m, c, k):
    """First-order ``A = [[0, I], [-M^-1 K, -M^-1 C]]`` for stacked matrices.

    Parameters
    ----------
    m, c, k : numpy.ndarray
        Mass, damping and stiffness matrices, ``(..., n, n)``.

    Returns
    -------
    numpy.ndarray
        ``(..., 2 n, 2 n)``.
    """
    n = m.shape[-1]
    both = np.linalg.solve(m, np.concatenate([k, c], axis=-1))     # one factorisation
    minv_k, minv_c = both[..., :n], both[..., n:]
    top = np.concatenate([np.zeros_like(minv_k), np.broadcast_to(np.eye(n), minv_k.shape)],
                         axis=-1)
    return np.concatenate([top, np.concatenate([-minv_k, -minv_c], axis=-1)], axis=-2)
