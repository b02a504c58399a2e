#!/usr/bin/env python3
"""Checks a `lightpass bench` JSON: one run per variant of the cartesian product, in order, each
with a frame time and the pass the variants differ in.
  check_bench.py BENCH.json EXPECTED_RUNS PASS"""
import json
import sys

path, expected, focus = sys.argv[1], int(sys.argv[2]), sys.argv[3]
d = json.load(open(path))
runs = d["runs"]
assert len(runs) == expected, f"{len(runs)} runs, expected {expected}"
assert len({r["flags"] for r in runs}) == expected, "variants are not distinct"
for r in runs:
    assert r["passes"]["frame"]["median_ms"] > 0, r
    assert focus in r["passes"], f"{focus} missing from {r['flags']}"
    assert r["frames"] >= 1
print("bench json ok")
