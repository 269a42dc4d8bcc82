"""The station forces and their derivatives in one compiled pass (optional numba).

:func:`tefcore.model.jacobian.exact_jacobian` needs, at every aerodynamic
station and azimuth, the station forces of :func:`tefcore.model.station_terms.station_terms`
and their derivatives with respect to the local variables.  In numpy they are
taken by complex step on whole arrays, one copy of every array per local
variable.  This module does the same arithmetic in one pass over stations and
azimuths, compiled by numba, for the thin-airfoil section model
(:class:`tefcore.aero.thin_airfoil.ThinAirfoilFlap`): per point and local
variable one complex-step evaluation of the same formulas -- the section loads
of :func:`tefcore.aero.thin_airfoil.section_loads`, the airloads'
projection and the flap's equation of :func:`tefcore.model.flap.flap_moments`
-- in registers instead of temporaries.  Same steps, same first-order
functions: the results agree with the numpy path to round-off (measured:
3e-16 of the largest entry on MDART at mu = 0.3; the tests hold 1e-13).

numba is optional (``pip install tefcore[fast]``), and the kernel is asked
for by :data:`KERNEL_ENV`: ``numba`` (numba or an error), ``auto`` (numba
where it is installed) or ``numpy`` (the default).  It is not the default
because its first call in a process costs what hundreds of Jacobians save:
importing numba and loading the compiled kernel from its on-disk cache
(numba's ``cache=True``, next to this module or in numba's cache directory
where that is not writable) took 0.55-0.63 s of CPU in a fresh process, and
compiling it where no cache exists 4.6 s, against 2-3 ms saved per Jacobian
(two per stability point; measured on the shared 2-core machine, load 5):
worth it for a reproduction or a long sweep, not for one point.  The numpy
path is what runs without numba, for the C81 table model, and for the
Jacobian by piece; the two differ in round-off only.

Examples
--------
>>> kernel_name() in ("numba", "numpy")
True
"""

from __future__ import annotations

import functools
import math
import os

import numpy as np

from ..aero.thin_airfoil import MACH_CLIP, MACH_MAX, ThinAirfoilFlap

__all__ = ["KERNEL_ENV", "KERNELS", "covers", "kernel_name", "station_derivatives"]

#: Environment variable choosing the station kernel: ``auto``, ``numba`` or ``numpy``
#: (the default).
KERNEL_ENV = "TEFCORE_STATION_KERNEL"

#: The values of :data:`KERNEL_ENV`.
KERNELS = ("auto", "numba", "numpy")


def kernel_name(choice: str | None = None) -> str:
    """The station kernel that runs: ``numba`` or ``numpy``.

    Parameters
    ----------
    choice : str, optional
        One of :data:`KERNELS`; default :data:`KERNEL_ENV` (``numpy`` when unset).

    Returns
    -------
    str

    Raises
    ------
    ValueError
        An unknown choice, or ``numba`` where numba is not installed.
    """
    choice = (os.environ.get(KERNEL_ENV, "numpy") if choice is None else choice).strip().lower()
    if choice not in KERNELS:
        raise ValueError(f"{KERNEL_ENV} = {choice!r} is not one of {', '.join(KERNELS)}")
    if choice == "numpy":
        return "numpy"
    if _numba_available():
        return "numba"
    if choice == "numba":
        raise ValueError(f"{KERNEL_ENV} = 'numba' but numba is not installed "
                         "(pip install tefcore[fast])")
    return "numpy"


@functools.cache
def _numba_available() -> bool:
    import importlib.util

    return importlib.util.find_spec("numba") is not None


def covers(model) -> bool:
    """Whether the compiled kernel covers the model's station forces.

    The thin-airfoil section model (exactly :class:`~tefcore.aero.thin_airfoil.ThinAirfoilFlap`)
    without shed-wake states; the C81 table model takes the numpy path.

    Parameters
    ----------
    model : tefcore.model.coupled.CoupledModel
        The coupled model.

    Returns
    -------
    bool
    """
    return type(model.aero) is ThinAirfoilFlap and model.n_wake == 0


#: Indices of the packed constants of :func:`_constants`.
_P = {name: i for i, name in enumerate((
    "omega", "omega2", "accel", "speed", "force", "moment", "rho", "chord", "axis",
    "speed_of_sound", "compressible", "circ", "cla", "cld", "cma", "cmd", "cha", "chd",
    "cd0", "cd1", "cd2", "cm0", "d", "ih", "sf", "eta", "clip"))}


