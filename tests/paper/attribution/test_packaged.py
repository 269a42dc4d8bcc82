"""The packaged attribution is read only where it is this run's answer.

The default reproduction reads the package's attribution instead of searching
(``tefcore/paper/reference_data/attribution-mdart.*``).  A search's rows are a
function of the code, the data, the notebooks' settings and the claims'
verdicts; the package may stand in for a search only while every one of them
is the same, and a test here fails when the packaged pair is not this code's
(re-create it: ``tefcore reproduce --out OUT --attribute-again`` and
``python tools/package_attribution.py OUT``).
"""

import json

import pandas as pd

from tefcore.paper.attribution import packaged as pk
from tefcore.paper.attribution.differences import COLUMNS, failing_claims
from tefcore.paper.claims.files import reference_dir
from tefcore.paper.claims.reference import load_claims


def _packaged():
    ref = reference_dir()
    stamp = json.loads((ref / pk.PACKAGED[1]).read_text())
    table = pd.read_csv(ref / pk.PACKAGED[0], dtype=str, keep_default_na=False)
    return stamp, table


def _claims_of(stamp) -> pd.DataFrame:
    """The claims table of the run the package was made from (id, notebook, status, tag)."""
    tags = {c.id: c.tag for c in load_claims()}
    return pd.DataFrame([{"id": i, "notebook": nb, "status": s, "tag": tags.get(i, "validation")}
                         for i, (nb, s) in stamp["statuses"].items()])


def _params(stamp) -> dict:
    return {n: {k: v for k, v in p.items() if v is not None} for n, p in stamp["settings"].items()}


def test_the_packaged_attribution_is_this_codes():
    # fails after any change to the model code, the claims' code or definitions or
    # the data, until the attribution is searched again and packaged
    stamp, _ = _packaged()
    now = pk.run_stamp(_params(stamp))
    assert stamp["code_stamp"] == now["code_stamp"], (
        "the packaged attribution was searched with other code or data: re-create it "
        "(tefcore reproduce --out OUT --attribute-again; python tools/package_attribution.py OUT)")
    assert stamp["tefcore_version"] == now["tefcore_version"]
    assert stamp["inputs"] == now["inputs"]


def test_the_packaged_run_had_the_recorded_verdicts():
    # the default reproduction reads the package only when its claims check as they
    # did then; the recorded statuses are what the default reproduction gives
    stamp, table = _packaged()
    recorded = {c.id: c.recorded_status for c in load_claims() if c.recorded_status}
    statuses = {i: s for i, (_, s) in stamp["statuses"].items()}
    assert {i: statuses.get(i) for i in recorded} == recorded
    failing = set(failing_claims(_claims_of(stamp))["id"])
    assert set(table["claim"]) == failing       # every failing claim attributed, nothing else
    assert list(table.columns[:len(COLUMNS)]) == COLUMNS


def test_the_package_stands_in_for_a_search_of_the_same_run_only():
    stamp, table = _packaged()
    claims, params = _claims_of(stamp), _params(stamp)
    got, why = pk.packaged_attribution(claims, params)
    assert why == "" and set(got["claim"]) == set(table["claim"])
    # a run of some notebooks: their failing claims' rows, the same rows
    nb = claims["notebook"].iloc[0]
    some = claims[claims["notebook"] == nb]
    got, why = pk.packaged_attribution(some, {nb: params.get(nb, {})})
    assert why == "" and set(got["claim"]) == set(failing_claims(some)["id"])
    # one verdict moved (a claim's rows read its peers' verdicts): searched
    moved = claims.copy()
    i = moved.index[moved["status"] == "pass"][0]
    moved.loc[i, "status"] = "fail"
    got, why = pk.packaged_attribution(moved, params)
    assert got is None and moved.loc[i, "id"] in why
    # another setting of a notebook (a what-if): searched
    other = {**params, nb: {**params.get(nb, {}), "overrides": {"flap.cg_offset": 0.2}}}
    got, why = pk.packaged_attribution(claims, other)
    assert got is None and f"other settings of {nb}" in why


def test_edited_code_or_data_is_searched_again(monkeypatch):
    stamp, _ = _packaged()
    monkeypatch.setattr(pk, "code_stamp", lambda: "0" * 16)
    got, why = pk.packaged_attribution(_claims_of(stamp), _params(stamp))
    assert got is None and "code or data" in why


def test_the_stamp_covers_the_claims_definitions(tmp_path, monkeypatch):
    # a claim's threshold edited in the reference data changes the stamp
    ref = reference_dir()
    for f in ref.iterdir():
        if f.is_file():
            (tmp_path / f.name).write_bytes(f.read_bytes())
    before = pk.code_stamp()
    text = (tmp_path / "claims.toml").read_text()
    (tmp_path / "claims.toml").write_text(text + "\n# edited\n")
    monkeypatch.setenv("TEFCORE_REFERENCE_DATA", str(tmp_path))
    assert pk.code_stamp() != before


def test_every_paper_module_the_search_runs_is_stamped():
    # the search's code is the model (model_stamp) and the paper modules it imports;
    # each of them must be in the stamp, or an edit to it would read a stale package
    import subprocess
    import sys

    code = ("import sys; import tefcore.paper.attribution.differences, "
            "tefcore.paper.attribution.levers, tefcore.paper.attribution.search, "
            "tefcore.paper.attribution.evaluate, tefcore.paper.calibration; "
            "print('\\n'.join(m for m in sys.modules if m.startswith('tefcore.paper.')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    stamped = {name for name, _ in pk._paper_sources()
               if name.split("/")[0] not in pk.UNSTAMPED_FOLDERS}
    for module in out:
        parts = module.split(".")[2:]
        name = "/".join(parts) + ".py"
        if name not in {n for n, _ in pk._paper_sources()}:
            name = "/".join(parts + ["__init__.py"])
        assert name in stamped or name == "attribution/packaged.py", module
    assert "calibration.py" in stamped           # the torsion calibration the levers re-run

