#!/usr/bin/env bash
# bench/corpus.sh DIR [options]: renders every scene under DIR (each .gltf and .glb, and each .pbrt
# that is a whole scene, i.e. has WorldBegin; Include'd fragments are skipped) with photonfarm,
# small and briefly, and prints one line a scene:
#   clean         rendered with no warning
#   approximated  rendered with warnings: the features they name, with how many times each
#   refused       a non-zero exit: its error line
#   crashed       killed by a signal (which), or ran past --timeout ("hung")
# Where pbrt-v4 is present and the scene is pbrt, pbrt-v4 renders the same file at the same size
# (twice, seeds 1 and 2, --pbrt-spp samples in all; cached outside the repository, keyed by the
# scene's files, the settings and pbrt-v4's binary), and the line gives photonfarm's per-channel
# mean over pbrt-v4's, the least and greatest of the same ratio of R+G+B over the image's four
# quarters (a scene right on average but wrong in a region), and pbrt-v4's own noise in its mean
# (half the difference of its two runs' means, relative: an estimate from one pair, so rough).
# "differs" marks a channel outside 1 +- (--tolerance + 2 x noise) or a quarter outside
# 1 +- 2 x (--tolerance + 2 x noise); on a clean scene that is an unwarned difference.
# A summary follows: counts by class, crashes, refusals, differences. --markdown FILE writes the
# same as a Markdown table (docs/scene-survey.md is made from it). Exit status 0, or with
# --check 1 where a scene crashed or a clean scene differs from pbrt-v4.
#
# Options:
#   --build DIR        photonfarm's build folder (default: build beside this script's folder)
#   --photonfarm PATH  the photonfarm executable (default: BUILD/client/photonfarm)
#   --width N          image width in pixels (default 128); the height follows the scene's Film
#   --seconds S        photonfarm's time budget a scene (default 5)
#   --timeout S        longest a render may take before it counts as hung (default 600)
#   --threads N        threads for each renderer (default: all cores)
#   --pbrt PATH        pbrt-v4 (default: ../shared/tools/pbrt-v4/pbrt beside the repository)
#   --no-pbrt          no comparison
#   --pbrt-spp N       pbrt-v4's samples a pixel, over its two runs (default 256)
#   --cache DIR        pbrt-v4's renders (default: ${XDG_CACHE_HOME:-~/.cache}/photonfarm-corpus)
#   --images DIR       keep each scene's images there (photonfarm's EXR and PNG, pbrt-v4's PNG)
#   --markdown FILE    also write the results as a Markdown table
#   --tolerance T      relative difference that counts (default 0.03)
#   --only REGEX       only scenes whose path under DIR matches REGEX (grep -E)
#   --no-light ARGS    flags that light a scene refused for having no light, which is then
#                      rendered again with them (default "--environment-color 1,1,1")
#   --check            exit 1 where a scene crashed or a clean scene differs
#   -- ARGS...         further flags for `photonfarm render` (e.g. --integrator path)
set -uo pipefail

usage() { sed -n '2,/^set -uo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2; exit 2; }
[[ $# -ge 1 && $1 != -* ]] || usage
dir=$(cd "$1" && pwd) || exit 2
shift
source_dir=$(cd "$(dirname "$0")/.." && pwd)
build=$source_dir/build photonfarm=""
width=128 seconds=5 timeout_s=600 threads=$(nproc) pbrt=$source_dir/../shared/tools/pbrt-v4/pbrt
pbrt_spp=256 cache=${XDG_CACHE_HOME:-$HOME/.cache}/photonfarm-corpus images="" markdown=""
tolerance=0.03 only="" check=0
extra=()
no_light=(--environment-color "1,1,1")
while [[ $# -gt 0 ]]; do
    case $1 in
        --build) build=$2; shift ;;
        --photonfarm) photonfarm=$2; shift ;;
        --width) width=$2; shift ;;
        --seconds) seconds=$2; shift ;;
        --timeout) timeout_s=$2; shift ;;
        --threads) threads=$2; shift ;;
        --pbrt) pbrt=$2; shift ;;
        --no-pbrt) pbrt="" ;;
        --pbrt-spp) pbrt_spp=$2; shift ;;
        --cache) cache=$2; shift ;;
        --images) images=$2; shift ;;
        --markdown) markdown=$2; shift ;;
        --tolerance) tolerance=$2; shift ;;
        --only) only=$2; shift ;;
        --no-light) read -r -a no_light <<<"$2"; shift ;;
        --check) check=1 ;;
        --) shift; extra=("$@"); break ;;
        *) usage ;;
    esac
    shift
