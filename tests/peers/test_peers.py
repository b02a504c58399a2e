"""The peer benchmark's Python parts (bench/peers/): the converter's GLB, sidecar and material mapping,
the Filament runner's frame-time collection (without filly), and the summariser's table on a fixture.
Run from the repository root: python3 -m unittest discover -s tests/peers"""
import io
import json
import os
import shutil
import struct
import sys
import tempfile
import unittest
from contextlib import redirect_stderr, redirect_stdout

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "bench", "peers"))

import filament  # noqa: E402  (imports filly only inside main)
import scene_to_glb  # noqa: E402
import summarize_peers  # noqa: E402

DATA = os.path.join(ROOT, "tests", "data", "peers")


def read_glb(path):
    """(gltf JSON, BIN bytes), checking the container: header, chunk order, lengths, alignment."""
    with open(path, "rb") as f:
        data = f.read()
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    assert magic == b"glTF" and version == 2, (magic, version)
    assert length == len(data), (length, len(data))
    json_len, json_type = struct.unpack_from("<I4s", data, 12)
    assert json_type == b"JSON" and json_len % 4 == 0
    gltf = json.loads(data[20:20 + json_len])
    bin_off = 20 + json_len
    bin_len, bin_type = struct.unpack_from("<I4s", data, bin_off)
    assert bin_type == b"BIN\x00" and bin_len % 4 == 0
    assert bin_off + 8 + bin_len == len(data)
    return gltf, data[bin_off + 8:bin_off + 8 + bin_len]


class MaterialMapping(unittest.TestCase):
    def test_dielectric_keeps_lightpass_diffuse_layer(self):
        # lightpass's diffuse layer under a dielectric of F0 = Ks is Kd (1 - Ks).
        for ks in ([0.04] * 3, [0.0] * 3, [0.02, 0.03, 0.01]):
            base, metallic, _ = scene_to_glb.mtl_to_metallic_roughness([0.55, 0.5, 0.2], ks, 32)
            self.assertEqual(metallic, 0.0)
            for got, kd, s in zip(base, [0.55, 0.5, 0.2], ks):
                self.assertAlmostEqual(got, kd * (1.0 - s), places=12)

    def test_metallic_rises_with_specular_and_stays_in_range(self):
        last = -1.0
        for s in (0.05, 0.1, 0.2, 0.4, 0.6, 0.8, 1.0):
            base, metallic, _ = scene_to_glb.mtl_to_metallic_roughness([0.5, 0.5, 0.5], [s] * 3, 64)
            self.assertGreater(metallic, last)
            self.assertLessEqual(metallic, 1.0)
            self.assertTrue(all(0.0 <= c <= 1.0 for c in base))
            last = metallic

    def test_grey_material_reproduces_its_diffuse_albedo_and_f0(self):
        # Below full metal the blend is small: base (1 - m) ~ lightpass's diffuse layer Kd (1 - Ks) and
        # 0.04 (1 - m) + base m ~ Ks.
        kd, ks = 0.8, 0.2
        layer = kd * (1 - ks)
        base, m, _ = scene_to_glb.mtl_to_metallic_roughness([kd] * 3, [ks] * 3, 64)
        from_diffuse = layer / (1 - m)
        self.assertAlmostEqual(0.04 * (1 - m) + from_diffuse * m, ks, places=9)  # the quadratic's root
        self.assertLess(abs(base[0] * (1 - m) - layer), 0.02)

    def test_roughness_inverts_lightpass_gltf_shininess(self):
        # engine/scene/mesh_ops.cpp: shininessFromRoughness(r) = 2 / r^4 - 2.
        for ns in (0.0, 1.0, 10.0, 32.0, 256.0, 4000.0):
            r = scene_to_glb.roughness_from_shininess(ns)
            self.assertTrue(0.0 < r <= 1.0)
            self.assertAlmostEqual(2.0 / r ** 4 - 2.0, ns, delta=1e-9 * max(1.0, ns))


