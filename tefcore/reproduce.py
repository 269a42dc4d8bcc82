"""``tefcore reproduce``: run the numbered notebooks and write the claims report.

Two halves:

* **Runner** (:func:`reproduce`): executes ``notebooks/01_*.ipynb`` ...
  ``07_*.ipynb`` with papermill into an output folder, each with its own
  parameters (:func:`parse_cli_params`, :func:`load_params_file`,
  :func:`notebook_parameters`), then collects the claims tables and figures
  the notebooks wrote and writes ``report.md`` and a self-contained
  ``report.html`` (figures embedded as base64 PNG).  The exit code is
  non-zero when a notebook fails or a validation claim is worse than its
  recorded status (:func:`tefcore.validation.worse_than_recorded`).
* **Notebook helpers** (``setup_notebook``, ``figure_values``,
  ``run_stability_figure``, ``plot_modes``, ``mode_summary``,
  ``claims_table`` ...): the few functions every notebook shares, so the
  notebooks stay short and compute, plot and save the same way.

Output layout (``--out OUT``)::

    OUT/report.md, OUT/report.html, OUT/claims.csv
    OUT/mdart_modes.csv, OUT/mdart_frequency_checks.csv, OUT/mdart_fanplot.png
    OUT/notebooks/<name>.ipynb        executed notebooks
    OUT/<name>/                       each notebook's CSVs, PNGs and claims.csv

Parameters (YAML file, ``--params``)::

    all:                      # every notebook
      n_jobs: 2
    03_overhang:              # one notebook (also "03" or "03_overhang.ipynb")
      n_points: 8

and on the command line ``-p name value`` (all notebooks) or
``-p 03_overhang:name value`` (one).  Values are YAML (``-p n_points 5``
gives an int, ``-p overrides "{flight.ct_sigma: 0.08}"`` a dict).
Precedence: file ``all`` < file per notebook < ``-p`` all < ``-p`` per
notebook.

Examples
--------
>>> parse_cli_params([("n_jobs", "2"), ("03:n_points", "5")])
{'all': {'n_jobs': 2}, '03_overhang': {'n_points': 5}}
>>> merged = merge_params({"all": {"n_jobs": 1, "n_points": 4}},
...                       {"03_overhang": {"n_points": 6}})
>>> merged["03_overhang"], merged["04_cg_offset"]
({'n_jobs': 1, 'n_points': 6}, {'n_jobs': 1, 'n_points': 4})
>>> figure_values("fig11", 3)
[0.75, 1.375, 2.0]
>>> figure_values("fig10", 3)
['150 lb/in', '475 lb/in', '800 lb/in']
"""

from __future__ import annotations

import base64
import html
import math
import os
import re
import sys
import time
import warnings
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd

#: The notebooks, in order.
NOTEBOOKS = (
    "01_baseline_mdart_correlation",
    "02_hinge_moments_and_flap_response",
    "03_overhang",
    "04_cg_offset",
    "05_stiffness",
    "06_size_and_location",
    "07_flight_condition",
)
#: Which paper figures each notebook reproduces.
NOTEBOOK_FIGURES = {
    "01_baseline_mdart_correlation": ("fig3", "fig4"),
    "02_hinge_moments_and_flap_response": ("fig5", "fig6"),
    "03_overhang": ("fig7", "fig8"),
    "04_cg_offset": ("fig9",),
    "05_stiffness": ("fig10", "fig11", "fig12"),
    "06_size_and_location": ("fig13", "fig14", "fig15"),
    "07_flight_condition": ("fig16a", "fig16b", "fig17"),
}
KERNEL_NAME = "python3"
STATUS_ORDER = {"pass": 0, "not reproducible": 1, "fail": 2}


# ====================================================================== runner


def notebooks_dir() -> Path:
    """Folder of the numbered notebooks (``$TEFCORE_NOTEBOOKS`` or ``<repo>/notebooks``)."""
    env = os.environ.get("TEFCORE_NOTEBOOKS")
    if env:
        return Path(env).resolve()
    repo = (Path(__file__).resolve().parent.parent / "notebooks").resolve()
    if repo.is_dir() or not (Path.cwd() / "notebooks").is_dir():
        return repo
    return (Path.cwd() / "notebooks").resolve()     # a non-editable install, run from a clone


def resolve_notebook(key: str) -> str:
    """Notebook name from ``"03"``, ``"03_overhang"`` or ``"03_overhang.ipynb"``.

    >>> resolve_notebook("5"), resolve_notebook("07_flight_condition.ipynb")
    ('05_stiffness', '07_flight_condition')
    """
    k = str(key).strip().removesuffix(".ipynb")
    if k in NOTEBOOKS:
        return k
    if k.isdigit():
        hits = [n for n in NOTEBOOKS if int(n[:2]) == int(k)]
    else:
        hits = [n for n in NOTEBOOKS if n.startswith(k) or n[3:] == k]
    if len(hits) != 1:
        raise ValueError(f"unknown notebook {key!r}; known: {', '.join(NOTEBOOKS)}")
    return hits[0]