def _constants(model):
    """The model's scalars in the kernel's order, and the influence matrices."""
    key = "station_kernel_constants"
    if key in model.cache:
        return model.cache[key]
    sc, r, aero, f = model.scale, model.cfg.rotor, model.aero, model.flap
    d, sm, nm = aero.influence()
    dv = aero.derivatives
    vals = dict(omega=sc["omega"], omega2=sc["omega"] ** 2, accel=sc["accel"],
                speed=sc["speed"], force=sc["force"], moment=sc["moment"],
                rho=r.air_density, chord=r.chord, axis=r.elastic_axis,
                speed_of_sound=r.speed_of_sound, compressible=float(aero.compressibility),
                circ=aero.circulatory_scale, cla=dv["cl_alpha"], cld=dv["cl_delta"],
                cma=dv["cm_alpha"], cmd=dv["cm_delta"], cha=dv["ch_alpha"], chd=dv["ch_delta"],
                cd0=aero.cd0, cd1=aero.cd1, cd2=aero.cd2, cm0=aero.cm0, d=d,
                ih=f.get("inertia_hinge", 0.0), sf=f.get("first_moment", 0.0),
                eta=f.get("hinge_from_ea", 0.0), clip=MACH_CLIP)
    p = np.array([vals[k] for k in _P], float)
    out = (p, np.ascontiguousarray(sm, float), np.ascontiguousarray(nm, float))
    model.cache[key] = out
    return out


def station_derivatives(model, loc, n_var, h, kernel=None):
    """Station forces and their derivatives with respect to the local variables, fused.

    Parameters
    ----------
    model : tefcore.model.coupled.CoupledModel
        A model the kernel :func:`covers`.
    loc : dict
        The real local variables (:func:`tefcore.model.station_terms.local_variables`).
    n_var : int
        Local variables: the six station variables, then with the flap
        ``dl, dld, dldd, slope, v, dv, vdd, dvd, dwd`` (the order of the
        exact Jacobian's seeds).
    h : float
        Complex step.
    kernel : {"numba", "python", "numpy"}, optional
        Default :func:`kernel_name`; ``python`` runs the same kernel
        uncompiled (slowly: what the tests check without numba).

    Returns
    -------
    total : numpy.ndarray
        ``(6, n_var, n_psi, n_x)``: derivatives of the forces on the fields
        ``w, dw, v, dv, phi, flap``.
    dfz : numpy.ndarray
        ``(n_var, n_psi, n_x)``: derivatives of the normal force.
    forces : numpy.ndarray
        ``(6, n_psi, n_x)``: the forces themselves.
    fz : numpy.ndarray
        ``(n_psi, n_x)``: the normal force.
    None
        Where the compiled kernel does not run (numpy chosen or numba absent):
        the caller takes the numpy path.

    Raises
    ------
    ValueError
        A Mach number outside ``[0, MACH_MAX]`` (as the numpy path).
    """
    kernel = kernel_name() if kernel is None else kernel
    if kernel == "numpy":
        return None
    from .station_terms import FLAP_VARIABLES, STATION_VARIABLES

    station = np.stack([np.broadcast_to(loc[k], loc["ut"].shape) for k in STATION_VARIABLES])
    ut, up = station[3], station[4]
    speed = np.sqrt(ut * ut + up * up)
    mach = speed * (model.scale["speed"] / model.cfg.rotor.speed_of_sound)
    if not (np.isfinite(station).all() and mach.min() >= 0.0 and mach.max() <= MACH_MAX):
        return None          # the numpy path words the error (or carries the NaN)
    n_psi, n_x = ut.shape
    fs = model.flap_stations
    if model.has_flap:
        order = ("dl", "dld", "dldd") + tuple(v for v in FLAP_VARIABLES
                                              if v not in ("dl", "dld", "dldd"))
        flap = np.stack([np.broadcast_to(loc[k], (n_psi, fs.stop - fs.start)) for k in order])
        f0, f1 = fs.start, fs.stop
    else:
        flap, f0, f1 = np.zeros((9, n_psi, 0)), 0, 0
    p, sm, nm = _constants(model)
    total = np.zeros((6, n_var, n_psi, n_x))
    dfz = np.zeros((n_var, n_psi, n_x))
    forces = np.zeros((6, n_psi, n_x))
    fz = np.zeros((n_psi, n_x))
    run = _compiled() if kernel == "numba" else _kernel
    run(np.ascontiguousarray(station), np.ascontiguousarray(flap), model.x, model.w, f0, f1,
        p, sm, nm, h, total, dfz, forces, fz)
    return total, dfz, forces, fz


