#!/usr/bin/env bash
# A test that would skip for want of a prerequisite (Vulkan, podman, clang, clang-format)
# skips outside CI with its reason printed, and fails under CI=true naming what is missing:
# checked for the GoogleTest side (a Vulkan test run with no Vulkan driver) and the shell side
# (tests/support/prerequisite.sh, which the container, fuzzer and format tests source).
# Usage: prerequisites_test.sh VULKAN_TEST_BINARY SOURCE_DIR
set -u
binary=$1
source_dir=$2
failures=0
check() {  # check NAME EXPECTED_CODE PATTERN OUTPUT_FILE ACTUAL_CODE
    if [ "$5" -eq "$2" ] && grep -q -- "$3" "$4"; then
        echo "ok   $1 (exit $5)"
    else
        echo "FAIL $1: exit $5 (wanted $2), output:"
        tail -20 "$4"
        failures=$((failures + 1))
    fi
}
out=$(mktemp)
trap 'rm -f "$out"' EXIT

# The first Vulkan test case of the binary, run with no driver at all.
test_case=$("$binary" --gtest_list_tests | awk '/^[^ ]/{suite=$1} /^  /{print suite $1; exit}')
[ -n "$test_case" ] || { echo "FAIL: $binary lists no tests"; exit 1; }
env -u CI VK_ICD_FILENAMES=/nonexistent/icd.json "$binary" --gtest_filter="$test_case" >"$out" 2>&1
check "no Vulkan outside CI: $test_case skips" 0 "SKIPPED" "$out" $?
grep -q "no Vulkan" "$out" || { echo "FAIL the skip does not say why"; failures=$((failures + 1)); }
CI=true VK_ICD_FILENAMES=/nonexistent/icd.json "$binary" --gtest_filter="$test_case" >"$out" 2>&1
check "no Vulkan under CI=true: $test_case fails" 1 "CI=true requires Vulkan" "$out" $?

(env -u CI bash -c "source '$source_dir/tests/support/prerequisite.sh'; skip_for_want_of 'podman is not installed'") >"$out" 2>&1
check "shell prerequisite outside CI skips (77)" 77 "SKIPPED: podman is not installed" "$out" $?
(CI=true bash -c "source '$source_dir/tests/support/prerequisite.sh'; skip_for_want_of 'podman is not installed'") >"$out" 2>&1
check "shell prerequisite under CI=true fails" 1 "FAILED: podman is not installed" "$out" $?

[ "$failures" -eq 0 ] && echo "prerequisites: all checks passed" || { echo "prerequisites: $failures checks failed"; exit 1; }
