"""The flap inside its blade section: lumping rule and inertia checks (docs/theory.md §2.7).

The paper lumps "the actuator and flap mass ... into the baseline blade mass so
that the blade sectional structural properties reflect the entire section".
tefcore follows it literally:

* The blade tables (``blade.mass``, ``blade.cg_offset``, ``blade.im_lag +
  blade.im_flap``) are **whole sections**, the flap included, with the flap
  **mass-balanced** (its CG on its hinge), the design state of the MD900 flap.
* The flap's share of a section over the flap span is its mass ``m_f``, its
  first moment ``m_f eta_cg`` and its polar inertia ``I_cg + m_f eta_cg^2``
  about the elastic axis, ``eta_cg = eta_h - c_cg`` its CG ahead of the elastic
  axis.  A flap CG offset ``c_cg`` (``flap.cg_offset``) moves that share aft:
  the section keeps its mass, its first moment changes by ``-S_f``
  (``S_f = m_f c_cg``) and its polar inertia by ``S_f (c_cg - 2 eta_h)``
  (:func:`lumped_section`; the blade structure uses it, the flap equation the
  same ``m_f, S_f, I_h, eta_h``).
* The rest of the section, table minus the balanced flap (the *host*: spar,
  skins, nose ballast, actuator), must be a real body: positive mass and a
  positive polar inertia about its own CG.  That is a bound on the flap:
  ``flap.mass < (A M - S^2) / (I_hinge - I_cg)`` with ``A = I - I_cg`` and
  ``I_hinge`` the section's inertia about the hinge axis
  (:func:`flap_mass_limit`), checked at every station of the flap span when the
  blade or the coupled model is assembled (:func:`check_section_inertia`,
  called by :func:`tefcore.structure.blade.blade_model` and
  :func:`tefcore.model.coupled.coupled_model`; the configuration itself holds
  no physics, so a flap that does not fit is a valid configuration that no
  model can be built from).

Then every per-span mass block of the section and the flap (coordinates
``w, phi, delta``) is positive definite, and so are the assembled
finite-element mass (:func:`check_positive_definite`, called by
:func:`tefcore.structure.blade.blade_model`) and the coupled blade/flap mass
(:func:`check_coupled_mass`, called by :func:`tefcore.model.coupled.coupled_model`);
those two checks can only fail on a bug upstream, and say so.

Examples
--------
>>> from tefcore.config.io import load_config
>>> cfg = load_config("mdart")
>>> round(flap_mass_limit(cfg) / cfg.flap.mass_per_span, 2) > 1   # the baseline flap fits
True
>>> check_section_inertia(cfg.with_overrides({"flap.mass": "1.0 lb/ft"}))  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
ValueError: flap.mass = 1.488 kg/m (1 lb/ft) does not fit in the blade section ...
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg

from ..units import from_si

__all__ = [
    "FlapShare",
    "check_coupled_mass",
    "check_positive_definite",
    "check_section_inertia",
    "coupled_mass_matrix",
    "flap_mass_limit",
    "flap_share",
    "flap_span_mask",
    "host_section",
    "lumped_section",
    "section_mass_block",
]

#: Relative margin for "positive": a determinant below REL_TOL times its scale
#: (M I) counts as zero (round-off of the unit conversions is ~1e-15).
REL_TOL = 1e-9


@dataclass(frozen=True)
class FlapShare:
    """The flap's share of its blade section, per unit span (SI).

    Attributes
    ----------
    mass : float
        ``m_f`` [kg/m].
    first_moment : float
        ``m_f eta_cg`` about the elastic axis, positive ahead [kg].
    inertia : float
        Polar inertia about the elastic axis, ``I_cg + m_f eta_cg^2`` [kg m].
    hinge_from_ea : float
        ``eta_h``, hinge ahead of the elastic axis [m] (negative).
    first_moment_hinge : float
        ``S_f = m_f c_cg`` about the hinge, CG aft positive [kg].
    inertia_hinge : float
        ``I_h = I_cg + m_f c_cg^2`` [kg m].
    """

    mass: float
    first_moment: float
    inertia: float
    hinge_from_ea: float
    first_moment_hinge: float
    inertia_hinge: float


def flap_share(flap, rotor, balanced: bool = False) -> FlapShare:
    """The flap's mass, first moment and polar inertia about the elastic axis.

    Parameters
    ----------
    flap : tefcore.config.sections.FlapConfig
        The flap section (mass, inertia, hinge, chord ratio, CG offset).
    rotor : tefcore.config.sections.RotorConfig
        The rotor section (the chord and the elastic axis).
    balanced : bool
        The share of the mass-balanced flap (CG on the hinge), which the
        blade tables contain, instead of the configured one.

    Examples
    --------
    >>> from tefcore.config.io import load_config
    >>> cfg = load_config("mdart").with_overrides({"flap.cg_offset": 0.33})
    >>> flap, rotor = cfg.flap, cfg.rotor
    >>> cur, bal = flap_share(flap, rotor), flap_share(flap, rotor, balanced=True)
    >>> bool(cur.mass == bal.mass and cur.first_moment < bal.first_moment)   # CG moved aft
    True
    """
    r, f = rotor, flap
    eta = (r.elastic_axis - f.hinge_position) * r.chord
    m = f.mass_per_span
    d = 0.0 if balanced else f.cg_offset * f.chord_ratio * r.chord
    s_f = m * d
    i_h = f.inertia_cg_per_span + m * d * d
    return FlapShare(mass=m, first_moment=m * eta - s_f,
                     inertia=i_h - 2.0 * eta * s_f + m * eta * eta,
                     hinge_from_ea=eta, first_moment_hinge=s_f, inertia_hinge=i_h)


def flap_span_mask(flap, x) -> np.ndarray:
    """True where ``x`` (fractions of R) lies on the flap span ``[inboard, outboard)``.

    Parameters
    ----------
    flap : tefcore.config.sections.FlapConfig
        The flap section (its inboard and outboard edges).
    x : float or array_like
        Radial stations, fractions of R.

    Returns
    -------
    numpy.ndarray of bool
    """
    x = np.asarray(x, float)
    return (x >= flap.inboard) & (x < flap.outboard)


def lumped_section(cfg, x) -> dict[str, np.ndarray]:
    """Section properties at ``x`` with the flap's CG offset lumped in (SI).

    :meth:`tefcore.config.sections.BladeConfig.section` (the tables: whole sections
    with a mass-balanced flap) with, over the flap span, the first moment and
    polar inertia moved by the flap CG offset: ``cg_offset`` changes by
    ``-S_f / m`` and ``im_lag`` by ``S_f (c_cg - 2 eta_h)``.  The flap is thin,
    so its inertia is all chordwise (``im_lag``).  Mass is unchanged.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration: the blade tables, the flap and the rotor's
        chord and elastic axis that place the flap in its section.
    x : float or array_like
        Radial stations, fractions of R.

    Returns
    -------
    dict of str to numpy.ndarray
        The section properties of :meth:`tefcore.config.sections.BladeConfig.section`
        at ``x``.

    Examples
    --------
    >>> from tefcore.config.io import load_config
    >>> cfg = load_config("mdart").with_overrides({"flap.cg_offset": 0.33})
    >>> x = [0.5, cfg.flap.midspan]
    >>> sec, tab = lumped_section(cfg, x), cfg.blade.section(x)
    >>> d = sec["cg_offset"] - tab["cg_offset"]     # off the flap span: 0; on it: aft
    >>> bool(d[0] == 0.0 and d[1] < 0.0)
    True
    """
    sec = cfg.blade.section(x)
    on = flap_span_mask(cfg.flap, x)
    if not on.any():
        return sec
    cur, bal = flap_share(cfg.flap, cfg.rotor), flap_share(cfg.flap, cfg.rotor, balanced=True)
    d_first = cur.first_moment - bal.first_moment
    d_inertia = cur.inertia - bal.inertia
    sec["cg_offset"] = np.where(on, sec["cg_offset"] + d_first / sec["mass"], sec["cg_offset"])
    sec["im_lag"] = np.where(on, sec["im_lag"] + d_inertia, sec["im_lag"])
    return sec


def _check_points(blade, flap) -> np.ndarray:
    """Flap edges and the table stations between them (the host's extremes)."""
    f, st = flap, np.asarray(blade.stations, float)
    inner = st[(st > f.inboard) & (st < f.outboard)]
    # the outboard edge is evaluated just inside the span (the mask is half-open)
    out = np.nextafter(min(f.outboard, 1.0), -np.inf)
    return np.unique(np.concatenate([[f.inboard], inner, [out]]))


def host_section(cfg, x) -> dict[str, np.ndarray]:
    """The section without the (balanced) flap: mass, first moment, polar inertia (SI).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration: the blade tables, the flap and the rotor's
        chord and elastic axis that place the flap in its section.
    x : float or array_like
        Radial stations, fractions of R.

    Returns
    -------
    dict
        ``mass`` [kg/m], ``first_moment`` [kg] (about the elastic axis, ahead
        positive), ``inertia`` [kg m] (polar, about the elastic axis) and
        ``inertia_cg`` [kg m] (about the host's own CG; must be positive).
    """
    sec = cfg.blade.section(x)
    on = flap_span_mask(cfg.flap, x)
    bal = flap_share(cfg.flap, cfg.rotor, balanced=True)
    m = sec["mass"] - on * bal.mass
    s = sec["mass"] * sec["cg_offset"] - on * bal.first_moment
    i = sec["im_lag"] + sec["im_flap"] - on * bal.inertia
    with np.errstate(divide="ignore", invalid="ignore"):
        i_cg = np.where(m > 0, i - s * s / m, -np.inf)
    return {"mass": m, "first_moment": s, "inertia": i, "inertia_cg": i_cg}


def flap_mass_limit(cfg, x=None) -> float:
    """Largest flap mass per span [kg/m] that leaves the host section physical.

    With the section's mass ``M``, first moment ``S`` and polar inertia ``I``
    about the elastic axis, the flap's hinge ``eta_h`` and inertia ``I_cg``,
    the host's ``(M - m)(I - I_cg - m eta_h^2) - (S - m eta_h)^2`` is *linear*
    in the flap mass ``m`` (the ``m^2`` terms cancel), so the bound is
    ``m < (A M - S^2) / (A + M eta_h^2 - 2 S eta_h)``, ``A = I - I_cg``;
    the smallest over the flap span (or over ``x``) is returned.  It is below
    ``M`` whenever the section itself is physical.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration: the blade tables, the flap and the rotor's
        chord and elastic axis that place the flap in its section.
    x : float or array_like, optional
        Stations (fractions of R) to take the bound at; default the flap span
        (its edges and the table stations between).

    Returns
    -------
    float
        The bound [kg/m].
    """
    x = _check_points(cfg.blade, cfg.flap) if x is None else np.atleast_1d(np.asarray(x, float))
    sec = cfg.blade.section(x)
    bal = flap_share(cfg.flap, cfg.rotor, balanced=True)
    big_m, s = sec["mass"], sec["mass"] * sec["cg_offset"]
    a = sec["im_lag"] + sec["im_flap"] - cfg.flap.inertia_cg_per_span
    eta = bal.hinge_from_ea
    return float(np.min((a * big_m - s * s) / (a + big_m * eta**2 - 2.0 * s * eta)))


def _inertia_cg_limit(cfg, x) -> float:
    """Largest flap inertia about its CG per span [kg m] that fits, at the given mass.

    ``cfg``: the whole configuration (blade tables, flap, the rotor's chord and
    elastic axis).
    """
    sec = cfg.blade.section(np.atleast_1d(x))
    bal = flap_share(cfg.flap, cfg.rotor, balanced=True)
    m, eta = bal.mass, bal.hinge_from_ea
    big_m, s = sec["mass"], sec["mass"] * sec["cg_offset"]
    i = sec["im_lag"] + sec["im_flap"]
    with np.errstate(divide="ignore", invalid="ignore"):
        lim = np.where(big_m > m, i - m * eta**2 - (s - m * eta) ** 2 / (big_m - m), -np.inf)
    return float(np.min(lim))


def section_mass_block(cfg, x) -> np.ndarray:
    """Per-span mass matrices in ``(w, phi, delta)`` of host plus flap at ``x`` (SI).

    The host contributes ``[[m_h, s_h], [s_h, I_h]]`` in ``(w, phi)``; the flap
    (points ``s`` aft of the hinge move by ``w + (eta_h - s) phi - s delta``) the
    Gram matrix of ``(1, eta_h - s, -s)`` under its mass:
    ``[[m_f, m_f eta_h - S_f, -S_f], [., m_f eta_h^2 - 2 eta_h S_f + I_h, I_h - eta_h S_f],
    [., ., I_h]]``.  Off the flap span only the host (the whole section) and a
    zero flap row remain.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration: the blade tables, the flap and the rotor's
        chord and elastic axis that place the flap in its section.
    x : float or array_like
        Radial stations, fractions of R.

    Returns
    -------
    ndarray, shape (len(x), 3, 3)
    """
    x = np.atleast_1d(np.asarray(x, float))
    host = host_section(cfg, x)
    on = flap_span_mask(cfg.flap, x).astype(float)
    fl = flap_share(cfg.flap, cfg.rotor)
    eta, m, s_f, i_h = fl.hinge_from_ea, fl.mass, fl.first_moment_hinge, fl.inertia_hinge
    flap = np.array([[m, m * eta - s_f, -s_f],
                     [m * eta - s_f, m * eta**2 - 2 * eta * s_f + i_h, i_h - eta * s_f],
                     [-s_f, i_h - eta * s_f, i_h]])
    out = on[:, None, None] * flap[None]
    out[:, 0, 0] += host["mass"]
    out[:, 0, 1] += host["first_moment"]
    out[:, 1, 0] += host["first_moment"]
    out[:, 1, 1] += host["inertia"]
    return out


def _lbft(kg_per_m: float) -> str:
    return f"{from_si(kg_per_m, 'lb/ft', 'mass_per_length'):.3g} lb/ft"


def check_section_inertia(cfg) -> None:
    """Raise ``ValueError`` unless every blade section and the flap in it are physical.

    1. Each tabulated section: ``blade.im_lag + blade.im_flap > blade.mass *
       blade.cg_offset^2`` (positive inertia about its CG).
    2. Over the flap span (edges and table stations between): the host, section
       minus the balanced flap, has positive mass and inertia about its CG
       (:func:`flap_mass_limit` gives the bound on ``flap.mass``).
    3. With the dynamic flap: the per-span ``(w, phi, delta)`` mass block at the
       configured CG offset is positive definite (it needs ``I_h > 0``).

    Cost: a few dozen flops per station (no assembly); called where the blade
    and the coupled model are assembled, and by the batch file's checks before
    anything runs (:mod:`tefcore.paper.run.batch_spec`).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration: the blade tables, the flap, the rotor's chord
        and elastic axis that place it, and ``model.tef``.

    Raises
    ------
    ValueError
        Naming the station, the fields and the bound (e.g. the largest flap
        mass that fits).
    """
    b = cfg.blade
    st = np.asarray(b.stations, float)
    sec = b.section(st)
    i_tot = sec["im_lag"] + sec["im_flap"]
    need = sec["mass"] * sec["cg_offset"] ** 2
    bad = np.flatnonzero(i_tot - need <= REL_TOL * i_tot)
    if bad.size:
        k = int(bad[0])
        raise ValueError(
            f"blade.im_lag + blade.im_flap = {i_tot[k]:.4g} kg m at blade.stations[{k}] = "
            f"{st[k]:.4g} is not above blade.mass * blade.cg_offset^2 = {need[k]:.4g} kg m: a "
            "section's polar inertia about the elastic axis must exceed its mass times the "
            "CG offset squared (positive inertia about its own CG)")
    xs = _check_points(b, cfg.flap)
    host = host_section(cfg, xs)
    tab = b.section(xs)
    scale = tab["mass"] * (tab["im_lag"] + tab["im_flap"])
    det = host["mass"] * host["inertia"] - host["first_moment"] ** 2
    bad = np.flatnonzero((host["mass"] <= 0) | (det <= REL_TOL * scale))
    if bad.size:
        with np.errstate(divide="ignore", invalid="ignore"):   # scale underflows to 0
            ratio = det[bad] / scale[bad]
        k = int(bad[np.argmin(np.where(np.isfinite(ratio), ratio, -np.inf))])
        f, bal = cfg.flap, flap_share(cfg.flap, cfg.rotor, balanced=True)
        m_max = flap_mass_limit(cfg, xs[k])
        i_max = _inertia_cg_limit(cfg, xs[k])
        scaled = ""
        if f.chord_scale != 1.0:
            scaled = (f" (per span at flap.chord_ratio = {f.chord_ratio:.4g}, scaled from "
                      f"flap.reference_chord_ratio = {f.reference_chord_ratio:.4g} by "
                      f"flap.scaling = {f.scaling!r})")
        i_hint = (f"or flap.inertia_cg < {i_max / f.chord_scale**3:.4g} kg m at this mass"
                  if i_max > 0 else "and no flap.inertia_cg fits at this mass")
        raise ValueError(
            f"flap.mass = {f.mass:.4g} kg/m ({_lbft(f.mass)}) does not fit in the blade section "
            f"at x = {xs[k]:.4f} R{scaled}: with flap.inertia_cg = {f.inertia_cg:.4g} kg m and "
            f"the hinge {-bal.hinge_from_ea:.4g} m aft of the elastic axis the flap's polar "
            f"inertia about the elastic axis is {bal.inertia:.4g} kg m of the section's "
            f"{tab['im_lag'][k] + tab['im_flap'][k]:.4g} kg m (blade.im_lag + blade.im_flap), "
            f"which leaves the rest of the section (blade.mass - flap.mass = "
            f"{host['mass'][k]:.4g} kg/m) a non-positive inertia about its own CG "
            f"({host['inertia_cg'][k]:.3g} kg m). Allowed here: flap.mass < "
            f"{m_max / f.chord_scale:.4g} kg/m ({_lbft(m_max / f.chord_scale)}) at this "
            f"inertia, {i_hint}")
    if cfg.model.tef == "dynamic":
        block = section_mass_block(cfg, xs)
        low = np.linalg.eigvalsh(block)[:, 0]
        top = np.abs(block).max(axis=(1, 2))
        bad = np.flatnonzero(low <= REL_TOL * REL_TOL * top)
        if bad.size:
            k = int(bad[0])
            fl = flap_share(cfg.flap, cfg.rotor)
            raise ValueError(
                f"the per-span mass block (w, phi, delta) of section and flap at x = "
                f"{xs[k]:.4f} R is not positive definite (smallest eigenvalue {low[k]:.3g}): "
                f"the flap's inertia about its hinge, flap.inertia_cg + flap.mass * "
                f"(flap.cg_offset c_f)^2 = {fl.inertia_hinge:.4g} kg m, must be positive "
                "for the flap degree of freedom (model.tef = 'dynamic')")


def check_positive_definite(matrix, what: str, fields: str) -> None:
    """Raise ``ValueError`` unless the symmetric ``matrix`` is positive definite.

    A Cholesky factorisation (the cheapest test). ``what`` names the matrix
    and ``fields`` the configuration fields that build it, for the message.

    Parameters
    ----------
    matrix : array_like
        A symmetric matrix.
    what : str
        What it is, for the message (``"the coupled mass matrix"``).
    fields : str
        The configuration fields that build it, for the message.

    Raises
    ------
    ValueError
        With the smallest eigenvalue.

    Examples
    --------
    >>> check_positive_definite(np.eye(2), "a mass matrix", "blade.mass")
    >>> check_positive_definite(np.diag([1.0, -1e-3]), "M", "blade.mass")
    Traceback (most recent call last):
    ...
    ValueError: M is not positive definite (smallest eigenvalue -0.001); check blade.mass
    """
    a = np.asarray(matrix, float)
    try:
        scipy.linalg.cholesky(0.5 * (a + a.T), check_finite=True)
    except (np.linalg.LinAlgError, ValueError):
        low = float(np.linalg.eigvalsh(0.5 * (a + a.T))[0]) if np.isfinite(a).all() else np.nan
        raise ValueError(f"{what} is not positive definite (smallest eigenvalue {low:.3g}); "
                         f"check {fields}") from None


def coupled_mass_matrix(model) -> np.ndarray:
    """Structural mass matrix of the coupled blade modes and flap, rotor units.

    ``M_RR`` is the modal mass (the flap's share is in the sections);
    ``M_RF = M_FR^T = sum_s w_s [-S_f cos(theta) W + S_f sin(theta) V +
    (I_h - S_f eta_h) Phi]`` over the flap stations and ``M_FF = I_h b_f + I_a``
    (``I_a`` the actuator's reflected inertia, which moves with the flap only):
    the ``delta**`` terms of the flap reactions and the flap equation of
    :class:`tefcore.model.coupled.CoupledModel` at the pitch the modes were computed
    for (aerodynamic apparent mass excluded).

    Parameters
    ----------
    model : tefcore.model.coupled.CoupledModel
        The coupled model.

    Returns
    -------
    numpy.ndarray
        ``(n_modes + 1, n_modes + 1)`` with the flap, ``(n_modes, n_modes)``
        without.
    """
    m_s = np.asarray(model.m_s, float)
    if not model.has_flap:
        return m_s
    fs, f = model.flap_stations, model.flap
    x, wf = model.x[fs], model.w[fs]
    th = model.modes.beam.pitch(x)
    sf, ih, eta = f["first_moment"], f["inertia_hinge"], f["hinge_from_ea"]
    sh = {k: model.shapes[k][fs] for k in ("w", "v", "phi")}
    coupling = (wf * (-sf * np.cos(th))) @ sh["w"] + (wf * sf * np.sin(th)) @ sh["v"] \
        + (wf * (ih - sf * eta)) @ sh["phi"]
    n = m_s.shape[0]
    out = np.zeros((n + 1, n + 1))
    out[:n, :n] = m_s
    out[:n, n] = out[n, :n] = coupling
    out[n, n] = ih * wf.sum() + f.get("reflected_inertia", 0.0)
    return out


def check_coupled_mass(model) -> None:
    """Raise ``ValueError`` unless :func:`coupled_mass_matrix` is positive definite.

    With the sections checked by :func:`check_section_inertia` it always is
    (the kinetic energy of host plus flap is positive at every station);
    failing here means the modal basis or the flap terms are inconsistent.

    Parameters
    ----------
    model : tefcore.model.coupled.CoupledModel
        The coupled model (its modes and flap).

    Raises
    ------
    ValueError
        Naming the matrix and the fields that build it.
    """
    check_positive_definite(
        coupled_mass_matrix(model), "the coupled blade/flap mass matrix",
        "flap.mass, flap.inertia_cg, flap.cg_offset against blade.mass, blade.im_lag, "
        "blade.im_flap, blade.cg_offset (the flap must be part of its blade section)")
