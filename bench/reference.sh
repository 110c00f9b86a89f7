# Sourced by the bench scripts that measure error against a reference (compare_integrators.sh,
# compare_backends.sh): one way to make a scene's reference.
#  - the path tracer for REF_SECONDS with a seed of its own; for caustic-glass, whose small light
#    the path tracer finds through the glass only by chance, stochastic progressive photon
#    mapping; for the furnaces the exact image L = 2.
# make_reference PHOTONFARM SCENE_FILE OUT_EXR SIZE REF_SECONDS [EXTRA_FLAGS...]
make_reference() {
    local photonfarm=$1 file=$2 out=$3 size=$4 ref_seconds=$5
    shift 5
    local scene
    scene=$(basename "$file" .gltf)
    if [[ $scene == furnace* ]]; then
        oiiotool --pattern constant:color=2,2,2 "${size}x${size}" 3 -d float -o "$out"
        return
    fi
    local integrator=path
    [[ $scene == caustic-glass ]] && integrator=sppm
    "$photonfarm" render "$file" "$@" --width "$size" --height "$size" --log-level warn \
        --integrator "$integrator" --seed 977 --seconds "$ref_seconds" --out "$out" \
        2>"$out.log" >/dev/null || { cat "$out.log" >&2; return 1; }
}
