#!/usr/bin/env python3
"""Turns bench/motion.sh's `lightpass bench` JSON into a Markdown table: per size and variant, the
G-buffer pass (without velocity when motion blur is off, with it otherwise), each motion-blur pass and
their sum, each with its floor (bytes the pass must move over the measured bandwidth: fill rate for the
raster G-buffer, compute copy bandwidth for the blur) and measured/floor, and the whole frame."""
import json
import re
import sys

BLUR = ["motion_blur_tiles", "motion_blur_neighbors", "motion_blur"]


def cell(p):
    """'ms (floor ms, x ratio)' for one pass entry, '-' when absent."""
    if not p:
        return "-"
    ms = p["median_ms"]
    fl = p.get("floor_ms")
    return f"{ms:.4f} ({fl:.4f}, {ms / fl:.1f}x)" if fl else f"{ms:.4f}"


def main(path):
    d = json.load(open(path))
    bw = d.get("bandwidth", {})
    print(f"Device: {d.get('device')}. Scene {d.get('scene')}, camera on its path, 60 fps from t = 1 s. "
          f"Median GPU ms over the frames; in brackets the floor (ms) and measured/floor "
          f"(compute copy {bw.get('compute_GBps', 0):.0f} GB/s, fragment fill {bw.get('fragment_GBps', 0):.0f} GB/s).\n")
    print("| size | variant | velocity | gbuffer | motion_blur_tiles | motion_blur_neighbors | motion_blur | blur total | frame |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for run in d["runs"]:
        p = run["passes"]
        flags = run["flags"]
        samples = re.search(r"--motion-blur-samples (\d+)", flags)
        variant = f"blur, {samples.group(1)} samples" if samples else "no blur"
        velocity = "yes" if samples else "no"
        blur = [p.get(n) for n in BLUR]
        if all(blur):
            total = sum(b["median_ms"] for b in blur)
            floors = [b.get("floor_ms") for b in blur]
            ftotal = sum(floors) if all(floors) else None
            total_cell = f"{total:.4f} ({ftotal:.4f}, {total / ftotal:.1f}x)" if ftotal else f"{total:.4f}"
        else:
            total_cell = "-"
        frame = p.get("frame", {}).get("median_ms")
        frame_cell = "-" if frame is None else f"{frame:.4f}"
        print(f"| {run['width']}x{run['height']} | {variant} | {velocity} | {cell(p.get('gbuffer'))} | "
              + " | ".join(cell(b) for b in blur) + f" | {total_cell} | {frame_cell} |")


if __name__ == "__main__":
    main(sys.argv[1])
