#!/usr/bin/env python3
"""run_corpus.py LIGHTPASS CORPUS_DIR OUT_DIR [CLASS...]: runs lightpass on every case of the bad-input
corpus (make_corpus.py) of the given classes and checks the promise of docs/bad-input.md:
  - no hang (each run under a timeout) and no crash (no exit by a signal);
  - an error case exits 1 with exactly one "lightpass: error:" line on stderr, which matches the case's
    regex (the file, and field or line, and what is wrong), no GL error lines, and leaves no file
    behind in its output folder (no partial output, no temporary);
  - a fallback case exits 0 with its warning; an ok case exits 0 without the forbidden words;
  - an "any" case (a mutation of a valid file, whose fate is not known in advance) either exits 0 or
    is an error case as above, its line naming the file;
  - a "signal" case is sent that signal as soon as a temporary output exists, must end killed by it,
    and leaves no file behind;
  - every line on stderr is one clean line: no control characters (a terminal escape), at most
    `max_line` characters (default 1000); an error line comes alone, without warnings before it;
  - `stack_kib` runs lightpass under that stack limit (ulimit -s), `fsize_limit` under that file-size
    limit (SIGXFSZ ignored, as for a full disk, unless `sigxfsz` is "default");
  - outputs the case names exist after success and are absent after failure.
Prints one line per case and "corpus ok: N cases" when all pass."""
import json, os, re, resource, shutil, signal, subprocess, sys, time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli"))
from png_pixel import read_png  # noqa: E402 (the one PNG reader of the tests)

lightpass, corpus, out_root = sys.argv[1], os.path.abspath(sys.argv[2]), os.path.abspath(sys.argv[3])
classes = {int(c) for c in sys.argv[4:]}
cases = [c for c in json.load(open(os.path.join(corpus, "manifest.json"))) if not classes or c["cls"] in classes]


def lit_fraction(path):
    """Fraction of pixels clearly brighter than the near-black background."""
    w, h, bpp, rows = read_png(path)
    lit = sum(1 for row in rows for x in range(w) if max(row[x * bpp:x * bpp + 3]) > 40)
    return lit / (w * h)


def files_under(folder):
    return sorted(os.path.relpath(os.path.join(d, f), folder) for d, _, fs in os.walk(folder) for f in fs)


