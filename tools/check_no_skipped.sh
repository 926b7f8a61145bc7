#!/usr/bin/env bash
# Fails if a ctest log shows a skipped or not-run test (CI runs every test; see .ci/run).
# Usage: check_no_skipped.sh CTEST_LOG
set -euo pipefail
log="$1"
if ! grep -q "tests passed" "$log"; then
  echo "check_no_skipped: $log has no ctest summary" >&2
  exit 1
fi
if grep -E "\*\*\*Skipped|\*\*\*Not Run|Not Run \(Disabled\)" "$log"; then
  echo "check_no_skipped: the tests above were skipped or not run ($log)" >&2
  exit 1
fi
echo "check_no_skipped: no test skipped in $log"
