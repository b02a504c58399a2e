#!/usr/bin/env python3
"""Turns a `lightpass bench` JSON into a Markdown table: one row per variant, the GPU ms of the
chosen passes (median), the focus pass against its floor, and its ratio to a baseline variant
(the same flags with one axis set to the baseline value).

  bench/summarize_bench.py bench.json --pass local_lights --ratio-axis=--local-lights --ratio-to fullscreen
"""
import argparse
import json
import sys


def flag_dict(flags):
    words, out, i = flags.split(), {}, 0
    while i < len(words):
        if i + 1 < len(words) and not words[i + 1].startswith("--"):
            out[words[i]] = words[i + 1]
            i += 2
        else:
            out[words[i]] = ""
            i += 1
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("json")
    ap.add_argument("--pass", dest="focus", help="the pass to compare against its floor and the baseline")
    ap.add_argument("--columns", default="", help="comma-separated passes to list (default: every pass)")
    ap.add_argument("--ratio-axis", help="flag whose baseline value the ratio divides by, e.g. --local-lights")
    ap.add_argument("--ratio-to", help="that flag's baseline value, e.g. fullscreen")
    a = ap.parse_args()
    d = json.load(open(a.json))
    runs = d["runs"]
    cols = [c for c in a.columns.split(",") if c] or sorted({p for r in runs for p in r["passes"]},
                                                         key=lambda p: (p != "frame", p))
    print(f"Device: {d['device']}; scene: `{d['scene']}`; common flags: `{d['common_flags']}`", end="")
    if "bandwidth" in d:
        bw = d["bandwidth"]
        print(f"; floors from compute copy {bw['compute_GBps']:.1f} GB/s, fragment fill {bw['fragment_GBps']:.1f} GB/s")
    print("\n")
    head = ["variant", "frames"] + [f"{c} ms" for c in cols]
    if a.focus:
        head += [f"{a.focus} measured/floor"]
        if a.ratio_axis:
            head += [f"{a.focus} / {a.ratio_to}"]
    print("| " + " | ".join(head) + " |")
    print("|" + " --- |" * len(head))
    by_flags = {r["flags"]: r for r in runs}
    for r in runs:
        row = [f"`{r['flags']}`", str(r["frames"])]
        row += [f"{r['passes'][c]['median_ms']:.4f}" if c in r["passes"] else "-" for c in cols]
        if a.focus:
            p = r["passes"].get(a.focus)
            row.append(f"{p['median_ms'] / p['floor_ms']:.1f}x" if p and p.get("floor_ms") else "-")
            if a.ratio_axis:
                fd = flag_dict(r["flags"])
                base = None
                if a.ratio_axis in fd:
                    want = dict(fd)
                    want[a.ratio_axis] = a.ratio_to
                    base = next((b for b in runs if flag_dict(b["flags"]) == want), None)
                bp = base["passes"].get(a.focus) if base else None
                row.append(f"{p['median_ms'] / bp['median_ms']:.3f}" if p and bp and bp["median_ms"] > 0 else "-")
        print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    sys.exit(main())
