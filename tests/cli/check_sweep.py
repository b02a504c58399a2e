#!/usr/bin/env python3
"""Checks a `lightpass sweep` run of one knob: sweep.csv has one row per value with the expected
columns, the reference (last) row has error 0, every image was written and finite, sweep.md has the
knob's table, stderr (run with --progress) has a progress line per value and a done line, and for a monotone knob the HDR RMSE never
rises as the value moves towards the reference (equal is allowed).
With --positive COLUMN, that column must be > 0 in every row of the knob (e.g. ibl_bake_gpu_ms).
With --max-rmse E, every row's HDR RMSE must be at most E (a knob that gives the same image by design).
With --timed-in VALUE:COLUMN, that value's row must have COLUMN > 0 (a pass only that value runs).
With --pathtraced SPP (sweep --reference pathtraced --spp SPP): no row is the reference, every row has
an error above zero, the CSV and sweep.md record the path tracer's samples and its noise (> 0).
With --term T: every row names the knob's light term T, its errors over the surfaces and of the term
alone are finite and at least 0 (0 for the reference against its own best value), and for --term frame
the term's error is the surface error. With --term-below-surface: every row's term error is below its
surface error (the term alone leaves out what the knob does not change).
  check_sweep.py OUTDIR STDERR_FILE KNOB VALUES [--monotone] [--positive COLUMN] [--max-rmse E] [--timed-in V:C]
                 [--pathtraced SPP] [--term T] [--term-below-surface]"""
import csv
import re
import os
import sys

out_dir, progress_file, knob, values = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
monotone = "--monotone" in sys.argv[5:]
positive = [sys.argv[i + 1] for i in range(5, len(sys.argv) - 1) if sys.argv[i] == "--positive"]
max_rmse = [float(sys.argv[i + 1]) for i in range(5, len(sys.argv) - 1) if sys.argv[i] == "--max-rmse"]
timed_in = [sys.argv[i + 1].split(":", 1) for i in range(5, len(sys.argv) - 1) if sys.argv[i] == "--timed-in"]
pathtraced = [int(sys.argv[i + 1]) for i in range(5, len(sys.argv) - 1) if sys.argv[i] == "--pathtraced"]
term = [sys.argv[i + 1] for i in range(5, len(sys.argv) - 1) if sys.argv[i] == "--term"]
term_below_surface = "--term-below-surface" in sys.argv[5:]

with open(os.path.join(out_dir, "sweep.csv")) as f:
    reader = csv.DictReader(f)
    columns = reader.fieldnames
    rows = [r for r in reader if r["knob"] == knob]
expected = ["knob", "value", "index", "reference", "frame_ms", "rmse", "psnr_db", "max_abs", "non_finite", "image",
            "reference_source", "reference_spp", "reference_noise_rmse", "surface_pixels", "surface_rmse",
            "surface_relative_error", "term", "term_rmse", "term_relative_error"]
missing = [c for c in expected if c not in columns]
assert not missing, f"columns missing: {missing} (have {columns})"
assert any(c.endswith("_ms") and c != "frame_ms" for c in columns), f"no per-pass time columns: {columns}"
assert len(rows) == values, f"{len(rows)} rows for {knob}, expected {values}"
assert [int(r["index"]) for r in rows] == list(range(values)), "rows out of order"
assert len({r["value"] for r in rows}) == values, "values are not distinct"
rmse = [float(r["rmse"]) for r in rows]
if pathtraced:
    assert [r["reference"] for r in rows] == ["0"] * values, "no value is the reference against the path tracer"
    for r in rows:
        assert r["reference_source"] == "pathtraced", f"reference_source {r['reference_source']}"
        assert int(r["reference_spp"]) == pathtraced[0], f"reference_spp {r['reference_spp']}, expected {pathtraced[0]}"
        assert float(r["reference_noise_rmse"]) > 0.0, "the path tracer's noise is not recorded"
        assert float(r["rmse"]) > 0.0, f"{r['value']}: error 0 against the path tracer"
    assert os.path.isfile(os.path.join(out_dir, knob, "reference.exr")), "no reference.exr"
