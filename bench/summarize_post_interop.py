#!/usr/bin/env python3
"""Markdown table of bench/post_interop.sh's runs (OUTDIR/{variant}_{effect}_k{K}_{W}x{H}.json).

Per run and pass: 'frame ms' is the pass's GL-timed median (what the frame pays: for CUDA passes the
host's interop work and syncs are inside it), 'kernels ms' the CUDA events around the kernels,
'interop ms' the host time of map+unmap (map path), of issuing the semaphore hand-overs (external
with Vulkan semaphores) or of the fence/event waits beyond the kernels (external with host waits), the floor (bytes the pass must move / measured compute copy bandwidth) and
measured/floor for both. Then the targets: CUDA (external) bloom+composite at kernel 5 1080p no
slower than GLSL, and CUDA <= 1.5x its floor at kernel 100 4K.

The floor of bloom + composite is what it must move and nothing else: the HDR read once and the
bloom and the composited HDR written once, RGBA16F each, 24 bytes a texel (no intermediate, no
re-read), at the measured compute copy bandwidth (the run's `bandwidth.compute_GBps`). The
per-pass floors of the table are the graph's declared traffic of each pass.

OUTDIR/bloom_kernels.txt (bench/cuda/post_cuda_bench.cpp: kernels, mip-chain-tuning, copy-kernels) adds the kernel-only table: the fused
bloom + composite on RGBA16F CUDA arrays timed by CUDA events, the separable bloom with the direct and
the tensor-core blur and what auto picks, and the mip chain, against the same 24-byte floor at the
copy bandwidth cudaMemcpy measured there; and plain copy kernels (CUDA array -> CUDA array, linear
-> linear) as the achievable bandwidth."""
import glob
import json
import os
import re
import sys

BLOOM_BYTES_PER_TEXEL = 24  # HDR read + bloom written + HDR written, RGBA16F


def bloom_floor_ms(run):
    bw = run.get("bandwidth", {}).get("compute_GBps")
    if not bw:
        return None
    return BLOOM_BYTES_PER_TEXEL * run["width"] * run["height"] / (bw * 1e9) * 1e3


