#!/usr/bin/python3
"""rktsph against PySPH on BAR-WAVE-2D (docs/theory.md §8.11): `make bench-peers`.

Usage::

    bench/peers/run_peers.py --build BUILD_DIR [--out DIR] [--sizes s l] [--threads 1 2]
        [--repetitions 3] [--accuracy-size s]

1. Accuracy: both codes run size S (by default) for 3 transits L/c_p at dt = 0.3 dx/c_p;
   rktsph with its artificial viscosity (alpha = 0.25) and without, PySPH with the
   ElasticSolidsScheme's defaults (bench/peers/pysph_bar_wave_2d.py). The metrics of §8.11 are
   computed by one function from the probe files the two codes write (same columns).
2. Speed: for each repetition, size and thread count, rktsph's step benchmark
   (BM_BarWaveStep, the stepping loop only) and then PySPH's timed steps (setup and compilation
   not timed), interleaved so that both see the same machine; medians over the repetitions, with
   the peak resident memory of each process (/usr/bin/time -v) and the load average.

Prints the two tables and writes them to OUT/peers.json. SI units throughout.
"""

import argparse
import csv
import json
import math
import os
import statistics
import subprocess
import sys
import time

LENGTH, WAVE_SPEED, PISTON_VELOCITY = 1.0, 300.0, 0.3
IMPEDANCE_STRESS = 2000.0 * WAVE_SPEED * PISTON_VELOCITY  # rho c_p V0 = 180 kPa
TRANSIT = LENGTH / WAVE_SPEED
SPACING = {"t": 0.01, "s": 0.005, "m": 0.0025, "l": 0.00125, "xl": 0.0005}
TIMED_SIZES = ["s", "m", "l", "xl"]  # the sizes of rktsph's step benchmark
TIMED_STEPS = {"t": 200, "s": 200, "m": 100, "l": 50, "xl": 50}  # the protocol of §8.11
HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))
PYSPH_SCRIPT = os.path.join(HERE, "pysph_bar_wave_2d.py")


def read_probes(path):
    """The probe columns of a CSV written by either code, as lists of floats."""
    with open(path, newline="") as handle:
        rows = list(csv.DictReader(handle))
    return {key: [float(row[key]) for row in rows] for key in rows[0]}


def first_crossing(time_values, values, level):
    """Time at which `values` first reaches `level`, linearly interpolated; inf if never."""
    for i in range(1, len(values)):
        if values[i] >= level > values[i - 1]:
            fraction = (level - values[i - 1]) / (values[i] - values[i - 1])
            return time_values[i - 1] + fraction * (time_values[i] - time_values[i - 1])
    return math.inf


def window(time_values, values, start, end):
    return [v for t, v in zip(time_values, values) if start <= t <= end]


def metrics(probes, spacing):
    """The accuracy metrics of docs/theory.md §8.11 from the mid-bar, end and v_y probes."""
    t = probes["time"]
    mid_velocity = probes["mid.velocity_x"]
    mid_stress = probes["mid.stress_xx"]
    arrival = first_crossing(t, mid_velocity, 0.5 * PISTON_VELOCITY)
    plateau = statistics.fmean(window(t, mid_stress, 0.75 * TRANSIT, 1.3 * TRANSIT))
    result = {
        "arrival_error_dx": abs(arrival - 0.5 * TRANSIT) / (spacing / WAVE_SPEED),
        "sigma_xx_plateau_error": abs(plateau / -IMPEDANCE_STRESS - 1.0),
        "overshoot": max(window(t, mid_velocity, 0.0, 1.3 * TRANSIT)) / PISTON_VELOCITY - 1.0,
        "max_vy_ratio": max(abs(v) for v in probes["all.velocity_y"]) / PISTON_VELOCITY,
    }
    if t[-1] >= 2.95 * TRANSIT - 1e-12:
        tension = statistics.fmean(window(t, mid_stress, 2.75 * TRANSIT, 2.95 * TRANSIT))
        result["tension_plateau_error"] = abs(tension / IMPEDANCE_STRESS - 1.0)
    return result


def run(command, log_path, env=None, timed=True):
    """Runs `command` (with /usr/bin/time -v when timed); returns its peak RSS in MB or None."""
    full = list(command)
    time_file = log_path + ".time"
    if timed and os.path.exists("/usr/bin/time"):
        full = ["/usr/bin/time", "-v", "-o", time_file] + full
    with open(log_path, "w") as log:
        status = subprocess.run(full, stdout=log, stderr=subprocess.STDOUT, env=env).returncode
    if status != 0:
        sys.exit(f"error: {' '.join(command)} failed with status {status}; see {log_path}")
    if timed and os.path.exists(time_file):
        with open(time_file) as handle:
            for line in handle:
                if "Maximum resident set size" in line:
                    return int(line.split(":")[1]) / 1024.0
    return None