else:
    assert [r["reference"] for r in rows] == ["0"] * (values - 1) + ["1"], "the last value must be the reference"
    assert all(r["reference_source"] == "best" and r["reference_spp"] == "0" for r in rows), "reference columns"
    assert rmse[-1] == 0.0 and float(rows[-1]["max_abs"]) == 0.0, f"reference error {rmse[-1]}"
for r in rows:
    assert int(r["non_finite"]) == 0, f"{r['value']}: {r['non_finite']} non-finite pixels"
    assert float(r["frame_ms"]) > 0.0, f"{r['value']}: no frame time"
    assert os.path.isfile(os.path.join(out_dir, r["image"])), f"missing {r['image']}"
for r in rows:
    assert int(r["surface_pixels"]) > 0, f"{r['value']}: no pixel sees a surface"
    for c in ("surface_rmse", "surface_relative_error", "term_rmse", "term_relative_error"):
        assert 0.0 <= float(r[c]) < float("inf"), f"{r['value']}: {c} = {r[c]}"
for t in term:
    assert all(r["term"] == t for r in rows), f"terms {[r['term'] for r in rows]}, expected {t}"
    if t == "frame":
        assert all(r["term_relative_error"] == r["surface_relative_error"] for r in rows), "a frame knob's term is the frame"
    if not pathtraced:
        assert float(rows[-1]["term_relative_error"]) == 0.0 and float(rows[-1]["surface_relative_error"]) == 0.0, \
            "the reference's own term and surface errors are not 0"
if term_below_surface:
    for r in rows:
        assert float(r["term_relative_error"]) < float(r["surface_relative_error"]), \
            f"{r['value']}: term error {r['term_relative_error']} not below the surface error {r['surface_relative_error']}"
for column in positive:
    assert column in columns, f"no {column} column (have {columns})"
    for r in rows:
        assert float(r[column]) > 0.0, f"{r['value']}: {column} = {r[column]}"
for bound in max_rmse:
    for r in rows:
        assert float(r["rmse"]) <= bound, f"{r['value']}: RMSE {r['rmse']} above {bound}"
for value, column in timed_in:
    assert column in columns, f"no {column} column (have {columns})"
    row = [r for r in rows if r["value"] == value]
    assert row and float(row[0][column] or 0) > 0.0, f"{value}: {column} not timed"
if monotone:
    for a, b, ea, eb in zip(rows, rows[1:], rmse, rmse[1:]):
        assert eb <= ea * (1.0 + 1e-9), f"RMSE rises from {a['value']} ({ea}) to {b['value']} ({eb})"
    assert rmse[0] > 0.0, "the cheapest value gives the reference's image: the knob does nothing"

with open(os.path.join(out_dir, "sweep.md")) as f:
    md = f.read()
assert f"## {knob}" in md, "no Markdown section for the knob"
if pathtraced:
    assert f"Reference: the path tracer, {pathtraced[0]} samples a pixel" in md, "sweep.md does not name the path tracer"
section = md.split(f"## {knob}", 1)[1].split("\n## ", 1)[0]
table_rows = [l for l in section.splitlines() if l.startswith("| ") and not l.startswith("| value") and "---" not in l]
assert len(table_rows) == values, f"{len(table_rows)} Markdown rows, expected {values}"

with open(progress_file) as f:
    text = f.read()
# Run with --progress and stderr not a terminal: one plain line per value, then the done line.
assert "\r" not in text, "a redrawn progress line in a log"
progress = [l for l in text.splitlines() if re.match(r"sweep +\d+% ", l)]
assert len(progress) == values, f"{len(progress)} progress lines, expected one per value: {progress}"
for i, r in enumerate(rows):
    pattern = rf"sweep +{100 * (i + 1) // values}% {i + 1}/{values}(, about \d+( min \d+)? s left)?: {re.escape(knob)} {re.escape(r['value'])}$"
    assert re.match(pattern, progress[i]), f"progress line {progress[i]!r} (want {pattern})"
assert re.search(rf"^sweep done in [0-9.]+ s \({values}/{values}\)$", text, re.M), "no done line"
print(f"sweep ok: {knob}, {values} values, RMSE {' >= '.join(f'{e:.3g}' for e in rmse)}")
