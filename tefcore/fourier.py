"""Periodic functions of the azimuth: grids, spectral derivatives, trigonometric series.

Everything periodic in tefcore (the trim's harmonic balance, the linearised
system's coefficients, the section analyses of Figs. 5-7) is sampled on
equally spaced azimuths ``psi_j = 2 pi j / N`` and differentiated or
interpolated by its Fourier series:

* :func:`azimuth_grid` -- the ``N`` azimuths;
* :func:`spectral_derivative` -- ``d/dpsi`` on the grid as a matrix;
* :func:`fourier_coefficients`, :func:`fourier_eval` -- the series of samples
  along their last axis, evaluated anywhere with its derivatives (the
  Nyquist term dropped from derivatives, as the spectral derivative does:
  what the trim's collocation resolves);
* :func:`trig_interpolate` -- the interpolant along the first axis whose
  derivatives keep the Nyquist cosine (the derivative of that very function:
  what the Floquet analysis integrates between grid points).
"""

from __future__ import annotations

import functools

import numpy as np

__all__ = ["azimuth_grid", "fourier_coefficients", "fourier_eval", "fourier_series",
           "spectral_derivative", "trig_interpolate"]


def spectral_derivative(n: int) -> np.ndarray:
    """d/dpsi on ``n`` equally spaced periodic points (Fourier collocation).

    Exact for trigonometric polynomials of degree below n/2 (the Nyquist
    term, whose derivative is ambiguous on the grid, is dropped).

    Parameters
    ----------
    n : int
        Number of points.

    Returns
    -------
    numpy.ndarray
        The ``(n, n)`` differentiation matrix (a copy: callers may change it).

    Examples
    --------
    >>> psi = np.linspace(0, 2 * np.pi, 16, endpoint=False)
    >>> bool(np.allclose(spectral_derivative(16) @ np.sin(3 * psi), 3 * np.cos(3 * psi)))
    True
    """
    return _spectral_derivative(int(n)).copy()


@functools.lru_cache(maxsize=16)
def _spectral_derivative(n: int) -> np.ndarray:
    k = np.fft.fftfreq(n, 1.0 / n)
    if n % 2 == 0:
        k[n // 2] = 0.0
    return np.real(np.fft.ifft(1j * k[:, None] * np.fft.fft(np.eye(n), axis=0), axis=0))


def azimuth_grid(n: int = 72) -> np.ndarray:
    """``n`` equally spaced azimuths over one revolution [rad].

    Parameters
    ----------
    n : int, optional
        Number of azimuths.

    Returns
    -------
    numpy.ndarray
        ``2 pi k / n``, k = 0 .. n-1.
    """
    return np.linspace(0.0, 2 * np.pi, n, endpoint=False)


def fourier_coefficients(samples: np.ndarray) -> np.ndarray:
    """Complex Fourier coefficients (last axis = equally spaced azimuths).

    Parameters
    ----------
    samples : numpy.ndarray
        Periodic samples; the last axis is ``N`` equally spaced azimuths
        from 0.

    Returns
    -------
    numpy.ndarray
        ``numpy.fft.rfft(samples) / N``: the coefficients ``c_k``, k = 0 .. N/2,
        of ``x(psi) = c_0 + 2 Re sum_k c_k exp(i k psi)`` (below the Nyquist
        term).
    """
    return np.fft.rfft(samples, axis=-1) / samples.shape[-1]


def fourier_eval(samples: np.ndarray, psi, derivative: int = 0) -> np.ndarray:
    """Trigonometric interpolation of periodic samples (and its derivatives).

    Exact for trigonometric polynomials of degree below ``N/2``; the Nyquist
    term is kept as a cosine in the value and dropped from derivatives (as in
    :func:`spectral_derivative`).

    Parameters
    ----------
    samples : numpy.ndarray
        Periodic samples; the last axis is ``N`` equally spaced azimuths from 0.
    psi : array_like
        Azimuths to evaluate at [rad].
    derivative : int, optional
        Order of the psi-derivative.

    Returns
    -------
    numpy.ndarray
        Shape ``samples.shape[:-1] + (len(psi),)``.

    Examples
    --------
    >>> grid = np.linspace(0, 2 * np.pi, 8, endpoint=False)
    >>> round(float(fourier_eval(np.sin(2 * grid), np.array([0.3]))[0]), 12)
    0.564642473395
    """
    return fourier_series(samples, psi, (derivative,))[0]


def fourier_series(samples, psi, derivatives):
    """:func:`fourier_eval` for several derivatives from one FFT.

    Parameters
    ----------
    samples : numpy.ndarray
        Periodic samples; the last axis is ``N`` equally spaced azimuths from 0.
    psi : array_like
        Azimuths to evaluate at [rad].
    derivatives : sequence of int
        Orders of the psi-derivatives.

    Returns
    -------
    list of numpy.ndarray
        One array per order, each ``samples.shape[:-1] + (len(psi),)``.
    """
    n = samples.shape[-1]
    c = fourier_coefficients(samples)
    k = np.arange(c.shape[-1])
    weight = np.where((k == 0) | ((n % 2 == 0) & (k == n // 2)), 1.0, 2.0)
    psi = np.atleast_1d(np.asarray(psi, float))
    basis = np.exp(1j * np.outer(k, psi))                # (n_k, n_psi)
    out = []
    for derivative in derivatives:
        ik = (1j * k) ** derivative
        if derivative and n % 2 == 0:
            ik = np.where(k == n // 2, 0.0, ik)
        out.append(np.real((c * weight * ik) @ basis))
    return out


def trig_interpolate(samples, psi, derivative: int = 0) -> np.ndarray:
    """Trigonometric interpolant of periodic samples and its exact derivatives.

    ``samples`` has the equally spaced azimuths ``2 pi j / N`` on its first
    axis; the interpolant is the unique trigonometric polynomial of degree
    ``N/2`` through them with the Nyquist term (even ``N``) as a cosine, and
    ``derivative`` differentiates that very function (so the derivative of
    the Nyquist term is kept: it vanishes on the grid, not between).

    Parameters
    ----------
    samples : array_like, shape (N, ...)
        Values at the azimuths ``2 pi j / N``.
    psi : array_like, shape (m,)
        Azimuths to evaluate at [rad].
    derivative : int
        Order of the psi-derivative.

    Returns
    -------
    ndarray, shape (m, ...)

    Examples
    --------
    >>> grid = np.linspace(0, 2 * np.pi, 8, endpoint=False)
    >>> f = np.cos(4 * grid) + np.sin(grid)
    >>> psi = np.array([0.3])
    >>> bool(np.allclose(trig_interpolate(f, psi, 1), -4 * np.sin(4 * psi) + np.cos(psi)))
    True
    """
    s = np.asarray(samples, float)
    n = s.shape[0]
    psi = np.atleast_1d(np.asarray(psi, float))
    c = np.fft.rfft(s, axis=0) / n
    k = np.arange(c.shape[0])
    weight = np.where((k == 0) | ((n % 2 == 0) & (k == n // 2)), 1.0, 2.0)
    # the Nyquist coefficient of real samples is real: its term is the
    # cosine c cos(k psi), and Re[(ik)^d c e^{ik psi}] its exact derivative
    coef = c * (weight * (1j * k) ** derivative).reshape((-1,) + (1,) * (s.ndim - 1))
    basis = np.exp(1j * np.outer(psi, k))                   # (m, n_k)
    flat = coef.reshape(coef.shape[0], -1)
    return np.real(basis @ flat).reshape((psi.size,) + s.shape[1:])
