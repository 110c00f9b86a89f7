#!/usr/bin/env bash
# The path tracer's two designs on the Vulkan backend (docs/integrators.md, "The path tracer on
# the GPU: megakernel or wavefront"): every shipped scene rendered with --integrator path for
# EPOCHS epochs by the megakernel (pixel_trace.comp) and by the wavefront (path_wavefront.comp,
# PHOTONFARM_VULKAN_PATH=wavefront). Both trace the same paths, so the images must be the same
# (checked: the largest pixel difference is printed) and equal work makes the rates' ratio the
# designs' whole answer: at equal time the faster one's error is lower by the square root.
# Rates are camera samples a second as each render reports them at its end (pipelines compiled
# and scene uploaded included, as a user waits for them; the wavefront compiles up to 6
# pipelines, the megakernel one); the runs' wall times beside them.
# Writes OUT/path_designs.md and prints it.
# Usage: bench/compare_path_designs.sh BUILD_DIR [OUT_DIR] [SIZE] [EPOCHS] [SPP]
set -euo pipefail
source "$(dirname "$0")/vulkan_device.sh"
build=${1:?usage: compare_path_designs.sh BUILD_DIR [OUT_DIR] [SIZE] [EPOCHS] [SPP]}
out=${2:-docs/integrators}
size=${3:-64}
epochs=${4:-4}
spp=${5:-16}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
photonfarm="$build/client/photonfarm"
device=$(vulkan_device "$build")

# run NAME DESIGN SCENE ARGS...: one render; prints "rate seconds" (camera samples a second as
# the render's last line says it, and the wall time of the whole run).
run() {
    local name=$1 design=$2
    shift 2
    local start end
    start=$(date +%s.%N)
    PHOTONFARM_VULKAN_PATH=$design "$photonfarm" render "$@" --integrator path --backend vulkan \
        --width "$size" --height "$size" --spp "$spp" --epochs "$epochs" --log-level info \
        --out "$work/$name.exr" >"$work/$name.log" 2>&1 || { cat "$work/$name.log" >&2; exit 1; }
    end=$(date +%s.%N)
    local rate
    rate=$(sed -n 's/^done: .*, \([0-9.]*[kMG]*\) samples\/s.*/\1/p' "$work/$name.log" | tail -1)
    echo "${rate:-?} $(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')"
}

units() { awk -v r="$1" 'BEGIN { m = 1; if (r ~ /k$/) m = 1e3; if (r ~ /M$/) m = 1e6; if (r ~ /G$/) m = 1e9; print r * m }'; }

rows="$work/rows.md"
: >"$rows"
for scene_file in scenes/*.gltf scenes/pbrt/cornell-lamps.pbrt scenes/pbrt/cornell-materials.pbrt \
    scenes/pbrt/cornell-room.pbrt; do
    scene=$(basename "${scene_file%.*}")
    [[ $scene == furnace ]] && continue  # no path at all leaves a furnace (max depth only)
    [[ -n ${SCENES:-} && " $SCENES " != *" $scene "* ]] && continue
    extra=()
    [[ -f scenes/$scene-sky.hdr ]] && extra=(--environment "scenes/$scene-sky.hdr")
    read -r mega_rate mega_wall < <(run "$scene-megakernel" megakernel "$scene_file" "${extra[@]}")
    read -r wave_rate wave_wall < <(run "$scene-wavefront" wavefront "$scene_file" "${extra[@]}")
    difference=$( (idiff -a "$work/$scene-megakernel.exr" "$work/$scene-wavefront.exr" 2>&1 || true) |
        sed -n 's/^ *Max error *= *\([^ ]*\).*/\1/p' | head -1)
    printf '| %s | %s | %s | %.2f | %s s | %s s | %s |\n' "$scene" "$mega_rate" "$wave_rate" \
        "$(awk -v a="$(units "$wave_rate")" -v b="$(units "$mega_rate")" 'BEGIN { print a / b }')" \
        "$mega_wall" "$wave_wall" "${difference:-0}" >>"$rows"
done
{
    echo "${size}x${size}, ${epochs} epochs of ${spp} samples a pixel; Vulkan device: ${device:-unknown}."
    echo
    echo "| scene | megakernel samples/s | wavefront samples/s | wavefront / megakernel | megakernel run | wavefront run | largest pixel difference |"
    echo "|---|---:|---:|---:|---:|---:|---:|"
    cat "$rows"
} >"$out/path_designs.md"
cat "$out/path_designs.md"
