#!/bin/bash
# What each shadow filter (--pcf off|3x3|5x5|poisson) costs on the GPU, in the deferred path's compute
# (global_lights: the suns and their shadows) and in forward+'s fragments (forward_opaque), on the
# gallery (two suns x 4 cascades; needs ../shared/assets) at 1080p and 4K, one local light, the
# shadow cache on (the maps themselves cost the same for every filter). From the repository root:
#   bench/shadow_filter.sh BUNDLE OUTDIR    (BUNDLE: run, lib/)
# Writes OUTDIR/shadow_filter_<filter>.json (lightpass bench) and OUTDIR/shadow_filter.md: median
# GPU ms of each pass and the frame, and global_lights against its floor (--floors).
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p "$R"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$R/device.txt" 2>/dev/null
$B/run --version
# A throwaway run first: a process's first variant could still be warming up after 10 frames (off at
# 1080p once took 0.173 ms against 0.064, with a 4.9 ms frame).
$B/run bench --scene scenes/gallery.json --frames 60 --warmup 30 --light-count 1 --vary '--size 1920x1080' -q \
  > /dev/null 2>&1
for f in off 3x3 5x5 poisson; do
  $B/run bench --scene scenes/gallery.json --frames 60 --warmup 30 --max-seconds 3 --min-frames 3 --light-count 1 \
    --pcf $f --floors --vary '--render-path deferred|--render-path forward+' --vary '--size 1920x1080,3840x2160' \
    --timings-json "$R/shadow_filter_$f.json" -q > "$R/shadow_filter_$f.log" 2>&1 \
    || echo "bench --pcf $f failed (see $R/shadow_filter_$f.log)"
done
python3 - "$R" <<'PY' | tee "$R/shadow_filter.md"
import json, os, re, sys
out = sys.argv[1]
print("| filter | size | deferred: global_lights ms (× floor) | deferred frame | forward+: forward_opaque ms | forward+ frame |")
print("| --- | --- | ---: | ---: | ---: | ---: |")
for f in ("off", "3x3", "5x5", "poisson"):
    try:
        runs = json.load(open(os.path.join(out, f"shadow_filter_{f}.json")))["runs"]
    except (OSError, ValueError) as e:
        print(f"| {f} | not readable: {e} | | | | |")
        continue
    cells = {}
    for r in runs:
        path = "forward+" if "--render-path forward+" in r["flags"] else "deferred"
        cells[(f"{r['width']}x{r['height']}", path)] = r["passes"]
    for size in ("1920x1080", "3840x2160"):
        d, fw = cells.get((size, "deferred"), {}), cells.get((size, "forward+"), {})
        g = d.get("global_lights", {})
        floor = g.get("floor_ms")
        gl = f"{g['median_ms']:.3f}" + (f" ({g['median_ms'] / floor:.1f}×)" if floor else "") if g else "-"
        ms = lambda p, k: f"{p[k]['median_ms']:.3f}" if k in p else "-"
        print(f"| {f} | {size} | {gl} | {ms(d, 'frame')} | {ms(fw, 'forward_opaque')} | {ms(fw, 'frame')} |")
PY
