#!/bin/bash
# IBL bake cost per GGX sample count, on the GPU: the `ibl-samples` sweep (64, 256, 1024, 4096; each
# value bakes afresh after an untimed warm-up bake, `ibl_bake_gpu_ms` in sweep.csv) under the lamp
# map of the Mitsuba comparison (a 50,000 lamp) and royal_esplanade, plus the same for the old build
# (run-base) where the bundle has one. Run from the repository root on the GPU machine:
#   bench/ibl_bake.sh BUNDLE OUTDIR      (BUNDLE: run [, run-base], lib/)
# Table: OUTDIR/ibl_bake.md (bake GPU ms per sample count, per build and map). The error side of the
# trade (sphere means against Mitsuba per sample count) is in bench/results/mitsuba/2026-11-24_ibl-against-mitsuba/README.md.
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
for v in new base; do
  LP=$B/run; [ $v = base ] && LP=$B/run-base
  [ -x "$LP" ] || continue
  for s in lamp50k royal_esplanade_1k; do
    $LP sweep --scene bench/mitsuba/scenes/$s.json --ibl --brdf ggx --knob ibl-samples --size 1920x1080 --frames 30 \
      --out-dir $R/$v-$s -q > $R/$v-$s.log 2>&1 || echo "sweep $v $s failed (see $R/$v-$s.log)"
  done
done
python3 - $R <<'PY'
import csv, glob, os, sys
R = sys.argv[1]
lines = ["# IBL bake GPU ms per --ibl-samples", "", "| build | map | samples | bake GPU ms | frame ms | RMSE vs 4096 |",
         "| --- | --- | ---: | ---: | ---: | ---: |"]
for path in sorted(glob.glob(f"{R}/*/sweep.csv")):
    build, scene = os.path.basename(os.path.dirname(path)).split("-", 1)
    for r in csv.DictReader(open(path)):
        lines.append(f"| {build} | {scene} | {r['value']} | {float(r.get('ibl_bake_gpu_ms') or 0):.3f} | "
                     f"{float(r['frame_ms']):.3f} | {float(r['rmse']):.3g} |")
open(f"{R}/ibl_bake.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
