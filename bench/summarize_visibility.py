#!/usr/bin/env python3
"""bench/visibility.sh's table: per scene, size and G-buffer layout, the G-buffer stage's median GPU ms
in the classic mode (the `gbuffer` pass) and the visibility mode (`gbuffer_visibility` raster +
`gbuffer_resolve` compute), each pass with measured/floor (the floor: the bytes the pass must move
once, over the measured fragment fill rate for raster passes and the copy bandwidth for compute),
the frame ms, and visibility/classic. With --sweep, the rows of `lightpass sweep --knob gbuffer-mode`
(HDR error against classic, frame ms)."""
import argparse
import csv
import json
import re

STAGE = {"classic": ["gbuffer"], "visibility": ["gbuffer_visibility", "gbuffer_resolve"]}


def flag(flags, name):
    m = re.search(rf"--{name} (\S+)", flags)
    return m.group(1) if m else None


def cell(p):
    if not p:
        return "-"
    floor = p.get("floor_ms")
    ratio = f" · {p['median_ms'] / floor:.2f}×" if floor else ""
    return f"{p['median_ms']:.3f}{ratio}"


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("json", nargs="+")
    ap.add_argument("--sweep", help="sweep.csv of lightpass sweep --knob gbuffer-mode")
    a = ap.parse_args()
    for path in a.json:
        try:
            d = json.load(open(path))
        except (OSError, ValueError) as e:
            print(f"## {path}\n\nnot read: {e}\n")
            continue
        print(f"## {d.get('scene', path)}\n\nDevice: {d.get('device', '?')}\n")
        print("G-buffer stage, median GPU ms · measured/floor per pass; stage = the sum of its passes.\n")
        print("| size | layout | classic `gbuffer` | visibility raster | resolve | visibility stage | "
              "visibility / classic | frame classic | frame visibility |")
        print("|---|---|---:|---:|---:|---:|---:|---:|---:|")
        rows = {}
        for run in d["runs"]:
            f = run["flags"]
            key = (f"{run['width']}x{run['height']}", f"{flag(f, 'gbuffer')}/{flag(f, 'gbuffer-position')}")
            rows.setdefault(key, {})[flag(f, "gbuffer-mode")] = run["passes"]
        for (size, layout), modes in sorted(rows.items(), key=lambda kv: (int(kv[0][0].split("x")[0]), kv[0][1])):
            c, v = modes.get("classic", {}), modes.get("visibility", {})
            cs = sum(c[n]["median_ms"] for n in STAGE["classic"] if n in c) if c else None
            vs = sum(v[n]["median_ms"] for n in STAGE["visibility"] if n in v) if v else None
            vfloor = sum(v[n].get("floor_ms") or 0 for n in STAGE["visibility"] if n in v) if v else 0
            stage = f"{vs:.3f}" + (f" · {vs / vfloor:.2f}×" if vfloor else "") if vs is not None else "-"
            ratio = f"{vs / cs:.2f}" if cs and vs is not None else "-"
            frame = lambda m: f"{m['frame']['median_ms']:.3f}" if m and "frame" in m else "-"
            print(f"| {size} | {layout} | {cell(c.get('gbuffer'))} | {cell(v.get('gbuffer_visibility'))} | "
                  f"{cell(v.get('gbuffer_resolve'))} | {stage} | {ratio} | {frame(c)} | {frame(v)} |")
        print()
    if a.sweep:
        print("## sweep --knob gbuffer-mode (HDR against classic)\n")
        try:
            with open(a.sweep) as fh:
                rows = list(csv.DictReader(fh))
        except OSError as e:
            print(f"not read: {e}")
            return
        print("| value | frame ms | G-buffer stage ms | RMSE | max abs | non-finite |")
        print("|---|---:|---:|---:|---:|---:|")
        for r in rows:
            stage = sum(float(r[f"{n}_ms"]) for n in ("gbuffer", "gbuffer_visibility", "gbuffer_resolve")
                        if r.get(f"{n}_ms") not in (None, ""))
            print(f"| {r['value']} | {float(r['frame_ms']):.3f} | {stage:.3f} | {r['rmse']} | {r['max_abs']} | "
                  f"{r['non_finite']} |")


if __name__ == "__main__":
    main()
