#!/usr/bin/env bash
# Renders converged path-traced references on a GPU (one reference for every device class:
# goldens/<case>/reference*.exr) to a measured noise floor: for each case with a reference,
# `gibench update-goldens --reference --only-reference --noise-floor` at START spp; while the
# floor (FLIP between seeds reference_seed and reference_seed + 1000, the case's flip_mode and
# ppd, the worst of the AOVs the case commits) is above TARGET, again at 4x the spp, up to MAX. golden.json records spp,
# seed, device, driver and the floor. Prints one line per case: spp, floor, seconds.
#
#   ci/gpu_references.sh [--gibench CMD] [--start N] [--max N] [--target F] [CASE...]
#
# CASE: case names (default: every case in cases/ whose reference_spp is not 0). Afterwards set
# each case's reference_spp to the spp golden.json records (the case states its reference).
set -euo pipefail
cd "$(dirname "$0")/.."
gibench=build/gibench start=65536 max=1048576 target=0.01 cases=()
while (($#)); do
  case "$1" in
    --gibench) gibench=$2; shift 2 ;;
    --start) start=$2; shift 2 ;;
    --max) max=$2; shift 2 ;;
    --target) target=$2; shift 2 ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    -*) echo "gpu_references.sh: unknown option $1" >&2; exit 2 ;;
    *) cases+=("$1"); shift ;;
  esac
done
if ((${#cases[@]} == 0)); then
  for f in cases/*.json; do
    [[ $f == cases/case.schema.json ]] && continue
    spp=$(grep -o '"reference_spp": *[0-9]*' "$f" | grep -o '[0-9]*$' || echo 256)
    ((spp > 0)) && cases+=("$(basename "$f" .json)")
  done
fi
status=0
for c in "${cases[@]}"; do
  spp=$start
  while :; do
    t0=$(date +%s.%N)
    log=$($gibench update-goldens --case "$c" --tier ci --reference --only-reference --noise-floor --spp "$spp" \
          --reason "converged reference on a GPU: noise floor <= $target FLIP (ci/gpu_references.sh)" 2>&1) || {
      echo "$log" >&2; echo "gpu_references.sh: $c: update-goldens failed at $spp spp" >&2; status=1; break; }
    t1=$(date +%s.%N)
    floor=$(sed -n 's/.*noise floor (FLIP between seeds.*): \([0-9.]*\)$/\1/p' <<<"$log" | tail -1)
    printf '%-28s %8s spp  noise floor %s  %s s\n' "$c" "$spp" "${floor:-?}" "$(awk "BEGIN{printf \"%.1f\", $t1 - $t0}")"
    [[ -n $floor ]] || { echo "$log" >&2; status=1; break; }
    below=$(awk "BEGIN{print ($floor <= $target) ? 1 : 0}")
    if ((below)) || ((spp * 4 > max)); then
      ((below)) || { echo "gpu_references.sh: $c: floor $floor > $target at $spp spp (--max $max)" >&2; status=1; }
      break
    fi
    spp=$((spp * 4))
  done
done
exit $status
