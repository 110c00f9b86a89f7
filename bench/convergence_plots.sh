#!/usr/bin/env bash
# Error against run time for every shipped scene, as docs/convergence.md shows it: for each
# scene a long reference (the same hit points through another --photon-stream, REF_FACTOR x
# the photons in small epochs; for the furnaces the exact image L = 2), then a render of
# EPOCHS small epochs measured against it with --report. Copies each convergence.png to
# OUT/<scene>.png and prints a table: final photons and seconds, measured and estimated
# relative error, the estimate's ratio to the measured RMSE (range from epoch 8 on), and the
# fitted slopes of the measured RMSE against photons and seconds. A scene lit by a sky alone
# (scenes/<scene>-sky.hdr beside it) renders with that as its --environment. SCENES="a b"
# renders those scenes alone.
# Usage: bench/convergence_plots.sh BUILD_DIR [OUT_DIR] [SIZE] [EPOCH_PHOTONS] [EPOCHS] [REF_FACTOR]
set -euo pipefail
build=${1:?usage: convergence_plots.sh BUILD_DIR [OUT_DIR] [SIZE] [EPOCH_PHOTONS] [EPOCHS] [REF_FACTOR]}
out=${2:-docs/convergence}
size=${3:-64}
epoch_photons=${4:-8192}
epochs=${5:-800}
ref_factor=${6:-20}
photons=$((epoch_photons * epochs))
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
photonfarm="$build/client/photonfarm"
common=(--width "$size" --height "$size" --log-level warn)

printf '%-16s %10s %8s %10s %10s %15s %10s %10s\n' scene photons seconds measured estimated "estimate/meas." slope/N slope/t
for gltf in scenes/*.gltf; do
    scene=$(basename "$gltf" .gltf)
    [[ -n ${SCENES:-} && " $SCENES " != *" $scene "* ]] && continue
    sky=()
    [[ -f scenes/$scene-sky.hdr ]] && sky=(--environment "scenes/$scene-sky.hdr")
    reference="$work/$scene-reference.exr"
    if [[ $scene == furnace* ]]; then
        oiiotool --pattern constant:color=2,2,2 "${size}x${size}" 3 -d float -o "$reference"
    else
        "$photonfarm" render "$gltf" "${sky[@]}" "${common[@]}" --photon-stream 1 --photons $((photons * ref_factor)) \
            --photons-per-batch $((epoch_photons * 2)) --batches-per-epoch 2 --out "$reference" 2>"$work/log" ||
            { cat "$work/log" >&2; exit 1; }
    fi
    "$photonfarm" render "$gltf" "${sky[@]}" "${common[@]}" --photons "$photons" --photons-per-batch "$epoch_photons" \
        --batches-per-epoch 1 --out "$work/$scene.exr" --reference "$reference" --report "$work/$scene" 2>"$work/log" ||
        { cat "$work/log" >&2; exit 1; }
    cp "$work/$scene/convergence.png" "$out/$scene.png"
    slopes=$(awk -F' = ' '/^ref_n_slope/ {n=$2} /^ref_t_slope/ {t=$2} END {printf "%.3f %.3f", n, t}' "$work/$scene/convergence.gp")
    awk -F, -v scene="$scene" -v slopes="$slopes" '
        NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
        {
            last_photons = $col["photons"]; last_seconds = $col["seconds"]
            measured = $col["reference_rel_error"]; estimated = $col["estimated_rel_error"]
            if ($col["epochs"] >= 8) {
                r = $col["estimated_rmse"] / $col["reference_rmse"]
                if (lo == "" || r < lo) lo = r
                if (hi == "" || r > hi) hi = r
            }
        }
        END {
            split(slopes, s, " ")
            printf "%-16s %10d %8.1f %9.2f%% %9.2f%% %7.2f-%-7.2f %10s %10s\n", scene, last_photons, last_seconds,
                   100 * measured, 100 * estimated, lo, hi, s[1], s[2]
        }' "$work/$scene/convergence.csv"
done
