#!/usr/bin/env bash
# Fuzzes reading and checking a case file: fuzz/run.sh BUILD_DIR [SECONDS]
#
# BUILD_DIR is a build configured with clang and -DRKTSPH_FUZZ=ON (README.md, "Fuzzing"). The seed
# corpus (the bundled cases, the test cases and every input that ever failed) is copied to a
# temporary folder, because libFuzzer adds the inputs it finds to its corpus folder. Limits: 1 s
# and 512 MB per input. Exits non-zero on a finding; the input that caused it is saved in
# BUILD_DIR/fuzz-findings/ (add it to tests/data/fuzz-regressions/ once it is fixed).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:?usage: fuzz/run.sh BUILD_DIR [SECONDS]}"
seconds="${2:-60}"

corpus="$(mktemp -d)"
trap 'rm -rf "$corpus"' EXIT
for case_file in "$root"/cases/*/case.yaml; do
  cp "$case_file" "$corpus/$(basename "$(dirname "$case_file")").yaml"
done
shopt -s nullglob
cp "$root"/tests/data/cases/*.yaml "$root"/tests/data/fuzz-regressions/*.yaml "$corpus/"

mkdir -p "$build/fuzz-findings"
# Leaks are findings too; an uncaught exception aborts and is reported as a crash.
# ASan keeps freed memory in a quarantine (256 MB by default) that counts in the process's RSS: a
# 60 s run once passed 512 MB of RSS with 28 MB live. A 16 MB quarantine keeps the RSS limit about
# the inputs' own memory; a single allocation over 512 MB is caught by -malloc_limit_mb.
ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}:quarantine_size_mb=16" UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}" \
  "$build/case_reader_fuzzer" "$corpus" -dict="$root/fuzz/case.dict" \
  -max_total_time="$seconds" -timeout=1 -rss_limit_mb=512 -malloc_limit_mb=512 \
  -artifact_prefix="$build/fuzz-findings/" -print_final_stats=1
