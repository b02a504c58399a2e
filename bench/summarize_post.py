#!/usr/bin/env python3
"""Turns bench/post_effects.sh's `render --timings-json` files into one Markdown table.

Per run (named VARIANT_WxH[_kK]): the effect's time (GL timer queries for GLSL passes; CUDA events
for CUDA kernels, whose GL pass time also holds the interop map/unmap and a synchronisation), its
floor (bytes the passes must move over the measured compute copy bandwidth) and measured/floor."""
import json
import os
import sys


def median(run, name):
    p = run["passes"].get(name)
    return p["median_ms"] if p else None


def floor(run, name):
    p = run["passes"].get(name)
    return p.get("floor_ms") if p else None


def fmt(x):
    return "-" if x is None else f"{x:.4f}"


def main(paths):
    rows = []
    device = None
    for path in paths:
        run = json.load(open(path))
        device = device or run.get("device")
        parts = os.path.basename(path)[:-5].split("_")
        variant, size = parts[0], parts[1]
        kernel = parts[2][1:] if len(parts) > 2 else "-"
        effect = ["toon"] if "toon" in variant else ["bloom", "bloom_composite"]
        cuda = variant.startswith("cuda")
        times = [median(run, f"{n} (cuda kernels)" if cuda else n) for n in effect]
        gl_times = [median(run, n) for n in effect]
        interop = [median(run, f"{n} (cuda interop)") for n in effect] if cuda else [None]
        floors = [floor(run, n) for n in effect]
        total = sum(t for t in times if t is not None) if any(t is not None for t in times) else None
        fl = sum(f for f in floors if f is not None) if any(f is not None for f in floors) else None
        ratio = f"{total / fl:.1f}x" if total and fl else "-"
        inter = sum(i for i in interop if i is not None) if any(i is not None for i in interop) else None
        rows.append((variant, size, kernel, total, sum(t for t in gl_times if t is not None), fl, ratio, inter))
    print(f"Device: {device}. Effect ms = median over the frames (CUDA rows: CUDA events around the kernels; "
          "'GL pass ms' is what the frame's GL timer saw, interop and sync included). Floor = bytes the passes "
          "must move / measured compute copy bandwidth.\n")
    print("| variant | size | kernel px | effect ms | GL pass ms | floor ms | effect/floor | interop map+unmap ms |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for v, s, k, t, g, f, r, i in rows:
        print(f"| {v} | {s} | {k} | {fmt(t)} | {fmt(g)} | {fmt(f)} | {r} | {fmt(i)} |")


if __name__ == "__main__":
    main(sys.argv[1:])
