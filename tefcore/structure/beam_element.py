"""Rotating beam finite element with fifteen degrees of freedom.

The element follows the UMARC-type element of the paper: flap bending ``w``
and lag bending ``v`` are cubic Hermite (value and slope at both ends),
elastic twist ``phi`` is quadratic (both ends and the mid-point) and axial
extension ``u`` is cubic (both ends and two interior points)::

    local dof  0..3    u(0), u(1/3), u(2/3), u(1)
               4..7    v(0), v'(0), v(1), v'(1)
               8..11   w(0), w'(0), w(1), w'(1)
               12..14  phi(0), phi(1/2), phi(1)

All quantities are in rotor nondimensional units (length R, time 1/Omega,
mass per length m0); see ``docs/theory.md`` for the energy expressions that
the quadratic forms below discretise.
"""

from __future__ import annotations

import functools

import numpy as np

__all__ = ["N_DOF", "N_GAUSS", "PHI_DOF", "U_DOF", "V_DOF", "W_DOF", "element_matrices",
           "field_operators", "gauss_legendre", "hermite", "lagrange"]

N_DOF = 15
U_DOF = slice(0, 4)
V_DOF = slice(4, 8)
W_DOF = slice(8, 12)
PHI_DOF = slice(12, 15)

#: Gauss points per element.  The integrands are at most of degree ~8 in xi for
#: linearly varying properties (tension is quadratic, curvatures linear), so
#: six points integrate the stiffness and mass exactly for such sections.
N_GAUSS = 6


@functools.lru_cache(maxsize=32)
def gauss_legendre(n: int):
    """Gauss-Legendre points and weights on [-1, 1] (cached, read-only).

    numpy computes them from an eigenproblem each call (~0.3 ms), which
    showed in the cost of one stability point.
    """
    g, w = np.polynomial.legendre.leggauss(n)
    g.setflags(write=False)
    w.setflags(write=False)
    return g, w


def hermite(xi, h):
    """Cubic Hermite shape functions and their x-derivatives.

    Parameters
    ----------
    xi : array_like
        Local coordinate in [0, 1].
    h : float or array_like
        Element length (broadcast against ``xi``).

    Returns
    -------
    n, dn, ddn : ndarray
        Values, first and second x-derivatives, each with a trailing axis of 4
        (value/slope at the inboard node, value/slope at the outboard node).

    Examples
    --------
    >>> n, dn, ddn = hermite(0.0, 0.5)
    >>> n.round(12).tolist(), dn.round(12).tolist()
    ([1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0])
    """
    xi = np.asarray(xi, dtype=float)
    h = np.asarray(h, dtype=float)
    xi, h = np.broadcast_arrays(xi, h)
    n = np.stack([1 - 3 * xi**2 + 2 * xi**3,
                  h * (xi - 2 * xi**2 + xi**3),
                  3 * xi**2 - 2 * xi**3,
                  h * (-(xi**2) + xi**3)], axis=-1)
    dn = np.stack([(-6 * xi + 6 * xi**2) / h,
                   1 - 4 * xi + 3 * xi**2,
                   (6 * xi - 6 * xi**2) / h,
                   -2 * xi + 3 * xi**2], axis=-1)
    ddn = np.stack([(-6 + 12 * xi) / h**2,
                    (-4 + 6 * xi) / h,
                    (6 - 12 * xi) / h**2,
                    (-2 + 6 * xi) / h], axis=-1)
    return n, dn, ddn


def lagrange(xi, h, order):
    """Equally spaced Lagrange shape functions of the given order on [0, 1].

    Parameters
    ----------
    xi : array_like
        Local coordinate in [0, 1].
    h : float or array_like
        Element length, for the x-derivative.
    order : int
        Polynomial order (2 for torsion, 3 for axial).

    Returns
    -------
    n, dn : ndarray
        Values and x-derivatives with a trailing axis of ``order + 1``.

    Examples
    --------
    >>> n, dn = lagrange(0.5, 1.0, 2)
    >>> (n.round(12) + 0.0).tolist()
    [0.0, 1.0, 0.0]
    """
    xi = np.asarray(xi, dtype=float)
    h = np.asarray(h, dtype=float)
    xi, h = np.broadcast_arrays(xi, h)
    nodes = np.linspace(0.0, 1.0, order + 1)
    n = np.ones(xi.shape + (order + 1,))
    dn = np.zeros(xi.shape + (order + 1,))
    for i, xi_i in enumerate(nodes):
        others = np.delete(nodes, i)
        denom = np.prod(xi_i - others)
        n[..., i] = np.prod(xi[..., None] - others, axis=-1) / denom
        # derivative of a product: sum over the factor that is differentiated
        for j in range(order):
            rest = np.delete(others, j)
            dn[..., i] += np.prod(xi[..., None] - rest, axis=-1) / denom
    return n, dn / h[..., None]


