#!/usr/bin/env bash
# How long deploy/install-deps.sh takes on a fresh Debian 12 machine, and what it installs: a
# minimal bookworm made with debootstrap (the mirror apt uses here), with git and make as a user
# would have them to clone and run `make`, then install-deps.sh inside it (chroot). Prints the
# seconds, the packages install-deps asked for, the packages apt installed in all (with their
# dependencies) and the size they occupy. Needs root, debootstrap and the network; removes the
# tree it made.
# Usage: bench/setup_time.sh [WORK_DIR]
set -euo pipefail
source_dir=$(cd "$(dirname "$0")/.." && pwd)
work=${1:-$(mktemp -d)}
mkdir -p "$work"
root=$work/rootfs
[ "$(id -u)" -eq 0 ] || { echo "setup_time: run as root (debootstrap, chroot)" >&2; exit 1; }
command -v debootstrap > /dev/null || { echo "setup_time: debootstrap is not installed" >&2; exit 1; }
mirror=$(awk '/^URIs:/{print $2; exit}' /etc/apt/sources.list.d/debian.sources 2> /dev/null || true)
[ -n "$mirror" ] || mirror=http://deb.debian.org/debian
cleanup() {
    set +e
    for mount in dev/pts dev proc sys; do umount "$root/$mount" 2> /dev/null; done
    rm -rf "$root"
}
trap cleanup EXIT

echo "setup_time: debootstrap bookworm (minbase, with git and make) from $mirror"
debootstrap --variant=minbase --include=git,make,ca-certificates bookworm "$root" "$mirror" \
    > "$work/debootstrap.log" 2>&1 || { tail -5 "$work/debootstrap.log"; exit 1; }
echo "deb $mirror bookworm main" > "$root/etc/apt/sources.list"
echo "deb $mirror bookworm-updates main" >> "$root/etc/apt/sources.list"
cp /etc/resolv.conf "$root/etc/resolv.conf"
mount -t proc proc "$root/proc" && mount --bind /dev "$root/dev" && mount --bind /dev/pts "$root/dev/pts"
mount -t sysfs sysfs "$root/sys"
# Services are not started inside the chroot (as on a machine whose init would start them).
printf '#!/bin/sh\nexit 101\n' > "$root/usr/sbin/policy-rc.d" && chmod +x "$root/usr/sbin/policy-rc.d"
mkdir -p "$root/src/deploy"
cp "$source_dir/deploy/install-deps.sh" "$root/src/deploy/"
before=$(chroot "$root" dpkg-query -W -f='${Package}\n' | wc -l)
used_before=$(du -sm --exclude=proc --exclude=sys --exclude=dev "$root" | cut -f1)
start=$(date +%s.%N)
chroot "$root" bash /src/deploy/install-deps.sh | tee "$work/install-deps.log"
end=$(date +%s.%N)
after=$(chroot "$root" dpkg-query -W -f='${Package}\n' | wc -l)
used_after=$(du -sm --exclude=proc --exclude=sys --exclude=dev "$root" | cut -f1)
asked=$(grep -o 'installing [0-9]* packages' "$work/install-deps.log" | grep -o '[0-9]*' || echo 0)
printf 'setup_time: install-deps.sh took %.0f s: %s packages asked for, %d installed with their dependencies, %d MB on disk\n' \
    "$(echo "$end - $start" | bc)" "$asked" $((after - before)) $((used_after - used_before))
