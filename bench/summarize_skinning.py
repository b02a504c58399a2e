#!/usr/bin/env python3
"""The table of bench/animation.sh's runs: per model and size, still and playing with --skinning gpu
and cpu, the frame's GPU ms, the skinning pass's GPU ms, the CPU ms of SceneGpu::pose and the CPU
frame (submit) ms, from the --timings-json files. Usage: summarize_skinning.py OUTDIR (writes
OUTDIR/skinning.md and prints it)."""
import json
import os
import sys


def row(path):
    with open(path) as f:
        j = json.load(f)
    passes = j.get("passes", {})
    cpu = j.get("cpu", {})
    pose = j.get("animation_pose_ms", {})
    frame_gpu = cpu.get("gpu_frame_median_ms")
    skinning = passes.get("skinning", {}).get("median_ms")
    return frame_gpu, skinning, pose.get("median_ms"), cpu.get("submit_median_ms"), cpu.get("wall_ms_per_frame")


def ms(v):
    return "-" if v is None else f"{v:.3f}"


def main():
    out = sys.argv[1]
    lines = ["| model | size | run | frame GPU ms | skinning pass GPU ms | CPU pose ms | CPU submit ms | wall ms/frame |",
             "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: |"]
    for model in ("grid", "skinned"):
        for size, label in (("1920x1080", "1080p"), ("3840x2160", "4K")):
            for animation, skinning, run in (("none", "gpu", "still"), ("0", "gpu", "playing, --skinning gpu"),
                                             ("0", "cpu", "playing, --skinning cpu")):
                path = os.path.join(out, f"{model}_{size}_{animation}_{skinning}.json")
                if not os.path.exists(path):
                    continue
                lines.append(f"| {model} | {label} | {run} | " + " | ".join(ms(v) for v in row(path)) + " |")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out, "skinning.md"), "w") as f:
        f.write(text)
    print(text, end="")


if __name__ == "__main__":
    main()
