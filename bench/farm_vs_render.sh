#!/usr/bin/env bash
# Whole-run throughput of the farm against the embedded renderer with the same total threads:
# photonfarm render --threads 2, then a coordinator and two one-thread workers on 127.0.0.1.
# Prints photons per second after the camera pass for both and their ratio (target >= 0.95).
# Usage: bench/farm_vs_render.sh BUILD_DIR [SCENE] [PHOTONS]
set -euo pipefail
build=${1:?usage: farm_vs_render.sh BUILD_DIR [SCENE] [PHOTONS]}
scene=${2:-scenes/cornell-box.gltf}
photons=${3:-33554432}
work=$(mktemp -d)
pids=()
cleanup() { for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done; wait 2>/dev/null || true; rm -rf "$work"; }
trap cleanup EXIT

render_line=$("$build/client/photonfarm" render "$scene" --photons "$photons" --threads 2 --out "$work/render.exr" 2>&1 | grep '^done:')
# done: 33.55M photons, epoch 8, 11.7 s, ...; ..., camera pass 0.31 s, ...
render_rate=$(echo "$render_line" | awk -v photons="$photons" '{
    for (i = 1; i <= NF; ++i) { if ($i == "s," && seconds == "") seconds = $(i - 1); if ($i == "pass") camera = $(i + 1) }
    printf "%.0f", photons / (seconds - camera) }')

"$build/server/photonfarm-coordinator" --listen 127.0.0.1:0 --log-level warn > "$work/coordinator.out" &
pids+=($!)
for _ in $(seq 50); do grep -q listening "$work/coordinator.out" && break; sleep 0.1; done
address=$(sed -n 's/^listening on //p' "$work/coordinator.out")
for _ in 1 2; do
    "$build/worker/photonfarm-worker" --coordinator "$address" --threads 1 --log-level warn &
    pids+=($!)
done
farm_json=$("$build/client/photonfarm" submit "$scene" --server "$address" --photons "$photons" --watch --json --log-level warn | tail -n 1)
farm_rate=$(echo "$farm_json" | sed 's/.*"photons_per_second":\([0-9.e+]*\).*/\1/')

awk -v r="$render_rate" -v f="$farm_rate" 'BEGIN {
    printf "render (2 threads):                 %.3g photons/s\n", r
    printf "coordinator + 2 one-thread workers: %.3g photons/s\n", f
    printf "farm / render: %.3f (target >= 0.95)\n", f / r }'
