#!/usr/bin/env bash
# Whole-run throughput of the farm against the embedded renderer with the same total threads:
# photonfarm render --threads 2, then a coordinator and two one-thread workers on 127.0.0.1,
# the same job (scene, photons, batch layout) for both, in alternation for ROUNDS rounds.
# Prints photons per second after the camera pass for both (the farm's is the coordinator's, from
# the submission's status) and their ratio per round
# (target >= 0.95). The default layout is one a farm would use: batches of 4 chunks, so the
# coordinator merges a quarter of the tally entries per photon of the one-machine default.
# Usage: bench/farm_vs_render.sh BUILD_DIR [SCENE] [PHOTONS] [ROUNDS] [LAYOUT FLAGS...]
set -euo pipefail
build=${1:?usage: farm_vs_render.sh BUILD_DIR [SCENE] [PHOTONS] [ROUNDS] [LAYOUT FLAGS...]}
scene=${2:-scenes/cornell-box.gltf}
photons=${3:-33554432}
rounds=${4:-2}
shift $(($# < 4 ? $# : 4))
layout=("$@")
[ ${#layout[@]} -gt 0 ] || layout=(--photons-per-batch 2097152 --batches-per-epoch 4)
work=$(mktemp -d)
workers=() coordinator=
stop_farm() {
    # Workers first (SIGTERM: they return their leases and leave), then the coordinator.
    [ ${#workers[@]} -eq 0 ] || { kill -TERM "${workers[@]}" 2>/dev/null || true; wait "${workers[@]}" 2>/dev/null || true; }
    [ -z "$coordinator" ] || { kill -TERM "$coordinator" 2>/dev/null || true; wait "$coordinator" 2>/dev/null || true; }
    workers=() coordinator=
}
trap 'stop_farm; rm -rf "$work"' EXIT

render_rate() {
    local line
    line=$("$build/client/photonfarm" render "$scene" --photons "$photons" "${layout[@]}" --threads 2 \
        --out "$work/render.exr" 2>&1 | grep '^done:')
    # done: 33.55M photons, epoch 8, 11.7 s, ...; ..., camera pass 0.31 s, ...
    echo "$line" | awk -v photons="$photons" '{
        for (i = 1; i <= NF; ++i) { if ($i == "s," && seconds == "") seconds = $(i - 1); if ($i == "pass") camera = $(i + 1) }
        printf "%.0f", photons / (seconds - camera) }'
}

farm_rate() {
    "$build/server/photonfarm-coordinator" --listen 127.0.0.1:0 --plaintext --log-level warn > "$work/coordinator.out" &
    coordinator=$!
    for _ in $(seq 50); do grep -q listening "$work/coordinator.out" && break; sleep 0.1; done
    local address
    address=$(sed -n 's/^listening on //p' "$work/coordinator.out")
    for _ in 1 2; do
        "$build/worker/photonfarm-worker" --coordinator "$address" --plaintext --threads 1 --log-level warn &
        workers+=($!)
    done
    # The first status is the submission's (its elapsed time: the camera pass, run by the
    # coordinator), the last the job's end: photons over the time between, as for the render.
    "$build/client/photonfarm" submit "$scene" --server "$address" --plaintext --photons "$photons" "${layout[@]}" --watch --json \
        --log-level warn > "$work/farm.json"
    sed -n '1p;$p' "$work/farm.json" | grep -o '"photons":"[0-9]*"\|"elapsed_seconds":[0-9.e+-]*' |
        sed 's/.*://; s/"//g' | paste - - | awk 'NR == 1 { camera = $2 } NR == 2 { printf "%.0f", $1 / ($2 - camera) }'
    stop_farm
}

echo "$scene, $photons photons, layout: ${layout[*]}"
for round in $(seq "$rounds"); do
    r=$(render_rate)
    f=$(farm_rate)
    awk -v r="$r" -v f="$f" -v round="$round" 'BEGIN {
        printf "round %d: render (2 threads) %.3g photons/s, coordinator + 2 one-thread workers %.3g photons/s: farm / render %.3f (target >= 0.95)\n",
            round, r, f, f / r }'
done
