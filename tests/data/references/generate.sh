#!/bin/sh
# Regenerates the reference CSVs that tests/validation/references_test.cpp compares against.
# Usage: sh tests/data/references/generate.sh SCRIPTS_DIR
# (SCRIPTS_DIR holds the stdlib-only Python reference scripts the project started from, which are
# not in the repository; needs /usr/bin/python3).
set -e
src=${1:?path to the shared reference scripts}
out=$(cd "$(dirname "$0")" && pwd)
py=/usr/bin/python3
cd "$src"
$py elastic_bar.py --preset 4.2 --nt 40 --no-disp > "$out/elastic_bar_4.2.csv"
$py elastic_bar.py --preset 5.3.2 --nt 40 --no-disp > "$out/elastic_bar_5.3.2.csv"
# The profile at t = 0.06 s is thinned to every 5th printed row to keep the file small.
$py viscoplastic_bar.py --H 0 --probes 0,2.5 --every 20 --profiles 0.06 |
  awk '/^# profile/ {p = 1; print; next} p && /^x,/ {print; next} p {if ((n++ % 5) == 0) print; next} {print}' \
  > "$out/viscoplastic_bar_H0.csv"
$py viscoplastic_bar.py --H=-1e7 --probes 0,2.5 --every 20 --profiles '' > "$out/viscoplastic_bar_softening.csv"
$py viscoplastic_bar.py --check-front > "$out/viscoplastic_front_decay.csv"
$py terzaghi.py > "$out/terzaghi.csv"
$py gravity_column.py --tr 0.5 --mu 0 --nt 40 > "$out/gravity_column_ramp.csv"
$py gravity_column.py --tr 0 --mu 0 --nt 40 > "$out/gravity_column_sudden.csv"
$py gravity_column.py --tr 0 --mu 20 --nt 40 > "$out/gravity_column_damped20.csv"
$py harmonic_column.py chart --Pi2 0.01,1,10 --depth 1.0 > "$out/harmonic_chart_base.csv"
$py harmonic_column.py profile --Pi2 1 --Pi1 0.001,0.1,1,10 --form up > "$out/harmonic_profiles_Pi2_1.csv"
$py strip_undrained.py --grid > "$out/strip_undrained.csv"
$py shear_band.py > "$out/shear_band.csv"
$py vertical_cut.py > "$out/vertical_cut.csv"
$py bearing.py --table > "$out/bearing.csv"
$py cantilever_plate.py > "$out/cantilever_plate.csv"
$py runout.py > "$out/runout.csv"
