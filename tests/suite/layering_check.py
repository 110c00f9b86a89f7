#!/usr/bin/env python3
"""Fails when a source file includes across a forbidden edge between the rooms of the tree.

The rooms (folders) and which rooms each may include are in layering.txt beside this script;
its header explains the format. Checked: every #include in *.h, *.hpp, *.cpp, *.cc, *.comp and
*.glsl that is rooted at the repo ("core/ppm/batch.h") or names generated protobuf/gRPC code
(room proto); every such file lies in a listed room; the room graph has no cycle.
Usage: layering_check.py [--rules FILE] SOURCE_DIR   exit 0 clean, 1 violations, 2 bad usage
       layering_check.py [--rules FILE] --dot        prints the room graph as Graphviz
"""
import argparse
import fnmatch
import os
import re
import sys

DEFAULT_RULES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "layering.txt")
SOURCE_SUFFIXES = (".h", ".hpp", ".cpp", ".cc", ".comp", ".glsl")
SKIPPED_DIRS = {"build", "out", "third_party", "third-party"}  # and hidden dirs, CMake build trees
PROTO = "proto"
PROTO_PREFIXES = ("proto/", "photonfarm/", "grpc/", "grpcpp/")
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


class UsageError(Exception):
    pass


def load_rules(path):
    """{room: (allowed rooms, or None for anything; the dependencies as written)}."""
    try:
        with open(path, encoding="utf-8") as rules_file:
            lines = rules_file.read().splitlines()
    except OSError as error:
        raise UsageError(f"cannot read rules file {path}: {error.strerror}")
    written = {}
    for number, line in enumerate(lines, 1):
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        room, colon, deps = line.partition(":")
        room = room.strip().rstrip("/")
        if not colon or not room or room in written:
            raise UsageError(f"{path}:{number}: expected 'ROOM: ROOMS IT MAY INCLUDE' "
                             f"naming a new room, got {line!r}")
        written[room] = (number, deps.replace(",", " ").split())
    rules = {}
    for room, (number, deps) in written.items():
        allowed = None if "*" in deps else []
        for dep in deps if allowed is not None else []:
            matched = [other for other in written if fnmatch.fnmatchcase(other, dep.rstrip("/"))]
            if not matched:
                raise UsageError(f"{path}:{number}: {room} may include {dep!r}, which is no room")
            allowed += [other for other in matched if other != room and other not in allowed]
        rules[room] = (allowed, ", ".join(deps) or "none")
    return rules


def room_of(path, rules):
    """The longest listed room that prefixes path, or None."""
    matches = [room for room in rules if path == room or path.startswith(room + "/")]
    return max(matches, key=len, default=None)


def edges(rules):
    """{room: rooms it may include}; a '*' room may include every room that is not '*'."""
    ordinary = [room for room, (allowed, _) in rules.items() if allowed is not None]
    return {room: [other for other in ordinary if other != room] if allowed is None else allowed
            for room, (allowed, _) in rules.items()}


def find_cycle(graph):
    """A list of rooms forming a cycle (first room repeated at the end), or None."""
    state, stack = {}, []

    def visit(room):
        state[room] = "open"
        stack.append(room)
        for other in graph[room]:
            if state.get(other) == "open":
                return stack[stack.index(other):] + [other]
            if other not in state and (cycle := visit(other)):
                return cycle
        state[room] = "done"
        stack.pop()
        return None

    for room in graph:
        if room not in state and (cycle := visit(room)):
            return cycle
    return None


def print_dot(rules):
    """The room graph as Graphviz, transitively reduced: an edge implied by a path is left out."""
    graph = edges(rules)

    def reachable(start, skip_edge):
        seen, todo = set(), [start]
        while todo:
            room = todo.pop()
            for other in graph[room]:
                if other not in seen and (room, other) != skip_edge:
                    seen.add(other)
                    todo.append(other)
        return seen

    print("digraph layering {\n  rankdir=BT;\n  node [shape=box];")
    for room, (allowed, _) in rules.items():
        label = f' [label="{room}\\n(may include anything)"]' if allowed is None else ""
        print(f'  "{room}"{label};')
    for room, (allowed, _) in rules.items():
        for other in allowed or []:
            if other not in reachable(room, (room, other)):
                print(f'  "{room}" -> "{other}";')
    print("}")


