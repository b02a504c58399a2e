"""bench/'s forward+ tools without a GPU: forward_terms.sh's shader patches still apply to
shaders/forward.frag (each variant changes exactly the line it names), summarize_forward_terms.py's
arithmetic on a fixture, summarize_render_path.py counting the visibility G-buffer's passes in
deferred's geometry + lighting, and project_python.py re-running a script under the project's .venv. Run from the repository root: python3 -m unittest discover -s tests/bench"""
import difflib
import io
import json
import os
import subprocess
import sys
import tempfile
import unittest
from contextlib import redirect_stdout

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "bench"))

import project_python  # noqa: E402
import summarize_forward_terms  # noqa: E402
import summarize_render_path  # noqa: E402


def run_json(path, runs):
    """A `lightpass bench --timings-json` file with the given runs: (flags, width, height, {pass: ms})."""
    out = {"device": "test GPU", "scene": "scenes/test.json", "runs": []}
    for flags, w, h, passes in runs:
        out["runs"].append({"flags": flags, "width": w, "height": h, "frames": 10,
                            "passes": {k: {"median_ms": v} for k, v in passes.items()}})
    with open(path, "w") as f:
        json.dump(out, f)


class ForwardTermsPatches(unittest.TestCase):
    def test_every_variant_changes_only_its_line(self):
        with tempfile.TemporaryDirectory() as d:
            env = dict(os.environ, PATCH_ONLY=d)
            env.pop("LIGHTPASS_SHADER_DIR", None)
            subprocess.run(["bash", "bench/forward_terms.sh"], cwd=ROOT, env=env, check=True)
            original = open(os.path.join(ROOT, "shaders", "forward.frag")).read().splitlines()
            expected = {"full": None, "no_sun": "lpSunRadiance", "no_ibl": "if (uIbl)",
                        "material": "uFlat", "early": None}
            for variant, removed in expected.items():
                patched = open(os.path.join(d, variant, "forward.frag")).read().splitlines()
                diff = [l for l in difflib.unified_diff(original, patched, lineterm="", n=0)
                        if l[:1] in "+-" and not l.startswith(("+++", "---"))]
                if variant == "full":
                    self.assertEqual(diff, [])
                elif variant == "early":
                    self.assertIn("+layout(early_fragment_tests) in;", diff)
                    self.assertFalse([l for l in diff if l.startswith("-")], diff)
                else:
                    minus = [l for l in diff if l.startswith("-")]
                    plus = [l for l in diff if l.startswith("+")]
                    self.assertEqual(len(minus), 1, diff)
                    self.assertEqual(len(plus), 1, diff)
                    self.assertIn(removed, minus[0])
                    self.assertIn(variant, plus[0])
                # The other shaders are copied untouched.
                self.assertEqual(open(os.path.join(d, variant, "common", "sun_light.glsl")).read(),
                                 open(os.path.join(ROOT, "shaders", "common", "sun_light.glsl")).read())

    def test_a_patch_that_no_longer_applies_stops_the_script(self):
        with tempfile.TemporaryDirectory() as d:
            shaders = os.path.join(d, "shaders")
            subprocess.run(["cp", "-r", os.path.join(ROOT, "shaders"), shaders], check=True)
            path = os.path.join(shaders, "forward.frag")
            text = open(path).read().replace("c += lpSunRadiance(", "c = c + lpSunRadiance(")
            open(path, "w").write(text)
            env = dict(os.environ, PATCH_ONLY=os.path.join(d, "out"), LIGHTPASS_SHADER_DIR=shaders)
            r = subprocess.run(["bash", "bench/forward_terms.sh"], cwd=ROOT, env=env, capture_output=True, text=True)
            self.assertNotEqual(r.returncode, 0)
            self.assertIn("no_sun patch did not apply", r.stderr)


class SummarizeForwardTerms(unittest.TestCase):
    def test_terms_are_differences_against_the_compute_passes(self):
        with tempfile.TemporaryDirectory() as d:
            size = (1920, 1080)
            forward = {"full": 10.0, "no_sun": 2.0, "no_ibl": 9.0, "material": 1.5, "early": 10.01}
            for v, ms in forward.items():
                run_json(os.path.join(d, f"forward_terms_gallery_{v}.json"),
                         [("--render-path forward+", *size, {"depth_prepass": 2.0, "forward_opaque": ms})])
            run_json(os.path.join(d, "forward_terms_gallery_deferred.json"),
                     [("--render-path deferred", *size, {"gbuffer_visibility": 1.0, "gbuffer_resolve": 0.25,
                                                         "global_lights": 0.2, "ibl": 0.05})])
            out = io.StringIO()
            with redirect_stdout(out):
                summarize_forward_terms.main(d)
            rows = [l for l in out.getvalue().splitlines() if l.startswith("| gallery 1920x1080")]
            self.assertEqual(len(rows), 1, out.getvalue())
            cells = [c.strip() for c in rows[0].strip("|").split("|")]
            self.assertEqual(cells[1], "10.000")
            self.assertEqual(cells[2], "8.000 / 0.200 (40.0×)")   # suns: 10 - 2 against global_lights
            self.assertEqual(cells[3], "1.000 / 0.050 (20.0×)")   # IBL: 10 - 9 against ibl
            self.assertEqual(cells[4], "1.500 / 0.250 (6.0×)")    # material against gbuffer_resolve
            self.assertEqual(cells[5], "2.000 / 1.000 (2.0×)")    # pre-pass against the visibility raster
            self.assertEqual(cells[6], "0.010")
            # A scene without files is reported missing, not skipped silently.
            self.assertIn("| cornell 1920x1080 | missing |", out.getvalue())


