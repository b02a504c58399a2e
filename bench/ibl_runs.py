"""Rows of the IBL benchmarks' tables (bench/ibl_specular.sh, bench/specular_masking.sh): what a
`lightpass bench` run's flags say about it and its passes' median GPU ms, one Markdown table."""
import json
import os


def flag_value(flags, name, default="-"):
    """The word after `name` in a run's flags ("--size 1920x1080" -> "1920x1080")."""
    return flags.split(name + " ")[1].split()[0] if name + " " in flags else default


def describe(flags):
    """Size, render path and specular method of a run."""
    spec = "split sum" if "split-sum" in flags else f"sampled {flag_value(flags, '--ibl-specular-samples', '64')}"
    return {"size": flag_value(flags, "--size"), "path": "forward+" if "forward+" in flags else "deferred", "spec": spec}


def table(out_md, jsons, columns, passes):
    """One row per run of each (scene, JSON path) in `jsons`: the scene, size, render path, specular
    method, each `columns` entry (header, function of the flags) and the median ms of each pass in
    `passes`; written to `out_md` and returned."""
    lines = ["| scene | size | render path | specular | " + "".join(f"{h} | " for h, _ in columns) +
             " | ".join(f"{p} ms" for p in passes) + " |",
             "| --- | --- | --- | --- | " + "--- | " * len(columns) + " | ".join("---:" for _ in passes) + " |"]
    for scene, path in jsons:
        if not os.path.isfile(path):
            continue
        for run in json.load(open(path))["runs"]:
            f, p = run["flags"], run["passes"]
            d = describe(f)
            cells = [f"{p[n]['median_ms']:.4f}" if n in p else "-" for n in passes]
            lines.append(f"| {scene} | {d['size']} | {d['path']} | {d['spec']} | " +
                         "".join(f"{fn(f)} | " for _, fn in columns) + " | ".join(cells) + " |")
    text = "\n".join(lines) + "\n"
    open(out_md, "w").write(text)
    return text
