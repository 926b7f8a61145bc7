#!/usr/bin/env python3
"""The layering rule of src/rktsph (README "Layout"): a file of one folder includes headers of its
own folder and of the folders below it in LAYERS, never of a folder above. Exits 1 and names every
offending include; `--self-test` checks that the rule catches a violation in a made-up tree.

The step, its controls and the physics seam (SCHEMA_FREE) do not include the case schema either.

Usage: check_layering.py SRC_DIR        (SRC_DIR is the directory holding rktsph/)
       check_layering.py --self-test
"""
import pathlib
import re
import sys
import tempfile

# Bottom to top. A folder may include its own layer and every layer before it.
LAYERS = [
    "core",           # errors, field arrays, checkpoint streams, time functions
    "linear_algebra", # sparse rows, conjugate gradients, smoothed-aggregation multigrid
    "mesh",           # the cell complex, cell kinds, the outline
    "sph",            # kernels, neighbour search, corrective operator tables, Laplacian
    "case",           # case file -> CaseDescription
    "geometry",       # shapes -> reference configuration, groups
    "materials",      # one material per file
    "physics",        # the seam: PhysicsModel, State, field layout, kinematics
    "boundary",       # constraints and surfaces with normals
    "stabilisation",  # zero-energy-mode controls
    "time",           # the one RK-TSPH step and its operator builder
    "models",         # dry solid, saturated v-pw, registry
    "simulation",     # assembly and the loop
    "output",         # observers that write files
    "driver",         # a run from a case file
    "strength_reduction",  # the factor of safety: strength-reduced runs and the bisection
    "validation",     # references and case checks (its own library)
]

# Folders above `case` that must still not read the case schema: the step, its controls and the
# seam between them and the models take plain values (README "Layout").
SCHEMA_FREE = ["physics", "stabilisation", "time"]

INCLUDE = re.compile(r'^\s*#\s*include\s*"rktsph/([a-z_]+)/')


def violations(src: pathlib.Path):
    rank = {name: i for i, name in enumerate(LAYERS)}
    root = src / "rktsph"
    found = []
    for path in sorted(root.rglob("*")):
        if path.suffix not in (".hpp", ".cpp") or not path.is_file():
            continue
        folder = path.relative_to(root).parts[0]
        if folder not in rank:
            found.append(f"{path}: folder '{folder}' has no layer in tools/check_layering.py")
            continue
        for number, line in enumerate(path.read_text().splitlines(), start=1):
            match = INCLUDE.match(line)
            if not match:
                continue
            target = match.group(1)
            if target not in rank:
                found.append(f"{path}:{number}: includes unknown folder '{target}'")
            elif rank[target] > rank[folder]:
                found.append(f"{path}:{number}: layer '{folder}' includes higher layer '{target}'")
            elif target == "case" and folder in SCHEMA_FREE:
                found.append(f"{path}:{number}: layer '{folder}' reads the case schema")
    return found


def self_test() -> int:
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp) / "rktsph"
        (root / "core").mkdir(parents=True)
        (root / "time").mkdir()
        (root / "time" / "step.hpp").write_text('#include "rktsph/core/a.hpp"\n')
        if violations(pathlib.Path(tmp)):
            print("self-test: a downward include was reported")
            return 1
        (root / "core" / "a.hpp").write_text('#include "rktsph/time/step.hpp"\n')
        if len(violations(pathlib.Path(tmp))) != 1:
            print("self-test: an upward include was not reported")
            return 1
        (root / "core" / "a.hpp").write_text("")
        (root / "case").mkdir()
        (root / "time" / "step.hpp").write_text('#include "rktsph/case/spec.hpp"\n')
        if len(violations(pathlib.Path(tmp))) != 1:
            print("self-test: the step reading the case schema was not reported")
            return 1
    print("self-test passed")
    return 0


def main(argv) -> int:
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) != 2:
        print(__doc__)
        return 2
    found = violations(pathlib.Path(argv[1]))
    for line in found:
        print(line)
    if found:
        print(f"{len(found)} include(s) break the layering rule")
        return 1
    print(f"layering rule holds ({' < '.join(LAYERS)})")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