done
[[ -n $photonfarm ]] || photonfarm=$build/client/photonfarm
[[ -x $photonfarm ]] || { echo "corpus.sh: no photonfarm at $photonfarm (--build)" >&2; exit 2; }
command -v oiiotool >/dev/null || { echo "corpus.sh: needs oiiotool (openimageio-tools)" >&2; exit 2; }
[[ -n $pbrt && ! -x $pbrt ]] && pbrt=""
helper=$source_dir/bench/corpus_pbrt.py
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
[[ -n $images ]] && mkdir -p "$images"
[[ -n $pbrt ]] && mkdir -p "$cache"

now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }
# The name of the signal behind an exit status over 128.
signal_name() { local name; name=$(kill -l $(($1 - 128)) 2>/dev/null) && echo "SIG$name" || echo "signal $(($1 - 128))"; }

# means IMAGE...: a line an image of 16 numbers: the R G B means over the image, then over each
# quarter (top left, top right, bottom left, bottom right), then its count of NaN or Inf values.
# One oiiotool (slow to start) for all.
means() {
    local args=() image half_w='{TOP.width//2}' half_h='{TOP.height//2}'
    local rest_w='{TOP.width-TOP.width//2}' rest_h='{TOP.height-TOP.height//2}'
    for image in "$@"; do
        args+=(-i "$image" --ch "R,G,B" --printstats --printstats:window="${half_w}x${half_h}+0+0"
               --printstats:window="${rest_w}x${half_h}+${half_w}+0"
               --printstats:window="${half_w}x${rest_h}+0+${half_h}"
               --printstats:window="${rest_w}x${rest_h}+${half_w}+${half_h}")
    done
    oiiotool "${args[@]}" 2>&1 |
        awk '/Stats Avg:/ { line = line $3 " " $4 " " $5 " "; if (++blocks % 5 == 0) { print line (bad + 0); line = ""; bad = 0 } }
             /Stats (NanCount|InfCount):/ && blocks % 5 == 1 { bad += $3 + $4 + $5 }'
}

# pbrt_render SCENE W H: pbrt-v4's two renders of SCENE at W x H, from the cache or made now;
# prints the cache folder, which holds a.exr and b.exr, or status (its error) and seconds.
pbrt_render() {
    local scene=$1 w=$2 h=$3 key entry
    key=$( { python3 "$helper" hash "$scene"; echo "$w $h $pbrt_spp"; stat -c '%s %Y' "$pbrt"; } | sha256sum | cut -c1-32)
    entry=$cache/$key
    if [[ ! -f $entry/status ]]; then
        rm -rf "$entry" "$work/pbrt"
        mkdir -p "$entry"
        python3 "$helper" rewrite "$scene" "$w" "$h" "$work/pbrt" 2>"$entry/log" || { echo "could not rewrite the Film" >"$entry/status"; echo "$entry"; return; }
        local start status=ok half=$(((pbrt_spp + 1) / 2)) seed
        start=$(now)
        for seed in 1 2; do
            local out=$entry/a.exr
            [[ $seed == 2 ]] && out=$entry/b.exr
            { (cd "$work/pbrt" && nice -n 19 timeout -k 10 "$timeout_s" "$pbrt" --quiet --nthreads "$threads" \
                --spp "$half" --seed "$seed" --outfile "$out" "$(basename "$scene")") >>"$entry/log" 2>&1; } 2>/dev/null
            local rc=$?
            if [[ $rc -ne 0 ]]; then
                if [[ $rc -eq 124 || $rc -eq 137 ]]; then status="hung past ${timeout_s} s"
                elif [[ $rc -gt 128 ]]; then status="crashed ($(signal_name "$rc"))"
                else status="failed: $(grep -a -i 'error' "$entry/log" | tail -1 | sed 's/\x1b\[[0-9;]*m//g' | cut -c1-200)"; fi
                break
            fi
        done
        elapsed "$start" >"$entry/seconds"
        echo "$status" >"$entry/status"
        rm -rf "$work/pbrt"
    fi
    echo "$entry"
}