def load_average():
    with open("/proc/loadavg") as handle:
        return float(handle.read().split()[0])


def accuracy(args):
    size = args.accuracy_size
    spacing = SPACING[size]
    case = os.path.join(SOURCE, "cases", f"bar-wave-2d-{size}", "case.yaml")
    end = f"{3.0 * TRANSIT:.17g}"
    runs = {}
    for label, viscosity in (("rktsph, alpha = 0.25", "0.25"), ("rktsph, no AV", "0")):
        folder = os.path.join(args.out, f"rktsph-{size}-av{viscosity}")
        run([os.path.join(args.build, "rktsph"), "run", case, "--overwrite", "-o", folder,
             "--set", f"numerics.artificial_viscosity={viscosity}", "--set", f"time.end={end}",
             "--set", "output.interval=0"], folder + ".log", timed=False)
        runs[label] = metrics(read_probes(os.path.join(folder, "probes.csv")), spacing)
    env = dict(os.environ, OMP_NUM_THREADS="1")
    run([sys.executable, PYSPH_SCRIPT, "--size", size, "--out", args.out, "--end-transits", "3"],
        os.path.join(args.out, f"pysph-{size}-accuracy.log"), env=env, timed=False)
    runs["PySPH ElasticSolidsScheme"] = metrics(
        read_probes(os.path.join(args.out, f"pysph-{size}-probes.csv")), spacing)
    return runs


def rktsph_step_rate(args, size, threads, log):
    json_path = log + ".json"
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    rss = run([os.path.join(args.build, "rktsph_bench"), f"--benchmark_filter=^BM_BarWaveStep/{size}/",
               "--benchmark_repetitions=1", f"--benchmark_out={json_path}",
               "--benchmark_out_format=json"], log, env=env)
    with open(json_path) as handle:
        report = json.load(handle)
    runs = [b for b in report.get("benchmarks", []) if b.get("run_type") == "iteration"]
    if not runs:
        sys.exit(f"error: rktsph's step benchmark has no size {size}; see {log}")
    bench = runs[0]
    if bench.get("error_occurred"):
        sys.exit(f"error: rktsph benchmark {size}: {bench.get('error_message')}")
    return bench["items_per_second"], int(bench["nodes"]), rss


def pysph_step_rate(args, size, threads, log):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    command = [sys.executable, PYSPH_SCRIPT, "--size", size, "--out", args.out,
               "--steps", str(TIMED_STEPS[size])]
    if threads > 1:
        command.append("--openmp")
    rss = run(command, log, env=env)
    with open(os.path.join(args.out, f"pysph-{size}-t{threads}.json")) as handle:
        report = json.load(handle)
    return report["particle_steps_per_second"], int(report["nodes"]), rss


def speed(args):
    samples = {}
    for repetition in range(args.repetitions):
        for size in args.sizes:
            for threads in args.threads:
                for code, measure in (("rktsph", rktsph_step_rate), ("pysph", pysph_step_rate)):
                    load = load_average()
                    log = os.path.join(args.out, f"speed-{code}-{size}-t{threads}-r{repetition}.log")
                    rate, nodes, rss = measure(args, size, threads, log)
                    entry = samples.setdefault((code, size, threads), {"rates": [], "loads": []})
                    entry["rates"].append(rate)
                    entry["loads"].append(load)
                    entry["nodes"], entry["rss_mb"] = nodes, rss
                    print(f"   {code:6s} {size.upper():2s} {threads} thread(s), repetition "
                          f"{repetition + 1}: {rate:.3e} particle-steps/s (load {load:.2f})",
                          flush=True)
    return samples


def print_accuracy(runs, size):
    names = ["arrival_error_dx", "sigma_xx_plateau_error", "overshoot", "max_vy_ratio",
             "tension_plateau_error"]
    targets = ["<= 1 dx/c_p", "< 0.01", "< 0.03 (AV)", "< 1e-10", "<= 0.02"]
    print(f"\n== accuracy, size {size.upper()}, 3 transits at dt = 0.3 dx/c_p "
          "(docs/theory.md §8.11; errors as fractions)")
    width = max(len(label) for label in runs)
    print(f"{'metric':<24}  {'target':<12}  " + "  ".join(f"{label:>{width}}" for label in runs))
    for name, target in zip(names, targets):
        cells = []
        for label in runs:
            value = runs[label].get(name)
            cells.append(f"{value:>{width}.3g}" if value is not None else f"{'-':>{width}}")
        print(f"{name:<24}  {target:<12}  " + "  ".join(cells))


