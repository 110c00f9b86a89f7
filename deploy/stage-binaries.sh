#!/usr/bin/env bash
# Copies photonfarm's three programs from a build folder into DEST/bin, the image module they
# load at their first image (core/CMakeLists.txt) into DEST/lib, and writes
# DEST/runtime-packages-{coordinator,worker}.txt: the Debian packages holding the shared
# libraries each image's programs load, which is what that image installs to run them
# (deploy/Containerfile).
# Usage: deploy/stage-binaries.sh BUILD_DIR DEST
set -euo pipefail
build=$1 dest=$2
programs=("$build/server/photonfarm-coordinator" "$build/worker/photonfarm-worker" "$build/client/photonfarm")
mkdir -p "$dest/bin"
for program in "${programs[@]}"; do
    [ -x "$program" ] || { echo "stage-binaries: $program is missing; build it first" >&2; exit 1; }
    install -m 0755 "$program" "$dest/bin/"
done
# Looked for in lib beside the programs' folder (core/scene/image_decode.cpp).
module="$build/lib/libpf_image_oiio.so"
[ -f "$module" ] || { echo "stage-binaries: $module is missing; build it first" >&2; exit 1; }
mkdir -p "$dest/lib"
install -m 0644 "$module" "$dest/lib/"
strip --strip-unneeded "$dest"/bin/* "$dest"/lib/* 2>/dev/null || true
# The Debian packages holding every library ldd resolves for the programs given, one per line
# (dpkg -S answers "package:arch: /path"); libc and the compiler's runtime come with the base.
packages_for() {
    ldd "$@" | awk '/=> \//{print $3}' | sort -u | while read -r library; do
        dpkg -S "$(readlink -f "$library")" 2>/dev/null || dpkg -S "$library" 2>/dev/null || true
    done | cut -d: -f1 | sort -u | grep -v -E '^(libc6|libgcc-s1|libstdc\+\+6)$'
}
# One list per image: the worker's holds no scene parser and no image library. The module
# is not linked, so ldd looks at it too: the coordinator's image gets OpenImageIO's packages.
packages_for "$dest/bin/photonfarm-coordinator" "$dest/bin/photonfarm" "$dest/lib/libpf_image_oiio.so" \
    > "$dest/runtime-packages-coordinator.txt"
packages_for "$dest/bin/photonfarm-worker" > "$dest/runtime-packages-worker.txt"
echo "stage-binaries: $(wc -l < "$dest/runtime-packages-coordinator.txt") runtime packages for the" \
    "coordinator image, $(wc -l < "$dest/runtime-packages-worker.txt") for the worker's, in $dest"
