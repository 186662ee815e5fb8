#!/usr/bin/env bash
# The scenario suite on the default device (lavapipe without a GPU): every case in cases/
# against its reference and approved goldens; results.json, junit.xml and index.html in out/.
# Extra arguments go to `gibench run` (e.g. --case cornell --device NVIDIA).
# Then the report is opened in headless Chromium (`gibench check-report`, the checker the
# report tests use): an error banner or console output from the page fails the suite too.
# Exit status: non-zero when the run failed or the report did not load cleanly.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${GIB_OUT:-out}"
build/gibench devices
stamp=$(mktemp)
trap 'rm -f "$stamp"' EXIT
rc=0
build/gibench run --out "$out" "$@" || rc=$?
# Only a report this run wrote (a run that stopped on an error may have left an older one).
if [ "$out/index.html" -nt "$stamp" ]; then
  build/gibench check-report "$out" || { [ "$rc" -ne 0 ] || rc=1; }  # its one line says why
else
  echo "suite.sh: no report was written to $out/index.html (gibench run exited $rc)" >&2
  [ "$rc" -ne 0 ] || rc=1
fi
exit "$rc"
