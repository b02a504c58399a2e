#!/bin/bash
# Where forward+'s opaque pass spends its time, term by term, against the deferred compute passes
# that evaluate the same shader functions (shaders/common/: material, suns with their shadows, IBL).
# forward_opaque is timed with forward.frag as it is and with one term taken out at a time, each from
# a patched copy of shaders/ through $LIGHTPASS_SHADER_DIR (timing only: the images differ):
#   full       forward.frag as it is
#   no_sun     lpSunRadiance (suns and their shadow filtering) left out
#   no_ibl     lpIblRadiance left out
#   material   only the material (lpEvaluateSurface) and the write: the flat-lit branch for every surface
#   early      full with layout(early_fragment_tests): does the driver test depth before the shader?
# beside deferred (the default visibility G-buffer) in one more process: gbuffer_resolve (the
# material, in compute), global_lights (suns and shadows), ibl. One local light (--light-count 1),
# the gallery (needs ../shared/assets) and the Cornell box, 1080p and 4K. From the repository root:
#   bench/forward_terms.sh BUNDLE OUTDIR    (BUNDLE: run, lib/)
# Writes OUTDIR/forward_terms_<scene>_<variant>.json and OUTDIR/forward_terms.md.
# PATCH_ONLY=DIR bench/forward_terms.sh writes the patched shader copies to DIR/<variant>/ and stops
# (no bundle needed: tests/bench checks that every patch still applies).
set -u
SRC=${LIGHTPASS_SHADER_DIR:-shaders}
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
# patch VARIANT SED-EXPRESSION PATTERN: a copy of shaders/ with forward.frag edited; the pattern must
# be found afterwards, so a reworded forward.frag fails here, not silently in the table.
patch() {
  cp -r "$SRC" "$T/$1"
  [ -n "$2" ] && sed -i "$2" "$T/$1/forward.frag"
  grep -q -- "$3" "$T/$1/forward.frag" || { echo "forward_terms: the $1 patch did not apply to forward.frag" >&2; exit 1; }
}
patch full "" "lpSunRadiance"
patch no_sun 's/^    c += lpSunRadiance(.*);$/    c += vec3(0.0);  \/\/ no_sun/' "no_sun"
patch no_ibl 's/^    if (uIbl)$/    if (false)  \/\/ no_ibl/' "no_ibl"
patch material 's/^    if (!uLightingOnly \&\& uFlat) {/    if (true) {  \/\/ material/' "// material"
patch early 's/^layout(location = 0) out vec4 outHdr;$/&\n#ifndef LP_FORWARD_TRANSPARENT\nlayout(early_fragment_tests) in;\n#endif/' "early_fragment_tests"
if [ -n "${PATCH_ONLY:-}" ]; then mkdir -p "$PATCH_ONLY" && cp -r "$T"/. "$PATCH_ONLY"/; exit 0; fi
B=$(cd "$1" && pwd); R=$2; mkdir -p "$R"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$R/device.txt" 2>/dev/null
$B/run --version
for s in gallery cornell; do
  for v in full no_sun no_ibl material early; do
    LIGHTPASS_SHADER_DIR=$T/$v $B/run bench --scene scenes/$s.json --frames 60 --warmup 10 --max-seconds 3 --min-frames 3 \
      --render-path forward+ --light-count 1 --vary '--size 1920x1080,3840x2160' \
      --timings-json "$R/forward_terms_${s}_$v.json" -q > "$R/forward_terms_${s}_$v.log" 2>&1 \
      || echo "bench $s $v failed (see $R/forward_terms_${s}_$v.log)"
  done
  $B/run bench --scene scenes/$s.json --frames 60 --warmup 10 --max-seconds 3 --min-frames 3 \
    --render-path deferred --light-count 1 --vary '--size 1920x1080,3840x2160' \
    --timings-json "$R/forward_terms_${s}_deferred.json" -q > "$R/forward_terms_${s}_deferred.log" 2>&1 \
    || echo "bench $s deferred failed (see $R/forward_terms_${s}_deferred.log)"
done
python3 bench/summarize_forward_terms.py "$R" | tee "$R/forward_terms.md"
