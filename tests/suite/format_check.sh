#!/usr/bin/env bash
# Every C++ source of the repository is formatted as .clang-format says (clang-format from
# Debian, installed by deploy/install-deps.sh): a file that is not fails the test, named with
# the first lines clang-format would change. Fix with: clang-format -i FILE.
# Usage: format_check.sh SOURCE_DIR
set -euo pipefail
source_dir=$(cd "$1" && pwd)
source "$source_dir/tests/support/prerequisite.sh"
command -v clang-format >/dev/null ||
    skip_for_want_of "clang-format is not installed (deploy/install-deps.sh installs it)"
cd "$source_dir"
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    mapfile -t files < <(git ls-files -- '*.cpp' '*.h')
else
    mapfile -t files < <(find . -path ./build -prune -o \( -name '*.cpp' -o -name '*.h' \) -print)
fi
[ ${#files[@]} -gt 0 ] || { echo "format_check: no C++ sources found under $source_dir"; exit 1; }
existing=()
for file in "${files[@]}"; do [ -f "$file" ] && existing+=("$file"); done  # skip deleted ones
if clang-format --dry-run --Werror "${existing[@]}" >/dev/null 2>&1; then
    echo "format_check: all ${#existing[@]} C++ files are formatted"
    exit 0
fi
unformatted=()
for file in "${existing[@]}"; do
    clang-format --dry-run --Werror "$file" >/dev/null 2>&1 || unformatted+=("$file")
done
if [ ${#unformatted[@]} -gt 0 ]; then
    echo "format_check: ${#unformatted[@]} of ${#files[@]} files differ from .clang-format ($(clang-format --version)):"
    for file in "${unformatted[@]}"; do
        echo "  $file: $(clang-format --dry-run "$file" 2>&1 | grep -m1 -o 'warning: .*' || true)"
    done
    echo "format_check: run clang-format -i on them"
fi
exit 1
