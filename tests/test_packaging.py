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
        assert any(_ships(rel, pat) for pat in data[package]), rel


def test_every_file_of_the_data_folders_ships():
    """Each file of the folders the package reads its data from matches a package-data
    pattern: a file added beside the others (a variant's converged-basis verdicts, the
    packaged attribution) would otherwise be missing from a wheel and the installed
    tool would say it has none."""
    data = PYPROJECT["tool"]["setuptools"]["package-data"]
    missing = []
    for package, folder in (("tefcore", "data"), ("tefcore.paper", "reference_data")):
        root = ROOT / package.replace(".", "/")
        for f in sorted((root / folder).rglob("*")):
            if f.is_file() and not f.name.startswith(".") and "__pycache__" not in f.parts:
                rel = f.relative_to(root).as_posix()
                if not any(_ships(rel, pat) for pat in data[package]):
                    missing.append(f"{package}: {rel}")
    assert not missing, missing


def _ships(rel: str, pattern: str) -> bool:
    """Does a package-data glob match `rel` as setuptools reads it: part by part (a
    ``*`` never crosses a ``/``), the same number of parts."""
    import fnmatch

    parts, pats = rel.split("/"), pattern.split("/")
    return len(parts) == len(pats) and all(fnmatch.fnmatchcase(a, b)
                                           for a, b in zip(parts, pats, strict=True))


def test_a_glob_of_one_folder_does_not_ship_its_subfolders():
    # the check above reads the patterns as setuptools does, or it could pass for a
    # file a wheel leaves out
    assert _ships("data/mdart.toml", "data/*.toml")
    assert not _ships("data/inference/results/x.toml", "data/*.toml")
    assert not _ships("reference_data/curves/a.csv", "reference_data/*.csv")
