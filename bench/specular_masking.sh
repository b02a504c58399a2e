#!/bin/bash
# Cost of the GGX masking model on the GPU (--specular-masking separable|height-correlated): the passes
# that evaluate GGX's Smith term per pixel, "global_lights" (suns, --brdf ggx), "ibl" (the extracted
# lights and, with --ibl-specular sampled, its per-sample weights) and forward+'s "forward_opaque", plus
# the DFG LUT's bake (once per masking change; lightpass sweep reports the bake's GPU ms). Scenes: the
# Mitsuba sphere grid under royal_esplanade_1k (4 extracted lights) and the Cornell box with its sun,
# GGX, IBL on; 1920x1080 and 3840x2160, deferred and forward+, split sum and sampled 64.
# From the repository root on the GPU machine:
#   bench/specular_masking.sh BUNDLE OUTDIR    (BUNDLE: run, gl_tests, lib/)
# Writes OUTDIR/specular_masking_<scene>.json (lightpass bench), OUTDIR/gl_tests_masking.txt (the
# masking tests on the driver) and OUTDIR/specular_masking.md (the table: median ms per pass).
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
LD_LIBRARY_PATH=$B/lib $B/gl_tests --gtest_brief=1 \
  --gtest_filter='*Masking*:ShaderGgx.*:Ibl.WhiteFurnace*:Ibl.Dfg*:Ibl.SampledSpecular*' > $R/gl_tests_masking.txt 2>&1
tail -3 $R/gl_tests_masking.txt
for s in bench/mitsuba/scenes/royal_esplanade_1k.json scenes/cornell.json; do
  name=$(basename $s .json)
  $B/run bench --scene $s --ibl --brdf ggx --frames 200 --warmup 30 \
    --vary '--specular-masking separable,height-correlated' \
    --vary '--ibl-specular split-sum|--ibl-specular sampled --ibl-specular-samples 64' \
    --vary '--size 1920x1080,3840x2160' --vary '--render-path deferred,forward+' \
    --timings-json $R/specular_masking_$name.json -q > $R/specular_masking_$name.log 2>&1 ||
    echo "bench $name failed (see $R/specular_masking_$name.log)"
done
$B/run sweep --scene bench/mitsuba/scenes/royal_esplanade_1k.json --size 1920x1080 --frames 50 \
  --knob specular-masking --out-dir $R/sweep -q > $R/sweep.log 2>&1 || echo "sweep failed (see $R/sweep.log)"
python3 - $R <<'PY'
import sys
sys.path.insert(0, "bench")
from ibl_runs import table
R = sys.argv[1]
masking = [("masking", lambda f: "height-correlated" if "height-correlated" in f else "separable")]
print(table(f"{R}/specular_masking.md",
            [(s, f"{R}/specular_masking_{s}.json") for s in ["royal_esplanade_1k", "cornell"]], masking,
            ["global_lights", "ibl", "forward_opaque", "frame"]))
PY
