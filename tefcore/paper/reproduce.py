"""``tefcore reproduce``: run the numbered notebooks and write the claims report.


* **Runner** (:func:`reproduce`): executes ``notebooks/01_*.ipynb`` ...
  ``07_*.ipynb`` with papermill into an output folder, each with its own
  parameters (:func:`parse_cli_params`, :func:`load_params_file`,
  :func:`notebook_parameters`), then collects the claims tables and figures
  the notebooks wrote and writes ``report.md`` and a self-contained
  ``report.html`` (figures embedded as base64 PNG).  The exit code is
  non-zero when a notebook fails or a validation claim is worse than its
  recorded status (:func:`tefcore.paper.validation.worse_than_recorded`).
* The notebooks' shared helpers live in :mod:`tefcore.paper.notebook_tools`.

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
"""

from __future__ import annotations

import base64
import html
import os
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import pandas as pd

from ..errors import OutputError
from .notebook_tools import _validation, deterministic_matplotlib, savefig
from ..safe_io import atomic_output, atomic_write_text, check_output_file, check_output_folder

#: The notebooks, in order.
NOTEBOOKS = (
    "01_baseline_mdart_correlation",
    "02_hinge_moments_and_flap_response",
    "03_overhang",
    "04_cg_offset",
    "05_stiffness",
    "06_size_and_location",
    "07_flight_condition",
    "08_assumptions",
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
    "08_assumptions": (),               # no figure: the sensitivity of the headline results
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

    from ..blade import blade_modes, fan_plot
    from .calibration import frequency_checks
    from ..config_io import load_config

    deterministic_matplotlib()
    cfg = load_config("mdart")
    with atomic_output(out / "mdart_modes.csv", newline="") as f:
        blade_modes(cfg).table().to_csv(f, index=False, float_format="%.6g")
    checks = frequency_checks(cfg)
    with atomic_output(out / "mdart_frequency_checks.csv", newline="") as f:
        checks.to_csv(f, index=False, float_format="%.6g")
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
    atomic_write_text(md_path, "\n".join(md))
    atomic_write_text(html_path, "<!DOCTYPE html><html><head><meta charset=\"utf-8\">"
                         "<title>tefcore reproduction report</title>"
                         f"<style>{_CSS}</style></head><body>"
                         + "\n".join(html_parts) + "</body></html>\n")
    return md_path, html_path


def _tracked_files(paths: list[Path]) -> list[str]:
    """Those of `paths` (files or folders) tracked by git; [] outside a work tree, or no git."""
    import subprocess

    probe = next((p for p in (paths[0], *paths[0].parents) if p.is_dir()), None)
    if probe is None:
        return []
    try:
        top = subprocess.run(["git", "-C", str(probe), "rev-parse", "--show-toplevel"],
                             capture_output=True, text=True, timeout=30)
        if top.returncode != 0:
            return []
        root = Path(top.stdout.strip()).resolve()
        rel = [str(p.relative_to(root)) for p in paths if p.is_relative_to(root)]
        if not rel:
            return []
        listed = subprocess.run(["git", "-C", str(root), "ls-files", "-z", "--", *rel],
                                capture_output=True, text=True, timeout=30)
    except (OSError, subprocess.SubprocessError):
        return []
    return [f for f in listed.stdout.split("\0") if f] if listed.returncode == 0 else []


def check_reproduce_folder(out, names=NOTEBOOKS, nb_dir: Path | None = None) -> Path:
    """Refuse an output folder whose files would overwrite sources; return it resolved.

    ``reproduce`` writes ``OUT/notebooks/<name>.ipynb``, ``OUT/<name>/`` and
    the report files.  Refused (:class:`~tefcore.errors.OutputError`,
    before anything runs): ``OUT/notebooks`` is the folder of the source
    notebooks (``--out .`` from the repository root), or any file that would
    be written is tracked by git, or a destination is a link or a folder.
    """
    out = Path(out).resolve()
    if out.exists() or out.is_symlink():
        check_output_folder(out, "reproduce --out")
    nb_dir = (nb_dir or notebooks_dir()).resolve()
    if (out / "notebooks").resolve() == nb_dir:
        raise OutputError(f"reproduce --out {out}: the executed notebooks would overwrite the "
                          f"source notebooks in {nb_dir}; choose another output folder "
                          "(default: output)")
    files = [out / f for f in ("report.md", "report.html", "claims.csv", "mdart_modes.csv",
                               "mdart_frequency_checks.csv", "mdart_fanplot.png")]
    files += [out / "notebooks" / f"{n}.ipynb" for n in names]
    tracked = _tracked_files(files + [out / n for n in names])
    if tracked:
        shown = ", ".join(tracked[:3]) + (f" and {len(tracked) - 3} more" if len(tracked) > 3
                                          else "")
        raise OutputError(f"reproduce --out {out} would overwrite file(s) tracked by git: "
                          f"{shown}; choose another output folder (default: output)")
    for f in files:
        if f.exists() or f.is_symlink():
            check_output_file(f, "reproduce output")
    return out


def reproduce(out, params=None, notebooks=None, progress: bool = True,
              nb_dir: Path | None = None) -> int:
    """Run the notebooks into ``out`` and write the report; return the exit code.

    ``params``: ``{"all"|notebook: {name: value}}`` or a list of such layers
    (later wins, see :func:`merge_params`). Non-zero when a notebook failed or
    a claim is worse than its recorded status.
    """
    names = [resolve_notebook(n) for n in notebooks] if notebooks else list(NOTEBOOKS)
    out = check_reproduce_folder(out, names, nb_dir)
    out.mkdir(parents=True, exist_ok=True)
    layers = params if isinstance(params, list | tuple) else [params or {}]
    merged = merge_params(*layers, notebooks=names)
    start = time.perf_counter()
    checks = _baseline_blade(out)
    runs = run_notebooks(out, merged, names, progress=progress, nb_dir=nb_dir)
    claims = collect_claims(out, names)
    with atomic_output(out / "claims.csv", newline="") as f:
        (claims if claims.empty else claims.drop(columns=["notebook"])).to_csv(f, index=False)
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
