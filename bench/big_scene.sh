#!/bin/bash
# Big instanced scenes (issue #44; docs/performance.md, "Big scenes"): does the frame grow with the
# triangles in view or with the triangles stored and drawn? scripts/make_big_scene.py writes, for
# the Stanford dragon (100k triangles, from ../shared/assets) stored once:
#   big_10m    10M triangles drawn, 5M of them in view, the rest hidden behind a wall and the camera
#   big_100m   100M triangles drawn, the same 5M in view (the same image)
# each with a turning sun and eight spinning dragons (no cache can hold), and the same scenes
# --still (sun and dragons still). Every scene is timed at 1920x1080 and 3840x2160, 200 frames after
# 20 at 60 frames a second of scene time (the sun turns 0.2 rad/s). The table (OUTDIR/big_scene.md):
# median GPU ms of the frame and of each pass over 0.05 ms, CPU submit ms, wall/GPU, and the ratio
# 100M / 10M (the target: within 1.5x while nothing culls the hidden copies, this measures what
# culling has to win). OUTDIR/explain_*.txt: what each pass draws. About 6 minutes on an H100.
# From the repository root on the GPU machine:
#   bench/big_scene.sh BUNDLE OUTDIR    (BUNDLE: run, lib/; ../shared/assets beside the repository)
# MODEL=sphere needs no assets; FRAMES, WARMUP and SIZES shrink it for a dry run.
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null | tee $R/device.txt
MODEL=${MODEL:-dragon}
SIZES=${SIZES:-1920x1080 3840x2160}
for n in 10M 100M; do
  python3 scripts/make_big_scene.py --triangles $n --visible-triangles 5M --model $MODEL --out $R/big_$n.json || exit 1
  python3 scripts/make_big_scene.py --triangles $n --visible-triangles 5M --model $MODEL --still --out $R/big_${n}_still.json || exit 1
done
for scene in big_10M big_100M big_10M_still big_100M_still; do
  $B/run graph --scene $R/$scene.json --size 1920x1080 --explain > $R/explain_$scene.txt 2>&1
  for size in $SIZES; do
    $B/run bench --scene $R/$scene.json --size $size --frames ${FRAMES:-200} --warmup ${WARMUP:-20} --fps 60 -q \
      --timings-json $R/${scene}_$size.json > /dev/null 2> $R/progress_${scene}_$size.txt \
      || { echo "bench $scene $size failed"; tail -3 $R/progress_${scene}_$size.txt; }
  done
done
python3 - "$R" $SIZES <<'PY'
import json, sys
R, sizes = sys.argv[1], sys.argv[2:]
def run(scene, size):
    try:
        return json.load(open(f"{R}/{scene}_{size}.json"))["runs"][0]
    except (OSError, KeyError, ValueError, IndexError):
        return None
rows = ["| scene | size | frame GPU ms | CPU submit ms | wall / GPU | 100M / 10M | passes over 0.05 ms |",
        "| --- | --- | ---: | ---: | ---: | ---: | --- |"]
for kind in ["", "_still"]:
    for size in sizes:
        base = run(f"big_10M{kind}", size)
        for n in ["10M", "100M"]:
            r = run(f"big_{n}{kind}", size)
            if not r:
                rows.append(f"| big_{n}{kind} | {size} | missing | | | | |"); continue
            frame = r["passes"]["frame"]["median_ms"]
            cpu = r.get("cpu", {})
            ratio = frame / base["passes"]["frame"]["median_ms"] if base else float("nan")
            passes = ", ".join(f"{k} {v['median_ms']:.2f}" for k, v in sorted(r["passes"].items(), key=lambda kv: -kv[1]["median_ms"])
                               if k != "frame" and v["median_ms"] > 0.05)
            rows.append(f"| big_{n}{kind} | {size} | {frame:.3f} | {cpu.get('submit_median_ms', float('nan')):.3f} | "
                        f"{cpu.get('wall_over_gpu', float('nan')):.3f} | {ratio:.2f} | {passes} |")
open(f"{R}/big_scene.md", "w").write("\n".join(rows) + "\n")
print("\n".join(rows))
PY
