"""The paper-replication layer: figures, claims, validation, notebooks, report.

The solver (``tefcore``) knows nothing of the paper; this subpackage defines
the paper's figures as analyses, loads what the paper states about them
(reference data and claims), checks the claims, and reproduces the figures
through notebooks into a report.  Its modules (import each by name; the
package itself exports nothing)::

    figures         Figs. 3-17 as analyses: swept field and caption; flap responses (5-7)
    figure_runs     a figure's configuration and sweep values as the notebooks run them
    figure_frames   any figure's result as one long table with an x column
    reference       the paper's claims and digitised curves, loaded and checked
    curve_metrics   zero crossings, stability intervals, digitised-curve comparison
    claim_checks    one check per kind of claim, against one figure's result
    validation      run every figure with a claim, check all claims, compare with records
    calibration     stated first-torsion frequencies (Figs. 10a, 11a) and the fit to them
    fig6_calibration  the actuator's reflected inertia fitted to Fig. 6 (mdart-fig6), the conflict
    variants        the packaged variants (mdart, mdart-fig6): tags, records, differences
    variant_runs    reproduce's check of the other variant's claims, beside the notebooks
    modal_truncation  the imbalanced flap's flutter versus the blade modes retained
    assumptions     each assumed MDART property and the plausible range it is varied over
    sensitivity     headline results with each assumption at its range's ends (tornado)
    attribution     why we differ: what would flip each failing claim, within plausible ranges
    attribution_levers  the assumptions and model options it moves, the Fig. 6 inertia hook
    attribution_eval    a claim's own check on a moved configuration, on its deciding points
    attribution_search  the bisection of a lever for one claim, confirmation, conflicts
    plotting        tracked modes, root loci, participation on the paper's axes; byte-stable PNGs
    captions        figure titles and captions written from the configuration run
    summaries       rounded, deterministic printed tables for cells nbval checks
    departures      where the compact model departs from the paper's UMARC analysis
    explorer        interactive Floquet root map with sliders (static without widgets)
    notebook_tools  everything the notebooks use, imported as nt
    notebook_files  the shipped numbered notebooks: names, figures, parameters, copies
    run_params      notebook parameters from a YAML file and -p options, in layers
    reproduce       tefcore reproduce: run the notebooks, check claims, write report
    report          the reproduction report as one model, to markdown and HTML
    batch_spec      the batch file: named runs, parameters, grids, checked before running
    batch_state     what decided a batch run's results: skip, recompute or refuse (stale)
    batch           tefcore batch: every run's notebooks in one pool, resumable
    batch_report    the batch's comparison: runs side by side, headlines, overlaid curves
    commands        the reproduce, batch and notebooks subcommands of the tefcore CLI
"""

__all__: list[str] = []
