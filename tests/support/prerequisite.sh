# Sourced by the shell tests that need a tool from outside the project (podman, clang, ...).
# skip_for_want_of REASON...: outside CI the test is skipped (exit 77, CTest's skip code) with
# its reason printed; under CI=true, as CI runs .ci/run, the missing prerequisite is a broken
# machine and the test fails (exit 1) naming what is missing.
skip_for_want_of() {
    if [ "${CI:-}" = true ]; then
        echo "FAILED: $* (CI=true: a prerequisite a test would skip for must be present)" >&2
        exit 1
    fi
    echo "SKIPPED: $*"
    exit 77
}
