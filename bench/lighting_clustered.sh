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
# VARIANTS=1: instead of the run below, the clustered kernel's variants against tiled in one run (timing
# only; every variant gives the same image within the tests' bounds), each from a patched copy of
# shaders/ through $LIGHTPASS_SHADER_DIR: `default` (shaders/ as they are), `stop28` (main's kernel at
# 99b0145, bench/kernels/local_light_clustered_stop28.comp: every surface texel read and written, lit
# or not), stop 31's kernels (bench/kernels/local_light_clustered_<name>.comp; each tile's slice boxes
# made where tested, not kept in shared memory): `compact2` (the tiled method's list of the tile's
# lights, double-buffered, each light with a 32-bit mask of its slices; every pixel walks the whole
# list and skips the lights its slice lacks), `compact` (the same, one buffer), `bits32` (main's kernel
# with 3.8 KB of shared memory instead of 8.5: slices counted from the tile's nearest), `group_walk`
# (`bits32` where 32 invocations walk their pixels' slices' lights together), `merged_list` (main's
# kernel where a tile in one froxel walks the tiled method's list), `pair_union` (main's kernel where a
# tile with two occupied slices walks both slices' lights together), `tiled_pad8k` (the tiled
# kernel with 8 KB more shared memory: its column is tiled's), `lists` (main's fused kernel up to
# 0b4a46a, bench/kernels/local_light_clustered_lists.comp: it writes the froxel lists every frame),
# and patched defaults: `all_slices` (every occupied slice tested, not only those the light's
# eye-depth interval reaches), `no_box` (the slices' depth ranges only), `merge1_5`, `merge2`,
# `merge4`, `merge8` (tiles whose farthest pixel is <= 1.5x, 2x, 4x, 8x their nearest shade as one
# froxel), and those that split the cost:
# `cull_only` (the culling and the bits as the default, no light shaded), `tile_only` (every tile one
# froxel: tiled's lights, shaded in this kernel) and `tiled_cull_only` (the tiled method culling and
# shading nothing; its column is tiled's, against the default's tiled).
# Measured and removed (bench/results/lighting/clustered/variants_run4_*, variants_run5_*): sorting a
# tile's pixels by slice, reading the shading texels after that sort, loading the next batch's light
# bounds early, the tile's bounds re-read from shared memory per batch, the view direction made per
# light; variants_run6_*: shared arrays sized for the grid's slice count, not 64 (no change);
# variants_run7_*: tiles with at most 2 or 3 occupied slices, or with consecutive ones, shading as one
# froxel (slower).
# VARIANT_LIST picks them (default: default stop28 cull_only tiled_cull_only);
# `default` and `stop28` also time tiled in their process. Three scenes x 1080p, 4K x
# 1..16384 lights, 50 frames (2 s cap): OUTDIR/variants_<variant>_<scene>.json and OUTDIR/clustered_variants.md
# (clustered / tiled per variant, against the tiled of its own process where it has one).
if [ -n "${VARIANTS:-}" ]; then
  variant_dir() {  # $1 name -> a patched copy of shaders/ in $R/shaders_$1 (echoes its path; empty on failure)
    local P=$R/shaders_$1 f=$R/shaders_$1/local_light_clustered.comp
    rm -rf "$P"; cp -r shaders "$P"
    case $1 in
      lists) cp bench/kernels/local_light_clustered_lists.comp "$f" ;;
      stop28) cp bench/kernels/local_light_clustered_stop28.comp "$f" ;;
      compact|compact2|bits32|group_walk|merged_list|pair_union) cp bench/kernels/local_light_clustered_$1.comp "$f" ;;
      tiled_pad8k) f=$P/local_light_tiled.comp; cp bench/kernels/local_light_tiled_pad8k.comp "$f" ;;
      default) ;;
      tiled_cull_only) f=$P/local_light_tiled.comp
        sed -i 's/for (uint k = 0u; k < n; ++k) {$/for (uint k = 0u; k < 0u; ++k) {/' "$f"
        cmp -s shaders/local_light_tiled.comp "$f" && { echo "variant $1: shaders/local_light_tiled.comp changed shape, skipped" >&2; return; } ;;
      all_slices) sed -i 's/uvec2 candidates = clusterCandidateSlices(dist, r, occ);/uvec2 candidates = occ;/' "$f" ;;
      no_box) sed -i 's/    return clusterLightTouchesBox(b, apex, axis, sBoxLo\[j\].xyz, sBoxHi\[j\].xyz);$/    return true;/' \
        "$P/common/cluster_tile.glsl"
        cmp -s shaders/common/cluster_tile.glsl "$P/common/cluster_tile.glsl" && { echo "variant $1: common/cluster_tile.glsl changed shape, skipped" >&2; return; } ;;
      merge2) sed -i 's/^#define LP_CLUSTER_MERGE_RATIO .*/#define LP_CLUSTER_MERGE_RATIO 2.0/' "$f" ;;
      merge1_5) sed -i 's/^#define LP_CLUSTER_MERGE_RATIO .*/#define LP_CLUSTER_MERGE_RATIO 1.5/' "$f" ;;
      merge4) sed -i 's/^#define LP_CLUSTER_MERGE_RATIO .*/#define LP_CLUSTER_MERGE_RATIO 4.0/' "$f" ;;
      merge8) sed -i 's/^#define LP_CLUSTER_MERGE_RATIO .*/#define LP_CLUSTER_MERGE_RATIO 8.0/' "$f" ;;
      tile_only) sed -i 's/^#define LP_CLUSTER_MERGE_RATIO .*/#define LP_CLUSTER_MERGE_RATIO 3.0e38/' "$f" ;;
      cull_only) sed -i 's/for (; bits != 0u; bits \&= bits - 1u)$/for (; false; bits \&= bits - 1u)/' "$f"
        grep -q 'for (; false; bits' "$f" || { echo "variant $1: the shading loop changed shape, skipped" >&2; return; } ;;
      *) echo "variant $1: unknown" >&2; return ;;
    esac
    case $1 in default|no_box|tiled_*) ;; *) if cmp -s shaders/local_light_clustered.comp "$f"; then
      echo "variant $1: shaders/local_light_clustered.comp changed shape, skipped" >&2; return
    fi ;; esac
    echo "$P"
  }
  for v in ${VARIANT_LIST:-default stop28 cull_only tiled_cull_only}; do
    P=$(variant_dir "$v"); [ -n "$P" ] || continue
    methods='--local-lights clustered --cluster-size 16 --clustered-kernel froxels'  # the kernel itself, never the race
    case $v in
      default|stop28) methods="--local-lights tiled|$methods" ;;
      tiled_*) methods='--local-lights tiled' ;;  # a variant of the tiled method: its own column
    esac
    for s in ${SCENES:-gallery depth-discontinuity fence}; do
      LIGHTPASS_SHADER_DIR=$P $B/run bench --scene scenes/$s.json --frames 50 --warmup 8 --max-seconds 2 \
        --min-frames 3 --vary "$methods" --vary '--light-count 1,16,256,1024,4096,16384' \
        --vary '--size 1920x1080,3840x2160' --timings-json "$R/variants_${v}_$s.json" -q \
        > "$R/variants_${v}_$s.log" 2>&1 || echo "variant $v $s failed (see $R/variants_${v}_$s.log)"
    done
  done
  python3 bench/summarize_clustered_variants.py "$R" | tee "$R/clustered_variants.md"
  exit 0
fi
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
