"""Packaging metadata in the current fields.

``python -m build`` warned that the TOML-table ``project.license`` and the
license classifiers are deprecated (setuptools >= 77, PEP 639): the license
is an SPDX expression with its file named in ``license-files``.
"""

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))


def test_the_license_is_an_spdx_expression_with_its_file():
    project = PYPROJECT["project"]
    assert project["license"] == "BSD-3-Clause"
    files = project["license-files"]
    assert files and all(list(ROOT.glob(pattern)) for pattern in files)
    assert (ROOT / "LICENSE").read_text(encoding="utf-8").startswith("BSD 3-Clause License")


def test_no_license_classifier():
    assert not [c for c in PYPROJECT["project"]["classifiers"] if c.startswith("License ::")]


def test_the_build_backend_reads_the_license_fields():
    # setuptools reads PEP 639's license / license-files from version 77 on
    requires = PYPROJECT["build-system"]["requires"]
    assert any(r.replace(" ", "").startswith("setuptools>=") and
               int(r.replace(" ", "").split(">=")[1].split(".")[0]) >= 77 for r in requires)


def test_the_packaged_data_files_are_in_the_package_data():
    """Every data file the package reads at run time is declared (a wheel would lack it)."""
    import fnmatch

    data = PYPROJECT["tool"]["setuptools"]["package-data"]
    for package, rel in (("tefcore", "data/mdart.toml"), ("tefcore", "data/mdart-fig6.toml"),
                         ("tefcore.paper.claims", "variants.toml"),
                         ("tefcore.paper.run", "templates/report.html.j2"),
                         ("tefcore.paper.attribution", "departures.toml"),
                         ("tefcore", "data/mdart-inferred.toml"),
                         ("tefcore", "data/inference/results/summary.json"),
                         ("tefcore", "data/inference/results/trials.csv"),
                         ("tefcore", "data/inference/results/claims.csv"),
                         ("tefcore.paper", "reference_data/converged_basis.csv"),
                         ("tefcore.paper", "reference_data/converged_basis.json")):
        assert (ROOT / package.replace(".", "/") / rel).is_file(), rel
        assert any(fnmatch.fnmatch(rel, pat) for pat in data[package]), rel
