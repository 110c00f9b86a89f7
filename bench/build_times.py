#!/usr/bin/env python3
"""Where a build's time went, from its folder's .ninja_log.

    bench/build_times.py BUILD_DIR [--top N]

Prints the slowest steps, the time per kind of step (compiles, links, glslc, protoc) and per
target, the sum of the steps against the build's wall time, and the stretches where fewer
steps ran than the build had jobs (ninja -j), with what ran then: what gates the end of a
build. Read a fresh build's log (a folder built once, from empty, e.g. with CCACHE_DISABLE=1):
ninja keeps only each output's latest step, so an incremental build shows only what it redid.
Times are wall-clock milliseconds as ninja logged them; on a shared machine compare ratios.
"""

import argparse
import collections
import os
import re
import sys


def read_steps(build_dir):
    """The steps of the log's latest build: one per command (outputs of one command merged)."""
    path = os.path.join(build_dir, ".ninja_log")
    with open(path, encoding="utf-8") as log:
        header = log.readline()
        if not header.startswith("# ninja log v"):
            sys.exit(f"{path}: not a ninja log")
        latest = {}
        for line in log:
            fields = line.rstrip("\n").split("\t")
            if len(fields) != 5:
                continue
            start, end, _, output, command_hash = fields
            latest[output] = (int(start), int(end), command_hash)
    # One command with several outputs (protoc, glslc's output under two names) is one step.
    steps = {}
    for output, (start, end, command_hash) in latest.items():
        key = (start, end, command_hash)
        if key not in steps or len(output) < len(steps[key]):
            steps[key] = output
    return sorted((start, end, output) for (start, end, _), output in steps.items())


def relative(output, build_dir):
    prefix = os.path.abspath(build_dir) + os.sep
    return output[len(prefix):] if output.startswith(prefix) else output


def classify(output):
    """(kind, target) of a step from its output's path."""
    if output.endswith(".spv.inc"):
        return "glslc", "shaders"
    if re.search(r"\.(pb|grpc\.pb)\.(cc|h)$", output):
        return "protoc", "proto"
    match = re.search(r"(?:^|/)CMakeFiles/([^/]+)\.dir/(.*)$", output)
    if match:
        target, rest = match.groups()
        if rest.endswith((".gch", ".pch")):
            return "precompiled header", target
        if rest.endswith(".o"):
            generated = "pb.cc" in rest
            return ("compile (generated proto)" if generated else "compile"), target
        return "other", target
    if output.endswith(".a"):
        return "archive", os.path.basename(output)[3:-2]
    if output.startswith("embedded/") or "/embedded/" in output:
        return "embed", "embedded"
    if "." not in os.path.basename(output) or output.endswith(".so"):
        return "link", os.path.basename(output)
    return "other", output


def under_parallel(steps, jobs):
    """Stretches (ms) during which fewer than `jobs` steps ran, and the steps running then."""
    events = sorted([(s, 1, o) for s, _, o in steps] + [(e, -1, o) for _, e, o in steps])
    running, stretches, last = set(), [], None
    for time, delta, output in events:
        if last is not None and time > last and 0 < len(running) < jobs:
            stretches.append((last, time, tuple(sorted(running))))
        last = time
        (running.add if delta > 0 else running.discard)(output)
    merged = collections.defaultdict(int)
    for start, end, running_now in stretches:
        for output in running_now:
            merged[output] += end - start
    total = sum(end - start for start, end, _ in stretches)
    return total, merged


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("build_dir")
    parser.add_argument("--top", type=int, default=25, help="slowest steps to list")
    parser.add_argument("--jobs", type=int, default=2, help="the build's -j (default 2)")
    args = parser.parse_args()
    steps = [(s, e, relative(o, args.build_dir)) for s, e, o in read_steps(args.build_dir)]
    if not steps:
        sys.exit("no steps in the log")

    def seconds(ms):
        return f"{ms / 1000:8.1f}"

    total = sum(e - s for s, e, _ in steps)
    wall = max(e for _, e, _ in steps) - min(s for s, _, _ in steps)
    print(f"{len(steps)} steps; sum of steps {total / 1000:.1f} s; wall {wall / 1000:.1f} s; "
          f"mean parallelism {total / wall:.2f}")

    print(f"\nslowest {args.top} steps (s, start s, output):")
    for s, e, output in sorted(steps, key=lambda step: step[0] - step[1])[: args.top]:
        print(f"{seconds(e - s)} {seconds(s)}  {output}")

    by_kind, by_target = collections.Counter(), collections.Counter()
    count_kind, count_target = collections.Counter(), collections.Counter()
    for s, e, output in steps:
        kind, target = classify(output)
        by_kind[kind] += e - s
        count_kind[kind] += 1
        by_target[target] += e - s
        count_target[target] += 1
    print("\nby kind (s, share, steps):")
    for kind, ms in by_kind.most_common():
        print(f"{seconds(ms)} {100 * ms / total:5.1f}% {count_kind[kind]:4d}  {kind}")
    print(f"\nby target, slowest {args.top} (s, share, steps; compiles and its link or archive):")
    for target, ms in by_target.most_common(args.top):
        print(f"{seconds(ms)} {100 * ms / total:5.1f}% {count_target[target]:4d}  {target}")

    starved, culprits = under_parallel(steps, args.jobs)
    print(f"\n{starved / 1000:.1f} s of the wall time ran fewer than {args.jobs} steps; "
          "the steps running then (s):")
    for output, ms in sorted(culprits.items(), key=lambda item: -item[1])[:10]:
        print(f"{seconds(ms)}  {output}")


if __name__ == "__main__":
    main()
