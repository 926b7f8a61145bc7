#!/usr/bin/python3
"""Checks that the points of every field file of a run are its current positions X + u: X read
from the first file (t = 0, where u = 0), u the file's displacement field. Fails, too, if no point
ever moves, since then the check would say nothing.

    check_positions.py RUN_DIR
Exit status 0 when every file holds; the first mismatch is printed otherwise.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import read_vtu  # noqa: E402


def main(run_dir):
    datasets = read_vtu.read_pvd(os.path.join(run_dir, "series.pvd"))["datasets"]
    grids = [read_vtu.read_vtu(os.path.join(run_dir, d["file"])) for d in datasets]
    first = grids[0]
    assert max(abs(u) for u in first["PointData"]["displacement"]["values"]) == 0.0, \
        "the first file is not at u = 0"
    reference = first["Points"]["values"]
    largest_motion = 0.0
    for dataset, grid in zip(datasets, grids):
        points = grid["Points"]["values"]
        displacement = grid["PointData"]["displacement"]["values"]
        for k, (x, X, u) in enumerate(zip(points, reference, displacement)):
            assert abs(x - (X + u)) <= 1e-12 * max(1.0, abs(X)), \
                f"{dataset['file']}: point {k // 3} axis {k % 3}: {x} is not X + u = {X} + {u}"
            largest_motion = max(largest_motion, abs(u))
    assert largest_motion > 0.0, "no point moved"
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1]))
    except (AssertionError, KeyError, OSError, read_vtu.FormatError) as error:
        print(f"check_positions.py: {error}", file=sys.stderr)
        sys.exit(1)