def parse_value(text: str):
    """A ``-p`` value as YAML: ``"5"`` -> 5, ``"[0.1, 0.2]"`` -> list, ``"abc"`` -> 'abc'."""
    import yaml

    try:
        return yaml.safe_load(text)
    except yaml.YAMLError:
        return text


def parse_cli_params(pairs) -> dict:
    """``[(name, value), ...]`` from ``-p`` -> ``{"all"|notebook: {name: value}}``."""
    out: dict[str, dict] = {}
    for name, value in pairs or ():
        target, sep, pname = str(name).rpartition(":")
        target = resolve_notebook(target) if sep else "all"
        if not pname.isidentifier():
            raise ValueError(f"-p: parameter name {pname!r} is not an identifier")
        out.setdefault(target, {})[pname] = parse_value(value) if isinstance(value, str) \
            else value
    return out


def load_params_file(path) -> dict:
    """YAML parameters file -> ``{"all"|notebook: {name: value}}`` (keys checked)."""
    import yaml

    data = yaml.safe_load(Path(path).read_text()) or {}
    if not isinstance(data, dict):
        raise ValueError(f"{path}: expected a mapping of notebook (or 'all') to parameters")
    out = {}
    for key, params in data.items():
        if params is None:
            params = {}
        if not isinstance(params, dict):
            raise ValueError(f"{path}: {key!r} must map parameter names to values")
        out["all" if str(key) == "all" else resolve_notebook(str(key))] = dict(params)
    return out


def merge_params(*layers, notebooks=NOTEBOOKS) -> dict:
    """Per-notebook parameters from layers of ``{"all"|notebook: {...}}`` (later wins)."""
    merged = {nb: {} for nb in notebooks}
    for layer in layers:
        for nb in notebooks:
            merged[nb].update((layer or {}).get("all", {}))
            merged[nb].update((layer or {}).get(nb, {}))
    return merged


def _papermill():
    try:
        import papermill
    except ImportError:
        raise SystemExit("tefcore reproduce needs papermill: "
                         "python -m pip install -e \".[notebooks]\"") from None
    return papermill


def notebook_parameters(path) -> dict:
    """Names and defaults of a notebook's ``parameters`` cell (papermill inspection)."""
    papermill = _papermill()

    return {k: v["default"] for k, v in papermill.inspect_notebook(str(path)).items()}


def check_parameters(params: dict, names=NOTEBOOKS, nb_dir: Path | None = None) -> None:
    """Raise ``ValueError`` naming any parameter a notebook does not declare."""
    nb_dir = nb_dir or notebooks_dir()
    for name in names:
        src = nb_dir / f"{name}.ipynb"
        if not src.exists():
            raise ValueError(f"notebook {src} not found")
        known = notebook_parameters(src)
        unknown = sorted(set(params.get(name, {})) - set(known))
        if unknown:
            raise ValueError(f"{name}: unknown parameter(s) {unknown}; "
                             f"the notebook has {sorted(known)}")


def _ensure_kernel(name: str = KERNEL_NAME) -> None:
    """Register the current interpreter's ipykernel as ``name`` if no such kernelspec."""
    from jupyter_client.kernelspec import NoSuchKernel, get_kernel_spec

    try:
        get_kernel_spec(name)
    except NoSuchKernel:
        from ipykernel.kernelspec import install

        install(user=True, kernel_name=name)


@dataclass
class NotebookRun:
    name: str
    status: str = "not run"          # ok | failed
    error: str = ""
    seconds: float = 0.0
    parameters: dict = field(default_factory=dict)


def run_notebooks(out: Path, params: dict, names=NOTEBOOKS, progress: bool = True,
                  nb_dir: Path | None = None, kernel_name: str = KERNEL_NAME) -> list:
    """Execute the notebooks with papermill into ``out``; never raises for a failing one."""
    from tqdm.auto import tqdm

    papermill = _papermill()

    nb_dir = nb_dir or notebooks_dir()
    _ensure_kernel(kernel_name)
    (out / "notebooks").mkdir(parents=True, exist_ok=True)
    check_parameters(params, names, nb_dir)
    runs = []
    bar = tqdm(names, desc="notebooks", unit="nb", disable=not progress, file=sys.stderr)
    for name in bar:
        bar.set_postfix_str(name)
        src = nb_dir / f"{name}.ipynb"
        p = dict(params.get(name, {}))
        p["output_dir"] = str((out / name).resolve())
        run = NotebookRun(name, parameters=p)
        start = time.perf_counter()
        try:
            papermill.execute_notebook(
                str(src), str(out / "notebooks" / f"{name}.ipynb"), parameters=p,
                kernel_name=kernel_name, progress_bar=False, log_output=False,
                cwd=str(nb_dir), extra_arguments=["--IPKernelApp.log_level=ERROR"])
            run.status = "ok"
        except Exception as exc:      # recorded, the other notebooks still run
            run.status = "failed"
            run.error = f"{type(exc).__name__}: {str(exc).strip().splitlines()[-1][:300]}" \
                if str(exc).strip() else type(exc).__name__
        run.seconds = time.perf_counter() - start
        runs.append(run)
    bar.close()
    return runs


