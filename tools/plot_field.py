#!/usr/bin/python3
"""Draws one output field of an rktsph run as a picture of its particles (`rktsph plot`).

    plot_field.py RUN_DIR --field NAME [--component C] [--time T] [--magnify M] -o FILE.png
                  [--title TEXT] [--dump]

Reads RUN_DIR/series.pvd, takes the snapshot whose time is nearest T (the last one without
--time), reads its .vtu with the test suite's independent reader (tests/output/read_vtu.py) and
draws every particle as a square of the lattice spacing, coloured by the field, at X + M u: X its
reference position, u its displacement, for every model (M = 0: the undeformed body, M = 1: the
current positions, which are the points of the field files). --component picks one entry of the VTK tuple (stress: 0 = xx,
1 = xy, 4 = yy; velocity: 0 = x, 1 = y); without it a scalar is drawn as is and a vector or
tensor as its magnitude. --dump prints what would be drawn as JSON (for tests); -o is then
optional.

Exit status: 0 drawn, 2 bad input (no such run, field, component or time), 1 anything else.
"""

import argparse
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "output"))
import read_vtu  # noqa: E402  (the standard-library VTU/PVD reader shared with the tests)

VECTOR_COMPONENTS = ["x", "y", "z"]
TENSOR_COMPONENTS = ["xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"]
UNITS = {"stress": "Pa", "total_stress": "Pa", "pressure": "Pa", "pore_pressure": "Pa",
         "deviatoric_stress": "Pa", "velocity": "m/s", "displacement": "m", "eps_vp": "-",
         "material": "-"}


class InputProblem(Exception):
    """Something the user asked for that the run does not have (exit status 2)."""


def pick_snapshot(datasets, time):
    if not datasets:
        raise InputProblem("series.pvd lists no snapshots")
    if time is None or time < 0:
        return datasets[-1]
    # Nearest in time; on a tie the earlier one, as min() keeps the first.
    return min(datasets, key=lambda entry: abs(entry["timestep"] - time))


def component_name(field, components, component):
    if component < 0:
        return field if components == 1 else f"|{field}|"
    if components == 3:
        return f"{field}_{VECTOR_COMPONENTS[component]}"
    if components == 9:
        return f"{field}_{TENSOR_COMPONENTS[component]}"
    return f"{field}[{component}]"


def field_values(grid, field, component):
    """The value to colour each point by, and its label."""
    arrays = grid["PointData"]
    if field not in arrays:
        raise InputProblem(f"no field {field!r} in this output; it has: "
                           + ", ".join(sorted(arrays)))
    array = arrays[field]
    components = array["components"]
    values = array["values"]
    count = grid["NumberOfPoints"]
    if component >= components:
        raise InputProblem(f"field {field!r} has {components} component(s); "
                           f"--component must be below {components}")
    if component >= 0:
        data = [values[i * components + component] for i in range(count)]
    elif components == 1:
        data = list(values)
    else:
        data = [math.sqrt(sum(v * v for v in values[i * components:(i + 1) * components]))
                for i in range(count)]
    return data, component_name(field, components, component)


def drawn_positions(grid, magnification):
    """x and y of each point at X + magnification * u. The points of a field file are the current
    positions X + u (every model), so X + M u = points + (M - 1) u."""
    points = grid["Points"]["values"]
    count = grid["NumberOfPoints"]
    x = [points[3 * i] for i in range(count)]
    y = [points[3 * i + 1] for i in range(count)]
    if magnification != 1:
        if "displacement" not in grid["PointData"]:
            raise InputProblem("this output has no displacement field, so only --magnify 1 "
                               "(the current positions) can be drawn")
        displacement = grid["PointData"]["displacement"]["values"]
        shift = magnification - 1.0
        x = [x[i] + shift * displacement[3 * i] for i in range(count)]
        y = [y[i] + shift * displacement[3 * i + 1] for i in range(count)]
    return x, y


def positions_text(magnification):
    """What the drawn positions are, for the title."""
    if magnification == 0:
        return "undeformed, X"
    if magnification == 1:
        return "current positions, X + u"
    return f"X + {magnification:g} u"


