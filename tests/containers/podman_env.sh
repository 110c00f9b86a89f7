# Sourced by the container tests: podman as it works on these machines (../shared notes:
# runc instead of crun, explicit ulimits), with its storage, networks and temporary files in a
# folder of the build tree, so nothing touches /var/lib/containers and cleaning up is rm -rf.
# Exits 77 (CTest's skip code) with a message when podman cannot run containers at all, and
# fails instead under CI=true (tests/support/prerequisite.sh).
# Needs: BUILD (the build folder), SOURCE (the source folder). Sets: W, PF_BASE, PF_TAG.
set -euo pipefail
BUILD=$(cd "$BUILD" && pwd) SOURCE=$(cd "$SOURCE" && pwd)
W=$BUILD/containers
PF_BASE=localhost/photonfarm-base:bookworm
PF_TAG=localhost/photonfarm
mkdir -p "$W"/{conf,storage,run,networks,tmp,libpod-tmp}
cat > "$W/conf/storage.conf" <<EOC
[storage]
driver = "overlay"
runroot = "$W/run"
graphroot = "$W/storage"
EOC
cat > "$W/conf/containers.conf" <<EOC
[containers]
default_ulimits = ["nofile=$(ulimit -Hn):$(ulimit -Hn)", "nproc=32768:32768"]
[engine]
runtime = "runc"
cgroup_manager = "cgroupfs"
events_logger = "file"
tmp_dir = "$W/libpod-tmp"
[network]
network_backend = "netavark"  # with aardvark-dns, containers find each other by name
network_config_dir = "$W/networks"
EOC
export CONTAINERS_STORAGE_CONF="$W/conf/storage.conf" CONTAINERS_CONF="$W/conf/containers.conf" TMPDIR="$W/tmp"

source "$SOURCE/tests/support/prerequisite.sh"
skip() { skip_for_want_of "$@"; }
say() { echo "[$(date +%T)] $*"; }
command -v podman >/dev/null || skip "podman is not installed (deploy/install-deps.sh installs it)"
[ "$(id -u)" -eq 0 ] || skip "the container tests run rootful podman: run them as root"

# The Debian 12 base image, made once with debootstrap from the mirror apt uses (no registry).
ensure_base_image() {
    podman image exists "$PF_BASE" && return 0
    command -v debootstrap >/dev/null || skip "debootstrap is not installed"
    local mirror
    mirror=$(awk '/^URIs:/{print $2; exit}' /etc/apt/sources.list.d/debian.sources 2>/dev/null || true)
    [ -n "$mirror" ] || mirror=$(awk '/^deb /{print $2; exit}' /etc/apt/sources.list 2>/dev/null || true)
    [ -n "$mirror" ] || skip "no Debian mirror found in /etc/apt"
    say "debootstrap bookworm from $mirror"
    rm -rf "$W/rootfs"
    debootstrap --variant=minbase bookworm "$W/rootfs" "$mirror" > "$W/debootstrap.log" 2>&1 \
        || { tail -5 "$W/debootstrap.log"; echo "debootstrap failed"; exit 1; }
    rm -rf "$W"/rootfs/var/cache/apt/archives/*.deb "$W"/rootfs/var/lib/apt/lists/*
    tar -C "$W/rootfs" -c . | podman import --change 'CMD ["/bin/bash"]' - "$PF_BASE" > /dev/null
    rm -rf "$W/rootfs"
}

# podman itself must run a container, or there is nothing to test here.
ensure_base_image
podman run --rm --pull=never "$PF_BASE" true > /dev/null 2>&1 \
    || skip "podman cannot run a container here: $(podman run --rm --pull=never "$PF_BASE" true 2>&1 | tail -1)"

# The coordinator and worker images, from deploy/Containerfile with this build's binaries.
# Built once for all the container tests: a stamp of what went into them (the recipe, the
# binaries, the host's package database that names their libraries' packages, the base image)
# is kept beside them, and a test that finds the same stamp and both images uses those.
build_images() {
    local context=$W/context stamp
    stamp=$( { cat "$SOURCE/deploy/Containerfile" "$SOURCE/deploy/stage-binaries.sh" \
        "$BUILD/server/photonfarm-coordinator" "$BUILD/worker/photonfarm-worker" "$BUILD/lib/libpf_image_oiio.so" "$BUILD/client/photonfarm" \
        /var/lib/dpkg/status; podman image inspect --format '{{.Id}}' "$PF_BASE"; } | sha256sum)
    if [ "$(cat "$W/images.stamp" 2> /dev/null)" = "$stamp" ] && podman image exists "$PF_TAG-coordinator:test" \
        && podman image exists "$PF_TAG-worker:test"; then
        say "images: as built for the same binaries and recipe"
    else
        build_image_pair "$context"
        echo "$stamp" > "$W/images.stamp"
    fi
    check_image_sizes
}
build_image_pair() {
    local context=$1
    rm -f "$W/images.stamp"
    rm -rf "$context" && mkdir -p "$context/deploy"
    bash "$SOURCE/deploy/stage-binaries.sh" "$BUILD" "$context/prebuilt" > /dev/null
    cp "$SOURCE/deploy/Containerfile" "$context/deploy/"
    for target in coordinator worker; do
        say "building $PF_TAG-$target"
        # --network host: the build's apt reaches the mirror through the host's resolver, which a
        # bridge network may not reach (a resolver on a host-only address).
        podman build --runtime runc --network host --format docker -q -f "$context/deploy/Containerfile" --target "$target" \
            --build-arg BASE="$PF_BASE" --build-arg BINARIES=prebuilt -t "$PF_TAG-$target:test" "$context" > /dev/null
    done
}
check_image_sizes() {
    # Every node of a scaling cluster pulls the worker image: it carries no scene parser and
    # no image library, and stays within 300 MB (issue 22).
    local base_bytes worker_bytes coordinator_bytes
    base_bytes=$(podman image inspect --format '{{.Size}}' "$PF_BASE")
    worker_bytes=$(podman image inspect --format '{{.Size}}' "$PF_TAG-worker:test")
    coordinator_bytes=$(podman image inspect --format '{{.Size}}' "$PF_TAG-coordinator:test")
    say "images: worker $((worker_bytes / 1000000)) MB, coordinator $((coordinator_bytes / 1000000)) MB, base $((base_bytes / 1000000)) MB"
    if [ "$worker_bytes" -gt 300000000 ]; then
        echo "FAIL: the worker image is $((worker_bytes / 1000000)) MB, over 300 MB" >&2
        return 1
    fi
}
