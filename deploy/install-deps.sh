#!/usr/bin/env bash
# Installs the Debian 12 packages photonfarm builds, tests and runs with.
# Idempotent: when every package is already present it returns in well under a second.
set -euo pipefail

packages=(
    build-essential cmake ninja-build pkg-config git python3 openssl
    libgrpc++-dev protobuf-compiler-grpc libprotobuf-dev protobuf-compiler libssl-dev prometheus-cpp-dev
    libembree-dev libtbb-dev
    libopenimageio-dev openimageio-tools libopenexr-dev
    libspdlog-dev libgtest-dev libgmock-dev libbenchmark-dev
    libvulkan-dev glslc mesa-vulkan-drivers vulkan-validationlayers
    libzstd-dev zlib1g-dev nlohmann-json3-dev libcli11-dev libtinygltf-dev libstb-dev libdraco-dev libmeshoptimizer-dev
    libcpp-httplib-dev
    chromium chromium-driver python3-selenium
    gnuplot-nox fonts-dejavu-core
    clang libclang-rt-14-dev clang-format
    podman runc netavark aardvark-dns debootstrap catatonit docker-compose
)

missing=()
for package in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "ok installed"; then
        missing+=("$package")
    fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -ne 0 ]; then
    echo "install-deps: missing packages (${missing[*]}); run as root or install them with apt-get" >&2
    exit 1
fi
echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
# --force-unsafe-io: dpkg skips its fsync per unpacked file (as Debian's container images do),
# which is most of an install's time on a slow disk; a machine that loses power mid-install
# reinstalls.
apt-get install -y -qq --no-install-recommends -o Dpkg::Options::=--force-unsafe-io \
    "${missing[@]}" >/dev/null
echo "install-deps: done"
