#!/bin/bash
# Local-light culling on the GPU, one run: deferred tiled, deferred clustered (16- and 32-pixel froxel
# tiles; 16 is the default, run with --clustered-kernel auto, the default, and froxels, its own kernel
# alone) and forward+ (which reads the clustered lists), light counts 1..16384 at
# 1080p and 4K, on three scenes: the gallery (needs ../shared/assets; continuous surfaces, where
# tiled's per-tile depth bounds are already tight), scenes/depth-discontinuity.json (thin pillars
# against a wall 40 m away: the tiles on a pillar's edge span 1-40 m) and scenes/fence.json (a 5 cm
# fence 1.5 m away before a corridor 40 m long: nearly every tile spans near and far). From the
# repository root:
#   bench/lighting_clustered.sh BUNDLE OUTDIR    (BUNDLE: run, lib/)
# SCENES="fence" (a subset of the three) runs only those; the tables cover every clustered_<scene>.json
# already in OUTDIR, so a run split over several calls still ends with the whole table.
# METHODS (a --vary value) replaces the methods compared, e.g. METHODS='--local-lights tiled|--local-lights
# clustered --cluster-size 16' for a quicker run without forward+.
# Writes OUTDIR/clustered_<scene>.json (lightpass bench), OUTDIR/clustered_<scene>.log and
# OUTDIR/lighting_clustered.md (the tables: local_lights ms, measured/floor, clustered/tiled, the
# frame with forward+, and issue #18's targets).
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p "$R"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$R/device.txt" 2>/dev/null
$B/run --version
# The clustered kernel's variants measured and not kept (the VARIANTS=1 mode and bench/kernels/):
# docs/notes/clustered-kernel-variants.md; the git tag experiments/clustered-kernel-variants keeps them.
DEFAULT_METHODS='--local-lights tiled|--local-lights clustered --cluster-size 16|--local-lights clustered --cluster-size 16 --clustered-kernel froxels|--local-lights clustered --cluster-size 32|--render-path forward+'
for s in ${SCENES:-gallery depth-discontinuity fence}; do
  $B/run bench --scene scenes/$s.json --frames 100 --warmup 10 --floors --max-seconds 3 --min-frames 3 \
    --vary "${METHODS:-$DEFAULT_METHODS}" \
    --vary '--light-count 1,16,256,1024,4096,16384' --vary '--size 1920x1080,3840x2160' \
    --timings-json "$R/clustered_$s.json" -q > "$R/clustered_$s.log" 2>&1 \
    || echo "bench $s failed (see $R/clustered_$s.log)"
done
# ABLATE=1: what lpShadeLocalLight's early-out is worth (a light whose range does not reach the pixel
# returns 0 before the rest of the shading): tiled and clustered (16 px) at 1080p on the two scenes
# whose tiles span near and far, from a patched copy of shaders/ without it, through
# $LIGHTPASS_SHADER_DIR (timing only; the same images). OUTDIR/ablate_no_early_out.md.
if [ -n "${ABLATE:-}" ]; then
  a=no_early_out; P=$R/shaders_$a; rm -rf "$P"; cp -r shaders "$P"
  sed -i '/d2 >= l.positionRange.w \* l.positionRange.w) return vec3(0.0);$/d' "$P/common/local_light.glsl"
  if diff -rq shaders "$P" > /dev/null; then
    echo "ablation $a: shaders/common/local_light.glsl changed shape, skipped"
  else
    for s in depth-discontinuity fence; do
      LIGHTPASS_SHADER_DIR=$P $B/run bench --scene scenes/$s.json --frames 100 --warmup 10 --floors --max-seconds 3 \
        --min-frames 3 --vary '--local-lights tiled|--local-lights clustered --cluster-size 16' \
        --vary '--light-count 1,16,256,1024,4096,16384' --vary '--size 1920x1080' \
        --timings-json "$R/ablate_${a}_$s.json" -q > "$R/ablate_${a}_$s.log" 2>&1 || echo "ablation $a $s failed"
    done
    { echo "# Ablation: $a (patched shaders, timing only)"; echo
      python3 bench/summarize_clustered.py "$R/ablate_${a}_depth-discontinuity.json" "$R/ablate_${a}_fence.json"; } \
      > "$R/ablate_$a.md"
  fi
fi
tables=()
for s in gallery depth-discontinuity fence; do [ -f "$R/clustered_$s.json" ] && tables+=("$R/clustered_$s.json"); done
python3 bench/summarize_clustered.py "${tables[@]}" | tee "$R/lighting_clustered.md"
