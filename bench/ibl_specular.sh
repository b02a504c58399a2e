#!/bin/bash
# Cost of the specular IBL method on the GPU: the "ibl" pass (deferred; split sum or per-pixel GGX
# samples of the prefiltered chain, --ibl-specular sampled --ibl-specular-samples N) and forward+'s
# "forward_opaque" (which evaluates the same IBL per fragment), at 1920x1080 and 3840x2160, for the
# split sum and 4, 8, 16, 32, 64 samples. Scenes: gallery (IBL on every surface) and the Mitsuba
# sphere grid under the 50,000 lamp (bench/mitsuba/scenes/lamp50k.json). The accuracy side of the
# trade is bench/results/mitsuba/2026-11-24_ibl-against-mitsuba/sampled_specular.md. From the repository root on the GPU machine:
#   bench/ibl_specular.sh BUNDLE OUTDIR    (BUNDLE: run, gl_tests, lib/; the gallery needs ../shared/assets)
# Writes OUTDIR/ibl_specular_<scene>.json (lightpass bench) and OUTDIR/ibl_specular.md (the table), and
# for light extraction (0 or 4 sources lit analytically) OUTDIR/ibl_extract_<scene>.json and OUTDIR/ibl_extract.md.
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
LD_LIBRARY_PATH=$B/lib $B/gl_tests --gtest_brief=1 --gtest_filter='*Ibl*:*Forward*' > $R/gl_tests_ibl.txt 2>&1
tail -3 $R/gl_tests_ibl.txt
settings='--ibl-specular split-sum'
for n in 4 8 16 32 64; do settings="$settings|--ibl-specular sampled --ibl-specular-samples $n"; done
for s in scenes/gallery.json bench/mitsuba/scenes/lamp50k.json; do
  name=$(basename $s .json)
  $B/run bench --scene $s --ibl --brdf ggx --frames 200 --warmup 30 --vary "$settings" \
    --vary '--size 1920x1080,3840x2160' --vary '--render-path deferred,forward+' \
    --timings-json $R/ibl_specular_$name.json -q > $R/ibl_specular_$name.log 2>&1 ||
    echo "bench $name failed (see $R/ibl_specular_$name.log)"
done
# Light extraction (--ibl-extract-lights): the extracted sources are a few directional lights per pixel
# in the ibl pass and forward+'s forward_opaque. lamp50k extracts 1, royal_esplanade_1k 4 (the most).
for s in bench/mitsuba/scenes/lamp50k.json bench/mitsuba/scenes/royal_esplanade_1k.json; do
  name=$(basename $s .json)
  $B/run bench --scene $s --ibl --brdf ggx --frames 200 --warmup 30 --vary '--ibl-extract-lights 0,4' \
    --vary '--ibl-specular split-sum|--ibl-specular sampled --ibl-specular-samples 64' \
    --vary '--size 1920x1080,3840x2160' --vary '--render-path deferred,forward+' \
    --timings-json $R/ibl_extract_$name.json -q > $R/ibl_extract_$name.log 2>&1 ||
    echo "bench extract $name failed (see $R/ibl_extract_$name.log)"
done
# The two tables: OUTDIR/ibl_specular.md (specular methods) and OUTDIR/ibl_extract.md (extracted lights).
python3 - $R <<'PY'
import sys
sys.path.insert(0, "bench")
from ibl_runs import flag_value, table
R = sys.argv[1]
lights = [("extracted lights", lambda f: flag_value(f, "--ibl-extract-lights"))]
passes = ["ibl", "forward_opaque", "frame"]
print(table(f"{R}/ibl_extract.md", [(s, f"{R}/ibl_extract_{s}.json") for s in ["lamp50k", "royal_esplanade_1k"]],
            lights, passes))
print(table(f"{R}/ibl_specular.md", [(s, f"{R}/ibl_specular_{s}.json") for s in ["gallery", "lamp50k"]], [], passes))
PY
