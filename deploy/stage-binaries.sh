#!/usr/bin/env bash
# Copies photonfarm's three programs from a build folder into DEST/bin and writes
# DEST/runtime-packages.txt: the Debian packages holding the shared libraries they load, which
# is what a container image installs to run them (deploy/Containerfile).
# Usage: deploy/stage-binaries.sh BUILD_DIR DEST
set -euo pipefail
build=$1 dest=$2
programs=("$build/server/photonfarm-coordinator" "$build/worker/photonfarm-worker" "$build/client/photonfarm")
mkdir -p "$dest/bin"
for program in "${programs[@]}"; do
    [ -x "$program" ] || { echo "stage-binaries: $program is missing; build it first" >&2; exit 1; }
    install -m 0755 "$program" "$dest/bin/"
done
strip --strip-unneeded "$dest"/bin/* 2>/dev/null || true
# Every library ldd resolves, mapped to its package (dpkg -S answers "package:arch: /path").
ldd "${programs[@]}" | awk '/=> \//{print $3}' | sort -u | while read -r library; do
    dpkg -S "$(readlink -f "$library")" 2>/dev/null || dpkg -S "$library" 2>/dev/null || true
done | cut -d: -f1 | sort -u | grep -v -E '^(libc6|libgcc-s1|libstdc\+\+6)$' > "$dest/runtime-packages.txt"
echo "stage-binaries: $(wc -l < "$dest/runtime-packages.txt") runtime packages for ${#programs[@]} programs in $dest"
