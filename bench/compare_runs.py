#!/usr/bin/env python3
"""Before/after table of `lightpass bench` JSONs taken in one sitting on one GPU machine, interleaved A B A B.

  bench/compare_runs.py DIR NAME...   (DIR holds base1/ new1/ base2/ new2/ with NAME.json in each)

Prints, per variant, each run's frame median (GPU ms), the mean of the two rounds and new/base, then
the same for every pass present in both. Rounds differing by more than new/base does is noise.
"""
import json
import sys


def runs(path):
    return {(r["flags"] if isinstance(r["flags"], str) else " ".join(r["flags"])) or "(default)": r
            for r in json.load(open(path))["runs"]}


def main():
    top, names = sys.argv[1], sys.argv[2:]
    for name in names:
        data = {v: runs(f"{top}/{v}/{name}.json") for v in ("base1", "new1", "base2", "new2")}
        print(f"\n### {name}\n")
        print("| variant | pass | base (run 1 / 2) | new (run 1 / 2) | new / base |")
        print("| --- | --- | --- | --- | --- |")
        for variant, first in data["base1"].items():
            passes = ["frame"] + sorted(p for p in first["passes"] if p != "frame" and "(" not in p)
            for p in passes:
                ms = {v: data[v][variant]["passes"].get(p, {}).get("median_ms") for v in data}
                if any(m is None for m in ms.values()):
                    print(f"| {variant} | {p} | {ms['base1']} / {ms['base2']} | {ms['new1']} / {ms['new2']} | (not in both) |")
                    continue
                base = (ms["base1"] + ms["base2"]) / 2
                new = (ms["new1"] + ms["new2"]) / 2
                ratio = new / base if base > 0 else float("nan")
                print(f"| {variant} | {p} | {ms['base1']:.3f} / {ms['base2']:.3f} | {ms['new1']:.3f} / {ms['new2']:.3f} | {ratio:.3f} |")


if __name__ == "__main__":
    main()
