#!/usr/bin/env python3
"""Renders a `lightpass report` page and checks it in a real headless browser (Chromium).

    check_report.py frame LIGHTPASS OUTDIR SCENE SIZE [FLAGS...]   # lightpass report --scene SCENE
    check_report.py sweep LIGHTPASS OUTDIR SCENE SIZE               # lightpass sweep, then report --sweep
    check_report.py bench LIGHTPASS OUTDIR SCENE SIZE               # lightpass bench, then report --bench

Chromium loads OUTDIR/.../index.html twice at one fixed window size: --dump-dom gives the DOM after the
page's closing script ran (its title ends with "[page ok]" when no script error, console error or
undecoded image was recorded; #page-layout holds the page-coordinate box of every element marked
data-check), --screenshot the pixels. The checks then look at the screenshot inside those boxes: the
graph's boxes in their colours (app/report_html.cpp's kLiveBox / kSkippedBox), each view's thumbnail
showing the very image embedded for it, the time and floor bars, the sweep plot's points. Every
candidate pass of `lightpass graph --explain` must have its box, and the thumbnails must be exactly
the views whose passes run there. Exits 77 (skipped) when no chromium is installed (scripts/setup
installs the Debian package), or for the gallery scene without ../shared/assets.
"""
import base64
import io
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

WINDOW = (1400, 3800)  # tall enough for every view thumbnail of the gallery report (its last row ends at ~3630)
LIVE_BOX = (0x3B, 0x7D, 0xD8)
SKIPPED_BOX = (0xD9, 0xD9, 0xD9)
TIME_BAR = (0xE4, 0x57, 0x2E)
FLOOR_BAR = (0x2A, 0x9D, 0x8F)
FRONT_POINT = (0xD6, 0x27, 0x28)
OTHER_POINT = (0x88, 0x88, 0x88)

failures = []


def fail(message):
    failures.append(message)
    print("FAIL: " + message)


def run(cmd, **kw):
    p = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if p.returncode != 0:
        print(p.stdout + p.stderr)
        sys.exit(f"command failed ({p.returncode}): {' '.join(cmd)}")
    return p


def chromium(binary, page, profile, extra):
    cmd = [binary, "--headless", "--no-sandbox", "--disable-gpu", "--user-data-dir=" + profile,
           "--force-color-profile=srgb", "--force-device-scale-factor=1", "--hide-scrollbars",
           "--enable-logging=stderr", "--v=0", f"--window-size={WINDOW[0]},{WINDOW[1]}"] + extra + ["file://" + page]
    # Its home, config and cache in the temporary profile too: Chromium writes "Crash Reports" under
    # the config folder whatever --user-data-dir says, and a test leaves nothing in the user's home.
    env = dict(os.environ, HOME=profile, XDG_CONFIG_HOME=os.path.join(profile, "config"),
               XDG_CACHE_HOME=os.path.join(profile, "cache"))
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=60, env=env)
    if p.returncode != 0:
        print(p.stderr[-3000:])
        sys.exit(f"chromium failed ({p.returncode})")
    # The page logs nothing itself: any console message is an error of the page.
    for line in p.stderr.splitlines():
        if ":CONSOLE" in line:
            fail("console message: " + line.strip())
    return p.stdout


def load_page(binary, page):
    from PIL import Image
    with tempfile.TemporaryDirectory(prefix="lightpass-chromium-") as profile:
        dom = chromium(binary, page, profile, ["--dump-dom"])
        shot_path = os.path.join(profile, "shot.png")
        chromium(binary, page, profile, ["--screenshot=" + shot_path])
        shot = Image.open(shot_path).convert("RGB")
        shot.load()
    title = re.search(r"<title>(.*?)</title>", dom, re.S)
    if not title or not title.group(1).endswith("[page ok]"):
        errors = re.search(r'<pre id="page-errors"[^>]*>(.*?)</pre>', dom, re.S)
        fail("page title %r: the page recorded errors %s" % (title.group(1) if title else None,
                                                            errors.group(1) if errors else "(none read)"))
    layout = re.search(r'<pre id="page-layout"[^>]*>(.*?)</pre>', dom, re.S)
    if not layout or not layout.group(1).strip():
        sys.exit("FAIL: the page's closing script left no layout (did it run?)")
    boxes = {b["id"]: b for b in json.loads(layout.group(1).replace("&quot;", '"').replace("&amp;", "&"))}
    if shot.size != WINDOW:
        fail(f"screenshot is {shot.size}, asked {WINDOW}")
    return dom, boxes, shot


def pixels(shot, box, inset=1):
    x0, y0 = int(round(box["x"])) + inset, int(round(box["y"])) + inset
    x1, y1 = int(round(box["x"] + box["w"])) - inset, int(round(box["y"] + box["h"])) - inset
    if x1 <= x0 or y1 <= y0 or x1 > shot.size[0] or y1 > shot.size[1]:
        return None
    return shot.crop((x0, y0, x1, y1))


def share_of(region, colour, tolerance=6):
    data = list(region.getdata())
    near = sum(1 for p in data if all(abs(a - b) <= tolerance for a, b in zip(p, colour)))
    return near / max(len(data), 1)


