#!/usr/bin/env bash
# The farm in containers, as deploy/compose.yaml runs it: the images built from
# deploy/Containerfile, then `docker-compose up --scale worker=3` against podman's Docker API
# (no Docker engine here), a job rendered to completion through the published port over TLS,
# its image bit-identical to `photonfarm render`, the health check and the metrics checked.
# Usage: farm_in_containers_test.sh BUILD_DIR SOURCE_DIR. Skips (77) where podman cannot run.
BUILD=$1 SOURCE=$2
source "$SOURCE/tests/containers/podman_env.sh"
command -v docker-compose >/dev/null || skip "docker-compose is not installed (deploy/install-deps.sh installs it)"

project=pftest$$
secrets=$W/secrets-$$
out=$W/out-$$
service_pid=
cleanup() {
    set +e
    [ -n "${DOCKER_HOST:-}" ] && docker-compose -p "$project" -f "$SOURCE/deploy/compose.yaml" down -v -t 30 > /dev/null 2>&1
    [ -n "$service_pid" ] && kill "$service_pid" 2> /dev/null && wait "$service_pid" 2> /dev/null
    rm -rf "$secrets" "$out" "$W/podman-$$.sock"
}
trap cleanup EXIT
free_port() { python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
# same_image IMAGE REFERENCE: bit-identical, with no NaN or Inf pixel in either. `compare`
# leaves such pixels out of its metrics (max_abs alone would pass an all-NaN image) and exits 3
# on them, so its exit status is checked as well as max_abs and the counts.
same_image() {
    local report
    if ! report=$("${client[@]}" compare "$1" "$2" --json --log-level warn 2>&1); then
        echo "compare $1 $2 failed: $report"
        return 1
    fi
    grep -q '"max_abs":0,' <<< "$report" && grep -q '"nonfinite_pixels":0,' <<< "$report" \
        && grep -q '"nonfinite_reference_pixels":0}' <<< "$report" || { echo "$report"; return 1; }
}
# nan_exr PATH WIDTH HEIGHT: an uncompressed float EXR whose every channel is NaN.
nan_exr() {
    python3 - "$@" <<'PY'
import struct, sys
path, width, height = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
def attribute(name, kind, data):
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data
channels = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in "BGR") + b"\0"
window = struct.pack("<4i", 0, 0, width - 1, height - 1)
header = (struct.pack("<ii", 20000630, 2) + attribute("channels", "chlist", channels)
          + attribute("compression", "compression", b"\0") + attribute("dataWindow", "box2i", window)
          + attribute("displayWindow", "box2i", window) + attribute("lineOrder", "lineOrder", b"\0")
          + attribute("pixelAspectRatio", "float", struct.pack("<f", 1))
          + attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0))
          + attribute("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
line = struct.pack("<%df" % (3 * width), *[float("nan")] * (3 * width))
first = len(header) + 8 * height
offsets = struct.pack("<%dQ" % height, *(first + y * (8 + len(line)) for y in range(height)))
with open(path, "wb") as out:
    out.write(header + offsets + b"".join(struct.pack("<ii", y, len(line)) + line for y in range(height)))
PY
}

build_images
bash "$SOURCE/deploy/make-certs.sh" "$secrets" localhost 127.0.0.1 coordinator > /dev/null
chmod -R a+rX "$secrets"  # the containers' user (uid 10001) reads them; a test folder only
mkdir -p "$out"

podman system service --time=0 "unix://$W/podman-$$.sock" > "$W/service.log" 2>&1 &
service_pid=$!
export DOCKER_HOST=unix://$W/podman-$$.sock
for _ in $(seq 100); do [ -S "$W/podman-$$.sock" ] && break; sleep 0.1; done

port=$(free_port) metrics_port=$(free_port) web_port=$(free_port)
export PHOTONFARM_IMAGE=$PF_TAG PHOTONFARM_TAG=test PHOTONFARM_SECRETS=$secrets PHOTONFARM_PORT=$port \
    PHOTONFARM_METRICS_PORT=$metrics_port PHOTONFARM_WEB_PORT=$web_port
say "docker-compose up --scale worker=3 (coordinator on 127.0.0.1:$port)"
docker-compose -p "$project" -f "$SOURCE/deploy/compose.yaml" up -d --no-build --scale worker=3 > "$W/compose.log" 2>&1 \
    || { cat "$W/compose.log"; exit 1; }

client=("$BUILD/client/photonfarm")
farm=(--server "127.0.0.1:$port" --tls-ca "$secrets/ca.pem" --token-file "$secrets/client-token" --log-level warn)
workers=0
for _ in $(seq 120); do
    workers=$("${client[@]}" workers "${farm[@]}" 2> /dev/null | tail -n +2 | grep -c . || true)
    [ "$workers" -ge 3 ] && break
    sleep 1
