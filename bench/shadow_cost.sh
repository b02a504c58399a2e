#!/bin/bash
# Cost of the sun cascades on a moving camera: the gallery's two suns x 4 cascades of 2048^2 at
# 1920x1080, on scenes/gallery-flythrough.json's camera path (frames at 60 fps from t = 1 s, so every
# frame has a new camera and new cascades). The rasters: conservative and split each grown in
# hardware (GL_NV_conservative_raster, --shadow-conservative hardware) and by the geometry shader
# (--shadow-conservative geometry-shader), plain and compute. 'lightpass info' (OUTDIR/info.txt) says
# whether this GPU has the hardware conservative raster; on a GPU without it the hardware rows fall
# back to the geometry shader (the table's "grown by" column and the explain files say so).
#  1. --shadow-cache off / on x the six rasters (culling on, the default --shadow-origin-step):
#     shadow_cost.json.
#  2. --shadow-cache on x --shadow-origin-step 0, 0.03125, 0.0625, 0.125, 0.25 x raster
#     conservative-hardware and plain: how much the origin's room (less resolution) buys:
#     shadow_cost_origin_step.json.
#  3. caster culling off, cache off, the six rasters (against 1's cache-off rows: what culling alone
#     saves): shadow_cost_culling.json.
#  4. the hardware conservative and split rows (cache off, culling on) with fragment shaders that
#     write no depth: what the depth export costs: shadow_cost_no_depth_write.json / .md.
#  0. --shadow-redraw-budget 0, 1, 2 (default), 3, 4 on the default settings, and plain and split at
#     the default budget: the same per-frame statistics, tiles lagging behind their new square and
#     quarters drawn: shadow_cost_budget.json -> OUTDIR/shadow_cost_budget.md. BUDGET_ONLY=1 runs
#     the gl_tests and this alone (about 2 minutes).
#  5. --shadow-cache on x --shadow-scroll on,off x conservative-hardware (the default), split-hardware
#     and plain, 600 frames after 20 (the 8 s path and more): per frame the two suns' shadow passes
#     summed; mean, median, 99th percentile and maximum, tiles kept / scrolled / drawn whole per
#     cascade: shadow_cost_scroll.json -> OUTDIR/shadow_cost_scroll.md (also at the top of
#     shadow_cost.md); then conservative-hardware with scroll on at --shadow-origin-step 1/32, and
#     --shadow-size-hold on with scroll on and off: shadow_cost_scroll_variants.json. Runs first;
#     SCROLL_ONLY=1 runs the gl_tests and this alone (about 3 minutes).
# Per variant: the shadow passes' GPU ms summed (median of 200 frames after 20) against the floor
# of drawing every atlas texel every frame (depth bytes at the fragment fill, --floors), the share
# of cascade tiles kept from an earlier frame (per cascade), the triangles each cascade drew
# ('graph --explain' at t = 1 s) and the frame. The gl_tests log has the compute rasteriser's depth
# against the plain raster on this driver (ulps and coverage), the crease test, the hardware raster's
# atlas against the geometry shader's and plain's, and the cache's exactness tests. About 8 minutes.
# From the repository root on the GPU machine:
#   bench/shadow_cost.sh BUNDLE OUTDIR    (BUNDLE: run, gl_tests, lib/; needs ../shared/assets)
# Writes OUTDIR/shadow_cost*.json (lightpass bench), OUTDIR/explain_*.txt, OUTDIR/shadow_cost.md
# (bench/summarize_shadow_cost.py), OUTDIR/auto_choice.txt (what --shadow-raster auto measured and
# chose) and OUTDIR/shadow_cost_no_depth_write.md.
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
S=scenes/gallery-flythrough.json
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
$B/run info > $R/info.txt 2>&1; grep "shadow casters" $R/info.txt
LD_LIBRARY_PATH=$B/lib $B/gl_tests --gtest_brief=1 \
  --gtest_filter='ShadowCasterCulling*:ShadowComputeRaster*:ShadowRender.ConcaveCorner*:ShadowConservativeRaster*:ShaderShadowCasterDepth*:ShadowCache*:ShadowRedrawBudget*' \
  > $R/gl_tests_shadow_cost.txt 2>&1