def run(case):
    out = os.path.join(out_root, case["name"])
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    sub = lambda s: s.replace("{C}", corpus).replace("{O}", out)
    for d in case.get("make_dirs", []):
        os.makedirs(sub(d))
    before = files_under(out)
    args = [lightpass] + [sub(a) for a in case["args"]]
    env = dict(os.environ, **case.get("env", {}))
    limit, stack = case.get("fsize_limit"), case.get("stack_kib")

    def limits():
        if limit:  # a full disk: writes past `limit` bytes fail with EFBIG (SIGXFSZ ignored, unless left at its default)
            if case.get("sigxfsz") != "default":
                signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
            resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
        if stack:
            resource.setrlimit(resource.RLIMIT_STACK, (stack * 1024, resource.getrlimit(resource.RLIMIT_STACK)[1]))

    if case["expect"] == "signal":
        return run_until_signal(case, args, env, out)
    try:
        p = subprocess.run(args, capture_output=True, text=True, errors="replace", env=env, timeout=case.get("timeout", 30),
                           preexec_fn=limits if limit or stack else None, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        return "hang: no exit within the timeout"
    err = p.stderr
    # The regex of an "any" case names the file; it is an error case when lightpass says so.
    expect = case["expect"] if case["expect"] != "any" else ("error" if p.returncode == 1 else "ok")
    regex = case["regex"].replace("{C}", re.escape(corpus)).replace("{O}", re.escape(out))
    if p.returncode < 0:
        return f"crash: killed by signal {-p.returncode}: {err.strip()[-300:]}"
    errors = [l for l in err.splitlines() if l.startswith("lightpass: error:")]
    if re.search(r"^lightpass: (error|warning): GL:", err, re.M):
        return f"raw GL message on stderr: {err.strip()[-300:]}"
    for line in err.splitlines():
        if re.search(r"[\x00-\x08\x0b-\x1f\x7f]", line):
            return f"a control character on stderr: {ascii(line[:300])}"
        if len(line) > case.get("max_line", 1000):
            return f"a line of {len(line)} characters on stderr, want at most {case.get('max_line', 1000)}: {line[:300]}..."
        if re.search(r"json\.exception|tinygltf|Invalid glTF binary", line):
            return f"a raw library message: {line[:300]}"
    if expect == "error":
        if p.returncode != 1:
            return f"exit code {p.returncode}, want 1: {err.strip()[-300:]}"
        if len(errors) != 1:
            return f"want exactly one error line, got {len(errors)}: {err.strip()[-300:]}"
        if not re.search(regex, errors[0]):
            return f"error does not match /{regex}/: {errors[0]}"
        if case["cls"] >= 11 and err.count("lightpass: warning:"):
            return f"warnings before the error line: {err.strip()[-400:]}"
        left = [f for f in files_under(out) if f not in before]
        if left:
            return f"left files behind after the error: {left}"
    else:
        if p.returncode != 0 or errors:
            return f"exit code {p.returncode}, want 0: {err.strip()[-300:]}"
        if not re.search(regex, err + p.stdout, re.S):
            return f"output does not match /{regex}/: {(err + p.stdout).strip()[-400:]}"
        if case.get("forbid") and re.search(case["forbid"], err):
            return f"stderr matches the forbidden /{case['forbid']}/: {err.strip()[-300:]}"
        for o in case.get("outputs", []):
            if not os.path.isfile(sub(o)) or os.path.getsize(sub(o)) == 0:
                return f"missing output {sub(o)}"
        if "max_warnings" in case and err.count("warning:") > case["max_warnings"]:
            return f"{err.count('warning:')} warning lines, want at most {case['max_warnings']}"
        if case.get("covered"):
            png, want = case["covered"]
            got = lit_fraction(sub(png))
            if got < want:
                return f"{sub(png)}: only {got:.0%} of the image is lit, want at least {want:.0%}"
        if [f for f in files_under(out) if ".tmp-" in f]:
            return "left a temporary file behind"
    for a in case.get("absent", []):
        if os.path.exists(sub(a)):
            return f"{sub(a)} exists after a failed run"
    return None


def run_until_signal(case, args, env, out):
    """Starts lightpass, waits for its first temporary output, sends the signal; it must end killed by
    that signal, leaving no file behind."""
    sig = getattr(signal, "SIG" + case["signal"])
    p = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL, env=env)
    deadline = time.time() + case.get("timeout", 60)
    while not [f for f in files_under(out) if ".tmp-" in f]:
        if p.poll() is not None:
            return f"exited ({p.returncode}) before writing a temporary: {p.stderr.read().decode(errors='replace').strip()[-300:]}"
        if time.time() > deadline:
            p.kill()
            p.wait()
            return "no temporary output appeared within the timeout"
        time.sleep(0.005)
    p.send_signal(sig)
    try:
        p.wait(timeout=30)
    except subprocess.TimeoutExpired:
        p.kill()
        p.wait()
        return f"did not end within 30 s of SIG{case['signal']}"
    p.stderr.close()
    if p.returncode != -sig:
        return f"exit status {p.returncode}, want killed by SIG{case['signal']} ({-sig})"
    left = files_under(out)
    if left:
        return f"left files behind after SIG{case['signal']}: {left}"
    return None


failed = 0
for case in cases:
    problem = run(case)
    print(f"{'FAIL' if problem else 'ok  '} class {case['cls']} {case['name']}" + (f": {problem}" if problem else ""))
    failed += bool(problem)
if failed:
    print(f"corpus FAILED: {failed} of {len(cases)} cases")
    sys.exit(1)
print(f"corpus ok: {len(cases)} cases")
