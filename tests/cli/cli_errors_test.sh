#!/usr/bin/env bash
# The photonfarm executables meet bad input with one clear line and a non-zero exit code, and
# a good render writes its outputs. Every class of numeric flag (counts with units, whole
# numbers, reals, addresses) refuses negative, zero where meaningless, NaN, infinite and
# overflowing values on render, submit, the coordinator and the worker, naming the flag and
# its range.
# The checks come in sections, each a CTest test of its own (cli.errors.SECTION), so that
# `ctest -j` runs them side by side: every check is a process of its own, most of their time
# is the executables' start-up, and one long sequence of them held one core for minutes.
# Usage: cli_errors_test.sh PHOTONFARM COORDINATOR WORKER SOURCE_DIR [SECTION...]
#        SECTIONs: scenes options numbers_render numbers_submit farm servers renders (all if none)
set -u
photonfarm=$1
coordinator=$2
worker=$3
source_dir=$4
shift 4
all_sections=(scenes options numbers_render numbers_submit farm servers renders)
sections=("$@")
[ ${#sections[@]} -gt 0 ] || sections=("${all_sections[@]}")
for section in "${sections[@]}"; do
    [[ " ${all_sections[*]} " == *" $section "* ]] || { echo "cli_errors_test.sh: no section '$section'"; exit 2; }
done
work=$(mktemp -d)
failures=0

# A port nothing listens on: held bound (not listening) by a helper for the whole test, so no
# other process can take it; connecting to it is refused at once.
coproc PORT_HOLDER {
    exec python3 -c 'import socket, sys
s = socket.socket()
s.bind(("127.0.0.1", 0))
print(s.getsockname()[1], flush=True)
sys.stdin.read()'
}
read -r closed_port <&"${PORT_HOLDER[0]}"
closed=127.0.0.1:$closed_port
trap 'kill "$PORT_HOLDER_PID" 2>/dev/null; rm -rf "$work"' EXIT

# expect_failure_of BINARY NAME PATTERN ARGS...: the command must exit non-zero, print one line
# on stderr containing PATTERN, and nothing on stdout.
expect_failure_of() {
    local binary=$1 name=$2 pattern=$3
    shift 3
    timeout 60 "$binary" "$@" >"$work/out" 2>"$work/err"
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
expect_failure() { expect_failure_of "$photonfarm" "$@"; }

# small.exr: a 4x4 image, for a reference of the wrong size and a file that is no scene.
make_small_exr() { [ -s "$work/small.exr" ] || oiiotool --pattern constant:color=1,1,1 4x4 3 -d float -o "$work/small.exr"; }
scene=$source_dir/scenes/cornell-box.gltf

# Scenes that cannot be read or rendered as asked, and scenes that can.
section_scenes() {
    make_small_exr
    printf '{"asset": {"version": "2.0"' >"$work/broken.gltf"
    cp -r "$source_dir/scenes/pbrt" "$work/pbrt"
    expect_failure "unknown flag" "--frobnicate" render "$source_dir/scenes/cornell-box.gltf" --out "$work/a.exr" --frobnicate
    expect_failure "missing scene" "nope.gltf" render "$work/nope.gltf" --out "$work/a.exr"
    expect_failure "malformed scene" "broken.gltf" render "$work/broken.gltf" --out "$work/a.exr" --photons 1000
    printf 'LookAt 0 0 -1  0 0 0  0 1 0\nCamera "perspective"\nWorldBegin\nShape "sphere" "float radius" "big"\n' >"$work/bad.pbrt"
    expect_failure "malformed pbrt scene" "bad.pbrt:4:16: parameter \"float radius\" needs numbers, found \"big\"" \
        render "$work/bad.pbrt" --out "$work/a.exr" --photons 1000
    printf 'WorldBegin\nInclude "../secret.pbrt"\n' >"$work/escape.pbrt"
    expect_failure "pbrt include outside the folder" "escape.pbrt:2:1: Include: scene reference '../secret.pbrt' leaves" \
        render "$work/escape.pbrt" --out "$work/a.exr" --photons 1000
    expect_failure "a scene root that does not hold the scene" "--scene-root .*: must be a folder that holds" \
        render "$source_dir/scenes/cornell-box.gltf" --out "$work/a.exr" --photons 1000 --scene-root "$work/pbrt"
    expect_failure "unknown scene format" "unknown scene format" render "$work/small.exr" --out "$work/a.exr" --photons 1000
    expect_failure "reference of another size" "reference: the image is" render "$source_dir/scenes/cornell-box.gltf" \
        --out "$work/b.exr" --width 8 --height 8 --photons 1000 --reference "$work/small.exr"
    expect_failure "both budgets" "excludes" render "$source_dir/scenes/cornell-box.gltf" --out "$work/a.exr" --photons 1000 --seconds 1
    expect_failure "unwritable output" "cannot write here" render "$source_dir/scenes/cornell-box.gltf" \
        --out "$work/no/such/dir/a.exr" --photons 1000 --width 16 --log-level error
    expect_failure "a camera the scene does not have" "--camera side: no such camera; the scene has 0 " \
        render "$source_dir/scenes/cornell-box.gltf" --out "$work/a.exr" --photons 1000 --camera side
    expect_failure "another camera of a pbrt scene" "--camera 2: .*cornell-box.pbrt is a pbrt scene, with one camera" \
        render "$source_dir/scenes/pbrt/cornell-box.pbrt" --out "$work/a.exr" --photons 1000 --camera 2

    # A scene with no light says so and names the way out; --environment-color lights it.
    printf 'LookAt 0 0 5  0 0 0  0 1 0\nCamera "perspective" "float fov" 40\nWorldBegin\nShape "sphere"\n' \
        >"$work/dark.pbrt"
    expect_failure "a scene with no light" "dark.pbrt: scene has no light .* --environment FILE or --environment-color" \
        render "$work/dark.pbrt" --out "$work/a.exr" --photons 1000
    if "$photonfarm" render "$work/dark.pbrt" --out "$work/sky.exr" --environment-color 0.5,0.6,0.7 \
            --integrator path --epochs 1 --width 16 --threads 1 >/dev/null 2>"$work/err" && [ -s "$work/sky.exr" ]; then
        echo "ok   --environment-color lights a scene that has no light"
    else
        echo "FAIL --environment-color render"; cat "$work/err"; failures=$((failures + 1))
    fi
}

# Options refused by value: backends, integrators, photon maps; NaN and Inf in any real flag.
section_options() {
    VK_ICD_FILENAMES=/nonexistent/icd.json expect_failure "vulkan without a driver" "vulkan backend: no Vulkan driver" \
        render "$source_dir/scenes/cornell-box.gltf" --out "$work/a.exr" --backend vulkan
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
}

# numeric_flags COMMAND: every numeric flag class, on render and on submit alike (submit parses
# before it connects).
numeric_flags() {
    local command=$1 target value args case flag range flags pattern
    if [ "$command" = render ]; then target=(--out "$work/a.exr"); else target=(--server "$closed"); fi
    # Counts with units: a sign, zero, overflow, a fraction left over, unknown units, NaN.
    for value in -5 =-5 0 99999999999T 5X 1.0000005k nan 1e999 ""; do
        if [ "$value" = "=-5" ]; then args=(--photons=-5); else args=(--photons "$value"); fi
        expect_failure "$command --photons '$value'" "--photons: must be a count in \[1, 1000T\]" \
            "$command" "$scene" "${target[@]}" "${args[@]}"
    done
    for value in -1 99999999999999T 2.5; do
        expect_failure "$command --pm-photons $value" "--pm-photons: must be a count in \[0, " \
            "$command" "$scene" "${target[@]}" --integrator pm --epochs 1 --pm-photons "$value"
    done
    # Whole numbers: negative, zero where meaningless, too large, fractions.
    for case in "--spp 0 [1, 1024]" "--spp 1025 [1, 1024]" "--width -3 [1, 32768]" "--width 1.5 [1, 32768]" \
        "--height 40000 [1, 32768]" "--epochs 0 [1, 1099511627776]" "--epochs -1 [1, 1099511627776]" \
        "--seed -1 [0, 18446744073709551615]" "--seed 18446744073709551616 [0, 18446744073709551615]" \
        "--photon-stream -2 [0, 18446744073709551615]" "--photons-per-batch 0 [1, 67108864]" \
        "--photons-per-batch 4294967297 [1, 67108864]" "--batches-per-epoch -1 [1, 65536]" \
        "--pm-nearest 0 [1, 4096]" "--final-gather -1 [0, 4096]" "--max-depth 0 [1, 65536]" \
        "--max-depth 65537 [1, 65536]"; do
        read -r flag value range <<<"$case"
        expect_failure "$command $flag $value" "$flag: must be a whole number in \\$range" \
            "$command" "$scene" "${target[@]}" "$flag" "$value"
    done
    # Reals: out of range and negative (NaN and Inf below).
    for case in "--alpha 0" "--alpha -1" "--alpha 1.5" "--seconds -1" "--seconds 0" "--seconds 1e9" \
        "--radius -1" "--radius 0" "--target-error 0" "--target-error -0.1" "--pm-max-radius -1"; do
        read -r flag value <<<"$case"
        expect_failure "$command $flag $value" "$flag: must .*, not '$value'" \
            "$command" "$scene" "${target[@]}" "$flag" "$value"
    done
    expect_failure "$command --until-cancelled with a budget" "excludes --until-cancelled" \
        "$command" "$scene" "${target[@]}" --until-cancelled --photons 1M
    # The environment's flags: three finite non-negative values, a scale and a turn in range,
    # a file that exists, and not both a file and a colour.
    for case in "--environment-color 1,2|At least 3 required" "--environment-color 1,1,1,1|At Most 3" \
        "--environment-color 1,-1,1|--environment-color: must lie in \[0, 1e+12\], not '-1'" \
        "--environment-color nan,1,1|--environment-color: must be a finite number" \
        "--environment-scale 0|--environment-scale: must lie in" \
        "--environment-rotate 400|--environment-rotate: must lie in \[-360, 360\]" \
        "--environment $work/none.exr|--environment: File does not exist" \
        "--environment-scale 2|--environment-scale/--environment-rotate apply to an environment" \
        "--environment-color 1,1,1 --environment $source_dir/Makefile|--environment excludes --environment-color"; do
        IFS='|' read -r flags pattern <<<"$case"
        # shellcheck disable=SC2086
        expect_failure "$command $flags" "$pattern" "$command" "$scene" "${target[@]}" $flags
    done
}
section_numbers_render() {
    numeric_flags render
    for value in 0 -1 5000 two; do
        expect_failure "render --threads $value" "--threads" render "$scene" --out "$work/a.exr" --threads "$value"
    done
}
section_numbers_submit() { numeric_flags submit; }

# The farm commands, against a port nothing listens on, and their own flags.
section_farm() {
    make_small_exr
    expect_failure "unreachable server" "cannot reach the coordinator at $closed" jobs --server $closed
    expect_failure "unreachable server on submit" "cannot reach the coordinator" submit "$source_dir/scenes/cornell-box.gltf" \
        --server $closed --photons 1000
    expect_failure "no server given" "server" workers
    expect_failure "certificate without its key" "--tls-cert and --tls-key: give both or neither" \
        jobs --server $closed --tls-cert "$work/small.exr"
    expect_failure "missing token file" "token file $work/none: cannot open" jobs --server $closed --token-file "$work/none"
    printf 'short\n' >"$work/short-token"
    expect_failure "guessable token" "short-token:1: the token is 5 characters" \
        jobs --server $closed --token-file "$work/short-token"
    PHOTONFARM_CLIENT_TOKEN=tiny expect_failure "guessable token from the environment" "PHOTONFARM_CLIENT_TOKEN: the token is 4" \
        jobs --server $closed
    expect_failure "outputs without --watch" "need --watch" submit "$source_dir/scenes/cornell-box.gltf" \
        --server $closed --out "$work/a.exr"
    for value in 99999999999 -1000001 1.5; do
        expect_failure "submit --priority $value" "--priority: must be a whole number in \[-1000000, 1000000\]" \
            submit "$scene" --server "$closed" --priority "$value"
    done
    expect_failure "submit --interval -1" "--interval: must lie in \[0, 3600\]" submit "$scene" --server "$closed" \
        --interval -1
    # Addresses: the port in range and a number, IPv6 hosts in brackets.
    for address in 127.0.0.1:70000 127.0.0.1:-1 127.0.0.1:abc 127.0.0.1: nocolon ::1:50 127.0.0.1:0; do
        expect_failure "jobs --server $address" "--server: must be HOST:PORT with a port in \[1, 65535\]" \
            jobs --server "$address"
    done
}

# The coordinator and the worker: addresses, durations, limits and thread counts; the dashboard.
section_servers() {
    for case in "--listen 127.0.0.1:70000" "--listen localhost:x" "--metrics-listen 127.0.0.1:-1" "--web-listen 127.0.0.1:x" \
        "--heartbeat-seconds 0" "--heartbeat-seconds nan" "--worker-timeout-seconds -1" "--lease-seconds inf" \
        "--checkpoint-seconds 0" "--max-jobs 0" "--max-jobs-per-client -1" "--max-watchers-per-job 0" \
        "--max-bundle-bytes -1" "--max-render-pixels 0" "--max-photons-per-batch 0" "--max-message-bytes 0" \
        "--max-scene-triangles -5" "--max-scene-instances 0" "--max-image-pixels 0"; do
        read -r flag value <<<"$case"
        expect_failure_of "$coordinator" "coordinator $flag $value" "$flag" --plaintext "$flag" "$value"
    done
    for case in "--coordinator 127.0.0.1:0" "--coordinator 127.0.0.1:65536" "--threads 0" "--threads -2" \
        "--chunks-per-lease 0" "--chunks-per-lease 99999999"; do
        read -r flag value <<<"$case"
        expect_failure_of "$worker" "worker $flag $value" "$flag" --coordinator "$closed" "$flag" "$value"
    done
    expect_failure_of "$coordinator" "coordinator --web-listen on a port in use" "--web-listen: cannot listen on $closed" \
        --plaintext --listen 127.0.0.1:0 --web-listen "$closed"
    # The embedded dashboard: plain HTTP with no login, so not on a public address unless asked.
    expect_failure "render --web-listen on a public address" "--web-listen: 0.0.0.0:0 is not a loopback address.*--plaintext" \
        render "$scene" --out "$work/a.exr" --web-listen 0.0.0.0:0
    expect_failure "render --web-listen not an address" "--web-listen: must be HOST:PORT" \
        render "$scene" --out "$work/a.exr" --web-listen dashboard
}

# Renders that work: outputs, snapshots, and Ctrl-C.
section_renders() {
    if "$photonfarm" render "$source_dir/scenes/cornell-box.gltf" --out "$work/ok.exr" --png "$work/ok.png" \
            --photons 20k --width 32 --threads 1 >/dev/null 2>"$work/err" && [ -s "$work/ok.exr" ] && [ -s "$work/ok.png" ]; then
        echo "ok   good render writes EXR and PNG"
    else
        echo "FAIL good render"; cat "$work/err"; failures=$((failures + 1))
    fi

    if "$photonfarm" render "$source_dir/scenes/furnace.gltf" --out "$work/snap.exr" --epochs 4 \
            --photons-per-batch 65536 --batches-per-epoch 2 --width 16 --threads 1 \
            --snapshot-every 0.001 --snapshot-dir "$work/snapshots" >/dev/null 2>"$work/err" &&
            [ -s "$work/snapshots/snapshot-0001.exr" ] && [ -s "$work/snapshots/snapshot-0002.exr" ]; then
        echo "ok   snapshots are written while rendering"
    else
        echo "FAIL snapshots"; cat "$work/err"; failures=$((failures + 1))
    fi

    # Ctrl-C stops after the current epoch and still writes the image: nothing computed is lost.
    # The render must be under way (its first snapshot written) before the signal: if it never
    # gets there within a minute the check fails, rather than interrupting a render not started.
    "$photonfarm" render "$source_dir/scenes/furnace.gltf" --out "$work/interrupted.exr" --seconds 120 \
        --photons-per-batch 65536 --batches-per-epoch 2 --width 16 --threads 1 \
        --snapshot-every 0.001 --snapshot-dir "$work/interrupt-snapshots" >/dev/null 2>"$work/err" &
    render_pid=$!
    started=no
    for _ in $(seq 600); do  # poll (at most 60 s) for the first snapshot
        [ -s "$work/interrupt-snapshots/snapshot-0001.exr" ] && { started=yes; break; }
        kill -0 "$render_pid" 2>/dev/null || break
        sleep 0.1
    done
    kill -INT "$render_pid"
    wait "$render_pid"
    code=$?
    if [ "$started" != yes ]; then
        echo "FAIL SIGINT: the render wrote no snapshot within 60 s (exit $code)"; cat "$work/err"
        failures=$((failures + 1))
    elif [ "$code" -eq 0 ] && [ -s "$work/interrupted.exr" ] && grep -q "stopped early" "$work/err"; then
        echo "ok   SIGINT stops after the epoch and writes the image"
    else
        echo "FAIL SIGINT: exit $code"; cat "$work/err"; failures=$((failures + 1))
    fi
}

for section in "${sections[@]}"; do
    echo "== $section"
    "section_$section"
done
[ "$failures" -eq 0 ] && echo "all CLI checks passed (${sections[*]})" || { echo "$failures CLI checks failed"; exit 1; }