done
[ "$workers" -eq 3 ] || { echo "FAIL: $workers of 3 workers registered"; docker-compose -p "$project" -f "$SOURCE/deploy/compose.yaml" logs | tail -20; exit 1; }
say "3 workers registered"

# 20 epochs of 6 batches, for every worker to run some; small batches on a small image, since
# what is checked is bit-identity, which no statistic needs many photons for.
photons=$((20 * 6 * 2048))
job=(--width 32 --height 32 --photons-per-batch 2048 --batches-per-epoch 6 --seed 3 --photons "$photons")
"${client[@]}" submit "$SOURCE/scenes/cornell-box.gltf" "${farm[@]}" "${job[@]}" --watch --interval 0 --out "$out/farm.exr" \
    || { echo "FAIL: the job did not finish"; exit 1; }
"${client[@]}" render "$SOURCE/scenes/cornell-box.gltf" "${job[@]}" --threads 2 --out "$out/local.exr" --log-level warn
# The check can fail: an all-NaN image of the same size, on either side, is refused.
nan_exr "$out/nan.exr" 32 32
for pair in "$out/nan.exr $out/local.exr" "$out/local.exr $out/nan.exr"; do
    # shellcheck disable=SC2086
    ! same_image $pair > /dev/null || { echo "FAIL: same_image passed an all-NaN image ($pair)"; exit 1; }
done
same_image "$out/farm.exr" "$out/local.exr" || { echo "FAIL: the farm's image differs from photonfarm render"; exit 1; }
say "the image is bit-identical to photonfarm render (and an all-NaN image is refused)"

# Every worker ran batches.
idle=$("${client[@]}" workers "${farm[@]}" | awk 'NR > 1 && $5 == 0' | wc -l)
[ "$idle" -eq 0 ] || { echo "FAIL: $idle workers ran no batch"; exit 1; }
# The image's health check (the gRPC health service over TLS), and the metrics.
coordinator=$(podman ps --filter "label=com.docker.compose.project=$project" --filter "label=com.docker.compose.service=coordinator" --format '{{.Names}}')
podman healthcheck run "$coordinator" > /dev/null || { echo "FAIL: the coordinator's health check"; exit 1; }
exec 3<> "/dev/tcp/127.0.0.1/$metrics_port"
printf 'GET /metrics HTTP/1.0\r\nHost: localhost\r\n\r\n' >&3
metrics=$(cat <&3)
exec 3>&-
grep -q '^photonfarm_workers{backend="cpu"} 3' <<< "$metrics" || { echo "FAIL: metrics: workers"; grep photonfarm_workers <<< "$metrics"; exit 1; }
grep -q "^photonfarm_photons_total $photons" <<< "$metrics" || { echo "FAIL: metrics: photons"; grep photons_total <<< "$metrics"; exit 1; }
# The dashboard's JSON endpoint over HTTPS with the coordinator's certificate and a client token.
python3 - "$web_port" "$secrets" <<'PY' || { echo "FAIL: the dashboard's /api/jobs"; exit 1; }
import json, ssl, sys, urllib.request
port, secrets = sys.argv[1:3]
token = open(f"{secrets}/client-token").read().strip()
request = urllib.request.Request(f"https://127.0.0.1:{port}/api/jobs", headers={"Authorization": f"Bearer {token}"})
jobs = json.load(urllib.request.urlopen(request, context=ssl.create_default_context(cafile=f"{secrets}/ca.pem"), timeout=30))["jobs"]
assert [job["state"] for job in jobs] == ["JOB_STATE_DONE"], jobs
PY
say "health check, metrics and the dashboard agree"

# Workers leave cleanly on SIGTERM (compose stop sends it): exit 0 and unregistered.
docker-compose -p "$project" -f "$SOURCE/deploy/compose.yaml" stop -t 60 worker > /dev/null 2>&1
for name in $(podman ps -a --filter "label=com.docker.compose.project=$project" --filter "label=com.docker.compose.service=worker" --format '{{.Names}}'); do
    code=$(podman inspect --format '{{.State.ExitCode}}' "$name")
    [ "$code" = 0 ] || { echo "FAIL: $name exited $code on SIGTERM"; podman logs "$name" | tail -5; exit 1; }
done
left=$("${client[@]}" workers "${farm[@]}" | tail -n +2 | grep -c . || true)
[ "$left" -eq 0 ] || { echo "FAIL: $left workers still registered after SIGTERM"; exit 1; }
say "PASS: the workers left cleanly on SIGTERM"
