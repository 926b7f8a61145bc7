#!/usr/bin/python3
"""Sideways motion of BAR-WAVE-2D on unstructured triangles: rktsph against textbook finite
elements on the same meshes (docs/theory.md §8.11, "An independent reference"):
`make bench-fe-triangles`.

Usage::

    bench/peers/fe_triangles_bar_wave_2d.py --build BUILD_DIR [--out DIR]
        [--sizes 0.01 0.007 0.005]

The plane P-wave of BAR-WAVE-2D (bar 1 m x 0.25 m, E = 150 MPa, nu = 0.25, rho = 2000 kg/m3,
c_p = 300 m/s, piston v = (0.3, 0) m/s at x = 0 from t = 0, free at x = 1 m, rollers on y = 0 and
y = 0.25 m, plane strain) is run to half a transit, 0.5 L/c_p, on triangle meshes written by Gmsh
(Debian `gmsh`): its Frontal-Delaunay mesher at each target edge length of --sizes, and, as
the control, a lattice whose squares are cut into four by both diagonals ("Alternate"), which is
symmetric about every horizontal line through a node row, so v_y must stay zero to rounding; and
the project's own mesh of `triangles-bar-wave-2d` at each spacing of --project-sizes (CGAL, with
its boundary layer), written by `rktsph check --write-mesh`.

On each mesh two codes run at dt = 0.3 of the narrowest cell width over c_p:

* rktsph, the mesh read through `geometry.mesh`, with its artificial viscosity alpha = 0.25 (the
  setting of `triangles-bar-wave-2d`);
* explicit finite elements written here from the textbook (Hughes, The Finite Element Method,
  ch. 7 and 9; Belytschko, Liu & Moran, Nonlinear Finite Elements, §6.2): three-node constant-strain
  triangles, lumped mass rho A / 3 per corner, central differences, the same piston and rollers as
  velocity constraints; undamped, and with a linear bulk viscosity q = b rho c_p l tr(eps_dot) in
  compression (l the cell width; b = 0.25 and 1).

Printed for every run: max |v_y| over all nodes and steps over V0 (the quantity of
`max_vy_ratio`), the same once the front has passed 5 cm and 30 cm, and, to show the finite
elements carry the right wave, the error of the mean v_x behind the front (0.1-0.4 m at 0.5 L/c_p)
against V0. Writes OUT/fe-triangles.json. Needs numpy (a dependency of python3-matplotlib).
"""

import argparse
import csv
import json
import os
import subprocess
import sys

import numpy as np

LENGTH, HEIGHT = 1.0, 0.25
DENSITY, YOUNG, POISSON = 2000.0, 1.5e8, 0.25
PISTON_VELOCITY = 0.3
COURANT = 0.3
LAME = YOUNG * POISSON / ((1 + POISSON) * (1 - 2 * POISSON))
SHEAR = YOUNG / (2 * (1 + POISSON))
WAVE_SPEED = np.sqrt((LAME + 2 * SHEAR) / DENSITY)  # 300 m/s
END = 0.5 * LENGTH / WAVE_SPEED

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))

GEO_FRONTAL = """// BAR-WAVE-2D bar meshed by Gmsh's Frontal-Delaunay, edges about {size} m
Point(1) = {{0, 0, 0, {size}}}; Point(2) = {{{length}, 0, 0, {size}}};
Point(3) = {{{length}, {height}, 0, {size}}}; Point(4) = {{0, {height}, 0, {size}}};
Line(1) = {{1, 2}}; Line(2) = {{2, 3}}; Line(3) = {{3, 4}}; Line(4) = {{4, 1}};
Curve Loop(1) = {{1, 2, 3, 4}}; Plane Surface(1) = {{1}};
Physical Surface("solid") = {{1}};
Mesh.Algorithm = 6;
"""
GEO_CROSSED = """// BAR-WAVE-2D bar: a lattice of {size} m squares, each cut by both diagonals
Point(1) = {{0, 0, 0}}; Point(2) = {{{length}, 0, 0}};
Point(3) = {{{length}, {height}, 0}}; Point(4) = {{0, {height}, 0}};
Line(1) = {{1, 2}}; Line(2) = {{2, 3}}; Line(3) = {{3, 4}}; Line(4) = {{4, 1}};
Curve Loop(1) = {{1, 2, 3, 4}}; Plane Surface(1) = {{1}};
Transfinite Curve{{1, 3}} = {along}; Transfinite Curve{{2, 4}} = {across};
Transfinite Surface{{1}} = {{1, 2, 3, 4}} Alternate;
Physical Surface("solid") = {{1}};
"""


def read_msh22(path):
    """Nodes (x, y) and 3-node triangles of an ASCII MSH 2.2 file."""
    with open(path) as stream:
        lines = stream.read().split("\n")
    start = lines.index("$Nodes")
    count = int(lines[start + 1])
    index, points = {}, []
    for k in range(count):
        fields = lines[start + 2 + k].split()
        index[int(fields[0])] = k
        points.append((float(fields[1]), float(fields[2])))
    start = lines.index("$Elements")
    triangles = []
    for k in range(int(lines[start + 1])):
        fields = lines[start + 2 + k].split()
        if fields[1] == "2":
            tags = int(fields[2])
            triangles.append([index[int(v)] for v in fields[3 + tags : 6 + tags]])
    return np.array(points), np.array(triangles)


