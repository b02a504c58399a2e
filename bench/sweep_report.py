#!/usr/bin/env python3
"""Adds FLIP and a Pareto plot to a `lightpass sweep` output folder.

    bench/sweep_report.py SWEEP_DIR

Reads SWEEP_DIR/sweep.csv and the PNGs beside it; writes SWEEP_DIR/sweep_report.md (the table with
FLIP on the tone-mapped images) and SWEEP_DIR/sweep_pareto.png (error against GPU ms per knob, the
Pareto front marked). FLIP needs the `flip-evaluator` package and the plot matplotlib: scripts/setup-tools
installs both (FLIP in .venv, which this script re-runs itself under when its python3 lacks FLIP:
bench/project_python.py); without them those parts are skipped with a note.
"""
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from project_python import use_project_venv  # noqa: E402


def load_rgb(path):
    import numpy as np
    from PIL import Image
    return np.asarray(Image.open(path).convert("RGB"), dtype=np.float32) / 255.0


def flip_error(test_png, ref_png):
    try:
        import flip_evaluator as flip
    except ImportError:
        return None
    _, mean, _ = flip.evaluate(load_rgb(ref_png), load_rgb(test_png), "LDR")
    return float(mean)


def pareto(points):
    """Indices of points not dominated in (ms, error): no other point is both faster and better."""
    front = []
    for i, (t, e) in enumerate(points):
        if not any((t2 <= t and e2 <= e) and (t2 < t or e2 < e) for j, (t2, e2) in enumerate(points) if j != i):
            front.append(i)
    return front


def time_axis(krows):
    """The time a knob's values differ in: the frame's GPU ms, or, where the frame time is flat (within
    3%) and each value baked its IBL, the one-off bake's GPU ms (the IBL knobs change only the bake)."""
    frame = [float(r["frame_ms"]) for r in krows]
    bake = [float(r.get("ibl_bake_gpu_ms") or 0.0) for r in krows]
    flat = max(frame) <= 1.03 * min(frame)
    if flat and min(bake) > 0.0 and max(bake) > 1.1 * min(bake):
        return "ibl_bake_gpu_ms", "IBL bake GPU ms (one-off, per environment change)"
    return "frame_ms", "frame GPU ms (median)"


def main(folder):
    rows = list(csv.DictReader(open(os.path.join(folder, "sweep.csv"))))
    notes = []
    for r in rows:
        knob_dir = os.path.join(folder, r["knob"])
        f = flip_error(os.path.join(folder, r["image"]), os.path.join(knob_dir, "reference.png"))
        r["flip"] = f
    if any(r["flip"] is None for r in rows):
        notes.append("FLIP skipped: `scripts/setup-tools` installs it (flip-evaluator, in .venv).")
    out = ["# What accuracy costs: " + os.path.basename(os.path.abspath(folder)), ""]
    out += notes
    knobs = []
    for r in rows:
        if r["knob"] not in knobs:
            knobs.append(r["knob"])
    for k in knobs:
        krows = [r for r in rows if r["knob"] == k]
        axis, _ = time_axis(krows)
        pts = [(float(r[axis]), float(r["rmse"])) for r in krows]
        front = set(pareto(pts))
        baked = any(float(r.get("ibl_bake_gpu_ms") or 0.0) > 0.0 for r in krows)
        bake_head = " IBL bake GPU ms |" if baked else ""
        out += ["", f"## {k}", "", f"Pareto front over {axis.replace('_', ' ')} and RMSE.", "",
                f"| value | frame ms |{bake_head} RMSE (HDR) | PSNR dB | FLIP (LDR) | Pareto |",
                "| --- | --- |" + (" --- |" if baked else "") + " --- | --- | --- | --- |"]
        for i, r in enumerate(krows):
            flip = "-" if r["flip"] is None else f"{r['flip']:.4f}"
            ref = " (reference)" if r["reference"] == "1" else ""
            bake = f" {float(r.get('ibl_bake_gpu_ms') or 0.0):.3f} |" if baked else ""
            out.append(f"| {r['value']}{ref} | {float(r['frame_ms']):.4f} |{bake} {float(r['rmse']):.3g} | {float(r['psnr_db']):.2f} | {flip} | {'yes' if i in front else ''} |")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, axes = plt.subplots(1, len(knobs), figsize=(5 * len(knobs), 4), squeeze=False)
        for ax, k in zip(axes[0], knobs):
            krows = [r for r in rows if r["knob"] == k]
            axis, label = time_axis(krows)
            pts = [(float(r[axis]), max(float(r["rmse"]), 1e-7)) for r in krows]
            front = sorted(pareto(pts), key=lambda i: pts[i][0])
            ax.scatter([p[0] for p in pts], [p[1] for p in pts], color="#888")
            for r, p in zip(krows, pts):
                ax.annotate(r["value"], p, fontsize=7, xytext=(3, 3), textcoords="offset points")
            ax.plot([pts[i][0] for i in front], [pts[i][1] for i in front], "-o", color="#d62728", label="Pareto front")
            ax.set_yscale("log")
            ax.set_xlabel(label)
            ax.set_ylabel("RMSE vs reference (linear HDR)")
            ax.set_title(k)
            ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(folder, "sweep_pareto.png"), dpi=120)
        out += ["", "![error against time](sweep_pareto.png)"]
    except ImportError:
        out += ["", "Plot skipped: install python3-matplotlib."]
    tmp = os.path.join(folder, "sweep_report.md.tmp")
    open(tmp, "w").write("\n".join(out) + "\n")
    os.replace(tmp, os.path.join(folder, "sweep_report.md"))
    print("\n".join(out))


if __name__ == "__main__":
    use_project_venv(["flip_evaluator"])
    main(sys.argv[1] if len(sys.argv) > 1 else "sweep")
