#!/usr/bin/python3
"""Checks a run folder of the 1D elastic bar written by `rktsph run`, independently of rktsph:
every file listed in series.pvd parses (tests/output/read_vtu.py), and in the last one the driven
end moves at the imposed velocity and the free end carries no stress.

    check_run_output.py RUN_DIR IMPOSED_VELOCITY
Exit status 0 when every check holds; the failed check is printed otherwise.
"""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "output"))
import read_vtu  # noqa: E402


def main(run_dir, imposed_velocity):
    collection = read_vtu.read_pvd(os.path.join(run_dir, "series.pvd"))["datasets"]
    assert len(collection) >= 2, "fewer than two snapshots"
    times = [d["timestep"] for d in collection]
    assert times == sorted(times), "snapshots not in time order"
    grids = [read_vtu.read_vtu(os.path.join(run_dir, d["file"])) for d in collection]
    last = grids[-1]
    x = last["Points"]["values"][0::3]
    velocity = last["PointData"]["velocity"]["values"]
    stress = last["PointData"]["stress"]["values"]
    driven = max(range(len(x)), key=lambda i: x[i])
    free = min(range(len(x)), key=lambda i: x[i])
    assert velocity[3 * driven] == imposed_velocity, f"driven end v = {velocity[3 * driven]}"
    assert stress[9 * free] == 0.0, f"free end sigma_xx = {stress[9 * free]}"
    summary = json.load(open(os.path.join(run_dir, "summary.json")))
    assert summary["status"] == "completed", summary
    assert summary["steps"] > 0
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1], float(sys.argv[2])))
    except (AssertionError, KeyError, OSError, read_vtu.FormatError) as error:
        print(f"check_run_output.py: {error}", file=sys.stderr)
        sys.exit(1)