def cell_widths(points, triangles):
    corners = points[triangles]
    edges = [np.linalg.norm(corners[:, (k + 1) % 3] - corners[:, k], axis=1) for k in range(3)]
    doubled_area = np.abs(
        (corners[:, 1, 0] - corners[:, 0, 0]) * (corners[:, 2, 1] - corners[:, 0, 1])
        - (corners[:, 2, 0] - corners[:, 0, 0]) * (corners[:, 1, 1] - corners[:, 0, 1]))
    return doubled_area / np.max(edges, axis=0)


def finite_elements(points, triangles, bulk):
    """Explicit CST finite elements; returns the run's sideways and plateau measures."""
    corners = points[triangles]
    x, y = corners[..., 0], corners[..., 1]
    doubled_area = ((x[:, 1] - x[:, 0]) * (y[:, 2] - y[:, 0])
                    - (x[:, 2] - x[:, 0]) * (y[:, 1] - y[:, 0]))
    flip = doubled_area < 0
    triangles = np.where(flip[:, None], triangles[:, [0, 2, 1]], triangles)
    corners = points[triangles]
    x, y = corners[..., 0], corners[..., 1]
    doubled_area = np.abs(doubled_area)
    area = 0.5 * doubled_area
    dndx = np.stack([y[:, 1] - y[:, 2], y[:, 2] - y[:, 0], y[:, 0] - y[:, 1]], 1)
    dndy = np.stack([x[:, 2] - x[:, 1], x[:, 0] - x[:, 2], x[:, 1] - x[:, 0]], 1)
    dndx, dndy = dndx / doubled_area[:, None], dndy / doubled_area[:, None]
    width = cell_widths(points, triangles)
    dt = COURANT * width.min() / WAVE_SPEED
    nodes = len(points)
    mass = np.zeros(nodes)
    np.add.at(mass, triangles.ravel(), np.repeat(DENSITY * area / 3.0, 3))
    tolerance = 1e-9 * LENGTH
    piston = np.abs(points[:, 0]) < tolerance
    roller = (np.abs(points[:, 1]) < tolerance) | (np.abs(points[:, 1] - HEIGHT) < tolerance)
    displacement = np.zeros((nodes, 2))
    velocity = np.zeros((nodes, 2))
    velocity[piston] = (PISTON_VELOCITY, 0.0)
    steps = int(np.ceil(END / dt))
    sideways = np.zeros(steps)
    for step in range(steps):
        u, v = displacement[triangles], velocity[triangles]
        exx = (dndx * u[..., 0]).sum(1)
        eyy = (dndy * u[..., 1]).sum(1)
        gxy = (dndy * u[..., 0] + dndx * u[..., 1]).sum(1)
        sxx = LAME * (exx + eyy) + 2 * SHEAR * exx
        syy = LAME * (exx + eyy) + 2 * SHEAR * eyy
        sxy = SHEAR * gxy
        if bulk > 0:
            rate = (dndx * v[..., 0]).sum(1) + (dndy * v[..., 1]).sum(1)
            q = np.where(rate < 0, bulk * DENSITY * WAVE_SPEED * width * rate, 0.0)
            sxx, syy = sxx + q, syy + q
        force = np.zeros((nodes, 2))
        corner_x = -area[:, None] * (dndx * sxx[:, None] + dndy * sxy[:, None])
        corner_y = -area[:, None] * (dndx * sxy[:, None] + dndy * syy[:, None])
        np.add.at(force[:, 0], triangles.ravel(), corner_x.ravel())
        np.add.at(force[:, 1], triangles.ravel(), corner_y.ravel())
        velocity += dt * force / mass[:, None]
        velocity[piston] = (PISTON_VELOCITY, 0.0)
        velocity[roller, 1] = 0.0
        displacement += dt * velocity
        sideways[step] = np.abs(velocity[:, 1]).max()
    behind = (points[:, 0] > 0.1) & (points[:, 0] < 0.4)
    return measures(dt * np.arange(1, steps + 1), sideways, velocity[behind, 0].mean())


def measures(times, sideways, behind_velocity):
    """max |v_y| / V0 over the run and once the front is past 5 and 30 cm; v_x behind the front."""
    def largest_after(distance):
        return float(sideways[times > distance / WAVE_SPEED].max() / PISTON_VELOCITY)
    return {
        "steps": len(times),
        "max_vy_ratio": largest_after(0.0),
        "max_vy_ratio_front_past_5cm": largest_after(0.05),
        "max_vy_ratio_front_past_30cm": largest_after(0.3),
        "plateau_vx_error": float(abs(behind_velocity / PISTON_VELOCITY - 1.0)),
    }


