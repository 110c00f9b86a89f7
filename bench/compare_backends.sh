#!/usr/bin/env bash
# The CPU and Vulkan backends side by side (docs/integrators.md, "The family on the CPU and the
# GPU"): every shipped scene rendered by every integrator on each backend for SECONDS, measured
# against bench/reference.sh's reference: the rate each run reports at its end (photons a
# second for ppm, sppm and rpm, camera samples a second for path and pm; pm's maps of PM_PHOTONS
# photons each, built on the host for both) and its relative error. Both backends run on the
# same machine one after the other: on lavapipe the Vulkan kernels run on the same cores as the
# CPU backend, so the ratio says what the kernels cost there, not what a GPU would give.
# Writes OUT/backends.md (a row per scene and integrator) and prints it.
# Usage: bench/compare_backends.sh BUILD_DIR [OUT_DIR] [SIZE] [SECONDS] [REF_SECONDS]
set -euo pipefail
source "$(dirname "$0")/reference.sh"
source "$(dirname "$0")/vulkan_device.sh"
build=${1:?usage: compare_backends.sh BUILD_DIR [OUT_DIR] [SIZE] [SECONDS] [REF_SECONDS]}
out=${2:-docs/integrators}
size=${3:-64}
seconds=${4:-10}
ref_seconds=${5:-60}
pm_photons=${PM_PHOTONS:-300k}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
photonfarm="$build/client/photonfarm"
device=$(vulkan_device "$build")

# run NAME ARGS...: one render; prints "rate error" (the rate as the render's last line says it,
# e.g. 853.9k, and the relative error at its end).
run() {
    local name=$1
    shift
    "$photonfarm" render "$@" "${sky[@]}" --width "$size" --height "$size" --log-level warn \
        --seconds "$seconds" --out "$work/$name.exr" --report "$work/$name" >"$work/$name.log" 2>&1 ||
        { cat "$work/$name.log" >&2; exit 1; }
    local rate
    rate=$(sed -n 's/^done: .*, \([0-9.]*[kMG]*\) \(photons\|samples\)\/s.*/\1/p' "$work/$name.log" | tail -1)
    awk -F, -v rate="${rate:-?}" 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
        { e = $col["reference_rel_error"] } END { printf "%s %s\n", rate, e }' "$work/$name/convergence.csv"
}

# A rate as the render prints it (853.9k) in units.
units() { awk -v r="$1" 'BEGIN { m = 1; if (r ~ /k$/) m = 1e3; if (r ~ /M$/) m = 1e6; if (r ~ /G$/) m = 1e9; print r * m }'; }

rows="$work/rows.md"
: >"$rows"
for gltf in scenes/*.gltf; do
    scene=$(basename "$gltf" .gltf)
    [[ -n ${SCENES:-} && " $SCENES " != *" $scene "* ]] && continue
    sky=()
    [[ -f scenes/$scene-sky.hdr ]] && sky=(--environment "scenes/$scene-sky.hdr")
    reference="$work/$scene-reference.exr"
    make_reference "$photonfarm" "$gltf" "$reference" "$size" "$ref_seconds" "${sky[@]}"
    for integrator in ppm sppm rpm pm path; do
        flags=(--integrator "$integrator" --reference "$reference")
        [[ $integrator == pm ]] && flags+=(--pm-photons "$pm_photons" --pm-caustic-photons "$pm_photons")
        read -r cpu_rate cpu_error < <(run "$scene-$integrator-cpu" "$gltf" "${flags[@]}" --backend cpu)
        read -r gpu_rate gpu_error < <(run "$scene-$integrator-vulkan" "$gltf" "${flags[@]}" --backend vulkan)
        unit=photons
        [[ $integrator == pm || $integrator == path ]] && unit="camera samples"
        printf '| %s | %s | %s | %s | %s | %.2f | %.2f%% | %.2f%% |\n' "$scene" "$integrator" "$unit" \
            "$cpu_rate" "$gpu_rate" "$(awk -v a="$(units "$gpu_rate")" -v b="$(units "$cpu_rate")" 'BEGIN { print a / b }')" \
            "$(awk -v e="$cpu_error" 'BEGIN { print 100 * e }')" "$(awk -v e="$gpu_error" 'BEGIN { print 100 * e }')" >>"$rows"
    done
done
{
    echo "${size}x${size}, ${seconds} s a run, 2 threads; Vulkan device: ${device:-unknown}."
    echo
    echo "| scene | integrator | rate of | cpu rate /s | vulkan rate /s | vulkan / cpu | cpu error | vulkan error |"
    echo "|---|---|---|---:|---:|---:|---:|---:|"
    cat "$rows"
} >"$out/backends.md"
cat "$out/backends.md"
