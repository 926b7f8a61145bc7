#!/usr/bin/env bash
# Runs the benchmarks of bench/ and prints the BAR-WAVE-2D speed table (bench/README.md,
# docs/theory.md §8.11). Called by `make bench` as
#   tools/run_benchmarks.sh BUILD_DIR
#
# 1. Kernel benchmarks (operator application, neighbour tables) at each thread count, and the
#    serial table-build benchmark once, medians of RKTSPH_BENCH_REPETITIONS runs.
# 2. The full step on BAR-WAVE-2D per size and thread count, one process each, so that the peak
#    resident memory (from /usr/bin/time -v) belongs to that size alone.
# 3. The moving-configuration step (large-deformation model).
# 4. The saturated model's pressure solve: its share of the step on vpw-strip-footing-elastic and
#    on a 10^6-node consolidation column (rktsph runs, read from their summary.json).
#
# Settings (environment):
#   RKTSPH_BENCH_THREADS      thread counts, default "1 2"
#   RKTSPH_BENCH_SIZES        BAR-WAVE-2D sizes, default "s m l xl"
#   RKTSPH_BENCH_TRIANGLE_SIZES  BAR-WAVE-2D sizes on a triangle mesh (cases/triangles-bar-wave-2d),
#                             default "s l"; "" skips them
#   RKTSPH_BENCH_REPETITIONS  repetitions per measurement, default 3
#   RKTSPH_BENCH_XL_THREADS   thread counts for XL, default: the largest of RKTSPH_BENCH_THREADS
#                             (XL at one thread alone would take about 80 s per repetition)
#   RKTSPH_BENCH_XL_REPETITIONS  default 1
#   RKTSPH_BENCH_KERNELS      0 skips part 1
#   RKTSPH_BENCH_MOVING       0 skips the moving-configuration step
#   RKTSPH_BENCH_PRESSURE     0 skips the saturated model's pressure solve
#   RKTSPH_BENCH_COLUMN_STEPS steps of the 10^6-node saturated column, default 60
#   RKTSPH_BENCH_OUT          directory for the JSON results and logs, default BUILD_DIR/bench
# Exits non-zero only if a benchmark program fails (or reports an error).
set -uo pipefail

