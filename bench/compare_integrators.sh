#!/usr/bin/env bash
# The photon mapping family side by side (docs/integrators.md): every shipped scene rendered by
# each integrator and measured against a long reference, as error against run time, with the
# memory each run took.
#  - The reference: bench/reference.sh's (the path tracer for REF_SECONDS; sppm for
#    caustic-glass; the exact image for the furnaces).
#  - path, ppm, sppm and rpm: one render of SECONDS each; their convergence logs (every epoch
#    measured against the reference) are the curves.
#  - pm: its error is fixed by its maps, so it runs once per map size (PM_SIZES photons per
#    map, PM_EPOCHS epochs each); each run is one point.
# Writes OUT/<scene>.png (log-log relative error against seconds, one curve per integrator),
# OUT/<scene>.csv (integrator,photons,seconds,relative_error,peak_memory_mb per run),
# OUT/table.md (the last point of every run) and OUT/ratios.md (for ppm, sppm and rpm, the time to
# the path tracer's error at a quarter of its run and at its end, over the path tracer's time:
# below 1, faster than the path tracer; bench/time_to_error.awk), and prints both tables.
# SCENES="a b" renders those scenes alone and keeps the other scenes' rows of OUT/table.md. A
# scene lit by a sky alone (scenes/<scene>-sky.hdr beside it) renders with that as its
# --environment.
# Usage: bench/compare_integrators.sh BUILD_DIR [OUT_DIR] [SIZE] [SECONDS] [REF_SECONDS]
set -euo pipefail
source "$(dirname "$0")/reference.sh"
build=${1:?usage: compare_integrators.sh BUILD_DIR [OUT_DIR] [SIZE] [SECONDS] [REF_SECONDS]}
out=${2:-docs/integrators}
size=${3:-96}
seconds=${4:-20}
ref_seconds=${5:-120}
pm_sizes=${PM_SIZES:-"30k 100k 300k 1M 3M"}
pm_epochs=${PM_EPOCHS:-4}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
photonfarm="$build/client/photonfarm"
common=(--width "$size" --height "$size" --log-level warn)

# render NAME ARGS...: one render into $work/NAME (image, report, log); prints "seconds error memory".
render() {
    local name=$1
    shift
    "$photonfarm" render "$@" "${sky[@]}" "${common[@]}" --out "$work/$name.exr" --report "$work/$name" >"$work/$name.log" 2>&1 ||
        { cat "$work/$name.log" >&2; exit 1; }
    local memory
    memory=$(sed -n 's/.*peak memory \([0-9]*\) MB.*/\1/p' "$work/$name.log" | tail -1)
    awk -F, -v memory="${memory:-0}" 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
        { s = $col["seconds"]; e = $col["reference_rel_error"]; p = $col["photons"] }
        END { printf "%s %s %s %s\n", s, e, memory, p }' "$work/$name/convergence.csv"
}

