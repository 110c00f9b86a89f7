#!/usr/bin/env bash
# Every CTest test of the build carries a TIMEOUT of its own, so a stalled test fails in
# bounded time instead of holding CI until its 90 minutes run out.
# Usage: every_test_has_a_timeout.sh BUILD_DIR
set -euo pipefail
ctest --test-dir "$1" --show-only=json-v1 | python3 -c '
import json, sys
tests = json.load(sys.stdin)["tests"]
missing = []
for test in tests:
    properties = {p["name"]: p["value"] for p in test.get("properties", [])}
    timeout = properties.get("TIMEOUT")
    if timeout is None or not 0 < float(timeout) <= 1800:
        missing.append(test["name"])
if not tests:
    sys.exit("every_test_has_a_timeout: ctest lists no tests")
if missing:
    print(f"{len(missing)} of {len(tests)} tests have no TIMEOUT (or one over 30 minutes):")
    for name in missing[:50]:
        print("  " + name)
    sys.exit(1)
print(f"all {len(tests)} tests have a TIMEOUT")
'
