#!/bin/bash
# Auto exposure's cost and the new views' passes on the GPU, plus the GL tests (built with the GL
# state check) and CUDA tests on that driver. From the repository root:
#   bench/views_exposure.sh BUNDLE OUTDIR    (BUNDLE: run, gl_tests, cuda_tests, lib/)
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
LD_LIBRARY_PATH=$B/lib $B/gl_tests --gtest_brief=1 > $R/gl_tests.txt 2>&1; tail -4 $R/gl_tests.txt
LD_LIBRARY_PATH=$B/lib $B/cuda_tests > $R/cuda_tests.txt 2>&1; tail -2 $R/cuda_tests.txt
$B/run --version
for s in cornell gallery; do
  $B/run bench --scene scenes/$s.json --frames 200 --warmup 30 --floors --vary '--exposure 0|--auto-exposure' \
    --vary '--size 1920x1080,3840x2160' --timings-json $R/auto_exposure_$s.json -q > /dev/null 2>&1 || echo "bench $s failed"
done
$B/run bench --scene scenes/gallery.json --frames 100 --warmup 10 --floors --size 1920x1080 \
  --vary '--view final,invalid-pixels,exposure-ev,world-position,eye-vector,depth-fitted' --timings-json $R/views_gallery.json -q > /dev/null 2>&1 || echo "bench views failed"
python3 - $R <<'PY'
import json, sys
R = sys.argv[1]
for name in ["auto_exposure_cornell", "auto_exposure_gallery", "views_gallery"]:
    d = json.load(open(f"{R}/{name}.json"))
    for run in d["runs"]:
        p = run["passes"]
        extra = {k: (round(v["median_ms"], 4), round(v["median_ms"] / v["floor_ms"], 1) if v.get("floor_ms") else None)
                 for k, v in p.items() if k in ("auto_exposure", "tonemap", "hdr_view", "debug_view")}
        print(name, run["flags"], "frame", round(p["frame"]["median_ms"], 3), extra)
PY
