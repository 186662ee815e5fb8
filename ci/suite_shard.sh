#!/usr/bin/env bash
# One shard of the scenario suite under CTest's resource allocation (CMakeLists.txt,
# GIB_SUITE_SHARDS): runs `gibench run --shard K/N --out DIR` on the GPU CTest gave this test
# (CTEST_RESOURCE_GROUP_0_GPUS="id:I,slots:1" -> --device I); without an allocation (no
# --resource-spec-file) on the default device. Exit status: gibench run's.
#
#   ci/suite_shard.sh GIBENCH K/N DIR [gibench run options...]
set -euo pipefail
gibench=${1:?usage: suite_shard.sh GIBENCH K/N DIR [options]} shard=${2:?K/N} out=${3:?DIR}
shift 3
device=()
if [[ -n ${CTEST_RESOURCE_GROUP_0_GPUS:-} ]]; then
  id=$(sed -n 's/^id:\([^,]*\),.*/\1/p' <<<"$CTEST_RESOURCE_GROUP_0_GPUS")
  [[ -n $id ]] || { echo "suite_shard.sh: CTEST_RESOURCE_GROUP_0_GPUS: expected id:I,slots:N, got '$CTEST_RESOURCE_GROUP_0_GPUS'" >&2; exit 2; }
  device=(--device "$id")
fi
rm -rf "$out"
exec "$gibench" run --shard "$shard" --out "$out" "${device[@]}" "$@"
