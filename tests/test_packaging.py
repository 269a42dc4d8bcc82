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


def test_every_file_of_the_data_folders_ships():
    """Each file of the folders the package reads its data from matches a package-data
    pattern: a file added beside the others (a variant's converged-basis verdicts, the
    packaged attribution) would otherwise be missing from a wheel and the installed
    tool would say it has none."""
    import fnmatch

    data = PYPROJECT["tool"]["setuptools"]["package-data"]
    folders = (("tefcore", "data"), ("tefcore", "data/inference"),
               ("tefcore", "data/inference/results"), ("tefcore.paper", "reference_data"),
               ("tefcore.paper", "reference_data/curves"))
    missing = []
    for package, folder in folders:
        root = ROOT / package.replace(".", "/")
        for f in sorted((root / folder).iterdir()):
            if f.is_file() and not f.name.startswith("."):
                rel = f.relative_to(root).as_posix()
                if not any(fnmatch.fnmatch(rel, pat) for pat in data[package]):
                    missing.append(f"{package}: {rel}")
    assert not missing, missing
