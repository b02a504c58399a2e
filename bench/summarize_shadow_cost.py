#!/usr/bin/env python3
"""Turns bench/shadow_cost.sh's `lightpass bench` JSON into a Markdown table: per variant (caster
culling on/off x caster raster, conservative and split grown in hardware or by the geometry shader:
the "grown by" column is what the pass used, from its explain notes), each sun's shadow pass and their sum with the floor (bytes the
pass must move over the fragment fill rate) and measured/floor, the frame, and the triangles the
cascades drew at t = 1 s (from OUTDIR/explain_<culling>_<raster>.txt). The target: the sum <= 2 ms."""
import json
import os
import re
import sys


def raster_name(flags):
    """The variant's raster as bench/shadow_cost.sh names it: conservative and split with the
    conservative raster asked for (conservative-hardware, split-geometry-shader), else the raster."""
    m = re.search(r"--shadow-raster (\w+)", flags)
    raster = m.group(1) if m else "conservative"
    c = re.search(r"--shadow-conservative ([\w-]+)", flags)
    return f"{raster}-{c.group(1)}" if c and raster in ("conservative", "split") else raster


def explain_path(outdir, flags):
    cull = "no-shadow-culling" if "--no-shadow-culling" in flags else "shadow-culling"
    return os.path.join(outdir, f"explain_{cull}_{raster_name(flags)}.txt")


def conservative_used(outdir, flags):
    """'hardware' / 'geometry shader' from the explain file's notes (what the pass drew with), or '-'."""
    path = explain_path(outdir, flags)
    if not os.path.exists(path):
        return "-"
    m = re.search(r"raster, (hardware|geometry shader) conservative", open(path).read())
    return m.group(1) if m else "-"


def triangles(outdir, flags):
    """'a+b+c+d / total' per light from the explain file of this variant, or '-'."""
    path = explain_path(outdir, flags)
    if not os.path.exists(path):
        return "-"
    per_light = {}
    total = None
    light = None
    for line in open(path):
        head = re.match(r"\s+runs\s+(shadow_map_\d+)", line)
        if head:
            light = head.group(1)
            continue
        note = re.search(r"cascade \d+: .*?(\d+) of (\d+) triangles", line)
        if note and light:
            per_light.setdefault(light, []).append(note.group(1))
            total = note.group(2)
    if not per_light:
        return "-"
    return "; ".join(f"{'+'.join(v)}" for _, v in sorted(per_light.items())) + f" of {total}"


def main(path, outdir):
    d = json.load(open(path))
    bw = d.get("bandwidth", {})
    print(f"Device: {d.get('device')}. Scene {d.get('scene')}, camera on its path, 60 fps from t = 1 s, "
          f"two suns x 4 cascades of 2048^2, 1920x1080. Median GPU ms over the frames; in brackets the "
          f"floor (ms, fragment fill {bw.get('fragment_GBps', 0):.0f} GB/s) and measured/floor. "
          f"Target: shadow passes <= 2 ms.\n")
    print("| culling | raster | grown by | shadow_map passes | sum | frame | triangles drawn per cascade at t = 1 s |")
    print("| --- | --- | --- | --- | ---: | ---: | --- |")
    for run in d["runs"]:
        p = run["passes"]
        flags = run["flags"]
        cull = "off" if "--no-shadow-culling" in flags else "on"
        raster = raster_name(flags)
        shadow = sorted((k, v) for k, v in p.items() if k.startswith("shadow_map"))
        ms = sum(v["median_ms"] for _, v in shadow)
        floors = [v.get("floor_ms") for _, v in shadow]
        floor = sum(floors) if shadow and all(floors) else None
        each = ", ".join(f"{k} {v['median_ms']:.3f}" for k, v in shadow) or "-"
        total = f"{ms:.3f} ({floor:.3f}, {ms / floor:.1f}x)" if floor else f"{ms:.3f}"
        frame = p.get("frame", {}).get("median_ms")
        print(f"| {cull} | {raster} | {conservative_used(outdir, flags)} | {each} | {total} | {'-' if frame is None else f'{frame:.3f}'} | "
              f"{triangles(outdir, flags)} |")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else os.path.dirname(sys.argv[1]))
