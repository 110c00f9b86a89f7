#!/usr/bin/env bash
# The photonfarm command line meets bad input with one clear line and a non-zero exit code,
# and a good render writes its outputs. Usage: cli_errors_test.sh PHOTONFARM SOURCE_DIR
set -u
photonfarm=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

# expect_failure NAME PATTERN ARGS...: the command must exit non-zero, print one line on stderr
# containing PATTERN, and nothing on stdout.
expect_failure() {
    local name=$1 pattern=$2
    shift 2
    "$photonfarm" "$@" >"$work/out" 2>"$work/err"
    local code=$?
    local lines
    lines=$(grep -c . "$work/err")
    if [ "$code" -eq 0 ] || [ "$lines" -ne 1 ] || ! grep -q -- "$pattern" "$work/err"; then
        echo "FAIL $name: exit $code, $lines stderr lines:"
        cat "$work/err"
        failures=$((failures + 1))
    else
        echo "ok   $name: $(cat "$work/err")"
    fi
}

oiiotool --pattern constant:color=1,1,1 4x4 3 -d float -o "$work/small.exr"
printf '{"asset": {"version": "2.0"' >"$work/broken.gltf"
expect_failure "unknown flag" "--frobnicate" render "$source_dir/scenes/cornell-box.gltf" --out "$work/a.exr" --frobnicate
expect_failure "missing scene" "nope.gltf" render "$work/nope.gltf" --out "$work/a.exr"
expect_failure "malformed scene" "broken.gltf" render "$work/broken.gltf" --out "$work/a.exr" --photons 1000
printf 'LookAt 0 0 -1  0 0 0  0 1 0\nCamera "perspective"\nWorldBegin\nShape "sphere" "float radius" "big"\n' >"$work/bad.pbrt"
expect_failure "malformed pbrt scene" "bad.pbrt:4:16: parameter \"float radius\" needs numbers, found \"big\"" \
    render "$work/bad.pbrt" --out "$work/a.exr" --photons 1000
printf 'WorldBegin\nInclude "../secret.pbrt"\n' >"$work/escape.pbrt"
expect_failure "pbrt include outside the folder" "escape.pbrt:2:1: Include: scene reference '../secret.pbrt' leaves" \
    render "$work/escape.pbrt" --out "$work/a.exr" --photons 1000
expect_failure "unknown scene format" "unknown scene format" render "$work/small.exr" --out "$work/a.exr" --photons 1000
# The farm commands: nothing listens on port 1 here.
expect_failure "unreachable server" "cannot reach the coordinator at 127.0.0.1:1" jobs --server 127.0.0.1:1
expect_failure "unreachable server on submit" "cannot reach the coordinator" submit "$source_dir/scenes/cornell-box.gltf" \
    --server 127.0.0.1:1 --photons 1000
expect_failure "no server given" "server" workers
expect_failure "certificate without its key" "--tls-cert and --tls-key: give both or neither" \
    jobs --server 127.0.0.1:1 --tls-cert "$work/small.exr"
expect_failure "missing token file" "token file $work/none: cannot open" jobs --server 127.0.0.1:1 --token-file "$work/none"
printf 'short\n' >"$work/short-token"
expect_failure "guessable token" "short-token:1: the token is 5 characters" \
    jobs --server 127.0.0.1:1 --token-file "$work/short-token"
PHOTONFARM_CLIENT_TOKEN=tiny expect_failure "guessable token from the environment" "PHOTONFARM_CLIENT_TOKEN: the token is 4" \
    jobs --server 127.0.0.1:1
expect_failure "outputs without --watch" "need --watch" submit "$source_dir/scenes/cornell-box.gltf" \
    --server 127.0.0.1:1 --out "$work/a.exr"
VK_ICD_FILENAMES=/nonexistent/icd.json expect_failure "vulkan without a driver" "vulkan backend: no Vulkan driver" \
    render "$source_dir/scenes/cornell-box.gltf" --out "$work/a.exr" --backend vulkan
expect_failure "an integrator the backend does not run" "--backend vulkan runs --integrator ppm or sppm, not pm" \
    render "$source_dir/scenes/cornell-box.gltf" --out "$work/a.exr" --backend vulkan --integrator pm
