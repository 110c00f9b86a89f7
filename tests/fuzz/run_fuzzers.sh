#!/usr/bin/env bash
# Builds the scene-parser fuzzers, the gzip decoder's, the spectrum files', the Draco and
# meshopt decoders', the PLY reader's and the prepared-scene decoder's with clang (libFuzzer,
# AddressSanitizer, UBSan) in their own build folder and runs each for a fixed time over a copy
# of its seed corpus.
# Fails if a fuzzer finds a crash, a sanitizer error, a leak or a hang (the input is left in
# the build folder).
# Usage: run_fuzzers.sh SOURCE_DIR FUZZ_BUILD_DIR [SECONDS_EACH]
set -euo pipefail
source_dir=$1
build_dir=$2
seconds=${3:-${PF_FUZZ_SECONDS:-26}}
source "$source_dir/tests/support/prerequisite.sh"
command -v clang++ >/dev/null ||
    skip_for_want_of "run_fuzzers: clang++ is not installed (package clang); cannot build the fuzzers"
# Not float-cast-overflow: a double beyond float's range becomes +-inf on every target
# photonfarm builds for, and the loaders check converted values with IsFinite.
flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize=float-cast-overflow -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
if [ ! -f "$build_dir/build.ninja" ]; then
    cmake -S "$source_dir" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
        -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
        -DPF_BUILD_TESTS=OFF -DPF_BUILD_BENCH=OFF -DPF_BUILD_FUZZERS=ON >"$build_dir.configure.log" 2>&1 ||
        { cat "$build_dir.configure.log" >&2; exit 1; }
fi
cmake --build "$build_dir" --target pbrt_fuzzer gltf_fuzzer gzip_fuzzer spectrum_fuzzer draco_fuzzer meshopt_fuzzer ply_fuzzer prepared_scene_fuzzer prepared_scene_seeds -- -j "$(nproc)" >"$build_dir.build.log" 2>&1 ||
    { tail -50 "$build_dir.build.log" >&2; exit 1; }
status=0
for format in pbrt gltf gzip spectrum draco meshopt ply prepared_scene; do
    corpus="$build_dir/corpus-$format"
    rm -rf "$corpus" && mkdir -p "$corpus"
    if [ "$format" = prepared_scene ]; then  # seeds made from the shipped scenes, not kept
        ASAN_OPTIONS=detect_leaks=0 "$build_dir/tests/fuzz/prepared_scene_seeds" "$corpus" "$source_dir/scenes/cornell-box.gltf" \
            "$source_dir/scenes/pbrt/caustic-glass.pbrt" "$source_dir/scenes/cornell-bumpy.gltf" \
            "$source_dir/scenes/pbrt/cornell-materials.pbrt" "$source_dir/scenes/cornell-velvet.gltf" \
            "$source_dir/scenes/pbrt/cornell-curves.pbrt" 2>/dev/null
        seeds=()
    else
        cp "$source_dir/tests/fuzz/corpus/$format"/* "$corpus"/
        seeds=("$source_dir/tests/fuzz/corpus/$format")
    fi
    echo "run_fuzzers: $format for ${seconds}s over $(ls "$corpus" | wc -l) seed inputs"
    # -close_fd_mask=3: the loaders' warnings would flood the log.
    if ! (cd "$build_dir" && LSAN_OPTIONS="suppressions=$source_dir/tests/fuzz/lsan.supp" "./tests/fuzz/${format}_fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
            -max_len=16384 -close_fd_mask=3 -print_final_stats=1 "$corpus" "${seeds[@]}" \
            >"$build_dir/$format.log" 2>&1); then
        echo "run_fuzzers: the $format fuzzer found a problem:" >&2
        grep -E "ERROR|SUMMARY|Test unit written|artifact" "$build_dir/$format.log" >&2 || tail -30 "$build_dir/$format.log" >&2
        status=1
    else
        grep -E "stat::number_of_executed_units|stat::new_units_added" "$build_dir/$format.log" | tr '\n' ' '
        echo
    fi
done
exit $status