def embedded_image(html, check_id):
    from PIL import Image
    m = re.search(r'data-check="' + re.escape(check_id) + r'"[^>]*src="data:image/png;base64,([^"]+)"', html)
    if not m:
        return None
    return Image.open(io.BytesIO(base64.b64decode(m.group(1)))).convert("RGB")


def same_image(shot, box, image, label):
    """The screenshot inside the <img> box is the embedded image: mean difference under 3 of 255."""
    region = pixels(shot, box, inset=0)
    if region is None:
        return fail(f"{label}: box {box} is outside the screenshot")
    if region.size != image.size:
        return fail(f"{label}: shown at {region.size}, the image is {image.size}")
    a, b = list(region.getdata()), list(image.getdata())
    diff = sum(abs(p - q) for pa, pb in zip(a, b) for p, q in zip(pa, pb)) / (3 * len(a))
    if diff > 3.0:
        worst = max(range(len(a)), key=lambda i: sum(abs(p - q) for p, q in zip(a[i], b[i])))
        fail(f"{label}: the screenshot differs from the embedded image by {diff:.1f}/255 on average; texel "
             f"({worst % image.size[0]}, {worst // image.size[0]}) shows {a[worst]}, the image has {b[worst]}")


def check_frame(browser, lightpass, outdir, scene, size, flags):
    out = os.path.join(outdir, "report-" + scene)
    run([lightpass, "report", "--scene", scene, "--size", size, "--frames", "3", "--warmup", "1", "--out", out, "-q"] + flags)
    page = os.path.join(out, "index.html")
    html = open(page, encoding="utf-8").read()
    dom, boxes, shot = load_page(browser, page)

    # (c) Every candidate pass of the frame (graph --explain) has its box, drawn in its colour.
    explain = run([lightpass, "graph", "--scene", scene, "--size", size, "--explain"] + flags).stdout
    names = re.findall(r"^  runs     (.+)$", explain, re.M) + re.findall(r"^  -        (.+?)  \(", explain, re.M)
    if len(names) < 10:
        fail(f"graph --explain listed only {len(names)} passes")
    live = skipped = 0
    for name in names:
        box = boxes.get("pass:" + name)
        if not box:
            fail(f"pass {name}: no box on the page")
            continue
        region = pixels(shot, box)
        if region is None:
            fail(f"pass {name}: box {box} is outside the screenshot")
            continue
        blue, grey = share_of(region, LIVE_BOX), share_of(region, SKIPPED_BOX)
        if blue > 0.5:
            live += 1
        elif grey > 0.5:
            skipped += 1
        else:
            fail(f"pass {name}: its box shows {blue:.0%} of the live colour and {grey:.0%} of the skipped one")
        if f">{name}<" not in dom:
            fail(f"pass {name}: its name is not on the page")
    if live < 5 or skipped < 1:
        fail(f"{live} boxes of passes that run and {skipped} of passes that do not: expected both kinds")

    # The thumbnails: every view the frame has (the G-buffer's always, the others where their pass
    # runs), each showing its own embedded image.
    views = [k[len("view:"):] for k in boxes if k.startswith("view:")]
    running = set(re.findall(r"^  runs     (.+)$", explain, re.M))
    expected = {"final", "depth", "normals", "diffuse", "specular", "velocity", "lighting"}
    if "ao_denoise" in running:
        expected.add("ao")
    if "ibl" in running:
        expected |= {"environment", "irradiance", "prefiltered", "dfg"}
    if "shadow_map_0" in running:
        expected.add("shadowmap")
    if "local_lights" in running:
        expected |= {"light-ranges", "lights-per-tile", "lights-per-cluster"}
    for view in sorted(expected - set(views)):
        fail(f"view {view}: no thumbnail, though the frame has it")
    for view, needs in (("ao", "ao_denoise"), ("environment", "ibl"), ("shadowmap", "shadow_map_0"),
                        ("light-ranges", "local_lights")):
        if view in views and needs not in running:
            fail(f"view {view}: a thumbnail, though {needs} does not run")
    for view in views:
        image = embedded_image(html, "view:" + view)
        if image is None:
            fail(f"view {view}: no embedded image")
            continue
        same_image(shot, boxes["view:" + view], image, "view " + view)
    final = embedded_image(html, "view:final")
    if final is not None:
        lo, hi = zip(*final.getextrema())
        if max(hi) - min(lo) < 30:
            fail(f"the final view is nearly uniform (channels {final.getextrema()})")

    # The bars: each timed pass has one; those wide enough to see are drawn in the bar colours.
    bars = [k[len("bar:"):] for k in boxes if k.startswith("bar:")]
    if len(bars) < 5:
        fail(f"only {len(bars)} time bars")
    seen_time = seen_floor = 0
    for name in bars:
        if name not in names:
            fail(f"bar {name}: no such pass in the graph")
        for kind, colour in (("bar:", TIME_BAR), ("floor:", FLOOR_BAR)):
            box = boxes.get(kind + name)
            if not box or box["w"] < 4:
                continue
            region = pixels(shot, {**box, "x": box["x"], "w": box["w"]}, inset=1)
            share = share_of(region, colour) if region else 0
            if share < 0.8:
                fail(f"{kind}{name}: {share:.0%} of its box in its colour")
            if kind == "bar:":
                seen_time += 1
            else:
                seen_floor += 1
    if seen_time < 3 or seen_floor < 3:
        fail(f"{seen_time} time bars and {seen_floor} floor bars wide enough to see")
    for text in ["llvmpipe", "lightpass report --scene " + scene, "MiB"]:
        if text not in dom:
            fail(f"{text!r} is not on the page")
    return f"{len(names)} passes, {len(views)} views, {len(bars)} bars"


