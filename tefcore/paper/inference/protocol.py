"""The inference protocol, declared before a study runs: fitted and held-out claims, readings.

``tefcore/data/inference/protocol.toml`` states which claims a study fits
(the calibration claims and whole figures chosen by a stated rule), which it
holds out (every other validation claim), how the paper's "TEF" is read, and
the objective.  :func:`load_protocol` reads it; :meth:`Protocol.split` splits
a claim list; :func:`read_claims` gives the claims as one reading of the mode
names reads them.

Examples
--------
>>> from tefcore.paper.claims.reference import load_claims
>>> p = load_protocol()
>>> fit, held = p.split(load_claims())
>>> len(fit), len(held), p.readings
(28, 36, ('continued', 'flutter'))
>>> sorted({c.figure for c in held})[:3]
['fig10', 'fig11', 'fig13']
"""

from __future__ import annotations

import dataclasses
import tomllib
from dataclasses import dataclass
from functools import cache
from importlib import resources
from pathlib import Path

__all__ = ["READINGS", "SAMPLERS", "Protocol", "inference_file", "load_protocol", "read_claims"]

#: The readings of the paper's "TEF": the continued root, or the flutter root.
READINGS = ("continued", "flutter")

#: The samplers a study may use (:func:`tefcore.paper.inference.study.make_sampler`).
SAMPLERS = ("tpe", "qmc", "random", "nsga2")


@dataclass(frozen=True)
class Protocol:
    """What a study fits and holds out, how it reads the TEF, what it maximises.

    Parameters
    ----------
    space : str
        The space file (``tefcore/data/inference/<space>.toml``).
    fit_calibration : bool
        The calibration claims are fitted.
    fit_figures : tuple of str
        Whole figures whose validation claims are fitted.
    readings : tuple of str
        The readings studied (:data:`READINGS`), side by side.
    flutter_quantities : tuple of str
        The quantities on which the ``flutter`` reading puts the flutter root
        in the TEF's place.
    torsion : str
        ``"recalibrated"``: the torsion level is re-fitted to the stated
        frequencies for every sample; ``"fixed"``: the baseline's is kept.
    objective : str
        ``"sum_tanh_margin"``.
    ambiguous_value, no_margin_fail_value : float
        What an ambiguous claim and a failed claim without a margin (or one
        whose figure is not computable) add to the objective.
    refine : bool
        Refine the sweeps' mode identity between points in the study.
    """

    space: str
    fit_calibration: bool
    fit_figures: tuple
    readings: tuple
    flutter_quantities: tuple
    torsion: str
    objective: str
    ambiguous_value: float
    no_margin_fail_value: float
    refine: bool

    def is_fitted(self, claim) -> bool:
        """True for a claim the study fits (a calibration claim, or one of a fitted figure)."""
        if claim.tag == "calibration":
            return self.fit_calibration
        return claim.figure in self.fit_figures

    def split(self, claims, without=()) -> tuple[list, list]:
        """(fitted, held out) claims, in their order; `without`: figures left out of the fit.

        Parameters
        ----------
        claims : iterable of Claim
            Every claim (:func:`tefcore.paper.claims.reference.load_claims`).
        without : iterable of str
            Figures whose claims are held out too (leave-one-figure-out).

        Returns
        -------
        tuple of (list, list)
            The fitted claims (never a ``not_reproducible`` one: it has no
            check) and the held-out claims.
        """
        leave = set(without)
        fit, held = [], []
        for c in claims:
            keep = (self.is_fitted(c) and c.kind != "not_reproducible"
                    and (c.tag == "calibration" or c.figure not in leave))
            (fit if keep else held).append(c)
        return fit, held


def read_claims(claims, reading: str, quantities=("real_part", "damping", "damping_ratio")):
    """The claims as the `reading` of the paper's mode names reads them.

    Parameters
    ----------
    claims : iterable of Claim
        The claims (:func:`tefcore.paper.claims.reference.load_claims`).
    reading : {"continued", "flutter"}
        ``continued``: unchanged (the root the uncoupled flap mode continues
        into); ``flutter``: the flutter root
        (:data:`tefcore.modes.roles.FLUTTER_ROOT`) in the TEF's place,
        as ``mode`` and as ``other_mode``, on the stability `quantities`.
    quantities : tuple of str
        The quantities the flutter reading applies to.

    Returns
    -------
    list of Claim

    Examples
    --------
    >>> from tefcore.paper.claims.reference import load_claims
    >>> c = [c for c in load_claims() if c.id == "fig17-tef-more-unstable-with-speed"]
    >>> read_claims(c, "flutter")[0].mode
    'flutter root'
    """
    if reading not in READINGS:
        raise ValueError(f"reading = {reading!r} is not one of {', '.join(READINGS)}")
    if reading == "continued":
        return list(claims)
    from ...modes.roles import FLUTTER_ROOT  # numpy: not imported at the CLI's start

    out = []
    for c in claims:
        q = {"mode": c.quantity, "other_mode": c.other_quantity or c.quantity}
        swap = {k: FLUTTER_ROOT for k in q if getattr(c, k) == "TEF" and q[k] in quantities}
        out.append(dataclasses.replace(c, **swap) if swap else c)
    return out


def inference_file(name: str) -> str:
    """The text of a packaged inference file, or of a ``.toml`` path.

    Parameters
    ----------
    name : str
        ``tefcore/data/inference/<name>.toml``, or a path ending in ``.toml``.

    Returns
    -------
    str
    """
    if name.endswith(".toml"):
        return Path(name).read_text(encoding="utf-8")
    return resources.files("tefcore.data").joinpath(f"inference/{name}.toml").read_text(
        encoding="utf-8")


@cache
def load_protocol(name: str = "protocol") -> Protocol:
    """The packaged protocol ``tefcore/data/inference/<name>.toml`` (or a ``.toml`` path).

    Raises
    ------
    ValueError
        An unknown reading, objective or torsion treatment, or a fitted
        figure tefcore does not compute.
    """
    from ..figures.catalogue import KNOWN_FIGURES

    raw = tomllib.loads(inference_file(name))
    p = Protocol(space=raw["space"], fit_calibration=bool(raw["fit_calibration"]),
                 fit_figures=tuple(raw["fit_figures"]), readings=tuple(raw["readings"]),
                 flutter_quantities=tuple(raw["flutter_quantities"]), torsion=raw["torsion"],
                 objective=raw["objective"], ambiguous_value=float(raw["ambiguous_value"]),
                 no_margin_fail_value=float(raw["no_margin_fail_value"]),
                 refine=bool(raw["refine"]))
    bad = [r for r in p.readings if r not in READINGS]
    if bad:
        raise ValueError(f"{name}.toml: readings {bad} not in {READINGS}")
    if p.objective != "sum_tanh_margin":
        raise ValueError(f"{name}.toml: objective = {p.objective!r}; known: sum_tanh_margin")
    if p.torsion not in ("recalibrated", "fixed"):
        raise ValueError(f"{name}.toml: torsion = {p.torsion!r}; known: recalibrated, fixed")
    unknown = [f for f in p.fit_figures if f not in KNOWN_FIGURES]
    if unknown:
        raise ValueError(f"{name}.toml: fit_figures {unknown} are not figures tefcore computes")
    return p
