#!/usr/bin/env bash
# Adaptive photon tracing against uniform tracing at equal time (docs/integrators.md, "Adaptive
# photon tracing"): each scene rendered by ppm for SECONDS with --photon-tracing uniform and
# adaptive, both measured against one reference of REF_SECONDS (uniform tracing, another photon
# stream, so neither side is measured against its own noise). Prints, per scene, the visible
# share the pilot found, each render's photons and RMSE, and uniform's RMSE over adaptive's
# (above 1: adaptive ahead). The reference carries noise of its own, about
# sqrt(SECONDS / REF_SECONDS) of a render's: both RMSEs hold it.
# Usage: bench/adaptive_vs_uniform.sh BUILD_DIR [SIZE] [SECONDS] [REF_SECONDS] [SCENE...]
# (default scenes: light-gap caustic-glass caustic-room cornell-box)
set -euo pipefail
build=${1:?usage: adaptive_vs_uniform.sh BUILD_DIR [SIZE] [SECONDS] [REF_SECONDS] [SCENE...]}
size=${2:-128}
seconds=${3:-20}
ref_seconds=${4:-150}
shift $(($# < 4 ? $# : 4))
scenes=("$@")
((${#scenes[@]})) || scenes=(light-gap caustic-glass caustic-room cornell-box)
photonfarm="$build/client/photonfarm"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
common=(--width "$size" --height "$size")

# rmse IMAGE REFERENCE: the RMSE `photonfarm compare` prints.
rmse() { "$photonfarm" compare "$1" "$2" | awk '$1 == "rmse" { print $2 }'; }

printf '| scene | visible share | uniform: photons, RMSE | adaptive: photons, RMSE | RMSE ratio |\n'
printf '|---|---:|---:|---:|---:|\n'
for scene in "${scenes[@]}"; do
    gltf=scenes/$scene.gltf
    "$photonfarm" render "$gltf" "${common[@]}" --seconds "$ref_seconds" --photon-stream 7 \
        --photon-tracing uniform --log-level warn --out "$work/$scene-ref.exr" >/dev/null 2>&1
    declare -A photons=() error=()
    share="?"
    for mode in uniform adaptive; do
        log=$work/$scene-$mode.log
        "$photonfarm" render "$gltf" "${common[@]}" --seconds "$seconds" --photon-tracing "$mode" \
            --out "$work/$scene-$mode.exr" >"$log" 2>&1
        photons[$mode]=$(sed -n 's/^done: \([^ ]*\) photons.*/\1/p' "$log")
        error[$mode]=$(rmse "$work/$scene-$mode.exr" "$work/$scene-ref.exr")
        found=$(sed -n 's/.*: \([0-9.]*%\) of photons reach what the camera sees.*/\1/p' "$log")
        [[ -n $found ]] && share=$found
    done
    printf '| %s | %s | %s, %s | %s, %s | %.2f |\n' "$scene" "$share" "${photons[uniform]}" \
        "${error[uniform]}" "${photons[adaptive]}" "${error[adaptive]}" \
        "$(awk -v u="${error[uniform]}" -v a="${error[adaptive]}" 'BEGIN { print u / a }')"
done
