#!/usr/bin/env bash
# bench/corpus.sh over a folder this test writes: a valid scene is "clean", one with a feature
# photonfarm approximates is "approximated" naming it, a malformed one "refused" with its file
# and line, an Include'd fragment is no scene, and a renderer killed by SIGABRT is "crashed"
# naming the signal (a stand-in executable that aborts). Against a stand-in pbrt-v4 and a
# stand-in photonfarm that write constant images whose ratios are known here, the per-channel
# ratios, the quarters' range and the pbrt-v4 noise are those ratios, a 10% difference on a clean
# scene fails --check where the same is within pbrt-v4's noise at 10%, and a second run takes
# pbrt-v4's renders from its cache.
# Usage: corpus_test.sh PHOTONFARM SOURCE_DIR
set -u
photonfarm=$1
source_dir=$2
corpus=$source_dir/bench/corpus.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
expect() {  # expect NAME PATTERN FILE: FILE has a line matching PATTERN (grep -E)
    if grep -qE -- "$2" "$3"; then
        echo "ok   $1"
    else
        echo "FAIL $1: no line matches '$2' in:"
        cat "$3"
        failures=$((failures + 1))
    fi
}

# The scenes: a lit sphere in front of a camera, the same with a sensor photonfarm does not
# model, a parameter that is no number, and a fragment (no WorldBegin).
mkdir -p "$work/scenes/sub"
scene() {
    printf 'LookAt 0 0 -3  0 0 0  0 1 0\nCamera "perspective" "float fov" 40\n%s\nWorldBegin\n' "$1"
    printf 'LightSource "infinite" "rgb L" [ 1 1 1 ]\n'
    printf 'Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]\nShape "sphere" "float radius" %s\n' "$2"
}
scene 'Film "rgb" "integer xresolution" 32 "integer yresolution" 16' 1 >"$work/scenes/good.pbrt"
scene 'Film "rgb" "integer xresolution" 32 "integer yresolution" 16 "string sensor" "canon_eos_100d"' 1 \
    >"$work/scenes/sub/sensor.pbrt"
scene 'Film "rgb" "integer xresolution" 32 "integer yresolution" 16' '"big"' >"$work/scenes/bad.pbrt"
printf 'Shape "sphere"\n' >"$work/scenes/fragment.pbrt"
cp "$work/scenes/good.pbrt" "$work/scenes/crash.pbrt"

# A photonfarm that aborts on crash.pbrt and runs the real one otherwise.
cat >"$work/photonfarm" <<EOF
#!/usr/bin/env bash
[[ \$2 == */crash.pbrt ]] && kill -ABRT \$\$
exec "$photonfarm" "\$@"
EOF
chmod +x "$work/photonfarm"
"$corpus" "$work/scenes" --photonfarm "$work/photonfarm" --no-pbrt --width 16 --seconds 0.2 --threads 1 --timeout 60 \
    --markdown "$work/table.md" >"$work/out" 2>&1
expect "a valid scene is clean" '^clean +good\.pbrt \| pf [0-9.]+s' "$work/out"
expect "a sensor is approximated, named" '^approximated +sub/sensor\.pbrt \|.*sensor "canon_eos_100d"' "$work/out"
expect "a malformed scene is refused with its line" '^refused +bad\.pbrt \|.*bad\.pbrt:7:[0-9]+:.*"float radius"' "$work/out"
expect "an abort is a crash, named" '^crashed +crash\.pbrt \|.*SIGABRT \(exit 134\)' "$work/out"
expect "the summary counts them" '^summary: 4 scenes: 1 clean, 1 approximated, 1 refused, 1 crashed' "$work/out"
expect "the Markdown table has each" '^\| sub/sensor\.pbrt \| approximated' "$work/table.md"
if grep -q fragment "$work/out"; then
    echo "FAIL an Include'd fragment is listed as a scene"
    failures=$((failures + 1))
fi

# Against pbrt-v4: stand-ins that write constant images, photonfarm's (0.5, 1, 2) against
# pbrt-v4's (0.5, 1, 2 - d) and (0.5, 1, 2 + d) over seeds 1 and 2 (mean (0.5, 1, 2): every
# channel agrees; noise (2d / 4) = d / 2), then photonfarm's blue 10% over it: with d = 0.02
# (noise 1%) that differs (1.1 > 1 + 0.03 + 2 x 0.01), with d = 0.2 (noise 10%) it is within the
# noise.
mkdir -p "$work/compare"
cp "$work/scenes/good.pbrt" "$work/compare/same.pbrt"
cat >"$work/fake-photonfarm" <<EOF
#!/usr/bin/env bash
out=\$(sed -n 's/.*--out \([^ ]*\).*/\1/p' <<<"\$*")
oiiotool --pattern constant:color=0.5,1,\${BLUE:-2} 16x8 3 -d float -o "\$out"
EOF
cat >"$work/fake-pbrt" <<EOF
#!/usr/bin/env bash
echo run >>"$work/pbrt-runs"
seed=\$(sed -n 's/.*--seed \([0-9]*\).*/\1/p' <<<"\$*")
out=\$(sed -n 's/.*--outfile \([^ ]*\).*/\1/p' <<<"\$*")
grep -q 'xresolution" \[ 16 \] "integer yresolution" \[ 8 \]' "\${@: -1}" || exit 1  # the rewritten Film
blue=\$(awk -v d=\${D:-0.02} -v s=\$seed 'BEGIN { print (s == 1 ? 2 - d : 2 + d) }')
oiiotool --pattern constant:color=0.5,1,\$blue 16x8 3 -d float -o "\$out"
EOF
chmod +x "$work/fake-photonfarm" "$work/fake-pbrt"
compare() {  # compare CACHE
    "$corpus" "$work/compare" --photonfarm "$work/fake-photonfarm" --pbrt "$work/fake-pbrt" --cache "$1" \
        --width 16 --seconds 1 --threads 1 --check >"$work/out" 2>&1
}
compare "$work/cache"
expect "equal means agree" '^clean +same\.pbrt \|.*\| R/G/B 1\.000 1\.000 1\.000 \| quarters 1\.00-1\.00 \| pbrt-v4 noise 1\.00% \| agrees' "$work/out"
BLUE=2.2 compare "$work/cache"
code=$?
expect "a 10% difference is seen" '^clean +same\.pbrt \|.*\| R/G/B 1\.000 1\.000 1\.100 \| quarters 1\.06-1\.06 .*\| differs' "$work/out"
expect "and summed up as unwarned" '1 differ \(1 of them with no warning\)' "$work/out"
if [[ $code -ne 1 ]]; then
    echo "FAIL --check exits $code, not 1, on a clean scene that differs"
    failures=$((failures + 1))
fi
if [[ $(wc -l <"$work/pbrt-runs") -ne 2 ]]; then
    echo "FAIL pbrt-v4 ran $(wc -l <"$work/pbrt-runs") times over two runs of one scene, not 2 (cache)"
    failures=$((failures + 1))
fi
D=0.2 BLUE=2.2 compare "$work/another-cache"
expect "within pbrt-v4's noise it agrees" '^clean +same\.pbrt \|.*\| R/G/B 1\.000 1\.000 1\.100 \|.*pbrt-v4 noise 10\.00% \| agrees' "$work/out"

[[ $failures -eq 0 ]] && echo "corpus_test: all passed" || echo "corpus_test: $failures failed"
[[ $failures -eq 0 ]]
