"""Package a default reproduction's attribution: ``python tools/package_attribution.py OUT``.

OUT is a finished ``tefcore reproduce --out OUT --attribute-again`` of the
default rotor with this code and data; its ``attribution.csv`` and
``attribution.json`` are checked (:func:`tefcore.paper.run.attribution_phase.package`)
and copied to ``tefcore/paper/reference_data/attribution-mdart.*``, which
``tefcore reproduce`` then reads instead of searching.
"""

import sys

from tefcore.paper.run.attribution_phase import package


def main(argv) -> int:
    if len(argv) != 1:
        print(__doc__.splitlines()[0], file=sys.stderr)
        return 2
    try:
        written = package(argv[0])
    except ValueError as err:
        print(f"package_attribution: {err}", file=sys.stderr)
        return 1
    print("wrote " + " and ".join(str(p) for p in written))
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
