"""Running the paper: notebooks, the reproduction and its report, batches.

Its modules, bottom up::

    notebook_files  the shipped numbered notebooks: names, figures, parameters, copies
    yaml_input      YAML parameter files read safely
    params          notebook parameters from a YAML file and -p options, in layers
    kernels         warm Jupyter kernels that run several notebooks each
    kernel_guard    the notebook kernels a run started, stopped with it
    output_folder   the reproduction's output folder: checked, locked, swapped in whole
    outcome         what the claims are compared with: the records, or a what-if's last run
    notebook_page   an executed notebook as an HTML page that reads offline
    variant_runs    the other packaged variant's claims, in a process beside the notebooks
    report          the reproduction report as one model, to markdown and HTML
    reproduce       ``tefcore reproduce``: run the notebooks, check claims, write the report
    batch_spec      the batch file: named runs, parameters, grids, checked before running
    batch_state     what decided a batch run's results: skip, recompute or refuse (stale)
    batch_report    the batch's comparison: runs side by side, headlines, overlaid curves
    batch           ``tefcore batch``: every run's notebooks in one pool, resumable
    commands        the reproduce, batch and notebooks subcommands of the tefcore command
"""

import sys

from ...faces import lazy_face

#: Public name -> the module that defines it (loaded on first use).
API = {
    "NOTEBOOKS": "tefcore.paper.run.notebook_files",
    "copy_notebooks": "tefcore.paper.run.notebook_files",
    "notebooks_dir": "tefcore.paper.run.notebook_files",
    "build_report": "tefcore.paper.run.report",
    "write_report": "tefcore.paper.run.report",
}

__all__ = list(API)
__getattr__, __dir__ = lazy_face(sys.modules[__name__], API)