# Warnings that say nothing of how the image is rendered (a file name not used, a view chosen for
# a scene that has none): shown as notes, left out of the classification.
benign=('Film: "filename" is not used' 'the scene has no camera: framed on its bounds'
        "renders as photonfarm's path tracer (the same light transport)")
# warnings STDERR SCENE: the distinct warnings photonfarm printed, without their file locations
# (file:line:column, or SCENE's name), each with its count.
warnings() {
    local name=${2##*/}
    grep -a ': warning: ' "$1" | sed -E 's/^[^:]*: warning: //; s/^[^ ]*:[0-9]+:[0-9]+: //; s/^warning: //; s/^job [^ ]+: //' |
        awk -v prefix="$name: " 'index($0, prefix) == 1 { $0 = substr($0, length(prefix) + 1) } { print }' |
        cut -c1-160 | sort | uniq -c | sort -k1,1nr -k2 | sed -E 's/^ *([0-9]+) (.*)/\2\t\1/'
}
# join: "; "-joined warning lines from stdin, with " (xN)" for those printed N > 1 times.
join() { awk -F'\t' '{ printf "%s%s%s", (NR > 1 ? "; " : ""), $1, ($2 > 1 ? " (x" $2 ")" : "") }'; }
is_benign() { local b; for b in "${benign[@]}"; do [[ $1 == *"$b"* ]] && return 0; done; return 1; }
# features STDERR SCENE: the warnings that name an approximation; notes_of STDERR SCENE: the others.
features() { warnings "$1" "$2" | while IFS= read -r l; do is_benign "$l" || printf '%s\n' "$l"; done | join; }
notes_of() {
    warnings "$1" "$2" | while IFS=$'\t' read -r l n; do
        is_benign "$l" || continue
        short=${l%%:*}
        [[ ${#short} -ge 12 ]] || short=${l%%;*}
        printf '%s\t%s\n' "$short" "$n"
    done | join
}

# The scenes, sorted.
mapfile -t candidates < <(cd "$dir" && find . -type f \( -name '*.pbrt' -o -name '*.gltf' -o -name '*.glb' \) | sed 's|^\./||' | LC_ALL=C sort)
scenes=()
pbrt_files=()
for f in "${candidates[@]}"; do
    [[ -z $only ]] || grep -qE -- "$only" <<<"$f" || continue
    if [[ $f == *.pbrt ]]; then pbrt_files+=("$f"); else scenes+=("$f"); fi
done
declare -A heights  # a pbrt scene's image height at --width, from its Film's aspect
if [[ ${#pbrt_files[@]} -gt 0 ]]; then
    while IFS=$'\t' read -r f h; do
        scenes+=("$f")
        heights[$f]=$h
    done < <(cd "$dir" && python3 "$helper" top "$width" "${pbrt_files[@]}")
fi
mapfile -t scenes < <(printf '%s\n' "${scenes[@]}" | LC_ALL=C sort)

results=$work/results.tsv
: >"$results"
echo "corpus.sh: ${#scenes[@]} scenes under $dir; ${width} px wide, ${seconds} s each$([[ -n $pbrt ]] && echo ", against pbrt-v4 at $pbrt_spp spp")$([[ ${#extra[@]} -gt 0 ]] && echo "; photonfarm ${extra[*]}")"
for scene in "${scenes[@]}"; do
    [[ -n $scene ]] || continue
    file=$dir/$scene
    size=(--width "$width")
    w=$width h=""
    if [[ $scene == *.pbrt ]]; then
        h=${heights[$scene]}
        size=(--width "$w" --height "$h")
    fi
    out=$work/pf.exr png=$work/pf.png
    lit=""
    render() {
        rm -f "$out" "$png"
        nice -n 19 timeout -k 10 "$timeout_s" "$photonfarm" render "$file" --out "$out" --png "$png" "${size[@]}" \
            --seconds "$seconds" --threads "$threads" --log-level warn "$@" "${extra[@]}" >"$work/stdout" 2>"$work/stderr" </dev/null
    }
    start=$(now)
    render 2>/dev/null  # not the shell's own line on a child killed by a signal
    rc=$?
    # A scene with no light of its own (most glTF samples, made for viewers' image-based light)
    # is refused by name; it is then rendered under a uniform white sky, and says so.
    if [[ $rc -ne 0 && $rc -lt 128 ]] && grep -q 'scene has no light' "$work/stderr"; then
        render "${no_light[@]}" 2>/dev/null
        rc=$?
        lit="no light of its own: lit by ${no_light[*]}"
    fi
    pf_seconds=$(elapsed "$start")
    notes="" integrator="" rel=(- - -) quarters="-" noise="-" pbrt_seconds="-" verdict=""
    if [[ $rc -eq 124 || $rc -eq 137 ]]; then
        class=crashed notes="hung: no exit within ${timeout_s} s"
    elif [[ $rc -gt 128 ]]; then
        class=crashed
        notes="$(signal_name "$rc") (exit $rc): $(grep -a -v '^ *$' "$work/stderr" | tail -1 | cut -c1-200)"
    elif [[ $rc -ne 0 ]]; then
        class=refused
        notes=$(grep -a ': error: ' "$work/stderr" | tail -1 | sed 's/^[^:]*: error: //' | cut -c1-240)
        [[ -n $notes ]] || notes="exit $rc, no error line: $(grep -a -v '^ *$' "$work/stderr" | tail -1 | cut -c1-200)"
    elif [[ ! -s $out ]]; then
        class=refused notes="exit 0 but no image written"
    else
        notes=$(features "$work/stderr" "$scene")
        if [[ -n $notes ]]; then class=approximated; else class=clean; fi
        benign_notes=$(notes_of "$work/stderr" "$scene")
        [[ -n $benign_notes ]] && notes+="${notes:+; }notes: $benign_notes"
        integrator=$(oiiotool --info -v "$out" 2>/dev/null | sed -n 's/.*photonfarm:integrator: "\(.*\)"/\1/p')
    fi
    [[ -n $lit ]] && notes+="${notes:+; }$lit"
    if [[ -n $images && -s $out ]]; then
        name=${scene//\//_}
        cp "$out" "$images/${name%.*}.pf.exr"
        [[ -s $png ]] && cp "$png" "$images/${name%.*}.pf.png"
    fi
    # pbrt-v4's side.
    if [[ -n $pbrt && $scene == *.pbrt ]]; then
        entry=$(pbrt_render "$file" "$w" "$h")
        pbrt_status=$(cat "$entry/status")
        pbrt_seconds=$(cat "$entry/seconds" 2>/dev/null || echo -)
        if [[ $pbrt_status != ok ]]; then
            verdict="pbrt-v4 $pbrt_status"
        elif [[ -s $out ]]; then
            mapfile -t measured < <(means "$out" "$entry/a.exr" "$entry/b.exr")
            read -r -a ours <<<"${measured[0]:-}"
            read -r -a ref_a <<<"${measured[1]:-}"
            read -r -a ref_b <<<"${measured[2]:-}"
            if [[ ${#ours[@]} -eq 16 && ${#ref_a[@]} -eq 16 && ${#ref_b[@]} -eq 16 ]]; then
                summary=$(awk -v tol="$tolerance" -v o="${ours[*]}" -v a="${ref_a[*]}" -v b="${ref_b[*]}" 'BEGIN {
                    split(o, O); split(a, A); split(b, B)
                    for (i = 1; i <= 15; ++i) R[i] = (A[i] + B[i]) / 2
                    off = 0; noise = 0
                    for (c = 1; c <= 3; ++c) if (R[c] > 0) {
                        n = (A[c] - B[c]) / (A[c] + B[c]); if (n < 0) n = -n; if (n > noise) noise = n
                    }
                    for (c = 1; c <= 3; ++c) {
                        if (R[c] > 0) { x[c] = O[c] / R[c]; if (x[c] < 1 - tol - 2 * noise || x[c] > 1 + tol + 2 * noise) off = 1 }
                        else { x[c] = (O[c] > 0 ? "inf" : "-"); if (O[c] > 1e-6) off = 1 }
                    }
                    lo = 1e30; hi = -1e30
                    for (q = 0; q < 4; ++q) {
                        so = 0; sr = 0
                        for (c = 1; c <= 3; ++c) { so += O[3 + 3 * q + c]; sr += R[3 + 3 * q + c] }
                        if (sr <= 0) continue
                        r = so / sr; if (r < lo) lo = r; if (r > hi) hi = r
                        if (r < 1 - 2 * tol - 4 * noise || r > 1 + 2 * tol + 4 * noise) off = 1
                    }
                    printf "%s %s %s ", (x[1] ~ /^[0-9.]+$/ ? sprintf("%.3f", x[1]) : x[1]),
                        (x[2] ~ /^[0-9.]+$/ ? sprintf("%.3f", x[2]) : x[2]), (x[3] ~ /^[0-9.]+$/ ? sprintf("%.3f", x[3]) : x[3])
                    printf "%s %.2f%% %s %d %d\n", (lo <= hi ? sprintf("%.2f-%.2f", lo, hi) : "-"), 100 * noise,
                        (off ? "differs" : "agrees"), O[16], A[16] + B[16]
                }')
                read -r r g b quarters noise verdict bad_ours bad_ref <<<"$summary"
                rel=("$r" "$g" "$b")
                [[ $bad_ours -gt 0 ]] && verdict="$verdict; $bad_ours NaN/Inf values"
                [[ $bad_ref -gt 0 ]] && verdict="$verdict; pbrt-v4 has $bad_ref NaN/Inf values"
            else
                verdict="images unreadable"
            fi
        fi
        if [[ -n $images && -s $entry/a.exr ]]; then
            name=${scene//\//_}
            oiiotool "$entry/a.exr" "$entry/b.exr" --add --mulc 0.5 --ch R,G,B --colorconvert linear sRGB -d uint8 \
                -o "$images/${name%.*}.pbrt.png" 2>/dev/null
        fi
    fi
    line=$(printf '%-13s %s | pf %ss%s' "$class" "$scene" "$pf_seconds" "${integrator:+ $integrator}")
    [[ $pbrt_seconds != - ]] && line+=" | pbrt-v4 ${pbrt_seconds}s"
    [[ ${rel[0]} != - ]] && line+=" | R/G/B ${rel[0]} ${rel[1]} ${rel[2]} | quarters $quarters | pbrt-v4 noise $noise"
    [[ -n $verdict ]] && line+=" | $verdict"
    [[ -n $notes ]] && line+=" | $notes"
    echo "$line"
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$scene" "$class" "$pf_seconds" "${integrator:--}" \
        "$pbrt_seconds" "${rel[0]}" "${rel[1]}" "${rel[2]}" "$quarters" "$noise" "${verdict:--}" "${notes:--}" >>"$results"
done

# The summary.
echo
awk -F'\t' '
    { n[$2]++; total++ }
    $11 ~ /^differs/ { d++; if ($2 == "clean") { u++; unwarned = unwarned "  " $1 " (R/G/B " $6 " " $7 " " $8 ", quarters " $9 ")\n" } }
    $11 ~ /^agrees/ { a++ }
    $2 == "crashed" { crashes = crashes "  " $1 ": " $12 "\n" }
    END {
        printf "summary: %d scenes: %d clean, %d approximated, %d refused, %d crashed", total, n["clean"], n["approximated"], n["refused"], n["crashed"]
        if (a + d > 0) printf "; against pbrt-v4: %d agree, %d differ (%d of them with no warning)", a, d, u
        printf "\n"
        if (crashes != "") printf "crashed:\n%s", crashes
        if (unwarned != "") printf "clean but differs from pbrt-v4:\n%s", unwarned
    }' "$results"

if [[ -n $markdown ]]; then
    {
        echo "| Scene | Result | photonfarm s | pbrt-v4 s | R | G | B | Quarters (R+G+B) | pbrt-v4 noise | Comparison | Warnings, error or signal |"
        echo "|---|---|---:|---:|---:|---:|---:|---|---:|---|---|"
        awk -F'\t' '{ note = $12; gsub(/\|/, "\\|", note); verdict = $11; gsub(/\|/, "\\|", verdict)
                      printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n",
                             $1, $2 ($4 != "-" ? " (" $4 ")" : ""), $3, $5, $6, $7, $8, $9, $10, verdict, note }' "$results"
    } >"$markdown"
fi
if [[ $check -eq 1 ]] && awk -F'\t' '$2 == "crashed" || ($2 == "clean" && $11 ~ /^differs/) { bad = 1 } END { exit !bad }' "$results"; then
    exit 1
fi
exit 0