if [[ $# -ne 1 ]]; then
  echo "usage: $0 BUILD_DIR" >&2
  exit 2
fi
build_dir=$1
bench=$build_dir/rktsph_bench
if [[ ! -x $bench ]]; then
  echo "error: $bench not found; build it first (make build)" >&2
  exit 2
fi

threads_list=${RKTSPH_BENCH_THREADS:-"1 2"}
sizes=${RKTSPH_BENCH_SIZES:-"s m l xl"}
triangle_sizes=${RKTSPH_BENCH_TRIANGLE_SIZES-"s l"}
repetitions=${RKTSPH_BENCH_REPETITIONS:-3}
largest_threads=$(tr ' ' '\n' <<<"$threads_list" | sort -n | tail -1)
xl_threads=${RKTSPH_BENCH_XL_THREADS:-$largest_threads}
xl_repetitions=${RKTSPH_BENCH_XL_REPETITIONS:-1}
out_dir=${RKTSPH_BENCH_OUT:-$build_dir/bench}
mkdir -p "$out_dir"

time_program=""
if [[ -x /usr/bin/time ]] && /usr/bin/time -v true >/dev/null 2>&1; then
  time_program=/usr/bin/time
fi

failures=0
started=$(date +%s)

echo "== rktsph benchmarks: $(date -u '+%Y-%m-%d %H:%M:%S UTC') on $(hostname)"
echo "   cores: $(nproc); cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
echo "   load average at start: $(cat /proc/loadavg)"
echo "   results and logs: $out_dir"

# Prints a median table of the kernel benchmarks from Google Benchmark JSON files.
summarise_kernels() {
  python3 - "$@" <<'PYTHON'
import json
import sys

rows = []
for path in sys.argv[1:]:
    with open(path) as handle:
        report = json.load(handle)
    threads = report["context"].get("omp_threads", "?")
    for run in report["benchmarks"]:
        if run.get("error_occurred"):
            rows.append((run["run_name"], threads, "ERROR", run.get("error_message", ""), "", ""))
            continue
        is_single = run.get("run_type") == "iteration"
        if not is_single and run.get("aggregate_name") != "median":
            continue
        name = run["run_name"].replace("/real_time", "")
        bytes_per_second = run.get("bytes_per_second")
        rows.append((
            name,
            threads,
            f"{run['real_time']:.3f} {run['time_unit']}",
            f"{run.get('items_per_second', 0.0):.3e}",
            f"{bytes_per_second / 1e9:.2f}" if bytes_per_second else "-",
            run.get("label", ""),
        ))
width = max([len(r[0]) for r in rows] + [9])
print(f"{'benchmark':<{width}}  {'threads':>7}  {'median time':>14}  {'items/s':>10}  "
      f"{'GB/s':>6}  label")
for name, threads, time, items, gigabytes, label in rows:
    print(f"{name:<{width}}  {threads:>7}  {time:>14}  {items:>10}  {gigabytes:>6}  {label}")
PYTHON
}

# Runs the benchmark program; arguments after the first two are passed on.
#   run_bench THREADS LOG_FILE ARGS...
run_bench() {
  local threads=$1 log=$2
  shift 2
  OMP_NUM_THREADS=$threads "$bench" --benchmark_context=omp_threads="$threads" "$@" >"$log" 2>&1
}

# Runs the benchmarks matching FILTER once per thread count of $threads_list, medians of
# $repetitions, into $out_dir/PREFIX-tN.json (log beside it); the JSON files of the runs that
# succeeded are left in the array json_files, and each failure is counted.
#   run_per_thread_count PREFIX WHAT FILTER EXTRA_ARGS...
run_per_thread_count() {
  local prefix=$1 what=$2 filter=$3 threads json
  shift 3
  json_files=()
  for threads in $threads_list; do
    json=$out_dir/$prefix-t$threads.json
    if run_bench "$threads" "$out_dir/$prefix-t$threads.log" --benchmark_filter="$filter" \
      --benchmark_repetitions="$repetitions" --benchmark_report_aggregates_only=true \
      --benchmark_out="$json" --benchmark_out_format=json "$@"; then
      json_files+=("$json")
    else
      echo "FAILED: $what at $threads threads (see $out_dir/$prefix-t$threads.log)"
      failures=$((failures + 1))
    fi
  done
}

if [[ ${RKTSPH_BENCH_KERNELS:-1} != 0 ]]; then
  echo
  echo "== kernel benchmarks (medians of $repetitions; the table build is serial, run once)"
  run_per_thread_count kernels "kernel benchmarks" '^BM_(ApplyOperator|NodeToStressPointTable)/' \
    --benchmark_min_time=0.1
  kernel_files=("${json_files[@]}")
  json=$out_dir/table-build.json
  if run_bench 1 "$out_dir/table-build.log" --benchmark_filter='^BM_(BuildOperatorTables|StepOperatorRebuild|DelaunayCells)/' \
    --benchmark_out="$json" --benchmark_out_format=json; then
    kernel_files+=("$json")
  else
    echo "FAILED: table-build benchmark (see $out_dir/table-build.log)"
    failures=$((failures + 1))
  fi
  if [[ ${#kernel_files[@]} -gt 0 ]]; then
    summarise_kernels "${kernel_files[@]}" || failures=$((failures + 1))
  fi
fi

echo
echo "== BAR-WAVE-2D step (advance() only; 200 / 100 / 50 / 50 steps per measurement at S / M / L / XL;"
echo "   TRI-S, TRI-L: the bar on a triangle mesh of edges at most the S and L spacings)"
step_records=$out_dir/steps.tsv
: >"$step_records"
# Each size once per thread count, in a process of its own: the lattice's sizes, then the
# triangle mesh's as tri-<size> (BM_TriangleBarWaveStep).
for size in $sizes $(for s in $triangle_sizes; do echo "tri-$s"; done); do
  size_threads=$threads_list
  size_repetitions=$repetitions
  if [[ $size == xl ]]; then
    size_threads=$xl_threads
    size_repetitions=$xl_repetitions
  fi
  filter="^BM_BarWaveStep/$size/"
  [[ $size == tri-* ]] && filter="^BM_TriangleBarWaveStep/${size#tri-}/"
  for threads in $size_threads; do
    json=$out_dir/step-$size-t$threads.json
    log=$out_dir/step-$size-t$threads.log
    load=$(cut -d' ' -f1 /proc/loadavg)
    rss_kb=""
    args=(--benchmark_filter="$filter" --benchmark_repetitions="$size_repetitions"
      --benchmark_report_aggregates_only=true --benchmark_out="$json" --benchmark_out_format=json)
    if [[ -n $time_program ]]; then
      timing=$out_dir/step-$size-t$threads.time
      OMP_NUM_THREADS=$threads "$time_program" -v -o "$timing" "$bench" \
        --benchmark_context=omp_threads="$threads" "${args[@]}" >"$log" 2>&1
      status=$?
      rss_kb=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$timing" 2>/dev/null)
    else
      run_bench "$threads" "$log" "${args[@]}"
      status=$?
    fi
    if [[ $status -ne 0 ]]; then
      echo "FAILED: BAR-WAVE-2D $size at $threads threads (exit $status, see $log)"
      failures=$((failures + 1))
      continue
    fi
    printf '%s\t%s\t%s\t%s\t%s\n' "$size" "$threads" "$json" "${rss_kb:--}" "$load" \
      >>"$step_records"
    echo "   done: $size at $threads threads ($(($(date +%s) - started)) s elapsed)"
  done
done

echo
if ! python3 - "$step_records" "${time_program:+rss}" <<'PYTHON'
import json
import sys

records_path = sys.argv[1]
show_rss = len(sys.argv) > 2 and sys.argv[2] == "rss"
errors = 0
rows = []
with open(records_path) as records:
    for line in records:
        size, threads, path, rss_kb, load = line.rstrip("\n").split("\t")
        with open(path) as handle:
            report = json.load(handle)
        runs = report["benchmarks"]
        failed = [r for r in runs if r.get("error_occurred")]
        if failed or not runs:
            errors += 1
            message = failed[0].get("error_message", "") if failed else "no result"
            print(f"ERROR: {size} at {threads} threads: {message}")
            continue
        medians = [r for r in runs if r.get("aggregate_name") == "median"]
        run = medians[0] if medians else runs[0]
        scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[run["time_unit"]]
        seconds_per_step = run["real_time"] * scale
        nodes = int(run["nodes"])
        rss = f"{int(rss_kb) / 1024:.0f}" if rss_kb not in ("", "-") else "-"
        rows.append((size.upper(), nodes, threads, seconds_per_step, nodes / seconds_per_step, rss,
                     load, "median" if medians else "1 run"))

header = f"{'size':>5}  {'nodes':>9}  {'threads':>7}  {'s/step':>10}  {'particle-steps/s':>16}"
if show_rss:
    header += f"  {'peak RSS MB':>11}  {'KB/node':>7}"
header += f"  {'load(1 min)':>11}  of"
print(header)
for size, nodes, threads, seconds, rate, rss, load, basis in rows:
    line = f"{size:>5}  {nodes:>9}  {threads:>7}  {seconds:>10.4g}  {rate:>16.3e}"
    if show_rss:
        per_node = f"{float(rss) * 1024 / nodes:.2f}" if rss != "-" else "-"
        line += f"  {rss:>11}  {per_node:>7}"
    line += f"  {load:>11}  {basis}"
    print(line)


def rate_of(size, threads):
    found = [r for r in rows if r[0] == size and r[2] == threads]
    return found[0][4] if found else None


def verdict(text, value, met):
    print(f"{text}: {'met' if met else 'NOT met'} ({value}).")


# The targets of docs/theory.md §8.11 and §4.7 (the speed-and-memory issue).
print()
l1, l2, xl2 = rate_of("L", "1"), rate_of("L", "2"), rate_of("XL", "2")
if l2 is not None:
    verdict("Target >= 1.0e7 particle-steps/s at L with 2 threads", f"{l2:.3e}", l2 >= 1e7)
if l1 is not None:
    verdict("Target >= 5.0e6 particle-steps/s at L with 1 thread", f"{l1:.3e}", l1 >= 5e6)
if l1 is not None and l2 is not None:
    verdict("Target 2 threads >= 1.8 x 1 thread at L", f"{l2 / l1:.2f} x", l2 >= 1.8 * l1)
if l2 is not None and xl2 is not None:
    verdict("Target XL within 10 % of L per node (2 threads)", f"{xl2 / l2:.2f} of L",
            xl2 >= 0.9 * l2)
if show_rss:
    for size, nodes, threads, seconds, rate, rss, load, basis in rows:
        if size in ("L", "XL") and rss != "-":
            per_node = float(rss) * 1024 / nodes
            verdict(f"Target peak memory <= 1 KB per node at {size}, {threads} thread(s)",
                    f"{per_node:.2f} KB", per_node <= 1.0)
sys.exit(1 if errors else 0)
PYTHON
then
  failures=$((failures + 1))
fi

if [[ ${RKTSPH_BENCH_MOVING:-1} != 0 ]]; then
  echo
  echo "== moving configuration (large-deformation model: BAR-WAVE-2D S/M/L and the collapsing"
  echo "   low-cohesion block; every step recomputes its weights, and searches its stencils after"
  echo "   0.1 dx of motion; medians of $repetitions)"
  run_per_thread_count moving "moving-configuration benchmarks" \
    '^BM_(MovingBarWaveStep|ReformedBarWaveStep|LowCohesionSlopeStep)/'
  if [[ ${#json_files[@]} -gt 0 ]] && ! python3 - "${json_files[@]}" <<'PYTHON'
import json
import sys

# particle-steps/s and where the step's time goes (docs/theory.md §9.5): the neighbour search's
# cell lists, the operator tables, moving the configuration and its faces, the rest of the step.
target = None
print(f"{'benchmark':<28}  {'threads':>7}  {'particle-steps/s':>16}  {'cell lists':>10}  "
      f"{'tables':>7}  {'moving':>7}  {'rest':>6}")
for path in sys.argv[1:]:
    with open(path) as handle:
        report = json.load(handle)
    threads = report["context"].get("omp_threads", "?")
    for run in report["benchmarks"]:
        if run.get("error_occurred"):
            print(f"ERROR: {run['run_name']}: {run.get('error_message', '')}")
            sys.exit(1)
        single = run.get("run_type") == "iteration" and run.get("repetitions", 1) <= 1
        if run.get("aggregate_name") != "median" and not single:
            continue
        name = run["run_name"].split("/iterations")[0]
        print(f"{name:<28}  {threads:>7}  {run.get('items_per_second', 0.0):>16.3e}  "
              f"{run.get('pct_cell_lists', 0.0):>9.1f}%  {run.get('pct_tables', 0.0):>6.1f}%  "
              f"{run.get('pct_surface', 0.0):>6.1f}%  {run.get('pct_integration', 0.0):>5.1f}%")
        if name == "BM_MovingBarWaveStep/l" and str(threads) == "2":
            target = run.get("items_per_second", 0.0)
if target is not None:
    verdict = "met" if target >= 3e6 else "NOT met"
    print(f"\nTarget >= 3.0e6 particle-steps/s on the moving BAR-WAVE-2D L with 2 threads: "
          f"{verdict} ({target:.3e}).")
PYTHON
  then
    failures=$((failures + 1))
  fi
fi

if [[ ${RKTSPH_BENCH_PRESSURE:-1} != 0 ]]; then
  echo
  echo "== pressure solve of the saturated model (default multigrid preconditioner; 2 threads):"
  echo "   vpw-strip-footing-elastic (full run), and the vpw-consolidation column at dx = 2/256 m"
  echo "   (257 x 3841 = 987 137 nodes; ${RKTSPH_BENCH_COLUMN_STEPS:-60} steps at a fixed dt of 8e-5 s)"
  rktsph_program=$build_dir/rktsph
  cases_dir=$(cd "$(dirname "$0")/.." && pwd)/cases
  column_steps=${RKTSPH_BENCH_COLUMN_STEPS:-60}
  pressure_records=$out_dir/pressure.tsv
  : >"$pressure_records"
  run_pressure_case() {
    local name=$1 case_file=$2
    shift 2
    local run_dir=$out_dir/pressure-$name
    local timing=$out_dir/pressure-$name.time load
    load=$(cut -d' ' -f1 /proc/loadavg)
    rm -rf "$run_dir"
    if OMP_NUM_THREADS=2 ${time_program:+$time_program -v -o "$timing"} "$rktsph_program" run \
      "$case_file" --output "$run_dir" "$@" >"$out_dir/pressure-$name.log" 2>&1; then
      printf '%s\t%s\t%s\t%s\n' "$name" "$run_dir/summary.json" \
        "$(awk -F': ' '/Maximum resident set size/ {print $2}' "$timing" 2>/dev/null)" "$load" \
        >>"$pressure_records"
    else
      echo "FAILED: $name (see $out_dir/pressure-$name.log)"
      failures=$((failures + 1))
    fi
  }
  run_pressure_case strip-footing "$cases_dir"/vpw-strip-footing-elastic/case.yaml
  run_pressure_case column-1M "$cases_dir"/vpw-consolidation/case.yaml --set geometry.spacing=0.0078125 \
    --set numerics.time_step=8e-5 --set "time.end=$(python3 -c "print($column_steps * 8e-5)")" \
    --set output.interval=0 --set output.probe_interval=0
  if [[ -s $pressure_records ]] && ! python3 - "$pressure_records" <<'PYTHON'
import json
import sys

# The pressure solve's share of the step (docs/theory.md §6.7; target: at most 30 %).
print(f"{'run':<14}  {'nodes':>9}  {'steps':>5}  {'s/step':>8}  {'iterations':>10}  {'levels':>6}  "
      f"{'solve share':>11}  {'projection':>10}  {'peak RSS MB':>11}  {'load':>5}")
shares = []
with open(sys.argv[1]) as records:
    for line in records:
        name, path, rss_kb, load = line.rstrip("\n").split("\t")
        with open(path) as handle:
            summary = json.load(handle)
        solver = summary["pressure_solver"]
        steps = summary["steps"]
        step_seconds = sum(summary["step_time"].values())
        rss = f"{int(rss_kb) / 1024:.0f}" if rss_kb else "-"
        print(f"{name:<14}  {summary['sph_nodes']:>9}  {steps:>5}  {step_seconds / steps:>8.4f}  "
              f"{solver['mean_iterations']:>10.2f}  {solver.get('multigrid_levels', 0):>6}  "
              f"{solver['solve_share']:>10.1%}  {solver['projection_share']:>9.1%}  {rss:>11}  "
              f"{load:>5}")
        shares.append((name, solver["solve_share"]))
print()
for name, share in shares:
    print(f"Target pressure solve <= 30 % of the step on {name}: "
          f"{'met' if share <= 0.30 else 'NOT met'} ({share:.1%}).")
PYTHON
  then
    failures=$((failures + 1))
  fi
fi

echo
echo "   load average at end: $(cat /proc/loadavg)  (total $(($(date +%s) - started)) s)"
if [[ $failures -ne 0 ]]; then
  echo "$failures benchmark program(s) failed" >&2
  exit 1
fi