def kernel_table(path, kind="bloom_kernels"):
    rows = {}
    for line in open(path):
        m = re.match(kind + r" size=(\d+x\d+) kernel=(\d+) blur=(\w+) ran=(\w+) ms=([\d.]+) floor_ms=([\d.]+)", line)
        if m:
            size, kernel, blur, ran, ms, floor = m.groups()
            rows.setdefault((size, int(kernel)), {})[blur] = (float(ms), float(floor), ran)
    if not rows:
        print("\n(bloom_kernels.txt has no results: " + (open(path).read().strip().splitlines() or ["empty"])[-1] + ")")
        return
    if kind == "bloom_kernels":
        print("\nKernel-only (CUDA events, fused bloom + composite on RGBA16F CUDA arrays, no GL; floor = 24 B/texel "
              "at the measured copy bandwidth):\n")
    else:
        print("\nKernel-only, the bloom buffer alone (no composite, not in place; floor = 16 B/texel: HDR read, "
              "bloom written):\n")
    print("| size | kernel | separable direct ms | separable tensor ms | separable auto ms (ran) | mip chain ms | floor ms "
          "| direct/floor | tensor/floor | auto/floor | mip chain/floor |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for (size, kernel), r in sorted(rows.items(), key=lambda kv: (int(kv[0][0].split("x")[0]), kv[0][1])):
        floor = next(iter(r.values()))[1]
        d, t, a, mc = r.get("direct"), r.get("tensor"), r.get("auto"), r.get("mipchain")
        cell = lambda x: f"{x[0]:.4f}" if x else "-"
        ratio = lambda x: f"{x[0] / floor:.2f}x" if x and floor else "-"
        print(f"| {size} | {kernel} | {cell(d)} | {cell(t)} | {cell(a)}{f' ({a[2]})' if a else ''} | {cell(mc)} | "
              f"{floor:.4f} | {ratio(d)} | {ratio(t)} | {ratio(a)} | {ratio(mc)} |")
    print()
    for size in sorted({s for s, _ in rows}):
        wins = [k for (s, k), r in sorted(rows.items()) if s == size and "direct" in r and "tensor" in r
                and r["tensor"][2] == "tensor" and r["tensor"][0] < r["direct"][0]]
        print(f"- {size}: the tensor-core blur is faster than the direct one at kernel {', '.join(map(str, wins)) or 'none'}")
    if kind == "bloom_kernels":
        for size in ("3840x2160", "1920x1080"):
            for label, key in (("separable (auto)", "auto"), ("separable direct", "direct"),
                               ("separable tensor", "tensor"), ("mip chain", "mipchain")):
                x = rows.get((size, 100), {}).get(key)
                if x:
                    print(f"- Target kernel 100 {size}, {label}: {x[0]:.4f} ms = {x[0] / x[1]:.2f}x the floor "
                          f"{x[1]:.4f} ms ({'met' if x[0] <= 1.5 * x[1] else 'not met'}: <= 1.5x)")


def tuning_table(path):
    rows = {}
    for line in open(path):
        m = re.match(r"mip_chain_tuning size=(\d+x\d+) kernel=(\d+) variant=(\w+) ms=([\d.]+) floor_ms=([\d.]+)", line)
        if m:
            size, kernel, variant, ms, floor = m.groups()
            rows.setdefault((size, int(kernel)), {})[variant] = (float(ms), float(floor))
    if not rows:
        return
    variants = ["default", "no_tail", "tail_16k", "no_overlap"]
    print("\nMip chain, what each part buys (fused bloom + composite, kernel-only ms; x floor in brackets): default = as "
          "the passes run it; each other row changes one setting (README, MipChainTuning): no_tail = every level its own "
          "launches; tail_16k = levels up to 16384 texels in the one-block tail; no_overlap = no programmatic dependent "
          "launches. The variants that lost in older runs (bench/results/post/2026-11-24_cuda-interop/mip_chain/) were removed from the "
          "kernels after measurement:\n")
    cases = sorted(rows, key=lambda k: (int(k[0].split("x")[0]), k[1]))
    print("| variant | " + " | ".join(f"{size} k{kernel}" for size, kernel in cases) + " |")
    print("| --- | " + " | ".join("---" for _ in cases) + " |")
    for v in variants + sorted({v for r in rows.values() for v in r} - set(variants)):
        if not any(v in rows[c] for c in cases):
            continue
        cells = [f"{rows[c][v][0]:.4f} ({rows[c][v][0] / rows[c][v][1]:.2f}x)" if v in rows[c] else "-" for c in cases]
        print(f"| {v} | " + " | ".join(cells) + " |")


def steps_table(path):
    rows = {}
    for line in open(path):
        m = re.match(r"mip_chain_step size=(\d+x\d+) kernel=(\d+) variant=(\w+) step=(\w+) ms=([\d.]+) MB=([\d.]+) "
                     r"GBps=([\d.]+)", line)
        if m:
            size, kernel, variant, step, ms, mb, gbps = m.groups()
            rows.setdefault((size, int(kernel), variant), []).append((step, float(ms), float(mb), float(gbps)))
    if not rows:
        return
    print("\nMip chain, each launch timed alone (no overlap; MB = what it must read and write at least, GB/s = MB / ms):\n")
    print("| size | kernel | variant | launches: ms (GB/s) | sum ms |")
    print("| --- | --- | --- | --- | --- |")
    for (size, kernel, variant), steps in sorted(rows.items(), key=lambda kv: (int(kv[0][0].split("x")[0]), kv[0][1], kv[0][2])):
        cells = ", ".join(f"{name} {ms:.4f} ({gbps:.0f})" for name, ms, _, gbps in steps)
        print(f"| {size} | {kernel} | {variant} | {cells} | {sum(s[1] for s in steps):.4f} |")


def copy_table(path):
    rows = []
    for line in open(path):
        m = re.match(r"copy_kernels size=(\d+x\d+) kind=(\w+) ms=([\d.]+) GBps=([\d.]+) floor_ms=([\d.]+) "
                     r"copy_GBps=([\d.]+)", line)
        if m:
            rows.append(m.groups())
    if not rows:
        return
    print("\nCopy kernels (the achievable bandwidth; an RGBA16F image copied, 16 B/texel moved; floor = at "
          "cudaMemcpy's device-to-device bandwidth):\n")
    print("| size | copy | ms | GB/s | floor ms | / floor | cudaMemcpy GB/s |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    names = {"array": "CUDA array -> CUDA array (surfaces)", "linear": "linear half4 -> linear half4"}
    for size, kind, ms, gbps, floor, copy in rows:
        print(f"| {size} | {names.get(kind, kind)} | {float(ms):.4f} | {float(gbps):.0f} | {float(floor):.4f} | "
              f"{float(ms) / float(floor):.2f}x | {float(copy):.0f} |")


def fmt(x, suffix=""):
    return "-" if x is None else f"{x:.4f}{suffix}"


def passes_of(effect):
    return ["toon"] if effect == "toon" else ["bloom", "bloom_composite"]


def kernel_tables(outdir):
    kernels = os.path.join(outdir, "bloom_kernels.txt")
    if os.path.exists(kernels):
        kernel_table(kernels)
        kernel_table(kernels, "bloom_only_kernels")
        tuning_table(kernels)
        steps_table(kernels)
        copy_table(kernels)


def main(outdir):
    runs = {}
    device = None
    for path in sorted(glob.glob(os.path.join(outdir, "*_*_k*_*x*.json"))):
        variant, effect, kernel, size = os.path.basename(path)[:-5].split("_")
        run = json.load(open(path))
        device = device or run.get("device")
        runs[(variant, effect, kernel, size)] = run
    if not runs:  # KERNELS_ONLY=1: the kernel-only benchmark alone
        device_txt = os.path.join(outdir, "device.txt")
        if os.path.exists(device_txt):
            print("Device: " + open(device_txt).read().strip())
        kernel_tables(outdir)
        return
    print(f"Device: {device}. Medians over the frames; floor = bytes moved / measured compute copy bandwidth.")
    info = os.path.join(outdir, "info.txt")
    if os.path.exists(info):
        for line in open(info):
            if line.startswith(("interop:", "sync:")):
                print(f"`{line.strip()}`  ")
    print()
    print("| variant | effect | kernel | size | pass | frame ms | kernels ms | interop ms | floor ms | frame/floor | kernels/floor |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    totals = {}
    for (variant, effect, kernel, size), run in sorted(runs.items(), key=lambda kv: (kv[0][2], kv[0][3], kv[0][1], kv[0][0])):
        p = run["passes"]
        tot = [0.0, 0.0, 0.0]
        for name in passes_of(effect):
            if name not in p:
                continue
            frame = p[name]["median_ms"]
            kern = p.get(f"{name} (cuda kernels)", {}).get("median_ms")
            inter = p.get(f"{name} (cuda interop)", {}).get("median_ms")
            fl = p[name].get("floor_ms")
            ratio = lambda x: f"{x / fl:.2f}x" if x is not None and fl else "-"
            print(f"| {variant} | {effect} | {kernel[1:]} | {size} | {name} | {fmt(frame)} | {fmt(kern)} | {fmt(inter)} | "
                  f"{fmt(fl)} | {ratio(frame)} | {ratio(kern)} |")
            tot[0] += frame
            tot[1] += kern if kern is not None else frame
            tot[2] += fl or 0.0
        exact = bloom_floor_ms(run)
        if effect in ("bloom", "mipchain") and exact:
            tot[2] = exact
        totals[(variant, effect, kernel, size)] = tot
    print("\nTargets (bloom + composite, all passes summed; floor = 24 B/texel, see above):\n")
    for effect, kernel, size in sorted({(e, k, s) for (_, e, k, s) in totals if e in ("bloom", "mipchain")}):
        g = totals.get(("glsl", effect, kernel, size))
        for variant in ("cuda-external", "cuda-map", "cuda-auto", "auto"):
            c = totals.get((variant, effect, kernel, size))
            if not c or not g:
                continue
            wf = lambda v: runs.get((v, effect, kernel, size), {}).get("passes", {}).get("frame", {}).get("median_ms")
            if wf(variant) is not None and wf("glsl") is not None:
                print(f"- {effect} {kernel[1:]} px {size} {variant}: whole frame {wf(variant):.4f} ms vs GLSL's {wf('glsl'):.4f} ms "
                      f"({'no slower' if wf(variant) <= wf('glsl') else 'slower'}; the pass times below can move a "
                      f"drain of earlier GL work into the CUDA pass)")
            print(f"- {effect} {kernel[1:]} px {size} {variant}: frame {c[0]:.4f} ms vs GLSL {g[0]:.4f} ms "
                  f"({'no slower' if c[0] <= g[0] else 'slower'}); kernels {c[1]:.4f} ms = "
                  f"{c[1] / c[2]:.2f}x floor {c[2]:.4f} ms; frame = {c[0] / c[2]:.2f}x floor" if c[2] else "")
    # The whole frame's GPU time per run: whether a CUDA pass's cost is its own or moved from its
    # neighbours (GL drains before a hand-over; the queues switch contexts twice per CUDA pass).
    print("\nWhole frame GPU ms (median; same scene and post settings per row):\n")
    variants = sorted({v for (v, _, _, _) in runs})
    print("| effect | kernel | size | " + " | ".join(variants) + " |")
    print("| --- | --- | --- | " + " | ".join("---:" for _ in variants) + " |")
    for effect, kernel, size in sorted({(e, k, s) for (_, e, k, s) in runs}):
        cells = []
        for v in variants:
            run = runs.get((v, effect, kernel, size))
            frame = run["passes"].get("frame", {}).get("median_ms") if run else None
            cells.append(fmt(frame))
        print(f"| {effect} | {kernel[1:]} | {size} | " + " | ".join(cells) + " |")
    kernel_tables(outdir)
    choices = os.path.join(outdir, "auto_choices.txt")
    if os.path.exists(choices):
        print("\nWhat --post-backend auto measured and chose:\n")
        for line in open(choices):
            print("    " + line.rstrip())


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "bench/results/post/2026-11-24_cuda-interop")