def collect_claims(out: Path, names=NOTEBOOKS) -> pd.DataFrame:
    """The claims tables the notebooks wrote (``OUT/<name>/claims.csv``), concatenated."""
    frames = []
    for name in names:
        path = out / name / "claims.csv"
        if path.exists() and path.stat().st_size:
            df = pd.read_csv(path, dtype=str, keep_default_na=False)
            df.insert(0, "notebook", name)
            frames.append(df)
    if not frames:
        return pd.DataFrame(columns=["notebook", "id", "figure", "statement", "expected",
                                     "computed", "status", "reason", "tag",
                                     "recorded_status"])
    return pd.concat(frames, ignore_index=True)


def _validation():
    try:
        from . import validation
    except ImportError:
        return None
    return validation


def regressions(claims: pd.DataFrame) -> pd.DataFrame:
    """Claims whose status is worse than recorded (empty when nothing to compare)."""
    val = _validation()
    if val is None or claims.empty or not hasattr(val, "worse_than_recorded"):
        return claims.iloc[0:0]
    table = claims.drop(columns=["notebook"], errors="ignore")
    worse = val.worse_than_recorded(table)
    return worse if isinstance(worse, pd.DataFrame) else pd.DataFrame(worse)


def score(claims: pd.DataFrame) -> tuple[int, int]:
    """(passed, total) of a claims table."""
    val = _validation()
    if val is not None and hasattr(val, "claims_score") and not claims.empty:
        return tuple(int(v) for v in val.claims_score(
            claims.drop(columns=["notebook"], errors="ignore")))
    st = claims.get("status", pd.Series(dtype=str))
    return int((st == "pass").sum()), int(len(st))