@functools.lru_cache(maxsize=16)
def _reference_shapes(xi: tuple):
    """Shape functions and xi-derivatives for a unit element (cached)."""
    xi = np.asarray(xi)
    hn, hdn, hddn = hermite(xi, 1.0)
    un, udn = lagrange(xi, 1.0, 3)
    pn, pdn = lagrange(xi, 1.0, 2)
    return hn, hdn, hddn, un, udn, pn, pdn


def field_operators(xi, h):
    """Rows that map the 15 element dofs to every field the energies need.

    Parameters
    ----------
    xi : array_like, shape (n,) or (m, n)
        Local coordinates (the same row of points is shared by all elements
        when 2-D, e.g. Gauss points).
    h : array_like
        Element lengths, broadcast against ``xi``.

    Returns
    -------
    dict of ndarray, each of shape ``xi.shape + (15,)``
        Keys ``u, du, v, dv, ddv, w, dw, ddw, phi, dphi``.
    """
    xi, h = np.broadcast_arrays(np.asarray(xi, float), np.asarray(h, float))
    if xi.ndim == 2 and np.all(xi == xi[:1]):
        ref = [np.broadcast_to(a, xi.shape + a.shape[1:])
               for a in _reference_shapes(tuple(xi[0]))]
    else:
        ref = _reference_shapes(tuple(xi.ravel()))
        ref = [a.reshape(xi.shape + a.shape[1:]) for a in ref]
    hn, hdn, hddn, un, udn, pn, pdn = ref
    hh = h[..., None]
    # Hermite slope dofs carry a factor h in the value (unit-element form)
    slope = np.array([1.0, 0.0, 1.0, 0.0]) + np.array([0.0, 1.0, 0.0, 1.0]) * hh
    shape = xi.shape + (N_DOF,)
    ops = {k: np.zeros(shape) for k in
           ("u", "du", "v", "dv", "ddv", "w", "dw", "ddw", "phi", "dphi")}
    ops["u"][..., U_DOF], ops["du"][..., U_DOF] = un, udn / hh
    for f, sl in (("v", V_DOF), ("w", W_DOF)):
        ops[f][..., sl] = hn * slope
        ops["d" + f][..., sl] = hdn * slope / hh
        ops["dd" + f][..., sl] = hddn * slope / hh**2
    ops["phi"][..., PHI_DOF], ops["dphi"][..., PHI_DOF] = pn, pdn / hh
    return ops


#: Fields of the element energies, in the order of the quadratic-form index.
_FIELDS = ("u", "du", "v", "dv", "w", "dw", "phi", "dphi", "kap_c", "kap_f", "slope_c", "slope_f")
_F = {name: i for i, name in enumerate(_FIELDS)}


