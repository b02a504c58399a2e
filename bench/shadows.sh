#!/bin/bash
# Shadow-map cost before/after the cascade fitting, on the GPU: the Cornell box and the gallery at
# 1920x1080, --shadow-cascades 1..4, shadow pass GPU ms (median of 200 frames after 30) with its
# floor (--floors), for the new build (run) and the old one (run-base), interleaved base, new, base,
# new. Also `graph --explain` of both scenes (which cascades were dropped and why). From the
# repository root on the GPU machine:
#   bench/shadows.sh BUNDLE OUTDIR      (BUNDLE: run, run-base, lib/; the gallery needs ../shared/assets)
# Table: OUTDIR/shadows.md.
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
for s in cornell gallery; do $B/run graph --scene scenes/$s.json --explain > $R/graph_$s.txt 2>&1; done
for round in 1 2; do for v in base new; do
  LP=$B/run; [ $v = base ] && LP=$B/run-base
  [ -x "$LP" ] || continue
  for s in cornell gallery; do
    $LP bench --scene scenes/$s.json --size 1920x1080 --frames 200 --warmup 30 --floors \
      --vary '--shadow-cascades 1,2,3,4' --timings-json $R/$v${round}_$s.json -q > $R/$v${round}_$s.log 2>&1 \
      || echo "bench $v $s failed (see $R/$v${round}_$s.log)"
  done
done; done
python3 - $R <<'PY'
import glob, json, os, sys
R = sys.argv[1]
lines = ["# Shadow passes, GPU ms (median; floor in brackets)", "",
         "| run | scene | flags | shadow passes ms | frame ms |", "| --- | --- | --- | ---: | ---: |"]
for path in sorted(glob.glob(f"{R}/*_*.json")):
    run, scene = os.path.basename(path)[:-5].split("_", 1)
    for r in json.load(open(path))["runs"]:
        p = r["passes"]
        shadow = [v for k, v in p.items() if k.startswith("shadow_map")]
        ms = sum(v["median_ms"] for v in shadow)
        floor = sum(v.get("floor_ms") or 0.0 for v in shadow)
        lines.append(f"| {run} | {scene} | {r['flags']} | {ms:.3f} ({floor:.3f}) | {p['frame']['median_ms']:.3f} |")
open(f"{R}/shadows.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
