#!/usr/bin/env python3
"""Guards on what the repository holds, run by CTest from the source tree (a git checkout).

  check_tree.py session-names SOURCE_DIR
      Fails when a tracked file's path or text names a work session or a review folder instead of
      saying what the product does: prints file:line and the words for each hit.
  check_tree.py results-index SOURCE_DIR
      Fails unless every file under bench/results is reachable from bench/results/README.md: each
      result is a folder bench/results/<topic>/<date>_<what>/ whose README.md the index links, and
      every other file in that folder is named in its README.
  check_tree.py skips-in-frame-builder SOURCE_DIR
      Fails when product code other than the frame builder (frame/frame_builder.cpp) records a skipped
      pass (FrameGraph::skipPass): a feature says why it would not run (its ...SkipReason function
      or a result field) and the builder alone records it, so every skip decision is in one place.

Outside a git checkout (a source tarball) both say so and exit 77, which CTest reports as skipped.
"""
import os
import re
import subprocess
import sys

SKIP = 77

# BEGIN PATTERNS: the only lines of the tree that the work-session name check does not read.
PATH_PATTERN = re.compile(r"(^|/)(stop[0-9]+|merged_stop[0-9]*|review_[0-9a-f]{7})(/|$|_|\.)", re.IGNORECASE)
TEXT_PATTERNS = [
    re.compile(r"\b[Ss]top ?[0-9]{2}\b"),
    re.compile(r"\bmerged_stop[0-9]*"),
    re.compile(r"\breview_[0-9a-f]{7}\b"),
    re.compile(r"\b(the|this) session\b", re.IGNORECASE),
]
# END PATTERNS

ENTRY_NAME = re.compile(r"^[0-9]{4}-[0-9]{2}-[0-9]{2}_[a-z0-9][a-z0-9-]*$")


def tracked_files(root):
    """The tracked files (paths relative to root), or None when root is not a git checkout."""
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z"], capture_output=True, check=True)
    except (OSError, subprocess.CalledProcessError):
        return None
    return [p for p in out.stdout.decode("utf-8", "surrogateescape").split("\0") if p]


def pattern_lines(path):
    """Line numbers (1-based) of this script's pattern definitions."""
    lines = open(path, encoding="utf-8").read().split("\n")
    begin = next(i for i, l in enumerate(lines) if l.startswith("# BEGIN PATTERNS"))
    end = next(i for i, l in enumerate(lines) if l.startswith("# END PATTERNS"))
    return set(range(begin + 1, end + 2))


def session_names(root, files):
    own = os.path.relpath(os.path.abspath(__file__), os.path.abspath(root))
    skipped = pattern_lines(__file__)
    hits = []
    for rel in files:
        m = PATH_PATTERN.search(rel)
        if m:
            hits.append(f"{rel}: path names a work session ({m.group(2)})")
        full = os.path.join(root, rel)
        try:
            data = open(full, "rb").read()
        except OSError:  # a submodule or a file deleted from the work tree
            continue
        if b"\0" in data[:8192]:  # binary (images): no text to read
            continue
        for number, line in enumerate(data.decode("utf-8", "replace").split("\n"), 1):
            if rel == own and number in skipped:
                continue
            for pattern in TEXT_PATTERNS:
                for found in pattern.finditer(line):
                    hits.append(f"{rel}:{number}: names a work session: '{found.group(0)}'")
    for hit in hits:
        print(hit)
    if hits:
        print(f"{len(hits)} place(s) name a work session; say what the product does or measured instead"
              " (results: bench/results/<topic>/<date>_<what>/)")
        return 1
    print(f"no work session named in {len(files)} tracked files")
    return 0


def results_index(root, files):
    prefix = "bench/results/"
    results = [f[len(prefix):] for f in files if f.startswith(prefix)]
    index_path = os.path.join(root, prefix, "README.md")
    if "README.md" not in results:
        print("bench/results/README.md: missing (the index of the results)")
        return 1
    index = open(index_path, encoding="utf-8").read()
    problems = []
    entries = {}
    for rel in results:
        if rel == "README.md":
            continue
        parts = rel.split("/")
        if len(parts) < 3 or not ENTRY_NAME.match(parts[1]):
            problems.append(f"bench/results/{rel}: not inside a result folder bench/results/<topic>/<date>_<what>/")
            continue
        entries.setdefault("/".join(parts[:2]), []).append("/".join(parts[2:]))
    for entry, inside in sorted(entries.items()):
        if "README.md" not in inside:
            problems.append(f"bench/results/{entry}/: no README.md (device, command, table, conclusion, commit)")
            continue
        if f"]({entry}/README.md)" not in index:
            problems.append(f"bench/results/README.md: does not link {entry}/README.md")
        readme = open(os.path.join(root, prefix, entry, "README.md"), encoding="utf-8").read()
        for rel in inside:
            if rel == "README.md":
                continue
            folder, name = os.path.split(rel)
            named = rel in readme or (f"`{name}`" in readme and (not folder or f"`{folder}/" in readme))
            if not named:
                problems.append(f"bench/results/{entry}/{rel}: not named in bench/results/{entry}/README.md")
    for link in re.findall(r"\]\(([^)#\s]+)\)", index):
        if "://" not in link and not os.path.exists(os.path.join(root, prefix, link)):
            problems.append(f"bench/results/README.md: links {link}, which does not exist")
    for p in problems:
        print(p)
    if problems:
        print(f"{len(problems)} file(s) or link(s) of bench/results not reachable from its index")
        return 1
    print(f"{len(entries)} results, {len(results)} files, all reachable from bench/results/README.md")
    return 0


SKIP_CALL = re.compile(r"\bskipPass\s*\(")
SKIP_ALLOWED = {"frame/frame_builder.cpp", "engine/graph/frame_graph.hpp", "engine/graph/frame_graph.cpp"}
PRODUCT_SOURCE = re.compile(r"^(app|engine|frame|passes|cuda)/.*\.(cpp|hpp|cu|cuh)$")


def skips_in_frame_builder(root, files):
    hits = []
    for rel in files:
        if not PRODUCT_SOURCE.match(rel) or rel in SKIP_ALLOWED:
            continue
        try:
            text = open(os.path.join(root, rel), encoding="utf-8", errors="replace").read()
        except OSError:
            continue
        for number, line in enumerate(text.split("\n"), 1):
            if SKIP_CALL.search(line.split("//")[0]):
                hits.append(f"{rel}:{number}: records a skipped pass outside the frame builder: {line.strip()}")
    for hit in hits:
        print(hit)
    if hits:
        print(f"{len(hits)} skip(s) recorded outside frame/frame_builder.cpp; return the reason and let the builder record it")
        return 1
    print("every skipped pass is recorded by frame/frame_builder.cpp")
    return 0


MODES = {"session-names": session_names, "results-index": results_index, "skips-in-frame-builder": skips_in_frame_builder}


def main(argv):
    if len(argv) != 3 or argv[1] not in MODES:
        print(__doc__)
        return 2
    root = argv[2]
    files = tracked_files(root)
    if files is None:
        print(f"skipped: {root} is not a git checkout (git ls-files failed), so there is no list of tracked files")
        return SKIP
    return MODES[argv[1]](root, files)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
