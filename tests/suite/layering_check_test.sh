#!/usr/bin/env bash
# Self-test of tests/suite/layering_check.py on a tiny fake tree: an allowed include passes, a
# forbidden one and a file in an unlisted room fail, a cycle in the rules is reported, a missing
# SOURCE_DIR is a usage error, and --dot prints the room graph.
# Usage: layering_check_test.sh SOURCE_DIR
set -u
checker="${1:?usage: layering_check_test.sh SOURCE_DIR}/tests/suite/layering_check.py"
failures=0
check() {  # check NAME EXPECTED_CODE PATTERN ACTUAL_CODE: the output ($out) must match PATTERN
    if [ "$4" -eq "$2" ] && grep -q -- "$3" "$out"; then
        echo "ok   $1 (exit $4)"
    else
        echo "FAIL $1: exit $4 (wanted $2, output matching '$3'), output:"
        cat "$out"
        failures=$((failures + 1))
    fi
}
tree=$(mktemp -d)
trap 'rm -rf "$tree"' EXIT
out="$tree/out"

mkdir -p "$tree/src/lo" "$tree/src/hi" "$tree/src/build"
printf 'lo:\nhi: lo  # hi sits on lo\n' >"$tree/rules.txt"
printf 'lo: hi\nhi: lo\n' >"$tree/cycle.txt"
printf '#pragma once\n#include <vector>\n' >"$tree/src/lo/a.h"
printf '#include "lo/a.h"\n#include "hi/b.h"\n' >"$tree/src/hi/b.cpp"
printf '#include "hi/b.h"\n' >"$tree/src/build/ignored.h"

python3 "$checker" --rules "$tree/rules.txt" "$tree/src" >"$out" 2>&1
check "allowed includes only" 0 "^layering: clean; 2 files" $?

printf '#pragma once\n\n#include "hi/b.h"\n' >"$tree/src/lo/c.h"
mkdir "$tree/src/stray" && printf '\n' >"$tree/src/stray/d.cpp"
python3 "$checker" --rules "$tree/rules.txt" "$tree/src" >"$out" 2>&1
code=$?
check "forbidden include" 1 "^lo/c.h:3 includes hi/b.h: lo may not include hi (allowed: none)$" $code
check "unlisted room" 1 "^stray/d.cpp: unlisted room stray/" $code
check "summary line" 1 "^layering: 2 violation(s) in 2 file(s)" $code
grep -q "hi/b.cpp\|ignored" "$out" && { echo "FAIL allowed or build/ include reported"; failures=$((failures + 1)); }

python3 "$checker" --rules "$tree/cycle.txt" "$tree/src/lo" >"$out" 2>&1
check "cycle in the rules" 1 "cycle.txt: the room graph has a cycle: lo -> hi -> lo" $?

python3 "$checker" --rules "$tree/rules.txt" "$tree/missing" >"$out" 2>&1
check "missing SOURCE_DIR" 2 "^layering_check: SOURCE_DIR .*missing is not a directory" $?
[ "$(wc -l <"$out")" -eq 1 ] || { echo "FAIL the usage error is not one line"; failures=$((failures + 1)); }

python3 "$checker" --rules "$tree/rules.txt" --dot >"$out" 2>&1
check "--dot" 0 '"hi" -> "lo";' $?

[ "$failures" -eq 0 ] && echo "layering_check: all self-tests passed" || echo "$failures failure(s)"
[ "$failures" -eq 0 ]