def element_matrices(x0, h, sec, pitch, tension):
    """Mass, elastic stiffness and centrifugal stiffness of many elements at once.

    Each energy density is a quadratic form ``f^T C(x) f`` in the fields
    ``f = (u, u', v, v', w, w', phi, phi', kappa_c, kappa_f, v_c', w_f')``
    (docs/theory.md section 2), and each field is a row ``B`` acting on the
    15 element dofs, so an element matrix is ``sum_g w_g h B_g^T C_g B_g``
    over the Gauss points: one batched product for all elements and all
    four matrices.

    Parameters
    ----------
    x0, h : ndarray, shape (n_el,)
        Inboard station and length of each element (fractions of R).
    sec : callable
        ``sec(x)`` returns a dict of nondimensional section properties at the
        radial stations ``x`` (any shape): ``mass, ei_flap, ei_lag, gj, ea,
        im_flap, im_lag, cg_offset, tension_offset, ka``.
    pitch : callable
        ``pitch(x)``: geometric pitch angle (collective plus pretwist) in rad.
    tension : callable
        ``tension(x)``: nondimensional centrifugal tension per Omega^2,
        ``T(x) = int_x^1 m(s) s ds``.

    Returns
    -------
    m_el, k_el, k_cf, g_el : ndarray, shape (n_el, 15, 15)
        Mass; elastic stiffness (scales with (Omega_ref/Omega)^2 when the
        rotor speed changes); centrifugal stiffness (per Omega^2, i.e.
        independent of rotor speed in rotor units); Coriolis (gyroscopic,
        per Omega, skew-symmetric).
    """
    g, wg = gauss_legendre(N_GAUSS)
    xi = 0.5 * (g + 1.0)
    wg = 0.5 * wg
    x0 = np.asarray(x0, float)[:, None]
    h = np.asarray(h, float)[:, None]
    x = x0 + xi[None, :] * h                      # (n_el, n_g)
    ops = field_operators(np.broadcast_to(xi, x.shape), np.broadcast_to(h, x.shape))
    p = sec(x)
    th = pitch(x)
    c, s = np.cos(th), np.sin(th)
    t = tension(x)
    m, eg, ea_off = p["mass"], p["cg_offset"], p["tension_offset"]

    # field rows (n_el, n_g, n_fields, 15); curvatures and slopes in the
    # section principal axes (chordwise / flapwise)
    cc, ss = c[..., None], s[..., None]
    b = np.stack([ops["u"], ops["du"], ops["v"], ops["dv"], ops["w"], ops["dw"], ops["phi"],
                  ops["dphi"], cc * ops["ddv"] + ss * ops["ddw"],
                  cc * ops["ddw"] - ss * ops["ddv"], cc * ops["dv"] + ss * ops["dw"],
                  cc * ops["dw"] - ss * ops["dv"]], axis=-2)
    # C_g B_g built row by row from the few nonzero entries of C (a dense
    # 12 x 12 product per Gauss point was 3x slower), quadrature weight
    # and element length folded in
    n_el, n_g = x.shape
    wh = wg[None, :] * h
    cb = np.zeros((4,) + b.shape)
    mass_c, elastic, centrifugal, coriolis = cb

    def add(mat, a, bb, value):             # row a of C B += value B_bb
        mat[..., _F[a], :] += (value * wh)[..., None] * b[..., _F[bb], :]

    def sq(mat, a, value):                  # energy term value * a^2
        add(mat, a, a, value)

    def sym(mat, a, bb, value):             # energy term 2 * value * a * b
        add(mat, a, bb, value)
        add(mat, bb, a, value)

    # elastic strain energy; bending stiffnesses are given about the tension
    # axis, so the elastic-axis value adds EA e_A^2 (parallel-axis theorem)
    sq(elastic, "du", p["ea"])
    sym(elastic, "du", "kap_c", -p["ea"] * ea_off)
    sq(elastic, "kap_c", p["ei_lag"] + p["ea"] * ea_off**2)
    sq(elastic, "kap_f", p["ei_flap"])
    sq(elastic, "dphi", p["gj"])

    # centrifugal terms: tension stiffening, in-plane/axial softening,
    # propeller moment, tension-torsion and CG / tension-axis couplings
    for f in ("dv", "dw"):
        sq(centrifugal, f, t)
    sq(centrifugal, "dphi", t * p["ka"] ** 2)
    for f in ("u", "v"):
        sq(centrifugal, f, -m)
    sq(centrifugal, "phi", (p["im_lag"] - p["im_flap"]) * np.cos(2 * th))
    sym(centrifugal, "phi", "kap_f", -t * ea_off)
    sym(centrifugal, "phi", "slope_f", x * m * eg)
    sym(centrifugal, "u", "slope_c", m * eg)
    sym(centrifugal, "v", "phi", m * eg * s)

    for f in ("u", "v", "w"):
        sq(mass_c, f, m)
    sq(mass_c, "phi", p["im_flap"] + p["im_lag"])
    sym(mass_c, "w", "phi", m * eg * c)
    sym(mass_c, "v", "phi", -m * eg * s)

    # Coriolis: T_kin contains m (v* u - u* v), so row v gets +2 m u* and
    # row u gets -2 m v* (skew-symmetric gyroscopic matrix)
    add(coriolis, "v", "u", 2.0 * m)
    add(coriolis, "u", "v", -2.0 * m)

    # sum_g B_g^T (C_g B_g): the Gauss-point sum folded into one product per
    # element, (15, n_g n_f) @ (n_g n_f, 15)
    cb = cb.reshape(4, n_el, n_g * len(_FIELDS), N_DOF)
    bt = np.swapaxes(b.reshape(n_el, n_g * len(_FIELDS), N_DOF), -1, -2)
    return tuple(bt[None] @ cb)