def lattice_spacing(grid):
    """Typical distance to the nearest other point in the undeformed configuration."""
    import numpy
    points = numpy.array(grid["Points"]["values"], dtype=float).reshape(-1, 3)
    if len(points) < 2:
        return 1.0
    # A sample of points against all keeps this O(n) for large lattices; the median ignores the
    # odd node placed closer (boundary layers, refinements).
    step = max(1, len(points) // 200)
    nearest = []
    for point in points[::step]:
        distance = numpy.sqrt(((points - point) ** 2).sum(axis=1))
        distance = distance[distance > 0]
        if len(distance):
            nearest.append(distance.min())
    return float(numpy.median(nearest)) if nearest else 1.0


def colour_scale(values):
    """Colour map and limits: symmetric about zero when the field changes sign."""
    low, high = min(values), max(values)
    if low < 0 < high:
        bound = max(-low, high)
        return "coolwarm", -bound, bound
    if high - low <= 1e-12 * max(abs(low), abs(high), 1e-300):
        # A uniform field still needs a colour bar with a range.
        pad = 0.5 * abs(high) if high != 0 else 1.0
        return "viridis", low - pad, high + pad
    return "viridis", low, high


def draw(path, x, y, values, spacing, label, unit, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.axes_grid1 import make_axes_locatable

    margin = 2.0 * spacing
    x_range = (min(x) - margin, max(x) + margin)
    y_range = (min(y) - margin, max(y) + margin)
    width, height = x_range[1] - x_range[0], y_range[1] - y_range[0]
    # Figure shaped like the body (within limits) so that the equal-aspect plot fills it.
    plot_width = 8.0
    plot_height = min(max(plot_width * height / width, 1.2), 8.0)
    figure, axes = plt.subplots(figsize=(plot_width + 1.8, plot_height + 1.4), dpi=120)
    axes.set_xlim(*x_range)
    axes.set_ylim(*y_range)
    axes.set_aspect("equal", adjustable="box")
    figure.canvas.draw()  # fixes the final limits and axes box before measuring a spacing
    origin = axes.transData.transform((0.0, 0.0))
    corner = axes.transData.transform((spacing, spacing))
    side_points = min(abs(corner[0] - origin[0]), abs(corner[1] - origin[1])) * 72.0 / figure.dpi
    colour_map, low, high = colour_scale(values)
    markers = axes.scatter(x, y, c=values, cmap=colour_map, vmin=low, vmax=high, marker="s",
                           s=side_points ** 2, linewidths=0)
    # A colour bar as tall as the (often flat) axes box, not as the figure.
    bar_axes = make_axes_locatable(axes).append_axes("right", size=0.15, pad=0.15)
    bar = figure.colorbar(markers, cax=bar_axes)
    bar.set_label(f"{label} [{unit}]")
    axes.set_xlabel("x [m]")
    axes.set_ylabel("y [m]")
    axes.set_title(title)
    figure.savefig(path, bbox_inches="tight")
    plt.close(figure)


def main(arguments):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("run_directory")
    parser.add_argument("--field", required=True)
    parser.add_argument("--component", type=int, default=-1)
    parser.add_argument("--time", type=float, default=None)
    parser.add_argument("--magnify", type=float, default=0.0)
    parser.add_argument("-o", "--output")
    parser.add_argument("--title")
    parser.add_argument("--dump", action="store_true")
    options = parser.parse_args(arguments)
    if options.output is None and not options.dump:
        parser.error("-o FILE.png is required (or --dump)")
    if options.component < -1:
        raise InputProblem("--component must be 0 or more (-1: scalar value or magnitude)")

    pvd = os.path.join(options.run_directory, "series.pvd")
    if not os.path.isfile(pvd):
        raise InputProblem(f"{pvd} does not exist (is {options.run_directory} a run folder "
                           "with field output?)")
    snapshot = pick_snapshot(read_vtu.read_pvd(pvd)["datasets"], options.time)
    grid = read_vtu.read_vtu(os.path.join(options.run_directory, snapshot["file"]))
    values, label = field_values(grid, options.field, options.component)
    x, y = drawn_positions(grid, options.magnify)
    time = snapshot["timestep"]
    if options.dump:
        print(json.dumps({"time": time, "file": snapshot["file"], "label": label, "x": x,
                          "y": y, "values": values,
                          "positions": positions_text(options.magnify)}))
    if options.output:
        title = f"{options.title or label}, t = {time:.4g} s ({positions_text(options.magnify)})"
        draw(options.output, x, y, values, lattice_spacing(grid), label,
             UNITS.get(options.field, "-"), title)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except InputProblem as problem:
        print(f"plot_field.py: {problem}", file=sys.stderr)
        sys.exit(2)
    except ImportError:
        print("plot_field.py: matplotlib is missing: install python3-matplotlib "
              "(make deps-report)", file=sys.stderr)
        sys.exit(1)
    except (read_vtu.FormatError, OSError) as problem:
        print(f"plot_field.py: cannot read the run: {problem}", file=sys.stderr)
        sys.exit(2)
