#!/usr/bin/env bash
# The scenario suite as it stands: until the case harness lands (issue 3) it renders the
# sample Cornell scene with every technique on the default device (lavapipe without a GPU)
# and writes EXR + PNG + JSON timing records to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=build/gibench
OUT=${GIB_OUT:-out}
mkdir -p "$OUT"
$BIN devices
$BIN render --scene cases/scenes/cornell.json --technique direct --frames 4 \
  --out "$OUT/cornell.direct.exr" --json "$OUT/cornell.direct.json" "$@"
$BIN render --scene cases/scenes/cornell.json --technique reference --spp 64 \
  --out "$OUT/cornell.reference.exr" --json "$OUT/cornell.reference.json" "$@"
echo "suite: wrote $OUT/"