tail -3 $R/gl_tests_shadow_cost.txt
grep " ulps " $R/gl_tests_shadow_cost.txt | tee $R/compute_raster_vs_plain.txt
grep -E "conservative raster|SKIPPED" $R/gl_tests_shadow_cost.txt | tee $R/conservative_raster_tests.txt
grep "tiles scrolled over the walk" $R/gl_tests_shadow_cost.txt | tee $R/scroll_vs_redraw.txt
grep -E "redraw budget|FAILED" $R/gl_tests_shadow_cost.txt | tee $R/redraw_budget_tests.txt
COMMON="--shadow-size 2048 --shadow-cascades 4"
# 0. --shadow-redraw-budget (BUDGET_ONLY=1: the gl_tests above and this alone, about 2 minutes):
#    default settings (cache, scroll, hardware conservative where the GPU has it) with the budget at
#    0 (resized squares drawn whole at once, as before), 1, 2 (the default), 3 and 4 quarter tiles a
#    frame (a scroll is a unit too), budgets 1 and 2 with --shadow-scroll off, 600 frames after 20;
#    then plain and split at the default budget: per frame the two suns'
#    shadow passes summed -> shadow_cost_budget.json, OUTDIR/shadow_cost_budget.md.
$B/run graph --scene $S --size 1920x1080 --time 1 $COMMON --explain > $R/explain_default.txt 2>&1
$B/run bench --scene $S --time 1 --fps 60 --frames 600 --warmup 20 --size 1920x1080 $COMMON \
  --vary '--shadow-redraw-budget 0|--shadow-redraw-budget 1|--shadow-redraw-budget 2|--shadow-redraw-budget 3|--shadow-redraw-budget 4|--shadow-redraw-budget 1 --shadow-scroll off|--shadow-redraw-budget 2 --shadow-scroll off|--shadow-raster plain|--shadow-raster split' \
  --timings-json $R/shadow_cost_budget.json -q > /dev/null 2> $R/bench_budget_progress.txt \
  || { echo "budget bench failed"; tail -3 $R/bench_budget_progress.txt; }
python3 bench/summarize_shadow_cost.py $R/shadow_cost_budget.json --outdir $R | tee $R/shadow_cost_budget.md
[ "${BUDGET_ONLY:-0}" = 1 ] && exit 0
# Rasters: NAME FLAGS (the explain files and the table's rows are named by NAME).
RASTERS=("conservative-hardware|--shadow-raster conservative --shadow-conservative hardware"
         "conservative-geometry-shader|--shadow-raster conservative --shadow-conservative geometry-shader"
         "split-hardware|--shadow-raster split --shadow-conservative hardware"
         "split-geometry-shader|--shadow-raster split --shadow-conservative geometry-shader"
         "plain|--shadow-raster plain" "compute|--shadow-raster compute")
