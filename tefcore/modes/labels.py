"""Labels of the roots of one point: which coordinate a root carries.

A point's roots are named by the coordinate that carries most of their
participation (participation factors: right times left eigenvectors, or the
periodic shapes times their duals for Floquet modes): ``blade flap 1``,
``blade torsion 2``, ``TEF``.  These are *point labels*: they say what a root
looks like at one point, not where it comes from (its identity, which
continuation and tracking give, :mod:`tefcore.modes.continuation`,
:mod:`tefcore.modes.tracking`).

* :func:`coordinate_shares` -- each coordinate's share of a root;
* :func:`label_modes` -- one coordinate per root, by assignment;
* :func:`tracking_shapes` -- the physical shapes roots are compared by
  between points.
"""

from __future__ import annotations

import numpy as np

from .names import locked_name

__all__ = ["coordinate_shares", "label_modes", "tracking_shapes", "trajectory_shapes"]


def label_modes(frac, labels, freqs, rates, disp, periodic: bool = False):
    """Label modes by the coordinate they carry, one coordinate per mode.

    ``frac`` are the coordinates' shares of participation (coordinates x
    modes); the labels are the assignment
    (``scipy.optimize.linear_sum_assignment``) that maximises the product of
    the shares, so every coordinate names exactly one mode, even where two
    modes share one coordinate (flutter). Kinetic-energy shares would hide the
    light coordinates: the MDART torsion mode in hover carries 0.5 % of its
    kinetic energy in torsion but 65 % of its participation (measured). A
    complex pair whose multipliers have become two real ones (frequency
    locked to a multiple of 1/2 per rev, or overdamped) gives one mode more
    than coordinates: the pair shares its coordinate's label, the less damped
    root carrying it plainly and the other with ``(locked)`` appended (the
    partner is the assigned mode at the closest frequency -- for Floquet
    exponents modulo 1/rev and up to its sign, so that the two real roots of
    a lock at 1/2 /rev are partners whether the convention wrote them 0.5 or
    2.5 -- ties by the MAC of the physical shapes ``disp``).

    Parameters
    ----------
    frac : numpy.ndarray
        Shares of the coordinates in each mode, coordinates x modes
        (:func:`coordinate_shares`).
    labels : list of str
        The coordinates' labels (``blade flap 1``, ..., ``TEF``).
    freqs, rates : numpy.ndarray
        Frequencies and damping rates of the modes [1/rev].
    disp : numpy.ndarray
        Physical shapes of the modes, one column each (:func:`tracking_shapes`).
    periodic : bool, optional
        Floquet exponents: frequencies known modulo 1/rev and up to their sign.

    Returns
    -------
    list of str
        One label per mode.
    """
    # maximise the product of the shares (sum of logs): a coordinate must
    # participate materially in the mode that carries its name.  Maximising
    # the plain sum can hand a coordinate a mode where its share is 1e-4
    # (seen: the TEF label on a flap mode while the TEF flutter mode took a
    # blade label)
    from scipy.optimize import linear_sum_assignment  # on first use: 0.2 s
    rows, cols = linear_sum_assignment(-np.log(frac + 1e-300))
    out = [None] * frac.shape[1]
    for r, c in zip(rows, cols, strict=True):
        out[c] = labels[r]
    unit = disp / np.linalg.norm(disp, axis=0, keepdims=True)
    mac = np.abs(unit.conj().T @ unit) ** 2
    for j, lab in enumerate(out):
        if lab is None:
            best = min(cols, key=lambda i: (round(_gap(freqs[i], freqs[j], periodic), 6),
                                            -mac[i, j]))
            # the two roots of a locked pair have nearly the same shape, so
            # which one the assignment named is decided by round-off; name the
            # less damped root (the one that matters for stability) after the
            # coordinate, deterministically
            if rates[j] > rates[best]:
                out[j], out[best] = out[best], locked_name(out[best])
            else:
                out[j] = locked_name(out[best])
    return out