def check_sweep(browser, lightpass, outdir, scene, size):
    sweep = os.path.join(outdir, "report-sweep-" + scene)
    out = os.path.join(outdir, "report-sweep-page-" + scene)
    run([lightpass, "sweep", "--scene", scene, "--knob", "shadow-size", "--size", size, "--frames", "1",
         "--warmup", "0", "--out-dir", sweep, "-q"])
    run([lightpass, "report", "--sweep", sweep, "--out", out, "-q"])
    page = os.path.join(out, "index.html")
    dom, boxes, shot = load_page(browser, page)
    rows = list(__import__("csv").DictReader(open(os.path.join(sweep, "sweep.csv"))))
    from PIL import Image
    front = 0
    for i, row in enumerate(rows):
        point = boxes.get(f"point:shadow-size:{i}")
        if not point:
            fail(f"value {row['value']}: no point in the plot")
            continue
        region = pixels(shot, {"x": point["x"] + point["w"] / 2 - 2, "y": point["y"] + point["h"] / 2 - 2, "w": 4, "h": 4}, 0)
        red, grey = (share_of(region, FRONT_POINT), share_of(region, OTHER_POINT)) if region else (0, 0)
        if red < 0.5 and grey < 0.5:
            fail(f"value {row['value']}: its point shows neither point colour")
        front += red >= 0.5
        image = Image.open(os.path.join(sweep, row["image"])).convert("RGB")
        box = boxes.get(f"image:shadow-size:{i}")
        if not box:
            fail(f"value {row['value']}: no image")
            continue
        same_image(shot, box, image, f"value {row['value']}'s image")
    if not front:
        fail("no point is drawn on the Pareto front")
    if "shadow-size" not in dom:
        fail("the knob's name is not on the page")
    return f"{len(rows)} values, {front} on the front"


def check_bench(browser, lightpass, outdir, scene, size):
    bench = os.path.join(outdir, "report-bench-" + scene + ".json")
    out = os.path.join(outdir, "report-bench-page-" + scene)
    run([lightpass, "bench", "--scene", scene, "--size", size, "--frames", "2", "--warmup", "0",
         "--vary", "--shadow-size 512,1024", "--vary", "--aa off|--aa fxaa", "--timings-json", bench, "-q"])
    run([lightpass, "report", "--bench", bench, "--out", out, "-q"])
    dom, boxes, shot = load_page(browser, os.path.join(out, "index.html"))
    runs = json.load(open(bench))["runs"]
    if len(runs) != 4:
        fail(f"bench wrote {len(runs)} variants, expected 4")
    wide = 0
    for i, r in enumerate(runs):
        if "bar:variant:" + r["flags"] not in boxes:
            fail(f"variant {r['flags']!r}: no frame bar")
        for name, p in r["passes"].items():
            if name == "frame":
                continue
            box = boxes.get(f"bar:{i}:{name}")
            if not box:
                fail(f"variant {r['flags']!r}: no bar for pass {name}")
                continue
            if box["w"] >= 4:
                region = pixels(shot, box)
                share = share_of(region, TIME_BAR) if region else 0
                if share < 0.8:
                    fail(f"variant {r['flags']!r}, pass {name}: {share:.0%} of its bar in the bar colour")
                wide += 1
    if wide < 4:
        fail(f"only {wide} pass bars wide enough to see")
    return f"{len(runs)} variants, {wide} pass bars seen"


def main():
    mode, lightpass, outdir, scene, size = sys.argv[1:6]
    flags = sys.argv[6:]
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if not browser:
        print("SKIP: chromium is not installed (scripts/setup installs the Debian package)")
        return 77
    assets = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "shared", "assets")
    if scene == "gallery" and not os.path.isdir(assets):
        print(f"SKIP: the gallery scene needs {os.path.normpath(assets)}, which is absent")
        return 77
    try:
        import PIL  # noqa: F401
    except ImportError:
        sys.exit("FAIL: python3-pil is missing (scripts/setup installs it)")
    if mode == "frame":
        summary = check_frame(browser, lightpass, outdir, scene, size, flags)
    elif mode == "sweep":
        summary = check_sweep(browser, lightpass, outdir, scene, size)
    else:
        summary = check_bench(browser, lightpass, outdir, scene, size)
    if failures:
        print(f"{len(failures)} checks failed")
        return 1
    print(f"report ok in chromium: {scene} ({mode}), {summary}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
