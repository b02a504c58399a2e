#!/usr/bin/env python3
"""The peer table: lightpass `bench` frame medians against Filament's own GPU frame time, per scene and
size, with the ratio lightpass / Filament (below 1: lightpass is faster). Reads what bench/peers/run.sh
writes into OUTDIR:

  peers_lightpass_NAME.json            lightpass bench, one run per --size
  peers_filament_NAME_WxH.json         bench/peers/filament.py, one per size

and writes OUTDIR/peers.md (also printed).

  summarize_peers.py OUTDIR NAME [NAME ...]
"""
import glob
import json
import os
import re
import sys

SIZE_LABELS = {(1920, 1080): "1080p", (2560, 1440): "1440p", (3840, 2160): "4K"}


def size_label(w, h):
    return SIZE_LABELS.get((w, h), f"{w}x{h}")


def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def read_results(out_dir, names):
    """{name: {"lightpass": {(w, h): ms}, "filament": {(w, h): result}}}, plus the lightpass device."""
    results, device, flags = {}, None, set()
    for name in names:
        entry = {"lightpass": {}, "filament": {}, "lightpass_frames": {}, "gbuffer_modes": set()}
        lp_path = os.path.join(out_dir, f"peers_lightpass_{name}.json")
        if os.path.isfile(lp_path):
            d = load(lp_path)
            device = device or d.get("device")
            flags.add(shown_flags(d.get("common_flags", "")))
            for run in d.get("runs", []):
                frame = run.get("passes", {}).get("frame")
                mode = gbuffer_mode(run.get("passes", {}))
                if mode:
                    entry["gbuffer_modes"].add(mode)
                if frame and "width" in run and "height" in run:
                    entry["lightpass"][(run["width"], run["height"])] = frame["median_ms"]
                    entry["lightpass_frames"][(run["width"], run["height"])] = run.get("frames")
        for path in sorted(glob.glob(os.path.join(out_dir, f"peers_filament_{name}_*.json"))):
            if not re.fullmatch(rf"peers_filament_{re.escape(name)}_\d+x\d+\.json", os.path.basename(path)):
                continue
            d = load(path)
            entry["filament"][(d["width"], d["height"])] = d
        results[name] = entry
    return results, device, sorted(flags)


def gbuffer_mode(passes):
    """How a lightpass run made its G-buffer, from the passes it timed (--gbuffer-mode auto, the default,
    picks per GPU): 'visibility', 'classic', or None when neither was timed."""
    if "gbuffer_resolve" in passes or "gbuffer_visibility" in passes:
        return "visibility"
    return "classic" if "gbuffer" in passes else None


def shown_flags(common):
    """lightpass's common flags without the per-scene path and the quiet switch."""
    words, out, i = common.split(), [], 0
    while i < len(words):
        if words[i] in ("--scene", "--timings-json"):
            i += 2
            continue
        if words[i] not in ("-q", "--quiet"):
            out.append(words[i])
        i += 1
    return " ".join(out)


def scene_label(name, entry):
    """'gallery, 1 sun (282k triangles)', from what the Filament run drew (the light-matched scene)."""
    runs = list(entry["filament"].values())
    if not runs:
        return name
    s = runs[0].get("settings", {})
    suns, points = s.get("suns", 0), s.get("local_lights", 0)
    label = f"{name}, {suns} sun{'s' if suns != 1 else ''}"
    if points:
        label += f", {points} point{'s' if points != 1 else ''}"
    tris = runs[0].get("triangles")
    if tris:
        label += f" ({tris / 1000:.0f}k triangles)" if tris >= 1000 else f" ({tris} triangles)"
    return label


def fmt(ms):
    return f"{ms:.2f}" if ms is not None else "-"


def table(results, device, lightpass_flags=()):
    sizes = sorted({sz for e in results.values() for sz in list(e["lightpass"]) + list(e["filament"])},
                   key=lambda s: s[0] * s[1])
    head = ["scene"]
    for w, h in sizes:
        lab = size_label(w, h)
        head += [f"lightpass {lab}", f"Filament {lab}", f"ratio {lab}"]
    lines = ["| " + " | ".join(head) + " |", "|" + " --- |" * len(head)]
    for name, e in results.items():
        row = [scene_label(name, e)]
        for sz in sizes:
            lp = e["lightpass"].get(sz)
            fr = e["filament"].get(sz)
            fm = fr["gpu_frame_ms"]["median_ms"] if fr else None
            row += [fmt(lp), fmt(fm), f"{lp / fm:.2f}" if lp is not None and fm else "-"]
        lines.append("| " + " | ".join(row) + " |")
    filly = sorted({f"filly {r.get('filly_version', '?')} ({r.get('gl_platform', '?')})"
                    for e in results.values() for r in e["filament"].values()})
    frames = sorted({r["frames"] for e in results.values() for r in e["filament"].values()})
    settings = set()
    for e in results.values():
        for r in e["filament"].values():
            st = r.get("settings", {})
            settings.add(f"{st.get('shadow_cascades', '?')} shadow cascade of {st.get('shadow_map_size', '?')}², "
                         f"IBL {'on' if st.get('ibl') else 'off'}, sky {'on' if st.get('sky') else 'off'}, "
                         f"tone map {st.get('tone_mapping', '?')}, bloom/SSAO/MSAA off")
    notes = [f"GPU ms per frame (medians). Device: {device or 'unknown'}; Filament through {', '.join(filly) or 'filly (no runs)'}.",
             "lightpass: `bench` frame median; Filament: median of renderer.stats.gpu_frame_ms over "
             f"{'/'.join(str(f) for f in frames) or '-'} reported frames. Ratio: lightpass / Filament (below 1: lightpass faster).",
             "Matched: same triangles (GLB from bench/peers/scene_to_glb.py), camera, size and lights; Filament: "
             + (", ".join(sorted(settings)) or "-") + "; lightpass flags: "
             + (", ".join(f"`{f}`" for f in lightpass_flags) or "-") + ".",
             "lightpass G-buffer (from the passes it timed): "
             + (", ".join(f"{name} {'/'.join(sorted(e['gbuffer_modes']))}" for name, e in results.items()
                          if e["gbuffer_modes"]) or "-") + ".",
             ""]
    return "\n".join(notes + lines) + "\n"


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) < 2:
        print(__doc__.strip().splitlines()[-1].strip(), file=sys.stderr)
        return 2
    out_dir, names = argv[0], argv[1:]
    if not os.path.isdir(out_dir):
        print(f"summarize_peers.py: {out_dir}: no such folder", file=sys.stderr)
        return 1
    results, device, lightpass_flags = read_results(out_dir, names)
    if not any(e["lightpass"] or e["filament"] for e in results.values()):
        print(f"summarize_peers.py: {out_dir}: no peers_lightpass_*.json or peers_filament_*.json for {', '.join(names)}",
              file=sys.stderr)
        return 1
    text = table(results, device, lightpass_flags)
    with open(os.path.join(out_dir, "peers.md"), "w", encoding="utf-8") as f:
        f.write(text)
    sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