def print_speed(samples, args):
    print("\n== speed: particle-steps/s, medians of "
          f"{args.repetitions} interleaved runs (stepping loop only; rktsph h = 0.75 dx without "
          "AV, PySPH h = 1.3 dx)")
    print(f"{'size':>4}  {'threads':>7}  {'rktsph':>10}  {'PySPH':>10}  {'ratio':>6}  "
          f"{'rktsph KB/node':>14}  {'PySPH KB/node':>13}  {'t to 1.25 L/c_p rktsph / PySPH [s]':>35}"
          f"  {'load':>5}")
    table = []
    for size in args.sizes:
        for threads in args.threads:
            ours, theirs = samples[("rktsph", size, threads)], samples[("pysph", size, threads)]
            rate_ours, rate_theirs = (statistics.median(ours["rates"]),
                                      statistics.median(theirs["rates"]))
            steps = math.ceil(1.25 * TRANSIT / (0.3 * SPACING[size] / WAVE_SPEED) - 1e-9)
            solution_ours = steps * ours["nodes"] / rate_ours
            solution_theirs = steps * theirs["nodes"] / rate_theirs

            def per_node(entry):
                return entry["rss_mb"] * 1024.0 / entry["nodes"] if entry["rss_mb"] else None

            load = max(ours["loads"] + theirs["loads"])
            row = {"size": size, "threads": threads, "rktsph": rate_ours, "pysph": rate_theirs,
                   "ratio": rate_ours / rate_theirs, "rktsph_kb_per_node": per_node(ours),
                   "pysph_kb_per_node": per_node(theirs), "rktsph_nodes": ours["nodes"],
                   "pysph_nodes": theirs["nodes"], "seconds_to_1_25_transits_rktsph":
                   solution_ours, "seconds_to_1_25_transits_pysph": solution_theirs,
                   "largest_load": load}
            table.append(row)
            kb = [f"{v:.2f}" if v else "-" for v in (row["rktsph_kb_per_node"],
                                                     row["pysph_kb_per_node"])]
            print(f"{size.upper():>4}  {threads:>7}  {rate_ours:>10.3e}  {rate_theirs:>10.3e}  "
                  f"{row['ratio']:>5.1f}x  {kb[0]:>14}  {kb[1]:>13}  "
                  f"{solution_ours:>16.3g} / {solution_theirs:<16.3g}  {load:>5.2f}")
    return table


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", required=True, help="build directory with rktsph, rktsph_bench")
    parser.add_argument("--out", help="results directory (default BUILD/bench-peers)")
    parser.add_argument("--sizes", nargs="+", default=["s", "l"], choices=TIMED_SIZES)
    parser.add_argument("--threads", nargs="+", type=int, default=[1, 2])
    parser.add_argument("--repetitions", type=int, default=3)
    parser.add_argument("--accuracy-size", default="s", choices=sorted(SPACING))
    args = parser.parse_args()
    args.out = os.path.abspath(args.out or os.path.join(args.build, "bench-peers"))
    os.makedirs(args.out, exist_ok=True)
    for program in ("rktsph", "rktsph_bench"):
        if not os.access(os.path.join(args.build, program), os.X_OK):
            sys.exit(f"error: {args.build}/{program} not found; build first (make build)")
    try:
        import pysph  # noqa: F401 (only whether the Debian package is there)
    except ImportError:
        sys.exit("error: PySPH is not installed (Debian package python3-pysph; make bench-peers "
                 "installs it)")
    started = time.time()
    print(f"== rktsph vs PySPH on BAR-WAVE-2D: {time.strftime('%Y-%m-%d %H:%M:%S UTC', time.gmtime())}"
          f", {os.cpu_count()} cores, load average {load_average():.2f}; results in {args.out}",
          flush=True)
    runs = accuracy(args)
    print_accuracy(runs, args.accuracy_size)
    print("\n== speed runs", flush=True)
    samples = speed(args)
    table = print_speed(samples, args)
    print(f"\n   load average at end {load_average():.2f}; total {time.time() - started:.0f} s")
    with open(os.path.join(args.out, "peers.json"), "w") as handle:
        json.dump({"accuracy_size": args.accuracy_size, "accuracy": runs, "speed": table}, handle,
                  indent=1)


if __name__ == "__main__":
    main()