def rktsph(build, mesh, folder):
    """rktsph on the mesh file, with its artificial viscosity; the same measures from probes.csv."""
    case = os.path.join(folder, "case.yaml")
    with open(case, "w") as stream:
        stream.write(f"""name: fe-triangles-bar-wave-2d
description: BAR-WAVE-2D on a Gmsh mesh, half a transit
dimension: 2
plane: strain
geometry:
  mesh: {os.path.abspath(mesh)}
materials:
  solid: {{model: linear_elastic, density: {DENSITY}, young_modulus: {YOUNG}, poisson_ratio: {POISSON}}}
groups:
  behind: {{box: {{min: [0.1, 0.0], max: [0.4, {HEIGHT}]}}}}
boundary_conditions:
  - {{group: xmin, velocity: {{x: {PISTON_VELOCITY}, y: 0.0}}}}
  - {{group: ymin, roller: y}}
  - {{group: ymax, roller: y}}
numerics: {{courant: {COURANT}, artificial_viscosity: 0.25}}
time: {{end: {END!r}}}
output: {{interval: {END!r}}}
probes:
  - {{name: all, group: all, fields: [velocity_y], reduction: max_abs}}
  - {{name: behind, group: behind, fields: [velocity_x], reduction: mean}}
""")
    out = os.path.join(folder, "rktsph")
    subprocess.run([os.path.join(build, "rktsph"), "run", case, "-o", out, "--quiet", "--overwrite"],
                   check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "probes.csv")) as stream:
        rows = list(csv.DictReader(stream))
    rows = rows[1:]  # the row of t = 0
    times = np.array([float(r["time"]) for r in rows])
    sideways = np.array([abs(float(r["all.velocity_y"])) for r in rows])
    return measures(times, sideways, float(rows[-1]["behind.velocity_x"]))


def mesh(kind, size, folder, build):
    geo = os.path.join(folder, "bar.geo")
    msh = os.path.join(folder, "bar.msh")
    if kind == "project":
        # The mesh of triangles-bar-wave-2d itself (CGAL, with its boundary layer), as rktsph
        # check writes it.
        case = os.path.join(SOURCE, "cases", "triangles-bar-wave-2d", "case.yaml")
        subprocess.run([os.path.join(build, "rktsph"), "check", case, "--set",
                        f"geometry.spacing={size}", "--write-mesh", msh], check=True,
                       stdout=subprocess.DEVNULL)
        return msh
    with open(geo, "w") as stream:
        if kind == "frontal":
            stream.write(GEO_FRONTAL.format(size=size, length=LENGTH, height=HEIGHT))
        else:
            stream.write(GEO_CROSSED.format(size=size, length=LENGTH, height=HEIGHT,
                                            along=round(LENGTH / size) + 1,
                                            across=round(HEIGHT / size) + 1))
    subprocess.run(["gmsh", "-2", "-format", "msh22", geo, "-o", msh], check=True,
                   stdout=subprocess.DEVNULL)
    return msh


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", required=True)
    parser.add_argument("--out")
    parser.add_argument("--sizes", nargs="+", type=float, default=[0.01, 0.007, 0.005])
    parser.add_argument("--project-sizes", nargs="*", type=float, default=[0.01, 0.005])
    args = parser.parse_args()
    out = args.out or os.path.join(args.build, "bench-fe-triangles")
    meshes = [("crossed", 0.01)] + [("frontal", size) for size in args.sizes]
    meshes += [("project", size) for size in args.project_sizes]
    results = []
    header = (f"{'mesh':<16}{'nodes':>7}{'code':>22}{'steps':>7}{'max|vy|/V0':>12}"
              f"{'past 5cm':>10}{'past 30cm':>11}{'vx plateau':>12}")
    print(header)
    for kind, size in meshes:
        folder = os.path.join(out, f"{kind}-{size:g}")
        os.makedirs(folder, exist_ok=True)
        points, triangles = read_msh22(mesh(kind, size, folder, args.build))
        runs = [("rktsph (alpha 0.25)",
                 rktsph(args.build, os.path.join(folder, "bar.msh"), folder))]
        for bulk in (0.0, 0.25, 1.0):
            runs.append((f"CST FE (bulk {bulk:g})", finite_elements(points, triangles, bulk)))
        for code, measured in runs:
            label = f"{kind} {size:g}"
            print(f"{label:<16}{len(points):>7}{code:>22}{measured['steps']:>7}"
                  f"{measured['max_vy_ratio']:>12.3g}{measured['max_vy_ratio_front_past_5cm']:>10.3g}"
                  f"{measured['max_vy_ratio_front_past_30cm']:>11.3g}{measured['plateau_vx_error']:>12.2g}")
            results.append({"mesh": kind, "size": size, "nodes": len(points),
                            "triangles": len(triangles), "code": code, **measured})
        sys.stdout.flush()
    with open(os.path.join(out, "fe-triangles.json"), "w") as stream:
        json.dump(results, stream, indent=1)
    print(f"written {os.path.join(out, 'fe-triangles.json')}")


if __name__ == "__main__":
    main()
