#!/usr/bin/env python3
"""The test suite's time: the slowest tests, the total, and each label against its budget.

Reads the JUnit file of a CTest run (`make test` writes BUILD/Testing/junit.xml), the labels of
each test (`ctest --show-only=json-v1`) and the budget per label from the table under
"## Labels" in docs/testing.md (its "budget" column, in test-seconds). A test counts toward its
first label (`integration;vulkan` counts as integration). Prints the run's wall-clock time, the
sum of test times, the slowest tests and one line per label; with --check, exits 1 when a label
is over its budget or the run's wall-clock time is over --wall-budget.

Usage: suite_times.py [BUILD_DIR] [--junit FILE] [--top N] [--check] [--wall-budget SECONDS]
"""
import argparse
import json
import pathlib
import re
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

SOURCE_DIR = pathlib.Path(__file__).resolve().parent.parent


def test_labels(build_dir: pathlib.Path) -> dict[str, str]:
    """Each test's first label, from CTest's JSON description of the suite."""
    listing = subprocess.run(["ctest", "--test-dir", str(build_dir), "--show-only=json-v1"],
                             check=True, capture_output=True, text=True).stdout
    labels = {}
    for test in json.loads(listing)["tests"]:
        first = "(none)"
        for prop in test.get("properties", []):
            if prop["name"] == "LABELS" and prop["value"]:
                first = prop["value"][0]
        labels[test["name"]] = first
    return labels


def label_budgets(testing_md: pathlib.Path) -> dict[str, float]:
    """The budget column of the label table in docs/testing.md: {label: test-seconds}."""
    budgets = {}
    in_labels, budget_column = False, None
    for line in testing_md.read_text().splitlines():
        if line.startswith("## "):
            in_labels = line.strip() == "## Labels"
            continue
        if not in_labels or not line.startswith("|"):
            continue
        cells = [cell.strip() for cell in line.strip().strip("|").split("|")]
        if budget_column is None:
            if "budget" in cells:
                budget_column = cells.index("budget")
            continue
        match = re.match(r"`?([\w.-]+)`?$", cells[0])
        seconds = re.match(r"(\d+(?:\.\d+)?)\s*s\b", cells[budget_column]) if len(cells) > budget_column else None
        if match and seconds:
            budgets[match.group(1)] = float(seconds.group(1))
    return budgets


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("build_dir", nargs="?", default=str(SOURCE_DIR / "build"))
    parser.add_argument("--junit", help="the run's JUnit file (default BUILD/Testing/junit.xml)")
    parser.add_argument("--top", type=int, default=15, help="how many of the slowest to list")
    parser.add_argument("--check", action="store_true", help="exit 1 when over a budget")
    parser.add_argument("--wall-budget", type=float, default=None,
                        help="the run's wall-clock budget in seconds (with --check)")
    args = parser.parse_args()
    build_dir = pathlib.Path(args.build_dir)
    junit = pathlib.Path(args.junit) if args.junit else build_dir / "Testing" / "junit.xml"
    if not junit.is_file():
        print(f"suite_times: {junit} not found: run `make test` (or ctest --output-junit) first",
              file=sys.stderr)
        return 2
    suite = ElementTree.parse(junit).getroot()
    times = {case.get("name"): float(case.get("time", "0")) for case in suite.iter("testcase")}
    statuses = {case.get("name"): case.get("status", "") for case in suite.iter("testcase")}
    labels = test_labels(build_dir)
    budgets = label_budgets(SOURCE_DIR / "docs" / "testing.md")

    total = sum(times.values())
    wall = float(suite.get("time", "0"))
    print(f"{len(times)} tests, {total:.0f} test-seconds, {wall:.0f} s wall-clock "
          f"({total / wall if wall else 0:.2f} tests running on average)")
    print(f"\nthe {min(args.top, len(times))} slowest:")
    for name, seconds in sorted(times.items(), key=lambda item: -item[1])[:args.top]:
        print(f"  {seconds:7.1f} s  {labels.get(name, '?'):12} {name}"
              f"{'' if statuses[name] in ('run', '') else '  (' + statuses[name] + ')'}")

    per_label: dict[str, list[float]] = {}
    for name, seconds in times.items():
        per_label.setdefault(labels.get(name, "(none)"), []).append(seconds)
    over = []
    print(f"\n{'label':12} {'tests':>5} {'seconds':>8} {'budget':>7}")
    for label, values in sorted(per_label.items(), key=lambda item: -sum(item[1])):
        budget = budgets.get(label)
        spent = sum(values)
        flag = ""
        if budget is None:
            flag = "  (no budget in docs/testing.md)"
        elif spent > budget:
            flag = "  OVER"
            over.append(label)
        shown = f"{budget:.0f}" if budget is not None else "-"
        print(f"{label:12} {len(values):5d} {spent:8.0f} {shown:>7}"
              f"{flag}")
    if args.wall_budget is not None and wall > args.wall_budget:
        print(f"\nwall-clock {wall:.0f} s is over its budget of {args.wall_budget:.0f} s")
        over.append("wall-clock")
    return 1 if args.check and over else 0


if __name__ == "__main__":
    sys.exit(main())
