#!/usr/bin/env python3
"""Turns `lightpass render --timings-json` files into one Markdown table (pass x size, median ms)."""
import json
import sys


def main(paths):
    runs = [json.load(open(p)) for p in paths]
    passes = []
    for r in runs:
        for name in r["passes"]:
            if name not in passes:
                passes.append(name)
    head = "| pass | " + " | ".join(f"{r['width']}x{r['height']} median ms" for r in runs) + " |"
    print(f"Device: {runs[0]['device']}; frames per size: {', '.join(str(r['frames']) for r in runs)}; "
          f"view: {runs[0]['view']}\n")
    print(head)
    print("|" + " --- |" * (len(runs) + 1))
    for name in passes:
        cells = []
        for r in runs:
            p = r["passes"].get(name)
            cells.append(f"{p['median_ms']:.4f}" if p else "-")
        print(f"| {name} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1:])
