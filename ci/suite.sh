#!/usr/bin/env bash
# The scenario suite on the default device (lavapipe without a GPU): every case in cases/
# against its reference and approved goldens; results.json, junit.xml and index.html in out/.
# Extra arguments go to `gibench run` (e.g. --case cornell --device NVIDIA).
set -euo pipefail
cd "$(dirname "$0")/.."
build/gibench devices
build/gibench run --out "${GIB_OUT:-out}" "$@"