table="$out/table.md"
ratios="$out/ratios.md"
# keep TABLE: the rows of the scenes not rendered this time, into $work/kept-<table's name>.
keep() {
    : >"$work/kept-$(basename "$1")"
    if [[ -n ${SCENES:-} && -f $1 ]]; then
        tail -n +3 "$1" | awk -v scenes=" $SCENES " -F' [|] ' 'index(scenes, " " substr($1, 3) " ") == 0' \
            >"$work/kept-$(basename "$1")"
    fi
}
keep "$table"
keep "$ratios"
{
    echo "| scene | integrator | settings | photons | seconds | relative error | peak memory (MB) |"
    echo "|---|---|---|---:|---:|---:|---:|"
} >"$table"
{
    echo "| scene | integrator | path's error | path's seconds to it | seconds to it | ratio |"
    echo "|---|---|---:|---:|---:|---:|"
} >"$ratios"
rows="$work/rows.md"
ratio_rows="$work/ratio-rows.md"
: >"$rows"
: >"$ratio_rows"
for gltf in scenes/*.gltf; do
    scene=$(basename "$gltf" .gltf)
    [[ -n ${SCENES:-} && " $SCENES " != *" $scene "* ]] && continue
    sky=()
    [[ -f scenes/$scene-sky.hdr ]] && sky=(--environment "scenes/$scene-sky.hdr")
    reference="$work/$scene-reference.exr"
    make_reference "$photonfarm" "$gltf" "$reference" "$size" "$ref_seconds" "${sky[@]}"
    csv="$out/$scene.csv"
    echo "integrator,photons,seconds,relative_error,peak_memory_mb" >"$csv"
    plots=()
    for integrator in path ppm sppm rpm; do
        read -r s e m p < <(render "$scene-$integrator" "$gltf" --integrator "$integrator" --seconds "$seconds" \
                               --reference "$reference")
        echo "$integrator,$p,$s,$e,$m" >>"$csv"
        printf '| %s | %s | %s s | %s | %.1f | %.2f%% | %s |\n' "$scene" "$integrator" "$seconds" "$p" "$s" \
            "$(awk -v e="$e" 'BEGIN { print 100 * e }')" "$m" >>"$rows"
        cp "$work/$scene-$integrator/convergence.csv" "$work/$scene-$integrator.curve.csv"
        plots+=("'$work/$scene-$integrator.curve.csv' using (column(\"seconds\")):(column(\"reference_rel_error\")) with lines lw 2 title '$integrator'")
    done
    # The path tracer's error at a quarter of its run and at its end; each photon mapper's
    # time to it.
    path_curve="$work/$scene-path.curve.csv"
    for at in 0.25 1; do
        read -r path_s path_e < <(awk -F, -v at="$at" -v seconds="$seconds" '
            NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
            { s = $col["seconds"]; e = $col["reference_rel_error"] }
            !done && s >= at * seconds { print s, e; done = 1 }
            END { if (!done) print s, e }' "$path_curve")
        for integrator in ppm sppm rpm; do
            t=$(awk -F, -v target="$path_e" -v column=reference_rel_error \
                -f "$(dirname "$0")/time_to_error.awk" "$work/$scene-$integrator.curve.csv")
            if [[ $t == never ]]; then
                ratio=$(awk -v a="$seconds" -v b="$path_s" 'BEGIN { printf "> %.2f", a / b }')
            else
                ratio=$(awk -v a="$t" -v b="$path_s" 'BEGIN { printf "%.2f", a / b }')
            fi
            printf '| %s | %s | %.2f%% | %.1f | %s | %s |\n' "$scene" "$integrator" \
                "$(awk -v e="$path_e" 'BEGIN { print 100 * e }')" "$path_s" "$t" "$ratio" >>"$ratio_rows"
        done
    done
    pm_points="$work/$scene-pm.points"
    : >"$pm_points"
    for photons in $pm_sizes; do
        read -r s e m p < <(render "$scene-pm-$photons" "$gltf" --integrator pm --pm-photons "$photons" \
                               --pm-caustic-photons "$photons" --epochs "$pm_epochs" --reference "$reference")
        echo "pm,$p,$s,$e,$m" >>"$csv"
        echo "$s,$e,$photons" >>"$pm_points"
        printf '| %s | pm | %s photons a map, %s epochs | %s | %.1f | %.2f%% | %s |\n' "$scene" "$photons" \
            "$pm_epochs" "$p" "$s" "$(awk -v e="$e" 'BEGIN { print 100 * e }')" "$m" >>"$rows"
    done
    gnuplot <<EOF
set terminal pngcairo size 900,600 font ",11"
set output "$out/$scene.png"
set datafile separator ","
set logscale xy
set xlabel "seconds (2 cores)"
set ylabel "relative error against the reference"
set title "$scene, ${size}x${size}: error against run time"
set grid
set key top right
plot ${plots[0]}, ${plots[1]}, ${plots[2]}, ${plots[3]}, \\
     "$pm_points" using 1:2 with linespoints pt 7 lw 2 title "pm (one run per map size)", \\
     "$pm_points" using 1:2:3 with labels offset 0,1 notitle
EOF
done
cat "$work/kept-table.md" "$rows" | sort -s -t'|' -k2,2 >>"$table"
cat "$work/kept-ratios.md" "$ratio_rows" | sort -s -t'|' -k2,2 >>"$ratios"
cat "$table"
echo
cat "$ratios"
