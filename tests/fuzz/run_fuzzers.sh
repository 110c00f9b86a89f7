#!/usr/bin/env bash
# Builds the scene-parser fuzzers, the gzip decoder's, the spectrum files', the Draco and
# meshopt decoders', the PLY reader's and the prepared-scene decoder's with clang (libFuzzer,
# AddressSanitizer, UBSan) in their own build folder, replays every kept input of each one's
# corpus (tests/fuzz/corpus/<format>/) and then fuzzes each for a fixed time from there.
# Fails if a kept input or a new one finds a crash, a sanitizer error, a leak or a hang (the
# input is left in the build folder).
#
# The kept corpora are regression seeds: the committed hand-written seeds (every input that
# once found a bug among them) and what a long run found past them, each fuzzer grown alone
# for minutes (README in tests/fuzz/corpus/) and minimised with -merge=1 into what adds
# coverage. Replaying them costs a second or two a fuzzer and covers what seconds of fuzzing
# from the bare seeds would not reach; the few seconds of fuzzing after it look past them.
# The prepared_scene seeds are generated here from the shipped scenes (they follow the
# encoding), and its kept inputs are added to them.
#
# Usage: run_fuzzers.sh SOURCE_DIR FUZZ_BUILD_DIR [SECONDS_EACH]
# SECONDS_EACH (the replay included) defaults to 10, what CTest gives; PF_FUZZ_SECONDS overrides
# it for a longer local run: `PF_FUZZ_SECONDS=120 ctest -L fuzz` (within the test's TIMEOUT),
# or the script alone for minutes (PF_FUZZ_SECONDS=600 bash tests/fuzz/run_fuzzers.sh . build/fuzz).
set -euo pipefail
source_dir=$1
build_dir=$2
seconds=${PF_FUZZ_SECONDS:-${3:-10}}
source "$source_dir/tests/support/prerequisite.sh"
command -v clang++ >/dev/null ||
    skip_for_want_of "run_fuzzers: clang++ is not installed (package clang); cannot build the fuzzers"
# Not float-cast-overflow: a double beyond float's range becomes +-inf on every target
# photonfarm builds for, and the loaders check converted values with IsFinite.
flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize=float-cast-overflow -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
# -O1 and line tables only: AddressSanitizer's and UBSan's reports name file and line from line
# tables alone, and -O1 is what AddressSanitizer recommends. Against -O2 -g a source compiles
# in about 12% less CPU time, and the links read a fraction of the debug information.
optimisation="-O1 -gline-tables-only -DNDEBUG"
configuration="$flags | $optimisation"
if [ ! -f "$build_dir/build.ninja" ] || [ "$(cat "$build_dir/pf_fuzz_configuration" 2>/dev/null)" != "$configuration" ]; then
    cmake -S "$source_dir" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
        -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
        -DCMAKE_C_FLAGS_RELWITHDEBINFO="$optimisation" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$optimisation" \
        -DPF_BUILD_TESTS=OFF -DPF_BUILD_BENCH=OFF -DPF_BUILD_FUZZERS=ON >"$build_dir.configure.log" 2>&1 ||
        { cat "$build_dir.configure.log" >&2; exit 1; }
    echo "$configuration" >"$build_dir/pf_fuzz_configuration"
fi
formats=(pbrt gltf gzip spectrum draco meshopt ply prepared_scene)
cmake --build "$build_dir" --target "${formats[@]/%/_fuzzer}" prepared_scene_seeds -- -j "$(nproc)" >"$build_dir.build.log" 2>&1 ||
    { tail -50 "$build_dir.build.log" >&2; exit 1; }
max_len=16384
# A kept input longer than -max_len would be replayed cut short: refuse it.
too_long=$(find "$source_dir/tests/fuzz/corpus" -type f -size +${max_len}c)
if [ -n "$too_long" ]; then
    echo "run_fuzzers: kept inputs over $max_len bytes (-max_len): $too_long" >&2
    exit 1
fi
status=0
for format in "${formats[@]}"; do
    corpus="$build_dir/corpus-$format"
    rm -rf "$corpus" && mkdir -p "$corpus"
    if [ "$format" = prepared_scene ]; then  # seeds made from the shipped scenes
        ASAN_OPTIONS=detect_leaks=0 "$build_dir/tests/fuzz/prepared_scene_seeds" "$corpus" "$source_dir/scenes/cornell-box.gltf" \
            "$source_dir/scenes/pbrt/caustic-glass.pbrt" "$source_dir/scenes/cornell-bumpy.gltf" \
            "$source_dir/scenes/pbrt/cornell-materials.pbrt" "$source_dir/scenes/cornell-velvet.gltf" \
            "$source_dir/scenes/pbrt/cornell-curves.pbrt" >"$build_dir/prepared_scene_seeds.log" 2>&1 ||
            { cat "$build_dir/prepared_scene_seeds.log" >&2; exit 1; }
    fi
    if [ -d "$source_dir/tests/fuzz/corpus/$format" ]; then cp "$source_dir/tests/fuzz/corpus/$format"/* "$corpus"/; fi
    inputs=$(ls "$corpus" | wc -l)
    # libFuzzer runs every input of the corpus before it mutates any (a crash among them fails
    # as any other); new units it finds go into the copy, not into the source tree.
    # -close_fd_mask=3: the loaders' warnings would flood the log.
    if ! (cd "$build_dir" && LSAN_OPTIONS="suppressions=$source_dir/tests/fuzz/lsan.supp" "./tests/fuzz/${format}_fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
            -max_len=$max_len -close_fd_mask=3 -print_final_stats=1 "$corpus" \
            >"$build_dir/$format.log" 2>&1); then
        echo "run_fuzzers: the $format fuzzer found a problem:" >&2
        grep -E "ERROR|SUMMARY|Test unit written|artifact" "$build_dir/$format.log" >&2 || tail -30 "$build_dir/$format.log" >&2
        status=1
    else
        final_stat() { sed -n "s/^stat::$1: *//p" "$build_dir/$format.log"; }
        echo "run_fuzzers: $format: $inputs inputs replayed and fuzzed for ${seconds} s in all:" \
             "$(final_stat number_of_executed_units) executions, $(final_stat new_units_added) new units," \
             "corpus $(ls "$corpus" | wc -l) inputs"
    fi
done
exit $status