def included_room(bracket, name, including_file, source_dir, rules):
    """(room, path) an include counts against, or (None, path) for one the check ignores."""
    if name.endswith(".pb.h") or name.startswith(PROTO_PREFIXES):
        return PROTO, name
    if bracket == "<":
        return None, name  # the standard library and third-party code
    if name.startswith("."):
        name = os.path.normpath(os.path.join(os.path.dirname(including_file), name))
    top_folders = {room.split("/")[0] for room in rules}
    if name.split("/")[0] in top_folders or os.path.isfile(os.path.join(source_dir, name)):
        return room_of(name, rules) or "", name  # "": rooted at the repo, but in no room
    return None, name  # a sibling ("common.glsl") or third-party header ("absl/...")


def source_files(source_dir):
    for folder, subfolders, files in os.walk(source_dir):
        subfolders[:] = sorted(name for name in subfolders
                               if not name.startswith((".", "build-")) and name not in SKIPPED_DIRS
                               and not os.path.exists(os.path.join(folder, name, "CMakeCache.txt")))
        for name in sorted(files):
            if name.endswith(SOURCE_SUFFIXES):
                yield os.path.relpath(os.path.join(folder, name), source_dir).replace(os.sep, "/")


def check(source_dir, rules, rules_name):
    """The violations, one message each, and how many files were scanned."""
    violations, scanned = [], 0
    if cycle := find_cycle(edges(rules)):
        violations.append(f"{rules_name}: the room graph has a cycle: {' -> '.join(cycle)}")
    for path in source_files(source_dir):
        scanned += 1
        room = room_of(path, rules)
        if room is None:
            violations.append(f"{path}: unlisted room {os.path.dirname(path) or '.'}/ "
                              f"(place it in {rules_name})")
            continue
        allowed, written = rules[room]
        if allowed is None:
            continue
        with open(os.path.join(source_dir, path), encoding="utf-8", errors="replace") as source:
            for number, line in enumerate(source, 1):
                if not (match := INCLUDE.match(line)):
                    continue
                target, name = included_room(*match.groups(), path, source_dir, rules)
                if target is None or target == room or target in allowed:
                    continue
                reason = (f"{room} may not include {target}" if target
                          else f"{name} is in no room listed in {rules_name}")
                violations.append(f"{path}:{number} includes {name}: {reason} (allowed: {written})")
    return violations, scanned


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("source_dir", nargs="?", metavar="SOURCE_DIR")
    parser.add_argument("--rules", default=DEFAULT_RULES, help="rules file (default: %(default)s)")
    parser.add_argument("--dot", action="store_true", help="print the room graph as Graphviz")

    def usage_error(message):
        print(f"layering_check: {message} (usage: layering_check.py [--rules FILE] [--dot] "
              f"SOURCE_DIR)", file=sys.stderr)
        sys.exit(2)

    parser.error = usage_error
    args = parser.parse_args()
    try:
        rules = load_rules(args.rules)
    except UsageError as error:
        usage_error(error)
    if args.dot:
        print_dot(rules)
        return 0
    if args.source_dir is None:
        usage_error("no SOURCE_DIR given")
    if not os.path.isdir(args.source_dir):
        usage_error(f"SOURCE_DIR {args.source_dir} is not a directory")
    rules_name = os.path.basename(args.rules)
    violations, scanned = check(args.source_dir, rules, rules_name)
    for violation in violations:
        print(violation)
    if violations:
        files = len({violation.split(":")[0] for violation in violations})
        print(f"layering: {len(violations)} violation(s) in {files} file(s); "
              f"{scanned} files checked against {len(rules)} rooms of {args.rules}")
        return 1
    print(f"layering: clean; {scanned} files checked against {len(rules)} rooms of {args.rules}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
