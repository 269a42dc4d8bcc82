"""The reproduction's attribution phase reads the package or searches, and packages.

``tefcore reproduce`` reads the default rotor's packaged attribution only where
it is this run's answer (:mod:`tefcore.paper.attribution.packaged` decides),
otherwise searches and stamps the search; ``package`` puts only a default
search made with this code into the package.
"""

import json

import pandas as pd
import pytest

from tefcore.paper.attribution import packaged as pk
from tefcore.paper.attribution.differences import Attribution
from tefcore.paper.run import attribution_phase as ap
from tests.paper.attribution.test_packaged import _claims_of, _packaged, _params


def test_only_a_default_search_with_this_code_is_packaged(tmp_path):
    stamp, table = _packaged()
    claims, params = _claims_of(stamp), _params(stamp)
    out = tmp_path / "out"
    out.mkdir()
    table.to_csv(out / "attribution.csv", index=False)
    pk.write_stamp(out / "attribution.json", claims, params, Attribution(table, 12.0, 7.0, 3))
    target = tmp_path / "ref"
    target.mkdir()
    csv, meta = ap.package(out, target)
    assert csv.read_bytes() == (out / "attribution.csv").read_bytes()
    assert json.loads(meta.read_text())["cpu_seconds"] == 12.0
    # a what-if search is not the default rotor's
    nb = next(iter(params))
    what_if = {**params, nb: {**params[nb], "overrides": {"flap.cg_offset": 0.2}}}
    pk.write_stamp(out / "attribution.json", claims, what_if, Attribution(table, 1.0, 1.0, 1))
    with pytest.raises(ValueError, match="what-if"):
        ap.package(out, target)
    # a search with other code
    rec = json.loads((out / "attribution.json").read_text())
    rec.update(settings=stamp["settings"], code_stamp="0" * 16)
    (out / "attribution.json").write_text(json.dumps(rec))
    with pytest.raises(ValueError, match="code or data"):
        ap.package(out, target)
    # a search of another packaged variant is not the default rotor's
    variant = {n: {**p, "config": "mdart-inferred"} for n, p in params.items()}
    pk.write_stamp(out / "attribution.json", claims, variant, Attribution(table, 1.0, 1.0, 1))
    with pytest.raises(ValueError, match="another variant"):
        ap.package(out, target)
    # a run of some of the notebooks
    nb_claims = claims[claims["notebook"] == nb]
    pk.write_stamp(out / "attribution.json", nb_claims, {nb: params[nb]},
                   Attribution(table, 1.0, 1.0, 1))
    with pytest.raises(ValueError, match="of the 12 notebooks"):
        ap.package(out, target)
    # rows of only some failing claims
    pk.write_stamp(out / "attribution.json", claims, params, Attribution(table, 1.0, 1.0, 1))
    table[table["claim"] == table["claim"].iloc[0]].to_csv(out / "attribution.csv", index=False)
    with pytest.raises(ValueError, match="not the run's whole attribution"):
        ap.package(out, target)
    (out / "attribution.csv").unlink()
    with pytest.raises(ValueError, match="missing"):
        ap.package(out, target)


def test_a_run_that_read_the_package_is_never_packaged(tmp_path):
    # reading writes this run's stamp, marked: packaging it would ship the package's
    # rows under another run's stamp (a subset run's rows under the full run's)
    stamp, table = _packaged()
    claims, params = _claims_of(stamp), _params(stamp)
    got = ap.attribute_claims(tmp_path, claims, {"params": params, "n_jobs": 1})
    assert got.source
    with pytest.raises(ValueError, match="read the packaged attribution"):
        ap.package(tmp_path, tmp_path / "ref")


def test_the_reproduction_reads_the_package_or_searches_and_stamps(tmp_path, monkeypatch, capsys):
    from tefcore.paper.attribution import differences

    stamp, table = _packaged()
    claims, params = _claims_of(stamp), _params(stamp)
    searched = []

    def search(out, claims, params=None, n_jobs=1, **kw):
        searched.append(out)
        (out / "attribution.csv").write_text("claim\n")
        return Attribution(table.iloc[0:0], 5.0, 3.0, 2)

    monkeypatch.setattr(differences, "attribute_run", search)
    got = ap.attribute_claims(tmp_path, claims, {"params": params, "n_jobs": 1})
    assert searched == [] and got.source and got.cpu_seconds == 0.0
    assert set(pd.read_csv(tmp_path / "attribution.csv")["claim"]) == set(table["claim"])
    rec = json.loads((tmp_path / "attribution.json").read_text())
    assert rec["read_from_package"] is True and rec["statuses"] == stamp["statuses"]
    assert rec["code_stamp"] == stamp["code_stamp"] and "tasks" not in rec
    # the default rotor named (-p config mdart) or a notebook's default given is the
    # same run: the package is read
    named = {n: {**p, "config": "mdart"} for n, p in params.items()}
    assert ap.attribute_claims(tmp_path, claims, {"params": named, "n_jobs": 1}).source
    # asked to search: it searches, and stamps what it searched with
    got = ap.attribute_claims(tmp_path, claims, {"params": params, "n_jobs": 1, "again": True})
    assert searched == [tmp_path] and got.source == ""
    rec = json.loads((tmp_path / "attribution.json").read_text())
    assert rec["cpu_seconds"] == 5.0 and rec["statuses"] == stamp["statuses"]
    # a verdict moved: the package does not apply, the run says why and searches
    moved = claims.copy()
    moved.loc[0, "status"] = "fail" if moved.loc[0, "status"] == "pass" else "pass"
    ap.attribute_claims(tmp_path, moved, {"params": params, "n_jobs": 1})
    assert len(searched) == 2 and "checked otherwise" in capsys.readouterr().err


def test_a_run_that_checked_no_claim_attributes_nothing(tmp_path):
    # a notebook that failed leaves no claims: nothing is read or searched, and the
    # run does not say it read the package for them
    stamp, _ = _packaged()
    empty = _claims_of(stamp).iloc[0:0]
    assert ap.attribute_claims(tmp_path, empty, {"params": _params(stamp), "n_jobs": 1}) is None
    assert not (tmp_path / "attribution.csv").exists()