class SummarizeRenderPath(unittest.TestCase):
    def test_deferred_geometry_counts_the_visibility_gbuffer(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "render_path_test.json")
            lighting = {"global_lights": 0.2, "ibl": 0.05, "local_lights": 0.1}
            run_json(path, [
                ("--render-path deferred --local-lights tiled --light-count 1", 1920, 1080,
                 dict(lighting, gbuffer_visibility=1.0, gbuffer_resolve=0.25, frame=2.0)),
                ("--render-path deferred --local-lights clustered --light-count 1", 1920, 1080,
                 dict(lighting, gbuffer=3.0, frame=4.0)),
                ("--render-path forward+ --light-count 1", 1920, 1080,
                 {"depth_prepass": 2.0, "forward_opaque": 6.0, "frame": 8.5}),
            ])
            out = io.StringIO()
            with redirect_stdout(out):
                summarize_render_path.main([path])
            row = [l for l in out.getvalue().splitlines() if l.startswith("| 1 |")]
            self.assertEqual(len(row), 1, out.getvalue())
            cells = [c.strip() for c in row[0].strip("|").split("|")]
            self.assertEqual(cells[1], "2.000 / 1.600 (10)")   # visibility: 1 + 0.25 + 0.35
            self.assertEqual(cells[2], "4.000 / 3.350 (10)")   # classic: 3 + 0.35
            self.assertEqual(cells[3], "8.500 / 8.000 (10)")
            self.assertEqual(cells[4], "2.12")                  # 8.5 / 4


class ProjectPython(unittest.TestCase):
    """bench/*.py that need FLIP find it in .venv (scripts/setup-tools) from the system python3."""

    def fake_root(self, d, with_venv=True):
        """A tree with bench/project_python.py, a script needing a module nothing has, and (with_venv)
        a .venv/bin/python3 that only says it ran and with what."""
        def write(path, text):
            with open(path, "w") as f:
                f.write(text)
        os.makedirs(os.path.join(d, "bench"))
        with open(os.path.join(ROOT, "bench", "project_python.py")) as f:
            write(os.path.join(d, "bench", "project_python.py"), f.read())
        write(os.path.join(d, "bench", "needs_flip.py"),
            "import sys, os\nsys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))\n"
            "from project_python import use_project_venv\n"
            "use_project_venv(['no_such_module_lp', 'os'])\nprint('ran under', sys.executable)\n")
        if with_venv:
            python = os.path.join(d, ".venv", "bin", "python3")
            os.makedirs(os.path.dirname(python))
            write(python, '#!/bin/sh\necho "venv python: $*"\n')
            os.chmod(python, 0o755)
        return os.path.join(d, "bench", "needs_flip.py")

    def test_choice(self):
        with tempfile.TemporaryDirectory() as d:
            self.fake_root(d)
            venv_python = os.path.join(d, ".venv", "bin", "python3")
            self.assertEqual(project_python.interpreter_for(["x"], d, prefix="/usr", have=lambda m: False), venv_python)
            self.assertIsNone(project_python.interpreter_for(["x"], d, prefix="/usr", have=lambda m: True))
            self.assertIsNone(project_python.interpreter_for(["x"], d, prefix=os.path.join(d, ".venv"),
                                                             have=lambda m: False))  # already there: no loop
        with tempfile.TemporaryDirectory() as d:
            self.fake_root(d, with_venv=False)
            self.assertIsNone(project_python.interpreter_for(["x"], d, prefix="/usr", have=lambda m: False))

    def test_script_reruns_under_venv(self):
        with tempfile.TemporaryDirectory() as d:
            script = self.fake_root(d)
            out = subprocess.run([sys.executable, script, "sweep"], capture_output=True, text=True, check=True).stdout
            self.assertEqual(out.strip(), f"venv python: {script} sweep")
        with tempfile.TemporaryDirectory() as d:
            script = self.fake_root(d, with_venv=False)
            out = subprocess.run([sys.executable, script], capture_output=True, text=True, check=True).stdout
            self.assertTrue(out.startswith("ran under"), out)

    def test_flip_scripts_use_it(self):
        for name in ("sweep_report.py", "summarize_aa.py"):
            with open(os.path.join(ROOT, "bench", name)) as f:
                text = f.read()
            self.assertIn('use_project_venv(["flip_evaluator"])', text, name)


if __name__ == "__main__":
    unittest.main()
