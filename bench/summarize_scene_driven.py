#!/usr/bin/env python3
"""Markdown table of bench/scene_driven.sh's runs: per scene, frame time (median GPU ms of the
whole frame) and texture memory (pooled transients + persistent environment cubes; and the graph's
live transients before the pool reuses memory) of the scene-driven graph against --all-passes, with the passes only
the forced graph runs. Input: the timings JSON files, named SCENE_scene.json and SCENE_all.json."""
import json
import os
import sys


def load(path):
    with open(path) as f:
        return json.load(f)


def mib(n):
    return n / (1024.0 * 1024.0)


def main(paths):
    runs = {}
    for p in paths:
        stem = os.path.basename(p)[:-len(".json")]
        scene, mode = stem.rsplit("_", 1)
        if mode not in ("scene", "all"):
            sys.exit(f"summarize_scene_driven.py: {p}: expected a name ending _scene.json or _all.json")
        runs.setdefault(scene, {})[mode] = load(p)
    first = next(iter(next(iter(runs.values())).values()))
    print(f"Scene-driven graph vs every pass forced on (--all-passes), {first['width']}x{first['height']}, "
          f"{first['frames']} frames, {first['device']}\n")
    print("| scene | frame ms (scene) | frame ms (all) | saved | texture MiB (scene) | texture MiB (all) | saved "
          "| before pooling MiB (scene / all) | passes only forced |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---|")
    for scene, modes in runs.items():
        if "scene" not in modes or "all" not in modes:
            sys.exit(f"summarize_scene_driven.py: {scene}: needs both _scene and _all runs")
        a, b = modes["scene"], modes["all"]
        fa = a["passes"]["frame"]["median_ms"]
        fb = b["passes"]["frame"]["median_ms"]
        ma, mb = a["memory"]["total_bytes"], b["memory"]["total_bytes"]
        extra = sorted(set(b["passes"]) - set(a["passes"]))
        saved = f"{100.0 * (fb - fa) / fb:.0f}%" if fb > 0 else "-"
        msaved = f"{100.0 * (mb - ma) / mb:.0f}%" if mb > 0 else "-"
        ga, gb = a["memory"]["graph_transient_bytes"], b["memory"]["graph_transient_bytes"]
        print(f"| {scene} | {fa:.3f} | {fb:.3f} | {saved} | {mib(ma):.1f} | {mib(mb):.1f} | {msaved} | "
              f"{mib(ga):.1f} / {mib(gb):.1f} | {', '.join(extra) or '-'} |")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: summarize_scene_driven.py SCENE_scene.json SCENE_all.json ...")
    main(sys.argv[1:])