expect_failure "unknown backend" "--backend" render "$source_dir/scenes/cornell-box.gltf" --out "$work/a.exr" \
    --backend cuda
expect_failure "bad alpha" "alpha" render "$source_dir/scenes/cornell-box.gltf" --out "$work/a.exr" --alpha 2
expect_failure "unknown integrator" "--integrator" render "$source_dir/scenes/cornell-box.gltf" --out "$work/a.exr" \
    --integrator bdpt
expect_failure "photon budget for the path tracer" "--photons is a budget of photons traced progressively" \
    render "$source_dir/scenes/cornell-box.gltf" --out "$work/a.exr" --integrator path --photons 1M
expect_failure "photon maps that will not fit" "--pm-photons/--pm-caustic-photons: .* would store about" \
    render "$source_dir/scenes/cornell-box.gltf" --out "$work/a.exr" --integrator pm --pm-photons 16G --epochs 1
expect_failure "unknown photon index" "--photon-index" render "$source_dir/scenes/cornell-box.gltf" \
    --out "$work/a.exr" --integrator pm --photon-index octree
# NaN and Inf in any number flag: refused by name before any work.
for flag in --alpha --radius --seconds --target-error --exposure --snapshot-every; do
    for value in nan inf -inf 1e999; do
        expect_failure "$flag $value" "$flag: must be a finite number" render "$source_dir/scenes/cornell-box.gltf" \
            --out "$work/a.exr" "$flag" "$value"
    done
done
expect_failure "reference of another size" "reference: the image is" render "$source_dir/scenes/cornell-box.gltf" \
    --out "$work/b.exr" --width 8 --height 8 --photons 1000 --reference "$work/small.exr"
expect_failure "both budgets" "excludes" render "$source_dir/scenes/cornell-box.gltf" --out "$work/a.exr" --photons 1000 --seconds 1
expect_failure "unwritable output" "cannot write here" render "$source_dir/scenes/cornell-box.gltf" \
    --out "$work/no/such/dir/a.exr" --photons 1000 --width 16 --log-level error

if "$photonfarm" render "$source_dir/scenes/cornell-box.gltf" --out "$work/ok.exr" --png "$work/ok.png" \
        --photons 20k --width 32 --threads 1 >/dev/null 2>"$work/err" && [ -s "$work/ok.exr" ] && [ -s "$work/ok.png" ]; then
    echo "ok   good render writes EXR and PNG"
else
    echo "FAIL good render"; cat "$work/err"; failures=$((failures + 1))
fi

if "$photonfarm" render "$source_dir/scenes/furnace.gltf" --out "$work/snap.exr" --photons 3M \
        --photons-per-batch 65536 --batches-per-epoch 2 --width 16 --threads 1 \
        --snapshot-every 0.001 --snapshot-dir "$work/snapshots" >/dev/null 2>"$work/err" &&
        [ -s "$work/snapshots/snapshot-0001.exr" ] && [ -s "$work/snapshots/snapshot-0002.exr" ]; then
    echo "ok   snapshots are written while rendering"
else
    echo "FAIL snapshots"; cat "$work/err"; failures=$((failures + 1))
fi

# Ctrl-C stops after the current epoch and still writes the image: nothing computed is lost.
"$photonfarm" render "$source_dir/scenes/furnace.gltf" --out "$work/interrupted.exr" --seconds 120 \
    --photons-per-batch 65536 --batches-per-epoch 2 --width 16 --threads 1 \
    --snapshot-every 0.001 --snapshot-dir "$work/interrupt-snapshots" >/dev/null 2>"$work/err" &
render_pid=$!
for _ in $(seq 300); do  # wait (at most 30 s) until the render is under way
    [ -s "$work/interrupt-snapshots/snapshot-0001.exr" ] && break
    sleep 0.1
done
kill -INT "$render_pid"
wait "$render_pid"
code=$?
if [ "$code" -eq 0 ] && [ -s "$work/interrupted.exr" ] && grep -q "stopped early" "$work/err"; then
    echo "ok   SIGINT stops after the epoch and writes the image"
else
    echo "FAIL SIGINT: exit $code"; cat "$work/err"; failures=$((failures + 1))
fi

[ "$failures" -eq 0 ] && echo "all CLI checks passed" || { echo "$failures CLI checks failed"; exit 1; }
