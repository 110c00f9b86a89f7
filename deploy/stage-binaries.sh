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
# Looked for in lib beside the programs' folder (core/scene_io/image_decode.cpp).
module="$build/lib/libpf_image_oiio.so"
[ -f "$module" ] || { echo "stage-binaries: $module is missing; build it first" >&2; exit 1; }
mkdir -p "$dest/lib"
install -m 0644 "$module" "$dest/lib/"
strip --strip-unneeded "$dest"/bin/* "$dest"/lib/* 2>/dev/null || true
# The Debian packages holding every library ldd resolves for the programs given, one per line
# (dpkg -S answers "package[:arch][, package]: /path"); libc and the compiler's runtime come
# with the base. dpkg -S reads its whole database on every call (a second or more), so it is
# asked once for all the libraries' real paths, and once more for those that no package lists
# under their real path (ldd's path then: a package that ships a /lib symlink, say).
packages_for() {
    local -A original=()
    local library
    while read -r library; do
        original[$(readlink -f "$library")]=$library
    done < <(ldd "$@" | awk '/=> \//{print $3}' | sort -u)
    local owners unlisted=()
    owners=$(dpkg -S "${!original[@]}" 2>/dev/null || true)
    local -A listed=()
    while read -r library; do listed[$library]=1; done < <(awk -F': ' 'NF > 1 {print $NF}' <<< "$owners")
    for library in "${!original[@]}"; do
        [ -n "${listed[$library]:-}" ] || unlisted+=("${original[$library]}")
    done
    [ ${#unlisted[@]} -eq 0 ] || owners+=$'\n'$(dpkg -S "${unlisted[@]}" 2>/dev/null || true)
    grep -v '^$' <<< "$owners" | cut -d: -f1 | sort -u | grep -v -E '^(libc6|libgcc-s1|libstdc\+\+6)$'
}
# One list per image: the worker's holds no scene parser and no image library. The module
# is not linked, so ldd looks at it too: the coordinator's image gets OpenImageIO's packages.
packages_for "$dest/bin/photonfarm-coordinator" "$dest/bin/photonfarm" "$dest/lib/libpf_image_oiio.so" \
    > "$dest/runtime-packages-coordinator.txt"
packages_for "$dest/bin/photonfarm-worker" > "$dest/runtime-packages-worker.txt"
echo "stage-binaries: $(wc -l < "$dest/runtime-packages-coordinator.txt") runtime packages for the" \
    "coordinator image, $(wc -l < "$dest/runtime-packages-worker.txt") for the worker's, in $dest"