VARY=""
for r in "${RASTERS[@]}"; do VARY="$VARY${VARY:+|}${r#*|}"; done
for cull in shadow-culling no-shadow-culling; do for r in "${RASTERS[@]}"; do
  $B/run graph --scene $S --size 1920x1080 --time 1 $COMMON --$cull ${r#*|} --explain > $R/explain_${cull}_${r%%|*}.txt 2>&1
done; done
# --shadow-raster auto's own start-up measurement on this GPU (a fresh cache), beside the table.
LIGHTPASS_CACHE_DIR=$R/auto_cache $B/run render --scene $S --size 1920x1080 --time 1 $COMMON --shadow-raster auto \
  --out $R/auto.png 2>&1 | grep "shadow raster auto" | tee $R/auto_choice.txt
BENCH="$B/run bench --scene $S --time 1 --fps 60 --frames 200 --warmup 20 --floors --size 1920x1080 $COMMON"
# 5. Scrolling cascades: the frame-by-frame cost (what a frame that moves the near squares pays).
$B/run bench --scene $S --time 1 --fps 60 --frames 600 --warmup 20 --size 1920x1080 $COMMON --shadow-cache on \
  --vary '--shadow-scroll on,off' \
  --vary '--shadow-raster conservative --shadow-conservative hardware|--shadow-raster split --shadow-conservative hardware|--shadow-raster plain' \
  --timings-json $R/shadow_cost_scroll.json -q > /dev/null 2> $R/bench_scroll_progress.txt \
  || { echo "scroll bench failed"; tail -3 $R/bench_scroll_progress.txt; }
# A finer origin step (resolution back, more and narrower scrolls), and squares that hold their size
# (--shadow-size-hold: fewer whole redraws on the path's zoom) with scrolling on and off.
$B/run bench --scene $S --time 1 --fps 60 --frames 600 --warmup 20 --size 1920x1080 $COMMON --shadow-cache on \
  --shadow-raster conservative --shadow-conservative hardware \
  --vary '--shadow-scroll on --shadow-origin-step 0.03125|--shadow-scroll on --shadow-size-hold on|--shadow-scroll off --shadow-size-hold on' \
  --timings-json $R/shadow_cost_scroll_variants.json -q > /dev/null 2>> $R/bench_scroll_progress.txt \
  || { echo "scroll origin-step bench failed"; tail -3 $R/bench_scroll_progress.txt; }
python3 bench/summarize_shadow_cost.py $R/shadow_cost_scroll.json $R/shadow_cost_scroll_variants.json --outdir $R \
  | tee $R/shadow_cost_scroll.md
[ "${SCROLL_ONLY:-0}" = 1 ] && exit 0
$BENCH --vary '--shadow-cache off,on' --vary "$VARY" \
  --timings-json $R/shadow_cost.json -q > /dev/null 2> $R/bench_progress.txt || { echo "bench failed"; tail -3 $R/bench_progress.txt; }
$BENCH --shadow-cache on --vary '--shadow-origin-step 0,0.03125,0.0625,0.125,0.25' \
  --vary '--shadow-raster conservative --shadow-conservative hardware|--shadow-raster plain' \
  --timings-json $R/shadow_cost_origin_step.json -q > /dev/null 2>> $R/bench_progress.txt || { echo "bench failed"; tail -3 $R/bench_progress.txt; }
$BENCH --shadow-cache off --no-shadow-culling --vary "$VARY" \
  --timings-json $R/shadow_cost_culling.json -q > /dev/null 2>> $R/bench_progress.txt || { echo "bench failed"; tail -3 $R/bench_progress.txt; }
python3 bench/summarize_shadow_cost.py $R/shadow_cost_scroll.json $R/shadow_cost_scroll_variants.json $R/shadow_cost.json $R/shadow_cost_origin_step.json $R/shadow_cost_culling.json \
  --outdir $R | tee $R/shadow_cost.md
# What the hardware conservative raster's time is made of (cache off, culling on): the same draws
# (conservative coverage, one draw per facing, the faces away offset nearer) with fragment shaders
# that write no depth, from a patched copy of shaders/ through $LIGHTPASS_SHADER_DIR. A measurement
# only: its atlas holds rasterised depths (it leaks); the difference to the rows above is the depth
# export and what it costs the early depth test. Where the GPU lacks the hardware raster the rows fall back.
P=$R/shaders_no_depth_write; rm -rf $P; cp -r shaders $P
sed -i -e 's/^layout(depth_greater) out float gl_FragDepth;$//' \
  -e 's/^    gl_FragDepth = conservativeCasterDepth(centre,/    float unwritten = conservativeCasterDepth(centre,/' \
  -e 's/^    gl_FragDepth = max(conservativeCasterDepth(gl_FragCoord.z,/    float unwritten = max(conservativeCasterDepth(gl_FragCoord.z,/' \
  $P/shadow_depth.frag
if [ "$(grep -c 'float unwritten' $P/shadow_depth.frag)" = 2 ] && ! grep -q 'depth_greater) out' $P/shadow_depth.frag; then
  LIGHTPASS_SHADER_DIR=$P $BENCH --shadow-cache off --shadow-culling \
    --vary '--shadow-raster conservative --shadow-conservative hardware|--shadow-raster split --shadow-conservative hardware' \
    --timings-json $R/shadow_cost_no_depth_write.json -q > /dev/null 2> $R/bench_no_depth_write_progress.txt \
    && { echo "Hardware conservative raster without the depth write (patched shaders: timing only, the atlas is wrong)"
         python3 bench/summarize_shadow_cost.py $R/shadow_cost_no_depth_write.json --outdir $R; } | tee $R/shadow_cost_no_depth_write.md \
    || { echo "no-depth-write bench failed"; tail -3 $R/bench_no_depth_write_progress.txt; }
else
  echo "shaders/shadow_depth.frag changed shape: the no-depth-write breakdown is skipped"
fi
