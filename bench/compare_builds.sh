#!/usr/bin/env bash
# What a change costs scenes that do not use it: bench/photon_bench of two builds (say, one of
# the commit before a feature and this one), run in turns on the same machine, and the ratio
# of their photon-pass rates per scene (new / old; 1.00 is no cost). Each build's rate is its
# best of ROUNDS runs, so a noisy neighbour hurts both alike.
#
#   bench/compare_builds.sh OLD_BUILD NEW_BUILD [ROUNDS]
#
# OLD_BUILD and NEW_BUILD are build folders (with bench/photon_bench). A build of an older
# commit: git worktree add /tmp/old COMMIT && cmake -S /tmp/old -B /tmp/old/build -G Ninja
# -DCMAKE_BUILD_TYPE=Release && cmake --build /tmp/old/build --target photon_bench.
set -euo pipefail
if [ $# -lt 2 ]; then
    echo "usage: $0 OLD_BUILD NEW_BUILD [ROUNDS]" >&2
    exit 2
fi
old="$1/bench/photon_bench" new="$2/bench/photon_bench" rounds="${3:-3}"
for binary in "$old" "$new"; do
    [ -x "$binary" ] || { echo "$0: $binary: no photon_bench there (build it first)" >&2; exit 1; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
filter='BM_PhotonPass/'
for round in $(seq "$rounds"); do
    for which in old new; do
        binary=$old
        [ "$which" = new ] && binary=$new
        "$binary" --benchmark_filter="$filter" --benchmark_format=csv 2>/dev/null |
            sed -n '/^name,/,/^$/p' >"$work/$which.$round.csv" || {
            echo "$0: $binary failed" >&2
            exit 1
        }
    done
done
# The benchmark's "segments/s" counter: photon segments traced per second.
python3 - "$work" "$rounds" <<'EOF'
import csv, glob, sys
work, rounds = sys.argv[1], int(sys.argv[2])
def best(which):
    rates = {}
    for path in glob.glob(f"{work}/{which}.*.csv"):
        for row in csv.DictReader(line for line in open(path) if line.strip()):
            if not row["name"].startswith("BM_PhotonPass/"):
                continue
            name = row["name"].split("/")[1]
            rates[name] = max(rates.get(name, 0.0), float(row["segments/s"]))
    return rates
old, new = best("old"), best("new")
print(f"{'scene':<16}{'old seg/s':>14}{'new seg/s':>14}{'new/old':>10}")
for scene in sorted(old):
    if scene in new:
        print(f"{scene:<16}{old[scene]:>14.0f}{new[scene]:>14.0f}{new[scene] / old[scene]:>10.3f}")
EOF