class Converter(unittest.TestCase):
    def setUp(self):
        self.out = tempfile.mkdtemp()

    def tearDown(self):
        shutil.rmtree(self.out)

    def convert(self, scene, **kw):
        with redirect_stdout(io.StringIO()):
            return scene_to_glb.convert(scene, self.out, log=lambda *_: None, **kw)

    def test_glb_is_consistent_and_complete(self):
        side = self.convert(os.path.join(DATA, "small.json"), suns=1, points=1)
        gltf, blob = read_glb(os.path.join(self.out, "small.glb"))
        self.assertEqual(gltf["buffers"][0]["byteLength"], len(blob))
        sizes = {5126: 4, 5125: 4}
        widths = {"SCALAR": 1, "VEC2": 2, "VEC3": 3}
        for acc in gltf["accessors"]:
            view = gltf["bufferViews"][acc["bufferView"]]
            self.assertEqual(view["byteOffset"] % 4, 0)
            self.assertLessEqual(view["byteOffset"] + view["byteLength"], len(blob))
            self.assertEqual(acc["count"] * widths[acc["type"]] * sizes[acc["componentType"]], view["byteLength"])
        triangles = 0
        for mesh in gltf["meshes"]:
            for prim in mesh["primitives"]:
                self.assertEqual(prim["mode"], 4)
                pos = gltf["accessors"][prim["attributes"]["POSITION"]]
                self.assertIn("min", pos)  # required by the spec for POSITION
                idx = gltf["accessors"][prim["indices"]]
                view = gltf["bufferViews"][idx["bufferView"]]
                ids = struct.unpack_from(f"<{idx['count']}I", blob, view["byteOffset"])
                self.assertLess(max(ids), pos["count"])
                triangles += idx["count"] // 3
                self.assertTrue(gltf["materials"][prim["material"]]["doubleSided"])
        self.assertEqual(triangles, side["triangles"])
        # Four models + the camera node, all in the scene; the camera looks as the scene's does.
        self.assertEqual(len(gltf["nodes"]), 5)
        self.assertEqual(gltf["scenes"][0]["nodes"], list(range(5)))
        cam_node = gltf["nodes"][4]
        self.assertEqual(cam_node["camera"], 0)
        m = cam_node["matrix"]
        self.assertEqual(m[12:15], [1.5, 2.0, 6.0])
        self.assertAlmostEqual(gltf["cameras"][0]["perspective"]["yfov"], 50 * 3.141592653589793 / 180, places=12)

    def test_instances_are_one_mesh_and_a_node_each(self):
        scene = {"camera": {"position": [0, 2, 6], "target": [0, 0, 0]},
                 "models": [{"name": "balls", "primitive": "sphere", "scale": 0.5, "translate": [0, 1, 0],
                             "instances": [{"translate": [-2, 0, 0]}, {"translate": [2, 0, 0], "scale": 2}]}]}
        path = os.path.join(self.out, "instanced.json")
        with open(path, "w") as f:
            json.dump(scene, f)
        side = self.convert(path)
        gltf, _ = read_glb(os.path.join(self.out, "instanced.glb"))
        self.assertEqual(len(gltf["meshes"]), 1)
        meshes = [n for n in gltf["nodes"] if "mesh" in n]
        self.assertEqual([n["mesh"] for n in meshes], [0, 0])
        # Each node: the instance's placement after the model's own (column-major matrices).
        self.assertEqual([n["matrix"][12:15] for n in meshes], [[-2, 1, 0], [2, 2, 0]])
        self.assertEqual(meshes[1]["matrix"][0], 1.0)  # 0.5 x 2
        one_copy = sum(gltf["accessors"][prim["indices"]]["count"] // 3 for prim in gltf["meshes"][0]["primitives"])
        self.assertEqual(side["triangles"], 2 * one_copy)
        self.assertAlmostEqual(side["bounds"][1][0], 2.5, places=5)

    def test_sidecar_and_matched_scene_keep_the_chosen_lights(self):
        side = self.convert(os.path.join(DATA, "small.json"), suns=1, points=1)
        self.assertEqual(len(side["suns"]), 1)
        self.assertEqual(side["suns"][0]["intensity"], 3.0)
        self.assertEqual(len(side["points"]), 1)
        self.assertEqual(side["points"][0]["range"], 3.0)
        # Filament gets the .exr's .hdr twin, with the sun lightpass extracts taken out of it
        # (NAME.env.hdr) and listed as a light; lightpass reads the map itself.
        env = side["environment"]
        self.assertTrue(os.path.isfile(env["map"]))
        if env.get("lights"):
            self.assertTrue(env["map"].endswith("small.env.hdr"))
            self.assertTrue(env["unextracted_map"].endswith("sky.hdr"))
            for light in env["lights"]:
                self.assertAlmostEqual(sum(t * t for t in light["towards"]), 1.0, places=9)
                self.assertTrue(all(e > 0.0 for e in light["irradiance"]))
        else:
            self.assertTrue(env["map"].endswith("sky.hdr"))
        self.assertEqual(side["environment"]["rotation"], 30.0)
        with open(os.path.join(self.out, "small.lightpass.json")) as f:
            matched = json.load(f)
        self.assertEqual([l["type"] for l in matched["lights"]], ["directional", "point"])
        self.assertEqual(matched["environment"]["map"], env.get("unextracted_map", env["map"]))
        self.assertTrue(matched["environment"]["ibl"])
        self.assertEqual(matched["exposure"], 0)  # Filament's camera, not auto exposure
        self.assertTrue(os.path.isabs(matched["models"][0]["obj"]))
        with open(os.path.join(DATA, "small.json")) as f:
            self.assertEqual(matched["camera"], json.load(f)["camera"])
        all_lights = self.convert(os.path.join(DATA, "small.json"), name="all")
        self.assertEqual((len(all_lights["suns"]), len(all_lights["points"])), (2, 2))

    def test_obj_quads_polygons_and_drops(self):
        warnings = []
        mesh = scene_to_glb.load_obj(os.path.join(DATA, "small.obj"), warnings)
        # 2 triangles + quad (2) + pentagon (3) + 3 triangles (2 degenerate, dropped) + quad (2).
        self.assertEqual(len(mesh.triangles), 10)
        self.assertTrue(any("dropped 2 degenerate" in w for w in warnings))
        # Materials: shiny, matte, then the default for the unknown 'not_in_mtl'.
        self.assertEqual([m["name"] for m in mesh.materials], ["shiny", "matte", "default"])
        self.assertEqual(sorted(set(mesh.triangle_material.tolist())), [0, 1, 2])
        # Some faces lack normals: every normal is then generated, unit length.
        lengths = (mesh.normals.astype(float) ** 2).sum(axis=1)
        self.assertTrue(all(abs(l - 1.0) < 1e-5 for l in lengths))

    def test_quad_splits_on_the_shorter_diagonal(self):
        # Quad 5 6 7 8: |v7 - v5| vs |v8 - v6|: tinyobjloader keeps the shorter one as the shared edge.
        warnings = []
        mesh = scene_to_glb.load_obj(os.path.join(DATA, "small.obj"), warnings)
        p = mesh.positions.astype(float)
        quad = [t for t, m in zip(mesh.triangles.tolist(), mesh.triangle_material.tolist()) if m == 1][:2]
        shared = set(map(tuple, p[quad[0]].tolist())) & set(map(tuple, p[quad[1]].tolist()))
        self.assertEqual(shared, {(2.0, 0.0, 0.0), (3.0, 1.0, 0.5)})  # v5-v7: 1.5 against v6-v8: 1.6

    def test_bad_input_names_the_file(self):
        bad = os.path.join(self.out, "bad.json")
        with open(bad, "w") as f:
            json.dump({"camera": {"position": [0, 0, 1]}, "models": [{"obj": "nothere.obj"}]}, f)
        with self.assertRaisesRegex(scene_to_glb.ConvertError, r"bad\.json: models\[0\]: .*nothere\.obj: file not found"):
            self.convert(bad)
        with open(bad, "w") as f:
            json.dump({"camera": {"position": [0, 0, 1]}, "models": [{"primitive": "plane"}],
                       "environment": {"map": os.path.join(self.out, "sky.exr")}}, f)
        with self.assertRaisesRegex(scene_to_glb.ConvertError, r"sky\.exr: filly reads Radiance \.hdr"):
            self.convert(bad)
        with open(bad, "w") as f:
            f.write("{ nope")
        with self.assertRaisesRegex(scene_to_glb.ConvertError, r"bad\.json: invalid JSON"):
            self.convert(bad)
        self.assertFalse(os.path.exists(os.path.join(self.out, "bad.glb")))


class FilamentRunner(unittest.TestCase):
    def test_collects_each_reported_frame_once_after_the_warmup(self):
        # Filament reports a frame's time two frames late, sometimes repeats the last report and
        # sometimes reports nothing yet.
        rendered = []
        reports = {}

        def render():
            rendered.append(len(rendered))

        def stats():
            n = len(rendered) - 3
            if n < 0:
                return None, None
            if n % 5 == 4:  # repeated report
                n -= 1
            reports.setdefault(n, 1.0 + n)
            return reports[n], n

        times = filament.collect_gpu_times(render, stats, frames=6, warmup=4, max_renders=100)
        self.assertEqual(len(times), 6)
        self.assertEqual(len(set(times)), 6)
        # After 4 warm-up renders frame 1 was the last report: the first collected is frame 2.
        self.assertEqual(times[0], 3.0)
        self.assertEqual(times, sorted(times))

    def test_environment_rotation_lines_the_map_up_with_lightpass(self):
        # The two conventions as measured (see FILAMENT_ENVIRONMENT_TURN_DEG): the map coordinate u a
        # world direction d shows, with the map rotated by r degrees right-handed about +Y.
        import math

        def unrotate(d, degrees):  # rotateY(d, -r)
            c, s = math.cos(math.radians(-degrees)), math.sin(math.radians(-degrees))
            return (c * d[0] + s * d[2], d[1], -s * d[0] + c * d[2])

        def u_lightpass(d, r):
            x, _, z = unrotate(d, r)
            return (math.atan2(x, -z) / (2 * math.pi) + 0.5) % 1.0

        def u_filament(d, r):
            x, _, z = unrotate(d, r)
            return (math.atan2(-x, z) / (2 * math.pi) + 0.5) % 1.0

        for r in (0.0, 30.0, -75.0, 180.0):
            for k in range(16):
                a = 2 * math.pi * (k + 0.25) / 16
                d = (math.sin(a), 0.3, math.cos(a))
                got = u_filament(d, filament.filament_environment_rotation(r))
                diff = abs(got - u_lightpass(d, r))
                self.assertLess(min(diff, 1.0 - diff), 1e-9, (r, k))
        # Without the half turn the two disagree: the test tells the conventions apart.
        self.assertGreater(abs(u_filament((0.0, 0.0, -1.0), 0.0) - u_lightpass((0.0, 0.0, -1.0), 0.0)), 0.4)

    def test_gives_up_after_max_renders(self):
        times = filament.collect_gpu_times(lambda: None, lambda: (None, None), frames=5, warmup=2, max_renders=7)
        self.assertEqual(times, [])

    def test_summary_and_units(self):
        s = filament.summary([3.0, 1.0, 2.0, 10.0])
        self.assertEqual(s["median_ms"], 2.5)
        self.assertEqual((s["min_ms"], s["max_ms"]), (1.0, 10.0))
        # f/16, 1/125 s, ISO 100: EV100 = log2(16^2 * 125) ; 1.2 * 2^EV100 = 38400.
        import math
        self.assertAlmostEqual(filament.photometric_scale(math.log2(256 * 125)), 38400.0, places=6)

    def test_sidecar_errors(self):
        with tempfile.TemporaryDirectory() as d:
            p = os.path.join(d, "x.peer.json")
            with self.assertRaisesRegex(filament.PeerError, r"x\.peer\.json: file not found"):
                filament.load_sidecar(p)
            with open(p, "w") as f:
                json.dump({"glb": "x.glb", "camera": {}, "suns": [], "points": []}, f)
            with self.assertRaisesRegex(filament.PeerError, r"glb .*x\.glb: file not found"):
                filament.load_sidecar(p)


class Summariser(unittest.TestCase):
    def test_fixture_table(self):
        with tempfile.TemporaryDirectory() as d:
            src = os.path.join(DATA, "results")
            for name in os.listdir(src):
                if name.endswith(".json"):
                    shutil.copy(os.path.join(src, name), d)
            with redirect_stdout(io.StringIO()) as out:
                self.assertEqual(summarize_peers.main([d, "gallery", "cornell"]), 0)
            with open(os.path.join(src, "expected_peers.md"), encoding="utf-8") as f:
                expected = f.read()
            with open(os.path.join(d, "peers.md"), encoding="utf-8") as f:
                self.assertEqual(f.read(), expected)
            self.assertEqual(out.getvalue(), expected)
            self.assertIn("| gallery, 1 sun (282k triangles) | 4.62 | 4.65 | 0.99 | 14.31 | 12.65 | 1.13 |", expected)

    def test_missing_filament_runs_leave_dashes(self):
        with tempfile.TemporaryDirectory() as d:
            shutil.copy(os.path.join(DATA, "results", "peers_lightpass_cornell.json"), d)
            with redirect_stdout(io.StringIO()) as out:
                self.assertEqual(summarize_peers.main([d, "cornell"]), 0)
            self.assertIn("| cornell | 4.01 | - | - | 13.63 | - | - |", out.getvalue())

    def test_names_the_gbuffer_mode_each_run_timed(self):
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(DATA, "results", "peers_lightpass_cornell.json"), encoding="utf-8") as f:
                run = json.load(f)
            for r in run["runs"]:  # what --gbuffer-mode auto times on a GPU
                r["passes"]["gbuffer_visibility"] = r["passes"].pop("gbuffer")
                r["passes"]["gbuffer_resolve"] = r["passes"]["gbuffer_visibility"]
            with open(os.path.join(d, "peers_lightpass_cornell.json"), "w", encoding="utf-8") as f:
                json.dump(run, f)
            shutil.copy(os.path.join(DATA, "results", "peers_lightpass_gallery.json"), d)
            with redirect_stdout(io.StringIO()) as out:
                self.assertEqual(summarize_peers.main([d, "gallery", "cornell"]), 0)
            self.assertIn("lightpass G-buffer (from the passes it timed): gallery classic, cornell visibility.",
                          out.getvalue())

    def test_no_results_is_an_error(self):
        with tempfile.TemporaryDirectory() as d:
            with redirect_stdout(io.StringIO()), redirect_stderr(io.StringIO()) as err:
                self.assertEqual(summarize_peers.main([d, "cornell"]), 1)
            self.assertIn("no peers_lightpass_*.json", err.getvalue())


if __name__ == "__main__":
    unittest.main()