def _baseline_blade(out: Path) -> pd.DataFrame:
    """MDART mode table, stated-frequency checks and fan plot at the top of ``out``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .blade import blade_modes, fan_plot
    from .calibration import frequency_checks
    from .config import load_config

    deterministic_matplotlib()
    cfg = load_config("mdart")
    blade_modes(cfg).table().to_csv(out / "mdart_modes.csv", index=False,
                                    float_format="%.6g")
    checks = frequency_checks(cfg)
    checks.to_csv(out / "mdart_frequency_checks.csv", index=False, float_format="%.6g")
    ax = fan_plot(cfg)
    ax.set_title("MDART blade (assumed properties), coupled modes")
    savefig(ax.figure, out, "mdart_fanplot")
    plt.close(ax.figure)
    return checks


def _img_tag(path: Path, alt: str) -> str:
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    return (f'<figure><img alt="{html.escape(alt)}" src="data:image/png;base64,{data}">'
            f"<figcaption>{html.escape(alt)}</figcaption></figure>")


def _md_table(df: pd.DataFrame) -> str:
    if df.empty:
        return "_(none)_"
    cols = list(df.columns)

    def cell(v):
        return str(v).replace("|", "\\|").replace("\n", " ")

    lines = ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    lines += ["| " + " | ".join(cell(v) for v in row) + " |"
              for row in df.itertuples(index=False)]
    return "\n".join(lines)


_CSS = """body{font-family:system-ui,sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;
color:#222}table{border-collapse:collapse;font-size:0.85em;margin:1em 0}
td,th{border:1px solid #ccc;padding:3px 6px;vertical-align:top}th{background:#f3f3f3}
.pass{background:#e5f5e5}.fail{background:#fbe3e3}.notrep{background:#fff6d6}
figure{display:inline-block;margin:0.5em;max-width:100%}img{max-width:100%}
figcaption{font-size:0.85em;color:#555}code{background:#f3f3f3;padding:0 3px}"""


def claims_summary(claims: pd.DataFrame) -> pd.DataFrame:
    """Per figure and tag: how many claims pass, are not reproducible, fail."""
    if claims.empty:
        return pd.DataFrame(columns=["figure", "tag", "pass", "not reproducible", "fail"])
    t = claims.assign(tag=claims.get("tag", "")).fillna("")
    order = {f: i for i, f in enumerate(dict.fromkeys(t["figure"]))}
    out = (t.groupby(["figure", "tag"], sort=False)["status"].value_counts().unstack(
        fill_value=0).reindex(columns=list(STATUS_ORDER), fill_value=0).reset_index())
    out = out.sort_values(["figure", "tag"], key=lambda c: c.map(order) if c.name == "figure"
                          else c, kind="stable", ignore_index=True)
    out.columns.name = None
    return out


def write_report(out: Path, runs, claims: pd.DataFrame, worse: pd.DataFrame,
                 checks: pd.DataFrame | None = None) -> tuple[Path, Path]:
    """``report.md`` (figures linked) and ``report.html`` (figures embedded)."""
    passed, total = score(claims)
    cols = [c for c in ("id", "figure", "panel", "tag", "status", "recorded_status",
                        "statement", "expected", "computed", "reason") if c in claims.columns]
    shown = claims[cols] if cols else claims
    md = ["# tefcore reproduction report", "",
          "Replication of *Aeroelastic Stability of Trailing-Edge Flap Helicopter Rotors* "
          "with the compact tefcore model (equivalent root springs, linear inflow, "
          "quasi-steady aerodynamics, assumed MDART properties). Each notebook explains "
          "its figures; this page lists every claim of the paper with its status.", "",
          f"**Claims: {passed} passed of {total}.** "
          f"Worse than recorded: {len(worse)}.", "",
          "## Notebooks", "",
          _md_table(pd.DataFrame([{"notebook": r.name, "status": r.status,
                                   "error": r.error} for r in runs])), ""]
    html_parts = [f"<h1>tefcore reproduction report</h1><p>{html.escape(md[2])}</p>",
                  f"<p><b>Claims: {passed} passed of {total}.</b> "
                  f"Worse than recorded: {len(worse)}.</p>",
                  "<h2>Notebooks</h2><table><tr><th>notebook</th><th>status</th>"
                  "<th>error</th></tr>"
                  + "".join(f"<tr class=\"{'pass' if r.status == 'ok' else 'fail'}\">"
                            f"<td><a href=\"notebooks/{r.name}.ipynb\">{r.name}</a></td>"
                            f"<td>{r.status}</td><td>{html.escape(r.error)}</td></tr>"
                            for r in runs) + "</table>"]
    if not worse.empty:
        md += ["## Worse than recorded", "", _md_table(worse), ""]
        html_parts.append("<h2>Worse than recorded</h2>" + worse.to_html(index=False))
    summary = claims_summary(claims)
    md += ["## Claims by figure", "",
           "Counts of the claims' statuses; the score counts the `validation` claims "
           "(calibration targets are listed, not scored).", "", _md_table(summary), "",
           "## Claims", "", _md_table(shown), ""]
    html_parts.append("<h2>Claims by figure</h2>" + summary.to_html(index=False))
    rows = []
    for row in shown.itertuples(index=False):
        d = row._asdict()
        cls = {"pass": "pass", "fail": "fail"}.get(d.get("status", ""), "notrep")
        rows.append(f'<tr class="{cls}">' + "".join(
            f"<td>{html.escape(str(v))}</td>" for v in d.values()) + "</tr>")
    html_parts.append("<h2>Claims</h2><table><tr>" + "".join(
        f"<th>{html.escape(c)}</th>" for c in shown.columns) + "</tr>" + "".join(rows)
        + "</table>")
    if checks is not None:
        c = checks.drop(columns="source", errors="ignore")
        md += ["## Stated blade frequencies (calibration targets)", "",
               _md_table(c.round(3)), "", "![fan plot](mdart_fanplot.png)", ""]
        html_parts.append("<h2>Stated blade frequencies (calibration targets)</h2>"
                          + c.to_html(index=False, float_format=lambda v: f"{v:.3f}")
                          + _img_tag(out / "mdart_fanplot.png", "MDART fan plot"))
    md += ["## Figures", ""]
    html_parts.append("<h2>Figures</h2>")
    for r in runs:
        pngs = sorted((out / r.name).glob("*.png")) if (out / r.name).exists() else []
        if not pngs:
            continue
        md += [f"### {r.name}", ""]
        html_parts.append(f"<h3>{html.escape(r.name)}</h3>")
        for p in pngs:
            md += [f"![{r.name} {p.stem}]({r.name}/{p.name})", ""]
            html_parts.append(_img_tag(p, f"{r.name}: {p.stem}"))
    md_path, html_path = out / "report.md", out / "report.html"
    md_path.write_text("\n".join(md))
    html_path.write_text("<!DOCTYPE html><html><head><meta charset=\"utf-8\">"
                         "<title>tefcore reproduction report</title>"
                         f"<style>{_CSS}</style></head><body>"
                         + "\n".join(html_parts) + "</body></html>\n")
    return md_path, html_path


def reproduce(out, params=None, notebooks=None, progress: bool = True,
              nb_dir: Path | None = None) -> int:
    """Run the notebooks into ``out`` and write the report; return the exit code.

    ``params``: ``{"all"|notebook: {name: value}}`` or a list of such layers
    (later wins, see :func:`merge_params`). Non-zero when a notebook failed or
    a claim is worse than its recorded status.
    """
    out = Path(out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    names = [resolve_notebook(n) for n in notebooks] if notebooks else list(NOTEBOOKS)
    layers = params if isinstance(params, list | tuple) else [params or {}]
    merged = merge_params(*layers, notebooks=names)
    start = time.perf_counter()
    checks = _baseline_blade(out)
    runs = run_notebooks(out, merged, names, progress=progress, nb_dir=nb_dir)
    claims = collect_claims(out, names)
    claims.drop(columns=["notebook"]).to_csv(out / "claims.csv", index=False) \
        if not claims.empty else claims.to_csv(out / "claims.csv", index=False)
    worse = regressions(claims)
    md, html_path = write_report(out, runs, claims, worse, checks)
    passed, total = score(claims)
    for r in runs:
        print(f"{r.name:38s} {r.status:7s} {r.seconds:6.1f} s  {r.error}")
    print(f"claims: {passed} passed of {total}; worse than recorded: {len(worse)}")
    print(f"wrote {md} and {html_path} in {time.perf_counter() - start:.1f} s")
    failed = [r.name for r in runs if r.status != "ok"]
    if failed:
        print(f"tefcore reproduce: notebook(s) failed: {', '.join(failed)}", file=sys.stderr)
    if not worse.empty:
        print("tefcore reproduce: claim(s) worse than recorded:\n"
              + worse.to_string(index=False), file=sys.stderr)
    return 1 if failed or not worse.empty else 0


# ============================================================ notebook helpers


def deterministic_matplotlib() -> None:
    """rcParams that make saved figures byte-identical between runs."""
    import matplotlib as mpl

    mpl.rcParams.update({"svg.hashsalt": "tefcore", "pdf.compression": 6,
                         "figure.dpi": 80, "savefig.dpi": 110,
                         "figure.figsize": (6.4, 4.2), "axes.grid": True,
                         "grid.alpha": 0.3, "legend.fontsize": "small"})


def setup_notebook(output_dir) -> Path:
    """Create the output folder, fix seeds, printing and matplotlib settings."""
    import matplotlib.pyplot as plt

    np.random.seed(0)  # noqa: NPY002 -- the legacy global RNG, for user code in notebooks
    deterministic_matplotlib()
    plt.rcParams["figure.max_open_warning"] = 0
    pd.set_option("display.width", 120)
    pd.set_option("display.max_columns", 30)
    pd.set_option("display.max_colwidth", 60)
    out = Path(output_dir)
    out.mkdir(parents=True, exist_ok=True)
    return out


def savefig(fig, output_dir, stem: str) -> None:
    """Save ``fig`` as ``<output_dir>/<stem>.png`` with fixed metadata.

    Returns None, so that a notebook cell ending with it displays nothing
    extra (nbval executes cells without history, where IPython's trailing
    ``;`` does not suppress the result).
    """
    fig.savefig(Path(output_dir) / f"{stem}.png", metadata={"Software": None},
                bbox_inches="tight")


def save_csv(df: pd.DataFrame, output_dir, stem: str) -> Path:
    """Write ``df`` as ``<output_dir>/<stem>.csv`` (10 significant digits)."""
    path = Path(output_dir) / f"{stem}.csv"
    df.to_csv(path, index=False, float_format="%.10g")
    return path


def base_config(aero_model: str = "thin_airfoil", overrides: dict | None = None):
    """MDART configuration with the chosen section aerodynamics.

    ``aero_model``: ``"thin_airfoil"`` (quasi-steady Theodorsen-type) or
    ``"table"`` (C81 look-up with the shipped *generated* example deck).
    """
    from .c81 import example_deck_path
    from .config import load_config

    cfg = load_config("mdart")
    if aero_model in ("table", "c81"):
        cfg = cfg.with_overrides({"model.aero_model": "c81",
                                  "model.c81_deck": str(example_deck_path())})
    elif aero_model != "thin_airfoil":
        raise ValueError(f"aero_model must be 'thin_airfoil' or 'table', got {aero_model!r}")
    return cfg.with_overrides(overrides) if overrides else cfg


def section_aero(aero_model: str, cfg=None):
    """Section model for the Fig. 5 hinge moment: ``"thin_airfoil"`` or ``"table"``
    (the shipped generated deck), with the flap geometry of ``cfg``."""
    from .coupled import section_model

    cfg = base_config(aero_model) if cfg is None else cfg
    return section_model(base_config(aero_model).with_overrides({
        "flap.chord_ratio": cfg.flap.chord_ratio, "flap.overhang": cfg.flap.overhang}))


_NUM_UNIT = re.compile(r"^\s*([-+0-9.eE]+)\s*(.*)$")


def _split(value):
    if isinstance(value, str):
        m = _NUM_UNIT.match(value)
        if not m:
            raise ValueError(f"cannot read a number from {value!r}")
        return float(m.group(1)), m.group(2).strip()
    return float(value), ""


def figure_values(name: str, n_points: int | None = None, values=None,
                  claim_points: bool = True) -> list:
    """Sweep values of a figure: explicit ``values``, ``n_points`` evenly over the
    paper's range, or (both None) the paper's values of
    :data:`tefcore.figures.FIGURES` plus (``claim_points``) the x values that
    the figure's value claims name -- the same sweep as
    :func:`tefcore.validation.validate_all` runs."""
    from .figures import FIGURES

    if values is not None:
        return list(values)
    base = list(FIGURES[name].values)
    if n_points is None:
        return (_claim_sweep_values(name) if claim_points else None) or base
    n = int(n_points)
    if n < 2:
        raise ValueError(f"n_points must be at least 2, got {n_points!r}")
    (lo, unit), (hi, _) = _split(base[0]), _split(base[-1])
    grid = np.linspace(lo, hi, n)
    if unit:
        return [f"{v:.6g} {unit}" for v in grid]
    return [float(f"{v:.10g}") for v in grid]


def _claim_sweep_values(name: str):
    val = _validation()
    fn = getattr(val, "_sweep_values", None) if val is not None else None
    if fn is None:
        return None
    try:
        from .reference import load_claims

        mine = [c for c in load_claims() if c.figure == name and c.kind != "not_reproducible"]
        return fn(name, mine)
    except (ValueError, KeyError, FileNotFoundError):   # no or unusable reference data
        return None


def variant_key(overrides: dict) -> str:
    """Key of a configuration variant for :func:`claims_table` (validation's own)."""
    val = _validation()
    if val is not None and hasattr(val, "variant_key"):
        return val.variant_key(overrides)
    import json

    return json.dumps(overrides, sort_keys=True) if overrides else ""


def quiet_stability(cfg):
    """:func:`tefcore.stability.stability` with its numerical warnings counted,
    not printed (workers' stderr would otherwise reach the notebook); the count
    is the sweep column ``trim_numerical_warnings``."""
    from .stability import stability

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = stability(cfg)
    trim = dict(res.trim)
    trim["numerical_warnings"] = len(caught)
    return SimpleNamespace(modes=res.modes, eigenvectors=res.eigenvectors, trim=trim)


def run_stability_figure(name: str, base=None, overrides: dict | None = None,
                         values=None, n_jobs: int = 1, cg_offset=None):
    """A stability figure's sweep: the caption's fixed parameters, then ``overrides``.

    Same as :func:`tefcore.figures.run_figure` except that ``overrides``
    (e.g. another advance ratio) win over the caption, and warnings are
    counted instead of printed.  Returns the SweepResult.
    """
    from .figures import FIGURES, figure_config
    from .sweep import sweep

    cfg = figure_config(name, base)
    if overrides:
        cfg = cfg.with_overrides(overrides)
    if cg_offset is not None:
        cfg = cfg.with_overrides({"flap.cg_offset": cg_offset})
    fig = FIGURES[name]
    vals = list(fig.values) if values is None else list(values)
    return sweep(cfg, fig.parameter, vals, point=quiet_stability, n_jobs=n_jobs,
                 progress=False)


#: x axis per figure: (label, function of the table's value column)
def _x_collective(v):
    return np.rad2deg(np.asarray(v, float))


AXES = {
    "fig3": ("collective pitch θ₀ [deg]", _x_collective),
    "fig4": ("collective pitch θ₀ [deg]", _x_collective),
    "fig8": ("flap overhang c_b/c_f", None),
    "fig9": ("flap CG offset c_cg/c_f (positive aft)", None),
    "fig10": ("pitch link stiffness [lb/in]", None),
    "fig11": ("torsional stiffness GJ / baseline GJ", None),
    "fig12": ("actuator stiffness / baseline (81.52 ft-lb/rad)",
              lambda v: np.array([_split(s)[0] for s in v]) / 81.52),
    "fig13": ("flap midspan location r/R", None),
    "fig14": ("flap length / R", None),
    "fig15": ("flap chord c_f/c", None),
    "fig16a": ("collective pitch θ₀ [deg]", _x_collective),
    "fig16b": ("collective pitch θ₀ [deg]", _x_collective),
    "fig17": ("advance ratio μ", None),
}


def x_values(name: str, table: pd.DataFrame) -> np.ndarray:
    """The paper's x-axis quantity for each row of a sweep table."""
    _, fn = AXES[name]
    v = table["value"].tolist()
    if fn is not None:
        return np.asarray(fn(v), float)
    return np.array([_split(s)[0] for s in v], float)


#: modes shown in the paper's damping panels
PAPER_MODES = ("TEF", "blade flap 1", "blade lag 1", "blade torsion 1")
_STYLE = {"TEF": ("C3", "o", "-"), "blade flap 1": ("C0", "s", "-"),
          "blade lag 1": ("C2", "^", "--"), "blade torsion 1": ("C1", "D", "-.")}
MEASURES = {
    "decay_rate": ("damping −Re(s)/Ω  [1/rev]  (> 0 stable)",
                   lambda t: -t["real_part"]),
    "damping_ratio": ("damping ratio ζ [%]  (> 0 stable)",
                      lambda t: 100 * t["damping_ratio"]),
}


def _base_label(s: pd.Series) -> pd.Series:
    return s.astype(str).str.removesuffix(" (locked)")


def curves(name: str, table: pd.DataFrame, labels=PAPER_MODES,
           measure: str = "decay_rate") -> pd.DataFrame:
    """One tracked curve per mode, for plotting and printing.

    The track of mode ``m`` is the one labelled ``m`` or ``m (locked)`` that is
    present at the most points (ties: the exact label) -- the same choice as
    :mod:`tefcore.validation`.  Columns ``label, track, x, frequency_per_rev,
    damping, same_character``; ``same_character`` is False where the mode's
    own label at that point is another mode's (strong coupling: the modes
    exchange character).
    """
    _, fn = MEASURES[measure]
    ok = table[table["status"] == "ok"].copy()
    ok["base"] = _base_label(ok["label"])
    parts = []
    for lab in labels:
        sub = ok[ok["base"] == lab]
        if sub.empty:
            continue
        sizes = sub.groupby("track", sort=False).agg(n=("point", "size"),
                                                     first=("label", "first"))
        sizes = sizes.assign(exact=sizes["first"] == lab).sort_values(
            ["n", "exact"], ascending=False, kind="stable")
        g = sub[sub["track"] == sizes.index[0]].copy()
        g["label"] = lab
        parts.append(g)
    cols = ["label", "track", "x", "frequency_per_rev", "damping", "same_character"]
    if not parts:
        return pd.DataFrame(columns=cols)
    cv = pd.concat(parts, ignore_index=True)
    cv["x"] = x_values(name, cv)
    cv["damping"] = fn(cv)
    cv["same_character"] = _base_label(cv["label_here"]) == cv["label"]
    cv = cv.sort_values(["x"], kind="stable")
    order = {lab: i for i, lab in enumerate(labels)}
    cv = cv.sort_values("label", key=lambda s: s.map(order), kind="stable")
    return cv[cols].reset_index(drop=True)


def natural_frequencies(name: str, values, base=None, overrides: dict | None = None,
                        labels=("blade flap 1", "blade lag 1", "blade torsion 1")):
    """Blade natural frequencies (:func:`tefcore.blade.blade_modes`, no aerodynamics,
    zero collective) at each sweep value: the "blade frequency" panels of
    Figs. 10a/11a, as the paper's stated frequencies (and the validation) use them."""
    from .blade import blade_modes
    from .figures import FIGURES, figure_config

    cfg = figure_config(name, base)
    if overrides:
        cfg = cfg.with_overrides(overrides)
    rows = []
    for v in values:
        m = blade_modes(cfg.with_overrides({FIGURES[name].parameter: v}))
        for lab, f in zip(m.labels, m.frequencies, strict=True):
            if f"blade {lab}" in labels:
                rows.append({"point": len(rows), "value": v, "label": f"blade {lab}",
                             "frequency_per_rev": float(f)})
    t = pd.DataFrame(rows)
    t["x"] = x_values(name, t)
    t["track"] = t["label"]
    t["damping"] = np.nan
    t["same_character"] = True
    return t[["label", "track", "x", "frequency_per_rev", "damping", "same_character"]]


def plot_modes(ax, name: str, table: pd.DataFrame, labels=PAPER_MODES,
               quantity: str = "damping", measure: str = "decay_rate",
               reference: pd.DataFrame | None = None, label_suffix: str = "",
               style=None, natural: pd.DataFrame | None = None):
    """Frequency or damping of the tracked modes against the paper's x axis.

    Hollow markers: points where the mode has the character of another mode
    (strong coupling).  ``natural``: plot these natural frequencies
    (:func:`natural_frequencies`) instead of the table's.  ``reference``:
    digitised curves (``label, x, y``) drawn as black crosses.
    """
    xlabel, _ = AXES[name]
    cv = natural if natural is not None else curves(name, table, labels, measure)
    ycol = "frequency_per_rev" if quantity == "frequency" else "damping"
    for lab in labels:
        g = cv[cv["label"] == lab]
        if g.empty:
            continue
        color, marker, ls = (style or _STYLE).get(lab, ("0.3", "o", "-"))
        ax.plot(g["x"], g[ycol], ls=ls, color=color, lw=1.4, label=f"{lab}{label_suffix}")
        filled, hollow = g[g["same_character"]], g[~g["same_character"]]
        ax.plot(filled["x"], filled[ycol], ls="none", marker=marker, color=color, ms=5)
        ax.plot(hollow["x"], hollow[ycol], ls="none", marker=marker, ms=5,
                markerfacecolor="white", markeredgecolor=color)
    if reference is not None and not reference.empty:
        for lab, g in reference.groupby("label", sort=True):
            ax.plot(g["x"], g["y"], ls="none", marker="x", color="k", ms=6,
                    label=f"paper: {lab}")
    if quantity == "damping":
        ax.axhline(0.0, color="k", lw=0.8)
        ax.set_ylabel(MEASURES[measure][0])
    else:
        ax.set_ylabel("natural frequency [/rev]" if natural is not None
                      else "frequency [/rev]")
    ax.set_xlabel(xlabel)
    return ax


def mode_summary(name: str, table: pd.DataFrame | None, labels=PAPER_MODES,
                 measure: str = "decay_rate", quantity: str = "damping",
                 digits: int = 3, natural: pd.DataFrame | None = None) -> pd.DataFrame:
    """Wide table (x by mode), rounded, for printing in checked cells."""
    cv = natural if natural is not None else curves(name, table, labels, measure)
    col = "frequency_per_rev" if quantity == "frequency" else "damping"
    wide = cv.pivot_table(index="x", columns="label", values=col, aggfunc="first",
                          sort=True)
    wide = wide[[c for c in labels if c in wide.columns]]
    wide.index = np.round(wide.index.to_numpy(float), 4)
    wide.index.name = AXES[name][0]
    wide.columns.name = None
    return clean(wide.round(digits))


def clean(df: pd.DataFrame) -> pd.DataFrame:
    """Replace ``-0.0`` by ``0.0`` (so printed tables do not flip sign)."""
    return df.apply(lambda c: c.mask(c == 0, 0.0) if c.dtype.kind == "f" else c)


def sign_changes(name: str, table: pd.DataFrame, label: str = "TEF",
                 measure: str = "decay_rate") -> list:
    """Where a mode's damping changes sign (linear interpolation), paper units."""
    cv = curves(name, table, (label,), measure)
    out = []
    for _, g in cv.groupby("track", sort=True):
        x, y = g["x"].to_numpy(), g["damping"].to_numpy()
        for i in range(len(x) - 1):
            if y[i] == 0 or y[i] * y[i + 1] < 0:
                xc = x[i] - y[i] * (x[i + 1] - x[i]) / (y[i + 1] - y[i])
                out.append((round(float(xc), 3),
                            "stable -> unstable" if y[i] > 0 else "unstable -> stable"))
    return out


def theodorsen_c(k: float) -> complex:
    """Theodorsen's lift-deficiency function C(k) = H1(k) / (H1(k) + i H0(k))."""
    from scipy.special import hankel2

    return complex(hankel2(1, k) / (hankel2(1, k) + 1j * hankel2(0, k)))


def unsteadiness(name: str, result, base=None) -> None:
    """Print the TEF mode's reduced frequency at the flap and Theodorsen's C(k):
    how far from quasi-steady (C = 1) the flap mode of this sweep is."""
    from .figures import figure_config

    cfg = figure_config(name, base)
    t = result.table
    own = t[(t["status"] == "ok") & (_base_label(t["label_here"]) == "TEF")]
    if own.empty:
        print(f"{name}: no TEF mode in the sweep")
        return
    f = float(np.median(own["frequency_per_rev"]))   # where the mode is TEF-like itself
    # k = omega b / U with b = c/2 and U = x R Omega (hover speed at the flap midspan)
    k = f * cfg.rotor.chord / (2 * cfg.flap.midspan * cfg.rotor.radius)
    c = theodorsen_c(k)
    print(f"{name}: TEF mode at {f:.1f}/rev (median over the sweep) -> reduced frequency "
          f"k = {k:.2f} at {cfg.flap.midspan:.2f} R;")
    print(f"  Theodorsen C(k): |C| = {abs(c):.2f}, phase {np.degrees(np.angle(c)):.1f} deg "
          "(quasi-steady theory uses C = 1, phase 0)")


@contextmanager
def counted_warnings(what: str):
    """Collect the warnings of a block and print one deterministic line counting
    them by category (nothing when there are none), instead of a stderr flood."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        yield caught
    if caught:
        counts = pd.Series([w.category.__name__ for w in caught]).value_counts().sort_index()
        print(f"{what}: " + ", ".join(f"{n} {cat}" for cat, n in counts.items()))


def report_sweep(name: str, result) -> None:
    """One deterministic line: points, failures, points with numerical warnings."""
    t = result.table
    pts = t.drop_duplicates("point")
    n_warn = int((pts.get("trim_numerical_warnings", pd.Series(dtype=float)).fillna(0) > 0)
                 .sum())
    print(f"{name}: {len(pts)} points of {result.parameter}, "
          f"{int((pts['status'] != 'ok').sum())} failed, {n_warn} with numerical warnings")
    for row in result.failed.itertuples(index=False):
        print(f"  failed at {row.value}: {row.error}")


def claims_table(name: str, result, cfg=None, variants=None, others=None) -> pd.DataFrame:
    """:func:`tefcore.validation.validate_figure` for one figure.

    ``variants``: ``{overrides dict as JSON (validation.variant_key): result}``
    of runs already made (e.g. Fig. 12's balanced flap); ``others``: figure
    name -> result, for claims comparing figures.  Anything else a claim needs
    is computed by the validation module.  Without reference data, one row
    saying so.
    """
    val = _validation()
    if val is not None:
        try:
            return val.validate_figure(name, result, cfg=cfg, variants=variants,
                                       others=others).reset_index(drop=True)
        except Exception as exc:
            if type(exc).__name__ != "ReferenceDataError":
                raise
            why = "no reference data (reference_data/claims.toml)"
    else:
        why = "tefcore.validation is not installed"
    return pd.DataFrame([{"id": f"{name}-none", "figure": name, "statement": "",
                          "expected": "", "computed": "", "status": "not reproducible",
                          "reason": why, "tag": "", "recorded_status": ""}])


def reference_curves(name: str):
    """Digitised reference curves of a figure (``label, x, y``), or None."""
    val = _validation()
    fn = getattr(val, "reference_curves", None) if val is not None else None
    if fn is None:
        return None
    try:
        return fn(name)
    except (KeyError, FileNotFoundError, ValueError):
        return None


def show_claims(table: pd.DataFrame, width: int = 70) -> None:
    """Print a claims table compactly and deterministically (claim, status, computed)."""
    if table.empty:
        print("no claims for this figure")
        return
    t = table.copy()
    if "computed" in t:
        t["computed"] = [_fmt(v) for v in t["computed"]]
    cols = [c for c in ("id", "status", "computed") if c in t.columns]
    with pd.option_context("display.max_colwidth", width, "display.width", 200):
        print(t[cols or list(t.columns)].to_string(index=False))


_NUMBER = re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?:e[-+]?\d+)?(?![\w.])")


def _round_number(text: str) -> str:
    v = float(text)
    if abs(v) < 1e-9:          # round-off (e.g. 2.2e-16 for "unchanged"): not a result
        return "0"
    return f"{v:.4g}"


def _fmt(v) -> str:
    """A value printed with 4 significant digits; |x| < 1e-9 (round-off) as 0."""
    if isinstance(v, float | np.floating):
        return "nan" if math.isnan(v) else _round_number(repr(float(v)))
    return _NUMBER.sub(lambda m: _round_number(m.group()), str(v))
