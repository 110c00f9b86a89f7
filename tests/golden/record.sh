#!/usr/bin/env bash
# Records the golden images (tests/golden/cpu_images.txt): every shipped scene with every
# integrator on the CPU backend, as rendered by the commit REV, for integration_golden_test to
# compare the working tree's renders with bit for bit. Record from the commit before a change
# that must not alter any image; record again, naming the commit, after one that means to.
#
#   tests/golden/record.sh [--commit REV] [--images DIR]
#     --commit REV  the commit to render with (default HEAD); built in a worktree under
#                   build/golden/ (ccache makes a second build quick), the checkout untouched
#     --images DIR  also write each render as DIR/SCENE-INTEGRATOR.exr, and leave the manifest
#                   as it is: run it for two commits into two folders to see what differs
set -euo pipefail

usage() { echo "usage: $0 [--commit REV] [--images DIR]" >&2; exit 2; }
rev=HEAD images=
while [[ $# -gt 0 ]]; do
    case "$1" in
        --commit) [[ $# -ge 2 ]] || usage; rev=$2; shift 2 ;;
        --images) [[ $# -ge 2 ]] || usage; images=$(realpath -m "$2"); shift 2 ;;
        *) usage ;;
    esac
done

root=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
commit=$(git -C "$root" rev-parse --verify "$rev^{commit}") ||
    { echo "$0: $rev is not a commit of $root" >&2; exit 1; }
git -C "$root" cat-file -e "$commit:tests/integration/golden_images_test.cpp" 2>/dev/null ||
    { echo "$0: $rev has no tests/integration/golden_images_test.cpp to record with" >&2; exit 1; }

work="$root/build/golden"
tree="$work/src-${commit:0:12}"
mkdir -p "$work"
if [[ ! -d "$tree" ]]; then
    git -C "$root" worktree prune  # a tree removed with build/ is forgotten
    git -C "$root" worktree add --quiet --detach "$tree" "$commit"
fi
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
log="$tree/build.log"
echo "building ${commit:0:12}'s integration_golden_test in $tree (log: $log)"
if ! { cmake -S "$tree" -B "$tree/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPF_BUILD_BENCH=OFF \
           "${launcher[@]}" &&
       cmake --build "$tree/build" --target integration_golden_test -- -j"$(nproc)"; } >"$log" 2>&1; then
    tail -n 20 "$log" >&2
    echo "$0: building ${commit:0:12} failed (the whole log: $log)" >&2
    exit 1
fi

out=$(mktemp)
trap 'rm -f "$out"' EXIT
if [[ -n "$images" ]]; then
    mkdir -p "$images"
    export PF_GOLDEN_IMAGES="$images"
fi
# The tree's own scenes (a commit renders what it shipped), recorded one process for all.
if ! PF_GOLDEN_RECORD="$out" "$tree/build/tests/integration_golden_test" \
        --gtest_filter='Shipped/GoldenImages.*' >"$tree/record.log" 2>&1; then
    grep -A4 'Failure' "$tree/record.log" >&2 || tail -n 20 "$tree/record.log" >&2
    echo "$0: ${commit:0:12} did not render every scene (the whole log: $tree/record.log)" >&2
    exit 1
fi
if [[ -n "$images" ]]; then
    echo "$(wc -l <"$out") renders of ${commit:0:12} in $images"
    exit 0
fi
manifest="$root/tests/golden/cpu_images.txt"
{
    echo "# recorded from commit ${commit:0:12} ($(git -C "$root" log -1 --format=%s "$commit"))"
    echo "# by tests/golden/record.sh; scene, integrator, SHA-256 of the pixels (golden_images_test.cpp)"
    sort "$out"
} >"$manifest"
echo "$(grep -vc '^#' "$manifest") digests of ${commit:0:12} in $manifest"