@functools.cache
def _compiled():
    """:func:`_kernel` compiled by numba (cached on disk), on first use."""
    import numba

    return numba.njit(cache=True, nogil=True)(_kernel)


def _kernel(station, flap, x, w, f0, f1, p, sm, nm, h, total, dfz, forces, fz):
    """The loop over azimuths, stations and seeds; per seed the arithmetic of
    :func:`~tefcore.model.station_terms.station_terms` at one station in its
    order (section loads, airloads, the flap's equation), with the first-order
    complex-step forms of sin, cos, arctan and sqrt.  Compiled by numba; it
    runs as Python too (slowly)."""
    n_psi, n_x = station.shape[1], station.shape[2]
    v = np.zeros(15, np.complex128)
    rho, chd, ax, d, clip = p[6], p[7], p[8], p[22], p[26]
    ih, sf, eta = p[23], p[24], p[25]
    ipe = ih - sf * eta
    b = 0.5 * chd
    a = 2.0 * ax - 1.0
    rb2 = rho * b * b
    for m in range(n_psi):
        for s_ in range(n_x):
            on = f0 <= s_ < f1
            xs, wq = x[s_], w[s_]
            for k in range(6):
                v[k] = station[k, m, s_]
            for k in range(9):
                v[6 + k] = flap[k, m, s_ - f0] if on else 0.0
            for k in range(15 if on else 6):
                v[k] += 1j * h
                theta, theta_d, theta_dd, ut, up, wdd = v[0], v[1], v[2], v[3], v[4], v[5]
                dl, dld, dldd = v[6], v[7], v[8]
                sign = 1.0 if ut.real > 0 else (-1.0 if ut.real < 0 else 0.0)
                z = ut * ut + up * up
                r = math.sqrt(z.real)
                speed = complex(r, z.imag * (0.5 / r))
                z = up / ut
                al = theta - complex(math.atan(z.real), z.imag * (1.0 / (1.0 + z.real * z.real)))
                ar, aa, pa = theta_d * p[0], theta_dd * p[1], wdd * p[2]
                dr, da = dld * p[0], dldd * p[1]
                u = speed * p[3]
                mach = speed * (p[3] / p[9])
                mc = min(mach.real, clip)
                pgr = 1.0 / math.sqrt(1.0 - mc * mc)
                pg = complex(pgr, 0.0 if mach.real > clip else mach.imag * mach.real * pgr ** 3)
                if p[10] == 0.0:
                    pg = complex(1.0, 0.0)
                # section_loads: static coefficients at the 3/4-chord angle of attack
                q = 0.5 * rho * u * u
                ae = al - 0.0 / u + (b * (0.5 - a)) * ar / u
                pg2 = pg * p[11]
                cl = pg2 * (p[12] * ae + p[13] * dl)
                cd = p[18] + p[19] * ae + p[20] * ae * ae
                cm = p[21] + pg2 * (p[14] * ae + p[15] * dl)
                ch = pg2 * (p[16] * ae + p[17] * dl)
                qc, qcc = q * chd, q * (chd * chd)
                lift, drag = qc * cl, qc * cd
                moment = qcc * (cm + cl * (ax - 0.25))
                hinge = qcc * ch
                circ = pg * p[11] * rho * u * b * b
                # the circulatory (pc) and apparent-mass (pn) increments, k = 0 .. 3
                pc0 = circ * (ar * (0.5 * sm[0, 0] - sm[1, 0]) + dr * (d * sm[2, 0] - sm[3, 0]))
                pc1 = circ * (ar * (0.5 * sm[0, 1] - sm[1, 1]) + dr * (d * sm[2, 1] - sm[3, 1]))
                pc2 = circ * (ar * (0.5 * sm[0, 2] - sm[1, 2]) + dr * (d * sm[2, 2] - sm[3, 2]))
                pc3 = circ * (ar * (0.5 * sm[0, 3] - sm[1, 3]) + dr * (d * sm[2, 3] - sm[3, 3]))
                pua = pa - u * ar
                pn0 = rb2 * (pua * nm[0, 0] + aa * (b * (a * nm[0, 0] - nm[1, 0]))
                             + (b * d * nm[2, 0] - b * nm[3, 0]) * da - u * dr * nm[2, 0])
                pn1 = rb2 * (pua * nm[0, 1] + aa * (b * (a * nm[0, 1] - nm[1, 1]))
                             + (b * d * nm[2, 1] - b * nm[3, 1]) * da - u * dr * nm[2, 1])
                pn2 = rb2 * (pua * nm[0, 2] + aa * (b * (a * nm[0, 2] - nm[1, 2]))
                             + (b * d * nm[2, 2] - b * nm[3, 2]) * da - u * dr * nm[2, 2])
                pn3 = rb2 * (pua * nm[0, 3] + aa * (b * (a * nm[0, 3] - nm[1, 3]))
                             + (b * d * nm[2, 3] - b * nm[3, 3]) * da - u * dr * nm[2, 3])
                lift = lift + pc0 + pn0
                moment = moment - b * (pc1 - a * pc0) - b * (pn1 - a * pn0)
                hinge = hinge - b * (pc3 - d * pc2) - b * (pn3 - d * pn2)
                # airload_terms
                cphi, sphi = ut * sign / speed, sign * up / speed
                lift, drag = sign * lift / p[4], sign * drag / p[4]
                moment = sign * moment / p[5]
                f_z = (lift * cphi - drag * sphi) * wq
                f_y = -(lift * sphi + drag * cphi) * wq
                out_w, out_v, out_phi = -f_z, -f_y, -(moment * wq)
                out_dw = out_dv = out_flap = complex(0.0, 0.0)
                if on:
                    # flap_moments: the flap's reactions on the blade and its own row
                    slope, lv, ldv, lvdd, ldvd, ldwd = v[9], v[10], v[11], v[12], v[13], v[14]
                    c = complex(math.cos(theta.real), theta.imag * -math.sin(theta.real))
                    s = complex(math.sin(theta.real), theta.imag * math.cos(theta.real))
                    cdl = complex(math.cos(dl.real), dl.imag * -math.sin(dl.real))
                    sdl = complex(math.sin(dl.real), dl.imag * math.cos(dl.real))
                    s_f, c_f = s * cdl + c * sdl, c * cdl - s * sdl
                    s2, c2 = 2 * s * c, c * c - s * s
                    m_cf = ih * (s_f * c_f - s * c) - eta * sf * ((s2 * cdl + c2 * sdl) - s2)
                    prop = ih * s_f * c_f - sf * eta * c * s_f
                    centrifugal = prop - sf * xs * (slope * c - ldv * s) - sf * lv * s
                    coriolis = ipe * (ldvd * s2 + ldwd * (1 - c2))
                    hinge_row = sign * hinge / p[5]
                    out_w += -sf * c * dldd * wq
                    out_v += sf * s * dldd * wq + (-sf * s * dl) * wq
                    out_phi += ipe * dldd * wq + m_cf * wq
                    out_dw = (-sf * xs * c * dl) * wq + (-2 * ipe * s * s * dld) * wq
                    out_dv = (sf * xs * s * dl) * wq + (-2 * ipe * s * c * dld) * wq
                    out_flap = (ih * dldd * wq + ipe * theta_dd * wq
                                + (-sf * (wdd * c - lvdd * s)) * wq + centrifugal * wq
                                + coriolis * wq + (-hinge_row) * wq)
                v[k] = v[k].real
                total[0, k, m, s_] = out_w.imag / h
                total[1, k, m, s_] = out_dw.imag / h
                total[2, k, m, s_] = out_v.imag / h
                total[3, k, m, s_] = out_dv.imag / h
                total[4, k, m, s_] = out_phi.imag / h
                total[5, k, m, s_] = out_flap.imag / h
                if k == 0:
                    forces[0, m, s_], forces[1, m, s_] = out_w.real, out_dw.real
                    forces[2, m, s_], forces[3, m, s_] = out_v.real, out_dv.real
                    forces[4, m, s_], forces[5, m, s_] = out_phi.real, out_flap.real
                dfz[k, m, s_] = f_z.imag / h
                if k == 0:
                    fz[m, s_] = f_z.real
