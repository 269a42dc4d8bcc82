"""The paper-replication layer: the paper's figures, its claims, why we differ, running it.

The solver (``tefcore``) knows nothing of the paper; this package defines the
paper's figures as analyses, loads what the paper states about them and checks
it, attributes each disagreement to the assumed properties, and reproduces the
figures through notebooks into a report.  Its rooms, bottom up (each room's
``__init__`` lists its modules and the names it offers)::

    figures/      Figs. 3-17: what each sweeps, how it is run, tabled, drawn, captioned
    claims/       the paper's statements, their checks and validation, the variants
    attribution/  the assumed properties, their ranges, and what flips each failing claim
    run/          the reproduction, its report, batches, notebook kernels, the subcommands
    notebooks/    the numbered notebooks (jupytext sources and executed ``.ipynb``)

and the modules that are one thing each::

    calibration       the stated first-torsion frequencies (Figs. 10a, 11a) and the fit to them
    fig6_calibration  the actuator's reflected inertia fitted to Fig. 6 (mdart-fig6)
    summaries         rounded, deterministic printed tables for the cells nbval checks
    explorer          the Floquet root map with sliders (static without widgets)
    explorer_app      the explorer as a web page (``tefcore explore``)
    notebook_tools    everything the notebooks use, imported as ``nt``

Imports run down this list: ``figures`` and ``calibration`` import no other
part of the paper, ``claims`` reads ``figures``, ``attribution`` reads both, and
``run`` sits on top (``tests/test_architecture.py`` checks it).

Examples
--------
>>> from tefcore.paper import claims, figures
>>> figures.FIGURES["fig9"].parameter
'flap.cg_offset'
>>> sum(c.tag == "validation" for c in claims.load_claims())
58
"""

__all__: list[str] = []
