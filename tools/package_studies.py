"""Run the packaged inference studies and write their results into the package.

    python tools/package_studies.py STORAGE [--jobs N] [--no-check] [--sobol]

Runs every study of ``tefcore.paper.inference.packaged.STUDIES`` in STORAGE (a
journal file or an RDB URL; a study already there is resumed to its trials),
then writes ``tefcore/data/inference/results/`` (trials, claims, summary and the
check of the baseline and the best rotors on every claim).  Each study is the
``tefcore infer`` command :func:`~tefcore.paper.inference.packaged.study_command`
prints.  ``--sobol`` also runs the packaged Sobol analysis
(:func:`~tefcore.paper.inference.packaged.export_sobol`: 64 rotors, about 8 min on
two cores).
"""

import argparse

from tefcore.paper.inference.packaged import STUDIES, export_results, export_sobol, study_command
from tefcore.paper.inference.study import StudySpec, run_study
from tefcore.runtime import apply_defaults


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("storage")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--no-check", action="store_true")
    ap.add_argument("--sobol", action="store_true")
    args = ap.parse_args()
    apply_defaults()
    for s in STUDIES:
        print(study_command(s), f"--storage {args.storage}", flush=True)
        run_study(StudySpec(reading=s["reading"], sampler=s["sampler"], seed=s["seed"],
                            storage=args.storage), s["trials"], args.jobs)
    print("results:", export_results(args.storage, check=not args.no_check))
    if args.sobol:
        print("Sobol:", export_sobol(cache_folder=f"{args.storage}.sobol", n_jobs=args.jobs))


if __name__ == "__main__":
    main()
