#!/bin/bash
# Ambient occlusion's cost on the GPU: its passes ("ao_depth", "ao" (GTAO), "ao_blur", "ao_denoise")
# at 1920x1080 and 3840x2160, half and full size, the default setting (2 directions x 8 steps, 1 m)
# and a heavier one (4 x 8, 2 m), each against its floor (engine/render/floors: the bytes it moves at
# the compute copy bandwidth). The issue's budget: the AO passes together <= 0.3 ms at 1080p and
# <= 1 ms at 4K (default setting). Scenes: cornell and gallery with IBL on. From the repository root
# on the GPU machine:
#   bench/ao.sh BUNDLE OUTDIR    (BUNDLE: run, gl_tests, lib/; the gallery needs ../shared/assets)
# Writes OUTDIR/ao_<scene>.json (lightpass bench) and OUTDIR/ao.md (the table).
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
LD_LIBRARY_PATH=$B/lib $B/gl_tests --gtest_brief=1 --gtest_filter='*AmbientOcclusion*' > $R/gl_tests_ao.txt 2>&1
tail -3 $R/gl_tests_ao.txt
$B/run --version
settings='--ao-resolution half|--ao-resolution full|--ao-resolution half --ao-directions 4 --ao-steps 8 --ao-radius 2|--ao-resolution full --ao-directions 4 --ao-steps 8 --ao-radius 2|--no-ao'
for s in cornell gallery; do
  $B/run bench --scene scenes/$s.json --ibl --frames 200 --warmup 30 --floors --vary "$settings" \
    --vary '--size 1920x1080,3840x2160' --timings-json $R/ao_$s.json -q > $R/ao_$s.log 2>&1 || echo "bench $s failed (see $R/ao_$s.log)"
done
python3 - $R <<'PY' | tee $R/ao.md
import json, os, sys
R = sys.argv[1]
PASSES = ("ao_depth", "ao", "ao_blur", "ao_denoise")
print("| scene | flags | " + " | ".join(f"{n} ms (floor)" for n in PASSES) + " | AO total ms | budget | frame ms |")
print("| --- | --- | " + "---: | " * len(PASSES) + "---: | --- | ---: |")
for scene in ["cornell", "gallery"]:
    path = f"{R}/ao_{scene}.json"
    if not os.path.isfile(path):
        continue
    for run in json.load(open(path))["runs"]:
        p = run["passes"]
        def cell(name):
            if name not in p:
                return "-"
            v = p[name]
            floor = v.get("floor_ms")
            return f"{v['median_ms']:.4f} ({floor:.4f})" if floor else f"{v['median_ms']:.4f}"
        total = sum(p[n]["median_ms"] for n in PASSES if n in p)
        budget = 1.0 if "3840x2160" in run["flags"] else 0.3
        verdict = "-" if "--no-ao" in run["flags"] else ("ok" if total <= budget else "OVER") + f" (<= {budget} ms)"
        print(f"| {scene} | {run['flags']} | " + " | ".join(cell(n) for n in PASSES) + f" | {total:.4f} | {verdict} | "
              f"{p['frame']['median_ms']:.3f} |")
PY
