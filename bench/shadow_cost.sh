#!/bin/bash
# Cost of the sun cascades on a moving camera: the gallery's two suns x 4 cascades of 2048^2 at
# 1920x1080, on scenes/gallery-flythrough.json's camera path (frames at 60 fps from t = 1 s, so every
# frame has a new camera and new cascades).
#  1. --shadow-cache off / on x caster raster conservative, split, plain and compute (culling on,
#     the default --shadow-origin-step): shadow_cost.json.
#  2. --shadow-cache on x --shadow-origin-step 0, 0.03125, 0.0625, 0.125, 0.25 x raster conservative and
#     plain: how much the origin's room (less resolution) buys: shadow_cost_origin_step.json.
#  3. caster culling on / off, cache off (what culling alone saves): shadow_cost_culling.json.
# Per variant: the shadow passes' GPU ms summed (median of 300 frames after 30) against the floor
# of drawing every atlas texel every frame (depth bytes at the fragment fill, --floors), the share
# of cascade tiles kept from an earlier frame (per cascade), the triangles each cascade drew
# ('graph --explain' at t = 1 s) and the frame. The gl_tests log has the compute rasteriser's depth
# against the plain raster on this driver (ulps and coverage) and the cache's exactness tests.
# From the repository root on the GPU machine:
#   bench/shadow_cost.sh BUNDLE OUTDIR    (BUNDLE: run, gl_tests, lib/; needs ../shared/assets)
# Writes OUTDIR/shadow_cost*.json (lightpass bench), OUTDIR/explain_*.txt, OUTDIR/shadow_cost.md
# (bench/summarize_shadow_cost.py) and OUTDIR/auto_choice.txt (what --shadow-raster auto measured and chose).
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
S=scenes/gallery-flythrough.json
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
LD_LIBRARY_PATH=$B/lib $B/gl_tests --gtest_brief=1 \
  --gtest_filter='ShadowCasterCulling*:ShadowComputeRaster*:ShadowRender.ConcaveCorner*:ShadowCache*' \
  > $R/gl_tests_shadow_cost.txt 2>&1
tail -3 $R/gl_tests_shadow_cost.txt
grep " ulps " $R/gl_tests_shadow_cost.txt | tee $R/compute_raster_vs_plain.txt
COMMON="--shadow-size 2048 --shadow-cascades 4"
for cull in shadow-culling no-shadow-culling; do for raster in conservative split plain compute; do
  $B/run graph --scene $S --size 1920x1080 --time 1 $COMMON --$cull --shadow-raster $raster --explain > $R/explain_${cull}_$raster.txt 2>&1
done; done
# --shadow-raster auto's own start-up measurement on this GPU (a fresh cache), beside the table.
LIGHTPASS_CACHE_DIR=$R/auto_cache $B/run render --scene $S --size 1920x1080 --time 1 $COMMON --shadow-raster auto \
  --out $R/auto.png 2>&1 | grep "shadow raster auto" | tee $R/auto_choice.txt
BENCH="$B/run bench --scene $S --time 1 --fps 60 --frames 300 --warmup 30 --floors --size 1920x1080 $COMMON"
$BENCH --vary '--shadow-cache off,on' --vary '--shadow-raster conservative,split,plain,compute' \
  --timings-json $R/shadow_cost.json -q > /dev/null 2> $R/bench_progress.txt || { echo "bench failed"; tail -3 $R/bench_progress.txt; }
$BENCH --shadow-cache on --vary '--shadow-origin-step 0,0.03125,0.0625,0.125,0.25' --vary '--shadow-raster conservative,plain' \
  --timings-json $R/shadow_cost_origin_step.json -q > /dev/null 2>> $R/bench_progress.txt || { echo "bench failed"; tail -3 $R/bench_progress.txt; }
$BENCH --shadow-cache off --vary '--shadow-culling|--no-shadow-culling' --vary '--shadow-raster conservative,plain' \
  --timings-json $R/shadow_cost_culling.json -q > /dev/null 2>> $R/bench_progress.txt || { echo "bench failed"; tail -3 $R/bench_progress.txt; }
python3 bench/summarize_shadow_cost.py $R/shadow_cost.json $R/shadow_cost_origin_step.json $R/shadow_cost_culling.json \
  --outdir $R | tee $R/shadow_cost.md
