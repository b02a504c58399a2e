#!/usr/bin/env python3
"""Anti-aliasing's cost against its error, from `lightpass sweep --knob aa` folders.

    bench/summarize_aa.py OUTDIR SWEEP_DIR [SWEEP_DIR ...]

Each SWEEP_DIR holds sweep.csv and the PNGs of one sweep (its name, e.g. gallery_1080p, labels it).
Writes OUTDIR/aa.md (per sweep and value: frame GPU ms, the anti-aliasing pass's ms, HDR RMSE and
PSNR against the knob's reference, FLIP on the tone-mapped PNGs when the flip-evaluator package is
installed: scripts/setup-tools puts it in .venv, which this script re-runs itself under) and OUTDIR/aa_pareto.png (error against frame ms, one panel per sweep, Pareto front
marked). HDR RMSE cannot see FXAA (it changes only the tone-mapped image): FLIP is the error that
compares all methods; without it the plot uses HDR RMSE and says so.
"""
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from project_python import use_project_venv  # noqa: E402
from sweep_report import flip_error, pareto  # noqa: E402

AA_PASSES = ("ssaa_downsample", "fxaa", "taa")


def load(folder):
    rows = list(csv.DictReader(open(os.path.join(folder, "sweep.csv"))))
    for r in rows:
        r["flip"] = flip_error(os.path.join(folder, r["image"]), os.path.join(folder, r["knob"], "reference.png"))
        r["aa_ms"] = sum(float(r.get(p + "_ms") or 0.0) for p in AA_PASSES)
    return rows


def main(out_dir, folders):
    sweeps = [(os.path.basename(os.path.abspath(f)), load(f)) for f in folders if os.path.exists(os.path.join(f, "sweep.csv"))]
    have_flip = all(r["flip"] is not None for _, rows in sweeps for r in rows)
    md = ["# Anti-aliasing: cost against error", "",
          "Errors are against each knob's last value (aa: ssaa4, 4x4 samples a pixel). GPU ms are medians of the "
          "sweep's frames. \"AA pass ms\" is the ssaa_downsample / fxaa / taa pass alone; the rest of SSAA's "
          "cost is every pass before it running at S x S the pixels.", ""]
    if not have_flip:
        md += ["FLIP skipped (`scripts/setup-tools` installs it); the plot uses HDR RMSE, which cannot see FXAA.", ""]
    for name, rows in sweeps:
        for knob in dict.fromkeys(r["knob"] for r in rows):
            krows = [r for r in rows if r["knob"] == knob]
            md += [f"## {name}: {knob}", "", "| value | frame ms | AA pass ms | HDR RMSE | PSNR dB | FLIP |",
                   "| --- | --- | --- | --- | --- | --- |"]
            for r in krows:
                ref = " (reference)" if r["reference"] == "1" else ""
                flip = "-" if r["flip"] is None else f"{r['flip']:.4f}"
                md.append(f"| {r['value']}{ref} | {float(r['frame_ms']):.3f} | {r['aa_ms']:.3f} | {float(r['rmse']):.4g} | "
                          f"{float(r['psnr_db']):.2f} | {flip} |")
            md.append("")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        aa_sweeps = [(n, [r for r in rows if r["knob"] == "aa"]) for n, rows in sweeps]
        aa_sweeps = [(n, rows) for n, rows in aa_sweeps if rows]
        fig, axes = plt.subplots(1, max(1, len(aa_sweeps)), figsize=(5 * max(1, len(aa_sweeps)), 4), squeeze=False)
        for ax, (name, rows) in zip(axes[0], aa_sweeps):
            rows = [r for r in rows if r["reference"] != "1"]  # the reference is the error's zero
            err = [(r["flip"] if have_flip else float(r["rmse"])) for r in rows]
            pts = [(float(r["frame_ms"]), max(e, 1e-7)) for r, e in zip(rows, err)]
            front = sorted(pareto(pts), key=lambda i: pts[i][0])
            ax.scatter([p[0] for p in pts], [p[1] for p in pts], color="#888")
            for r, p in zip(rows, pts):
                ax.annotate(r["value"], p, fontsize=8, xytext=(3, 3), textcoords="offset points")
            ax.plot([pts[i][0] for i in front], [pts[i][1] for i in front], "-o", color="#d62728", label="Pareto front")
            ax.set_xlabel("frame GPU ms (median)")
            ax.set_ylabel("FLIP vs ssaa4" if have_flip else "HDR RMSE vs ssaa4")
            ax.set_title(name)
            ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(out_dir, "aa_pareto.png"), dpi=120)
        md += ["![error against GPU ms](aa_pareto.png)"]
    except ImportError:
        md += ["Plot skipped: install python3-matplotlib."]
    open(os.path.join(out_dir, "aa.md"), "w").write("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    use_project_venv(["flip_evaluator"])
    main(sys.argv[1], sys.argv[2:])
