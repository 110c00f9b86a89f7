#!/usr/bin/env python3
"""Prints what the last CTest run skipped and why, from its JUnit file (ctest --output-junit).

A skip passes CTest, so `make test` ends with this summary: the reason is the line a shell test
printed after "SKIPPED:", or the message GoogleTest printed after "Skipped" (GTEST_SKIP).
Usage: skip_summary.py JUNIT_XML
"""
import sys
import xml.etree.ElementTree as ElementTree


def skip_reason(output: str) -> str | None:
    """The reason a test's output gives for its skip, or None if it did not skip."""
    lines = output.splitlines()
    for line in lines:
        if line.startswith("SKIPPED: "):
            return line[len("SKIPPED: "):]
    for index, line in enumerate(lines):
        # GoogleTest: "file:line: Skipped" then the message, then "[  SKIPPED ] Case".
        if line.endswith(": Skipped"):
            message = []
            for following in lines[index + 1:]:
                if following.startswith("[  SKIPPED ]"):
                    break
                message.append(following.strip())
            return " ".join(part for part in message if part) or "(no reason given)"
    if any(line.startswith("[  SKIPPED ]") for line in lines):
        return "(no reason given)"
    return None


def main() -> int:
    if len(sys.argv) != 2:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    try:
        root = ElementTree.parse(sys.argv[1]).getroot()
    except (OSError, ElementTree.ParseError) as error:
        print(f"skip summary: cannot read {sys.argv[1]}: {error}", file=sys.stderr)
        return 1
    skipped = []
    for case in root.iter("testcase"):
        output = case.findtext("system-out") or ""
        reason = skip_reason(output)
        if reason is None and case.find("skipped") is not None:
            reason = case.find("skipped").get("message", "(no reason given)")
        if reason is not None:
            skipped.append((case.get("name"), reason))
    total = len(list(root.iter("testcase")))
    if not skipped:
        print(f"skip summary: none of the {total} tests was skipped")
        return 0
    print(f"skip summary: {len(skipped)} of {total} tests were SKIPPED (they would fail under CI=true):")
    for name, reason in skipped:
        print(f"  {name}: {reason}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
