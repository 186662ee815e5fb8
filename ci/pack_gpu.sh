#!/usr/bin/env bash
# Packs built binaries and every shared library they load into one folder that runs on a GPU
# machine with only an NVIDIA driver (no Debian packages of ours): bin/, lib/ (ldd closure,
# Vulkan loader included), lib/glibc/ (the C library and its loader, used only with
# GIB_PACK_GLIBC=1 on hosts whose glibc is older than Debian 12's), data/ (console profiles and
# seed timings), layers/ (Khronos validation, with --validation) and run.sh.
#
#   ci/pack_gpu.sh [--build DIR] [--out DIR] [--full] [--validation] [--archive] [BINARY...]
#
# Default binaries: gibench-perf, gibench-bench and gib_gpu_tests (if built): none links an
# image library, so the pack is ~14 MiB. --full adds gibench and gib_tests, which link OpenEXR
# (gibench + gibench-perf: 29 MiB, 10 libraries): both fit the device tool's 64 MiB carry with
# the cases and CI-tier goldens. Run a packed binary with
#   OUT/run.sh gibench-perf bench --profile all
set -euo pipefail
cd "$(dirname "$0")/.."
build=build out=.gpu/pack full=0 validation=0 archive=0 bins=()
while (($#)); do
  case "$1" in
    --build) build=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --full) full=1; shift ;;
    --validation) validation=1; shift ;;
    --archive) archive=1; shift ;;
    -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
    -*) echo "pack_gpu.sh: unknown option $1" >&2; exit 2 ;;
    *) bins+=("$1"); shift ;;
  esac
done
if ((${#bins[@]} == 0)); then
  bins=(gibench-perf gibench-bench)
  [[ -x $build/gib_gpu_tests ]] && bins+=(gib_gpu_tests)
  ((full)) && bins+=(gibench gib_tests)
fi
# Build what is packed: gib_gpu_tests is EXCLUDE_FROM_ALL, so a plain build leaves it stale.
cmake --build "$build" --target "${bins[@]}" >/dev/null || { echo "pack_gpu.sh: building ${bins[*]} in $build failed" >&2; exit 1; }

rm -rf "$out"
mkdir -p "$out/bin" "$out/lib/glibc" "$out/data"
# The C library stays the host's unless GIB_PACK_GLIBC=1: mixing our libc with the NVIDIA
# driver's libraries is the riskier choice, needed only on old hosts.
is_glibc() { [[ $1 =~ /(libc|libm|libpthread|libdl|librt|libresolv|libutil)\.so|/ld-linux ]]; }
declare -A seen=()
for b in "${bins[@]}"; do
  cp "$build/$b" "$out/bin/"
  while read -r lib; do
    [[ -n $lib && -z ${seen[$lib]:-} ]] || continue
    seen[$lib]=1
    if is_glibc "$lib"; then cp -L "$lib" "$out/lib/glibc/"; else cp -L "$lib" "$out/lib/"; fi
  done < <(ldd "$build/$b" | awk '/=> \//{print $3} /^[ \t]*\/.*ld-linux/{print $1}')
done

data=${GIB_DATA_DIR:-data}
cp "$data/console-profiles.json" "$data/seed-timings.json" "$data/budgets.json" "$out/data/"

if ((validation)); then
  mkdir -p "$out/layers"
  # awk reads to the end (no early exit) so ldconfig never gets SIGPIPE under pipefail.
  layer=$(ldconfig -p | awk '/libVkLayer_khronos_validation.so/ && !f {print $NF; f = 1}')
  [[ -n $layer ]] || layer=/usr/lib/x86_64-linux-gnu/libVkLayer_khronos_validation.so
  cp -L "$layer" "$out/layers/"
  sed 's#"library_path": *"[^"]*"#"library_path": "./libVkLayer_khronos_validation.so"#' \
    /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json > "$out/layers/VkLayer_khronos_validation.json"
fi

cat > "$out/run.sh" <<'RUN'
#!/usr/bin/env bash
# run.sh BINARY [ARGS...]: a packed binary with the packed libraries and data.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:?usage: run.sh BINARY [ARGS...]}; shift
export LD_LIBRARY_PATH=$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
export GIB_DATA_DIR=${GIB_DATA_DIR:-$here/data}
[[ -d $here/layers ]] && export VK_LAYER_PATH=$here/layers
# Containers often mount the NVIDIA driver under /usr/local/nvidia without registering its ICD.
if [[ -z ${VK_DRIVER_FILES:-}${VK_ICD_FILENAMES:-} && ! -e /usr/share/vulkan/icd.d/nvidia_icd.json && \
      ! -e /etc/vulkan/icd.d/nvidia_icd.json && -e /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json ]]; then
  export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
fi
if [[ ${GIB_PACK_GLIBC:-0} == 1 ]]; then
  exec "$here/lib/glibc/ld-linux-x86-64.so.2" --library-path "$here/lib/glibc:$here/lib" "$here/bin/$bin" "$@"
fi
exec "$here/bin/$bin" "$@"
RUN
chmod +x "$out/run.sh"
echo "packed ${bins[*]} into $out ($(du -sh "$out" | cut -f1); $(ls "$out/lib" | grep -c so) libraries)"
if ((archive)); then
  tar -C "$(dirname "$out")" -cJf "$out.tar.xz" "$(basename "$out")"
  echo "archive $out.tar.xz ($(du -sh "$out.tar.xz" | cut -f1))"
fi