def _gap(f, g, periodic):
    """|f - g|, for Floquet frequencies modulo 1/rev and up to the sign."""
    if not periodic:
        return abs(f - g)
    def circ(x):
        return abs((x + 0.5) % 1.0 - 0.5)
    return min(circ(f - g), circ(f + g))


def trajectory_shapes(basis, res, n, samples: int = 8):
    """Physical shapes of Floquet modes over one revolution, free of the frequency convention.

    The motion ``x(psi) = exp(i omega psi) p(psi)`` of a mode (without its
    decay over the revolution) sampled at `samples` equally spaced azimuths,
    displacements only, through ``basis``, stacked.  Whichever integer shift
    of the frequency the convention chose, ``exp(i omega psi) p(psi)`` is the
    same; so is the conjugate up to conjugation (compare both).  Two modes
    whose shapes at psi = 0 are alike (MAC 0.96 between MDART's first flap
    and torsion modes at mu = 0.3) differ over the revolution.

    Parameters
    ----------
    basis : numpy.ndarray
        Map from coordinates to physical shapes.
    res : tefcore.floquet.FloquetResult
        Roots with their periodic shapes (``res.shapes``; without them, the
        displacement shapes at psi = 0).
    n : int
        Number of coordinates.
    samples : int, optional
        Azimuths sampled, equally spaced from 0; must divide the result's
        grid (``ValueError`` otherwise).

    Returns
    -------
    numpy.ndarray
        ``(samples * n_phys, n_modes)``.
    """
    if res.shapes is None:
        return basis @ res.eigenvectors[:n]
    if len(res.psi) % samples:
        raise ValueError(f"trajectory_shapes: {samples} azimuths do not divide the result's "
                         f"grid of {len(res.psi)}; shapes sampled at different azimuths "
                         "cannot be compared")
    idx = np.arange(0, len(res.psi), len(res.psi) // samples)
    psi = res.psi[idx]
    x = res.shapes[idx][:, :n, :] * np.exp(1j * np.outer(psi, res.exponents.imag))[:, None, :]
    return np.concatenate([basis @ x[k] for k in range(idx.size)], axis=0)


def tracking_shapes(basis, res, n):
    """Physical shapes to compare modes by: displacement and velocity at psi = 0.

    ``[B q(0); B q*(0)]`` (velocities per radian of azimuth) from the state
    eigenvector, which the integer frequency shift of a Floquet mode does not
    change.  Two Floquet modes can share one displacement shape at psi = 0
    (MAC 0.96 between MDART's first flap and first torsion modes at
    mu = 0.3, measured); their velocities, which scale with the frequency,
    tell them apart.  A sampled motion over the revolution would too, but
    aliases for modes far above the Floquet steps' frequencies (a 0.1 c
    flap near 100 /rev), whose velocity shape stays steady.

    Parameters
    ----------
    basis : numpy.ndarray
        Map from coordinates to physical shapes
        (:meth:`tefcore.model.coupled.CoupledModel.tracking_basis`).
    res : tefcore.floquet.FloquetResult
        The roots, with state eigenvectors ``[q; q*]`` at psi = 0.
    n : int
        Number of coordinates.

    Returns
    -------
    numpy.ndarray
        ``(2 n_phys, n_modes)``.
    """
    vec = res.eigenvectors
    return np.concatenate([basis @ vec[:n], basis @ vec[n:2 * n]], axis=0)


def coordinate_shares(participation, n):
    """Shares of the coordinates in each mode (n x modes), summing to 1.

    The participation factors of a coordinate's displacement and velocity
    states, in magnitude, added and normalised per mode.

    Parameters
    ----------
    participation : numpy.ndarray
        Participation factors, states x modes (displacements, then velocities,
        then any first-order states).
    n : int
        Number of coordinates.

    Returns
    -------
    numpy.ndarray
        ``(n, n_modes)``, each column summing to 1.
    """
    mag = np.abs(participation[:n]) + np.abs(participation[n:2 * n])
    return mag / mag.sum(axis=0, keepdims=True)
